!> Shared fixtures of the design suites (test_design_analysis,
!> test_design_transient, test_design_sensitivity, test_design_problem): the
!> rotating bar deck, a design deck's text loaded into its problem, and the
!> reason of a failed design evaluation for assertion messages.
module design_fixtures
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use linkage, only: mechanism_t
  use design_problem, only: design_problem_t, design_eval_t
  use design_sequence, only: design_sequence_t
  use design_analysis, only: load_design
  use deck_runner, only: open_deck_text, close_deck_text
  implicit none
  private
  public :: bar_deck, load_design_text, eval_reason

  !> A crank of 10 in, 0.25 x 1 in, free at its end, 1 rad/s
  !> (inputs/design_bar_frequency.nml); the &design group is the suite's.
  character(len=*), parameter :: bar_deck = '&run analysis = ''design'' /|&mechanism n_joints = 2, '// &
    'joint_type = ''clamp'', ''free'', joint_x(1) = 0, joint_y(1) = 0, n_links = 1, link_joint1 = 1, '// &
    'link_joint2 = 2, link_length = 10.0, link_b = 0.25, link_h = 1.0, link_n_elements = 4, driver_link = 1, '// &
    'omega = 1.0 /|&steady damping_beta = 1.0e-4 /|&tennant d_k = 0, d_b = 0, d_g = 0 /|'

contains

  !> The deck `text` ('|' between lines) written to stem.nml and read by
  !> load_design into `prob` (not yet set up) and its start `x0`; the file is
  !> removed.  The mechanism and design-loop settings are dropped.
  subroutine load_design_text(stem, text, prob, x0, err)
    character(len=*), intent(in) :: stem, text
    type(design_problem_t), intent(out) :: prob
    real(dp), allocatable, intent(out) :: x0(:)
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(mechanism_t) :: mech
    type(design_sequence_t) :: seq
    call open_deck_text(stem, text, deck, err)
    if (.not. err%failed()) call load_design(deck, mech, prob, x0, seq, err)
    call close_deck_text(stem, deck)
  end subroutine load_design_text

  !> Why the evaluation failed ('' when it gave no reason).
  function eval_reason(ev) result(text)
    type(design_eval_t), intent(in) :: ev
    character(len=:), allocatable :: text
    text = ''
    if (allocated(ev%reason)) text = ev%reason
  end function eval_reason
end module design_fixtures
