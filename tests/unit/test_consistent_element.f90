!> Tests of the consistent beam element (module consistent_element) and of
!> the beam_element contract (point loads for both interpolations).
module test_consistent_element_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t
  use quadrature, only: max_gauss_points
  use element_effects, only: element_effects_t, effects_all_on
  use planar_element, only: planar_element_t, rigid_state_t, element_eval_info_t, station_x_over_l
  use kear_element, only: kear_element_t, kear_element_init, formulation_kear1987
  use consistent_element, only: consistent_element_t, consistent_element_init
  use beam_element, only: beam_point_load, beam_local_displacement, beam_tangent_stiffness, beam_strain_energy, &
                          resolve_formulation
  use assertions
  use element_fixtures, only: soft, l_u, b_u, t_u, rigid_at
  use fd_checks, only: fd_gradient, fd_jacobian
  use element_checks, only: unit_beam, check_force_is_gradient, check_tangent_is_jacobian, check_inertia_is_lagrange
  use test_text, only: rtoa
  implicit none
  private
  public :: run_all

  !> a strongly deformed state and rates, DOFs [U W th m ux uxx] per node
  real(dp), parameter :: q_big(12) = [0.02_dp, -0.03_dp, 0.15_dp, 0.3_dp, -0.04_dp, 0.1_dp, &
                                      -0.05_dp, 0.08_dp, -0.2_dp, 0.4_dp, 0.03_dp, -0.12_dp]
  real(dp), parameter :: qd_big(12) = [0.5_dp, -0.7_dp, 1.1_dp, -2.0_dp, 0.4_dp, -0.6_dp, &
                                       0.3_dp, 0.9_dp, -1.3_dp, 2.2_dp, -0.5_dp, 0.8_dp]
  real(dp), parameter :: qdd_big(12) = [3.0_dp, -2.0_dp, 5.0_dp, -8.0_dp, 2.5_dp, -3.0_dp, &
                                        -4.0_dp, 6.0_dp, 7.0_dp, -9.0_dp, 1.5_dp, 4.0_dp]

