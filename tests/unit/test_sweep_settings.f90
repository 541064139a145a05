!> Tests of sweep_settings (the &sweep group): a list, a linear and a log
!> range (values known in closed form), and the input errors (exit code 2).
module test_sweep_settings_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use sweep_settings, only: sweep_settings_t, read_sweep_settings
  use assertions
  use deck_runner, only: start_suite, suite_stem, open_deck_text, close_deck_text
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call start_suite('test_sweep_settings')
    call run_test('list_of_values', test_list)
    call run_test('linear_range', test_linear)
    call run_test('log_range', test_log)
    call run_test('bad_groups_are_input_errors', test_errors)
  end subroutine run_all

  subroutine read_text(text, s, err)
    character(len=*), intent(in) :: text
    type(sweep_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    call open_deck_text(suite_stem(), '&run analysis = ''steady'' /|'//text, deck, err)
    if (.not. err%failed()) call read_sweep_settings(deck, s, err)
    call close_deck_text(suite_stem(), deck)
  end subroutine read_text

  subroutine test_list()
    type(sweep_settings_t) :: s
    type(error_t) :: err
    call read_text('&sweep group = ''mechanism'', variable = ''omega'', values = 100, 175, 75 /', s, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_equal(size(s%values), 3, 'three values')
    call assert_all_close(s%values, [100.0_dp, 175.0_dp, 75.0_dp], 0.0_dp, 0.0_dp, 'in the order given')
  end subroutine test_list

  !> 25..150 in 6 points: steps of 25, exact in binary.
  subroutine test_linear()
    type(sweep_settings_t) :: s
    type(error_t) :: err
    call read_text('&sweep group = ''mechanism'', variable = ''omega'', first = 25, last = 150, n_points = 6 /', s, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_all_close(s%values, [25.0_dp, 50.0_dp, 75.0_dp, 100.0_dp, 125.0_dp, 150.0_dp], 0.0_dp, 0.0_dp, &
                          'steps of 25')
  end subroutine test_linear

  !> 1e-3..1e-7 in 5 log-spaced points: the decades, to the 15 digits kept.
  subroutine test_log()
    type(sweep_settings_t) :: s
    type(error_t) :: err
    call read_text('&sweep group = ''transient'', variable = ''rtol'', first = 1e-3, last = 1e-7, n_points = 5, '// &
                   'spacing = ''log'' /', s, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_all_close(s%values, [1.0e-3_dp, 1.0e-4_dp, 1.0e-5_dp, 1.0e-6_dp, 1.0e-7_dp], 0.0_dp, 0.0_dp, &
                          'decades')
  end subroutine test_log

  subroutine test_errors()
    type(sweep_settings_t) :: s
    type(error_t) :: err
    call read_text('&sweep group = ''mechanism'', variable = ''omega'', values = 1, 2, n_points = 4 /', s, err)
    call assert_true(err%failed() .and. err%code == 2, 'values and a range together')
    call err%clear()
    call read_text('&sweep group = ''mechanism'', variable = ''omega'', first = 1, last = 2, n_points = 1 /', s, err)
    call assert_true(err%failed() .and. err%code == 2, 'a range of one point')
    call err%clear()
    call read_text('&sweep group = ''mechanism'', variable = ''link_h(1:)'', values = 1, 2 /', s, err)
    call assert_true(err%failed() .and. err%code == 2, 'an open array section')
    call err%clear()
    call read_text('&sweep group = ''mechanism'', variable = ''omega'', values = 1, nan /', s, err)
    call assert_true(err%failed() .and. err%code == 2, 'a NaN value')
  end subroutine test_errors
end module test_sweep_settings_suite

program test_sweep_settings
  use assertions, only: finish_suite
  use test_sweep_settings_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_sweep_settings')
end program test_sweep_settings
