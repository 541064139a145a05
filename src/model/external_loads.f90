!> External loads of the transient model: gravity and point forces and
!> moments at joints or link points, constant or scaled by a time table.
!> The loads as a deck gives them (loads_input_t, with their documented
!> defaults) are read by the analysis layer (loads_settings, the group
!> &loads, doc/decks.md) and resolved here onto the elements.
!>
!> A point force is dead (fixed global direction), its work f . r(x); a
!> moment works through the section angle.  Gravity acts on the distributed
!> and the joint masses.  Positions on a link are fractions of its length
!> from end 1; a load at a joint acts on the first link end listed there
!> (the translations of a pin are shared, so any end gives the same force;
!> a moment at a pin acts on that link).
module external_loads
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use linkage, only: mechanism_t
  implicit none
  private
  public :: point_load_t, load_factor_at, loads_input_t, resolve_loads
  public :: max_loads, max_load_points

  integer, parameter :: max_loads = 20, max_load_points = 100

  !> A point load resolved to an element.
  type :: point_load_t
    integer :: element = 0
    real(dp) :: x_over_l = 0.0_dp          !< position in the element, 0..1
    real(dp) :: force(2) = 0.0_dp          !< global X, Y
    real(dp) :: moment = 0.0_dp            !< counter-clockwise
    real(dp), allocatable :: times(:)      !< time table (empty: constant)
    real(dp), allocatable :: factors(:)    !< factor at those times
  end type point_load_t

  !> The loads as given (the group &loads); the default initialisation is
  !> the documented defaults (doc/decks.md): no gravity, no loads.
  type :: loads_input_t
    real(dp) :: gravity_g = 0.0_dp
    real(dp) :: gravity_direction(2) = [0.0_dp, -1.0_dp]
    integer :: n_loads = 0
    character(len=16) :: load_joint(max_loads) = ''
    character(len=16) :: load_link(max_loads) = ''
    real(dp) :: load_position(max_loads) = 1.0_dp
    real(dp) :: load_fx(max_loads) = 0.0_dp
    real(dp) :: load_fy(max_loads) = 0.0_dp
    real(dp) :: load_moment(max_loads) = 0.0_dp
    integer :: load_n_points(max_loads) = 0
    real(dp) :: load_time(max_load_points, max_loads) = 0.0_dp
    real(dp) :: load_factor(max_load_points, max_loads) = 0.0_dp
  end type loads_input_t

contains

  !> Factor of a load at time t: 1 without a table, else piecewise linear
  !> in the table, held at the end values outside it.
  pure real(dp) function load_factor_at(load, t) result(f)
    type(point_load_t), intent(in) :: load
    real(dp), intent(in) :: t
    integer :: k, n
    f = 1.0_dp
    if (.not. allocated(load%times)) return
    n = size(load%times)
    if (n == 0) return
    if (t <= load%times(1)) then
      f = load%factors(1)
      return
    end if
    do k = 2, n
      if (t <= load%times(k)) then
        f = load%factors(k - 1) + (load%factors(k) - load%factors(k - 1))*(t - load%times(k - 1)) &
            /(load%times(k) - load%times(k - 1))
        return
      end if
    end do
    f = load%factors(n)
  end function load_factor_at

  !> The loads of the deck on the elements of the mechanism, and the gravity vector.
  subroutine resolve_loads(inp, mech, gravity, point_loads, err)
    type(loads_input_t), intent(in) :: inp
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(out) :: gravity(2)
    type(point_load_t), allocatable, intent(out) :: point_loads(:)
    type(error_t), intent(inout) :: err
    integer :: k, j, lk, ie, m
    real(dp) :: s, xe
    gravity = 0.0_dp
    if (inp%gravity_g > 0.0_dp) gravity = inp%gravity_g*inp%gravity_direction/norm2(inp%gravity_direction)
    allocate(point_loads(inp%n_loads))
    do k = 1, inp%n_loads
      if (len_trim(inp%load_joint(k)) > 0) then
        j = findloc([(mech%joints(m)%name, m = 1, mech%n_joints)], inp%load_joint(k), 1)
        if (j == 0) then
          call err%set('point load', 'load_joint('//str(k)//') = '''//trim(inp%load_joint(k))//''' is not a joint')
          return
        end if
        lk = mech%joints(j)%link(1)
        s = merge(0.0_dp, 1.0_dp, mech%joints(j)%link_end(1) == 1)
      else
        lk = findloc([(mech%links(m)%name, m = 1, mech%n_links)], inp%load_link(k), 1)
        if (lk == 0) then
          call err%set('point load', 'load_link('//str(k)//') = '''//trim(inp%load_link(k))//''' is not a link')
          return
        end if
        s = inp%load_position(k)
      end if
      ! element of the link holding fraction s, and the position in it
      xe = s*mech%links(lk)%n_elements
      ie = min(int(xe), mech%links(lk)%n_elements - 1)
      point_loads(k)%element = mech%links(lk)%first_element + ie
      point_loads(k)%x_over_l = xe - ie
      point_loads(k)%force = [inp%load_fx(k), inp%load_fy(k)]
      point_loads(k)%moment = inp%load_moment(k)
      m = inp%load_n_points(k)
      point_loads(k)%times = inp%load_time(1:m, k)
      point_loads(k)%factors = inp%load_factor(1:m, k)
    end do
  end subroutine resolve_loads
end module external_loads

