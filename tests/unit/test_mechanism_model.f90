!> Tests of the assembled equations of motion (module mechanism_model) on
!> beams whose exact answers are known: Euler-Bernoulli natural frequencies of
!> pinned-pinned and clamped-clamped beams, the period of a beam released from
!> a mode shape, energy conservation, and the linear cost of one RHS.
module test_mechanism_model_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use correlation_table, only: link_end_t, joint_ground_pin, joint_clamp
  use element_effects, only: element_effects_t
  use planar_element, only: rigid_state_t
  use material_law, only: ramberg_osgood_t
  use mechanism_model, only: mechanism_model_t, element_spec_t
  use lsode_solver, only: lsode_t, mf_adams
  use linalg, only: solve_linear
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use assertions
  use transient_fixtures, only: fourbar_input, cantilever_input, mode_start
  implicit none
  private
  public :: run_all

  ! A slender aluminium beam (FORMULATION.md §8.1 material), 1.0 x 0.25 in section.
  real(dp), parameter :: length = 20.0_dp, width = 0.25_dp, depth = 1.0_dp
  real(dp), parameter :: e1 = 10.87e6_dp, e2 = 0.8387e11_dp, rho = 2.536e-4_dp
  ! Euler-Bernoulli eigenvalues beta_n L
  real(dp), parameter :: bl_clamped(2) = [4.730040744862704_dp, 7.853204624095838_dp]

