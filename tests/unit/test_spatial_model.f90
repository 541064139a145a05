!> Tests of the assembled spatial four-bar (module spatial_model): the
!> planar limit against the planar mechanism_model (Kear's element, same
!> physics and mesh), right-hand side and a quarter revolution of DLSODE;
!> the RSSR model (spherical joints, non-parallel axes): table, modes,
!> energy conservation of the free nonlinear structure; the RSUR (universal
!> joint at C): table and the energy balance of the driven run.
module test_spatial_model_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t
  use element_effects, only: element_effects_t
  use planar_element, only: stress_report_t
  use mechanism_model, only: mechanism_model_t
  use transient_fixtures, only: fourbar_input, make_model
  use lsode_solver, only: ode_system_t, lsode_t, lsode_counters_t, mf_adams, mf_bdf_full_user
  use quadrature, only: gauss_legendre_interval
  use spatial_section, only: spatial_section_init, section_rectangular, section_circular
  use spatial_beam, only: spatial_stress_t, spatial_to_local, spatial_local_displacement, spatial_formulation_kear
  use linalg, only: cross
  use spatial_kinematics, only: spatial_fourbar_t, spatial_fourbar_init, spatial_fourbar_set_universal, link_rocker
  use spatial_model
  use assertions
  implicit none
  private
  public :: run_all

  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=0.0002536_dp)
  real(dp), parameter :: g_alu = 10.87e6_dp/(2.0_dp*1.33_dp)
  !> planar DOFs [U1 W1 th1 m1 U2 W2 th2 m2] -> spatial element DOFs
  integer, parameter :: pmap(8) = [1, 2, 6, 7, 11, 12, 16, 17]

