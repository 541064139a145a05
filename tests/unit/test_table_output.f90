!> Tests of the tabular output (module table_output): a NaN or Inf is never
!> written into a data row; the first such row is named for the diagnosis.
module test_table_output_suite
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
  use kinds, only: dp
  use error_status, only: error_t
  use table_output, only: table_t
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('non_finite_row_is_refused_and_named', test_non_finite_row)
  end subroutine run_all

  !> Rows 1-2 finite, row 3 holds Inf in column 2, row 4 NaN: the file keeps
  !> rows 1-2 only and the diagnosis names row 3, column 2.
  subroutine test_non_finite_row()
    type(table_t) :: out
    type(error_t) :: err
    real(dp) :: nan, inf, x
    character(len=*), parameter :: path = 'test_table_output.tmp.out'
    character(len=256) :: line
    integer :: u, ios, n_data, n_bad
    nan = ieee_value(nan, ieee_quiet_nan)
    inf = ieee_value(inf, ieee_positive_inf)
    call out%open(path, err)
    call assert_true(.not. err%failed(), err%text())
    call out%columns([character(len=8) :: 'a', 'b'])
    call out%row([1.0_dp, 2.0_dp])
    call out%row([3.0_dp, 1.0e300_dp])
    call out%row([5.0_dp, inf])
    call out%row([nan, 8.0_dp])
    call assert_equal(out%bad_row, 3, 'first non-finite row')
    call assert_equal(out%bad_column, 2, 'its column')
    call assert_true(index(out%non_finite_text(), 'data row 3, column 2') > 0, out%non_finite_text())
    call out%commit(err)
    call assert_true(.not. err%failed(), err%text())
    open(newunit=u, file=path, status='old', action='read')
    n_data = 0
    n_bad = 0
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:1) == '#') cycle
      n_data = n_data + 1
      read(line, *) x, x
      if (index(line, 'NaN') > 0 .or. index(line, 'Inf') > 0) n_bad = n_bad + 1
      ! a three-digit exponent keeps its E (gnuplot and numpy read it)
      if (n_data == 2) call assert_close(x, 1.0e300_dp, 1.0e285_dp, '1e300 reads back')
    end do
    close(u, status='delete')
    call assert_equal(n_data, 2, 'rows written before the first non-finite one')
    call assert_equal(n_bad, 0, 'no NaN or Inf in the file')
  end subroutine test_non_finite_row
end module test_table_output_suite

program test_table_output
  use test_table_output_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_table_output')
end program test_table_output
