!> Shared fixtures of the beam-element suites (test_kear_element,
!> test_consistent_element): a "unit" element soft enough that large
!> deflections and the material term are visible in derivative checks, and a
!> prescribed, non-trivial rigid-body motion of the reference line.
module element_fixtures
  use kinds, only: dp
  use material_law, only: ramberg_osgood_t
  use planar_element, only: rigid_state_t
  implicit none
  private
  public :: soft, l_u, b_u, t_u, rigid_at

  type(ramberg_osgood_t), parameter :: soft = ramberg_osgood_t(e1=1000.0_dp, e2=2.0e6_dp, m=3.0_dp, rho=2.0_dp)
  real(dp), parameter :: l_u = 1.3_dp, b_u = 0.2_dp, t_u = 0.3_dp

contains

  !> Rotation, translation of the first node and their rates at time t.
  pure function rigid_at(t) result(rb)
    real(dp), intent(in) :: t
    type(rigid_state_t) :: rb
    rb%phi = 0.3_dp + 2.0_dp*t + 0.7_dp*t**2 + 0.2_dp*sin(3.0_dp*t)
    rb%phi_d = 2.0_dp + 1.4_dp*t + 0.6_dp*cos(3.0_dp*t)
    rb%phi_dd = 1.4_dp - 1.8_dp*sin(3.0_dp*t)
    rb%x1 = 0.5_dp + 0.3_dp*t + 0.4_dp*t**2 + 0.1_dp*cos(2.0_dp*t)
    rb%x1_d = 0.3_dp + 0.8_dp*t - 0.2_dp*sin(2.0_dp*t)
    rb%x1_dd = 0.8_dp - 0.4_dp*cos(2.0_dp*t)
    rb%y1 = -0.2_dp + 0.6_dp*t - 0.3_dp*t**2 + 0.05_dp*sin(5.0_dp*t)
    rb%y1_d = 0.6_dp - 0.6_dp*t + 0.25_dp*cos(5.0_dp*t)
    rb%y1_dd = -0.6_dp - 1.25_dp*sin(5.0_dp*t)
  end function rigid_at
end module element_fixtures
