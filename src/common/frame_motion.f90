!> The rigid-body motion of a link or of one of its elements: end 1, angle of
!> the reference line, length, and their first and second time derivatives.
!> The kinematics computes it (motion_t of module kinematics); Tennant's
!> element takes it as its frame state (frame_state_t, T1).  One type, so a
!> solved motion is an element's frame state as it stands.
module frame_motion
  use kinds, only: dp
  implicit none
  private
  public :: motion_t

  type :: motion_t
    real(dp) :: x1 = 0.0_dp, y1 = 0.0_dp, phi = 0.0_dp
    real(dp) :: x1_d = 0.0_dp, y1_d = 0.0_dp, phi_d = 0.0_dp
    real(dp) :: x1_dd = 0.0_dp, y1_dd = 0.0_dp, phi_dd = 0.0_dp
    real(dp) :: length = 0.0_dp, length_d = 0.0_dp, length_dd = 0.0_dp
  end type motion_t
end module frame_motion
