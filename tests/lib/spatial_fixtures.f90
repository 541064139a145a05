!> Small vector helpers of the spatial-beam suites (test_spatial_beam,
!> test_spatial_spinup): the cross product, and the frame rate Omega x
!> applied to the translation and rotation triads of a 20-DOF element.
module spatial_fixtures
  use kinds, only: dp
  implicit none
  private
  public :: cross3, spin_cross

contains

  pure function cross3(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross3

  !> W q: omega x on the displacement and rotation triads of both nodes
  !> (element DOFs 1:3, 4:6 and 11:13, 14:16); the other DOFs get 0.
  pure function spin_cross(omega, q) result(w)
    real(dp), intent(in) :: omega(3), q(20)
    real(dp) :: w(20)
    w = 0.0_dp
    w(1:3) = cross3(omega, q(1:3))
    w(4:6) = cross3(omega, q(4:6))
    w(11:13) = cross3(omega, q(11:13))
    w(14:16) = cross3(omega, q(14:16))
  end function spin_cross
end module spatial_fixtures
