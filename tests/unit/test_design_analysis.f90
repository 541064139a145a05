!> Tests of the `design` analysis (modules design_analysis, design_problem,
!> design_sequence): the closed-form optimum of a rotating bar with a
!> frequency constraint, and every bad &design value an input error (code 2).
module test_design_analysis_suite
  use kinds, only: dp
  use error_status, only: error_t
  use design_analysis, only: run_design
  use deck_runner, only: scratch_path, run_deck, has_line, summary_value, line_length
  use assertions
  implicit none
  private
  public :: run_all

  character(len=:), allocatable :: scratch
  !> A crank of 10 in, 0.25 x 1 in, free at its end, 1 rad/s (inputs/design_bar_frequency.nml).
  character(len=*), parameter :: bar = '&run analysis = ''design'' /|&mechanism n_joints = 2, '// &
    'joint_type = ''clamp'', ''free'', joint_x(1) = 0, joint_y(1) = 0, n_links = 1, link_joint1 = 1, '// &
    'link_joint2 = 2, link_length = 10.0, link_b = 0.25, link_h = 1.0, link_n_elements = 4, driver_link = 1, '// &
    'omega = 1.0 /|&steady damping_beta = 1.0e-4 /|&tennant d_k = 0, d_b = 0, d_g = 0 /|'

contains

  subroutine run_all()
    scratch = scratch_path('test_design_analysis')
    call run_test('minimum_mass_bar_reaches_the_closed_form_section', test_closed_form)
    call run_test('bad_design_values_are_input_errors', test_bad_values)
  end subroutine run_all

  subroutine run_text(text, err, lines)
    character(len=*), intent(in) :: text
    type(error_t), intent(inout) :: err
    character(len=line_length), allocatable, intent(out) :: lines(:)
    call run_deck(run_design, scratch, text, err, lines)
  end subroutine run_text

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
    call run_text(bar//'&design variables = ''link_h(1)'', lower = 0.01, upper = 10.0, frequency_factor = 100, '// &
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

  !> The design writes its final deck and two analyses beside its output.
  subroutine remove_side_files()
    character(len=16), parameter :: suffix(4) = [character(len=16) :: '.design.nml', '.initial.nml', &
                                                 '.initial.out', '.final.out']
    integer :: i, u, ios
    do i = 1, 4
      open(newunit=u, file=scratch//trim(suffix(i)), status='old', iostat=ios)
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
             'evaluator = ''transient'' /', 'evaluator')
    call bad('&steady /', 'group &design')
  contains
    subroutine bad(design_group, fragment)
      character(len=*), intent(in) :: design_group, fragment
      type(error_t) :: err
      character(len=line_length), allocatable :: lines(:)
      call run_text(bar//design_group, err, lines)
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
