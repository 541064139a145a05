!> The deck group &general_mechanism (doc/general_mechanism.md): its flat
!> namelist (staged through module variables, because the deck reader's
!> callback receives only the unit; general_input_t's default
!> initialisation is the documented default), its validation, naming
!> variable, value and deck line, and its echo.
module general_deck
  use kinds, only: dp
  use strings, only: str, lower
  use error_status, only: error_t
  use deck_reader, only: deck_t, invalid_value, group_read_t, input_error_in
  use deck_checks, only: check_real, check_integer, check_choice, all_finite
  use table_output, only: table_t
  use motion_profile, only: motion_names
  use general_mechanism, only: general_input_t, general_mechanism_t, build_general, max_gjoints, max_glinks, &
    max_drivers, max_table, gjoint_names, unit_or_zero
  use general_kinematics, only: general_kinematics_t
  implicit none
  private
  public :: read_general_mechanism, echo_general_mechanism

  character(len=*), parameter :: g = 'general_mechanism'

  character(len=8) :: space
  integer :: n_joints, n_links, n_drivers
  character(len=16) :: joint_name(max_gjoints), link_name(max_glinks)
  character(len=10) :: joint_kind(max_gjoints)
  logical :: joint_ground(max_gjoints)
  real(dp) :: joint_x(max_gjoints), joint_y(max_gjoints), joint_z(max_gjoints)
  real(dp) :: joint_axis(3, max_gjoints), joint_axis2(3, max_gjoints)
  integer :: link_joint1(max_glinks), link_joint2(max_glinks)
  real(dp) :: link_length(max_glinks)
  integer :: driver_joint(max_drivers), driver_n_table(max_drivers)
  character(len=8) :: driver_profile(max_drivers)
  real(dp) :: driver_start(max_drivers), driver_rate(max_drivers), driver_spinup_time(max_drivers)
  real(dp) :: driver_table_t(max_table, max_drivers), driver_table_value(max_table, max_drivers)
  real(dp) :: toggle_rcond
  namelist /general_mechanism/ space, n_joints, joint_name, joint_kind, joint_ground, joint_x, joint_y, joint_z, &
    joint_axis, joint_axis2, n_links, link_name, link_joint1, link_joint2, link_length, &
    n_drivers, driver_joint, driver_profile, driver_start, driver_rate, driver_spinup_time, &
    driver_n_table, driver_table_t, driver_table_value, toggle_rcond

