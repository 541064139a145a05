!> Banded Cholesky A = L L^T of a symmetric positive definite matrix in
!> LAPACK's lower band storage (ab(1 + i - j, j) = A(i, j), kd + 1 rows),
!> written out in plain loops.  LAPACK's DPBTRF calls its unblocked DPBTF2
!> for the narrow bands of the spatial model (kd ~ 16 < the block size),
!> which makes one BLAS DSYR call per column; at these sizes the call
!> overhead is a large part of the work (doc/spatial.md, "Cost").  Same
!> storage as linalg's band_cholesky_factor/solve, so the two are
!> interchangeable; the arithmetic is the same right-looking update.
module band_cholesky
  use kinds, only: dp
  implicit none
  private
  public :: band_llt_factor, band_llt_solve

contains

  !> ab := L (lower band).  ok = .false. if a pivot is not positive (not
  !> positive definite); ab is then partly overwritten.
  pure subroutine band_llt_factor(ab, kd, ok)
    real(dp), intent(inout), contiguous :: ab(:, :)   ! contiguous: unit-stride loops that vectorise
    integer, intent(in) :: kd
    logical, intent(out) :: ok
    integer :: n, j, c, r, kn
    real(dp) :: ajj, ljc
    n = size(ab, 2)
    ok = .false.
    do j = 1, n
      ajj = ab(1, j)
      if (.not. (ajj > 0.0_dp)) return
      ajj = sqrt(ajj)
      ab(1, j) = ajj
      kn = min(kd, n - j)
      ab(2:kn + 1, j) = ab(2:kn + 1, j)/ajj
      ! trailing update A(j+c.., j+c) -= l(j+c..) l(j+c), column by column
      do c = 1, kn
        ljc = ab(1 + c, j)
        do r = c, kn                              ! explicit loop: no temporary for the aliased sections
          ab(1 + r - c, j + c) = ab(1 + r - c, j + c) - ljc*ab(1 + r, j)
        end do
      end do
    end do
    ok = .true.
  end subroutine band_llt_factor

  !> b := A^-1 b with the factor of band_llt_factor.
  pure subroutine band_llt_solve(ab, kd, b)
    real(dp), intent(in), contiguous :: ab(:, :)
    integer, intent(in) :: kd
    real(dp), intent(inout), contiguous :: b(:)
    integer :: n, j, kn, i
    real(dp) :: bj
    n = size(ab, 2)
    do j = 1, n                                   ! L y = b
      bj = b(j)/ab(1, j)
      b(j) = bj
      kn = min(kd, n - j)
      do i = 1, kn
        b(j + i) = b(j + i) - bj*ab(1 + i, j)
      end do
    end do
    do j = n, 1, -1                               ! L^T x = y
      kn = min(kd, n - j)
      bj = b(j)
      do i = 1, kn
        bj = bj - ab(1 + i, j)*b(j + i)
      end do
      b(j) = bj/ab(1, j)
    end do
  end subroutine band_llt_solve
end module band_cholesky