contains

  subroutine run_all()
    call run_test('planar_limit_rhs_equals_planar_model', test_planar_rhs)
    call run_test('planar_limit_quarter_turn_equals_planar_transient', test_planar_transient)
    call run_test('rssr_model_table_modes_and_mass', test_rssr_model)
    call run_test('free_nonlinear_structure_conserves_energy', test_energy)
    call run_test('driven_rssr_jacobi_energy_balance', test_jacobi_balance)
    call run_test('rsur_table_holds_twist_at_the_universal_joint', test_rsur_model)
    call run_test('driven_rsur_jacobi_energy_balance', test_jacobi_balance_rsur)
    call run_test('support_forces_are_momentum_rate', test_support_forces)
    call run_test('banded_newton_matrix_equals_dense_p', test_banded_newton)
    call run_test('constant_factor_mass_solve_equals_dense_mass', test_constant_mass)
  end subroutine run_all

  function effects(variant) result(fx)
    integer, intent(in) :: variant
    type(element_effects_t) :: fx
    select case (variant)
    case (1)
      fx = element_effects_t(.false., .false., .false., .false., .false.)
    case default
      ! every effect whose physics both elements share (rotary inertia: the
      ! planar element uses the exact section angle with curvature on)
      fx = element_effects_t(.true., .true., .true., .false., .true.)
    end select
  end function effects

  !> Tennant's four-bar in the spatial code: revolute joints about Z.
  subroutine planar_spatial(n, omega, fx, beta, sm)
    integer, intent(in) :: n
    real(dp), intent(in) :: omega, beta
    type(element_effects_t), intent(in) :: fx
    type(spatial_model_t), intent(out) :: sm
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(error_t) :: err
    integer :: k
    call spatial_fourbar_init(kin, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [5.0_dp, 0.0_dp, 0.0_dp], &
                              [10.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], 10.5_dp, 11.0_dp, 1, err)
    do k = 1, 3
      links(k)%n_elements = n
      links(k)%material = alu
      links(k)%shear_modulus = g_alu
      call spatial_section_init(links(k)%sec, section_rectangular, [1.0_dp, 0.25_dp], alu, err)
    end do
    call sm%init(kin, omega, 0.0_dp, spatial_joint_revolute, spatial_joint_revolute, links, fx, beta, err, &
                 formulation=spatial_formulation_kear)     ! the planar Kear element's interpolation
    call assert_true(.not. err%failed(), 'spatial model: '//err%text())
  end subroutine planar_spatial

  !> Spatial global index of every planar global unknown (through the elements).
  function index_map(pm, sm) result(idx)
    type(mechanism_model_t), intent(in) :: pm
    type(spatial_model_t), intent(in) :: sm
    integer :: idx(pm%n)
    integer :: e, i
    idx = 0
    do e = 1, size(pm%el)
      do i = 1, 8
        if (pm%table%unknown(i, e) > 0) idx(pm%table%unknown(i, e)) = sm%table%unknown(pmap(i), e)
      end do
    end do
  end function index_map

  !> Accelerations at in-plane states: spatial = planar to 1e-10 of the
  !> largest (round-off of two different assemblies and factorisations of
  !> the same equations); out-of-plane accelerations 1e-12 of it.
  subroutine test_planar_rhs()
    type(mechanism_model_t) :: pm
    type(spatial_model_t) :: sm
    logical :: ok
    integer :: variant, i
    integer, allocatable :: idx(:)
    real(dp), allocatable :: qp(:), qdp(:), ap(:), qs(:), qds(:), as(:)
    logical, allocatable :: inplane(:)
    real(dp) :: t
    do variant = 1, 2
      call make_model(fourbar_input(2, 150.0_dp, 0.0_dp), effects(variant), 2.0e-5_dp, pm, ok, table=.false.)
      call planar_spatial(2, 150.0_dp, effects(variant), 2.0e-5_dp, sm)
      idx = index_map(pm, sm)
      call assert_true(all(idx > 0), 'every planar unknown has a spatial twin')
      allocate(qp(pm%n), qdp(pm%n), ap(pm%n), qs(sm%n), qds(sm%n), as(sm%n), inplane(sm%n))
      qp = [(1.0e-3_dp*sin(1.7_dp*i), i=1, pm%n)]
      qdp = [(0.3_dp*cos(2.3_dp*i), i=1, pm%n)]
      qs = 0.0_dp
      qds = 0.0_dp
      qs(idx) = qp
      qds(idx) = qdp
      inplane = .false.
      inplane(idx) = .true.
      t = 0.0123_dp
      call pm%accelerations(t, qp, qdp, ap)
      call sm%accelerations(t, qs, qds, as)
      call assert_true(.not. (pm%err%failed() .or. sm%err%failed()), 'accelerations')
      call assert_all_close(as(idx), ap, 0.0_dp, 1.0e-10_dp*maxval(abs(ap)), 'in-plane accelerations = planar')
      call assert_true(maxval(abs(as), mask=.not. inplane) <= 1.0e-12_dp*maxval(abs(ap)), &
                       'out-of-plane accelerations vanish')
      deallocate(qp, qdp, ap, qs, qds, as, inplane)
    end do
  end subroutine test_planar_rhs

  !> 30 degrees of crank at 100 rad/s from the rigid-body state, one element
  !> per link, both codes with DLSODE Adams at rtol = 1e-11: B's elastic
  !> displacement and every
  !> element's max |stress| agree to 1e-6 relative (each run is accurate to
  !> ~1e-9; they differ in step choices only), out-of-plane motion stays at
  !> round-off (1e-12 of the in-plane scale).
  subroutine test_planar_transient()
    type(mechanism_model_t), target :: pm
    type(spatial_model_t), target :: sm
    type(lsode_t) :: op, os
    type(error_t) :: err
    logical :: ok
    integer, allocatable :: idx(:)
    real(dp), allocatable :: yp(:), ys(:)
    type(stress_report_t) :: sp(3)
    type(spatial_stress_t) :: ss(3)
    real(dp) :: t, bp(2, 3), bs(3), scale, sp_max(3, 3)
    integer :: k, e
    call make_model(fourbar_input(1, 100.0_dp, 0.0_dp), effects(2), 0.0_dp, pm, ok, table=.false.)
    call planar_spatial(1, 100.0_dp, effects(2), 0.0_dp, sm)
    idx = index_map(pm, sm)
    allocate(yp(2*pm%n), ys(2*sm%n))
    yp = 0.0_dp
    ys = 0.0_dp
    ! DLSODE is not re-entrant: the planar run first, then the spatial one
    call op%init(size(yp), 0.0_dp, mf_adams, 1.0e-11_dp, [1.0e-14_dp], err, max_steps=100000)
    do k = 1, 3
      t = step_to(op, pm, yp, k, 'planar')
      call pm%set_time(t)
      bp(:, k) = yp(2*pm%table%unknowns_of([5, 6], 1) - 1)            ! crank end = B (U, W)
      call pm%element_stresses(yp(1::2), sp)
      sp_max(:, k) = sp%max_abs_stress
    end do
    call os%init(size(ys), 0.0_dp, mf_adams, 1.0e-11_dp, [1.0e-14_dp], err, max_steps=100000)
    do k = 1, 3
      t = step_to(os, sm, ys, k, 'spatial')
      call sm%set_time(t)
      bs = ys(2*sm%b_dofs - 1)
      scale = maxval(abs(bp(:, k)))
      call assert_all_close(bs(1:2), bp(:, k), 0.0_dp, 1.0e-6_dp*scale, 'B displacement = planar')
      call assert_true(abs(bs(3)) <= 1.0e-12_dp*scale, 'B stays in the plane')
      call sm%element_stresses(ys(1::2), ss)
      do e = 1, 3
        call assert_rel_close(ss(e)%max_abs_stress, sp_max(e, k), 1.0e-6_dp, 'element max |stress|')
      end do
    end do
    call assert_true(maxval(abs(ys(1::2))) > 0.0_dp, 'the structure moved')
  contains
    !> On to crank angle 10 k deg (100 rad/s).
    real(dp) function step_to(ode, sys, y, k, label) result(tk)
      type(lsode_t), intent(inout) :: ode
      class(ode_system_t), intent(inout), target :: sys
      real(dp), intent(inout), contiguous :: y(:)
      integer, intent(in) :: k
      character(len=*), intent(in) :: label
      tk = real(k, dp)*(pi/18.0_dp)/100.0_dp
      call ode%integrate_to(sys, y, tk, err)
      call assert_true(.not. err%failed(), label//' integration: '//err%text())
    end function step_to
  end subroutine test_planar_transient

  !> RSSR (crank axis Z, rocker axis X), spherical B and C, 2 elements per
  !> link, circular 0.2 in steel-like links: the table holds the coupler's
  !> twist at B, the mass matrix factors, the linearised structure has no
  !> zero-frequency mode (lowest > 1 rad/s), and the header lists the table.
  subroutine test_rssr_model()
    type(spatial_model_t) :: sm
    type(error_t) :: err
    real(dp), allocatable :: om(:), q(:), qdd(:)
    character(len=160), allocatable :: lines(:)
    call rssr_model(2, 50.0_dp, effects(2), 0.0_dp, sm)
    call assert_equal(sm%table%unknown(4, sm%links(2)%first_element), 0, 'coupler twist held at B')
    call assert_true(all(sm%table%unknowns_of([7, 8], sm%links(2)%first_element) == 0), 'no moment at spherical B')
    call assert_true(sm%el(sm%links(2)%first_element)%local_rotation(1), 'coupler rotations at B local')
    allocate(om(sm%n), q(sm%n), qdd(sm%n))
    call sm%linear_modes(om, err)
    call assert_true(.not. err%failed(), 'modes: '//err%text())
    call assert_true(om(1) > 1.0_dp, 'no free mechanism mode in the elastic structure')
    q = 0.0_dp
    call sm%accelerations(0.0_dp, q, q, qdd)
    call assert_true(.not. sm%err%failed(), 'mass factors: '//sm%err%text())
    call assert_true(maxval(abs(qdd)) > 0.0_dp, 'inertia loads the rigid-state structure')
    call sm%table%describe(lines)
    call assert_true(index(lines(1), 'half-bandwidth') > 0 .and. size(lines) > 6, 'table header')
  end subroutine test_rssr_model

  subroutine rssr_model(n, omega, fx, beta, sm, scale, radius, formulation, universal_c)
    integer, intent(in) :: n
    integer, intent(in), optional :: formulation   !< default: the consistent element
    logical, intent(in), optional :: universal_c   !< RSUR: universal joint at C, cross axis (0, 1, 1) in the rocker
    real(dp), intent(in) :: omega, beta
    real(dp), intent(in), optional :: scale, radius   !< geometry factor (1), link radius (0.1 in)
    type(element_effects_t), intent(in) :: fx
    type(spatial_model_t), intent(out) :: sm
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(error_t) :: err
    integer :: k, jc
    real(dp) :: f, r
    jc = spatial_joint_spherical
    f = 1.0_dp
    r = 0.1_dp
    if (present(scale)) f = scale
    if (present(radius)) r = radius
    call spatial_fourbar_init(kin, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], f*[1.5_dp, 0.0_dp, 0.0_dp], &
                              f*[0.0_dp, 5.0_dp, 3.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], f*3.0_dp, f*6.0_dp, 1, err)
    if (present(universal_c)) then
      if (universal_c) then
        call spatial_fourbar_set_universal(kin, .true., [0.0_dp, 1.0_dp, 1.0_dp], err)
        jc = spatial_joint_universal
      end if
    end if
    do k = 1, 3
      links(k)%n_elements = n
      links(k)%material = alu
      links(k)%shear_modulus = g_alu
      call spatial_section_init(links(k)%sec, section_circular, [r], alu, err)
    end do
    call sm%init(kin, omega, 0.0_dp, spatial_joint_spherical, jc, links, fx, beta, err, formulation=formulation)
    call assert_true(.not. err%failed(), 'rssr model: '//err%text())
  end subroutine rssr_model

  !> Crank at rest (omega = 0: a fixed spatial frame structure), every
  !> nonlinear effect and rotary inertia on, the RSSR scaled by 4 with one
  !> element per link (a mild stiffness spread for Adams), released from a
  !> large initial velocity: KE + SE stays constant to ~ the integration
  !> error.  Adams at rtol = 1e-8 over 2 periods of the lowest mode: drift
  !> bound 1e-5 relative (1000 rtol; a wrong sign or factor in any force
  !> term gives O(1) drift).
  subroutine test_energy()
    type(spatial_model_t), target :: sm
    type(lsode_t) :: ode
    type(error_t) :: err
    type(element_effects_t) :: fx
    real(dp), allocatable :: y(:), om(:)
    real(dp) :: ke0, se0, ke, se, e0, t1
    integer :: i, k
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call rssr_model(1, 0.0_dp, fx, 0.0_dp, sm, scale=4.0_dp, radius=0.2_dp, formulation=spatial_formulation_kear)
    allocate(y(2*sm%n), om(sm%n))
    call sm%linear_modes(om, err)
    y = 0.0_dp
    y(2::2) = [(20.0_dp*sin(0.9_dp*i), i=1, sm%n)]     ! in/s, rad/s: strains ~1e-3
    call sm%energies(0.0_dp, y(1::2), y(2::2), ke0, se0)
    e0 = ke0 + se0
    call ode%init(size(y), 0.0_dp, mf_adams, 1.0e-8_dp, [1.0e-12_dp], err, max_steps=200000)
    t1 = 2.0_dp*two_pi/om(1)
    do k = 1, 4
      call ode%integrate_to(sm, y, real(k, dp)*t1/4.0_dp, err)
      call assert_true(.not. err%failed(), 'integration: '//err%text())
      call sm%energies(real(k, dp)*t1/4.0_dp, y(1::2), y(2::2), ke, se)
      call assert_rel_close(ke + se, e0, 1.0e-5_dp, 'energy conserved')
    end do
    call assert_true(se > 1.0e-3_dp*e0, 'energy moved into strain')
  end subroutine test_energy
  !> Energy balance of the DRIVEN, undamped RSSR at 100 rad/s, every effect
  !> on, one element per link: with L(q, q', t) = KE - SE, the Jacobi
  !> integral h = q'.dL/dq' - L = KE2 - KE0 + SE obeys dh/dt = -dL/dt|_(q,q').
  !> The explicit time dependence is the rigid motion: in KE, and in SE too,
  !> because SE sees the local DOFs p = T(t)^T q of the global unknowns.
  !> KE2 - KE0 by polarisation, (KE(q') + KE(-q'))/2 - 2 KE(0); dL/dt by
  !> central differences (dt = 1e-8 s) with the kinematics re-solved; the
  !> integral by Simpson's rule on 0.05-degree steps (the elastic
  !> oscillations in dL/dt resolved) over 20 degrees.  Adams at rtol = 1e-9:
  !> measured residual 3.4e-9 lb in = 1.5e-9 of the largest strain energy;
  !> bound 1e-6 of it.  Leaving out dSE/dt (SE's dependence on T(t)) gives
  !> 3 % of it, a wrong inertia term, a rate of the kinematics inconsistent
  !> with its positions or a wrong joint rule O(1).
  subroutine test_jacobi_balance()
    call jacobi_balance(.false.)
  end subroutine test_jacobi_balance

  !> The same balance for the RSUR (universal joint at C, cross axis (0, 1, 1)
  !> in the rocker frame): the coupler's spin now follows the joint, its
  !> twist is held at C; same bound.  This checks the universal joint's
  !> coupler rates (omega, alpha) against its positions through the whole
  !> model, and that the joint rule is a consistent (workless) constraint.
  subroutine test_jacobi_balance_rsur()
    call jacobi_balance(.true.)
  end subroutine test_jacobi_balance_rsur

  !> RSUR, 2 elements per link: the coupler's twist is held at C (the
  !> universal joint) and free at B; both ends' rotations local, no moment
  !> (curvatures held) at B and C; the structure has no free mode; a
  !> universal joint with a revolute one is bad input (code 2).
  subroutine test_rsur_model()
    type(spatial_model_t) :: sm
    type(error_t) :: err
    real(dp), allocatable :: om(:)
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    integer :: ec
    call rssr_model(2, 50.0_dp, effects(2), 0.0_dp, sm, universal_c=.true.)
    ec = sm%links(2)%first_element + 1
    call assert_true(sm%table%unknown(4, sm%links(2)%first_element) > 0, 'coupler twist free at B')
    call assert_equal(sm%table%unknown(14, ec), 0, 'coupler twist held at C')
    call assert_true(all(sm%table%unknowns_of([17, 18], ec) == 0), 'no moment at universal C')
    call assert_true(sm%el(ec)%local_rotation(2), 'coupler rotations at C local')
    allocate(om(sm%n))
    call sm%linear_modes(om, err)
    call assert_true(.not. err%failed(), 'modes: '//err%text())
    call assert_true(om(1) > 1.0_dp, 'no free mechanism mode in the elastic structure')
    kin = sm%kin
    links = sm%links
    call sm%init(kin, 50.0_dp, 0.0_dp, spatial_joint_revolute, spatial_joint_universal, links, effects(2), &
                 0.0_dp, err)
    call assert_true(err%failed() .and. err%code == 2 .and. index(err%text(), 'universal') > 0, &
                     'universal with revolute refused: '//err%text())
  end subroutine test_rsur_model

  subroutine jacobi_balance(universal_c)
    logical, intent(in) :: universal_c
    type(spatial_model_t), target :: sm
    type(lsode_t) :: ode
    type(error_t) :: err
    type(element_effects_t) :: fx
    integer, parameter :: nint_steps = 400
    real(dp), allocatable :: y(:), zero(:)
    real(dp) :: h(0:nint_steps), dkdt(0:nint_steps), t, dt, kp, km, k0, ke, se, sdum, se_max, integral
    real(dp), parameter :: omega = 100.0_dp, delta = 1.0e-8_dp
    integer :: k
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call rssr_model(1, omega, fx, 0.0_dp, sm, scale=4.0_dp, radius=0.25_dp, universal_c=universal_c)
    allocate(y(2*sm%n), zero(sm%n))
    y = 0.0_dp
    zero = 0.0_dp
    dt = (0.05_dp*pi/180.0_dp)/omega
    se_max = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_adams, 1.0e-9_dp, [1.0e-13_dp], err, max_steps=500000)
    do k = 0, nint_steps
      t = real(k, dp)*dt
      if (k > 0) call ode%integrate_to(sm, y, t, err)
      call assert_true(.not. err%failed(), 'integration: '//err%text())
      call sm%energies(t, y(1::2), y(2::2), kp, se)
      call sm%energies(t, y(1::2), -y(2::2), km, sdum)
      call sm%energies(t, y(1::2), zero, k0, sdum)
      h(k) = 0.5_dp*(kp + km) - 2.0_dp*k0 + se
      se_max = max(se_max, se)
      call sm%energies(t + delta, y(1::2), y(2::2), kp, sdum)
      call sm%energies(t - delta, y(1::2), y(2::2), km, se)
      dkdt(k) = (kp - sdum - km + se)/(2.0_dp*delta)          ! dL/dt, L = KE - SE
      call sm%set_time(t)
    end do
    integral = 0.0_dp
    do k = 0, nint_steps - 2, 2
      integral = integral + dt/3.0_dp*(dkdt(k) + 4.0_dp*dkdt(k + 1) + dkdt(k + 2))
    end do
    ke = h(nint_steps) - h(0) + integral
    call assert_true(se_max > 0.1_dp, 'the links deform (strain energy > 0.1 lb in)')
    call assert_close(ke, 0.0_dp, 1.0e-6_dp*se_max, 'h(t1) - h(t0) + int dL/dt dt = 0')
    print '(a,es10.3,a,es10.3,a,es10.3)', '    Jacobi balance residual ', ke, ' lb in; max strain energy ', se_max, &
      ' ; int |dL/dt| ~ ', dt*sum(abs(dkdt))
  end subroutine jacobi_balance
  !> Support forces of the driven RSSR (100 rad/s, every effect on, two
  !> elements per link) at an elastic state (q, q'), against Newton's law
  !> computed independently from the material points: f_A + f_D =
  !> sum int rho A a dx, with the absolute acceleration of each point
  !> a = x1'' + alpha x r + omega x (omega x r) + 2 omega x r_el' + r_el''
  !> from the element shape functions, the rigid state and the local
  !> elastic acceleration p'' = T^T q'' - 2 W v + (W^2 - W') p (6 Gauss
  !> points per element: exact).  Tolerance 1e-9 of the largest force.
  subroutine test_support_forces()
    type(spatial_model_t) :: sm
    type(element_effects_t) :: fx
    real(dp), allocatable :: q(:), qd(:), qdd(:)
    real(dp) :: fa(3), fd(3), total(3), t
    real(dp) :: xg(6), wg(6), p(20), v(20), pd(20), pdd(20), wl(3), al(3), r(3), rd(3), rdd(3), acc(3)
    integer :: i, e, k
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call rssr_model(2, 100.0_dp, fx, 0.0_dp, sm, scale=4.0_dp, radius=0.25_dp)
    allocate(q(sm%n), qd(sm%n), qdd(sm%n))
    q = [(1.0e-3_dp*sin(1.3_dp*i), i=1, sm%n)]
    qd = [(0.5_dp*cos(0.7_dp*i), i=1, sm%n)]
    t = 0.0041_dp
    call sm%support_forces(t, q, qd, fa, fd)
    call sm%accelerations(t, q, qd, qdd)
    total = 0.0_dp
    do e = 1, size(sm%el)
      associate (el => sm%el(e), rb => sm%rb(e))
        call gauss_legendre_interval(6, 0.0_dp, el%length, xg, wg)
        wl = matmul(rb%omega, rb%rot)
        al = matmul(rb%alpha, rb%rot)
        p = spatial_to_local(rb%rot, sm%table%gather(e, q), el%local_rotation)
        v = spatial_to_local(rb%rot, sm%table%gather(e, qd), el%local_rotation)
        pd = v - wtimes(wl, p, el%local_rotation)
        pdd = spatial_to_local(rb%rot, sm%table%gather(e, qdd), el%local_rotation) &
              - 2.0_dp*wtimes(wl, v, el%local_rotation) + wtimes(wl, wtimes(wl, p, el%local_rotation), el%local_rotation) &
              - wtimes(al, p, el%local_rotation)
        do k = 1, 6
          r = [xg(k), 0.0_dp, 0.0_dp] + spatial_local_displacement(el, p, xg(k)/el%length)
          rd = spatial_local_displacement(el, pd, xg(k)/el%length)
          rdd = spatial_local_displacement(el, pdd, xg(k)/el%length)
          acc = matmul(rb%x1_dd, rb%rot) + cross(al, r) + cross(wl, cross(wl, r)) + 2.0_dp*cross(wl, rd) + rdd
          total = total + wg(k)*el%material%rho*el%sec%area*matmul(rb%rot, acc)
        end do
      end associate
    end do
    call assert_all_close(fa + fd, total, 0.0_dp, 1.0e-9_dp*maxval(abs([fa, fd])), 'f_A + f_D = momentum rate')
    call assert_true(maxval(abs(fa)) > 1.0_dp .and. maxval(abs(fd)) > 1.0_dp, 'both supports carry load')
  contains
    !> omega x each vector triple that turns with the frame (the element's T_dot = T W)
    function wtimes(w, x, local) result(y)
      real(dp), intent(in) :: w(3), x(20)
      logical, intent(in) :: local(2)
      real(dp) :: y(20)
      y = 0.0_dp
      y(1:3) = cross(w, x(1:3))
      if (.not. local(1)) y(4:6) = cross(w, x(4:6))
      y(11:13) = cross(w, x(11:13))
      if (.not. local(2)) y(14:16) = cross(w, x(14:16))
    end function wtimes
  end subroutine test_support_forces

  !> BDF through the model's banded N x N Newton matrix against DLSODE's dense
  !> 2N x 2N P formed from the same analytic J (structured = .false.): the two
  !> P are the same matrix up to round-off, so the banded route needs about
  !> as many right-hand sides as the dense one (bound 1.5x: the step
  !> sequences drift apart by round-off, measured 5559 against 6860 in the
  !> release build, 6613 against 5502 in the debug build; a wrong term in S
  !> or in the solve stalls the chord iteration) and
  !> the runs agree to 1e-6 of the deflection (rtol 1e-8).
  !> RSSR, 2 elements per link, every effect, damping beta = 1e-4 s (the
  !> beta h el0 K term), 20 degrees at 100 rad/s.
  subroutine test_banded_newton()
    type(spatial_model_t), target :: sm
    type(lsode_t) :: ode
    type(lsode_counters_t) :: c(2)
    type(error_t) :: err
    real(dp), allocatable :: y(:, :)
    real(dp) :: t_end
    integer :: k
    t_end = (pi/9.0_dp)/100.0_dp
    do k = 1, 2
      call rssr_model(2, 100.0_dp, element_effects_t(.true., .true., .true., .true., .true.), 1.0e-4_dp, sm, &
                      formulation=spatial_formulation_kear)
      if (k == 1) allocate(y(2*sm%n, 2))
      y(:, k) = 0.0_dp
      call ode%init(2*sm%n, 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, [1.0e-12_dp], err, max_steps=200000, &
                    structured=k == 1)
      call ode%integrate_to(sm, y(:, k), t_end, err)
      call assert_true(.not. err%failed(), 'integration: '//err%text())
      c(k) = ode%counters()
    end do
    call assert_true(c(1)%model_newton .and. .not. c(2)%model_newton, 'routes')
    print '(a,4i8)', '    steps, RHS banded and dense:', c(1)%steps, c(1)%rhs_evals, c(2)%steps, c(2)%rhs_evals
    call assert_true(c(1)%rhs_evals <= 1.5_dp*c(2)%rhs_evals, 'corrector work as with the dense P')
    call assert_all_close(y(1::2, 1), y(1::2, 2), 0.0_dp, 1.0e-6_dp*maxval(abs(y(1::2, 2))), 'same deflections')
    call assert_true(maxval(abs(y(1::2, 2))) > 0.0_dp, 'the structure deflected')
  end subroutine test_banded_newton
  !> spatial_mass (the constant link-frame factor with the joint unknowns'
  !> Schur complement) against the dense M(t) assembled element by element
  !> (assemble_dense): the planar four-bar (revolute B, C: shared global
  !> rotations), the RSSR (consistent element) and the RSUR, at five crank
  !> angles each: the path is active, and M(t) x = f to 1e-10 of |f| (the
  !> residual of a backward-stable solve is ~eps |M| |x|; measured up to
  !> 1.5e-12).
  !> A wrong rotation, Schur term or owned-triple rule leaves O(1) residuals.
  subroutine test_constant_mass()
    type(spatial_model_t) :: sm
    real(dp), allocatable :: mass(:, :), stiff(:, :), f(:), x(:), q(:)
    integer :: c, k, i
    logical :: ok
    real(dp) :: t
    do c = 1, 3
      select case (c)
      case (1)
        call planar_spatial(2, 100.0_dp, effects(1), 0.0_dp, sm)
      case (2)
        call rssr_model(2, 100.0_dp, effects(2), 0.0_dp, sm)
      case default
        call rssr_model(2, 100.0_dp, effects(2), 0.0_dp, sm, universal_c=.true.)
      end select
      call assert_true(sm%cmass%active, 'constant-factor path active')
      allocate(mass(sm%n, sm%n), stiff(sm%n, sm%n), f(sm%n), x(sm%n), q(sm%n))
      q = 0.0_dp
      do k = 1, 5
        t = real(k, dp)*0.013_dp
        call sm%set_time(t)
        call sm%assemble_dense(q, mass, stiff)
        call sm%cmass%update(sm%rb, ok)
        call assert_true(ok, 'Schur complement positive definite')
        f = [(cos(real(3*i + k, dp)), i = 1, sm%n)]
        x = f
        call sm%cmass%solve(sm%rb, x)
        call assert_all_close(matmul(mass, x), f, 0.0_dp, 1.0e-10_dp*maxval(abs(f)), 'M(t) x = f')
      end do
      deallocate(mass, stiff, f, x, q)
    end do
  end subroutine test_constant_mass
end module test_spatial_model_suite

program test_spatial_model
  use test_spatial_model_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_spatial_model')
end program test_spatial_model
