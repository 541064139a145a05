!> Tests of the shaking force (module shaking_force): the rigid four-bar
!> against the closed-form loop-equation analysis, full force balance by
!> Berkof-Lowen counterweights, and the periodic second derivative.
module test_shaking_force_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use shaking_force, only: rigid_momentum_rate, elastic_first_moment, periodic_second_derivative
  use assertions
  use mechanism_fixtures, only: fourbar_abcd
  use test_text, only: rtoa
  implicit none
  private
  public :: run_all

  !> Tennant's four-bar (FORMULATION.md §8.1), aluminium 0.25 x 1 in, 150 rad/s
  real(dp), parameter :: a1 = 10.0_dp, a2 = 5.0_dp, a3 = 11.0_dp, a4 = 10.5_dp, omega = 150.0_dp
  real(dp), parameter :: rho_a = 2.536e-4_dp*0.25_dp     !< mass per length
  real(dp), parameter :: theta0 = 0.3_dp

contains

  subroutine run_all()
    call run_test('rigid_fourbar_shaking_force_matches_closed_form', test_closed_form)
    call run_test('berkof_lowen_counterweights_cancel_the_shaking_force', test_balance)
    call run_test('periodic_second_derivative_is_exact_for_trig_polynomials', test_derivative)
  end subroutine run_all

  !> The four-bar with two elements per link; counterweights (mass, x) on crank and rocker.
  subroutine make_fourbar(cw1, cw3, mech, model)
    real(dp), intent(in) :: cw1(2), cw3(2)
    type(mechanism_t), intent(out) :: mech
    type(steady_model_t), intent(out) :: model
    type(mechanism_input_t) :: inp
    type(error_t) :: err
    type(tennant_options_t) :: opt
    type(link_sections_t) :: sections(3)
    inp = fourbar_abcd(a2, a3, a4, a1)
    inp%link_b(1:3) = 0.25_dp
    inp%link_h(1:3) = 1.0_dp
    inp%link_n_elements(1:3) = 2
    inp%omega = omega
    inp%theta0_deg = theta0*180.0_dp/pi
    inp%link_cw_mass(1) = cw1(1)
    inp%link_cw_x(1) = cw1(2)
    inp%link_cw_mass(3) = cw3(1)
    inp%link_cw_x(3) = cw3(2)
    call build_mechanism(inp, mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, opt, sections, err)
    call assert_true(.not. err%failed(), 'four-bar builds: '//err%text())
  end subroutine make_fourbar

  !> Closed form (vector loop a2 e2 + a3 e3 = a1 + a4 e4, differentiated
  !> twice at constant crank speed) against the model's rigid part at 24
  !> crank angles: 1e-6 of the peak (the kinematics converges to round-off;
  !> the margin is for the 2x2 solves near the transmission extremes).
  subroutine test_closed_form()
    type(mechanism_t) :: mech
    type(steady_model_t) :: model
    type(error_t) :: err
    real(dp) :: f(2), fc(2), peak, worst, t
    integer :: k
    call make_fourbar([0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], mech, model)
    peak = 0.0_dp
    worst = 0.0_dp
    do k = 0, 23
      t = real(k, dp)*(2.0_dp*pi/omega)/24.0_dp
      call model%set_time(t, err)
      f = rigid_momentum_rate(model, mech)
      fc = closed_form(theta0 + omega*t, model%fs(mech%links(2)%first_element)%phi)
      peak = max(peak, hypot(fc(1), fc(2)))
      worst = max(worst, hypot(f(1) - fc(1), f(2) - fc(2)))
    end do
    call assert_true(peak > 1.0_dp, 'the unbalanced four-bar shakes (peak '//rtoa(peak)//' lb)')
    call assert_true(worst <= 1.0e-6_dp*peak, 'rigid shaking force vs closed form: worst difference '// &
                     rtoa(worst)//' lb of peak '//rtoa(peak))
  end subroutine test_closed_form

  !> m a_G summed over crank, coupler and rocker; theta3_model picks the
  !> assembly branch only (the closed form's two solutions differ by far more).
  function closed_form(t2, theta3_model) result(f)
    real(dp), intent(in) :: t2, theta3_model
    real(dp) :: f(2)
    complex(dp) :: e2, e3, e4, b, d, c, r, ag2, ag3, ag4
    real(dp) :: l, beta, gam, t3, t4, w3, w4, al3, al4, det, m2, m3, m4
    complex(dp), parameter :: i = (0.0_dp, 1.0_dp)
    e2 = exp(i*t2)
    b = a2*e2
    d = cmplx(a1, 0.0_dp, dp)
    l = abs(d - b)
    beta = atan2(aimag(d - b), real(d - b))
    gam = acos((a3**2 + l**2 - a4**2)/(2.0_dp*a3*l))
    t3 = beta + gam
    if (abs(sin(0.5_dp*(t3 - theta3_model))) > abs(sin(0.5_dp*(beta - gam - theta3_model)))) t3 = beta - gam
    e3 = exp(i*t3)
    c = b + a3*e3
    t4 = atan2(aimag(c - d), real(c - d))
    e4 = exp(i*t4)
    ! velocities: a3 w3 i e3 - a4 w4 i e4 = -a2 w2 i e2
    det = a3*a4*sin(t4 - t3)
    w3 = -a2*omega*a4*sin(t4 - t2)/det
    w4 = -a2*omega*a3*sin(t3 - t2)/det
    ! accelerations: a3 al3 i e3 - a4 al4 i e4 = r
    r = a2*omega**2*e2 + a3*w3**2*e3 - a4*w4**2*e4
    ! Cramer on [-a3 sin t3, a4 sin t4; a3 cos t3, -a4 cos t4] (al3, al4) = (Re r, Im r)
    det = a3*a4*sin(t3 - t4)
    al3 = (-a4*cos(t4)*real(r) - a4*sin(t4)*aimag(r))/det
    al4 = (-a3*sin(t3)*aimag(r) - a3*cos(t3)*real(r))/det
    m2 = rho_a*a2
    m3 = rho_a*a3
    m4 = rho_a*a4
    ag2 = -omega**2*0.5_dp*a2*e2
    ag3 = -omega**2*a2*e2 + (i*al3 - w3**2)*0.5_dp*a3*e3
    ag4 = (i*al4 - w4**2)*0.5_dp*a4*e4
    f = [real(m2*ag2 + m3*ag3 + m4*ag4), aimag(m2*ag2 + m3*ag3 + m4*ag4)]
  end function closed_form

  !> Berkof-Lowen: with a uniform coupler, the total centre of mass is still
  !> when the crank's first moment about A is -(m2 + m3) a2/2 and the
  !> rocker's about D is -(m4 + m3) a4/2 (along each link).  Counterweights
  !> of mass m2 + m3 at -a2/2 and m4 + m3 at -a4/2 give that: the rigid
  !> shaking force vanishes to round-off (1e-9 of the unbalanced peak).
  subroutine test_balance()
    type(mechanism_t) :: mech, mech0
    type(steady_model_t) :: model, model0
    type(error_t) :: err
    real(dp) :: f(2), peak0, worst, t, m2, m3, m4
    integer :: k
    m2 = rho_a*a2
    m3 = rho_a*a3
    m4 = rho_a*a4
    call make_fourbar([0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp], mech0, model0)
    call make_fourbar([m2 + m3, -0.5_dp*a2], [m4 + m3, -0.5_dp*a4], mech, model)
    peak0 = 0.0_dp
    worst = 0.0_dp
    do k = 0, 23
      t = real(k, dp)*(2.0_dp*pi/omega)/24.0_dp
      call model0%set_time(t, err)
      call model%set_time(t, err)
      f = rigid_momentum_rate(model0, mech0)
      peak0 = max(peak0, hypot(f(1), f(2)))
      f = rigid_momentum_rate(model, mech)
      worst = max(worst, hypot(f(1), f(2)))
    end do
    call assert_true(worst <= 1.0e-9_dp*peak0, 'balanced shaking force '//rtoa(worst)//' lb, unbalanced '// &
                     rtoa(peak0))
  end subroutine test_balance

  !> s = (cos 3wt + 2 sin wt, sin 5wt) at 16 samples: s'' exact to round-off.
  subroutine test_derivative()
    integer, parameter :: n = 16
    real(dp) :: s(2, n), expect(2, n), got(2, n), t, period, w
    integer :: k
    period = 0.04_dp
    w = 2.0_dp*pi/period
    do k = 1, n
      t = real(k - 1, dp)*period/n
      s(:, k) = [cos(3.0_dp*w*t) + 2.0_dp*sin(w*t), sin(5.0_dp*w*t)]
      expect(:, k) = [-9.0_dp*w**2*cos(3.0_dp*w*t) - 2.0_dp*w**2*sin(w*t), -25.0_dp*w**2*sin(5.0_dp*w*t)]
    end do
    got = periodic_second_derivative(s, period)
    call assert_true(maxval(abs(got - expect)) <= 1.0e-10_dp*25.0_dp*w**2, 'trig polynomial second derivative')
  end subroutine test_derivative
end module test_shaking_force_suite

program test_shaking_force
  use test_shaking_force_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_shaking_force')
end program test_shaking_force
