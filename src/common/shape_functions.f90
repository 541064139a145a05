!> Element interpolation of Tennant (T20-T21) and Kear (K27, K29): linear
!> Lagrange n1, n2 for the axial displacement and quintic Hermite h1..h6 for
!> the transverse displacement (T20-T21 = K27, K29; doc/element.md).
!>
!> With e = x/l:  h1, h4 carry the nodal value, h2, h5 the nodal slope and
!> h3, h6 the nodal second derivative (curvature DOF), so w, w_x and w_xx are
!> continuous between elements (C2).  Derivatives returned here are with
!> respect to x, not e.
module shape_functions
  use kinds, only: dp
  implicit none
  private
  public :: quintic_hermite, linear_lagrange

contains

  !> h(1:6) at x = e*l and its first three x-derivatives (T20-T21, K27).
  pure subroutine quintic_hermite(e, l, h, hx, hxx, hxxx)
    real(dp), intent(in) :: e, l
    real(dp), intent(out) :: h(6)
    real(dp), intent(out), optional :: hx(6), hxx(6), hxxx(6)
    real(dp) :: e2, e3, e4, e5
    e2 = e*e
    e3 = e2*e
    e4 = e3*e
    e5 = e4*e
    h(1) = 1.0_dp - 10.0_dp*e3 + 15.0_dp*e4 - 6.0_dp*e5
    h(2) = l*(e - 6.0_dp*e3 + 8.0_dp*e4 - 3.0_dp*e5)      ! T prints "b e^3"; K and sympy give 6
    h(3) = 0.5_dp*l*l*(e2 - 3.0_dp*e3 + 3.0_dp*e4 - e5)
    h(4) = 10.0_dp*e3 - 15.0_dp*e4 + 6.0_dp*e5
    h(5) = l*(-4.0_dp*e3 + 7.0_dp*e4 - 3.0_dp*e5)
    h(6) = 0.5_dp*l*l*(e3 - 2.0_dp*e4 + e5)
    if (present(hx)) then
      hx(1) = (-30.0_dp*e2 + 60.0_dp*e3 - 30.0_dp*e4)/l
      hx(2) = 1.0_dp - 18.0_dp*e2 + 32.0_dp*e3 - 15.0_dp*e4
      hx(3) = 0.5_dp*l*(2.0_dp*e - 9.0_dp*e2 + 12.0_dp*e3 - 5.0_dp*e4)
      hx(4) = -hx(1)
      hx(5) = -12.0_dp*e2 + 28.0_dp*e3 - 15.0_dp*e4
      hx(6) = 0.5_dp*l*(3.0_dp*e2 - 8.0_dp*e3 + 5.0_dp*e4)
    end if
    if (present(hxx)) then
      hxx(1) = (-60.0_dp*e + 180.0_dp*e2 - 120.0_dp*e3)/(l*l)
      hxx(2) = (-36.0_dp*e + 96.0_dp*e2 - 60.0_dp*e3)/l
      hxx(3) = 0.5_dp*(2.0_dp - 18.0_dp*e + 36.0_dp*e2 - 20.0_dp*e3)
      hxx(4) = -hxx(1)
      hxx(5) = (-24.0_dp*e + 84.0_dp*e2 - 60.0_dp*e3)/l
      hxx(6) = 0.5_dp*(6.0_dp*e - 24.0_dp*e2 + 20.0_dp*e3)
    end if
    if (present(hxxx)) then
      hxxx(1) = (-60.0_dp + 360.0_dp*e - 360.0_dp*e2)/(l*l*l)
      hxxx(2) = (-36.0_dp + 192.0_dp*e - 180.0_dp*e2)/(l*l)
      hxxx(3) = 0.5_dp*(-18.0_dp + 72.0_dp*e - 60.0_dp*e2)/l
      hxxx(4) = -hxxx(1)
      hxxx(5) = (-24.0_dp + 168.0_dp*e - 180.0_dp*e2)/(l*l)
      hxxx(6) = 0.5_dp*(6.0_dp - 48.0_dp*e + 60.0_dp*e2)/l
    end if
  end subroutine quintic_hermite

  !> n(1:2) = (1 - e, e) and dn/dx (T20, K27).
  pure subroutine linear_lagrange(e, l, n, nx)
    real(dp), intent(in) :: e, l
    real(dp), intent(out) :: n(2)
    real(dp), intent(out), optional :: nx(2)
    n(1) = 1.0_dp - e
    n(2) = e
    if (present(nx)) then
      nx(1) = -1.0_dp/l
      nx(2) = 1.0_dp/l
    end if
  end subroutine linear_lagrange
end module shape_functions
