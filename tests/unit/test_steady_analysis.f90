!> Tests of the `steady` analysis (module steady_analysis): a deck in, the
!> table, summary and cost out; the harmonic series and the exact periodic
!> solution side by side; sections and the 14-DOF element from the deck;
!> the resonance diagnosis stops without rows; input errors have code 2.
module test_steady_analysis_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_runner, only: start_suite, run_text, has_line, count_rows, line_length
  use steady_analysis, only: run_steady
  use assertions
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: four_bar = '&mechanism|n_joints = 4|joint_name = ''A'', ''B'', ''C'', ''D''|'// &
    'joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin''|joint_x(1) = 0.0, joint_y(1) = 0.0|'// &
    'joint_x(4) = 10.0, joint_y(4) = 0.0|n_links = 3|link_name = ''crank'', ''coupler'', ''rocker''|'// &
    'link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|link_length = 5.0, 11.0, 10.5|'

contains

  subroutine run_all()
    call start_suite('test_steady_analysis', run_steady)
    call run_test('linear_harmonic_deck_gives_a_revolution_of_rows', test_linear_deck)
    call run_test('nonlinear_deck_reports_outer_iterations', test_nonlinear_deck)
    call run_test('both_methods_side_by_side_at_low_speed', test_both)
    call run_test('shear_angle_and_sections_from_the_deck', test_shear_sections)
    call run_test('resonance_stops_with_the_diagnosis_and_no_rows', test_resonance)
    call run_test('parametric_resonance_of_the_undamped_four_bar_stops', test_parametric)
    call run_test('bad_input_is_an_input_error', test_bad_input)
  end subroutine run_all

  !> Column line (last '#' line before the rows) split into names.
  integer function n_columns(lines) result(n)
    character(len=*), intent(in) :: lines(:)
    integer :: i, last
    last = 0
    do i = 1, size(lines)
      if (lines(i)(1:1) /= '#') exit
      last = i
    end do
    n = 0
    do i = 2, len_trim(lines(last))
      if (lines(last)(i:i) /= ' ' .and. lines(last)(i - 1:i - 1) == ' ') n = n + 1
    end do
  end function n_columns

  !> 10-degree rows over a revolution, both ends (37); columns crank_deg, t,
  !> B and C (U, W), three link ends (u, w), three stresses = 15.
  subroutine test_linear_deck()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 150.0|/|&steady output_step_deg = 10.0 /', &
                  err, lines)
    call assert_true(.not. err%failed(), 'run: '//err%text())
    call assert_equal(count_rows(lines), 37, 'rows')
    call assert_equal(n_columns(lines), 15, 'columns')
    call assert_true(has_line(lines, '# cost: factorizations = '), 'factorizations in the footer')
    call assert_true(has_line(lines, '# cost: harmonics_used = 8 of N = 8 (16 samples per revolution)'), 'harmonics')
    call assert_true(has_line(lines, 'all tracing constants zero: the linear analysis'), 'linear noted')
    call assert_true(has_line(lines, '# cost: nonlinear_integrand_evaluations = 0'), 'nothing nonlinear computed')
    call assert_true(has_line(lines, 'natural frequencies of the frozen structure'), 'frequency scan')
  end subroutine test_linear_deck

  subroutine test_nonlinear_deck()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 150.0|/|&steady output_step_deg = 30.0 /|'// &
                  '&tennant d_k = 1, d_b = 1, d_g = 1 /', err, lines)
    call assert_true(.not. err%failed(), 'run: '//err%text())
    call assert_true(has_line(lines, '# summary: outer iterations (K_n updates after the linear solution) = 4'), &
                     'four outer iterations at the default 1e-5')
    call assert_true(has_line(lines, '# summary: outer iteration 4 = max relative change of Q = '), &
                     'change of the last iteration')
    call assert_true(has_line(lines, '# summary: largest strain (harmonic series)'), 'strain')
  end subroutine test_nonlinear_deck

  !> 20 rad/s, N = 16, light damping: the footer compares the two (< 1%).
  subroutine test_both()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    integer :: i, k
    real(dp) :: diff
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 20.0|/|&steady method = ''both'', '// &
                  'n_harmonics = 16, output_step_deg = 30.0, damping_beta = 2.0e-5, rtol = 1.0e-6, atol = 1.0e-10, '// &
                  'newton_tol = 1.0e-4 /', err, lines)
    call assert_true(.not. err%failed(), 'run: '//err%text())
    call assert_equal(n_columns(lines), 28, 'harmonic and exact columns')
    call assert_true(has_line(lines, 'steady state = stable'), 'stable')
    diff = -1.0_dp
    do i = 1, size(lines)
      k = index(lines(i), 'max |Q_h - Q_exact| / max |Q_exact| = ')
      if (k > 0) read(lines(i)(k + 39:), *) diff
    end do
    call assert_true(diff >= 0.0_dp .and. diff < 0.01_dp, 'harmonic series within 1% at 20 rad/s')
  end subroutine test_both

  !> 14-DOF element with a tapered crank (two sections): runs, and the header
  !> names the default G = E1/2.66.
  subroutine test_shear_sections()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 100.0|/|&steady output_step_deg = 30.0 /|'// &
                  '&tennant shear = T, n_sections(1) = 2, section_end(1,1:2) = 0.4, 1.0, '// &
                  'section_b(1,1:2) = 0.3, 0.25, section_h(1,1:2) = 1.2, 1.0 /', err, lines)
    call assert_true(.not. err%failed(), 'run: '//err%text())
    call assert_true(has_line(lines, '14 DOFs with shear angle alpha; shear modulus G = 0.408647E+07 (default'), &
                     'default G')
    call assert_true(has_line(lines, 'elements of 14 DOFs'), '14-DOF table')
    call assert_equal(count_rows(lines), 13, 'rows')
  end subroutine test_shear_sections

  !> 176 rad/s: the eighth harmonic meets the lowest frozen natural
  !> frequency; the run stops (code /= 2) with the diagnosis, no rows.
  subroutine test_resonance()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 176.0|/|&steady output_step_deg = 2.0 /', &
                  err, lines)
    call assert_true(err%failed() .and. err%code /= 2, 'stopped with a diagnosis')
    call assert_true(index(err%text(), 'near resonance at crank speed 176.000 rad/s') > 0, 'message')
    call assert_true(index(err%text(), 'harmonic n = 8') > 0, 'names the harmonic')
    call assert_equal(count_rows(lines), 0, 'no rows')
    call assert_true(has_line(lines, 'warning: harmonic 8 of the crank speed'), 'header warning')
    call assert_true(has_line(lines, '# summary: worst conditioning of K - n^2 w^2 M'), 'rcond in the summary')
  end subroutine test_resonance

  !> Undamped, 295 rad/s: a pair of Floquet multipliers of modulus 1.0018
  !> (stable at 293 and 297 rad/s, doc/steady_state.md §6): the run stops
  !> with the multipliers in the summary, no rows.
  subroutine test_parametric()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 295.0|/|&steady method = ''shooting'', '// &
                  'integrator = ''adams'', rtol = 1.0e-8, atol = 1.0e-12, output_step_deg = 30.0 /', err, lines)
    call assert_true(err%failed() .and. err%code /= 2, 'stopped with a diagnosis')
    call assert_true(index(err%text(), 'UNSTABLE') > 0 .and. index(err%text(), 'modulus 1.00') > 0, &
                     'names the multiplier: '//err%text())
    call assert_true(has_line(lines, '# summary: Floquet multipliers, largest moduli =  1.001'), 'multipliers listed')
    call assert_equal(count_rows(lines), 0, 'no rows')
  end subroutine test_parametric

  subroutine test_bad_input()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 0.0|/', err, lines)
    call assert_true(err%failed() .and. err%code == 2, 'omega = 0')
    call assert_true(index(err%text(), 'omega') > 0, 'names omega')
    call err%clear()
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 100.0|/|&tennant d_k = 2.0 /', err, lines)
    call assert_error(err, 2, 'd_k', 'd_k = 2 is an input error naming d_k')
    call err%clear()
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 100.0|/|&steady method = ''fourier'' /', &
                  err, lines)
    call assert_true(err%failed() .and. err%code == 2, 'unknown method')
    call err%clear()
    call run_text('&run analysis = ''steady'' /|'//four_bar//'omega = 100.0|/|&tennant n_sections(2) = 2, '// &
                  'section_end(2,1:2) = 0.5, 0.9, section_b(2,1:2) = 0.25, 0.25, section_h(2,1:2) = 1.0, 1.0 /', &
                  err, lines)
    call assert_error(err, 2, 'section_end(2,2)', 'sections must reach the link end; names the section')
  end subroutine test_bad_input
end module test_steady_analysis_suite

program test_steady_analysis
  use assertions, only: finish_suite
  use test_steady_analysis_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_steady_analysis')
end program test_steady_analysis
