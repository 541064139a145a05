!> Tests of the banded Cholesky kernels (module band_kernels): the solve
!> against a dense solve of the same matrix, the factor against LAPACK's
!> DPBTRF (same arithmetic: equal to round-off), the first non-positive
!> leading minor reported by its order, bands wider than the matrix, the
!> diagonal of the inverse from the factor and the symmetric band product.
module test_band_kernels_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: solve_linear, band_cholesky_factor
  use band_kernels, only: band_cholesky_inplace, band_cholesky_substitute, band_cholesky_inverse_diagonal, &
                          symmetric_band_product
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('solve_equals_dense_solve', test_solve)
    call run_test('factor_equals_lapack', test_lapack)
    call run_test('indefinite_reports_minor', test_indefinite)
    call run_test('band_wider_than_matrix', test_wide)
    call run_test('inverse_diagonal_equals_dense', test_inverse_diagonal)
    call run_test('symmetric_product_equals_dense', test_product)
  end subroutine run_all

  !> SPD band matrix (n, kd): diagonally dominant, entries of mixed sign.
  subroutine spd_band(n, kd, a, ab)
    integer, intent(in) :: n, kd
    real(dp), intent(out) :: a(n, n), ab(kd + 1, n)
    integer :: i, j
    a = 0.0_dp
    ab = 0.0_dp
    do j = 1, n
      do i = j, min(n, j + kd)
        a(i, j) = cos(real(3*i + 7*j, dp))
        if (i == j) a(i, j) = 2.0_dp*real(kd, dp) + 1.0_dp + sin(real(j, dp))
        a(j, i) = a(i, j)
        ab(1 + i - j, j) = a(i, j)
      end do
    end do
  end subroutine spd_band

  !> x = A^-1 b against Gaussian elimination of the dense A; A's condition
  !> is below 10, so 1e-12 of |x| is far above round-off and far below any
  !> indexing error (which changes x at order 1).
  subroutine test_solve()
    integer, parameter :: n = 40, kd = 6
    real(dp) :: a(n, n), ab(kd + 1, n), b(n), x(n)
    type(error_t) :: err
    integer :: i, info
    call spd_band(n, kd, a, ab)
    b = [(sin(real(5*i, dp)), i = 1, n)]
    x = b
    call solve_linear(a, b, err)
    call assert_true(.not. err%failed(), 'dense solve')
    call band_cholesky_inplace(ab, kd, info)
    call assert_equal(info, 0, 'positive definite')
    call band_cholesky_substitute(ab, kd, x)
    call assert_all_close(x, b, 0.0_dp, 1.0e-12_dp*maxval(abs(b)), 'A^-1 b')
  end subroutine test_solve

  !> The same factor as DPBTRF to round-off (1e-14 of the largest entry:
  !> bit-equal without FMA contraction, a few ulps with it).
  subroutine test_lapack()
    integer, parameter :: n = 25, kd = 7
    real(dp) :: a(n, n), ab(kd + 1, n), ref(kd + 1, n)
    type(error_t) :: err
    integer :: info
    call spd_band(n, kd, a, ab)
    ref = ab
    call band_cholesky_factor(ref, kd, err)
    call assert_true(.not. err%failed(), 'DPBTRF')
    call band_cholesky_inplace(ab, kd, info)
    call assert_equal(info, 0, 'factored')
    call assert_all_close(reshape(ab, [size(ab)]), reshape(ref, [size(ref)]), 0.0_dp, 1.0e-14_dp*maxval(abs(ref)), &
                          'L = DPBTRF''s L')
  end subroutine test_lapack

  !> A(5, 5) made so small that the fifth pivot is negative: info = 5.
  subroutine test_indefinite()
    integer, parameter :: n = 10, kd = 3
    real(dp) :: a(n, n), ab(kd + 1, n)
    integer :: info
    call spd_band(n, kd, a, ab)
    ab(1, 5) = -1.0_dp
    call band_cholesky_inplace(ab, kd, info)
    call assert_equal(info, 5, 'first non-positive leading minor')
  end subroutine test_indefinite

  !> kd >= n: a dense SPD matrix in band storage.
  subroutine test_wide()
    integer, parameter :: n = 3, kd = 6
    real(dp) :: a(n, n), ab(kd + 1, n), b(n), x(n)
    type(error_t) :: err
    integer :: info
    call spd_band(n, kd, a, ab)
    b = [1.0_dp, -2.0_dp, 0.5_dp]
    x = b
    call solve_linear(a, b, err)
    call band_cholesky_inplace(ab, kd, info)
    call assert_equal(info, 0, 'factored')
    call band_cholesky_substitute(ab, kd, x)
    call assert_all_close(x, b, 0.0_dp, 1.0e-13_dp*maxval(abs(b)), 'A^-1 b')
  end subroutine test_wide

  !> diag(A^-1) from the factor against the dense solves of A x = e_i (A's
  !> condition below 10: 1e-12 is far above round-off; an indexing error
  !> changes an entry at order 1).
  subroutine test_inverse_diagonal()
    integer, parameter :: n = 30, kd = 5
    real(dp) :: a(n, n), ab(kd + 1, n), d(n), e(n)
    type(error_t) :: err
    integer :: i, info
    call spd_band(n, kd, a, ab)
    call band_cholesky_inplace(ab, kd, info)
    call assert_equal(info, 0, 'factored')
    call band_cholesky_inverse_diagonal(ab, kd, d)
    do i = 1, n
      e = 0.0_dp
      e(i) = 1.0_dp
      call solve_linear(a, e, err)
      call assert_close(d(i), e(i), 1.0e-12_dp, '(A^-1)_ii')
    end do
  end subroutine test_inverse_diagonal

  !> M a from the lower band against the dense product (the same sums
  !> per entry, so 1e-14 of |M a|).
  subroutine test_product()
    integer, parameter :: n = 23, kd = 4
    real(dp) :: a(n, n), ab(kd + 1, n), x(n), y(n)
    integer :: i
    call spd_band(n, kd, a, ab)
    x = [(cos(real(2*i, dp)), i = 1, n)]
    call symmetric_band_product(ab, kd, x, y)
    call assert_all_close(y, matmul(a, x), 0.0_dp, 1.0e-14_dp*maxval(abs(matmul(a, x))), 'M a')
  end subroutine test_product
end module test_band_kernels_suite

program test_band_kernels
  use assertions, only: finish_suite
  use test_band_kernels_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_band_kernels')
end program test_band_kernels
