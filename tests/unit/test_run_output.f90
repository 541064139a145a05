!> Tests of run_output (reading flexmech outputs back for plots and sweep
!> summaries): column names, rows and footer of reference outputs of three
!> analyses, whose contents are known from their decks.
module test_run_output_suite
  use kinds, only: dp
  use error_status, only: error_t
  use run_output, only: run_output_t, read_run_output, column_index
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('lsode_output_columns_and_rows', test_lsode)
    call run_test('optimizer_notes_between_names_and_rows', test_optimizer)
    call run_test('transient_output_footer', test_transient)
    call run_test('missing_file_is_an_error', test_missing)
  end subroutine run_all

  !> inputs/lsode_kinetics.nml asks for 12 outputs at t = 0.4*10^k: 5 columns.
  subroutine test_lsode()
    type(run_output_t) :: out
    type(error_t) :: err
    call read_run_output('reference_outputs/lsode_kinetics.out', out, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_equal(out%analysis, 'lsode_check', 'analysis from the echoed &run')
    call assert_equal(out%n_columns(), 5, 'columns')
    call assert_equal(out%column_name(5), 'y1+y2+y3-1', 'last column name')
    call assert_equal(size(out%data, 1), 12, 'rows')
    ! t = 0.4 * 10^(k-1): exact decimal values written with 16 digits
    call assert_rel_close(out%data(12, 1), 0.4e11_dp, 1.0e-15_dp, 'last t')
    call assert_equal(out%title, 'LSODE verification: stiff chemical kinetics', 'title')
  end subroutine test_lsode

  !> Rosen-Suzuki from 0: 3 iterations (rows k = 0..3), 16 columns; the
  !> '# k = 1: step-back ...' notes must not be taken for the names.
  subroutine test_optimizer()
    type(run_output_t) :: out
    type(error_t) :: err
    integer :: jf
    call read_run_output('reference_outputs/opt_rosen_suzuki_gnlc_x0_0000.out', out, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_equal(out%analysis, 'optimize', 'analysis')
    call assert_equal(out%n_columns(), 16, 'columns')
    call assert_equal(size(out%data, 1), 4, 'rows k = 0..3')
    jf = column_index(out, 'F')
    call assert_equal(jf, 3, 'F is column 3')
    ! the known optimum F* = -44 (P Table I), reached to rounding
    call assert_close(out%data(4, jf), -44.0_dp, 1.0e-10_dp, 'final F')
  end subroutine test_optimizer

  !> fourbar_150_damped: 5 revolutions every 2 deg = 901 rows; crank_deg ends
  !> at 1800; in the footer, the 3 links' peak stresses of the last revolution,
  !> then of the whole run.
  subroutine test_transient()
    type(run_output_t) :: out
    type(error_t) :: err
    integer :: i, n_last, n_whole
    call read_run_output('reference_outputs/fourbar_150_damped.out', out, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_equal(out%analysis, 'transient', 'analysis')
    call assert_equal(size(out%data, 1), 901, 'rows')
    call assert_close(out%data(901, column_index(out, 'crank_deg')), 1800.0_dp, 1.0e-9_dp, 'last crank angle')
    n_last = 0
    n_whole = 0
    do i = 1, size(out%footer)
      if (index(out%footer(i)%s, 'last revolution peak |stress|') > 0) n_last = n_last + 1
      if (index(out%footer(i)%s, 'whole run peak |stress|') > 0) n_whole = n_whole + 1
    end do
    call assert_equal(n_last, 3, 'peak summaries of the last revolution')
    call assert_equal(n_whole, 3, 'peak summaries of the whole run')
  end subroutine test_transient

  subroutine test_missing()
    type(run_output_t) :: out
    type(error_t) :: err
    call read_run_output('reference_outputs/no_such_output.out', out, err)
    call assert_true(err%failed(), 'a missing file is an error')
  end subroutine test_missing
end module test_run_output_suite

program test_run_output
  use test_run_output_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_run_output')
end program test_run_output