contains

  subroutine run_all()
    call run_test('pinned_pinned_frequencies_match_euler_bernoulli', test_pinned_frequencies)
    call run_test('clamped_clamped_frequencies_match_euler_bernoulli', test_clamped_frequencies)
    call run_test('pinned_beam_released_from_mode1_has_theory_period', test_pinned_period_mode1)
    call run_test('clamped_beam_released_from_mode2_has_theory_period', test_clamped_period_mode2)
    call run_test('energy_is_conserved_without_damping', test_energy_conservation)
    call run_test('fourbar_quasi_static_load_matches_rigid_body_statics', test_fourbar_statics)
    call run_test('rhs_cost_is_linear_in_elements', test_linear_cost_structure)
    call run_test('tabulated_rigid_motion_matches_kinematics', test_motion_table)
    call run_test('cantilever_with_tip_mass_has_exact_frequency', test_tip_mass)
    call run_test('spinning_arm_with_tip_mass_stretches_as_a_bar', test_tip_mass_load)
  end subroutine run_all

  !> A horizontal beam of n elements with the given end conditions.
  subroutine beam(n, end_kind, effects, model, err)
    integer, intent(in) :: n, end_kind
    type(element_effects_t), intent(in) :: effects
    type(mechanism_model_t), intent(out) :: model
    type(error_t), intent(inout) :: err
    type(element_spec_t) :: specs(n)
    type(rigid_state_t) :: states(n)
    type(link_end_t) :: ends(2, 1)
    integer :: e
    do e = 1, n
      specs(e) = element_spec_t(length/n, width, depth, ramberg_osgood_t(e1, e2, 3.0_dp, rho))
      states(e) = rigid_state_t(x1=(e - 1)*length/n, y1=0.0_dp, phi=0.0_dp)
    end do
    ends(:, 1) = link_end_t(end_kind, 0, 0.0_dp)
    call model%init_fixed(specs, states, [n], ends, effects, 'exact', 0.0_dp, err)
  end subroutine beam

  !> The deck's mechanism and its linear model (Kear's element, undamped).
  logical function linear_model(inp, mech, model) result(ok)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(out) :: mech
    type(mechanism_model_t), intent(out) :: model
    type(error_t) :: err
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'build_mechanism: '//err%text())
    if (.not. err%failed()) call model%init_mechanism(mech, element_effects_t(), 'exact', 0.0_dp, err)
    call assert_true(.not. err%failed(), 'init_mechanism: '//err%text())
    ok = .not. err%failed()
  end function linear_model

  real(dp) function euler_bernoulli(beta_l)
    real(dp), intent(in) :: beta_l
    real(dp) :: area, inertia
    area = width*depth
    inertia = width*depth**3/12.0_dp
    euler_bernoulli = (beta_l/length)**2*sqrt(e1*inertia/(rho*area))
  end function euler_bernoulli

  !> The lowest bending frequencies converge to (n pi / L)^2 sqrt(EI / rho A);
  !> with 4 quintic elements the first two are within 0.05 %.
  subroutine test_pinned_frequencies()
    call check_frequencies(joint_ground_pin, [pi, 2*pi], 'pinned-pinned')
  end subroutine test_pinned_frequencies

  subroutine test_clamped_frequencies()
    call check_frequencies(joint_clamp, bl_clamped, 'clamped-clamped')
  end subroutine test_clamped_frequencies

  !> The first two linear modes of the 4-element beam against Euler-Bernoulli
  !> with eigenvalues beta_l: 5e-4 relative.
  subroutine check_frequencies(end_kind, beta_l, label)
    integer, intent(in) :: end_kind
    real(dp), intent(in) :: beta_l(2)
    character(len=*), intent(in) :: label
    type(mechanism_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable :: omega(:), shapes(:, :)
    call beam(4, end_kind, element_effects_t(), model, err)
    call assert_true(.not. err%failed(), err%text())
    allocate(omega(model%n), shapes(model%n, model%n))
    call model%linear_modes(omega, shapes, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_rel_close(omega(1), euler_bernoulli(beta_l(1)), 5.0e-4_dp, label//' mode 1')
    call assert_rel_close(omega(2), euler_bernoulli(beta_l(2)), 5.0e-4_dp, label//' mode 2')
  end subroutine check_frequencies

  !> Release the beam from mode `k` (zero velocity) and time 4 periods by the
  !> zero crossings of the modal coordinate: within 0.5 % of the theory period.
  subroutine period_check(end_kind, mode, beta_l)
    integer, intent(in) :: end_kind, mode
    real(dp), intent(in) :: beta_l
    type(mechanism_model_t), target :: model
    type(error_t) :: err
    type(lsode_t) :: ode
    real(dp), allocatable :: omega(:), shapes(:, :), y(:)
    real(dp) :: t_theory, dt, t, a_prev, a, crossings(16), period, q(1000)
    integer :: k, n_cross
    call beam(4, end_kind, element_effects_t(), model, err)
    call mode_start(model, mode, 1.0e-3_dp, omega, shapes, y, err)
    t_theory = 2.0_dp*pi/euler_bernoulli(beta_l)
    dt = t_theory/200.0_dp
    call ode%init(size(y), 0.0_dp, mf_adams, 1.0e-9_dp, [1.0e-14_dp], err)
    q(1:model%n) = y(1::2)
    a_prev = dot_product(shapes(:, mode), q(1:model%n))
    n_cross = 0
    t = 0.0_dp
    do k = 1, 900
      t = k*dt
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      q(1:model%n) = y(1::2)
      a = dot_product(shapes(:, mode), q(1:model%n))
      if (a_prev*a < 0.0_dp .and. n_cross < size(crossings)) then
        n_cross = n_cross + 1
        crossings(n_cross) = t - dt*a/(a - a_prev)
      end if
      a_prev = a
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    call assert_true(n_cross >= 9, 'at least 4.5 periods observed')
    if (n_cross < 9) return
    period = (crossings(9) - crossings(1))/4.0_dp
    call assert_rel_close(period, t_theory, 5.0e-3_dp, 'period vs Euler-Bernoulli theory')
  end subroutine period_check

  subroutine test_pinned_period_mode1()
    call period_check(joint_ground_pin, 1, pi)
  end subroutine test_pinned_period_mode1

  subroutine test_clamped_period_mode2()
    call period_check(joint_clamp, 2, bl_clamped(2))
  end subroutine test_clamped_period_mode2

  !> Undamped, all effects on, large amplitude: kinetic + strain energy stays
  !> constant to a bound set by rtol (here 1e-8 -> drift below 1e-5 relative
  !> over 20 periods).
  subroutine test_energy_conservation()
    type(mechanism_model_t), target :: model
    type(error_t) :: err
    type(lsode_t) :: ode
    real(dp), allocatable :: omega(:), shapes(:, :), y(:)
    real(dp) :: t, ke, se, e0, drift, q(100), qd(100)
    integer :: k
    call beam(2, joint_ground_pin, element_effects_t(.true., .true., .true., .true., .true.), model, err)
    ! amplitude of about one section depth: strongly nonlinear (stretching)
    call mode_start(model, 1, 0.02_dp, omega, shapes, y, err)
    q(1:model%n) = y(1::2)
    qd(1:model%n) = y(2::2)
    call model%energies(0.0_dp, q(1:model%n), qd(1:model%n), ke, se)
    e0 = ke + se
    call ode%init(size(y), 0.0_dp, mf_adams, 1.0e-8_dp, [1.0e-13_dp], err)
    drift = 0.0_dp
    do k = 1, 40
      t = k*(pi/omega(1))
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      q(1:model%n) = y(1::2)
      qd(1:model%n) = y(2::2)
      call model%energies(t, q(1:model%n), qd(1:model%n), ke, se)
      drift = max(drift, abs(ke + se - e0)/e0)
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    call assert_true(drift < 1.0e-5_dp, 'relative energy drift over 20 periods < 1e-5')
  end subroutine test_energy_conservation
  !> The four-bar of FORMULATION.md §8.1 (2 elements per link) turned at
  !> omega from rest ('spinup', 0.02 s) or at constant speed.
  function profiled_fourbar(omega, profile) result(inp)
    real(dp), intent(in) :: omega
    character(len=*), intent(in) :: profile
    type(mechanism_input_t) :: inp
    inp = fourbar_input(2, omega, 0.0_dp)
    inp%profile = profile
    if (profile == 'spinup') inp%spinup_time = 0.02_dp
  end function profiled_fourbar

  !> Rigid states interpolated from the per-revolution table against the
  !> kinematics solved directly, at times spread over three revolutions
  !> (constant speed) and through a spin-up.  720 points per revolution,
  !> h = 8.7e-3 rad: quintic Hermite interpolation errs by O(h^6) ~ 1e-12 in
  !> positions, O(h^5) in rates and O(h^4) ~ 6e-9 in accelerations, relative
  !> to their scales; asked: 1e-10, 1e-9, 5e-8.
  subroutine test_motion_table()
    call compare_table_with_kinematics('constant')
    call compare_table_with_kinematics('spinup')
  end subroutine test_motion_table

  subroutine compare_table_with_kinematics(profile)
    character(len=*), intent(in) :: profile
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: direct, table
    type(error_t) :: err
    real(dp) :: t, scale_p, scale_v, scale_a, w
    integer :: k, e
    w = 150.0_dp
    call build_mechanism(profiled_fourbar(w, profile), mech, err)
    call direct%init_mechanism(mech, element_effects_t(), 'exact', 0.0_dp, err)
    call table%init_mechanism(mech, element_effects_t(), 'exact', 0.0_dp, err, table_points=720)
    call assert_true(.not. err%failed(), 'table: '//err%text())
    if (err%failed()) return
    scale_p = 10.0_dp
    scale_v = w*scale_p
    scale_a = w*w*scale_p
    do k = 1, 97
      t = k*(3.0_dp*two_pi_local()/w)/97.0_dp
      call direct%set_time(t)
      call table%set_time(t)
      do e = 1, size(direct%rb)
        call assert_close(table%rb(e)%x1, direct%rb(e)%x1, 1.0e-10_dp*scale_p, profile//' X1')
        call assert_close(table%rb(e)%phi, direct%rb(e)%phi, 1.0e-10_dp, profile//' phi')
        call assert_close(table%rb(e)%y1_d, direct%rb(e)%y1_d, 1.0e-9_dp*scale_v, profile//' Y1_dot')
        call assert_close(table%rb(e)%phi_d, direct%rb(e)%phi_d, 1.0e-9_dp*w, profile//' phi_dot')
        call assert_close(table%rb(e)%x1_dd, direct%rb(e)%x1_dd, 5.0e-8_dp*scale_a, profile//' X1_ddot')
        call assert_close(table%rb(e)%phi_dd, direct%rb(e)%phi_dd, 5.0e-8_dp*w*w, profile//' phi_ddot')
      end do
    end do
  end subroutine compare_table_with_kinematics

  !> A clamped-free beam carrying a point mass M at its tip (a joint mass):
  !> the lowest frequency solves 1 + cos(bL) cosh(bL) + mu bL (cos(bL) sinh(bL)
  !> - sin(bL) cosh(bL)) = 0, mu = M / (rho A L) (Euler-Bernoulli with a tip
  !> mass, e.g. Blevins, Formulas for natural frequency and mode shape, table
  !> 8-8).  4 quintic elements: within 1e-4.
  subroutine test_tip_mass()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable :: omega(:), shapes(:, :)
    real(dp) :: mu, lo, hi, mid, bl
    integer :: i
    mu = 0.5_dp
    inp = cantilever_input(4, 0.0_dp)       ! the beam clamped on a stopped crank shaft
    inp%joint_mass(2) = mu*rho*width*depth*length
    if (.not. linear_model(inp, mech, model)) return
    allocate(omega(model%n), shapes(model%n, model%n))
    call model%linear_modes(omega, shapes, err)
    lo = 0.5_dp
    hi = 1.875_dp
    do i = 1, 100
      mid = 0.5_dp*(lo + hi)
      if (tip_mass_equation(lo, mu)*tip_mass_equation(mid, mu) <= 0.0_dp) then
        hi = mid
      else
        lo = mid
      end if
    end do
    bl = 0.5_dp*(lo + hi)
    call assert_rel_close(omega(1), euler_bernoulli(bl), 1.0e-4_dp, 'tip-mass cantilever mode 1')
  end subroutine test_tip_mass

  !> An arm spinning at 100 rad/s about its clamped end with a tip mass M:
  !> the quasi-static axial stretch K q = F is that of a bar under its own
  !> centrifugal load plus M Omega^2 L at the tip,
  !>   u(L) = rho Omega^2 L^3 / (3 E) + M Omega^2 L^2 / (E A).
  !> The linear analysis leaves out centrifugal softening of the axial
  !> stiffness, of relative size rho Omega^2 L^2 / E = 1e-4: asked 1e-3.
  subroutine test_tip_mass_load()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable :: q(:), qd(:), qdd(:), mass(:, :), stiff(:, :), load(:)
    real(dp) :: big_m, omega, expected, qe(8)
    integer :: last
    omega = 100.0_dp
    big_m = 0.5_dp*rho*width*depth*length
    inp = cantilever_input(4, omega)
    inp%joint_mass(2) = big_m
    if (.not. linear_model(inp, mech, model)) return
    allocate(q(model%n), qd(model%n), qdd(model%n), mass(model%n, model%n), stiff(model%n, model%n))
    q = 0.0_dp
    qd = 0.0_dp
    call model%accelerations(0.0_dp, q, qd, qdd)
    load = model%force
    call model%assemble_dense(q, mass, stiff)
    call solve_linear(stiff, load, err)
    last = size(model%el)
    qe = model%table%gather(last, load)
    expected = rho*omega**2*length**3/(3.0_dp*e1) + big_m*omega**2*length**2/(e1*width*depth)
    call assert_rel_close(qe(5), expected, 1.0e-3_dp, 'tip stretch U (arm along +X at t = 0)')
  end subroutine test_tip_mass_load

  pure real(dp) function tip_mass_equation(x, mu)
    real(dp), intent(in) :: x, mu
    tip_mass_equation = 1.0_dp + cos(x)*cosh(x) + mu*x*(cos(x)*sinh(x) - sin(x)*cosh(x))
  end function tip_mass_equation

  pure real(dp) function two_pi_local()
    two_pi_local = 2.0_dp*pi
  end function two_pi_local

  !> Tennant's four-bar at crank angle 0, 150 rad/s: the quasi-static
  !> solution K q = F(q = 0, q_dot = 0) of the flexible model against an
  !> independent rigid-body statics calculation of the coupler and rocker
  !> loading the crank as a cantilever (tools/independent/fourbar_statics.py:
  !> crank-root curvature 4.67876606e-3 /in).  One quintic element per link
  !> represents these load cases exactly, so 1e-5 relative is asked.
  subroutine test_fourbar_statics()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable :: q(:), qd(:), qdd(:), mass(:, :), stiff(:, :), load(:)
    inp = profiled_fourbar(150.0_dp, 'constant')
    inp%link_n_elements(1:3) = 1
    if (.not. linear_model(inp, mech, model)) return
    allocate(q(model%n), qd(model%n), qdd(model%n), mass(model%n, model%n), stiff(model%n, model%n))
    q = 0.0_dp
    qd = 0.0_dp
    call model%accelerations(0.0_dp, q, qd, qdd)     ! fills model%force at t = 0
    load = model%force
    call model%assemble_dense(q, mass, stiff)
    call solve_linear(stiff, load, err)
    associate (root => model%table%unknown(4, 1))     ! m at node 1 of the crank's first element
      call assert_equal(trim(model%table%label_of(root)), 'L1 N1 m', 'the crank-root curvature unknown')
      call assert_rel_close(load(root), 4.67876606e-3_dp, 1.0e-5_dp, 'crank-root curvature vs rigid-body statics')
    end associate
  end subroutine test_fourbar_statics

  !> The assembled mass matrix is banded with a half-bandwidth that does not
  !> grow with the number of elements: the RHS cost (banded Cholesky, element
  !> loop) is linear in the number of elements.
  subroutine test_linear_cost_structure()
    type(mechanism_model_t) :: m4, m32
    type(error_t) :: err
    call beam(4, joint_clamp, element_effects_t(), m4, err)
    call beam(32, joint_clamp, element_effects_t(), m32, err)
    call assert_equal(m32%kd, m4%kd, 'half-bandwidth independent of the number of elements')
    call assert_true(m32%kd <= 7, 'half-bandwidth of a beam chain at most 7')
    call assert_equal(size(m32%mass_band, 1), m32%kd + 1, 'M stored in band form, not dense')
  end subroutine test_linear_cost_structure
end module test_mechanism_model_suite

program test_mechanism_model
  use test_mechanism_model_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_mechanism_model')
end program test_mechanism_model
