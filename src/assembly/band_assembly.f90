!> Adding an element matrix into a global symmetric band through the
!> element's correlation (global number map(i), 0 = not an unknown, and
!> coefficient coef(i) of its DOF i, from the correlation table): one loop
!> for the planar and the spatial transient models, whatever their
!> correlation table, whose add_lower_band and add_newton_bands call these
!> with an element's map.  (Dense global matrices: the correlation table's
!> scatter_add_matrix.)
module band_assembly
  use kinds, only: dp
  implicit none
  private
  public :: add_to_lower_band, add_to_newton_bands

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

  !> The element's M and K_t into the Newton matrix's bands: mass_lower in
  !> lower band storage (1 + gi - gj, gj), stiff_band in general band storage
  !> (kd + 1 + gi - gj, gj), each entry += coef(i) coef(j) times the element's.
  !> Only the element DOFs that reach an unknown are visited.
  pure subroutine add_to_newton_bands(mass_lower, stiff_band, kd, me, ke, map, coef)
    real(dp), intent(inout) :: mass_lower(:, :), stiff_band(:, :)
    integer, intent(in) :: kd
    real(dp), intent(in) :: me(:, :), ke(:, :), coef(:)
    integer, intent(in) :: map(:)
    real(dp) :: cij, c(size(map))
    integer :: i, j, gi, gj, na, ii, jj, act(size(map)), g(size(map))
    na = 0
    do i = 1, size(map)
      if (map(i) == 0) cycle
      na = na + 1
      act(na) = i
      g(na) = map(i)
      c(na) = coef(i)
    end do
    do jj = 1, na
      j = act(jj)
      gj = g(jj)
      do ii = 1, na
        i = act(ii)
        gi = g(ii)
        cij = c(ii)*c(jj)
        stiff_band(kd + 1 + gi - gj, gj) = stiff_band(kd + 1 + gi - gj, gj) + cij*ke(i, j)
        if (gi >= gj) mass_lower(1 + gi - gj, gj) = mass_lower(1 + gi - gj, gj) + cij*me(i, j)
      end do
    end do
  end subroutine add_to_newton_bands
end module band_assembly
