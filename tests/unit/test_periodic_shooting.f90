!> Tests of the exact periodic solution (module periodic_shooting): a damped
!> oscillator against its closed-form steady state and Floquet multipliers
!> (Adams and BDF), the undamped oscillator on the unit circle, Mathieu's
!> parametric resonance (a multiplier leaves the unit circle), resonance of
!> a harmonic with the natural frequency (singular Newton matrix), a Duffing
!> oscillator (Newton on a nonlinear map, against a long direct
!> integration); and on Tennant's four-bar: the harmonic series agrees at low
!> speed, and the transient analysis's model run long with light damping
!> settles on the same periodic orbit.
module test_periodic_shooting_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use periodic_shooting
  use lsode_solver, only: lsode_t, mf_adams, mf_bdf_band_user
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use harmonic_solver, only: harmonic_settings_t, harmonic_report_t, harmonic_solve
  use mechanism_model, only: mechanism_model_t
  use element_effects, only: element_effects_t
  use assertions
  use periodic_problems, only: oscillator_t
  use transient_fixtures, only: fourbar_input
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('damped_oscillator_closed_form_adams_and_bdf', test_damped_oscillator)
    call run_test('undamped_multipliers_lie_on_the_unit_circle', test_undamped_multipliers)
    call run_test('mathieu_parametric_resonance_is_unstable', test_mathieu)
    call run_test('harmonic_on_the_natural_frequency_is_singular', test_resonance)
    call run_test('duffing_newton_converges_to_the_attracting_orbit', test_duffing)
    call run_test('four_bar_harmonic_series_agrees_at_low_speed', test_four_bar_low_speed)
    call run_test('four_bar_long_damped_transient_settles_on_the_orbit', test_four_bar_transient)
  end subroutine run_all

  !> x(t) = Re[f1/(k - m w^2 + i c w) e^(i w t)] + Re[-i f2/(k - 4 m w^2 + 2 i c w) e^(2 i w t)]
  real(dp) function osc_exact(o, t) result(x)
    type(oscillator_t), intent(in) :: o
    real(dp), intent(in) :: t
    complex(dp) :: z1, z2
    z1 = o%f1/cmplx(o%k - o%m*o%omega**2, o%c*o%omega, dp)
    z2 = cmplx(0.0_dp, -o%f2, dp)/cmplx(o%k - 4.0_dp*o%m*o%omega**2, 2.0_dp*o%c*o%omega, dp)
    x = real(z1*exp(cmplx(0.0_dp, o%omega*t, dp)) + z2*exp(cmplx(0.0_dp, 2.0_dp*o%omega*t, dp)), dp)
  end function osc_exact

  !> m = 1, c = 0.2, k = 4, w = 1.3: the periodic solution and the multipliers
  !> exp(lambda T), lambda = -c/2 +- i sqrt(k - c^2/4), to 1e-7 (rtol 1e-10),
  !> by Adams with the variational equations and by banded BDF.
  subroutine test_damped_oscillator()
    type(oscillator_t), target :: o
    type(shooting_settings_t) :: s
    type(shooting_report_t) :: rep
    type(error_t) :: err
    real(dp) :: y0(2), times(9), q(1, 9), qd(1, 9), t_period, mu
    integer :: j, pass
    o = oscillator_t(n=1, omega=1.3_dp, m=1.0_dp, c=0.2_dp, k=4.0_dp, f1=1.5_dp, f2=-0.7_dp)
    t_period = two_pi/o%omega
    do j = 1, 9
      times(j) = (j - 1)*t_period/8
    end do
    do pass = 1, 2
      s = shooting_settings_t(rtol=1.0e-10_dp, atol=1.0e-12_dp, bdf=pass == 2)
      y0 = 0.0_dp
      call shooting_solve(o, s, y0, rep, err)
      call assert_true(.not. err%failed() .and. rep%converged, 'converged')
      call assert_equal(rep%newton_iterations, 1, 'linear: one Newton step')
      call periodic_orbit(o, s, y0, times, q, qd, rep, err)
      do j = 1, 9
        call assert_close(q(1, j), osc_exact(o, times(j)), 1.0e-7_dp, 'x(t)')
      end do
      mu = exp(-0.5_dp*o%c*t_period)
      call assert_close(rep%max_multiplier, mu, 1.0e-7_dp, '|multiplier| = exp(-c T / 2m)')
      call assert_true(rep%stable, 'stable')
    end do
  end subroutine test_damped_oscillator

  !> Shooting for the periodic orbit of `osc` from the rest state.
  subroutine shoot_from_rest(osc, s, rep, err)
    type(oscillator_t), intent(in) :: osc
    type(shooting_settings_t), intent(in) :: s
    type(shooting_report_t), intent(out) :: rep
    type(error_t), intent(inout) :: err
    type(oscillator_t), target :: o
    real(dp) :: y0(2)
    o = osc
    y0 = 0.0_dp
    call shooting_solve(o, s, y0, rep, err)
  end subroutine shoot_from_rest

  !> Without damping both multipliers have modulus 1 (1e-7).
  subroutine test_undamped_multipliers()
    type(shooting_report_t) :: rep
    type(error_t) :: err
    call shoot_from_rest(oscillator_t(n=1, omega=1.3_dp, k=4.0_dp, f1=1.0_dp), &
                         shooting_settings_t(rtol=1.0e-11_dp, atol=1.0e-13_dp), rep, err)
    call assert_true(rep%converged, 'converged')
    call assert_all_close(sqrt(rep%mult_re**2 + rep%mult_im**2), [1.0_dp, 1.0_dp], 0.0_dp, 1.0e-7_dp, '|mu| = 1')
    call assert_close(atan2(abs(rep%mult_im(1)), rep%mult_re(1)), two_pi - modulo(2.0_dp*two_pi/1.3_dp, two_pi), &
                      1.0e-7_dp, '|arg mu| = w_n T modulo 2 pi')
  end subroutine test_undamped_multipliers

  !> x'' + (1 + 0.3 cos 2t) x = 0 sits in the principal instability tongue of
  !> Mathieu's equation (w = 2 w_n): growth exponent ~ eps w_n/4 per unit
  !> time, |mu| ~ exp(0.075 pi) = 1.27 over T = pi.  Flagged unstable.
  subroutine test_mathieu()
    type(shooting_report_t) :: rep
    type(error_t) :: err
    call shoot_from_rest(oscillator_t(n=1, omega=2.0_dp, k=1.0_dp, eps=0.3_dp, f1=0.1_dp), &
                         shooting_settings_t(singular_rcond=0.0_dp), rep, err)
    call assert_true(.not. rep%stable, 'unstable')
    call assert_true(rep%max_multiplier > 1.15_dp .and. rep%max_multiplier < 1.4_dp, '|mu| about 1.27')
  end subroutine test_mathieu

  !> Undamped, w_n = 3 w: a multiplier is exactly 1, Y(T) - I is singular,
  !> no isolated periodic solution: reported with near_resonance.
  subroutine test_resonance()
    type(shooting_settings_t) :: s
    type(shooting_report_t) :: rep
    type(error_t) :: err
    call shoot_from_rest(oscillator_t(n=1, omega=1.0_dp, k=9.0_dp, f1=1.0_dp), s, rep, err)
    call assert_true(err%failed() .and. rep%near_resonance, 'near resonance reported')
    call assert_true(rep%rcond_newton < s%singular_rcond, 'rcond below the limit')
  end subroutine test_resonance

  !> Duffing: x'' + 0.1 x' + x + 0.5 x^3 = 0.3 cos(1.4 t).  Newton needs
  !> several iterations; the orbit is the one a long direct integration from
  !> rest settles on (60 periods, decay exp(-0.05 t) ~ 1e-6): 1e-5.
  subroutine test_duffing()
    type(oscillator_t), target :: o
    type(shooting_settings_t) :: s
    type(shooting_report_t) :: rep
    type(flow_t), target :: flow
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y0(2), y(2)
    o = oscillator_t(n=1, omega=1.4_dp, c=0.1_dp, gamma=0.5_dp, f1=0.3_dp)
    s = shooting_settings_t(rtol=1.0e-10_dp, atol=1.0e-12_dp)
    y0 = 0.0_dp
    call shooting_solve(o, s, y0, rep, err)
    call assert_true(rep%converged .and. rep%stable, 'converged, stable')
    call assert_true(rep%newton_iterations >= 2, 'nonlinear: more than one Newton step')
    y = 0.0_dp
    call flow%setup(o, .false.)
    call ode%init(2, 0.0_dp, mf_adams, 1.0e-10_dp, [1.0e-12_dp], err, max_steps=100000)
    call ode%integrate_to(flow, y, 60.0_dp*two_pi/o%omega, err)
    call assert_all_close(y, y0, 0.0_dp, 1.0e-5_dp, 'orbit = limit of the direct integration')
  end subroutine test_duffing

  ! ------------------------------------------------------------------ the four-bar

  subroutine four_bar_mech(w, mech)
    real(dp), intent(in) :: w
    type(mechanism_t), intent(out) :: mech
    type(mechanism_input_t) :: inp
    type(error_t) :: err
    inp = fourbar_input(1, w, 0.0_dp)
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'mechanism')
  end subroutine four_bar_mech

  !> Tennant's linear four-bar at w with damping beta and its periodic
  !> solution by shooting from rest (y0: the state at t = 0).
  subroutine damped_four_bar_orbit(w, beta, s, mech, model, y0, rep, err)
    real(dp), intent(in) :: w, beta
    type(shooting_settings_t), intent(in) :: s
    type(mechanism_t), intent(out) :: mech
    type(steady_model_t), intent(inout), target :: model
    real(dp), intent(out) :: y0(:)
    type(shooting_report_t), intent(out) :: rep
    type(error_t), intent(inout) :: err
    type(link_sections_t) :: secs(3)
    call four_bar_mech(w, mech)
    call model%init_mechanism(mech, tennant_options_t(damping_beta=beta), secs, err)
    y0 = 0.0_dp
    call shooting_solve(model, s, y0, rep, err)
  end subroutine damped_four_bar_orbit

  !> Linear four-bar at 20 rad/s (0.014 of the lowest natural frequency),
  !> light damping beta = 2e-5 s.  The harmonic series (N = 16: the forcing
  !> of this crank-rocker needs ~16 harmonics, with N = 8 the truncation alone
  !> is 16%) agrees with the exact periodic solution to 1% of the largest
  !> deformation: its neglected terms -- time derivatives of the frozen K(t),
  !> M(t), C Q_dot and damping -- are of order w/w_1 = 1.4%; measured 0.3%.
  subroutine test_four_bar_low_speed()
    type(mechanism_t) :: mech
    type(steady_model_t), target :: model
    type(harmonic_settings_t) :: hs
    type(harmonic_report_t) :: hrep
    type(shooting_settings_t) :: s
    type(shooting_report_t) :: rep
    type(error_t) :: err
    real(dp) :: times(13), qh(10, 13), qs(10, 13), qd(10, 13), y0(20)
    integer :: j
    s = shooting_settings_t(rtol=1.0e-6_dp, atol=1.0e-10_dp, newton_tol=1.0e-4_dp, bdf=.true.)
    call damped_four_bar_orbit(20.0_dp, 2.0e-5_dp, s, mech, model, y0, rep, err)
    do j = 1, 13
      times(j) = (j - 1)*(two_pi/12)/20.0_dp
    end do
    hs%n_harmonics = 16
    call harmonic_solve(model, hs, times, qh, hrep, err)
    call assert_true(.not. err%failed() .and. rep%converged .and. rep%stable, 'periodic solution')
    call periodic_orbit(model, s, y0, times, qs, qd, rep, err)
    call assert_true(maxval(abs(qs(:, 13) - qs(:, 1))) < 1.0e-4_dp*maxval(abs(qs)), 'periodic')
    call assert_true(maxval(abs(qh - qs)) < 1.0e-2_dp*maxval(abs(qs)), 'harmonic series within 1%')
  end subroutine test_four_bar_low_speed

  !> The transient analysis's model (Kear's element, linear, rotary inertia
  !> and coupling on: the same equations as Tennant's linear slender element,
  !> test_tennant_element) with the same objective damping beta = 2e-5 s,
  !> integrated from the rigid-body state: the slowest mode decays by about
  !> exp(-27) per revolution at 20 rad/s, so after two revolutions the motion
  !> is the periodic orbit to the integration accuracy (rtol 1e-7 both, ~1e-6):
  !> tolerance 1e-4 of the largest deformation.
  subroutine test_four_bar_transient()
    type(mechanism_t) :: mech
    type(steady_model_t), target :: model
    type(mechanism_model_t), target :: tmodel
    type(shooting_settings_t) :: s
    type(shooting_report_t) :: rep
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), parameter :: w = 20.0_dp, beta = 2.0e-5_dp
    real(dp) :: times(9), qs(10, 9), qd(10, 9), y0(20), y(20), t_period, qt(10, 9)
    integer :: j, ml, i, k, to_steady(10)
    s = shooting_settings_t(rtol=1.0e-7_dp, atol=1.0e-11_dp, newton_tol=1.0e-5_dp, bdf=.true.)
    call damped_four_bar_orbit(w, beta, s, mech, model, y0, rep, err)
    call assert_true(rep%converged, 'periodic solution')
    t_period = two_pi/w
    do j = 1, 9
      times(j) = (j - 1)*t_period/8
    end do
    call periodic_orbit(model, s, y0, times, qs, qd, rep, err)

    call tmodel%init_mechanism(mech, element_effects_t(rotary_inertia=.true., coupling=.true.), 'exact', beta, err)
    call assert_true(.not. err%failed(), 'transient model')
    call assert_equal(tmodel%n, model%n, 'same unknowns')
    ! the transient table may number its unknowns differently (band reduction): match them by name
    to_steady = 0
    do i = 1, tmodel%n
      do k = 1, model%n
        if (tmodel%table%label_of(i) == model%table%label_of(k)) to_steady(i) = k
      end do
    end do
    call assert_true(all(to_steady > 0), 'every transient unknown has a steady counterpart')
    if (any(to_steady == 0)) return
    ml = min(2*tmodel%kd + 1, 2*tmodel%n - 1)
    call ode%init(2*tmodel%n, 0.0_dp, mf_bdf_band_user, 1.0e-7_dp, [1.0e-11_dp], err, ml=ml, mu=ml, &
                  max_steps=200000)
    y = 0.0_dp
    do j = 1, 9
      call ode%integrate_to(tmodel, y, 2.0_dp*t_period + times(j), err)
      call assert_true(.not. err%failed(), 'transient run')
      qt(to_steady, j) = y(1::2)
    end do
    call assert_all_close(reshape(qt, [90]), reshape(qs, [90]), 0.0_dp, 1.0e-4_dp*maxval(abs(qs)), &
                          'transient after two revolutions = periodic orbit')
  end subroutine test_four_bar_transient
end module test_periodic_shooting_suite

program test_periodic_shooting
  use assertions, only: finish_suite
  use test_periodic_shooting_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_periodic_shooting')
end program test_periodic_shooting
