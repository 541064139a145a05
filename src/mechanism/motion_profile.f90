!> A prescribed joint motion v(t) with its first two derivatives: constant
!> rate, the spin-up profile of &mechanism (module linkage, driver_angle), or
!> a table of values against time interpolated by a natural cubic spline (C2:
!> value, slope and curvature continuous at the knots, zero curvature at the
!> two ends; de Boor, "A Practical Guide to Splines" (1978)).
module motion_profile
  use kinds, only: dp
  use linkage, only: driver_t, driver_angle, profile_constant, profile_spinup
  implicit none
  private
  public :: motion_profile_t, motion_constant, motion_spinup, motion_table, motion_names
  public :: make_spline, motion_value

  integer, parameter :: motion_constant = 1, motion_spinup = 2, motion_table = 3
  character(len=8), parameter :: motion_names(3) = [character(len=8) :: 'constant', 'spinup', 'table']

  type :: motion_profile_t
    integer :: kind = motion_constant
    real(dp) :: start = 0.0_dp        !< value at t = 0 (constant, spinup)
    real(dp) :: rate = 0.0_dp         !< rate (final rate for spinup)
    real(dp) :: spinup_time = 0.0_dp
    real(dp), allocatable :: t(:), v(:), m(:)   !< table knots, values, second derivatives
  end type motion_profile_t

contains

  !> A table profile: knots t (strictly increasing), values v; the natural
  !> spline's second derivatives by the tridiagonal (Thomas) solve.
  pure subroutine make_spline(t, v, p)
    real(dp), intent(in) :: t(:), v(:)
    type(motion_profile_t), intent(out) :: p
    integer :: n, i
    real(dp) :: h0, h1, w
    real(dp), allocatable :: diag(:), rhs(:), upper(:)
    n = size(t)
    p%kind = motion_table
    p%t = t
    p%v = v
    allocate(p%m(n), diag(n), rhs(n), upper(n))
    p%m = 0.0_dp
    if (n < 3) return
    ! rows i = 2..n-1: h0 m(i-1) + 2 (h0 + h1) m(i) + h1 m(i+1) = 6 (slope difference)
    diag = 1.0_dp
    upper = 0.0_dp
    rhs = 0.0_dp
    do i = 2, n - 1
      h0 = t(i) - t(i - 1)
      h1 = t(i + 1) - t(i)
      w = h0/diag(i - 1)          ! (row 1 is m(1) = 0: upper(1) = rhs(1) = 0)
      diag(i) = 2.0_dp*(h0 + h1) - w*upper(i - 1)
      upper(i) = h1
      rhs(i) = 6.0_dp*((v(i + 1) - v(i))/h1 - (v(i) - v(i - 1))/h0) - w*rhs(i - 1)
    end do
    do i = n - 1, 2, -1
      p%m(i) = (rhs(i) - upper(i)*p%m(i + 1))/diag(i)
    end do
  end subroutine make_spline

  !> v(t), v'(t), v''(t).  A table is held at its end values outside its
  !> range (the kinematics analysis refuses a run that leaves it).
  pure subroutine motion_value(p, t, v, vd, vdd)
    type(motion_profile_t), intent(in) :: p
    real(dp), intent(in) :: t
    real(dp), intent(out) :: v, vd, vdd
    type(driver_t) :: drv
    integer :: i, n
    real(dp) :: h, a, b
    select case (p%kind)
    case (motion_table)
      n = size(p%t)
      if (t <= p%t(1) .or. t >= p%t(n)) then
        v = merge(p%v(1), p%v(n), t <= p%t(1))
        vd = 0.0_dp
        vdd = 0.0_dp
        if (t < p%t(1) .or. t > p%t(n)) return
      end if
      i = 1
      do while (i < n - 1 .and. t > p%t(i + 1))
        i = i + 1
      end do
      h = p%t(i + 1) - p%t(i)
      a = (p%t(i + 1) - t)/h
      b = 1.0_dp - a
      v = a*p%v(i) + b*p%v(i + 1) + ((a**3 - a)*p%m(i) + (b**3 - b)*p%m(i + 1))*h*h/6.0_dp
      vd = (p%v(i + 1) - p%v(i))/h + ((1.0_dp - 3.0_dp*a*a)*p%m(i) + (3.0_dp*b*b - 1.0_dp)*p%m(i + 1))*h/6.0_dp
      vdd = a*p%m(i) + b*p%m(i + 1)
    case default
      drv%omega = p%rate
      drv%theta0 = p%start
      drv%spinup_time = p%spinup_time
      drv%profile = merge(profile_spinup, profile_constant, p%kind == motion_spinup)
      call driver_angle(drv, t, v, vd, vdd)
    end select
  end subroutine motion_value
end module motion_profile
