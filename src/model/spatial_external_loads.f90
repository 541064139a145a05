!> External loads of the spatial analysis (deck group &spatial_loads,
!> doc/spatial.md, "Loads"): gravity along a direction, and constant point
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
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  implicit none
  private
  public :: spatial_point_load_t, spatial_loads_input_t, read_spatial_loads, resolve_spatial_loads, &
            spatial_loads_group, max_spatial_loads

  integer, parameter :: max_spatial_loads = 20

  !> A point load resolved to an element end: force (global X, Y, Z, lb) and
  !> moment (global, lb in).
  type :: spatial_point_load_t
    integer :: element = 0
    integer :: node = 1                    !< 1: the element's end 1, 2: its end 2
    real(dp) :: force(3) = 0.0_dp
    real(dp) :: moment(3) = 0.0_dp
  end type spatial_point_load_t

  !> The group as given; the defaults are those of set_defaults.
  type :: spatial_loads_input_t
    real(dp) :: gravity_g
    real(dp) :: gravity_direction(3)
    logical :: initial_static
    integer :: n_loads
    character(len=16) :: load_joint(max_spatial_loads), load_link(max_spatial_loads)
    real(dp) :: load_position(max_spatial_loads)
    real(dp) :: load_force(3, max_spatial_loads), load_moment(3, max_spatial_loads)
  end type spatial_loads_input_t

  ! namelist staging variables
  real(dp) :: gravity_g, gravity_direction(3), load_position(max_spatial_loads)
  real(dp) :: load_force(3, max_spatial_loads), load_moment(3, max_spatial_loads)
  logical :: initial_static
  integer :: n_loads
  character(len=16) :: load_joint(max_spatial_loads), load_link(max_spatial_loads)
  namelist /spatial_loads/ gravity_g, gravity_direction, initial_static, n_loads, load_joint, load_link, &
    load_position, load_force, load_moment

  character(len=*), parameter :: g = 'spatial_loads'
  character(len=16), parameter :: link_choices(3) = [character(len=16) :: 'crank', 'coupler', 'rocker']

contains

  !> Read and check &spatial_loads (optional; without it: no loads, the start of &transient).
  subroutine read_spatial_loads(deck, inp, found, err)
    type(deck_t), intent(inout) :: deck
    type(spatial_loads_input_t), intent(out) :: inp
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    integer :: k, n
    real(dp) :: flat(3*max_spatial_loads)
    call set_defaults()
    call deck%read_group(g, spatial_loads_group, .false., found, err)
    if (err%failed()) return
    inp = spatial_loads_input_t(gravity_g, gravity_direction, initial_static, n_loads, load_joint, load_link, &
                                load_position, load_force, load_moment)
    call check_real(deck, g, 'gravity_g', inp%gravity_g, err, at_least=0.0_dp, at_most=1.0e6_dp, &
                    why='the magnitude of the gravity acceleration (386.09 in/s^2)')
    call check_reals(deck, g, 'gravity_direction', inp%gravity_direction, err, at_least=-1.0e6_dp, at_most=1.0e6_dp)
    if (.not. err%failed() .and. inp%gravity_g > 0.0_dp) then
      if (.not. norm2(inp%gravity_direction) > 1.0e-12_dp) &
        call invalid_value(deck, g, 'gravity_direction', str(norm2(inp%gravity_direction)), &
                           'must be a nonzero direction when gravity_g > 0', err)
    end if
    call check_integer(deck, g, 'n_loads', inp%n_loads, err, at_least=0, at_most=max_spatial_loads)
    if (err%failed()) return
    n = inp%n_loads
    call check_reals(deck, g, 'load_position', inp%load_position(1:n), err, at_least=0.0_dp, at_most=1.0_dp, &
                     why='a fraction of the link length from its end 1')
    flat(1:3*n) = reshape(inp%load_force(:, 1:n), [3*n])
    call check_reals(deck, g, 'load_force', flat(1:3*n), err, at_least=-1.0e12_dp, at_most=1.0e12_dp)
    flat(1:3*n) = reshape(inp%load_moment(:, 1:n), [3*n])
    call check_reals(deck, g, 'load_moment', flat(1:3*n), err, at_least=-1.0e12_dp, at_most=1.0e12_dp)
    do k = 1, n
      if (err%failed()) return
      if (len_trim(inp%load_joint(k)) > 0) &
        call check_choice(deck, g, 'load_joint', inp%load_joint(k), [character(len=16) :: 'B', 'C'], err)
      if (len_trim(inp%load_link(k)) > 0) call check_choice(deck, g, 'load_link', inp%load_link(k), link_choices, err)
      if (err%failed()) return
      if (len_trim(inp%load_joint(k)) == 0 .and. len_trim(inp%load_link(k)) == 0) then
        call invalid_value(deck, g, 'load_link('//str(k)//')', '''''', 'give load_joint (B or C) or load_link '// &
                           '(crank, coupler or rocker, with load_position) for every load', err)
      else if (inp%load_joint(k) == 'B' .and. inp%load_link(k) == 'rocker') then
        call invalid_value(deck, g, 'load_link('//str(k)//')', 'rocker', 'joint B joins the crank and the coupler', err)
      else if (inp%load_joint(k) == 'C' .and. inp%load_link(k) == 'crank') then
        call invalid_value(deck, g, 'load_link('//str(k)//')', 'crank', 'joint C joins the coupler and the rocker', err)
      end if
    end do
  end subroutine read_spatial_loads

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
                           trim(link_choices(lk))//' ('//str(n_elements(lk))//' elements): loads act at nodes; '// &
                           'choose link_n_elements to place one there', err)
        return
      end if
      if (node == 0 .and. lk /= 2) then
        call invalid_value(deck, g, 'load_position('//str(k)//')', str(s), 'is the '//trim(link_choices(lk))// &
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
    lk = findloc(link_choices, inp%load_link(k), 1)
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

  !> The documented defaults (doc/spatial.md): no gravity, no loads, the start of &transient.
  subroutine set_defaults()
    gravity_g = 0.0_dp
    gravity_direction = [0.0_dp, 0.0_dp, -1.0_dp]
    initial_static = .false.
    n_loads = 0
    load_joint = ''
    load_link = ''
    load_position = 1.0_dp
    load_force = 0.0_dp
    load_moment = 0.0_dp
  end subroutine set_defaults

  !> The &spatial_loads group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine spatial_loads_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=spatial_loads, delim='apostrophe')
    else
      read(r%unit, nml=spatial_loads, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine spatial_loads_group
end module spatial_external_loads
