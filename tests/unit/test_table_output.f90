!> Tests of the tabular output (module table_output): every finite double,
!> from the largest to the smallest subnormal, is written so that gnuplot and
!> numpy.loadtxt read it back: with its exponent letter (a three-digit
!> exponent without an explicit exponent width prints as 0.1+301, which
!> neither reads) and to the digits written.  Rows, the namelist echo of the
!> header and str() (summaries, messages) are checked.  A NaN or Inf is never
!> written into a data row; the first such row is named for the diagnosis.
module test_table_output_suite
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use table_output
  use assertions
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: path = 'test_table_output.tmp'

contains

  subroutine run_all()
    call run_test('rows_keep_the_exponent_letter_for_every_finite_double', test_rows)
    call run_test('namelist_echo_keeps_the_exponent_letter', test_echo)
    call run_test('str_keeps_the_exponent_letter', test_str)
    call run_test('discard_leaves_no_file', test_discard)
    call run_test('non_finite_row_is_refused_and_named', test_non_finite_row)
  end subroutine run_all

  !> Doubles across the whole range: next to huge (huge itself rounds up to
  !> 1.797693134862316E+308 in 16 digits, which reads back as Inf), three-digit exponents of both
  !> signs, the two-/three-digit boundary, the normal/subnormal boundary and
  !> subnormals down to the smallest, 4.9e-324.
  function extremes() result(x)
    real(dp) :: x(30)
    real(dp) :: smallest
    smallest = tiny(1.0_dp)*epsilon(1.0_dp)     ! 2^-1074, the smallest subnormal
    x(1:15) = [1.7976931348623e308_dp, 1.0e308_dp, 1.0e300_dp, 1.0e100_dp, 9.99e99_dp, 1.0e99_dp, 1.0_dp, &
               1.0e-99_dp, 1.0e-100_dp, 1.0e-300_dp, tiny(1.0_dp), 1.0e-310_dp, 3.0_dp*smallest, smallest, 0.0_dp]
    x(16:30) = -x(1:15)
  end function extremes

  !> Every blank-separated token of line(first:) read back as x(k).
  subroutine check_tokens(line, x, k, where)
    character(len=*), intent(in) :: line, where
    real(dp), intent(in) :: x(:)
    integer, intent(inout) :: k
    integer :: a, b, ios
    real(dp) :: back
    a = 1
    do
      if (verify(line(a:), ' ,') == 0) exit
      a = a + verify(line(a:), ' ,') - 1
      b = scan(line(a:), ' ,')
      b = merge(len(line), a + b - 2, b == 0)
      k = k + 1
      if (k > size(x)) exit
      call assert_true(scan(line(a:b), 'Ee') > 0 .or. verify(line(a + 1:b), '0123456789.') == 0, &
                       where//': '//line(a:b)//' has its exponent letter or is a plain decimal')
      read(line(a:b), *, iostat=ios) back
      call assert_true(ios == 0, where//': '//line(a:b)//' reads as a number')
      ! 16 significant digits are written: 1e-15 relative, or the subnormal spacing
      if (ios /= 0) back = huge(back)
      call assert_true(abs(back - x(k)) <= max(1.0e-15_dp*abs(x(k)), 2.0_dp*tiny(1.0_dp)*epsilon(1.0_dp)), &
                       where//': '//line(a:b)//' reads back as '//str(x(k), 17))
      a = b + 1
      if (a > len(line)) exit
    end do
  end subroutine check_tokens

  subroutine test_rows()
    type(table_t) :: t
    type(error_t) :: err
    real(dp) :: x(30)
    character(len=2048) :: line
    integer :: u, ios, k
    x = extremes()
    call t%open(path, err)
    call assert_true(.not. err%failed(), 'open: '//err%text())
    call t%columns([character(len=8) :: ('c', k = 1, size(x))])
    call t%row(x)
    call t%commit(err)
    call assert_true(.not. err%failed(), 'commit: '//err%text())
    open(newunit=u, file=path, status='old', action='read')
    k = 0
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:1) == '#') cycle
      call check_tokens(line, x, k, 'row')
    end do
    close(u, status='delete')
    call assert_equal(k, size(x), 'every value is in the row')
  end subroutine test_rows

  subroutine test_echo()
    type(table_t) :: t
    type(error_t) :: err
    real(dp) :: x(30)
    character(len=4096) :: line, all
    integer :: u, ios, k, e
    namelist /extreme/ x
    x = extremes()
    call t%open(path, err)
    e = t%echo_unit()
    write(e, nml=extreme)
    call t%end_echo()
    call t%commit(err)
    open(newunit=u, file=path, status='old', action='read')
    all = ''
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      ! '# &EXTREME', '#  V=  1.79E+308, ...', '#  /': keep the values
      if (index(line, '&') > 0 .or. index(line, '/') > 0) cycle
      if (index(line, '=') > 0) line = line(index(line, '=') + 1:)
      if (line(1:1) == '#') line = line(2:)
      all = trim(all)//' '//trim(line)
    end do
    close(u, status='delete')
    k = 0
    call check_tokens(all, x, k, 'namelist echo')
    call assert_equal(k, size(x), 'every value is in the echo')
  end subroutine test_echo

  subroutine test_str()
    real(dp) :: x(30)
    integer :: i, ios
    real(dp) :: back
    character(len=:), allocatable :: s
    x = extremes()
    do i = 1, size(x)
      if (.not. abs(x(i)) > 0.0_dp) cycle
      s = str(x(i))
      ! 8 significant digits by default: 1e-7 relative (subnormals: their spacing)
      read(s, *, iostat=ios) back
      call assert_true(ios == 0, 'str: '//s//' reads as a number')
      call assert_true(scan(s, 'Ee') > 0 .or. verify(s(2:), '0123456789.') == 0, &
                       'str: '//s//' has its exponent letter or is a plain decimal')
      call assert_true(abs(back - x(i)) <= max(1.0e-7_dp*abs(x(i)), 2.0_dp*tiny(1.0_dp)*epsilon(1.0_dp)), &
                       'str: '//s//' reads back')
    end do
    call assert_true(index(str(ieee_value(1.0_dp, ieee_quiet_nan)), 'NaN') > 0, 'str(NaN) says NaN')
    call assert_true(index(str(ieee_value(1.0_dp, ieee_positive_inf)), 'Inf') > 0, 'str(Inf) says Inf')
  end subroutine test_str

  subroutine test_discard()
    type(table_t) :: t
    type(error_t) :: err
    logical :: exists
    call t%open(path, err)
    call t%row([1.0_dp])
    call t%discard()
    inquire(file=path, exist=exists)
    call assert_true(.not. exists, 'no output after discard')
    inquire(file=t%tmp_path, exist=exists)
    call assert_true(.not. exists, 'no temporary file after discard')
  end subroutine test_discard

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
