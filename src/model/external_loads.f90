!> External loads of the transient model: gravity and point forces and
!> moments at joints or link points, constant or scaled by a time table
!> (deck group &loads, doc/mechanism_deck.md).
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
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer
  use linkage, only: mechanism_t
  implicit none
  private
  public :: point_load_t, load_factor_at, loads_input_t, read_loads, resolve_loads, loads_group
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

  !> The &loads group as given; the defaults are those of set_defaults.
  type :: loads_input_t
    real(dp) :: gravity_g
    real(dp) :: gravity_direction(2)
    integer :: n_loads
    character(len=16) :: load_joint(max_loads)
    character(len=16) :: load_link(max_loads)
    real(dp) :: load_position(max_loads)
    real(dp) :: load_fx(max_loads)
    real(dp) :: load_fy(max_loads)
    real(dp) :: load_moment(max_loads)
    integer :: load_n_points(max_loads)
    real(dp) :: load_time(max_load_points, max_loads)
    real(dp) :: load_factor(max_load_points, max_loads)
  end type loads_input_t

  ! namelist staging variables
  real(dp) :: gravity_g, gravity_direction(2), load_position(max_loads), load_fx(max_loads), load_fy(max_loads)
  real(dp) :: load_moment(max_loads), load_time(max_load_points, max_loads), load_factor(max_load_points, max_loads)
  integer :: n_loads, load_n_points(max_loads)
  character(len=16) :: load_joint(max_loads), load_link(max_loads)
  namelist /loads/ gravity_g, gravity_direction, n_loads, load_joint, load_link, load_position, load_fx, load_fy, &
    load_moment, load_n_points, load_time, load_factor

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

  !> Read and check &loads (optional group; without it: no loads).
  subroutine read_loads(deck, inp, err)
    type(deck_t), intent(inout) :: deck
    type(loads_input_t), intent(out) :: inp
    type(error_t), intent(inout) :: err
    logical :: found
    integer :: k, n
    character(len=*), parameter :: g = 'loads'
    call set_defaults()
    call deck%read_group(g, loads_group, .false., found, err)
    if (err%failed()) return
    inp = loads_input_t(gravity_g, gravity_direction, n_loads, load_joint, load_link, load_position, load_fx, &
                        load_fy, load_moment, load_n_points, load_time, load_factor)
    call check_real(deck, g, 'gravity_g', inp%gravity_g, err, at_least=0.0_dp, at_most=1.0e6_dp, &
                    why='the magnitude of the gravity acceleration (9.81 m/s^2, 386.09 in/s^2)')
    call check_reals(deck, g, 'gravity_direction', inp%gravity_direction, err, at_least=-1.0e6_dp, at_most=1.0e6_dp)
    if (.not. err%failed() .and. inp%gravity_g > 0.0_dp .and. .not. norm2(inp%gravity_direction) > 0.0_dp) &
      call invalid_value(deck, g, 'gravity_direction', str(inp%gravity_direction(1))//', '// &
                         str(inp%gravity_direction(2)), 'must be a nonzero vector when gravity_g > 0', err)
    call check_integer(deck, g, 'n_loads', inp%n_loads, err, at_least=0, at_most=max_loads)
    if (err%failed()) return
    n = inp%n_loads
    call check_reals(deck, g, 'load_position', inp%load_position(1:n), err, at_least=0.0_dp, at_most=1.0_dp, &
                     why='a fraction of the link length from its end 1')
    call check_reals(deck, g, 'load_fx', inp%load_fx(1:n), err, at_least=-1.0e12_dp, at_most=1.0e12_dp)
    call check_reals(deck, g, 'load_fy', inp%load_fy(1:n), err, at_least=-1.0e12_dp, at_most=1.0e12_dp)
    call check_reals(deck, g, 'load_moment', inp%load_moment(1:n), err, at_least=-1.0e12_dp, at_most=1.0e12_dp)
    do k = 1, n
      call check_integer(deck, g, 'load_n_points('//str(k)//')', inp%load_n_points(k), err, at_least=0, &
                         at_most=max_load_points, why='0 = constant load, else the points of its time table')
      if (err%failed()) return
      associate (m => inp%load_n_points(k))
        call check_reals(deck, g, 'load_time(:,'//str(k)//')', inp%load_time(1:m, k), err, at_least=0.0_dp, &
                         at_most=1.0e9_dp)
        call check_reals(deck, g, 'load_factor(:,'//str(k)//')', inp%load_factor(1:m, k), err, &
                         at_least=-1.0e9_dp, at_most=1.0e9_dp)
        if (.not. err%failed() .and. m > 1) then
          if (any(inp%load_time(2:m, k) <= inp%load_time(1:m - 1, k))) &
            call invalid_value(deck, g, 'load_time(:,'//str(k)//')', 'not increasing', &
                               'the times of a load table must increase strictly', err)
        end if
      end associate
      if (err%failed()) return
      if (len_trim(inp%load_joint(k)) == 0 .eqv. len_trim(inp%load_link(k)) == 0) then
        call invalid_value(deck, g, 'load_joint('//str(k)//')', ''''//trim(inp%load_joint(k))//'''', &
                           'give either load_joint or load_link (with load_position) for every load', err)
        return
      end if
    end do
  end subroutine read_loads

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

  !> The documented defaults (doc/mechanism_deck.md), on the namelist variables:
  !> no gravity, no loads.
  subroutine set_defaults()
    gravity_g = 0.0_dp
    gravity_direction = [0.0_dp, -1.0_dp]
    n_loads = 0
    load_joint = ''
    load_link = ''
    load_position = 1.0_dp
    load_fx = 0.0_dp
    load_fy = 0.0_dp
    load_moment = 0.0_dp
    load_n_points = 0
    load_time = 0.0_dp
    load_factor = 0.0_dp
  end subroutine set_defaults

  !> The &loads group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine loads_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=loads, delim='apostrophe')
    else
      read(r%unit, nml=loads, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine loads_group
end module external_loads
