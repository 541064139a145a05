!> External loads of the spatial analysis (deck group &spatial_loads, read by
!> spatial_loads_settings; doc/spatial.md, "Loads"): gravity along a direction, and constant point
!> forces and moments at the joints B, C and at nodes of the links; and the
!> choice of a static start.
!>
!> Gravity is a uniform acceleration field: the elements feel it as an
!> extra acceleration -g of their reference frames (the body force
!> -rho A (a_rigid - g)), so it loads the distributed and the rotary masses
!> consistently and passes the stiffening of the axial force it causes.  A
!> point force is dead (fixed global direction) and works through the
!> node's translation; a moment works through the node's small rotation.
!> Positions are fractions of a link's length from its end 1 (crank from A,
!> coupler from B, rocker from D) and must fall on a node (link_n_elements
!> places the nodes).  A component on a held unknown does no work (the
!> coupler's twist at B, or at the universal joint).
module spatial_external_loads
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value
  implicit none
  private
  public :: spatial_point_load_t, spatial_loads_input_t, resolve_spatial_loads, max_spatial_loads, load_link_names

  integer, parameter :: max_spatial_loads = 20

  !> A point load resolved to an element end: force (global X, Y, Z, lb) and
  !> moment (global, lb in).
  type :: spatial_point_load_t
    integer :: element = 0
    integer :: node = 1                    !< 1: the element's end 1, 2: its end 2
    real(dp) :: force(3) = 0.0_dp
    real(dp) :: moment(3) = 0.0_dp
  end type spatial_point_load_t

  !> The group as given, with the documented defaults (doc/spatial.md): no
  !> gravity, no loads, the start of &transient.  Read, checked and echoed by
  !> src/analysis/spatial_loads_settings.f90.
  type :: spatial_loads_input_t
    real(dp) :: gravity_g = 0.0_dp
    real(dp) :: gravity_direction(3) = [0.0_dp, 0.0_dp, -1.0_dp]
    logical :: initial_static = .false.
    integer :: n_loads = 0
    character(len=16) :: load_joint(max_spatial_loads) = '', load_link(max_spatial_loads) = ''
    real(dp) :: load_position(max_spatial_loads) = 1.0_dp
    real(dp) :: load_force(3, max_spatial_loads) = 0.0_dp, load_moment(3, max_spatial_loads) = 0.0_dp
  end type spatial_loads_input_t

  character(len=*), parameter :: g = 'spatial_loads'
  character(len=16), parameter :: load_link_names(3) = [character(len=16) :: 'crank', 'coupler', 'rocker']

contains

  !> The loads on the elements: gravity vector (in/s^2) and point loads.
  !> n_elements(k), first_element(k): the links' elements.  A position off the
  !> nodes, or on a support (crank at A, rocker at D), is an input error.
  subroutine resolve_spatial_loads(deck, inp, n_elements, first_element, gravity, point_loads, err)
    type(deck_t), intent(in) :: deck
    type(spatial_loads_input_t), intent(in) :: inp
    integer, intent(in) :: n_elements(3), first_element(3)
    real(dp), intent(out) :: gravity(3)
    type(spatial_point_load_t), allocatable, intent(out) :: point_loads(:)
    type(error_t), intent(inout) :: err
    integer :: k, lk, node
    real(dp) :: s, xn
    gravity = 0.0_dp
    if (inp%gravity_g > 0.0_dp) gravity = inp%gravity_g*inp%gravity_direction/norm2(inp%gravity_direction)
    allocate(point_loads(inp%n_loads))
    do k = 1, inp%n_loads
      call load_place(inp, k, lk, s)
      xn = s*n_elements(lk)
      node = nint(xn)
      if (abs(xn - node) > 1.0e-9_dp) then
        call invalid_value(deck, g, 'load_position('//str(k)//')', str(s), 'is not at a node of the '// &
                           trim(load_link_names(lk))//' ('//str(n_elements(lk))//' elements): loads act at nodes; '// &
                           'choose link_n_elements to place one there', err)
        return
      end if
      if (node == 0 .and. lk /= 2) then
        call invalid_value(deck, g, 'load_position('//str(k)//')', str(s), 'is the '//trim(load_link_names(lk))// &
                           '''s support, which takes the load directly: give a position > 0', err)
        return
      end if
      ! node j of a link: end 2 of its element j, or end 1 of its first element
      point_loads(k)%element = first_element(lk) + max(node, 1) - 1
      point_loads(k)%node = merge(1, 2, node == 0)
      point_loads(k)%force = inp%load_force(:, k)
      point_loads(k)%moment = inp%load_moment(:, k)
    end do
  end subroutine resolve_spatial_loads

  !> Link (1 crank, 2 coupler, 3 rocker) and position of load k: a joint is
  !> the end of the link named with it, by default the crank's at B and the
  !> rocker's at C.
  subroutine load_place(inp, k, lk, s)
    type(spatial_loads_input_t), intent(in) :: inp
    integer, intent(in) :: k
    integer, intent(out) :: lk
    real(dp), intent(out) :: s
    lk = findloc(load_link_names, inp%load_link(k), 1)
    s = inp%load_position(k)
    select case (trim(inp%load_joint(k)))
    case ('B')
      if (lk == 0) lk = 1
      s = merge(1.0_dp, 0.0_dp, lk == 1)
    case ('C')
      if (lk == 0) lk = 3
      s = 1.0_dp
    end select
  end subroutine load_place

end module spatial_external_loads
