!> The &loads group of a transient deck: gravity and point loads
!> (doc/decks.md).  The loads themselves, loads_input_t with its documented
!> defaults, belong to the model (external_loads); this module reads,
!> checks and echoes the group.
module loads_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer
  use table_output, only: table_t
  use external_loads, only: loads_input_t, max_loads, max_load_points
  implicit none
  private
  public :: read_loads, echo_loads

  ! staging variables of &loads
  real(dp) :: gravity_g, gravity_direction(2), load_position(max_loads), load_fx(max_loads), load_fy(max_loads)
  real(dp) :: load_moment(max_loads), load_time(max_load_points, max_loads), load_factor(max_load_points, max_loads)
  integer :: n_loads, load_n_points(max_loads)
  character(len=16) :: load_joint(max_loads), load_link(max_loads)
  namelist /loads/ gravity_g, gravity_direction, n_loads, load_joint, load_link, load_position, load_fx, load_fy, &
    load_moment, load_n_points, load_time, load_factor

contains

  !> Read and check &loads (optional group; without it: no loads).
  subroutine read_loads(deck, inp, err)
    type(deck_t), intent(inout) :: deck
    type(loads_input_t), intent(out) :: inp
    type(error_t), intent(inout) :: err
    logical :: found
    integer :: k, n
    character(len=*), parameter :: g = 'loads'
    type(loads_input_t) :: defaults
    call stage_from(defaults)
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

  !> Echo &loads when the deck loads the model (a deck without loads is
  !> echoed without the group).
  subroutine echo_loads(inp, out)
    type(loads_input_t), intent(in) :: inp
    type(table_t), intent(inout) :: out
    if (inp%n_loads == 0 .and. .not. inp%gravity_g > 0.0_dp) return
    call stage_from(inp)
    call out%echo_group(loads_group)
  end subroutine echo_loads

  !> The namelist variables from the loads (the defaults before a read).
  subroutine stage_from(inp)
    type(loads_input_t), intent(in) :: inp
    gravity_g = inp%gravity_g
    gravity_direction = inp%gravity_direction
    n_loads = inp%n_loads
    load_joint = inp%load_joint
    load_link = inp%load_link
    load_position = inp%load_position
    load_fx = inp%load_fx
    load_fy = inp%load_fy
    load_moment = inp%load_moment
    load_n_points = inp%load_n_points
    load_time = inp%load_time
    load_factor = inp%load_factor
  end subroutine stage_from

  !> The &loads group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine loads_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=loads, delim='apostrophe')
    else
      read(r%unit, nml=loads, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine loads_group
end module loads_settings
