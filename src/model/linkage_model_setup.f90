!> The first steps of every model of a linkage (transient, steady): the
!> correlation table from the joints (module sliding_link's description of
!> the link ends), the kinematics, and the rigid-body position at t = 0 that
!> sets the element lengths.  Each model then builds its own elements and
!> places the lumped masses (module lumped_masses).
module linkage_model_setup
  use kinds, only: dp
  use error_status, only: error_t
  use linkage, only: mechanism_t
  use kinematics, only: kinematics_t
  use correlation_table, only: correlation_table_t, link_end_t
  use sliding_link, only: mechanism_link_ends
  implicit none
  private
  public :: start_linkage_model

contains

  !> table and kin of the linkage mech, the kinematics solved at t = 0; the
  !> options are the correlation table's (correlation_table%build).
  subroutine start_linkage_model(mech, table, kin, err, reduce_band, axial_dofs, shear_dofs)
    type(mechanism_t), intent(in) :: mech
    type(correlation_table_t), intent(inout) :: table
    type(kinematics_t), intent(inout) :: kin
    type(error_t), intent(inout) :: err
    logical, intent(in), optional :: reduce_band, axial_dofs, shear_dofs
    type(link_end_t) :: ends(2, mech%n_links)
    integer :: n_elements(mech%n_links)
    call mechanism_link_ends(mech, ends)
    n_elements = mech%links(:)%n_elements
    call table%build(n_elements, ends, err, reduce_band=reduce_band, &
                     axial_dofs=axial_dofs, shear_dofs=shear_dofs)
    if (err%failed()) return
    call kin%init(mech, err)
    if (err%failed()) return
    call kin%solve(0.0_dp, err)
  end subroutine start_linkage_model
end module linkage_model_setup
