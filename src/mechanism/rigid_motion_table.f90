!> The rigid-body motion of every element of a linkage tabulated over one
!> crank revolution.  It depends on the crank angle only, so it is solved once
!> at n_points equally spaced crank angles: each element's end-1 position and
!> inclination P = (X1, Y1, phi) with dP/dtheta and d2P/dtheta2, interpolated
!> by quintic Hermite polynomials (error O(h^6): 1e-12 relative at 720
!> points) and turned into time derivatives with the driver's theta_dot,
!> theta_ddot.  This takes the kinematic Newton solves out of a model's
!> right-hand side; a toggle or a failure to assemble is found while
!> tabulating, naming the crank angle.  Any model about the rigid motion of a
!> linkage (transient, steady, periodic) can own one.
module rigid_motion_table
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use linkage, only: driver_t, driver_angle
  use kinematics, only: kinematics_t, motion_t
  use shape_functions, only: quintic_hermite
  implicit none
  private
  public :: motion_table_t

  !> The table's points, rates and turns hold together: private, read
  !> through motion_at only.
  type :: motion_table_t
    private
    integer :: n_table = 0                        !< intervals per revolution
    real(dp) :: theta_start = 0.0_dp              !< crank angle of the first table point
    real(dp), allocatable :: p(:, :, :)           !< (3, 0:n_table, element): X1, Y1, phi
    real(dp), allocatable :: dp1(:, :, :)         !< d/dtheta
    real(dp), allocatable :: ddp(:, :, :)         !< d2/dtheta2
    real(dp), allocatable :: phi_per_turn(:)      !< phi gained per crank revolution (0 or +-2 pi)
  contains
    procedure, public :: build
    procedure, public :: motion_at
  end type motion_table_t

contains

  !> Tabulate the rigid-body motion of kin's n_elements elements over one
  !> crank revolution from the driver's angle at t = 0.  Fails (err) where the
  !> kinematics fails, naming the crank angle.
  subroutine build(self, kin, n_elements, n_points, err)
    class(motion_table_t), intent(out) :: self
    type(kinematics_t), intent(inout) :: kin
    integer, intent(in) :: n_elements, n_points
    type(error_t), intent(inout) :: err
    real(dp) :: theta, theta_d, theta_dd, h
    type(motion_t) :: m
    integer :: k, e
    call driver_angle(kin%mech%driver, 0.0_dp, theta, theta_d, theta_dd)
    self%theta_start = theta
    self%n_table = n_points
    h = two_pi/n_points
    allocate(self%p(3, 0:n_points, n_elements), self%dp1(3, 0:n_points, n_elements), &
             self%ddp(3, 0:n_points, n_elements), self%phi_per_turn(n_elements))
    do k = 0, n_points
      ! theta_d = 1, theta_dd = 0: the rates are then d/dtheta and d2/dtheta2
      call kin%solve_angle(self%theta_start + k*h, 1.0_dp, 0.0_dp, err)
      if (err%failed()) then
        call err%add_context('tabulating the rigid-body motion over a revolution')
        return
      end if
      do e = 1, n_elements
        m = kin%element_motion_global(e)
        self%p(:, k, e) = [m%x1, m%y1, m%phi]
        self%dp1(:, k, e) = [m%x1_d, m%y1_d, m%phi_d]
        self%ddp(:, k, e) = [m%x1_dd, m%y1_dd, m%phi_dd]
      end do
    end do
    do e = 1, n_elements
      self%phi_per_turn(e) = two_pi*anint((self%p(3, n_points, e) - self%p(3, 0, e))/two_pi)
    end do
  end subroutine build

  !> Every element's rigid motion (position, rates, accelerations) at time t
  !> of the driver: quintic Hermite interpolation in the crank angle, chain
  !> rule for the time derivatives.
  subroutine motion_at(self, driver, t, m)
    class(motion_table_t), intent(in) :: self
    type(driver_t), intent(in) :: driver
    real(dp), intent(in) :: t
    type(motion_t), intent(inout) :: m(:)
    real(dp) :: theta, theta_d, theta_dd, h, x, turns, hw(6), hx(6), hxx(6), p(3), dp1(3), ddp(3)
    integer :: k, e
    call driver_angle(driver, t, theta, theta_d, theta_dd)
    h = two_pi/self%n_table
    turns = aint((theta - self%theta_start)/two_pi)
    x = theta - self%theta_start - turns*two_pi        ! in (-2 pi, 2 pi)
    if (x < 0.0_dp) then
      turns = turns - 1.0_dp
      x = x + two_pi
    end if
    ! the deck's ranges keep theta moderate; the clamp keeps the index in the
    ! table whatever rounding does at the ends of a turn
    k = max(0, min(int(x/h), self%n_table - 1))
    x = x - k*h
    call quintic_hermite(x/h, h, hw, hx, hxx)
    do e = 1, size(m)
      p = hw(1)*self%p(:, k, e) + hw(2)*self%dp1(:, k, e) + hw(3)*self%ddp(:, k, e) + &
          hw(4)*self%p(:, k + 1, e) + hw(5)*self%dp1(:, k + 1, e) + hw(6)*self%ddp(:, k + 1, e)
      dp1 = hx(1)*self%p(:, k, e) + hx(2)*self%dp1(:, k, e) + hx(3)*self%ddp(:, k, e) + &
            hx(4)*self%p(:, k + 1, e) + hx(5)*self%dp1(:, k + 1, e) + hx(6)*self%ddp(:, k + 1, e)
      ddp = hxx(1)*self%p(:, k, e) + hxx(2)*self%dp1(:, k, e) + hxx(3)*self%ddp(:, k, e) + &
            hxx(4)*self%p(:, k + 1, e) + hxx(5)*self%dp1(:, k + 1, e) + hxx(6)*self%ddp(:, k + 1, e)
      p(3) = p(3) + turns*self%phi_per_turn(e)
      m(e)%x1 = p(1)
      m(e)%y1 = p(2)
      m(e)%phi = p(3)
      m(e)%x1_d = dp1(1)*theta_d
      m(e)%y1_d = dp1(2)*theta_d
      m(e)%phi_d = dp1(3)*theta_d
      m(e)%x1_dd = ddp(1)*theta_d**2 + dp1(1)*theta_dd
      m(e)%y1_dd = ddp(2)*theta_d**2 + dp1(2)*theta_dd
      m(e)%phi_dd = ddp(3)*theta_d**2 + dp1(3)*theta_dd
    end do
  end subroutine motion_at
end module rigid_motion_table
