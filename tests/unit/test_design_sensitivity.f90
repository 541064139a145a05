!> Tests of the design derivatives from the periodic orbit's variational
!> equations (periodic_shooting's orbit_sensitivity, design_problem's
!> derivatives_at): against the closed-form steady state of a forced
!> oscillator, against central differences of converged shooting solutions
!> of a Duffing oscillator with a parametric stiffness (the tangent term of
!> S' = f_y S + f_p), and on the counterweight four-bar of example 3 against
!> central differences of whole converged analyses with tight tolerances.
module test_design_sensitivity_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use periodic_problems, only: oscillator_t
  use periodic_shooting, only: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit, &
                               orbit_sensitivity
  use design_problem, only: design_problem_t, design_eval_t
  use design_fixtures, only: load_design_text, eval_reason
  use deck_runner, only: scratch_path
  use assertions
  implicit none
  private
  public :: run_all

  character(len=:), allocatable :: scratch
  !> example 3 (inputs/design_fourbar_counterweights.nml) with the
  !> counterweights away from the pivots and the coupler's height a
  !> variable too; &steady and &design completed by the tests
  character(len=*), parameter :: example3 = '&run analysis = ''design'' /|&mechanism n_joints = 4, '// &
    'joint_name = ''A'', ''B'', ''C'', ''D'', joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin'', '// &
    'joint_x(1) = 0.0, joint_y(1) = 0.0, joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3, '// &
    'link_name = ''crank'', ''coupler'', ''rocker'', link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, '// &
    'link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, link_h = 3*1.0, link_n_elements = 3*1, '// &
    'link_cw_mass(1) = 0.001, link_cw_mass(3) = 0.001, link_cw_x(1) = -2.0, link_cw_y(1) = 0.3, '// &
    'link_cw_x(3) = -4.0, link_cw_y(3) = -0.2, driver_link = 1, omega = 75.0 /|'// &
    '&tennant d_k = 0, d_b = 0, d_g = 0, shear = F /|&design variables = ''link_cw_x(1)'', '// &
    '''link_cw_y(3)'', ''link_h(2)'', lower = -6.0, -3.0, 0.2, upper = 3.0, 3.0, 4.0, scale = 3*1.0, '// &
    'objective = ''shaking'', stress_allowable = 20000.0, '// &
    'samples = 36, '

contains

  subroutine run_all()
    scratch = scratch_path('test_design_sensitivity')
    call run_test('orbit_sensitivity_matches_closed_form_oscillator', test_linear_oscillator)
    call run_test('orbit_sensitivity_matches_differences_of_duffing_orbits', test_duffing)
    call run_test('design_derivatives_match_central_differences_of_analyses', test_design_derivatives)
    call run_test('nonlinear_design_derivatives_match_central_differences_of_analyses', test_nonlinear_derivatives)
    call run_test('parabola_peak_derivatives_match_central_differences_of_analyses', test_parabola_derivatives)
    call run_test('transmission_angle_constraint_matches_closed_form', test_transmission)
    call run_test('ground_bearing_forces_add_up_to_the_shaking_force', test_bearing_sum)
    call run_test('bearing_force_derivatives_match_central_differences_of_analyses', test_bearing_derivatives)
    call run_test('derivatives_switch_is_checked', test_switch)
  end subroutine run_all

  !> m x'' + c x' + k x = f1 cos(w t): x = Re(X e^(i w t)),
  !> X = f1 / (k - m w^2 + i c w).  Parameters k, c and f1 (stiffness,
  !> damping, load: f_p enters through K, C and F); dX/dk = -X / D,
  !> dX/dc = -i w X / D, dX/df1 = 1 / D, D = k - m w^2 + i c w.  DLSODE at
  !> rtol 1e-11: the orbit and its sensitivities to 1e-8 of their size (the
  !> central difference of the right-hand side is exact for a system linear
  !> in the parameter; 1e-8 leaves two orders for the integration).  Also:
  !> the start y0 moved by (I - Phi_y)^-1 dPhi/dp is checked at t = 0 (a
  !> missing correction would leave dq(0) = 0).
  subroutine test_linear_oscillator()
    type(oscillator_t), target :: sys
    type(oscillator_t), target :: plus(3), minus(3)
    character(len=*), parameter :: names(3) = [character(len=2) :: 'k', 'c', 'f1']
    type(shooting_settings_t) :: ss
    type(shooting_report_t) :: rep
    type(error_t) :: err
    real(dp), parameter :: w = 1.3_dp, hk = 1.0e-3_dp
    real(dp) :: times(9), q(1, 9), dq(1, 9, 3), expected(9), y0(2)
    complex(dp) :: x, d, dx(3)
    integer :: j, k
    sys = oscillator_t(m=1.0_dp, c=0.2_dp, k=4.0_dp, f1=1.5_dp)
    sys%n = 1
    sys%omega = w
    d = cmplx(sys%k - sys%m*w**2, sys%c*w, dp)
    x = sys%f1/d
    dx = [-x/d, -cmplx(0.0_dp, w, dp)*x/d, 1.0_dp/d]
    do j = 1, 3
      plus(j) = shifted(sys, names(j), hk)
      minus(j) = shifted(sys, names(j), -hk)
    end do
    ss%rtol = 1.0e-11_dp
    ss%atol = 1.0e-14_dp
    y0 = [real(x), -w*aimag(x)]
    do k = 1, 9
      times(k) = (k - 1)*(2.0_dp*pi/w)/8.0_dp
    end do
    call orbit_sensitivity(sys, plus, minus, [2*hk, 2*hk, 2*hk], ss, y0, times, q, dq, rep, err)
    call assert_true(.not. err%failed(), 'orbit_sensitivity runs: '//err%text())
    if (err%failed()) return
    call assert_all_close(q(1, :), real(x*exp(cmplx(0.0_dp, w*times, dp))), 0.0_dp, 1.0e-8_dp*abs(x), 'orbit')
    do j = 1, 3
      expected = real(dx(j)*exp(cmplx(0.0_dp, w*times, dp)))
      call assert_all_close(dq(1, :, j), expected, 0.0_dp, 1.0e-8_dp*abs(dx(j)), 'dq/dp of parameter '//char(48 + j))
    end do
    call assert_true(abs(real(dx(1))) > 0.1_dp*abs(dx(1)), 'the start itself moves (dq(0) /= 0)')
  end subroutine test_linear_oscillator

  !> x'' + 0.3 x' + 2 (1 + 0.4 cos w t) x + 1.5 x^3 = 1.2 cos w t at w = 1.1:
  !> nonlinear and time-varying, no closed form.  dq/dk and dq/dgamma from
  !> the variational equations against central differences of periodic
  !> orbits converged by shooting (Newton to 1e-12, DLSODE rtol 1e-12, step
  !> 1e-4: truncation ~1e-8, integration noise ~1e-12/1e-4 = 1e-8 of the
  !> sensitivity's size); tolerance 1e-6 of the largest sensitivity.  The
  !> cubic's tangent 3 gamma x^2 in S' is more than 0.2 k on the orbit
  !> (checked), so a missing tangent fails.
  subroutine test_duffing()
    type(oscillator_t), target :: sys, plus(2), minus(2)
    character(len=*), parameter :: names(2) = [character(len=5) :: 'k', 'gamma']
    type(shooting_settings_t) :: ss
    type(shooting_report_t) :: rep
    type(error_t) :: err
    real(dp), parameter :: w = 1.1_dp, h = 1.0e-4_dp
    real(dp) :: times(13), q(1, 13), dq(1, 13, 2), qp(1, 13), qm(1, 13), qd(1, 13), fd(13), y0(2), yp(2), ym(2)
    integer :: j, k
    sys = oscillator_t(m=1.0_dp, c=0.3_dp, k=2.0_dp, eps=0.4_dp, gamma=1.5_dp, f1=1.2_dp)
    sys%n = 1
    sys%omega = w
    ss%rtol = 1.0e-12_dp
    ss%atol = 1.0e-15_dp
    ss%newton_tol = 1.0e-12_dp
    ss%max_newton = 30
    y0 = 0.0_dp
    call shooting_solve(sys, ss, y0, rep, err)
    call assert_true(.not. err%failed() .and. rep%converged .and. rep%stable, 'the Duffing orbit: '//err%text())
    if (err%failed() .or. .not. rep%converged) return
    do k = 1, 13
      times(k) = (k - 1)*(2.0_dp*pi/w)/12.0_dp
    end do
    do j = 1, 2
      plus(j) = shifted(sys, names(j), h)
      minus(j) = shifted(sys, names(j), -h)
    end do
    call orbit_sensitivity(sys, plus, minus, [2*h, 2*h], ss, y0, times, q, dq, rep, err)
    call assert_true(.not. err%failed(), 'orbit_sensitivity runs: '//err%text())
    if (err%failed()) return
    do j = 1, 2
      yp = y0
      ym = y0
      call shooting_solve(plus(j), ss, yp, rep, err)
      if (.not. err%failed()) call periodic_orbit(plus(j), ss, yp, times, qp, qd, rep, err)
      if (.not. err%failed()) call shooting_solve(minus(j), ss, ym, rep, err)
      if (.not. err%failed()) call periodic_orbit(minus(j), ss, ym, times, qm, qd, rep, err)
      call assert_true(.not. err%failed(), 'the perturbed orbits: '//err%text())
      if (err%failed()) return
      fd = (qp(1, :) - qm(1, :))/(2*h)
      call assert_all_close(dq(1, :, j), fd, 0.0_dp, 1.0e-6_dp*maxval(abs(fd)), 'dq/dp against differences, '// &
                            'parameter '//char(48 + j))
    end do
    ! the cubic's tangent 3 gamma x^2 is a good part of the stiffness on the
    ! orbit: leaving it out of S' would fail the comparison above
    call assert_true(maxval(3*sys%gamma*q(1, :)**2) > 0.2_dp*sys%k, 'the orbit is nonlinear: '// &
                     'tangent 3 gamma x^2 above 0.2 k')
  end subroutine test_duffing

  !> Example 3's problem at a design away from the start, three variables of
  !> three kinds: the crank counterweight's x (it acts on the shaking force
  !> through the rigid motion only: a clamped crank's elastic equations do
  !> not see it), the rocker counterweight's y (through the rocker's
  !> elastic equations: f_p and the start's correction) and the coupler's
  !> height (logarithmic; mass, stiffness and stress recovery).  The
  !> derivatives of the stress constraints and of the shaking-force
  !> residuals from one sensitivity solve against central differences of
  !> whole analyses at x +- 1e-3 (analyses at rtol 1e-9, Newton to 1e-8:
  !> their noise, about 1e-9 of a result, is 1e-6 of the derivative; the
  !> truncation h^2 f''' / 6 about 1e-7).  Tolerance: 1e-4 of each
  !> derivative vector's largest entry, and 1e-5 absolute for the
  !> constraints (logarithms: the crank counterweight leaves the stresses
  !> alone, its variational derivative is 0 to round-off - checked - and
  !> the differences' noise there measured 1.2e-6).  Counted as one analysis.
  subroutine test_design_derivatives()
    type(design_problem_t) :: prob
    real(dp), allocatable :: x0(:), dg(:, :), dr(:, :)
    type(design_eval_t) :: ev
    logical :: ok
    integer :: before
    call load(example3//'/|&steady damping_beta = 1.0e-5, integrator = ''bdf'', rtol = 1.0e-9, '// &
              'atol = 1.0e-13 /', prob, x0)
    prob%shooting%newton_tol = 1.0e-8_dp
    prob%shooting%max_newton = 20
    call prob%setup('example 3', x0)
    call assert_true(prob%variational_applies(), 'the default derivatives are the variational ones')
    call prob%evaluate(x0, ev)
    call assert_true(ev%ok, 'example 3 at x0 analyses: '//eval_reason(ev))
    if (.not. ev%ok) return
    before = prob%n_analyses
    call prob%derivatives_at(x0, dg, dr, ok)
    call assert_true(ok, 'derivatives_at succeeds')
    if (.not. ok) return
    call assert_equal(prob%n_analyses - before, 1, 'a sensitivity solve counts one analysis')
    call assert_equal(prob%n_sensitivity, 1, 'one sensitivity solve')
    call assert_true(maxval(abs(dg(1, :))) <= 1.0e-12_dp, 'the crank counterweight leaves the stresses alone')
    call assert_true(maxval(abs(dr(1, :))) > 0.1_dp*maxval(abs(dr(3, :))), 'but moves the shaking force')
    call check_against_differences(prob, x0, dg, dr, 1.0e-3_dp)
  end subroutine test_design_derivatives

  !> The same check with the nonlinear analysis in the loop: example 1
  !> (Tennant's four-bar at 150 rad/s, inputs/design_fourbar_mass_150_nonlinear.nml)
  !> with the material, stretching and curvature terms on, at the heights
  !> 1.15, 0.53, 0.54 in the nonlinear design reaches in three iterations
  !> (below the Ramberg-Osgood peak everywhere), peak stresses as KS
  !> aggregates with rho = 10, and two deflection constraints (the
  !> coupler's middle from its chord, the rocker at 0.7 of its length from
  !> its rigid position, KS aggregates too).  The variational derivatives (the orbit's
  !> sensitivities with the nonlinear tangent) against central differences
  !> of whole analyses at x +- 1e-4 (rtol 1e-9, Newton to 1e-10).  The step
  !> is the point: measured at steps 3e-3, 1e-3, 3e-4 and 1e-4, the
  !> difference minus the variational derivative falls as h^2 to within 1 %
  !> (dg1/dx2: 2.64e-2, 3.02e-3, 2.73e-4, 2.88e-5), the truncation
  !> h^2 g'''/6 of the central difference with g''' about 2e4 along
  !> ln h2 (doc/design.md).  At h = 1e-3 that truncation is 1.5e-3 of the
  !> largest entry - the mismatch once taken for a missing term; at 1e-4 it
  !> is 1.5e-5, and the analyses' noise (about 1e-9 of a result, over 2e-4)
  !> 5e-6.  Tolerance 1e-4 of each derivative vector's largest entry, as the
  !> linear case's; and the coupler height's mismatch at 1e-3 is checked
  !> to be 50 to 200 times the one at 1e-4 (h^2: 100).  A missing tangent
  !> fails by far more (the Duffing test above: 20 %).
  subroutine test_nonlinear_derivatives()
    type(design_problem_t) :: prob
    real(dp), allocatable :: x0(:), dg(:, :), dr(:, :), gp(:), gm(:), rp(:), rm(:)
    type(design_eval_t) :: ev
    real(dp) :: xs(3), h, e3, e4
    logical :: ok
    integer :: j
    call load('&run analysis = ''design'' /|&mechanism n_joints = 4, joint_name = ''A'', ''B'', ''C'', ''D'', '// &
              'joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin'', joint_x(1) = 0.0, joint_y(1) = 0.0, '// &
              'joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3, link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, '// &
              'link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, link_h = 1.15, 0.53, 0.54, '// &
              'link_n_elements = 3*1, driver_link = 1, omega = 150.0 /|'// &
              '&steady damping_beta = 1.0e-5, integrator = ''bdf'', rtol = 1.0e-9, atol = 1.0e-14 /|'// &
              '&tennant d_k = 1, d_b = 1, d_g = 1, shear = F /|'// &
              '&design variables = ''link_h(1)'', ''link_h(2)'', ''link_h(3)'', lower = 3*0.2, upper = 3*4.0, '// &
              'stress_allowable = 20000.0, frequency_factor = 5.0, samples = 24, peak_stress = ''ks'', ks_rho = 10, '// &
              'deflection_link = 2, 3, deflection_at = 0.5, 0.7, deflection_from = ''chord'', ''rigid'', '// &
              'deflection_limit = 2*0.01 /', prob, x0)
    prob%shooting%newton_tol = 1.0e-10_dp
    prob%shooting%max_newton = 30
    call prob%setup('nonlinear example 1', x0)
    call prob%evaluate(x0, ev)
    call assert_true(ev%ok .and. .not. ev%past_peak, 'the nonlinear design analyses below the peak: '// &
                     eval_reason(ev))
    if (.not. ev%ok) return
    call prob%derivatives_at(x0, dg, dr, ok)
    call assert_true(ok, 'derivatives_at succeeds')
    if (.not. ok) return
    call assert_equal(size(dg, 2), 6, 'three stresses, a frequency, two deflections')
    call assert_true(minval(maxval(abs(dg(:, 5:6)), dim=1)) > 0.1_dp, 'the heights move the deflections: '// &
                     str(dg(2, 5))//', '//str(dg(3, 6)))
    do j = 1, 3
      h = 1.0e-4_dp
      xs = x0
      xs(j) = x0(j) + h
      call values(prob, xs, gp, rp)
      xs(j) = x0(j) - h
      call values(prob, xs, gm, rm)
      call assert_all_close(dg(j, :), (gp - gm)/(2*h), 0.0_dp, 1.0e-4_dp*maxval(abs((gp - gm)/(2*h))) + 1.0e-5_dp, &
                            'dg/dx of variable '//char(48 + j))
      if (j == 2) e4 = maxval(abs((gp - gm)/(2*h) - dg(j, :)))
    end do
    ! the coupler's height at ten times the step: the mismatch is the
    ! difference's truncation, h^2 g'''/6, a hundred times the one at 1e-4
    h = 1.0e-3_dp
    xs = x0
    xs(2) = x0(2) + h
    call values(prob, xs, gp, rp)
    xs(2) = x0(2) - h
    call values(prob, xs, gm, rm)
    e3 = maxval(abs((gp - gm)/(2*h) - dg(2, :)))
    call assert_true(e3 > 50*e4 .and. e3 < 200*e4, 'the mismatch grows as h^2: '//str(e3)//' at 1e-3, '// &
                     str(e4)//' at 1e-4')
  end subroutine test_nonlinear_derivatives

  !> The peaks read between the samples (peak_interpolation = 'parabola',
  !> the largest sample's parabola in ln) on the nonlinear example 1 at the
  !> heights its deflection-constrained design reached with 72 plain samples
  !> (1.0494, 0.4984, 0.4058 in; the crank's stress peaks between samples
  !> there; no frequency constraint: the frozen frequencies at 720 samples
  !> would be most of the test's cost).  (1) Against a fine sampling of the same analysis (720
  !> samples, 0.5 deg apart, no interpolation): the 72 samples read by
  !> their parabolas give the stress and deflection peaks no more than
  !> 0.2 % below the fine ones and at most 0.5 % above (the ln-constraints:
  !> -2e-3 .. 5e-3; measured: the rocker's 3.3e-3 above, a peak less
  !> rounded than a parabola in ln, the largest difference); the bare 72
  !> samples miss the crank's by more than 3 %, checked.  (2) The design derivatives of these constraints
  !> (variational, the chain rule through each sample's sensitivity) against
  !> central differences of whole analyses at x +- 1e-4, tolerance as the
  !> KS test above: 1e-4 of each derivative vector's largest entry plus 1e-5.
  subroutine test_parabola_derivatives()
    character(len=*), parameter :: deck = '&run analysis = ''design'' /|&mechanism n_joints = 4, '// &
      'joint_name = ''A'', ''B'', ''C'', ''D'', joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin'', '// &
      'joint_x(1) = 0.0, joint_y(1) = 0.0, joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3, '// &
      'link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, '// &
      'link_h = 1.0494, 0.4984, 0.4058, link_n_elements = 3*1, driver_link = 1, omega = 150.0 /|'// &
      '&steady damping_beta = 1.0e-5, integrator = ''bdf'', rtol = 1.0e-9, atol = 1.0e-14 /|'// &
      '&tennant d_k = 1, d_b = 1, d_g = 1, shear = F /|'// &
      '&design variables = ''link_h(1)'', ''link_h(2)'', ''link_h(3)'', lower = 3*0.2, upper = 3*4.0, '// &
      'stress_allowable = 20000.0, deflection_link = 2, deflection_at = 0.5, '// &
      'deflection_limit = 0.05, '
    type(design_problem_t) :: prob, fine
    real(dp), allocatable :: x0(:), dg(:, :), dr(:, :), gp(:), gm(:), rp(:), rm(:), g(:), g_fine(:), g_bare(:)
    type(design_eval_t) :: ev
    real(dp) :: xs(3), h
    logical :: ok
    integer :: j
    call load(deck//'samples = 720 /', fine, x0)
    fine%shooting%newton_tol = 1.0e-10_dp
    fine%shooting%max_newton = 30
    call fine%setup('the fine sampling', x0)
    call fine%evaluate(x0, ev)
    call assert_true(ev%ok .and. .not. ev%past_peak, 'the design analyses at 720 samples: '//eval_reason(ev))
    if (.not. ev%ok) return
    g_fine = fine%constraints_of(ev)
    call load(deck//'peak_interpolation = ''parabola'' /', prob, x0)
    prob%shooting%newton_tol = 1.0e-10_dp
    prob%shooting%max_newton = 30
    call prob%setup('the parabola', x0)
    call prob%evaluate(x0, ev)
    call assert_true(ev%ok .and. .not. ev%past_peak, 'the design analyses at 72 samples: '//eval_reason(ev))
    if (.not. ev%ok) return
    g = prob%constraints_of(ev)
    prob%peak_interpolation = 'none'
    g_bare = prob%constraints_of(ev)
    prob%peak_interpolation = 'parabola'
    call assert_equal(size(g), 4, 'three stresses and a deflection')
    call assert_true(g_fine(1) - g_bare(1) > 0.03_dp, 'the bare samples miss the crank''s peak: '// &
                     str(g_bare(1))//' against '//str(g_fine(1))//' at 720 samples')
    call assert_true(all(g - g_fine > -2.0e-3_dp) .and. &
                     all(g - g_fine < 5.0e-3_dp), &
                     'the parabolas read the fine sampling''s peaks to -0.2 % .. +0.5 %: '// &
                     str(g(1) - g_fine(1))//', '//str(g(2) - g_fine(2))//', '//str(g(3) - g_fine(3))//', '// &
                     str(g(4) - g_fine(4)))
    call prob%derivatives_at(x0, dg, dr, ok)
    call assert_true(ok, 'derivatives_at succeeds')
    if (.not. ok) return
    do j = 1, 3
      h = 1.0e-4_dp
      xs = x0
      xs(j) = x0(j) + h
      call values(prob, xs, gp, rp)
      xs(j) = x0(j) - h
      call values(prob, xs, gm, rm)
      call assert_all_close(dg(j, :), (gp - gm)/(2*h), 0.0_dp, 1.0e-4_dp*maxval(abs((gp - gm)/(2*h))) + 1.0e-5_dp, &
                            'dg/dx of variable '//char(48 + j))
    end do
  end subroutine test_parabola_derivatives

  !> The movability constraint on Tennant's four-bar (crank a = 5, coupler
  !> b = 11, rocker c = 10.5, ground d = 10 in): the transmission angle mu
  !> at the coupler-rocker pin C has cos mu = (b^2 + c^2 - BD^2) / (2 b c),
  !> BD the distance from the crank pin to the rocker's pivot, least
  !> (d - a) at crank angle 0, the first sample: peak |cos mu| =
  !> 206.25 / 231 (mu = 26.8 deg).  g = ln(peak |cos mu| / cos 30 deg) and
  !> its derivatives in x1 = ln(b / 11) and x2 = d / 10 in closed form:
  !> b dg/db = 2 b^2 / N - 1 and 10 dg/dd = -20 (d - a) / N, N = 206.25;
  !> the heights leave it alone.  From the variational path (one
  !> sensitivity solve: the perturbed linkages solve their own kinematics)
  !> to 1e-7, and x2's against a central difference of whole analyses.  The
  !> constraint is rigid-body kinematics: a loose rtol and 8 samples (crank
  !> angle 0 among them) keep the test cheap without touching its value.
  subroutine test_transmission()
    type(design_problem_t) :: prob
    real(dp), allocatable :: x0(:), dg(:, :), dr(:, :), gp(:), gm(:), rp(:), rm(:)
    real(dp) :: xs(3), h, g_exact
    type(design_eval_t) :: ev
    logical :: ok
    integer :: it
    call load('&run analysis = ''design'' /|&mechanism n_joints = 4, joint_name = ''A'', ''B'', ''C'', ''D'', '// &
              'joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin'', joint_x(1) = 0.0, joint_y(1) = 0.0, '// &
              'joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3, link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, '// &
              'link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, link_h = 3*1.0, '// &
              'link_n_elements = 3*1, driver_link = 1, omega = 75.0 /|'// &
              '&steady damping_beta = 1.0e-5, integrator = ''bdf'', rtol = 1.0e-6, atol = 1.0e-10 /|'// &
              '&tennant d_k = 0, d_b = 0, d_g = 0, shear = F /|'// &
              '&design variables = ''link_length(2)'', ''joint_x(4)'', ''link_h(2)'', lower = 9.0, 8.0, 0.2, '// &
              'upper = 13.0, 12.0, 4.0, transmission_joint = 3, transmission_min_deg = 30.0, samples = 8 /', prob, x0)
    call prob%setup('movability', x0)
    call assert_equal(prob%n_analysis_constraints(), 1, 'the movability constraint alone')
    call prob%evaluate(x0, ev)
    call assert_true(ev%ok, 'the four-bar analyses: '//eval_reason(ev))
    if (.not. ev%ok) return
    g_exact = log(206.25_dp/231.0_dp/cos(30.0_dp*pi/180.0_dp))
    gp = prob%constraints_of(ev)
    call assert_close(gp(1), g_exact, 1.0e-9_dp, 'g at the start, closed form')
    call assert_equal(maxloc(ev%sample_transmission, dim=1), 1, 'the least angle at crank angle 0')
    call prob%derivatives_at(x0, dg, dr, ok)
    call assert_true(ok, 'derivatives_at succeeds')
    if (.not. ok) return
    call assert_close(dg(1, 1), 2*121.0_dp/206.25_dp - 1.0_dp, 1.0e-7_dp, 'dg/d ln b, closed form')
    call assert_close(dg(2, 1), -20*5.0_dp/206.25_dp, 1.0e-7_dp, 'dg/d(d/10), closed form')
    call assert_close(dg(3, 1), 0.0_dp, 1.0e-9_dp, 'the coupler height leaves it alone')
    h = 1.0e-3_dp
    it = 2
    xs = x0
    xs(it) = x0(it) + h
    call values(prob, xs, gp, rp)
    xs(it) = x0(it) - h
    call values(prob, xs, gm, rm)
    call assert_close(dg(it, 1), (gp(1) - gm(1))/(2*h), 1.0e-5_dp, 'dg/d(d/10), differences of analyses')
  end subroutine test_transmission

  !> The ground pivots' bearing forces (module joint_bearing: element
  !> nodal forces) add up, at every sample, to the shaking force (module
  !> shaking_force: the rate of the total linear momentum), two computations
  !> that share only the periodic samples: example 3 with both counterweights
  !> away from the pivots, at 30 rad/s and 72 samples (the bearing
  !> objective's residuals are F_A, F_D per sample / sqrt(N), the shaking
  !> objective's F / sqrt(N)).  The elastic parts reach the accelerations
  !> differently (the element's consistent mass times the interpolated q_dd
  !> against the interpolated second derivative of the rotating first
  !> moment), so they agree as far as the samples resolve the elastic
  !> response: measured 1.7e-5 of the largest force here, 4.4e-3 at 36
  !> samples; at 75 rad/s 12 % at 36 samples (the elastic response has
  !> harmonics up to about the 36th), 3.2e-5 at 288 (the interpolation's
  !> error, falling fast with the samples).  Tolerance 1e-4 of the largest
  !> force.  Also the peak's minimax residuals: |F_A|, |F_D| at each sample.
  subroutine test_bearing_sum()
    type(design_problem_t) :: shaking, bearing, peak
    real(dp), allocatable :: x0(:), g(:), rs(:), rb(:), rp(:), sum_b(:)
    type(design_eval_t) :: ev
    integer :: k, n
    character(len=*), parameter :: tail = '/|&steady damping_beta = 1.0e-5, integrator = ''bdf'', rtol = 1.0e-8, '// &
                                          'atol = 1.0e-12 /'
    call load(slow(example3)//tail, shaking, x0)
    call load(slow(replace_objective('''bearing'', bearing_joints = 1, 4, '))//tail, bearing, x0)
    call load(slow(replace_objective('''bearing_peak'', bearing_joints = 1, 4, '))//tail, peak, x0)
    call shaking%setup('shaking', x0)
    call bearing%setup('bearing', x0)
    call peak%setup('bearing peak', x0)
    call values(shaking, x0, g, rs)
    call values(bearing, x0, g, rb)
    call assert_equal(size(rb), 2*size(rs), 'two joints, two components, each sample')
    if (size(rb) /= 2*size(rs)) return
    n = size(rs)/2
    allocate(sum_b(2*n))
    do k = 1, n
      sum_b(2*k - 1:2*k) = rb(4*k - 3:4*k - 2) + rb(4*k - 1:4*k)
    end do
    call assert_all_close(sum_b, rs, 0.0_dp, 1.0e-4_dp*maxval(abs(rs)), 'F_A + F_D = shaking force')
    call assert_true(maxval(abs(rb(1::4))) > 0.1_dp*maxval(abs(rs)), 'the crank pivot carries a force')
    call values(peak, x0, g, rp)
    call peak%evaluate(x0, ev)
    call assert_all_close(rp(1::2), sqrt(real(n, dp))*hypot(rb(1::4), rb(2::4)), 0.0_dp, &
                          1.0e-10_dp*maxval(rp), '|F_A| in the minimax residuals')
    call assert_close(ev%peak_bearing, maxval(rp), 1.0e-12_dp, 'the peak is the largest residual')
  end subroutine test_bearing_sum

  !> The peak bearing force's design derivatives (minimax residuals |F_A|,
  !> |F_D| at each sample) with the nonlinear analysis in the loop: example
  !> 3 with the material, stretching and curvature terms on, variational
  !> derivatives against central differences of whole analyses at x +- 1e-3
  !> (rtol 1e-9, Newton to 1e-8; the linear case's step and tolerance above:
  !> 1e-4 of each derivative vector's largest entry).  The three variables
  !> reach the forces three ways: the crank counterweight through the rigid
  !> motion (its mass on the crank pivot), the rocker's through the rocker's
  !> elastic equations, the coupler's height through mass and stiffness.
  subroutine test_bearing_derivatives()
    type(design_problem_t) :: prob
    real(dp), allocatable :: x0(:), dg(:, :), dr(:, :), g(:), r(:)
    type(design_eval_t) :: ev
    logical :: ok
    integer :: j
    call load(replace_objective('''bearing_peak'', bearing_joints = 1, 4, ')//'/|&steady damping_beta = 1.0e-5, '// &
              'integrator = ''bdf'', rtol = 1.0e-9, atol = 1.0e-13 /', prob, x0, nonlinear=.true.)
    prob%shooting%newton_tol = 1.0e-8_dp
    prob%shooting%max_newton = 20
    call prob%setup('example 3, bearing', x0)
    call prob%evaluate(x0, ev)
    call assert_true(ev%ok, 'the nonlinear example 3 analyses: '//eval_reason(ev))
    if (.not. ev%ok) return
    call prob%derivatives_at(x0, dg, dr, ok)
    call assert_true(ok, 'derivatives_at succeeds')
    if (.not. ok) return
    call assert_equal(size(dr, 2), 2*36, 'two joints at 36 samples')
    call values(prob, x0, g, r)
    do j = 1, 3
      call assert_true(maxval(abs(dr(j, :))) > 1.0e-3_dp*maxval(abs(r)), 'variable '//char(48 + j)// &
                       ' moves the bearing forces')
    end do
    call check_against_differences(prob, x0, dg, dr, 1.0e-3_dp)
  end subroutine test_bearing_derivatives

  !> dg/dx and dr/dx of each variable against central differences of whole
  !> analyses at x0 +- h: within 1e-4 of each derivative vector's largest
  !> entry (plus 1e-5 absolute for the constraints, logarithms).
  subroutine check_against_differences(prob, x0, dg, dr, h)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x0(:), dg(:, :), dr(:, :), h
    real(dp), allocatable :: gp(:), gm(:), rp(:), rm(:)
    real(dp) :: xs(size(x0))
    integer :: j
    do j = 1, size(x0)
      xs = x0
      xs(j) = x0(j) + h
      call values(prob, xs, gp, rp)
      xs(j) = x0(j) - h
      call values(prob, xs, gm, rm)
      call assert_all_close(dg(j, :), (gp - gm)/(2*h), 0.0_dp, 1.0e-4_dp*maxval(abs((gp - gm)/(2*h))) + 1.0e-5_dp, &
                            'dg/dx of variable '//char(48 + j))
      call assert_all_close(dr(j, :), (rp - rm)/(2*h), 0.0_dp, 1.0e-4_dp*maxval(abs((rp - rm)/(2*h))), &
                            'dr/dx of variable '//char(48 + j))
    end do
  end subroutine check_against_differences

  !> Example 3's text at 30 rad/s with 72 samples.
  function slow(text) result(moved)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: moved
    integer :: at
    moved = text
    at = index(moved, 'omega = 75.0')
    moved = moved(1:at - 1)//'omega = 30.0'//moved(at + 12:)
    at = index(moved, 'samples = 36')
    moved = moved(1:at - 1)//'samples = 72'//moved(at + 12:)
  end function slow

  !> Example 3's text with another objective.
  function replace_objective(objective) result(text)
    character(len=*), intent(in) :: objective
    character(len=:), allocatable :: text
    integer :: at
    at = index(example3, '''shaking'', ')
    text = example3(1:at - 1)//objective//example3(at + len('''shaking'', '):)
  end function replace_objective

  subroutine values(prob, x, g, r)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:)
    real(dp), allocatable, intent(out) :: g(:), r(:)
    type(design_eval_t) :: ev
    call prob%evaluate(x, ev)
    call assert_true(ev%ok, 'a neighbour analyses: '//eval_reason(ev))
    g = prob%constraints_of(ev)
    r = prob%residuals_of(ev)
  end subroutine values

  !> derivatives = 'variational' needs the shooting evaluator; an unknown
  !> choice is an input error; 'differences' is taken.
  subroutine test_switch()
    type(design_problem_t) :: prob
    real(dp), allocatable :: x0(:)
    type(error_t) :: err
    call load(example3//'derivatives = ''differences'' /|&steady integrator = ''bdf'' /', prob, x0)
    call assert_true(.not. prob%variational_applies(), '''differences'' switches the sensitivities off')
    call try_load(example3//'evaluator = ''harmonic'', derivatives = ''variational'' /|&steady rtol = 1e-7 /', err)
    call assert_error(err, 2, 'derivatives', 'variational with the harmonic evaluator', 'shooting')
    call err%clear()
    call try_load(example3//'derivatives = ''adjoint'' /|&steady rtol = 1e-7 /', err)
    call assert_error(err, 2, 'derivatives', 'an unknown choice')
  end subroutine test_switch

  !> A copy of the oscillator with its parameter `name` moved by dh (the
  !> central differences' neighbours).
  function shifted(sys, name, dh) result(moved)
    type(oscillator_t), intent(in) :: sys
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: dh
    type(oscillator_t) :: moved
    moved = sys
    select case (trim(name))
    case ('k')
      moved%k = sys%k + dh
    case ('c')
      moved%c = sys%c + dh
    case ('f1')
      moved%f1 = sys%f1 + dh
    case ('gamma')
      moved%gamma = sys%gamma + dh
    case default
      call assert_true(.false., 'no oscillator parameter '//name)
    end select
  end function shifted

  !> Load the deck text into a design problem (not yet set up).
  subroutine load(text, prob, x0, nonlinear)
    character(len=*), intent(in) :: text
    type(design_problem_t), intent(out) :: prob
    real(dp), allocatable, intent(out) :: x0(:)
    !> the material, stretching and curvature terms on (d_k = d_b = d_g = 1)
    logical, intent(in), optional :: nonlinear
    type(error_t) :: err
    integer :: at
    character(len=:), allocatable :: deck
    deck = text
    if (present(nonlinear)) then
      at = index(deck, 'd_k = 0, d_b = 0, d_g = 0')
      if (nonlinear .and. at > 0) deck = deck(1:at - 1)//'d_k = 1, d_b = 1, d_g = 1'//deck(at + 25:)
    end if
    call load_design_text(scratch, deck, prob, x0, err)
    call assert_true(.not. err%failed(), 'the deck loads: '//err%text())
  end subroutine load

  subroutine try_load(text, err)
    character(len=*), intent(in) :: text
    type(error_t), intent(inout) :: err
    type(design_problem_t) :: prob
    real(dp), allocatable :: x0(:)
    call load_design_text(scratch, text, prob, x0, err)
  end subroutine try_load
end module test_design_sensitivity_suite

program test_design_sensitivity
  use test_design_sensitivity_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_design_sensitivity')
end program test_design_sensitivity
