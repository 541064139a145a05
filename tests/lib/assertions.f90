!> A small assertion library with pFUnit's conventions: named test procedures,
!> assertions that carry a tolerance and a message, a summary line per suite.
!>
!>     call run_test('lsode_stiff_kinetics', test_stiff_kinetics)
!>     ...
!>     call finish_suite('test_lsode_solver')      ! prints "suite: N passed, M failed"
!>
!> finish_suite prints the number of assertions evaluated before that line
!> ("suite: K assertions"), so a refactoring of a suite can show it checks
!> as much as before (issue 9).
!>
!> A test procedure fails if any assertion inside it fails.  Every failure
!> prints expected, actual, the difference and the tolerance.
module assertions
  use kinds, only: dp
  use error_status, only: error_t
  use, intrinsic :: iso_fortran_env, only: output_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  implicit none
  private
  public :: run_test, finish_suite
  public :: assert_true, assert_close, assert_equal, assert_rel_close, assert_all_close
  public :: test_procedure, assert_error

  abstract interface
    subroutine test_procedure()
    end subroutine test_procedure
  end interface

  interface assert_equal
    module procedure assert_equal_int, assert_equal_str
  end interface assert_equal

  integer :: n_passed = 0, n_failed = 0
  integer :: n_assertions = 0
  integer :: failures_in_current = 0
  character(len=128) :: current_name = ''

contains

  subroutine run_test(name, test)
    character(len=*), intent(in) :: name
    procedure(test_procedure) :: test
    real :: t0, t1
    current_name = name
    failures_in_current = 0
    call cpu_time(t0)
    call test()
    call cpu_time(t1)
    ! the CPU time is printed to find the slow tests; nothing depends on it
    if (failures_in_current == 0) then
      n_passed = n_passed + 1
      write(output_unit, '(a,f0.2,a)') '  PASS '//trim(name)//' (', t1 - t0, ' s CPU)'
    else
      n_failed = n_failed + 1
      write(output_unit, '(a,f0.2,a)') '  FAIL '//trim(name)//' (', t1 - t0, ' s CPU)'
    end if
    flush(output_unit)
  end subroutine run_test

  !> Print "suite: K assertions", then "suite: N passed, M failed" (the
  !> line tests/run_tests.sh reads) and stop with status 1 if any failed.
  subroutine finish_suite(suite)
    character(len=*), intent(in) :: suite
    write(output_unit, '(a,": ",i0," assertions")') trim(suite), n_assertions
    write(output_unit, '(a,": ",i0," passed, ",i0," failed")') trim(suite), n_passed, n_failed
    if (n_failed > 0) error stop 1
  end subroutine finish_suite

  subroutine record_failure(message)
    character(len=*), intent(in) :: message
    failures_in_current = failures_in_current + 1
    write(output_unit, '(a)') '    assertion failed in '//trim(current_name)//': '//trim(message)
  end subroutine record_failure

  subroutine assert_true(condition, message)
    logical, intent(in) :: condition
    character(len=*), intent(in) :: message
    n_assertions = n_assertions + 1
    if (.not. condition) call record_failure(message)
  end subroutine assert_true

  !> |actual - expected| <= tol  (absolute tolerance).
  subroutine assert_close(actual, expected, tol, message)
    real(dp), intent(in) :: actual, expected, tol
    character(len=*), intent(in) :: message
    character(len=256) :: detail
    n_assertions = n_assertions + 1
    if (ieee_is_nan(actual) .or. .not. (abs(actual - expected) <= tol)) then
      write(detail, '(a,es23.15,a,es23.15,a,es10.3,a,es10.3)') ' expected ', expected, ' got ', actual, &
        ' diff ', actual - expected, ' tol ', tol
      call record_failure(trim(message)//trim(detail))
    end if
  end subroutine assert_close

  !> |actual - expected| <= rtol*|expected|  (relative tolerance).
  subroutine assert_rel_close(actual, expected, rtol, message)
    real(dp), intent(in) :: actual, expected, rtol
    character(len=*), intent(in) :: message
    character(len=256) :: detail
    n_assertions = n_assertions + 1
    if (ieee_is_nan(actual) .or. .not. (abs(actual - expected) <= rtol*abs(expected))) then
      write(detail, '(a,es23.15,a,es23.15,a,es10.3,a,es10.3)') ' expected ', expected, ' got ', actual, &
        ' rel.diff ', (actual - expected)/merge(expected, 1.0_dp, abs(expected) > 0.0_dp), ' rtol ', rtol
      call record_failure(trim(message)//trim(detail))
    end if
  end subroutine assert_rel_close

  !> Element-wise |a - e| <= atol + rtol*|e|; reports the worst entry.
  subroutine assert_all_close(actual, expected, rtol, atol, message)
    real(dp), intent(in) :: actual(:), expected(:), rtol, atol
    character(len=*), intent(in) :: message
    character(len=256) :: detail
    real(dp), allocatable :: excess(:)
    integer :: i
    n_assertions = n_assertions + 1
    if (size(actual) /= size(expected)) then
      write(detail, '(a,i0,a,i0)') ' size mismatch: got ', size(actual), ' expected ', size(expected)
      call record_failure(trim(message)//trim(detail))
      return
    end if
    if (size(actual) == 0) return
    allocate(excess(size(actual)))
    excess = abs(actual - expected) - (atol + rtol*abs(expected))
    where (ieee_is_nan(actual)) excess = huge(1.0_dp)
    i = maxloc(excess, dim=1)
    if (excess(i) > 0.0_dp) then
      write(detail, '(a,i0,a,es23.15,a,es23.15,a,es10.3)') ' worst entry ', i, ': expected ', expected(i), &
        ' got ', actual(i), ' diff ', actual(i) - expected(i)
      call record_failure(trim(message)//trim(detail))
    end if
  end subroutine assert_all_close

  !> err failed with `code` and its text contains `fragment` (every given
  !> fragment); the message of a failure shows the error's text.
  subroutine assert_error(err, code, fragment, message, fragment2)
    type(error_t), intent(in) :: err
    integer, intent(in) :: code
    character(len=*), intent(in) :: fragment, message
    character(len=*), intent(in), optional :: fragment2
    logical :: named
    n_assertions = n_assertions + 1
    named = index(err%text(), fragment) > 0
    if (present(fragment2)) named = named .and. index(err%text(), fragment2) > 0
    if (.not. (err%failed() .and. err%code == code .and. named)) &
      call record_failure(trim(message)//': got "'//err%text()//'"')
  end subroutine assert_error

  subroutine assert_equal_int(actual, expected, message)
    integer, intent(in) :: actual, expected
    character(len=*), intent(in) :: message
    character(len=96) :: detail
    n_assertions = n_assertions + 1
    if (actual /= expected) then
      write(detail, '(a,i0,a,i0)') ' expected ', expected, ' got ', actual
      call record_failure(trim(message)//trim(detail))
    end if
  end subroutine assert_equal_int

  subroutine assert_equal_str(actual, expected, message)
    character(len=*), intent(in) :: actual, expected
    character(len=*), intent(in) :: message
    n_assertions = n_assertions + 1
    if (actual /= expected) call record_failure(trim(message)//' expected "'//expected//'" got "'//actual//'"')
  end subroutine assert_equal_str
end module assertions
