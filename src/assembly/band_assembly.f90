!> Adding an element matrix into a global symmetric band through the
!> element's correlation (global number map(i), 0 = not an unknown, and
!> coefficient coef(i) of its DOF i): one loop for the planar and the
!> spatial transient models, whatever their correlation table.
module band_assembly
  use kinds, only: dp
  implicit none
  private
  public :: add_to_lower_band

contains

  !> band(1 + gi - gj, gj) += coef(i) me(i, j) coef(j) for gi >= gj: the
  !> lower triangle of a symmetric matrix in LAPACK's lower band storage.
  pure subroutine add_to_lower_band(band, me, map, coef)
    real(dp), intent(inout) :: band(:, :)
    real(dp), intent(in) :: me(:, :), coef(:)
    integer, intent(in) :: map(:)
    integer :: i, j, gi, gj
    do j = 1, size(map)
      gj = map(j)
      if (gj == 0) cycle
      do i = 1, size(map)
        gi = map(i)
        if (gi < gj) cycle
        band(1 + gi - gj, gj) = band(1 + gi - gj, gj) + coef(i)*me(i, j)*coef(j)
      end do
    end do
  end subroutine add_to_lower_band
end module band_assembly