contains

  subroutine run_all()
    call run_test('internal_force_is_gradient_of_strain_energy', test_force_is_gradient)
    call run_test('tangent_stiffness_is_symmetric_jacobian_of_internal_force', test_tangent_is_jacobian)
    call run_test('inertial_operator_equals_fd_lagrange_equations', test_lagrange_fd)
    call run_test('large_rigid_rotation_gives_zero_strain', test_rigid_rotation)
    call run_test('circular_arc_is_inextensible_where_kear_element_locks', test_arc_no_locking)
    call run_test('bending_block_of_linear_model_equals_kear_element', test_linear_bending_block)
    call run_test('point_load_is_gradient_of_its_work', test_point_load)
    call run_test('default_formulation_follows_stretching_switch', test_default_formulation)
    call run_test('tabulated_stress_stations_equal_direct_strains', test_station_strains)
    call run_test('switches_of_the_evaluation_apply_to_both_elements', test_evaluation_switches)
  end subroutine run_all

  function unit_element(fx) result(el)
    type(element_effects_t), intent(in) :: fx
    type(consistent_element_t) :: el
    type(error_t) :: err
    call consistent_element_init(el, l_u, b_u, t_u, soft, fx, err)
    if (err%failed()) call assert_true(.false., 'unit element: '//err%text())
  end function unit_element

  !> dSE/dq by 4th-order differences (h = 1e-4: truncation ~h^4) against the
  !> analytic internal force, each nonlinear effect alone and all on: 1e-8
  !> of the largest component.
  subroutine test_force_is_gradient()
    call check_force_is_gradient('consistent', q_big)
  end subroutine test_force_is_gradient

  !> d(internal force)/dq by 4th-order differences (h = 1e-4) against K_t:
  !> 1e-7 of max|K|; K_t symmetric to 1e-12 (a Hessian).  Also the tangent
  !> returned by the evaluation equals the stand-alone one.
  subroutine test_tangent_is_jacobian()
    type(consistent_element_t) :: el
    real(dp) :: kt(12, 12), k2(12, 12)
    real(dp) :: m(12, 12), f(12)
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    call check_tangent_is_jacobian(unit_beam('consistent', effects_all_on()), q_big, 'all on')
    el = unit_element(effects_all_on())
    rb = rigid_at(0.0_dp)
    call el%eval(q_big, qd_big, rb, m, f, info, k2)
    call beam_tangent_stiffness(el, q_big, rb%phi, kt)
    call assert_all_close(reshape(k2, [144]), reshape(kt, [144]), 0.0_dp, 1.0e-13_dp*maxval(abs(kt)), &
                          'tangent of eval = beam_tangent_stiffness')
  end subroutine test_tangent_is_jacobian

  !> M qdd - F - dSE/dq of the element against d/dt dT/dqdot - dT/dq by finite
  !> differences of the kinetic energy evaluated directly from the positions
  !> (K5) and the section angle (K8), along q(t) = q0 + qd0 s + qdd0 s^2/2
  !> with phi, X1, Y1 all accelerating: 1e-7 of the largest component (FD
  !> accuracy), all effects on, the linear section angle, the linear model.
  subroutine test_lagrange_fd()
    call check_inertia_is_lagrange('consistent', q_big, qd_big, qdd_big)
  end subroutine test_lagrange_fd

  !> A straight element turned rigidly by alpha = 2.5 rad about node 1
  !> (u = x (cos a - 1), w = x sin a: ux = cos a - 1, th = sin a) has zero
  !> strain energy to round-off (1e-20 of EA l, the energy of a unit strain).
  subroutine test_rigid_rotation()
    type(consistent_element_t) :: el
    real(dp) :: p(12), alpha, se
    alpha = 2.5_dp
    el = unit_element(effects_all_on())
    p = 0.0_dp
    p(3) = sin(alpha)
    p(5) = cos(alpha) - 1.0_dp
    p(7) = l_u*(cos(alpha) - 1.0_dp)
    p(8) = l_u*sin(alpha)
    p(9) = sin(alpha)
    p(11) = cos(alpha) - 1.0_dp
    se = beam_strain_energy(el, p, 0.0_dp)      ! phi = 0: q = p
    call assert_true(abs(se) <= 1.0e-20_dp*soft%e1*b_u*t_u*l_u, 'rigid rotation energy '//trim(rtoa(se)))
  end subroutine test_rigid_rotation

  !> An element bent into a circular arc of angle beta = pi/4 (one eighth of
  !> a circle: the elastica rolled up by M = 2 pi EI/L with 8 elements) with
  !> the nodal values of the exact inextensible arc u = R sin(x/R) - x,
  !> w = R (1 - cos(x/R)).  Consistent element: |eps_n| <= 2e-5 and kappa
  !> within 1e-3 of 1/R at every station (quintic interpolation error,
  !> O(beta^6)).  Kear's element given the same nodal u, w, w_x, w_xx has
  !> 1 + u_x constant = sin(beta)/beta, so eps_n reaches 0.02 -- a
  !> membrane strain 1000 times the bending strain t/(2R) of a slender beam:
  !> locking.
  subroutine test_arc_no_locking()
    type(consistent_element_t) :: el
    type(kear_element_t) :: kel
    type(error_t) :: err
    real(dp) :: r, beta, p(12), pk(8), eps, kap, worst_eps, worst_kap, kear_eps, x
    integer :: i
    beta = pi/4
    r = l_u/beta
    el = unit_element(element_effects_t(stretching=.true., curvature=.true.))
    p = [0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp/r, 0.0_dp, 0.0_dp, &
         r*sin(beta) - l_u, r*(1.0_dp - cos(beta)), sin(beta), cos(beta)/r, cos(beta) - 1.0_dp, -sin(beta)/r]
    worst_eps = 0.0_dp
    worst_kap = 0.0_dp
    do i = 0, 20
      x = i/20.0_dp
      call el%section_strains(p, x, eps, kap)
      worst_eps = max(worst_eps, abs(eps))
      worst_kap = max(worst_kap, abs(kap*r - 1.0_dp))
    end do
    call assert_true(worst_eps <= 2.0e-5_dp, 'consistent: arc strain '//trim(rtoa(worst_eps)))
    call assert_true(worst_kap <= 1.0e-3_dp, 'consistent: arc curvature error '//trim(rtoa(worst_kap)))
    call kear_element_init(kel, l_u, b_u, t_u, soft, element_effects_t(stretching=.true., curvature=.true.), err)
    pk = [p(1), p(2), p(3), p(4), p(7), p(8), p(9), p(10)]
    kear_eps = 0.0_dp
    do i = 0, 20
      call kel%section_strains(pk, i/20.0_dp, eps, kap)
      kear_eps = max(kear_eps, abs(eps))
    end do
    call assert_true(kear_eps > 0.02_dp, 'Kear element: arc strain '//trim(rtoa(kear_eps))//' (locks)')
  end subroutine test_arc_no_locking

  !> The stress recovery's strains from the gradients tabulated at its
  !> stations (both ends and the Gauss points) against the strains evaluated
  !> from the shape functions at those positions, for both elements on a
  !> strongly deformed state: 1e-12 relative (the same products; only the
  !> compiler's ordering may differ).  A station table in the wrong order or
  !> at the wrong positions would differ by the strain's variation, > 1e-3.
  subroutine test_station_strains()
    type(consistent_element_t) :: el
    type(kear_element_t) :: kel
    type(error_t) :: err
    real(dp) :: p(12), pk(8), e1(0:max_gauss_points + 1), k1(0:max_gauss_points + 1), e2, k2, worst
    integer :: i
    el = unit_element(effects_all_on())
    p = el%local_dofs(q_big, 0.3_dp)
    worst = 0.0_dp
    call el%station_strains(p, e1(:el%n_gauss + 1), k1(:el%n_gauss + 1))
    do i = 0, el%n_gauss + 1
      call el%section_strains(p, station_x_over_l(el%beam_properties_t, el%xg, i), e2, k2)
      worst = max(worst, abs(e1(i) - e2)/max(abs(e2), 1.0e-3_dp), abs(k1(i) - k2)/max(abs(k2), 1.0e-3_dp))
    end do
    call assert_true(worst <= 1.0e-12_dp, 'consistent: station strains differ by '//trim(rtoa(worst)))
    call kear_element_init(kel, l_u, b_u, t_u, soft, effects_all_on(), err)
    pk = kel%local_dofs([q_big(1:4), q_big(7:10)], 0.3_dp)
    worst = 0.0_dp
    call kel%station_strains(pk, e1(:kel%n_gauss + 1), k1(:kel%n_gauss + 1))
    do i = 0, kel%n_gauss + 1
      call kel%section_strains(pk, station_x_over_l(kel%beam_properties_t, kel%xg, i), e2, k2)
      worst = max(worst, abs(e1(i) - e2)/max(abs(e2), 1.0e-3_dp), abs(k1(i) - k2)/max(abs(k2), 1.0e-3_dp))
    end do
    call assert_true(worst <= 1.0e-12_dp, 'Kear: station strains differ by '//trim(rtoa(worst)))
  end subroutine test_station_strains

  !> With all effects off the w-w block of the linear stiffness is Kear's
  !> (the same quintic w, EI int h'' h''), and the u-u block is EA int h' h'
  !> of the quintics: for a uniform stretch (u = eps x) the energy is
  !> EA eps^2 l/2 exactly.
  subroutine test_linear_bending_block()
    type(consistent_element_t) :: el
    type(kear_element_t) :: kel
    type(error_t) :: err
    integer, parameter :: wc(6) = [2, 3, 4, 8, 9, 10], wk(6) = [2, 3, 4, 6, 7, 8]
    real(dp) :: p(12), eps
    el = unit_element(element_effects_t())
    call kear_element_init(kel, l_u, b_u, t_u, soft, element_effects_t(), err)
    call assert_all_close(reshape(el%k_linear(wc, wc), [36]), reshape(kel%k_linear(wk, wk), [36]), 0.0_dp, &
                          1.0e-12_dp*maxval(abs(kel%k_linear)), 'bending block = Kear element')
    eps = 1.0e-3_dp
    p = 0.0_dp
    p(5) = eps
    p(7) = eps*l_u
    p(11) = eps
    call assert_rel_close(beam_strain_energy(el, p, 0.0_dp), 0.5_dp*soft%e1*b_u*t_u*eps**2*l_u, 1.0e-12_dp, &
                          'uniform stretch energy')
  end subroutine test_linear_bending_block

  !> The generalized force of a point force f and moment mz at x = 0.6 l is
  !> the gradient of the work f . r(x) + mz theta(x), r and theta computed
  !> from the displacement field (beam_local_displacement; theta =
  !> atan2(w_x, 1 + u_x) with w_x, u_x by differences in x); its Jacobian
  !> the FD derivative.  Both interpolations; 1e-7 relative.
  subroutine test_point_load()
    character(len=10), parameter :: names(2) = [character(len=10) :: 'exact', 'consistent']
    class(planar_element_t), allocatable :: el
    real(dp) :: gen(12), g(12), dgen(12, 12), gp(12), gm(12), dfd(12, 12), e(12), q(12), f(2), mz, phi, h
    integer :: k, n, j
    f = [0.7_dp, -1.3_dp]
    mz = 0.45_dp
    phi = 0.6_dp
    h = 1.0e-5_dp
    do k = 1, size(names)
      if (allocated(el)) deallocate(el)
      allocate(el, source=unit_beam(trim(names(k)), effects_all_on()))
      n = el%n_dofs()
      q(1:n) = q_big(1:n)
      call beam_point_load(el, q(1:n), phi, 0.6_dp, f, mz, gen(1:n), dgen(1:n, 1:n))
      do j = 1, n
        e = 0.0_dp
        e(j) = h
        g(j) = (work(q(1:n) + e(1:n)) - work(q(1:n) - e(1:n)))/(2*h)
        call beam_point_load(el, q(1:n) + e(1:n), phi, 0.6_dp, f, mz, gp(1:n))
        call beam_point_load(el, q(1:n) - e(1:n), phi, 0.6_dp, f, mz, gm(1:n))
        dfd(1:n, j) = (gp(1:n) - gm(1:n))/(2*h)
      end do
      call assert_all_close(gen(1:n), g(1:n), 0.0_dp, 1.0e-7_dp*maxval(abs(g(1:n))), 'point load = d(work)/dq')
      call assert_all_close(reshape(dgen(1:n, 1:n), [n*n]), reshape(dfd(1:n, 1:n), [n*n]), 0.0_dp, &
                            1.0e-6_dp*maxval(abs(dfd(1:n, 1:n))), 'point load Jacobian')
    end do
  contains
    real(dp) function work(qq)
      real(dp), intent(in) :: qq(:)
      real(dp) :: uw(2), up(2), um(2), dx, r(2), th
      uw = beam_local_displacement(el, qq, phi, 0.6_dp)
      dx = 1.0e-4_dp
      up = beam_local_displacement(el, qq, phi, 0.6_dp + dx)
      um = beam_local_displacement(el, qq, phi, 0.6_dp - dx)
      th = atan2((up(2) - um(2))/(2*dx*l_u), 1.0_dp + (up(1) - um(1))/(2*dx*l_u))
      ! position relative to the rigid frame origin, in global axes
      r = [cos(phi)*(0.6_dp*l_u + uw(1)) - sin(phi)*uw(2), sin(phi)*(0.6_dp*l_u + uw(1)) + cos(phi)*uw(2)]
      work = dot_product(f, r) + mz*th
    end function work
  end subroutine test_point_load

  !> The evaluation's switches for both elements (one evaluation,
  !> planar_evaluation.inc): for the linear strain model, force_wanted =
  !> .false. (with the tangent) returns the M and K_t of the full evaluation
  !> (to 1e-14 of their largest entry: the same constant integrals rotated;
  !> a wrong rotation or a missing rotary term would differ by O(1));
  !> mass_wanted = .false. leaves the force unchanged; peak_wanted = .false.
  !> skips the informative strain peak, which is positive otherwise.
  subroutine test_evaluation_switches()
    character(len=10), parameter :: names(2) = [character(len=10) :: 'exact', 'consistent']
    class(planar_element_t), allocatable :: el
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    real(dp), allocatable :: m1(:, :), k1(:, :), f1(:), m2(:, :), k2(:, :), f2(:)
    integer :: k, n
    rb = rigid_at(0.2_dp)
    do k = 1, size(names)
      if (allocated(el)) deallocate(el, m1, k1, f1, m2, k2, f2)
      allocate(el, source=unit_beam(trim(names(k)), element_effects_t(rotary_inertia=.true., coupling=.true.)))
      n = el%n_dofs()
      allocate(m1(n, n), k1(n, n), f1(n), m2(n, n), k2(n, n), f2(n))
      call el%eval(q_big(1:n), qd_big(1:n), rb, m1, f1, info, k1)
      call assert_true(info%max_abs_strain > 0.0_dp, trim(names(k))//': strain peak computed')
      call el%eval(q_big(1:n), qd_big(1:n), rb, m2, f2, info, k2, force_wanted=.false.)
      call assert_all_close(reshape(m2, [n*n]), reshape(m1, [n*n]), 0.0_dp, 1.0e-14_dp*maxval(abs(m1)), &
                            trim(names(k))//': M without the force')
      call assert_all_close(reshape(k2, [n*n]), reshape(k1, [n*n]), 0.0_dp, 1.0e-14_dp*maxval(abs(k1)), &
                            trim(names(k))//': K_t without the force')
      call el%eval(q_big(1:n), qd_big(1:n), rb, m2, f2, info, mass_wanted=.false., peak_wanted=.false.)
      call assert_all_close(f2, f1, 0.0_dp, 1.0e-14_dp*maxval(abs(f1)), trim(names(k))//': F without M')
      call assert_true(info%max_abs_strain <= 0.0_dp, trim(names(k))//': strain peak skipped')
    end do
  end subroutine test_evaluation_switches

  !> 'default' is the consistent element with stretching on, Kear's element
  !> (exact equations) otherwise; unknown names are an error naming them.
  subroutine test_default_formulation()
    class(planar_element_t), allocatable :: mold
    character(len=:), allocatable :: resolved
    type(error_t) :: err
    call resolve_formulation('default', element_effects_t(stretching=.true.), mold, resolved, err)
    call assert_true(is_consistent(mold) .and. resolved == 'consistent', 'stretching on: '//resolved)
    call resolve_formulation('default', element_effects_t(curvature=.true.), mold, resolved, err)
    call assert_true(kear_formulation(mold) == 1 .and. resolved == 'exact', 'stretching off: '//resolved)
    call resolve_formulation('kear1987', element_effects_t(stretching=.true.), mold, resolved, err)
    call assert_true(kear_formulation(mold) == formulation_kear1987, 'kear1987 stays selectable')
    call resolve_formulation('corotational', element_effects_t(), mold, resolved, err)
    call assert_true(err%failed() .and. index(err%text(), 'corotational') > 0, 'unknown: '//err%text())
  end subroutine test_default_formulation

  logical function is_consistent(el)
    class(planar_element_t), intent(in) :: el
    select type (el)
    type is (consistent_element_t)
      is_consistent = .true.
    class default
      is_consistent = .false.
    end select
  end function is_consistent

  !> Kear's formulation code of the mold, 0 for another element.
  integer function kear_formulation(el)
    class(planar_element_t), intent(in) :: el
    select type (el)
    type is (kear_element_t)
      kear_formulation = el%formulation
    class default
      kear_formulation = 0
    end select
  end function kear_formulation
end module test_consistent_element_suite

program test_consistent_element
  use test_consistent_element_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_consistent_element')
end program test_consistent_element
