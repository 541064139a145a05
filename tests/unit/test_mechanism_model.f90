!> Tests of the assembled equations of motion (module mechanism_model) on
!> beams whose exact answers are known: Euler-Bernoulli natural frequencies of
!> pinned-pinned and clamped-clamped beams, the period of a beam released from
!> a mode shape, energy conservation, and the linear cost of one RHS.
module test_mechanism_model_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use correlation_table, only: link_end_t, joint_ground_pin, joint_clamp
  use kear_element, only: rigid_state_t, element_effects_t
  use material_law, only: ramberg_osgood_t
  use mechanism_model, only: mechanism_model_t, element_spec_t
  use lsode_solver, only: lsode_t, mf_adams
  use assertions
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
    type(mechanism_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable :: omega(:), shapes(:, :)
    call beam(4, joint_ground_pin, element_effects_t(), model, err)
    call assert_true(.not. err%failed(), err%text())
    allocate(omega(model%n), shapes(model%n, model%n))
    call model%linear_modes(omega, shapes, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_rel_close(omega(1), euler_bernoulli(pi), 5.0e-4_dp, 'pinned-pinned mode 1')
    call assert_rel_close(omega(2), euler_bernoulli(2*pi), 5.0e-4_dp, 'pinned-pinned mode 2')
  end subroutine test_pinned_frequencies

  subroutine test_clamped_frequencies()
    type(mechanism_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable :: omega(:), shapes(:, :)
    call beam(4, joint_clamp, element_effects_t(), model, err)
    call assert_true(.not. err%failed(), err%text())
    allocate(omega(model%n), shapes(model%n, model%n))
    call model%linear_modes(omega, shapes, err)
    call assert_rel_close(omega(1), euler_bernoulli(bl_clamped(1)), 5.0e-4_dp, 'clamped-clamped mode 1')
    call assert_rel_close(omega(2), euler_bernoulli(bl_clamped(2)), 5.0e-4_dp, 'clamped-clamped mode 2')
  end subroutine test_clamped_frequencies

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
    allocate(omega(model%n), shapes(model%n, model%n), y(model%state_size()))
    call model%linear_modes(omega, shapes, err)
    y = 0.0_dp
    y(1::2) = 1.0e-3_dp*shapes(:, mode)/maxval(abs(shapes(:, mode)))
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
    allocate(omega(model%n), shapes(model%n, model%n), y(model%state_size()))
    call model%linear_modes(omega, shapes, err)
    y = 0.0_dp
    ! amplitude of about one section depth: strongly nonlinear (stretching)
    y(1::2) = 0.02_dp*shapes(:, 1)/maxval(abs(shapes(:, 1)))
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
end module test_mechanism_model_suite

program test_mechanism_model
  use test_mechanism_model_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_mechanism_model')
end program test_mechanism_model
