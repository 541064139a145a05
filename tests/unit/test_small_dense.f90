!> Tests of the small dense LU (module small_dense): solutions equal LAPACK's,
!> transposed solves, the Hager-Higham condition estimate against DGECON,
!> singular matrices, and the switch to LAPACK above small_limit.
module test_small_dense_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: solve_linear, lu_factor
  use small_dense, only: dense_lu_t, small_limit
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('solve_equals_lapack', test_solve)
    call run_test('transposed_solve', test_transpose)
    call run_test('rcond_agrees_with_dgecon', test_rcond)
    call run_test('singular_matrix_is_an_error', test_singular)
  end subroutine run_all

  function test_matrix(n, seed) result(a)
    integer, intent(in) :: n, seed
    real(dp) :: a(n, n)
    integer :: i, j
    do j = 1, n
      do i = 1, n
        a(i, j) = sin(real(3*i + 7*j + seed, dp)) + merge(2.0_dp, 0.0_dp, i == j)
      end do
    end do
  end function test_matrix

  !> n = 10 (own code) and n = 60 (LAPACK): x equals DGETRS's to 1e-12.
  subroutine test_solve()
    integer :: k, n
    integer, parameter :: sizes(2) = [10, small_limit + 20]
    type(dense_lu_t) :: lu
    type(error_t) :: err
    real(dp), allocatable :: a(:, :), b(:), x(:)
    do k = 1, 2
      n = sizes(k)
      a = test_matrix(n, k)
      b = [(real(mod(7*k + 3*n, 5), dp) - 2.0_dp, n = 1, sizes(k))]
      x = b
      call solve_linear(a, x, err)
      call lu%factor(a, err)
      call assert_true(.not. err%failed(), 'factor')
      call lu%solve(b)
      call assert_all_close(b, x, 0.0_dp, 1.0e-12_dp*maxval(abs(x)), 'solution')
    end do
  end subroutine test_solve

  subroutine test_transpose()
    type(dense_lu_t) :: lu
    type(error_t) :: err
    real(dp) :: a(12, 12), b(12), x(12)
    integer :: i
    a = test_matrix(12, 5)
    b = [(real(i, dp), i = 1, 12)]
    x = b
    call solve_linear(transpose(a), x, err)
    call lu%factor(a, err)
    call lu%solve(b, trans=.true.)
    call assert_all_close(b, x, 0.0_dp, 1.0e-12_dp*maxval(abs(x)), 'A^T x = b')
  end subroutine test_transpose

  !> Both are estimates of 1/(|A|_1 |A^-1|_1) (DGECON uses the same
  !> estimator family); they agree within a factor 3 on a well and a badly
  !> conditioned (Hilbert 7 x 7, cond ~ 1e9) matrix.
  subroutine test_rcond()
    type(dense_lu_t) :: lu
    type(error_t) :: err
    real(dp) :: a(7, 7), w(7, 7), rc_lapack, rc
    integer :: ipiv(7), i, j
    do j = 1, 7
      do i = 1, 7
        a(i, j) = 1.0_dp/real(i + j - 1, dp)
      end do
    end do
    w = a
    call lu_factor(w, ipiv, err, rc_lapack)
    call lu%factor(a, err)
    rc = lu%rcond()
    call assert_true(rc > rc_lapack/3.0_dp .and. rc < 3.0_dp*rc_lapack, 'Hilbert matrix')
    call assert_true(rc < 1.0e-8_dp, 'Hilbert is ill conditioned')
    a = test_matrix(7, 2)
    w = a
    call lu_factor(w, ipiv, err, rc_lapack)
    call lu%factor(a, err)
    rc = lu%rcond()
    call assert_true(rc > rc_lapack/3.0_dp .and. rc < 3.0_dp*rc_lapack, 'diagonally dominant matrix')
  end subroutine test_rcond

  subroutine test_singular()
    type(dense_lu_t) :: lu
    type(error_t) :: err
    real(dp) :: a(4, 4)
    a = 1.0_dp
    call lu%factor(a, err)
    call assert_true(err%failed(), 'rank-one matrix')
  end subroutine test_singular
end module test_small_dense_suite

program test_small_dense
  use assertions, only: finish_suite
  use test_small_dense_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_small_dense')
end program test_small_dense