contains

  !> Read &general_mechanism (required), validate it, build the mechanism
  !> and set up its kinematics (mobility against the drivers).  Every
  !> failure is an input error.
  subroutine read_general_mechanism(deck, mech, kin, err)
    type(deck_t), intent(inout) :: deck
    type(general_mechanism_t), intent(out) :: mech
    type(general_kinematics_t), intent(out) :: kin
    type(error_t), intent(inout) :: err
    type(general_input_t) :: inp
    logical :: found
    integer :: i
    character(len=:), allocatable :: blame, blame_value, rule
    call stage_from(inp)
    call deck%read_group(g, general_mechanism_group, .true., found, err)
    if (err%failed()) return
    space = lower(space)
    do i = 1, max_gjoints
      joint_kind(i) = lower(joint_kind(i))
    end do
    do i = 1, max_drivers
      driver_profile(i) = lower(driver_profile(i))
    end do
    call validate(deck, err)
    if (err%failed()) return
    inp = general_input_t(space=space, n_joints=n_joints, joint_name=joint_name, joint_kind=joint_kind, &
      joint_ground=joint_ground, joint_x=joint_x, joint_y=joint_y, joint_z=joint_z, joint_axis=joint_axis, &
      joint_axis2=joint_axis2, n_links=n_links, link_name=link_name, link_joint1=link_joint1, &
      link_joint2=link_joint2, link_length=link_length, n_drivers=n_drivers, driver_joint=driver_joint, &
      driver_profile=driver_profile, driver_start=driver_start, driver_rate=driver_rate, &
      driver_spinup_time=driver_spinup_time, driver_n_table=driver_n_table, driver_table_t=driver_table_t, &
      driver_table_value=driver_table_value, toggle_rcond=toggle_rcond)
    mech = build_general(inp)
    call kin%init(mech, err, blame, blame_value)
    if (err%failed() .and. allocated(blame)) then
      rule = err%text()
      call err%clear()
      call invalid_value(deck, g, blame, blame_value, rule, err)
    else if (err%failed()) then
      call input_error_in(deck, g, err)
    end if
  end subroutine read_general_mechanism

  !> The rules of the flat input, in order; the first broken one is reported.
  subroutine validate(deck, err)
    type(deck_t), intent(in) :: deck
    type(error_t), intent(inout) :: err
    integer :: i, k, n, members
    logical :: spatial
    call check_choice(deck, g, 'space', space, [character(len=8) :: 'planar', 'spatial'], err)
    call check_integer(deck, g, 'n_joints', n_joints, err, at_least=1, at_most=max_gjoints)
    call check_integer(deck, g, 'n_links', n_links, err, at_least=1, at_most=max_glinks)
    call check_integer(deck, g, 'n_drivers', n_drivers, err, at_least=0, at_most=max_drivers)
    call check_real(deck, g, 'toggle_rcond', toggle_rcond, err, above=0.0_dp, below=1.0_dp, &
                    why='the reciprocal condition of the scaled constraint Jacobian below which a toggle is reported')
    if (err%failed()) return
    spatial = space == 'spatial'
    do i = 1, n_links
      call check_integer(deck, g, idx('link_joint1', i), link_joint1(i), err, at_least=1, at_most=n_joints)
      call check_integer(deck, g, idx('link_joint2', i), link_joint2(i), err, at_least=1, at_most=n_joints)
      call check_real(deck, g, idx('link_length', i), link_length(i), err, at_least=0.0_dp, &
                      why='0: the length of the drawing')
      if (err%failed()) return
      if (link_joint1(i) == link_joint2(i)) then
        call invalid_value(deck, g, idx('link_joint2', i), str(link_joint2(i)), &
                           'a link runs between two different joints', err)
        return
      end if
      if (len_trim(link_name(i)) == 0) link_name(i) = 'link'//str(i)
    end do
    do i = 1, n_joints
      if (len_trim(joint_name(i)) == 0) joint_name(i) = 'J'//str(i)
      call check_choice(deck, g, idx('joint_kind', i), joint_kind(i), gjoint_names, err)
      if (err%failed()) return
      if (.not. all_finite([joint_x(i), joint_y(i), joint_z(i), joint_axis(:, i), joint_axis2(:, i)])) then
        call invalid_value(deck, g, idx('joint_x', i), str(joint_x(i)), 'joint positions and axes must be finite', err)
        return
      end if
      if (.not. spatial .and. any(joint_kind(i) == [character(len=10) :: 'spherical', 'universal'])) then
        call invalid_value(deck, g, idx('joint_kind', i), quoted(joint_kind(i)), &
                           'a '//trim(joint_kind(i))//' joint needs space = ''spatial''', err)
        return
      end if
      members = count(link_joint1(1:n_links) == i) + count(link_joint2(1:n_links) == i)
      if (joint_ground(i)) members = members + 1
      if (joint_kind(i) == 'free') then
        if (members /= 1 .or. joint_ground(i)) then
          call invalid_value(deck, g, idx('joint_kind', i), quoted(joint_kind(i)), &
                             'a free end belongs to exactly one link and not to the ground', err)
          return
        end if
      else if (members < 2) then
        call invalid_value(deck, g, idx('joint_kind', i), quoted(joint_kind(i)), 'joint '''//trim(joint_name(i))// &
          ''' joins '//str(members)//' member(s): a joint joins two or more links, or the ground and links '// &
          '(joint_ground); the end of a single link is ''free''', err)
        return
      else if (members > 2 .and. any(joint_kind(i) == [character(len=10) :: 'universal', 'prismatic', 'slider'])) then
        call invalid_value(deck, g, idx('joint_kind', i), quoted(joint_kind(i)), &
                           'a '//trim(joint_kind(i))//' joint joins exactly two members', err)
        return
      end if
      if (spatial .or. any(joint_kind(i) == [character(len=10) :: 'prismatic', 'slider'])) then
        if (needs_axis(joint_kind(i)) .and. norm2(joint_axis(1:merge(3, 2, spatial), i)) < 1.0e-12_dp) then
          call invalid_value(deck, g, idx('joint_axis', i), '0', 'a '//trim(joint_kind(i))//' joint needs its '// &
            merge('axis     ', 'direction', joint_kind(i) == 'revolute')//' (in the plane: joint_axis(1:2))', err)
          return
        end if
      end if
      if (joint_kind(i) == 'universal') then
        if (norm2(joint_axis2(:, i)) < 1.0e-12_dp .or. abs(dot_product(unit_or_zero(joint_axis(:, i)), &
            unit_or_zero(joint_axis2(:, i)))) > 1.0e-9_dp) then
          call invalid_value(deck, g, idx('joint_axis2', i), str(joint_axis2(1, i))//', '//str(joint_axis2(2, i))// &
            ', '//str(joint_axis2(3, i)), 'the cross''s second axis: nonzero and normal to joint_axis', err)
          return
        end if
      end if
    end do
    do k = 1, n_drivers
      call check_integer(deck, g, idx('driver_joint', k), driver_joint(k), err, at_least=1, at_most=n_joints)
      if (err%failed()) return
      i = driver_joint(k)
      members = count(link_joint1(1:n_links) == i) + count(link_joint2(1:n_links) == i)
      if (joint_ground(i)) members = members + 1
      if (.not. any(joint_kind(i) == [character(len=10) :: 'revolute', 'prismatic', 'slider']) .or. members /= 2) then
        call invalid_value(deck, g, idx('driver_joint', k), str(i), 'a driver moves a revolute, prismatic or '// &
          'slider joint of two members (joint '''//trim(joint_name(i))//''' is a '//trim(joint_kind(i))// &
          ' of '//str(members)//')', err)
        return
      end if
      if (any(driver_joint(1:k - 1) == i)) then
        call invalid_value(deck, g, idx('driver_joint', k), str(i), 'joint '''//trim(joint_name(i))// &
          ''' has a driver already: the mechanism is over-driven', err)
        return
      end if
      call check_choice(deck, g, idx('driver_profile', k), driver_profile(k), motion_names, err)
      call check_real(deck, g, idx('driver_start', k), driver_start(k), err)
      call check_real(deck, g, idx('driver_rate', k), driver_rate(k), err)
      if (err%failed()) return
      select case (driver_profile(k))
      case ('spinup')
        call check_real(deck, g, idx('driver_spinup_time', k), driver_spinup_time(k), err, above=0.0_dp, &
                        at_most=1.0e6_dp, why='the spin-up duration')
      case ('table')
        call check_integer(deck, g, idx('driver_n_table', k), driver_n_table(k), err, at_least=2, &
                           at_most=max_table, why='the number of (time, value) points of the table')
        if (err%failed()) return
        n = driver_n_table(k)
        if (.not. all_finite([driver_table_t(1:n, k), driver_table_value(1:n, k)])) then
          call invalid_value(deck, g, 'driver_table_t(1:'//str(n)//', '//str(k)//')', 'non-finite', &
                             'table times and values must be finite', err)
        else if (any(driver_table_t(2:n, k) <= driver_table_t(1:n - 1, k))) then
          call invalid_value(deck, g, 'driver_table_t(1:'//str(n)//', '//str(k)//')', &
                             str(driver_table_t(1, k))//', ...', 'table times must increase strictly', err)
        else if (driver_table_t(1, k) > 0.0_dp) then
          call invalid_value(deck, g, 'driver_table_t(1, '//str(k)//')', str(driver_table_t(1, k)), &
                             'the table starts at t <= 0', err)
        end if
      end select
      if (err%failed()) return
    end do
  contains
    pure logical function needs_axis(kind)
      character(len=*), intent(in) :: kind
      needs_axis = any(kind == [character(len=10) :: 'revolute', 'prismatic', 'slider', 'universal', 'weld'])
      if (.not. spatial) needs_axis = kind == 'prismatic' .or. kind == 'slider'
    end function needs_axis
  end subroutine validate

  pure function idx(name, i) result(s)
    character(len=*), intent(in) :: name
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    s = name//'('//str(i)//')'
  end function idx

  pure function quoted(s) result(q)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: q
    q = "'"//trim(s)//"'"
  end function quoted

  !> The group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine general_mechanism_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=general_mechanism, delim='apostrophe')
    else
      read(r%unit, nml=general_mechanism, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine general_mechanism_group

  !> Echo the effective input into an output's header.
  subroutine echo_general_mechanism(mech, out)
    type(general_mechanism_t), intent(in) :: mech
    type(table_t), intent(inout) :: out
    call stage_from(mech%input)
    call out%echo_group(general_mechanism_group)
  end subroutine echo_general_mechanism

  subroutine stage_from(inp)
    type(general_input_t), intent(in) :: inp
    space = inp%space
    n_joints = inp%n_joints
    joint_name = inp%joint_name
    joint_kind = inp%joint_kind
    joint_ground = inp%joint_ground
    joint_x = inp%joint_x
    joint_y = inp%joint_y
    joint_z = inp%joint_z
    joint_axis = inp%joint_axis
    joint_axis2 = inp%joint_axis2
    n_links = inp%n_links
    link_name = inp%link_name
    link_joint1 = inp%link_joint1
    link_joint2 = inp%link_joint2
    link_length = inp%link_length
    n_drivers = inp%n_drivers
    driver_joint = inp%driver_joint
    driver_profile = inp%driver_profile
    driver_start = inp%driver_start
    driver_rate = inp%driver_rate
    driver_spinup_time = inp%driver_spinup_time
    driver_n_table = inp%driver_n_table
    driver_table_t = inp%driver_table_t
    driver_table_value = inp%driver_table_value
    toggle_rcond = inp%toggle_rcond
  end subroutine stage_from
end module general_deck
