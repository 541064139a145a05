!> Tests of the contact-force law of a clearance joint (module contact_law):
!> the Hertz force and its derivatives, friction, and the energy lost in one
!> impact of a mass on the contact integrated by DLSODE at tight tolerance
!> (an integrator and a dimensional set-up independent of the law's own
!> dimensionless Runge-Kutta calibration).
module test_contact_law_suite
  use kinds, only: dp
  use error_status, only: error_t
  use contact_law
  use lsode_solver, only: lsode_t, mf_adams
  use assertions
  use ode_problems, only: impact_t
  use test_text, only: rtoa
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('normal_force_is_hertz_without_rate_and_zero_out_of_contact', test_hertz)
    call run_test('force_derivatives_equal_difference_quotients', test_derivatives)
    call run_test('friction_is_smoothed_coulomb', test_friction)
    call run_test('lankarani_nikravesh_restitution_within_1e-3_for_e_0p98_to_1', test_ln_range)
    call run_test('lankarani_nikravesh_effective_e_at_0p8_and_0_match_independent_values', test_ln_low_e)
    call run_test('calibrated_law_loses_the_energy_of_its_restitution_1e-3', test_calibrated_energy)
    call run_test('flores_law_restitution_near_one', test_flores)
    call run_test('invalid_law_parameters_are_rejected', test_invalid)
  end subroutine run_all

  !> Exit speed of a mass m hitting the contact at v0 (DLSODE Adams, rtol
  !> 1e-11): integrated to 40 contact time scales, where the mass has long
  !> left the contact and flies at its exit speed.
  real(dp) function exit_speed(law, m, v0) result(v1)
    type(contact_law_t), intent(in) :: law
    real(dp), intent(in) :: m, v0
    type(impact_t), target :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(2), tscale
    integer :: k
    sys%law = law
    sys%mass = m
    sys%v0 = v0
    tscale = (m*v0**(1.0_dp - law%exponent)/law%stiffness)**(1.0_dp/(law%exponent + 1.0_dp))
    y = [0.0_dp, v0]
    call ode%init(2, 0.0_dp, mf_adams, 1.0e-11_dp, [1.0e-16_dp], err, max_steps=100000)
    do k = 1, 400
      call ode%integrate_to(sys, y, k*0.1_dp*tscale, err)
      if (err%failed()) exit
      if (y(1) < -0.5_dp*v0*tscale) exit   ! well clear of the contact
    end do
    call assert_true(.not. err%failed(), 'impact integration: '//err%text())
    call assert_true(y(1) < 0.0_dp, 'the mass left the contact')
    v1 = -y(2)
  end function exit_speed

  !> F = K delta^1.5 exactly at zero rate; nothing without penetration.
  subroutine test_hertz()
    type(contact_law_t) :: law
    type(error_t) :: err
    real(dp) :: f, d1, d2, delta
    integer :: i
    call contact_law_init(law, 'lankarani_nikravesh', 2.8e7_dp, 1.5_dp, 0.9_dp, 0.0_dp, 1.0_dp, err)
    call assert_true(.not. err%failed(), err%text())
    do i = 1, 4
      delta = 10.0_dp**(-i - 2)
      call normal_force(law, delta, 0.0_dp, 10.0_dp, f, d1, d2)
      call assert_rel_close(f, 2.8e7_dp*delta*sqrt(delta), 1.0e-14_dp, 'Hertz K delta^1.5 at delta = '//rtoa(delta))
    end do
    call normal_force(law, -1.0e-4_dp, -3.0_dp, 10.0_dp, f, d1, d2)
    call assert_true(abs(f) + abs(d1) + abs(d2) <= 0.0_dp, 'free flight: no force')
    ! the hysteresis factor of Lankarani-Nikravesh: 3(1 - e^2)/4
    call assert_rel_close(law%chi, 0.75_dp*(1.0_dp - 0.81_dp), 1.0e-15_dp, 'chi')
    ! approaching (rate > 0) the damping adds, separating it subtracts
    call normal_force(law, 1.0e-4_dp, 5.0_dp, 10.0_dp, f, d1, d2)
    call assert_rel_close(f, 2.8e7_dp*1.0e-6_dp*(1.0_dp + law%chi*0.5_dp), 1.0e-14_dp, 'damped loading')
  end subroutine test_hertz

  !> Central differences (step 1e-6 relative: truncation ~1e-12, round-off ~1e-10).
  subroutine test_derivatives()
    type(contact_law_t) :: law
    type(error_t) :: err
    real(dp) :: f, d1, d2, fp, fm, a, b, delta, rate, h
    call contact_law_init(law, 'flores', 1.0e6_dp, 1.5_dp, 0.6_dp, 0.3_dp, 0.5_dp, err)
    delta = 2.0e-3_dp
    rate = -0.7_dp
    call normal_force(law, delta, rate, 3.0_dp, f, d1, d2)
    h = 1.0e-6_dp*delta
    call normal_force(law, delta + h, rate, 3.0_dp, fp, a, b)
    call normal_force(law, delta - h, rate, 3.0_dp, fm, a, b)
    call assert_rel_close(d1, (fp - fm)/(2*h), 1.0e-7_dp, 'dF/d delta')
    h = 1.0e-6_dp
    call normal_force(law, delta, rate + h, 3.0_dp, fp, a, b)
    call normal_force(law, delta, rate - h, 3.0_dp, fm, a, b)
    call assert_rel_close(d2, (fp - fm)/(2*h), 1.0e-7_dp, 'dF/d rate')
    call friction_force(law, f, 0.2_dp, fp, d1)
    call friction_force(law, f, 0.2_dp + h, a, b)
    call friction_force(law, f, 0.2_dp - h, fm, b)
    call assert_rel_close(d1, (a - fm)/(2*h), 1.0e-7_dp, 'dFt/dv')
  end subroutine test_derivatives

  !> mu F_n opposite to sliding once the speed is a few v_s; 0 at rest; odd.
  subroutine test_friction()
    type(contact_law_t) :: law
    type(error_t) :: err
    real(dp) :: ft, d, ft2
    call contact_law_init(law, 'lankarani_nikravesh', 1.0e6_dp, 1.5_dp, 0.9_dp, 0.2_dp, 0.01_dp, err)
    call friction_force(law, 100.0_dp, 1.0_dp, ft, d)         ! 100 v_s: tanh = 1 - 2e-87
    call assert_rel_close(ft, -20.0_dp, 1.0e-15_dp, 'Coulomb mu F_n at 100 v_s')
    call friction_force(law, 100.0_dp, -1.0_dp, ft2, d)
    call assert_close(ft2, -ft, 0.0_dp, 'odd in the sliding speed')
    call friction_force(law, 100.0_dp, 0.0_dp, ft, d)
    call assert_close(ft, 0.0_dp, 0.0_dp, 'no force at zero sliding speed')
    call assert_rel_close(d, -20.0_dp/0.01_dp, 1.0e-15_dp, 'slope mu F_n / v_s at zero speed')
    call friction_force(law, 100.0_dp, 0.03_dp, ft, d)         ! 3 v_s: tanh 3 = 0.99505
    call assert_rel_close(ft, -20.0_dp*tanh(3.0_dp), 1.0e-15_dp, 'tanh regularisation at 3 v_s')
    law%friction = 0.0_dp
    call friction_force(law, 100.0_dp, 1.0_dp, ft, d)
    call assert_true(abs(ft) + abs(d) <= 0.0_dp, 'mu = 0: no friction')
  end subroutine test_friction

  !> Lankarani-Nikravesh derived the factor for e near 1: the effective
  !> restitution (exit/approach speed of a mass hitting the contact) is within
  !> 1e-3 of e for e in [0.98, 1] (measured 1.5e-4 at e = 0.99, 6e-4 at 0.98,
  !> 3.5e-3 at 0.95).  Two masses, stiffnesses and speeds: e is independent of
  !> them (the dimensionless argument of the module header).
  subroutine test_ln_range()
    type(contact_law_t) :: law
    type(error_t) :: err
    real(dp) :: e, v1
    integer :: i
    do i = 0, 2
      e = 1.0_dp - 0.01_dp*i
      call contact_law_init(law, 'lankarani_nikravesh', 2.8e7_dp, 1.5_dp, e, 0.0_dp, 1.0_dp, err)
      v1 = exit_speed(law, 1.0e-3_dp, 20.0_dp)
      call assert_close(v1/20.0_dp, e, 1.0e-3_dp, 'LN effective e vs e = '//rtoa(e))
      call contact_law_init(law, 'lankarani_nikravesh', 3.0e5_dp, 1.5_dp, e, 0.0_dp, 1.0_dp, err)
      call assert_close(exit_speed(law, 2.0_dp, 0.5_dp)/0.5_dp, v1/20.0_dp, 1.0e-7_dp, &
                        'LN effective e independent of m, K, v0 at e = '//rtoa(e))
    end do
    ! e = 0.95 is outside: the error exceeds 1e-3 (a check that the test can fail)
    call contact_law_init(law, 'lankarani_nikravesh', 2.8e7_dp, 1.5_dp, 0.95_dp, 0.0_dp, 1.0_dp, err)
    call assert_true(abs(exit_speed(law, 1.0e-3_dp, 20.0_dp)/20.0_dp - 0.95_dp) > 2.0e-3_dp, &
                     'LN off by more than 2e-3 at e = 0.95')
  end subroutine test_ln_range

  !> Far from e = 1 the Lankarani-Nikravesh factor dissipates too little: an
  !> independent fixed-step RK4 integration of u'' = -u^1.5 (1 + chi u')
  !> (Python, h = 1e-4, doc/clearance.md) gives effective e = 0.84710 at e = 0.8
  !> and 0.66296 at e = 0 (chi = 3/4); 5 digits quoted: tolerance 1e-5.
  subroutine test_ln_low_e()
    type(contact_law_t) :: law
    type(error_t) :: err
    call contact_law_init(law, 'lankarani_nikravesh', 1.0e6_dp, 1.5_dp, 0.8_dp, 0.0_dp, 1.0_dp, err)
    call assert_close(exit_speed(law, 0.01_dp, 3.0_dp)/3.0_dp, 0.84710_dp, 1.0e-5_dp, 'LN e = 0.8')
    call assert_close(impact_restitution(law%chi, 1.5_dp, 1.0e-3_dp), 0.84710_dp, 1.0e-5_dp, 'LN e = 0.8, RK4')
    call contact_law_init(law, 'lankarani_nikravesh', 1.0e6_dp, 1.5_dp, 0.0_dp, 0.0_dp, 1.0_dp, err)
    call assert_close(exit_speed(law, 0.01_dp, 3.0_dp)/3.0_dp, 0.66296_dp, 1.0e-5_dp, 'LN e = 0 (chi = 3/4)')
  end subroutine test_ln_low_e

  !> The calibrated law: energy lost in one impact, (1 - e^2) m v0^2 / 2,
  !> within 1e-3 relative over e = 0.9 ... 0.05 (the calibration's bisection
  !> and RK4 are good to ~1e-8 in e; DLSODE's rtol 1e-11).
  subroutine test_calibrated_energy()
    type(contact_law_t) :: law
    type(error_t) :: err
    real(dp), parameter :: es(5) = [0.9_dp, 0.7_dp, 0.5_dp, 0.2_dp, 0.05_dp]
    real(dp) :: m, v0, v1, lost, want
    integer :: i
    m = 0.02_dp
    v0 = 40.0_dp
    do i = 1, size(es)
      call contact_law_init(law, 'calibrated', 2.8e7_dp, 1.5_dp, es(i), 0.0_dp, 1.0_dp, err)
      call assert_true(.not. err%failed(), err%text())
      v1 = exit_speed(law, m, v0)
      lost = 0.5_dp*m*(v0**2 - v1**2)
      want = 0.5_dp*m*v0**2*(1.0_dp - es(i)**2)
      call assert_rel_close(lost, want, 1.0e-3_dp, 'energy lost per impact, e = '//rtoa(es(i)))
      call assert_close(v1/v0, es(i), 1.0e-6_dp, 'effective restitution, e = '//rtoa(es(i)))
    end do
    ! chi grows like 1/e as e -> 0 (the rebound speed is bounded by v0/chi)
    call assert_true(law%chi > 0.9_dp/0.05_dp .and. law%chi < 1.1_dp/0.05_dp, 'chi ~ 1/e at e = 0.05')
  end subroutine test_calibrated_energy

  !> Flores et al. 2011: within 1e-3 at e = 0.99 (measured 6.6e-4), and its
  !> factor 8(1-e)/(5e).
  subroutine test_flores()
    type(contact_law_t) :: law
    type(error_t) :: err
    call contact_law_init(law, 'flores', 1.0e6_dp, 1.5_dp, 0.99_dp, 0.0_dp, 1.0_dp, err)
    call assert_rel_close(law%chi, 1.6_dp*0.01_dp/0.99_dp, 1.0e-14_dp, 'chi = 8(1-e)/(5e)')
    call assert_close(exit_speed(law, 0.01_dp, 3.0_dp)/3.0_dp, 0.99_dp, 1.0e-3_dp, 'Flores e = 0.99')
  end subroutine test_flores

  subroutine test_invalid()
    type(contact_law_t) :: law
    type(error_t) :: err
    call contact_law_init(law, 'hertz', 1.0_dp, 1.5_dp, 0.5_dp, 0.0_dp, 1.0_dp, err)
    call assert_true(err%failed(), 'unknown law rejected')
    call err%clear()
    call contact_law_init(law, 'flores', 1.0_dp, 1.5_dp, 0.0_dp, 0.0_dp, 1.0_dp, err)
    call assert_true(err%failed(), 'Flores with e = 0 rejected')
    call err%clear()
    call contact_law_init(law, 'calibrated', 1.0_dp, 1.5_dp, 0.001_dp, 0.0_dp, 1.0_dp, err)
    call assert_true(err%failed(), 'calibrated with e < 0.01 rejected')
  end subroutine test_invalid
end module test_contact_law_suite

program test_contact_law
  use test_contact_law_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_contact_law')
end program test_contact_law
