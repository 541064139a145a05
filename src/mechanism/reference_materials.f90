!> Material constants the papers use, kept in one place: the deck's default
!> link material is Tennant's aluminium.
module reference_materials
  use kinds, only: dp
  implicit none
  private
  public :: tennant_aluminium_e1, tennant_aluminium_e2, tennant_aluminium_m, tennant_aluminium_rho

  ! Tennant's "approximating aluminum", section 8.1 (T6, T7): sigma = A eps - B eps^m.
  real(dp), parameter :: tennant_aluminium_e1 = 10.87e6_dp      !< A, lb/in^2
  real(dp), parameter :: tennant_aluminium_e2 = 0.8387e11_dp    !< B, lb/in^2
  real(dp), parameter :: tennant_aluminium_m = 3.0_dp           !< m
  real(dp), parameter :: tennant_aluminium_rho = 2.536e-4_dp    !< lb s^2/in^4
end module reference_materials
