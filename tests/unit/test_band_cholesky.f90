!> Tests of the plain-loop banded Cholesky (module band_cholesky): the
!> solution of A x = b against LAPACK's DPBTRF/DPBTRS route in linalg and
!> against a dense solve, on band widths from 0 to n - 1; a matrix that is not
!> positive definite is refused.
module test_band_cholesky_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: solve_linear, band_cholesky_factor, band_cholesky_solve
  use band_cholesky, only: band_llt_factor, band_llt_solve
  use assertions
  implicit none
  private
  public :: run_all

  integer, parameter :: n = 23

contains

  subroutine run_all()
    call run_test('solve_equals_lapack_and_dense', test_solve)
    call run_test('indefinite_refused', test_indefinite)
  end subroutine run_all

  !> SPD band matrix: diagonally dominant, symmetric, entries of both signs.
  subroutine spd(kd, a, ab)
    integer, intent(in) :: kd
    real(dp), intent(out) :: a(n, n), ab(kd + 1, n)
    integer :: i, j
    a = 0.0_dp
    ab = 0.0_dp
    do j = 1, n
      do i = j, min(n, j + kd)
        a(i, j) = cos(real(3*i + 7*j, dp)) + merge(real(2*kd + 2, dp), 0.0_dp, i == j)
        a(j, i) = a(i, j)
        ab(1 + i - j, j) = a(i, j)
      end do
    end do
  end subroutine spd

  !> Tolerance 1e-12 relative: the matrices are well conditioned (diagonal
  !> dominance), both routes are backward stable; the dense one differs in
  !> the order of operations only.
  subroutine test_solve()
    integer, parameter :: widths(5) = [0, 1, 4, 16, n - 1]
    real(dp), allocatable :: ab(:, :), ab2(:, :)
    real(dp) :: a(n, n), b(n), x1(n), x2(n), xd(n)
    type(error_t) :: err
    logical :: ok
    integer :: w, kd, i
    do w = 1, size(widths)
      kd = widths(w)
      allocate(ab(kd + 1, n))
      call spd(kd, a, ab)
      ab2 = ab
      b = [(sin(real(2*i, dp)) + 0.5_dp, i = 1, n)]
      x1 = b
      x2 = b
      xd = b
      call band_llt_factor(ab, kd, ok)
      call assert_true(ok, 'positive definite, kd = '//char(48 + mod(kd, 10)))
      call band_llt_solve(ab, kd, x1)
      call band_cholesky_factor(ab2, kd, err)
      call band_cholesky_solve(ab2, kd, x2, err)
      call solve_linear(a, xd, err)
      call assert_true(.not. err%failed(), 'LAPACK and dense routes')
      call assert_all_close(x1, x2, 0.0_dp, 1.0e-12_dp*maxval(abs(x2)), 'against DPBTRF/DPBTRS')
      call assert_all_close(x1, xd, 0.0_dp, 1.0e-12_dp*maxval(abs(xd)), 'against the dense solve')
      call assert_all_close(matmul(a, x1), b, 0.0_dp, 1.0e-12_dp*maxval(abs(b)), 'residual')
      call assert_all_close(ab(1, :), ab2(1, :), 0.0_dp, 1.0e-12_dp*maxval(abs(ab2(1, :))), 'factor diagonal')
      deallocate(ab, ab2)
    end do
  end subroutine test_solve

  subroutine test_indefinite()
    real(dp) :: a(n, n), ab(4, n)
    logical :: ok
    call spd(3, a, ab)
    ab(1, 11) = -ab(1, 11)           ! a negative diagonal entry: not positive definite
    call band_llt_factor(ab, 3, ok)
    call assert_true(.not. ok, 'refused')
  end subroutine test_indefinite
end module test_band_cholesky_suite

program test_band_cholesky
  use assertions, only: finish_suite
  use test_band_cholesky_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_band_cholesky')
end program test_band_cholesky
