!> Tests of Kear's planar beam element (module kear_element).
!>
!> Reference numbers that are not computed here: the rational element
!> matrices of the quintic Hermite functions (exact integrals of the
!> polynomials of FORMULATION.md section 4 with Python's fractions module,
!> l = 1; scaled here by powers of l).
module test_kear_element_suite
  use kinds, only: dp
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t, ro_stress, peak_strain, section_resultants_t, section_response
  use quadrature, only: gauss_legendre_interval
  use linalg, only: cholesky_factor
  use element_effects, only: element_effects_t, effects_all_on
  use planar_element, only: rigid_state_t, element_eval_info_t, stress_report_t
  use kear_element, only: kear_element_t, kear_element_init, formulation_exact, formulation_kear1987, &
                          formulation_from_name, formulation_name
  use beam_element, only: beam_tangent_stiffness, beam_strain_energy, beam_internal_force, beam_stress_recovery
  use assertions
  use element_fixtures, only: soft, l_u, b_u, t_u, rigid_at
  use element_checks, only: unit_beam, check_force_is_gradient, check_tangent_is_jacobian, check_inertia_is_lagrange
  use, intrinsic :: iso_fortran_env, only: output_unit
  implicit none
  private
  public :: run_all

  ! section 8.1 example: coupler 11 in, 0.25 x 1 in, "aluminum"
  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=0.0002536_dp)
  real(dp), parameter :: l_x = 11.0_dp, b_x = 0.25_dp, t_x = 1.0_dp

  !> a strongly deformed state (slopes up to ~0.3) and rates
  real(dp), parameter :: q_big(8) = [0.02_dp, -0.03_dp, 0.15_dp, 0.3_dp, -0.05_dp, 0.08_dp, -0.2_dp, 0.4_dp]
  real(dp), parameter :: qd_big(8) = [0.5_dp, -0.7_dp, 1.1_dp, -2.0_dp, 0.3_dp, 0.9_dp, -1.3_dp, 2.2_dp]
  real(dp), parameter :: qdd_big(8) = [3.0_dp, -2.0_dp, 5.0_dp, -8.0_dp, -4.0_dp, 6.0_dp, 7.0_dp, -9.0_dp]

  ! exact integrals of the quintic Hermite functions, l = 1, DOFs (w1 th1 m1 w2 th2 m2)
  real(dp), parameter :: mass_rat(6, 6) = reshape([ &
    181.0_dp/462, 311.0_dp/4620, 281.0_dp/55440, 25.0_dp/231, -151.0_dp/4620, 181.0_dp/55440, &
    311.0_dp/4620, 52.0_dp/3465, 23.0_dp/18480, 151.0_dp/4620, -19.0_dp/1980, 13.0_dp/13860, &
    281.0_dp/55440, 23.0_dp/18480, 1.0_dp/9240, 181.0_dp/55440, -13.0_dp/13860, 1.0_dp/11088, &
    25.0_dp/231, 151.0_dp/4620, 181.0_dp/55440, 181.0_dp/462, -311.0_dp/4620, 281.0_dp/55440, &
    -151.0_dp/4620, -19.0_dp/1980, -13.0_dp/13860, -311.0_dp/4620, 52.0_dp/3465, -23.0_dp/18480, &
    181.0_dp/55440, 13.0_dp/13860, 1.0_dp/11088, 281.0_dp/55440, -23.0_dp/18480, 1.0_dp/9240], [6, 6])
  real(dp), parameter :: stiff_rat(6, 6) = reshape([ &
    120.0_dp/7, 60.0_dp/7, 3.0_dp/7, -120.0_dp/7, 60.0_dp/7, -3.0_dp/7, &
    60.0_dp/7, 192.0_dp/35, 11.0_dp/35, -60.0_dp/7, 108.0_dp/35, -4.0_dp/35, &
    3.0_dp/7, 11.0_dp/35, 3.0_dp/35, -3.0_dp/7, 4.0_dp/35, 1.0_dp/70, &
    -120.0_dp/7, -60.0_dp/7, -3.0_dp/7, 120.0_dp/7, -60.0_dp/7, 3.0_dp/7, &
    60.0_dp/7, 108.0_dp/35, 4.0_dp/35, -60.0_dp/7, 192.0_dp/35, -11.0_dp/35, &
    -3.0_dp/7, -4.0_dp/35, 1.0_dp/70, 3.0_dp/7, -11.0_dp/35, 3.0_dp/35], [6, 6])
  real(dp), parameter :: rot_rat(6, 6) = reshape([ &
    10.0_dp/7, 3.0_dp/14, 1.0_dp/84, -10.0_dp/7, 3.0_dp/14, -1.0_dp/84, &
    3.0_dp/14, 8.0_dp/35, 1.0_dp/60, -3.0_dp/14, -1.0_dp/70, 1.0_dp/210, &
    1.0_dp/84, 1.0_dp/60, 1.0_dp/630, -1.0_dp/84, -1.0_dp/210, 1.0_dp/1260, &
    -10.0_dp/7, -3.0_dp/14, -1.0_dp/84, 10.0_dp/7, -3.0_dp/14, 1.0_dp/84, &
    3.0_dp/14, -1.0_dp/70, -1.0_dp/210, -3.0_dp/14, 8.0_dp/35, -1.0_dp/60, &
    -1.0_dp/84, 1.0_dp/210, 1.0_dp/1260, 1.0_dp/84, -1.0_dp/60, 1.0_dp/630], [6, 6])
  integer, parameter :: wdof(6) = [2, 3, 4, 6, 7, 8], lpow(6) = [0, 1, 2, 0, 1, 2]

