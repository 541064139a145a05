!> Material constants the papers use, kept in one place: the deck's default
!> link material is Tennant's aluminium.
module reference_materials
  use kinds, only: dp
  implicit none
  private
  public :: tennant_aluminium_e1, tennant_aluminium_e2, tennant_aluminium_m, tennant_aluminium_rho
  public :: default_link_material

  ! Tennant's "approximating aluminum", section 8.1 (T6, T7): sigma = A eps - B eps^m.
  real(dp), parameter :: tennant_aluminium_e1 = 10.87e6_dp      !< A, lb/in^2
  real(dp), parameter :: tennant_aluminium_e2 = 0.8387e11_dp    !< B, lb/in^2
  real(dp), parameter :: tennant_aluminium_m = 3.0_dp           !< m
  real(dp), parameter :: tennant_aluminium_rho = 2.536e-4_dp    !< lb s^2/in^4

  ! the in-lbf-s units in SI
  real(dp), parameter :: psi_in_pa = 6894.757293168_dp                 !< 1 lb/in^2 in Pa
  real(dp), parameter :: mass_density_in_si = 4.4482216152605_dp/0.0254_dp**4   !< 1 lb s^2/in^4 in kg/m^3

contains

  !> The deck's default link material in its system of units ('si': the same
  !> aluminium in Pa and kg/m^3; otherwise the in-lbf-s values).
  pure subroutine default_link_material(system, e1, e2, rho)
    character(len=*), intent(in) :: system
    real(dp), intent(out) :: e1, e2, rho
    e1 = tennant_aluminium_e1
    e2 = tennant_aluminium_e2
    rho = tennant_aluminium_rho
    if (system == 'si') then
      e1 = e1*psi_in_pa
      e2 = e2*psi_in_pa
      rho = rho*mass_density_in_si
    end if
  end subroutine default_link_material
end module reference_materials
