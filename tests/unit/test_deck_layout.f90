!> The strict deck layer: the suggestion of the name meant (spelling), the
!> layout check of a deck (deck_layout through run_settings), the unknown
!> variable on a line after an array (deck_reader), and the unit labels of
!> the run's system (unit_system).
module test_deck_layout_suite
  use error_status, only: error_t
  use deck_reader, only: deck_t, unknown_target
  use run_settings, only: check_deck_groups
  use spelling, only: edit_distance, nearest_name
  use unit_system, only: set_unit_system, labelled
  use deck_runner, only: scratch_path, open_deck_text, close_deck_text
  use assertions
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: head = '! a header comment block|!   second line||&run analysis = ''steady'' /|'
  character(len=*), parameter :: mechanism = '&mechanism|  n_links = 1|/|'

contains

  subroutine run_all()
    call run_test('edit_distance_counts_each_edit_once', test_distance)
    call run_test('nearest_name_only_for_a_misspelling', test_nearest)
    call run_test('layout_accepts_comments_and_blanks_outside_groups', test_accepts)
    call run_test('layout_refuses_what_would_be_ignored', test_refuses)
    call run_test('unknown_target_after_an_array', test_unknown_target)
    call run_test('unit_labels_follow_the_system', test_labels)
  end subroutine run_all

  subroutine test_distance()
    call assert_equal(edit_distance('transients', 'transient'), 1, 'one letter too many')
    call assert_equal(edit_distance('lenght', 'length'), 1, 'a transposition of neighbours is one edit')
    call assert_equal(edit_distance('rtol', 'rtol'), 0, 'the same word')
    call assert_equal(edit_distance('', 'abc'), 3, 'from nothing')
    call assert_equal(edit_distance('abc', 'xyz'), 3, 'three substitutions')
    call assert_equal(edit_distance('rtol', 'atol_rate'), 6, 'a substitution and five insertions')
  end subroutine test_distance

  subroutine test_nearest()
    character(len=20), parameter :: groups(4) = [character(len=20) :: 'run', 'mechanism', 'transient', 'effects']
    call assert_equal(nearest_name('transients', groups), 'transient', 'a letter too many')
    call assert_equal(nearest_name('TRANSIENT_', groups), 'transient', 'case ignored')
    call assert_equal(nearest_name('mechansim', groups), 'mechanism', 'a transposition')
    call assert_equal(nearest_name('effekts', groups), 'effects', 'a substitution')
    call assert_equal(nearest_name('steady', groups), '', 'no group within two edits')
    call assert_equal(nearest_name('rn', groups), 'run', 'one insertion')
    call assert_equal(nearest_name('e', groups), '', 'too short for a suggestion: as many edits as letters')
    call assert_equal(nearest_name('run', groups), '', 'the name itself is no suggestion')
  end subroutine test_nearest

  subroutine test_accepts()
    type(error_t) :: err
    err = layout_error(head//mechanism//'   ! a comment after the groups|| |&steady output_step_deg = 2.0 / ! here too|'// &
                       '&tennant|  d_k = 1.0|/')
    call assert_true(.not. err%failed(), 'comments, blanks and a comment after the closing / are fine: '//err%text())
  end subroutine test_accepts

  subroutine test_refuses()
    type(error_t) :: err
    err = layout_error(head//mechanism//'&steadi|/')
    call assert_error(err, 2, 'line 8: group &steadi is not a group of flexmech: did you mean &steady?', &
                      'misspelled group')
    err = layout_error(head//mechanism//'&transient|/')
    call assert_error(err, 2, 'group &transient is not read by the ''steady'' analysis', 'another analysis''s group', &
                      fragment2='reads &run, &mechanism, &steady, &tennant')
    err = layout_error(head//mechanism//'&mechanism|/')
    call assert_error(err, 2, 'group &mechanism is given a second time (first on line 5)', 'a group twice')
    err = layout_error(head//mechanism//'n_links = 2')
    call assert_error(err, 2, 'line 8: "n_links = 2" is outside any group', 'text after the last group', &
                      fragment2='it follows the group &mechanism of line 5')
    err = layout_error('n_links = 2|'//head)
    call assert_error(err, 2, 'line 1: "n_links = 2" is outside any group', 'text before the first group', &
                      fragment2='it comes before the group &run of line')
    err = layout_error(head//'&mechanism n_links = 1 / omega = 2.0')
    call assert_error(err, 2, 'the text after the ''/'' that closes the group &mechanism is outside any group', 'after the /')
    err = layout_error(head//'&mechanism|  n_links = 1')
    call assert_error(err, 2, 'group starting on line 5 is not closed', 'an open group')
  end subroutine test_refuses

  subroutine test_unknown_target()
    character(len=16), parameter :: names(3) = [character(len=16) :: 'link_joint2', 'link_length', 'link_name']
    call assert_equal(unknown_target('  link_lenght = 2.0, 8.0', names), 'link_lenght', 'the misspelled name')
    call assert_equal(unknown_target('  link_joint2 = 2, 3, 3', names), '', 'a known name')
    call assert_equal(unknown_target('  link_length(2) = 2.0, link_lenght = 1.0', names), 'link_lenght', &
                      'the second assignment of a line')
    call assert_equal(unknown_target('  link_name = ''a = b'', ''c''', names), '', 'text in quotes is a value')
    call assert_equal(unknown_target('  2.0e-3, 3*1.0, t, f', names), '', 'values only')
    call assert_equal(unknown_target('&mechanism link_length = 1 / other = 2', names), '', 'after the closing /')
  end subroutine test_unknown_target

  subroutine test_labels()
    character(len=*), parameter :: text = 'M_e<k> = bending moment (lb in), N_e<k> = axial force (lb); '// &
      'sigma_b_e<k> (psi; half the difference), U (in), chord (in, + to the left); 1.5 psi at; psi1 (inch)'
    call set_unit_system('SI')
    call assert_equal(labelled(text), 'M_e<k> = bending moment (N m), N_e<k> = axial force (N); '// &
      'sigma_b_e<k> (Pa; half the difference), U (m), chord (m, + to the left); 1.5 Pa at; psi1 (inch)', 'SI')
    call set_unit_system('none')
    call assert_equal(labelled(text), 'M_e<k> = bending moment, N_e<k> = axial force; '// &
      'sigma_b_e<k> (half the difference), U, chord (+ to the left); 1.5 at; psi1 (inch)', 'none')
    call set_unit_system('in-lbf-s')
    call assert_equal(labelled(text), text, 'in-lbf-s: as written')
    call set_unit_system('furlongs')
    call assert_equal(labelled(text), text, 'an unknown system leaves the system as it was')
  end subroutine test_labels

  !> The layout error of a steady deck with `text` ('|' separates lines).
  function layout_error(text) result(err)
    character(len=*), intent(in) :: text
    type(error_t) :: err
    type(deck_t) :: deck
    character(len=:), allocatable :: stem
    stem = scratch_path('deck_layout')
    call open_deck_text(stem, text, deck, err)
    if (.not. err%failed()) call check_deck_groups(deck, 'steady', .false., err)
    call close_deck_text(stem, deck)
  end function layout_error
end module test_deck_layout_suite

program test_deck_layout
  use test_deck_layout_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_deck_layout')
end program test_deck_layout
