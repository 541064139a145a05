!> The &spatial_loads group of a spatial deck: gravity, point forces and
!> moments, the static start (doc/spatial.md, "Loads").  The loads
!> themselves, spatial_loads_input_t with its documented defaults, belong to
!> the spatial model (spatial_external_loads); this module reads, checks and
!> echoes the group.
module spatial_loads_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  use spatial_external_loads, only: spatial_loads_input_t, max_spatial_loads, load_link_names
  implicit none
  private
  public :: read_spatial_loads, echo_spatial_loads

  ! staging variables of &spatial_loads
  real(dp) :: gravity_g, gravity_direction(3), load_position(max_spatial_loads)
  real(dp) :: load_force(3, max_spatial_loads), load_moment(3, max_spatial_loads)
  logical :: initial_static
  integer :: n_loads
  character(len=16) :: load_joint(max_spatial_loads), load_link(max_spatial_loads)
  namelist /spatial_loads/ gravity_g, gravity_direction, initial_static, n_loads, load_joint, load_link, &
    load_position, load_force, load_moment

  character(len=*), parameter :: g = 'spatial_loads'

contains

  !> Read and check &spatial_loads (optional; without it: no loads, the start of &transient).
  subroutine read_spatial_loads(deck, inp, found, err)
    type(deck_t), intent(inout) :: deck
    type(spatial_loads_input_t), intent(out) :: inp
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    integer :: k, n
    real(dp) :: flat(3*max_spatial_loads)
    type(spatial_loads_input_t) :: defaults
    call stage_from(defaults)
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
      if (len_trim(inp%load_link(k)) > 0) call check_choice(deck, g, 'load_link', inp%load_link(k), load_link_names, err)
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

  !> Echo &spatial_loads when the deck gives it.
  subroutine echo_spatial_loads(inp, out)
    type(spatial_loads_input_t), intent(in) :: inp
    type(table_t), intent(inout) :: out
    call stage_from(inp)
    call out%echo_group(spatial_loads_group)
  end subroutine echo_spatial_loads

  !> The namelist variables from the loads (the defaults before a read).
  subroutine stage_from(inp)
    type(spatial_loads_input_t), intent(in) :: inp
    gravity_g = inp%gravity_g
    gravity_direction = inp%gravity_direction
    initial_static = inp%initial_static
    n_loads = inp%n_loads
    load_joint = inp%load_joint
    load_link = inp%load_link
    load_position = inp%load_position
    load_force = inp%load_force
    load_moment = inp%load_moment
  end subroutine stage_from

  !> The &spatial_loads group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine spatial_loads_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=spatial_loads, delim='apostrophe')
    else
      read(r%unit, nml=spatial_loads, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine spatial_loads_group
end module spatial_loads_settings