contains

  subroutine run_all()
    call run_test('linear_matrices_equal_quintic_hermite_rationals', test_linear_matrices)
    call run_test('pure_bending_and_uniform_stretch_energies', test_bending_stretch_energy)
    call run_test('internal_force_is_gradient_of_strain_energy', test_force_is_gradient)
    call run_test('tangent_stiffness_is_jacobian_of_internal_force', test_tangent_is_jacobian)
    call run_test('strains_match_finite_differences_of_displacement_field', test_strains_vs_field)
    call run_test('rigid_rotation_gives_zero_strain_exact_formulation', test_rigid_rotation)
    call run_test('rigid_translation_changes_no_element_force', test_rigid_translation)
    call run_test('mass_symmetric_positive_definite_rigid_mass_rhoAl', test_mass_properties)
    call run_test('kinetic_energy_of_rotating_rigid_element', test_rigid_kinetic_energy)
    call run_test('inertial_operator_equals_fd_lagrange_equations', test_lagrange_fd)
    call run_test('kear1987_internal_force_is_printed_k17_k20_k24', test_kear1987_force)
    call run_test('mass_matrix_is_hessian_of_kinetic_energy_in_qdot', test_mass_is_ke_hessian)
    call run_test('coupling_off_drops_exactly_euler_and_coriolis_terms', test_coupling_switch)
    call run_test('switches_off_reproduce_reduced_models_and_cost', test_reduced_models)
    call run_test('stretching_gives_classical_geometric_stiffness', test_geometric_stiffness)
    call run_test('exact_and_kear1987_agree_to_order_strain', test_exact_vs_kear1987)
    call run_test('nonlinear_quadrature_converges_with_points', test_quadrature_convergence)
    call run_test('stress_recovery_finds_maximum_fibre_stress', test_stress_recovery)
    call run_test('strain_past_ramberg_osgood_peak_is_flagged', test_peak_detection)
    call run_test('stiffness_proportional_damping_acts_on_strain_rates', test_damping)
    call run_test('invalid_input_is_rejected_with_a_message', test_invalid_input)
  end subroutine run_all

  ! ------------------------------------------------------------ helpers

  function unit_element(fx, formulation, n_gauss, beta, objective) result(el)
    type(element_effects_t), intent(in) :: fx
    integer, intent(in), optional :: formulation, n_gauss
    real(dp), intent(in), optional :: beta
    logical, intent(in), optional :: objective
    type(kear_element_t) :: el
    type(error_t) :: err
    call kear_element_init(el, l_u, b_u, t_u, soft, fx, err, formulation, n_gauss, beta, objective)
    if (err%failed()) call assert_true(.false., 'unit element: '//err%text())
  end function unit_element

  function example_element(fx, formulation, n_gauss) result(el)
    type(element_effects_t), intent(in) :: fx
    integer, intent(in), optional :: formulation, n_gauss
    type(kear_element_t) :: el
    type(error_t) :: err
    call kear_element_init(el, l_x, b_x, t_x, alu, fx, err, formulation, n_gauss)
    if (err%failed()) call assert_true(.false., 'example element: '//err%text())
  end function example_element

  function all_off() result(fx)
    type(element_effects_t) :: fx
    fx = element_effects_t()
  end function all_off

  !> q from local nodal values p (inverse of K26's rotation).
  pure function to_q(phi, p) result(q)
    real(dp), intent(in) :: phi, p(8)
    real(dp) :: q(8)
    q = p
    q(1) = cos(phi)*p(1) - sin(phi)*p(2)
    q(2) = sin(phi)*p(1) + cos(phi)*p(2)
    q(5) = cos(phi)*p(5) - sin(phi)*p(6)
    q(6) = sin(phi)*p(5) + cos(phi)*p(6)
  end function to_q

  !> (u, w) -> (-w, u) at both nodes.
  pure function jb(p) result(r)
    real(dp), intent(in) :: p(8)
    real(dp) :: r(8)
    r = 0.0_dp
    r(1) = -p(2)
    r(2) = p(1)
    r(5) = -p(6)
    r(6) = p(5)
  end function jb

  !> Element inertial operator M qdd - F - dSE/dq (beta = 0).
  ! -------------------------------------------------------------- tests

  !> All effects off: K, translational M and rotary M (curvature off) are the
  !> exact integrals, equal to the rationals entry by entry (1e-13 of the
  !> block's largest entry: quadrature of degree-10 polynomials with the
  !> 6-point rule is exact up to round-off).  The u-block is EA/l [1 -1; -1 1]
  !> and rho A l/6 [2 1; 1 2]; u and w do not couple.
  subroutine test_linear_matrices()
    type(kear_element_t) :: el, elr
    real(dp) :: kt(8, 8), m(8, 8), mr(8, 8), f(8), ea, ei, ref(8, 8), refm(8, 8), refr(8, 8)
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    integer :: i, j
    el = unit_element(all_off())
    elr = unit_element(element_effects_t(rotary_inertia=.true.))
    ea = soft%e1*b_u*t_u
    ei = soft%e1*b_u*t_u**3/12.0_dp
    call beam_tangent_stiffness(el, q_big, 0.0_dp, kt)
    call el%eval(q_big, qd_big, rb, m, f, info)
    call elr%eval(q_big, qd_big, rb, mr, f, info)
    ref = 0.0_dp
    refm = 0.0_dp
    refr = 0.0_dp
    ref(1, 1) = ea/l_u; ref(5, 5) = ea/l_u; ref(1, 5) = -ea/l_u; ref(5, 1) = -ea/l_u
    refm(1, 1) = 2.0_dp; refm(5, 5) = 2.0_dp; refm(1, 5) = 1.0_dp; refm(5, 1) = 1.0_dp
    refm = refm*soft%rho*b_u*t_u*l_u/6.0_dp
    do j = 1, 6
      do i = 1, 6
        ref(wdof(i), wdof(j)) = ei*stiff_rat(i, j)*l_u**(lpow(i) + lpow(j) - 3)
        refm(wdof(i), wdof(j)) = soft%rho*b_u*t_u*mass_rat(i, j)*l_u**(lpow(i) + lpow(j) + 1)
        refr(wdof(i), wdof(j)) = soft%rho*b_u*t_u**3/12.0_dp*rot_rat(i, j)*l_u**(lpow(i) + lpow(j) - 1)
      end do
    end do
    call assert_all_close(reshape(kt, [64]), reshape(ref, [64]), 0.0_dp, 1.0e-13_dp*maxval(abs(ref)), &
                          'stiffness = EA/l, EI/l^3 x rationals')
    call assert_all_close(reshape(m, [64]), reshape(refm, [64]), 0.0_dp, 1.0e-13_dp*maxval(abs(refm)), &
                          'consistent mass = rho A l x rationals')
    call assert_all_close(reshape(mr - m, [64]), reshape(refr, [64]), 0.0_dp, 1.0e-13_dp*maxval(abs(refr)), &
                          'rotary mass = rho I / l x rationals')
  end subroutine test_linear_matrices

  !> Euler-Bernoulli energies of states the interpolation reproduces exactly
  !> (1e-13 relative): w = kappa x^2/2 -> EI kappa^2 l/2; u = eps x -> EA eps^2 l/2;
  !> and with exact stretching + material, uniform stretch -> A l (E1 eps^2/2 - E2 eps^4/4).
  subroutine test_bending_stretch_energy()
    type(kear_element_t) :: el
    real(dp), parameter :: kap = 0.04_dp, eps = 2.0e-3_dp, phi = 0.4_dp
    real(dp) :: p(8), se, a, i
    a = b_u*t_u
    i = b_u*t_u**3/12.0_dp
    el = unit_element(all_off())
    p = [0.0_dp, 0.0_dp, 0.0_dp, kap, 0.0_dp, kap*l_u**2/2, kap*l_u, kap]
    se = beam_strain_energy(el, to_q(phi, p), phi)
    call assert_rel_close(se, soft%e1*i*kap**2*l_u/2, 1.0e-13_dp, 'pure bending EI kappa^2 l/2')
    p = 0.0_dp
    p(5) = eps*l_u
    se = beam_strain_energy(el, to_q(phi, p), phi)
    call assert_rel_close(se, soft%e1*a*eps**2*l_u/2, 1.0e-13_dp, 'uniform stretch EA eps^2 l/2')
    el = unit_element(element_effects_t(stretching=.true., curvature=.true., material=.true.))
    se = beam_strain_energy(el, to_q(phi, p), phi)
    call assert_rel_close(se, a*l_u*(soft%e1*eps**2/2 - soft%e2*eps**4/4), 1.0e-13_dp, &
                          'uniform stretch, Ramberg-Osgood')
  end subroutine test_bending_stretch_energy

  !> dSE/dq by 4th-order differences (h = 1e-4: truncation ~h^4, round-off
  !> ~1e-16 SE/h) against the analytic internal force, for the exact
  !> formulation with each nonlinear effect alone and all together, at the
  !> strongly deformed state: agreement to 1e-8 of the largest component.
  subroutine test_force_is_gradient()
    call check_force_is_gradient('exact', q_big)
  end subroutine test_force_is_gradient

  !> d(internal force)/dq by 4th-order differences (h = 1e-4) against the
  !> analytic K_t, 1e-7 of max|K|: exact and kear1987 formulations, all
  !> effects on, and geometric effects with linear material.  The exact K_t
  !> is symmetric (a Hessian) to round-off.
  subroutine test_tangent_is_jacobian()
    call check_tangent_is_jacobian(unit_beam('exact', effects_all_on()), q_big, 'exact, all on')
    call check_tangent_is_jacobian(unit_beam('kear1987', effects_all_on()), q_big, &
                                   'kear1987, all on', symmetric=.false.)
    call check_tangent_is_jacobian(unit_beam('exact', element_effects_t(stretching=.true., curvature=.true.)), &
                                   q_big, 'exact, geometric only')
  end subroutine test_tangent_is_jacobian

  !> eps_n and kappa from kear_section_strains against formulas (K19), exact
  !> curvature, (K23) and the linear ones, evaluated on u(x), w(x) of (K26)
  !> differentiated numerically (4th-order, step 1e-3 l: error ~1e-11).
  subroutine test_strains_vs_field()
    type(kear_element_t) :: el
    real(dp) :: phi, e, de, uw(2, -2:2), ux, wx, wxx, uxx, a, r, eps_n, kap, p(8)
    integer :: k, i, variant
    phi = 1.1_dp
    de = 1.0e-3_dp
    do variant = 1, 3
      select case (variant)
      case (1)
        el = unit_element(effects_all_on())
      case (2)
        el = unit_element(effects_all_on(), formulation=formulation_kear1987)
      case default
        el = unit_element(all_off())
      end select
      p = el%local_dofs(q_big, phi)
      do k = 1, 4
        e = 0.2_dp*real(k, dp)
        do i = -2, 2
          uw(:, i) = el%local_displacement(q_big, phi, e + real(i, dp)*de)
        end do
        ux = (uw(1, -2) - 8*uw(1, -1) + 8*uw(1, 1) - uw(1, 2))/(12*de*l_u)
        wx = (uw(2, -2) - 8*uw(2, -1) + 8*uw(2, 1) - uw(2, 2))/(12*de*l_u)
        uxx = (-uw(1, -2) + 16*uw(1, -1) - 30*uw(1, 0) + 16*uw(1, 1) - uw(1, 2))/(12*(de*l_u)**2)
        wxx = (-uw(2, -2) + 16*uw(2, -1) - 30*uw(2, 0) + 16*uw(2, 1) - uw(2, 2))/(12*(de*l_u)**2)
        call el%section_strains(p, e, eps_n, kap)
        a = 1.0_dp + ux
        r = sqrt(a*a + wx*wx)
        select case (variant)
        case (1)
          call assert_close(eps_n, r - 1.0_dp, 1.0e-9_dp, 'exact stretch (K19)')
          call assert_close(kap, (wxx*a - wx*uxx)/r**3, 1.0e-8_dp, 'exact curvature')
        case (2)
          call assert_close(eps_n, r - 1.0_dp, 1.0e-9_dp, 'kear1987 stretch (K19)')
          call assert_close(kap, wxx*a - wx*uxx, 1.0e-8_dp, 'kear1987 curvature (K23)')
        case default
          call assert_close(eps_n, ux, 1.0e-9_dp, 'linear: eps_n = u_x')
          call assert_close(kap, wxx, 1.0e-8_dp, 'linear: kappa = w_xx')
        end select
      end do
    end do
  end subroutine test_strains_vs_field

  !> A finite rigid rotation (0.7 rad about node 1) plus a translation is
  !> exactly representable in (K26) (u = x(cos a - 1) is linear, w = x sin a
  !> is reproduced by th = sin a).  The exact strains vanish to round-off
  !> (1e-15), so do the energy and internal force; the linear model sees
  !> eps_n = cos a - 1.  Changing the reference angle phi and rotating the
  !> global translations with it leaves the energy unchanged (frame
  !> invariance of the p = T(phi) q parameterisation), 1e-13 relative.
  subroutine test_rigid_rotation()
    type(kear_element_t) :: el, ell
    real(dp), parameter :: alpha = 0.7_dp, phi = 0.35_dp
    real(dp) :: p(8), q(8), f(8), eps_n, kap, se1, se2, beta
    integer :: k
    el = unit_element(effects_all_on())
    ell = unit_element(all_off())
    p = [0.0_dp, 0.0_dp, sin(alpha), 0.0_dp, l_u*(cos(alpha) - 1), l_u*sin(alpha), sin(alpha), 0.0_dp]
    q = to_q(phi, p) + [0.3_dp, -0.2_dp, 0.0_dp, 0.0_dp, 0.3_dp, -0.2_dp, 0.0_dp, 0.0_dp]
    p = el%local_dofs(q, phi)
    do k = 0, 4
      call el%section_strains(p, 0.25_dp*k, eps_n, kap)
      call assert_close(eps_n, 0.0_dp, 1.0e-15_dp, 'exact eps_n of a rigid rotation')
      call assert_close(kap, 0.0_dp, 1.0e-15_dp, 'exact kappa of a rigid rotation')
      call ell%section_strains(p, 0.25_dp*k, eps_n, kap)
      call assert_close(eps_n, cos(alpha) - 1.0_dp, 1.0e-14_dp, 'linear eps_n = cos(alpha) - 1')
    end do
    call beam_internal_force(el, q, phi, f)
    call assert_true(maxval(abs(f)) <= 1.0e-12_dp*soft%e1*b_u*t_u, 'no internal force')
    call assert_close(beam_strain_energy(el, q, phi), 0.0_dp, 1.0e-24_dp*soft%e1*b_u*t_u*l_u, 'no energy')
    ! frame invariance with a deformed state
    se1 = beam_strain_energy(el, q_big, phi)
    beta = 0.9_dp
    p = el%local_dofs(q_big, phi)
    se2 = beam_strain_energy(el, to_q(phi + beta, p), phi + beta)
    call assert_rel_close(se2, se1, 1.0e-13_dp, 'energy independent of the frame angle')
  end subroutine test_rigid_rotation

  !> Adding a rigid translation D + V t to the nodes changes no particle
  !> acceleration and no strain, so M and F must not change (1e-12 relative),
  !> with all effects on and a deformed, moving state: checks that the
  !> Coriolis, Euler and centrifugal terms of the global translation DOFs
  !> cancel exactly.
  subroutine test_rigid_translation()
    type(kear_element_t) :: el
    real(dp) :: m0(8, 8), f0(8), m1(8, 8), f1(8), dq(8), dv(8)
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    el = unit_element(effects_all_on(), beta=1.0e-3_dp)
    rb = rigid_at(0.37_dp)
    dq = [0.4_dp, -0.25_dp, 0.0_dp, 0.0_dp, 0.4_dp, -0.25_dp, 0.0_dp, 0.0_dp]
    dv = [-1.5_dp, 2.5_dp, 0.0_dp, 0.0_dp, -1.5_dp, 2.5_dp, 0.0_dp, 0.0_dp]
    call el%eval(q_big, qd_big, rb, m0, f0, info)
    call el%eval(q_big + dq, qd_big + dv, rb, m1, f1, info)
    call assert_all_close(f1, f0, 0.0_dp, 1.0e-12_dp*maxval(abs(f0)), 'F unchanged by rigid translation')
    call assert_all_close(reshape(m1, [64]), reshape(m0, [64]), 0.0_dp, 1.0e-14_dp*maxval(abs(m0)), &
                          'M unchanged by rigid translation')
  end subroutine test_rigid_translation

  !> M(q) (all effects on, deformed) is symmetric to round-off and positive
  !> definite (Cholesky succeeds); a unit rigid translation in X or Y has
  !> d^T M d = rho A l (1e-14 relative), the element's mass.
  subroutine test_mass_properties()
    type(kear_element_t) :: el
    real(dp) :: m(8, 8), f(8), d(8), chol(8, 8)
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    type(error_t) :: err
    integer :: k
    el = unit_element(effects_all_on())
    rb = rigid_at(0.2_dp)
    call el%eval(q_big, qd_big, rb, m, f, info)
    call assert_true(maxval(abs(m - transpose(m))) <= 1.0e-15_dp*maxval(abs(m)), 'M symmetric')
    chol = m
    call cholesky_factor(chol, err)
    call assert_true(.not. err%failed(), 'M positive definite: '//err%text())
    do k = 1, 2
      d = 0.0_dp
      d(k) = 1.0_dp
      d(4 + k) = 1.0_dp
      call assert_rel_close(dot_product(d, matmul(m, d)), soft%rho*b_u*t_u*l_u, 1.0e-14_dp, &
                            'rigid translation mass rho A l')
    end do
  end subroutine test_mass_properties

  !> KE (K3) of the undeformed element moving rigidly with end velocity V
  !> and angular velocity w: (rho A/2)(l V^2 + w V_j l^2 + w^2 l^3/3) + rho I w^2 l/2,
  !> V_j the component of V along the element's j axis; 1e-14 relative.
  subroutine test_rigid_kinetic_energy()
    type(kear_element_t) :: el
    type(rigid_state_t) :: rb
    real(dp) :: ke, ra, ri, vj, q0(8)
    el = unit_element(effects_all_on())
    rb%phi = 0.6_dp
    rb%phi_d = 3.0_dp
    rb%x1_d = 1.2_dp
    rb%y1_d = -0.7_dp
    q0 = 0.0_dp
    ke = el%kinetic_energy(q0, q0, rb)
    ra = soft%rho*b_u*t_u
    ri = soft%rho*b_u*t_u**3/12.0_dp
    vj = -sin(rb%phi)*rb%x1_d + cos(rb%phi)*rb%y1_d
    call assert_rel_close(ke, 0.5_dp*ra*(l_u*(rb%x1_d**2 + rb%y1_d**2) + rb%phi_d*vj*l_u**2 &
                          + rb%phi_d**2*l_u**3/3) + 0.5_dp*ri*rb%phi_d**2*l_u, 1.0e-14_dp, 'rigid KE')
  end subroutine test_rigid_kinetic_energy

  !> The element's inertial operator M qdd - F_inertial against Lagrange's
  !> equations d/dt dT/dqdot - dT/dq of the kinetic energy T (K3 with K5, K8)
  !> computed by finite differences along q(t) = q0 + qd0 s + qdd0 s^2/2 with
  !> a prescribed rigid motion (phi, X1, Y1 all accelerating).  dT/dqdot:
  !> central difference with step 0.5 (exact: T is quadratic in qdot);
  !> d/dt and dT/dq: 4th-order differences (steps 1e-3 and 1e-4).
  !> Tolerance 1e-7 of the largest component.
  subroutine test_lagrange_fd()
    call check_inertia_is_lagrange('exact', q_big, qd_big, qdd_big)
  end subroutine test_lagrange_fd

  !> The printed internal force (K17) with (K20) and (K24):
  !>   F_j = int [ N ((1+u_x) u_x,qj + w_x w_x,qj) + M dkappa_K23/dq_j ] dx,
  !> N, M the resultants of (eps_n of K19, kappa of K23), rebuilt here from
  !> the element's strains at its 8 Gauss points, with (1+u_x) u_x,q +
  !> w_x w_x,q = d((1+eps_n)^2/2)/dq and dkappa/dq by central differences in
  !> q (h = 1e-6: error ~1e-12); agreement 1e-7 of the largest component.
  subroutine test_kear1987_force()
    type(kear_element_t) :: el
    real(dp) :: f(8), ref(8), x(8), w(8), e(8), phi, h, ep, em, kp, km, en, ka
    type(section_resultants_t) :: res
    integer :: i, j
    phi = 0.6_dp
    h = 1.0e-6_dp
    el = unit_element(effects_all_on(), formulation=formulation_kear1987)
    call beam_internal_force(el, q_big, phi, f)
    call gauss_legendre_interval(8, 0.0_dp, l_u, x, w)
    ref = 0.0_dp
    do i = 1, 8
      call el%section_strains(el%local_dofs(q_big, phi), x(i)/l_u, en, ka)
      res = section_response(soft, b_u*t_u, t_u, en, ka, .true.)
      do j = 1, 8
        e = 0.0_dp
        e(j) = h
        call el%section_strains(el%local_dofs(q_big + e, phi), x(i)/l_u, ep, kp)
        call el%section_strains(el%local_dofs(q_big - e, phi), x(i)/l_u, em, km)
        ref(j) = ref(j) + w(i)*(res%axial_force*((1 + ep)**2 - (1 + em)**2)/(4*h) + res%moment*(kp - km)/(2*h))
      end do
    end do
    call assert_all_close(f, ref, 0.0_dp, 1.0e-7_dp*maxval(abs(ref)), 'printed (K17) with (K20), (K24)')
  end subroutine test_kear1987_force

  !> T is quadratic in qdot, so its Hessian in qdot (central differences with
  !> step 1, exact up to round-off) is the mass matrix: for the exact
  !> formulation (K8) and for kear1987 (K9), all effects on, 1e-12 relative.
  subroutine test_mass_is_ke_hessian()
    type(kear_element_t) :: el
    type(rigid_state_t) :: rb
    type(element_eval_info_t) :: info
    real(dp) :: m(8, 8), f(8), hes(8, 8), ei(8), ej(8)
    integer :: i, j, k
    rb = rigid_at(0.8_dp)
    do k = 1, 2
      el = unit_element(effects_all_on(), formulation=merge(formulation_exact, formulation_kear1987, k == 1))
      call el%eval(q_big, qd_big, rb, m, f, info)
      do j = 1, 8
        ej = 0.0_dp
        ej(j) = 1.0_dp
        do i = 1, 8
          ei = 0.0_dp
          ei(i) = 1.0_dp
          hes(i, j) = (el%kinetic_energy(q_big, qd_big + ei + ej, rb) &
                       - el%kinetic_energy(q_big, qd_big + ei - ej, rb) &
                       - el%kinetic_energy(q_big, qd_big - ei + ej, rb) &
                       + el%kinetic_energy(q_big, qd_big - ei - ej, rb))/4
        end do
      end do
      call assert_all_close(reshape(m, [64]), reshape(hes, [64]), 0.0_dp, 1.0e-12_dp*maxval(abs(m)), &
                            'M = d2 KE / dqdot2, '//formulation_name(el%formulation))
    end do
  end subroutine test_mass_is_ke_hessian

  !> coupling = .false. removes exactly the terms proportional to phi_dd q
  !> (Euler) and phi_d q_dot (Coriolis), nothing else.  For the models linear
  !> in (q, qdot) (linear angle) this means
  !>   F_off(q, qd; phi_d, phi_dd) = F_on(q, 0; phi_d, 0) + F_on(0, 0; phi_d, phi_dd) - F_on(0, 0; phi_d, 0)
  !> to round-off (1e-13 of max|F|), while F_on differs from F_off by more than
  !> 1e-3 of max|F| at this state.  With phi_d = phi_dd = 0 the switch changes
  !> nothing, also in the nonlinear model.
  subroutine test_coupling_switch()
    type(kear_element_t) :: on, off
    type(rigid_state_t) :: rb, rb0
    real(dp) :: m(8, 8), f_off(8), f_on(8), f_a(8), f_b(8), f_c(8), z(8)
    type(element_eval_info_t) :: info
    z = 0.0_dp
    rb = rigid_at(0.5_dp)
    rb0 = rb
    rb0%phi_dd = 0.0_dp
    on = unit_element(element_effects_t(stretching=.true., material=.true., rotary_inertia=.true., coupling=.true.))
    off = unit_element(element_effects_t(stretching=.true., material=.true., rotary_inertia=.true.))
    call off%eval(q_big, qd_big, rb, m, f_off, info)
    call on%eval(q_big, qd_big, rb, m, f_on, info)
    call on%eval(q_big, z, rb0, m, f_a, info)
    call on%eval(z, z, rb, m, f_b, info)
    call on%eval(z, z, rb0, m, f_c, info)
    call assert_all_close(f_off, f_a + f_b - f_c, 0.0_dp, 1.0e-13_dp*maxval(abs(f_off)), &
                          'coupling off = on without Euler and Coriolis terms')
    write(output_unit, '(a,es10.3,a,es10.3)') '    coupling terms ', maxval(abs(f_on - f_off)), &
      ' vs rigid-body inertial forcing ', maxval(abs(f_b))
    call assert_true(maxval(abs(f_on - f_off)) > 1.0e-2_dp*maxval(abs(f_b)), 'the dropped terms matter here')
    ! no rotation rate: the switch has nothing to drop
    rb%phi_d = 0.0_dp
    rb%phi_dd = 0.0_dp
    on = unit_element(effects_all_on())
    off = on
    off%effects%coupling = .false.
    call off%eval(q_big, qd_big, rb, m, f_off, info)
    call on%eval(q_big, qd_big, rb, m, f_on, info)
    call assert_all_close(f_off, f_on, 0.0_dp, 1.0e-14_dp*maxval(abs(f_on)), 'identical without rotation')
  end subroutine test_coupling_switch

  !> Reduced models: material on with E2 = 0 equals material off (1e-14);
  !> stretching on equals off for a purely axial state (eps_n = u_x exactly);
  !> all effects off is linear in (q, qdot) and evaluates no nonlinear
  !> integrand (cost counter 0), each nonlinear effect costs n_gauss point
  !> evaluations per integral it needs.
  subroutine test_reduced_models()
    type(kear_element_t) :: el_a, el_b
    type(ramberg_osgood_t) :: lin
    type(error_t) :: err
    type(rigid_state_t) :: rb
    type(element_eval_info_t) :: info
    real(dp) :: ma(8, 8), fa(8), mb(8, 8), fb(8), f0(8), f2(8), ka(8, 8), kb(8, 8), p(8), z(8)
    rb = rigid_at(0.1_dp)
    z = 0.0_dp
    ! material switch
    lin = soft
    lin%e2 = 0.0_dp
    el_a = unit_element(element_effects_t(stretching=.true., curvature=.true., rotary_inertia=.true., coupling=.true.))
    call kear_element_init(el_b, l_u, b_u, t_u, lin, effects_all_on(), err)
    call el_a%eval(q_big, qd_big, rb, ma, fa, info, ka)
    call el_b%eval(q_big, qd_big, rb, mb, fb, info, kb)
    call assert_all_close(fa, fb, 0.0_dp, 1.0e-14_dp*maxval(abs(fa)), 'material off = E2 = 0: F')
    call assert_all_close(reshape(ka, [64]), reshape(kb, [64]), 0.0_dp, 1.0e-14_dp*maxval(abs(ka)), &
                          'material off = E2 = 0: K_t')
    ! stretching switch on a purely axial state
    p = 0.0_dp
    p(1) = -0.01_dp
    p(5) = 0.02_dp
    el_a = unit_element(element_effects_t(material=.true.))
    el_b = unit_element(element_effects_t(material=.true., stretching=.true.))
    call beam_internal_force(el_a, to_q(0.3_dp, p), 0.3_dp, fa)
    call beam_internal_force(el_b, to_q(0.3_dp, p), 0.3_dp, fb)
    call assert_all_close(fa, fb, 0.0_dp, 1.0e-14_dp*maxval(abs(fa)), 'stretching: axial state unchanged')
    ! all off: linear and cheap
    el_a = unit_element(all_off(), beta=1.0e-3_dp)
    call el_a%eval(z, z, rb, ma, f0, info)
    call el_a%eval(q_big, qd_big, rb, ma, fa, info)
    call assert_equal(info%n_nonlinear_points, 0, 'linear model evaluates no nonlinear integrand')
    call el_a%eval(2*q_big, 2*qd_big, rb, ma, f2, info)
    call assert_all_close(f2 - f0, 2*(fa - f0), 0.0_dp, 1.0e-13_dp*maxval(abs(fa - f0)), 'linear in (q, qdot)')
    el_b = unit_element(effects_all_on(), beta=1.0e-3_dp)
    call el_b%eval(z, z, rb, mb, f0, info)
    call el_b%eval(q_big, qd_big, rb, mb, fb, info)
    call assert_equal(info%n_nonlinear_points, 2*el_b%n_gauss, 'all on: strain and rotary integrals')
    call el_b%eval(2*q_big, 2*qd_big, rb, mb, f2, info)
    call assert_true(maxval(abs(f2 - f0 - 2*(fb - f0))) > 1.0e-3_dp*maxval(abs(fb - f0)), 'all on is nonlinear')
    el_a = unit_element(element_effects_t(rotary_inertia=.true., coupling=.true.))
    call el_a%eval(q_big, qd_big, rb, ma, fa, info)
    call assert_equal(info%n_nonlinear_points, 0, 'rotary inertia with linear angle uses constant integrals')
    el_a = unit_element(element_effects_t(stretching=.true.))
    call el_a%eval(q_big, qd_big, rb, ma, fa, info)
    call assert_equal(info%n_nonlinear_points, el_a%n_gauss, 'stretching alone: one strain loop')
  end subroutine test_reduced_models

  !> With exact stretching and linear material, a uniformly stretched element
  !> (u = eps x, w = 0) has K_t - K_linear = N/(1 + eps) int w_x,q w_x,q^T dx,
  !> N = E A eps: the classical geometric ("string") stiffness P/l x rot_rat
  !> (quintic version of the 6/5l matrix); 1e-12 relative.
  subroutine test_geometric_stiffness()
    type(kear_element_t) :: el_a, el_b
    real(dp), parameter :: eps = 3.0e-3_dp
    real(dp) :: p(8), ka(8, 8), kb(8, 8), ref(8, 8), n
    integer :: i, j
    el_a = unit_element(element_effects_t(stretching=.true.))
    el_b = unit_element(all_off())
    p = 0.0_dp
    p(5) = eps*l_u
    call beam_tangent_stiffness(el_a, p, 0.0_dp, ka)
    call beam_tangent_stiffness(el_b, p, 0.0_dp, kb)
    n = soft%e1*b_u*t_u*eps
    ref = 0.0_dp
    do j = 1, 6
      do i = 1, 6
        ref(wdof(i), wdof(j)) = n/(1.0_dp + eps)*rot_rat(i, j)*l_u**(lpow(i) + lpow(j) - 1)
      end do
    end do
    call assert_all_close(reshape(ka - kb, [64]), reshape(ref, [64]), 0.0_dp, 1.0e-12_dp*maxval(abs(ref)), &
                          'geometric stiffness')
  end subroutine test_geometric_stiffness

  !> Strains typical of the examples (outer-fibre strain ~1e-3 in the 11 in
  !> coupler of section 8.1): the printed (K20), (K23), (K9)/(K11) differ from
  !> the exact equations by relative terms of order eps_n and w_x^2.  Internal
  !> force: difference below 3 max|eps| and growing linearly with the
  !> deformation (doubling it doubles the difference, within 20%).  Rotary
  !> inertia contribution at 150 rad/s: difference below 1e-2.
  subroutine test_exact_vs_kear1987()
    type(kear_element_t) :: ex, kr
    real(dp) :: p(8), q(8), fe(8), fk(8), d1, d2, emax, phi, qd(8)
    real(dp) :: m(8, 8), f_on_e(8), f_off_e(8), f_on_k(8), f_off_k(8), dr
    type(stress_report_t) :: rep
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    integer :: k
    phi = 0.8_dp
    ex = example_element(effects_all_on())
    kr = example_element(effects_all_on(), formulation=formulation_kear1987)
    do k = 1, 2
      ! axial strain 2.5e-4, curvature ~2e-3 /in (outer fibre ~1e-3), slopes ~1e-2
      p = real(k, dp)*[0.0_dp, 0.0_dp, 0.01_dp, 2.0e-3_dp, 2.5e-4_dp*l_x, 0.02_dp, -0.012_dp, -1.5e-3_dp]
      q = to_q(phi, p)
      call beam_internal_force(ex, q, phi, fe)
      call beam_internal_force(kr, q, phi, fk)
      rep = beam_stress_recovery(ex, q, phi)
      if (k == 1) then
        d1 = maxval(abs(fk - fe))/maxval(abs(fe))
        emax = rep%max_abs_strain
        write(output_unit, '(a,es10.3,a,es10.3)') '    kear1987 vs exact internal force: rel. diff ', d1, &
          ' at max |eps| ', emax
        call assert_true(emax > 0.8e-3_dp .and. emax < 2.0e-3_dp, 'strain typical of the examples')
      else
        d2 = maxval(abs(fk - fe))/maxval(abs(fe))
        write(output_unit, '(a,es10.3,a,es10.3)') '    kear1987 vs exact internal force: rel. diff ', d2, &
          ' at max |eps| ', rep%max_abs_strain
      end if
    end do
    call assert_true(d1 < 3.0_dp*emax, 'internal forces agree to O(eps)')
    call assert_true(d2/d1 > 1.6_dp .and. d2/d1 < 2.4_dp, 'difference is first order in the deformation')
    ! rotary inertia part at 150 rad/s, vibration rates ~ 150 rad/s x deflection
    rb%phi = phi
    rb%phi_d = 150.0_dp
    rb%phi_dd = 0.0_dp
    p = [0.0_dp, 0.0_dp, 0.01_dp, 2.0e-3_dp, 2.5e-4_dp*l_x, 0.02_dp, -0.012_dp, -1.5e-3_dp]
    q = to_q(phi, p)
    qd = 150.0_dp*[0.01_dp, -0.02_dp, 0.005_dp, 1.0e-3_dp, 0.003_dp, 0.01_dp, 0.007_dp, -1.0e-3_dp]
    call ex%eval(q, qd, rb, m, f_on_e, info)
    call kr%eval(q, qd, rb, m, f_on_k, info)
    ex%effects%rotary_inertia = .false.
    kr%effects%rotary_inertia = .false.
    call ex%eval(q, qd, rb, m, f_off_e, info)
    call kr%eval(q, qd, rb, m, f_off_k, info)
    dr = maxval(abs((f_on_k - f_off_k) - (f_on_e - f_off_e)))/maxval(abs(f_on_e - f_off_e))
    write(output_unit, '(a,es10.3)') '    kear1987 vs exact rotary inertia force: rel. diff ', dr
    call assert_true(dr < 1.0e-2_dp, 'rotary inertia agrees to O(eps)')
  end subroutine test_exact_vs_kear1987

  !> Nonlinear integrands are not polynomials: the internal force with n
  !> Gauss points converges to the 30-point value.  (1) strongly deformed
  !> unit element (slopes ~0.3), geometric nonlinearity: the error falls
  !> from n = 4 to 8 to 12, and is below 1e-3 at the default n = 8.
  !> (2) example strains (~1e-3, section 8.1 coupler), all effects: below
  !> 1e-7 at n = 8 and 1e-11 at n = 12.  (Linear-kinematics integrands with
  !> the cubic law have degree 12 and are exact from n = 7.)
  subroutine test_quadrature_convergence()
    type(kear_element_t) :: el
    type(element_effects_t) :: fx
    real(dp) :: fref(8), f(8), err(3:12), phi, q(8)
    integer :: n, case
    phi = 0.2_dp
    do case = 1, 2
      if (case == 1) then
        fx = element_effects_t(stretching=.true., curvature=.true.)
        el = unit_element(fx, n_gauss=30)
        q = q_big
      else
        fx = effects_all_on()
        el = example_element(fx, n_gauss=30)
        q = to_q(phi, [0.0_dp, 0.0_dp, 0.01_dp, 2.0e-3_dp, 2.5e-4_dp*l_x, 0.02_dp, -0.012_dp, -1.5e-3_dp])
      end if
      call beam_internal_force(el, q, phi, fref)
      do n = 3, 12
        if (case == 1) then
          el = unit_element(fx, n_gauss=n)
        else
          el = example_element(fx, n_gauss=n)
        end if
        call beam_internal_force(el, q, phi, f)
        err(n) = maxval(abs(f - fref))/maxval(abs(fref))
      end do
      write(output_unit, '(a,i0,a,10es9.1)') '    case ', case, ': rel. error for n = 3..12:', err
      if (case == 1) then
        call assert_true(err(8) < err(4) .and. err(12) < err(8), 'error decreases with n')
        call assert_true(err(8) < 1.0e-3_dp, 'n = 8 within 1e-3 at large deflection')
      else
        call assert_true(err(8) < 1.0e-7_dp, 'n = 8 within 1e-7 at example strains')
        call assert_true(err(12) < 1.0e-11_dp, 'n = 12 within 1e-11 at example strains')
      end if
    end do
  end subroutine test_quadrature_convergence

  !> u = eps0 x, w = A x^3 (reproduced exactly), linear kinematics: fibre
  !> strain eps0 + (t/2) 6 A x at y = -t/2 is largest at x = l.  The report
  !> must give that point, fibre -1, sigma = E1 eps - E2 eps^3 (material on)
  !> or E1 eps (off), 1e-13 relative.
  subroutine test_stress_recovery()
    type(kear_element_t) :: el
    type(stress_report_t) :: rep
    real(dp), parameter :: eps0 = 1.0e-4_dp, eb = 2.0e-3_dp, phi = 2.0_dp
    real(dp) :: a, p(8), eps
    a = eb/(3.0_dp*t_x*l_x)         ! (t/2) 6 A l = eb
    p = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, eps0*l_x, a*l_x**3, 3*a*l_x**2, 6*a*l_x]
    eps = eps0 + eb
    el = example_element(element_effects_t(material=.true.))
    rep = beam_stress_recovery(el, to_q(phi, p), phi)
    call assert_rel_close(rep%max_abs_strain, eps, 1.0e-12_dp, 'max |eps|')
    call assert_rel_close(rep%max_abs_stress, alu%e1*eps - alu%e2*eps**3, 1.0e-12_dp, 'max |sigma|')
    call assert_close(rep%stress_x_over_l, 1.0_dp, 0.0_dp, 'at x = l')
    call assert_equal(rep%stress_fibre, -1, 'bottom fibre')
    call assert_true(.not. rep%beyond_peak, 'below eps*')
    el = example_element(all_off())
    rep = beam_stress_recovery(el, to_q(phi, -p), phi)
    call assert_rel_close(rep%stress, -alu%e1*eps, 1.0e-12_dp, 'linear sigma, compressive')
    call assert_equal(rep%stress_fibre, -1, 'bottom fibre')
  end subroutine test_stress_recovery

  !> Outer-fibre strain past eps* = 6.573e-3: both the evaluation (Gauss
  !> points) and the stress report flag it, with the strain; not below the
  !> peak, and not with the material switch off (the linear law has no peak).
  subroutine test_peak_detection()
    type(kear_element_t) :: el
    type(stress_report_t) :: rep
    type(element_eval_info_t) :: info
    type(rigid_state_t) :: rb
    real(dp) :: a, p(8), m(8, 8), f(8), eb
    integer :: k
    do k = 1, 2
      eb = merge(7.5e-3_dp, 4.0e-3_dp, k == 1)   ! plus ~1e-3 from w_x^2/2 at this deflection
      a = eb/(3.0_dp*t_x*l_x)
      p = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0e-4_dp*l_x, a*l_x**3, 3*a*l_x**2, 6*a*l_x]
      el = example_element(effects_all_on())
      rep = beam_stress_recovery(el, p, 0.0_dp)
      call el%eval(p, 0.0_dp*p, rb, m, f, info)
      if (k == 1) then
        call assert_true(rep%beyond_peak .and. rep%max_abs_strain > peak_strain(alu), 'report flags eps > eps*')
        call assert_true(info%beyond_peak .and. info%max_abs_strain > peak_strain(alu), 'evaluation flags it')
        call assert_true(info%x_over_l_max_strain > 0.9_dp, 'near x = l')
      else
        call assert_true(.not. rep%beyond_peak .and. .not. info%beyond_peak, 'not flagged below eps*')
      end if
    end do
    el = example_element(element_effects_t(stretching=.true., curvature=.true.))
    a = 7.5e-3_dp/(3.0_dp*t_x*l_x)
    p = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0e-4_dp*l_x, a*l_x**3, 3*a*l_x**2, 6*a*l_x]
    rep = beam_stress_recovery(el, p, 0.0_dp)
    call assert_true(.not. rep%beyond_peak .and. rep%max_abs_strain > peak_strain(alu), &
                     'material off: large strain not flagged')
  end subroutine test_peak_detection

  !> Damping force = -beta K_t(q) p_dot with p_dot = T q_dot - phi_d J_b p,
  !> the rate of the local nodal values (strain rates):
  !>  - linear model, phi_d = 0: exactly -beta K q_dot (1e-13);
  !>  - nonlinear model: -beta K_t(q)(q_dot - phi_d T^T J_b T q) (1e-12);
  !>  - a deformed element carried round by its frame (p_dot = 0) is not damped;
  !>    the non-objective option (-beta K_t q_dot) would damp it.
  subroutine test_damping()
    type(kear_element_t) :: el0, el1, el2
    type(rigid_state_t) :: rb
    type(element_eval_info_t) :: info
    real(dp), parameter :: beta = 2.0e-3_dp
    real(dp) :: m(8, 8), f0(8), f1(8), kt(8, 8), p(8), qd(8)
    ! linear, no rotation
    el0 = unit_element(all_off())
    el1 = unit_element(all_off(), beta=beta)
    call el0%eval(q_big, qd_big, rb, m, f0, info)
    call el1%eval(q_big, qd_big, rb, m, f1, info)
    call beam_tangent_stiffness(el0, q_big, rb%phi, kt)
    call assert_all_close(f1 - f0, -beta*matmul(kt, qd_big), 0.0_dp, 1.0e-13_dp*maxval(abs(f1 - f0)), &
                          'linear: -beta K qdot')
    ! nonlinear, rotating frame
    rb = rigid_at(0.3_dp)
    el0 = unit_element(effects_all_on())
    el1 = unit_element(effects_all_on(), beta=beta)
    call el0%eval(q_big, qd_big, rb, m, f0, info)
    call el1%eval(q_big, qd_big, rb, m, f1, info)
    call beam_tangent_stiffness(el0, q_big, rb%phi, kt)
    p = el0%local_dofs(q_big, rb%phi)
    call assert_all_close(f1 - f0, -beta*matmul(kt, qd_big - rb%phi_d*to_q(rb%phi, jb(p))), 0.0_dp, &
                          1.0e-12_dp*maxval(abs(f1 - f0)), 'nonlinear: -beta K_t p_dot')
    ! frozen deformation in a rotating frame: q_dot = T^T phi_d J_b p
    qd = rb%phi_d*to_q(rb%phi, jb(p))
    call el0%eval(q_big, qd, rb, m, f0, info)
    call el1%eval(q_big, qd, rb, m, f1, info)
    call assert_true(maxval(abs(f1 - f0)) <= 1.0e-12_dp*beta*maxval(abs(kt))*maxval(abs(q_big)), &
                     'rigidly carried deformation is not damped')
    el2 = unit_element(effects_all_on(), beta=beta, objective=.false.)
    call el2%eval(q_big, qd, rb, m, f1, info)
    call assert_true(maxval(abs(f1 - f0)) > 1.0e-3_dp*beta*maxval(abs(kt))*maxval(abs(q_big)), &
                     'non-objective option damps it')
  end subroutine test_damping

  subroutine test_invalid_input()
    type(kear_element_t) :: el
    type(error_t) :: err
    integer :: code
    call kear_element_init(el, 0.0_dp, b_u, t_u, soft, all_off(), err)
    call assert_true(err%failed() .and. index(err%text(), 'length') > 0, 'zero length: '//err%text())
    call err%clear()
    call kear_element_init(el, l_u, b_u, t_u, soft, all_off(), err, n_gauss=1)
    call assert_true(err%failed() .and. index(err%text(), 'n_gauss') > 0, 'one Gauss point: '//err%text())
    call err%clear()
    call kear_element_init(el, l_u, b_u, t_u, ramberg_osgood_t(e1=1.0_dp, e2=1.0_dp, m=0.5_dp), all_off(), err)
    call assert_true(err%failed() .and. index(err%text(), 'exponent') > 0, 'bad material: '//err%text())
    call err%clear()
    call formulation_from_name(' Kear1987 ', code, err)
    call assert_true(.not. err%failed() .and. code == formulation_kear1987, 'kear1987 by name')
    call formulation_from_name('printed', code, err)
    call assert_true(err%failed() .and. index(err%text(), 'printed') > 0, 'unknown name: '//err%text())
    call assert_equal(formulation_name(formulation_exact), 'exact', 'name of exact')
  end subroutine test_invalid_input
end module test_kear_element_suite

program test_kear_element
  use test_kear_element_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_kear_element')
end program test_kear_element
