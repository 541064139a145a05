!> Banded Cholesky factor and solve for the narrow bands of the mechanism
!> models (half-bandwidth kd of 5-12, N up to a few thousand), in lower band
!> storage ab(1+i-j, j) = A(i, j).  LAPACK's DPBTRF/DPBTRS do the same
!> arithmetic in the same order (DPBTF2: scale the column by 1/a_jj, then the
!> rank-1 update DSYR; DTBSV forward, then transposed) but with a BLAS call
!> per column: at kd = 6 the calls cost more than the flops (doc/benchmarks.md,
!> "Right-hand side").  The results are the same to the last bit when the
!> compiler does not contract a*b + c into FMAs (the release flags); with FMAs
!> they differ by round-off.
!> The inner loops of variable length carry !GCC$ vector: at -O2 gfortran
!> vectorizes only loops that need no remainder, which these always do.
module band_kernels
  use kinds, only: dp
  implicit none
  private
  public :: band_cholesky_inplace, band_cholesky_substitute, band_cholesky_inverse_diagonal, symmetric_band_product, &
            add_pair_band

contains

  !> (The dummies are contiguous: unit-stride addressing in the short inner
  !> loops; a strided actual would be copied in and out.)
  !>
  !> A = L L^T in place (L in lower band storage).  info = 0, or the order
  !> of the first leading minor that is not positive.
  pure subroutine band_cholesky_inplace(ab, kd, info)
    real(dp), intent(inout), contiguous :: ab(:, :)
    integer, intent(in) :: kd
    integer, intent(out) :: info
    integer :: n, j, kn, i, jj
    real(dp) :: ajj, r, xjj
    n = size(ab, 2)
    info = 0
    do j = 1, n
      ajj = ab(1, j)
      if (.not. ajj > 0.0_dp) then
        info = j
        return
      end if
      ajj = sqrt(ajj)
      ab(1, j) = ajj
      kn = min(kd, n - j)
      if (kn == 0) cycle
      r = 1.0_dp/ajj
      ab(2:kn + 1, j) = r*ab(2:kn + 1, j)
      ! trailing kn x kn block -= x x^T, x = ab(2:kn+1, j)
      do jj = 1, kn
        xjj = -ab(1 + jj, j)
        !GCC$ vector
        do i = jj, kn
          ab(1 + i - jj, j + jj) = ab(1 + i - jj, j + jj) + ab(1 + i, j)*xjj
        end do
      end do
    end do
  end subroutine band_cholesky_inplace

  !> b := A^-1 b with A = L L^T from band_cholesky_inplace.  The forward
  !> sweep is column-oriented (an axpy on contiguous slices the compiler
  !> vectorizes); the backward one a dot product per column, in LAPACK's order.
  pure subroutine band_cholesky_substitute(ab, kd, b)
    real(dp), intent(in), contiguous :: ab(:, :)
    integer, intent(in) :: kd
    real(dp), intent(inout), contiguous :: b(:)
    integer :: n, j, i, m
    real(dp) :: temp
    n = size(ab, 2)
    do j = 1, n                       ! L y = b
      b(j) = b(j)/ab(1, j)
      temp = b(j)
      m = min(kd, n - j)
      !GCC$ vector
      do i = 1, m
        b(j + i) = b(j + i) - temp*ab(1 + i, j)
      end do
    end do
    do j = n, 1, -1                   ! L^T x = y
      temp = b(j)
      do i = min(kd, n - j), 1, -1
        temp = temp - ab(1 + i, j)*b(j + i)
      end do
      b(j) = temp/ab(1, j)
    end do
  end subroutine band_cholesky_substitute

  !> The diagonal of A^-1 from A = L L^T (band_cholesky_inplace):
  !> (A^-1)_ii = |L^-1 e_i|^2, each by a forward sweep from row i.
  pure subroutine band_cholesky_inverse_diagonal(ab, kd, d)
    real(dp), intent(in), contiguous :: ab(:, :)
    integer, intent(in) :: kd
    real(dp), intent(out) :: d(:)
    real(dp) :: y(size(ab, 2)), temp
    integer :: n, i, j, r, last
    n = size(ab, 2)
    do i = 1, n
      y(i:) = 0.0_dp
      y(i) = 1.0_dp
      last = i                          ! the last nonzero row of y so far
      d(i) = 0.0_dp
      do j = i, n
        if (j > last) exit              ! y(j:) = 0: nothing more to sweep
        y(j) = y(j)/ab(1, j)
        temp = y(j)
        d(i) = d(i) + temp*temp
        do r = 1, min(kd, n - j)
          y(j + r) = y(j + r) - temp*ab(1 + r, j)
        end do
        last = max(last, min(n, j + kd))
      end do
    end do
  end subroutine band_cholesky_inverse_diagonal

  !> y = M a, M symmetric in lower band storage m(1+i-j, j): O(N kd).
  !> Column j adds M(j+1:, j) a_j below the diagonal (a vectorized axpy)
  !> and its dot product with a(j+1:) to y_j (the sums in the order of the
  !> fused loop: the same result to the last bit).
  pure subroutine symmetric_band_product(m, kd, a, y)
    real(dp), intent(in), contiguous :: m(:, :)
    integer, intent(in) :: kd
    real(dp), intent(in), contiguous :: a(:)
    real(dp), intent(out), contiguous :: y(:)
    real(dp) :: aj, s
    integer :: i, j, n, k
    n = size(m, 2)
    y = 0.0_dp
    do j = 1, n
      k = min(kd, n - j)
      aj = a(j)
      !GCC$ vector
      do i = 1, k
        y(j + i) = y(j + i) + m(1 + i, j)*aj
      end do
      s = m(1, j)*aj
      do i = 1, k
        s = s + m(1 + i, j)*a(j + i)
      end do
      y(j) = y(j) + s
    end do
  end subroutine symmetric_band_product

  !> band += s * G for the 4 x 4 G = [[B, -B], [-B, B]] of a 2 x 2 block B
  !> acting on e = (x(d1), x(d2)) - (x(d3), x(d4)) (a spring or damper
  !> between two points; d = 0: a grounded point), in band storage
  !> band(off + i - j, j); with lower, only i >= j (LAPACK's lower symmetric
  !> band, off = 1).
  pure subroutine add_pair_band(d, blk, s, band, off, lower)
    integer, intent(in) :: d(4)
    real(dp), intent(in) :: blk(2, 2), s
    real(dp), intent(inout) :: band(:, :)
    integer, intent(in) :: off
    logical, intent(in) :: lower
    integer :: a, b, i, j
    real(dp) :: sgn(4)
    sgn = [1.0_dp, 1.0_dp, -1.0_dp, -1.0_dp]
    do b = 1, 4
      j = d(b)
      if (j == 0) cycle
      do a = 1, 4
        i = d(a)
        if (i == 0) cycle
        if (lower .and. i < j) cycle
        band(off + i - j, j) = band(off + i - j, j) + s*sgn(a)*sgn(b)*blk(mod(a - 1, 2) + 1, mod(b - 1, 2) + 1)
      end do
    end do
  end subroutine add_pair_band
end module band_kernels
