!> Tests of the `design` analysis (modules design_analysis, design_problem,
!> design_sequence): the closed-form optimum of a rotating bar with a
!> frequency constraint, and every bad &design value an input error (code 2).
module test_design_analysis_suite
  use kinds, only: dp
  use error_status, only: error_t
  use design_analysis, only: run_design
  use design_fixtures, only: bar_deck
  use deck_runner, only: start_suite, suite_stem, run_text, has_line, summary_value, line_length
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call start_suite('test_design_analysis', run_design)
    call run_test('minimum_mass_bar_reaches_the_closed_form_section', test_closed_form)
    call run_test('bad_design_values_are_input_errors', test_bad_values)
    call run_test('counterweights_reach_berkof_lowen_balance_at_low_speed', test_counterweights)
    call run_test('minimax_shaking_reaches_berkof_lowen_balance_at_low_speed', test_counterweights_minimax)
    call run_test('several_speeds_the_fastest_sets_the_frequency_design', test_speeds_frequency)
    call run_test('structured_and_gauss_newton_reach_the_same_counterweights', test_structured_same_answer)
    call run_test('several_speeds_summed_shaking_reaches_berkof_lowen', test_speeds_shaking)
  end subroutine run_all

  !> Tennant's four-bar at `omega` rad/s with counterweights of 0.001 on
  !> crank and rocker, `tennant_extra` added to &tennant, and the start of a
  !> &design group over the four counterweight positions (to be completed).
  function fourbar_cw(omega, tennant_extra) result(text)
    character(len=*), intent(in) :: omega, tennant_extra
    character(len=:), allocatable :: text
    text = '&run analysis = ''design'' /|&mechanism n_joints = 4, joint_type = ''clamp'', ''pin'', '// &
      '''pin'', ''ground_pin'', joint_x(1) = 0, joint_y(1) = 0, joint_x(4) = 10, joint_y(4) = 0, n_links = 3, '// &
      'link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, '// &
      'link_h = 3*1.0, link_cw_mass(1) = 0.001, link_cw_mass(3) = 0.001, driver_link = 1, omega = '//omega//' /|'// &
      '&steady damping_beta = 1.0e-5 /|&tennant d_k = 0, d_b = 0, d_g = 0'//tennant_extra//' /|&design variables = '// &
      '''link_cw_x(1)'', ''link_cw_y(1)'', ''link_cw_x(3)'', ''link_cw_y(3)'', lower = -6, -3, -10, -3, '// &
      'upper = 3, 3, 3, 3, scale = 4*1.0, '
  end function fourbar_cw

  !> Berkof-Lowen full force balance of that four-bar: the counterweights on
  !> the link lines at -(m2 + m3) a2 / (2 m_cw) and -(m4 + m3) a4 / (2 m_cw),
  !> within 1e-4 in (see the tests for the elastic shift).
  subroutine assert_berkof_lowen(lines)
    character(len=*), intent(in) :: lines(:)
    real(dp), parameter :: rho_b = 2.536e-4_dp*0.25_dp, m_cw = 0.001_dp
    real(dp), parameter :: m2 = rho_b*5.0_dp, m3 = rho_b*11.0_dp, m4 = rho_b*10.5_dp
    call assert_close(summary_value(lines, '# summary: final link_cw_x(1) ='), -(m2 + m3)*5.0_dp/(2.0_dp*m_cw), &
                      1.0e-4_dp, 'crank counterweight on the Berkof-Lowen position')
    call assert_close(summary_value(lines, '# summary: final link_cw_x(3) ='), -(m4 + m3)*10.5_dp/(2.0_dp*m_cw), &
                      1.0e-4_dp, 'rocker counterweight on the Berkof-Lowen position')
    call assert_close(summary_value(lines, '# summary: final link_cw_y(1) ='), 0.0_dp, 1.0e-4_dp, 'on the crank line')
    call assert_close(summary_value(lines, '# summary: final link_cw_y(3) ='), 0.0_dp, 1.0e-4_dp, 'on the rocker line')
  end subroutine assert_berkof_lowen

  !> A converged counterweight design (the line `reported` in its output if
  !> given) on the Berkof-Lowen balance, its `measure` ('rms' or 'peak')
  !> shaking force below `factor` times the initial one; side files removed.
  subroutine check_balanced(err, lines, measure, factor, reported)
    type(error_t), intent(in) :: err
    character(len=*), intent(in) :: lines(:), measure
    real(dp), intent(in) :: factor
    character(len=*), intent(in), optional :: reported
    call assert_true(.not. err%failed(), 'converges: '//err%text())
    if (present(reported)) call assert_true(has_line(lines, reported), 'reported: '//reported)
    call assert_berkof_lowen(lines)
    call assert_true(summary_value(lines, '# summary: final '//measure//' shaking force =') < &
                     factor*summary_value(lines, '# summary: initial '//measure//' shaking force ='), &
                     measure//' shaking force cancelled')
    call remove_side_files()
  end subroutine check_balanced

  !> Lowest frozen frequency (1.8751/L)^2 h sqrt(E/(12 rho)) >= 100 rad/s:
  !> h* = 0.0475882 in.  The design aims feas_tol/2 = 5e-4 inside the
  !> constraint; with the 4-element mesh (1e-5) and the centrifugal
  !> stiffening at 1 rad/s (1e-4): 1.5e-3 relative.  The mass falls to h*/h0.
  subroutine test_closed_form()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    real(dp), parameter :: e1 = 10.87e6_dp, rho = 2.536e-4_dp, beta_l = 1.875104068711961_dp
    real(dp) :: h_star, h
    h_star = 100.0_dp/((beta_l/10.0_dp)**2*sqrt(e1/(12.0_dp*rho)))
    call run_text(bar_deck//'&design variables = ''link_h(1)'', lower = 0.01, upper = 10.0, frequency_factor = 100, '// &
                  'evaluator = ''harmonic'' /', err, lines)
    call assert_true(.not. err%failed(), 'converges: '//err%text())
    call assert_true(has_line(lines, '# summary: status = converged'), 'status converged')
    h = summary_value(lines, '# summary: final link_h(1) =')
    call assert_close(h, h_star, 1.5e-3_dp*h_star, 'final section vs the closed form')
    call assert_true(h >= h_star*(1.0_dp - 1.0e-4_dp), 'the final design is feasible (h >= h*)')
    call assert_true(summary_value(lines, '# cost: mechanism analyses NF (every distinct design, derivatives '// &
                     'included) =') < 40.0_dp, 'fewer than 40 analyses')
    call remove_side_files()
  end subroutine test_closed_form

  !> Example 3 in the rigid limit: Tennant's four-bar at 1 rad/s with
  !> counterweights of 0.001 on crank and rocker, their positions designed
  !> for the least mean square shaking force.  Berkof-Lowen full force
  !> balance puts them on the link lines at -(m2 + m3) a2 / (2 m_cw) =
  !> -2.536 in and -(m4 + m3) a4 / (2 m_cw) = -7.156275 in, where the rigid
  !> shaking force vanishes.  The elastic motion shifts the optimum by an
  !> amount growing as omega^2 (2.6e-5 in at 1 rad/s, 6.4e-4 in at 5 rad/s):
  !> tolerance 1e-4 in.  The shaking force falls by more than 1e-5.
  subroutine test_counterweights()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text(fourbar_cw('1.0', '')//'objective = ''shaking'', evaluator = ''harmonic'', samples = 36, '// &
      'move_limit = 1.0, xtol = 1e-7 /', err, lines)
    call check_balanced(err, lines, 'rms', 1.0e-5_dp)
  end subroutine test_counterweights

  !> The same four-bar and variables with the minimax objective (the peak
  !> shaking force over the revolution, posed as min t subject to
  !> |F(theta_k)| <= t): its answer is again Berkof-Lowen's full force
  !> balance, where every sample's force vanishes in the rigid limit.  The
  !> elastic share at 1 rad/s shifts it by about 1.4e-5 in (doc/design.md):
  !> tolerance 1e-4 in; the peak falls below 1e-4 of its start (it reaches
  !> 4e-6 of it: the elastic share).  The structured Hessian option does not
  !> apply to a minimax and must not disturb it.
  subroutine test_counterweights_minimax()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text(fourbar_cw('1.0', '')//'objective = ''shaking_peak'', evaluator = ''harmonic'', samples = 36, '// &
      'move_limit = 1.0, xtol = 1e-5, hessian = ''structured'' /', err, lines)
    call check_balanced(err, lines, 'peak', 1.0e-4_dp, '# design: least peak shaking force')
  end subroutine test_counterweights_minimax

  !> Several operating speeds: the rotating bar's frequency constraint
  !> (lowest frequency >= 100 x crank speed) at 0.4, 0.8 and 0.6 rad/s is
  !> set by the fastest, so h = 0.8 h*(1 rad/s) (the frequency is
  !> proportional to h): tolerance 1.5e-3 as in the single-speed test (the
  !> centrifugal stiffening differs by 1e-4 between the speeds).  Each design
  !> costs three analyses, and the constraint at 0.8 rad/s is the active one.
  subroutine test_speeds_frequency()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    real(dp), parameter :: e1 = 10.87e6_dp, rho = 2.536e-4_dp, beta_l = 1.875104068711961_dp
    real(dp) :: h_star, h, nf
    h_star = 0.8_dp*100.0_dp/((beta_l/10.0_dp)**2*sqrt(e1/(12.0_dp*rho)))
    call run_text(bar_deck//'&design variables = ''link_h(1)'', lower = 0.01, upper = 10.0, frequency_factor = 100, '// &
                  'evaluator = ''harmonic'', speeds = 0.4, 0.8, 0.6 /', err, lines)
    call assert_true(.not. err%failed(), 'converges: '//err%text())
    h = summary_value(lines, '# summary: final link_h(1) =')
    call assert_close(h, h_star, 1.5e-3_dp*h_star, 'final section vs the closed form at the fastest speed')
    call assert_true(h >= h_star*(1.0_dp - 1.0e-4_dp), 'feasible at the fastest speed')
    call assert_close(summary_value(lines, '# summary: final lowest frozen frequency at 0.800000 rad/s ='), &
                      80.0_dp, 1.5e-3_dp*80.0_dp, 'the constraint at 0.8 rad/s is active (100 x 0.8)')
    nf = summary_value(lines, '# cost: mechanism analyses NF (every distinct design, derivatives included) =')
    call assert_true(abs(nf/3.0_dp - nint(nf/3.0_dp)) < 1.0e-12_dp, 'three analyses per design')
    call remove_side_files()
  end subroutine test_speeds_frequency

  !> The counterweight design with the mean square shaking force summed over
  !> two speeds, 0.5 and 1 rad/s: the rigid force balance cancels it at every
  !> speed, so the answer is Berkof-Lowen's again (the elastic offsets are
  !> 6.5e-6 and 2.6e-5 in at these speeds: tolerance 1e-4 in).  The same
  !> answer at objective_speed = 2.
  subroutine test_speeds_shaking()
    character(len=:), allocatable :: deck
    deck = fourbar_cw('1.0', '')//'objective = ''shaking'', evaluator = ''harmonic'', samples = 36, '// &
      'move_limit = 1.0, xtol = 1e-6, hessian = ''structured'', speeds = 0.5, 1.0'
    call check(deck//' /')
    call check(deck//', objective_speed = 2 /')
  contains
    subroutine check(text)
      character(len=*), intent(in) :: text
      type(error_t) :: err
      character(len=line_length), allocatable :: lines(:)
      call run_text(text, err, lines)
      call check_balanced(err, lines, 'rms', 1.0e-4_dp, '# operating speeds (rad/s): 0.500000 1.00000')
    end subroutine check
  end subroutine test_speeds_shaking

  !> The two curvature options of the residual objectives are two routes to
  !> one answer: the counterweights of Tennant's four-bar at 75 rad/s for the
  !> least mean square shaking force (harmonic evaluator: its elastic shaking
  !> is small, rms 0.753 lb, and the answer near Berkof-Lowen's) with the
  !> Gauss-Newton matrix alone and with the structured secant term.  Both stop
  !> when F changes by about xtol/10 = 1e-4 relative: the rms forces agree to
  !> 5e-5 (half of that) and the positions to 2e-3 in (the objective is flat
  !> along the rocker counterweight's radius).
  subroutine test_structured_same_answer()
    character(len=:), allocatable :: deck
    character(len=16), parameter :: names(4) = [character(len=16) :: 'link_cw_x(1) =', 'link_cw_y(1) =', &
                                                'link_cw_x(3) =', 'link_cw_y(3) =']
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    real(dp) :: x(4, 2), rms(2)
    integer :: run, i
    deck = fourbar_cw('75.0', ', shear = F')//'objective = ''shaking'', evaluator = ''harmonic'', samples = 72, '// &
      'stress_allowable = 20000.0, move_limit = 1.0, hessian = '
    do run = 1, 2
      call run_text(deck//trim(merge('''gauss''     ', '''structured''', run == 1))//' /', err, lines)
      call assert_true(.not. err%failed(), 'converges: '//err%text())
      do i = 1, 4
        x(i, run) = summary_value(lines, '# summary: final '//trim(names(i)))
      end do
      rms(run) = summary_value(lines, '# summary: final rms shaking force =')
      call assert_true(rms(run) < 0.1_dp*summary_value(lines, '# summary: initial rms shaking force ='), &
                       'far below the unbalanced linkage''s')
      call remove_side_files()
    end do
    do i = 1, 4
      call assert_close(x(i, 2), x(i, 1), 2.0e-3_dp, 'the same '//trim(names(i))//' by both routes')
    end do
    call assert_close(rms(2), rms(1), 5.0e-5_dp*rms(1), 'the same rms shaking force')
  end subroutine test_structured_same_answer

  !> The design writes its final deck and two analyses beside its output.
  subroutine remove_side_files()
    character(len=16), parameter :: suffix(4) = [character(len=16) :: '.design.nml', '.initial.nml', &
                                                 '.initial.out', '.final.out']
    integer :: i, u, ios
    do i = 1, 4
      open(newunit=u, file=suite_stem()//trim(suffix(i)), status='old', iostat=ios)
      if (ios == 0) close(u, status='delete')
      call assert_true(ios == 0, 'side file '//trim(suffix(i))//' was written')
    end do
  end subroutine remove_side_files

  subroutine test_bad_values()
    call bad('&design variables = ''link_q(1)'', lower = 0.1, upper = 2, frequency_factor = 10 /', 'variables(1)')
    call bad('&design variables = ''link_h(2)'', lower = 0.1, upper = 2, frequency_factor = 10 /', 'variables(1)')
    call bad('&design variables = ''link_h(1)'', lower = 2, upper = 0.1, frequency_factor = 10 /', 'upper(1)')
    call bad('&design variables = ''link_h(1)'', lower = 2, upper = 3, frequency_factor = 10 /', 'within its bounds')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2 /', 'stress_allowable')
    call bad('&design variables = ''link_h(1)'', upper = 2, frequency_factor = 10 /', 'lower(1)')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = NaN /', 'frequency_factor')
    call bad('&design variables = ''link_h(1)'', lower = 0, upper = 2, frequency_factor = 10 /', 'must stay > 0')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = 10, '// &
             'evaluator = ''fourier'' /', 'evaluator')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = 10, '// &
             'hessian = ''newton'' /', 'hessian')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = 10, '// &
             'speeds = 1.0, -2.0 /', 'speeds(2)')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = 10, '// &
             'speeds = 1.0, NaN /', 'speeds(2)')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = 10, '// &
             'speeds(1) = 1.0, speeds(3) = 2.0 /', 'speeds')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, frequency_factor = 10, '// &
             'speeds = 1.0, 2.0, objective_speed = 3 /', 'objective_speed')
    call bad('&steady /', 'group &design')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, objective = ''path'', path_link = 1, '// &
             'path_r = 1, path_x = 1, 2, path_y = 1, path_dgamma_deg = 0, 90 /', 'path_y(2)')
    call bad('&design variables = ''link_h(1)'', lower = 0.1, upper = 2, objective = ''path'', path_link = 2, '// &
             'path_r = 1, path_x = 1, path_y = 1, path_dgamma_deg = 0 /', 'path_link')
    call bad('&design variables = ''path_r'', lower = 0.1, upper = 2, frequency_factor = 10 /', 'path objectives')
    call bad('&design variables = ''link_cw_x(1)'', lower = -1, upper = 2, scale = 1, objective = ''shaking'' /', &
             'uniform links', 'n_sections(1) = 1, section_end(1, 1) = 1.0, section_b(1, 1) = 0.25, '// &
             'section_h(1, 1) = 1.0, ')
    call bad('&design variables = ''link_cw_x(1)'', lower = -1, upper = 2, scale = 1, objective = ''shaking'' /', &
             'link_cw_mass(1)', 'link_cw_mass(1) = -1.0, ')
  contains
    subroutine bad(design_group, fragment, tennant_extra)
      character(len=*), intent(in) :: design_group, fragment
      character(len=*), intent(in), optional :: tennant_extra   !< put into &tennant, or into &mechanism for link_*
      type(error_t) :: err
      character(len=line_length), allocatable :: lines(:)
      character(len=:), allocatable :: text
      integer :: at
      text = bar_deck
      if (present(tennant_extra)) then
        if (tennant_extra(1:5) == 'link_') then
          at = index(text, 'omega = 1.0')
        else
          at = index(text, 'd_k = 0')
        end if
        text = text(1:at - 1)//tennant_extra//text(at:)
      end if
      call run_text(text//design_group, err, lines)
      call assert_true(err%failed() .and. err%code == 2, fragment//': an input error')
      call assert_true(index(err%text(), fragment) > 0, 'message names '//fragment//': '//err%text())
      call assert_true(size(lines) == 0, fragment//': no output')
    end subroutine bad
  end subroutine test_bad_values
end module test_design_analysis_suite

program test_design_analysis
  use test_design_analysis_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_design_analysis')
end program test_design_analysis
