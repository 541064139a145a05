!> The deck group &general_support (doc/general_mechanism.md, "Support
!> structure"): lumped mounts under named ground joints of the
!> &general_mechanism, each with a mass, a stiffness and a damping per global
!> direction X, Y, Z.  Optional: without it every ground joint is rigid.
!> Every value is checked here (code 2 naming deck, group, variable and line).
module general_support_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_reals, check_integer
  use table_output, only: table_t
  use general_mechanism, only: general_mechanism_t
  use support_mounts, only: support_mount_t
  implicit none
  private
  public :: general_support_input_t, read_general_support, echo_general_support, build_mounts, max_mounts

  integer, parameter :: max_mounts = 8

  !> The group as read; the default initialisation is the documented defaults.
  type :: general_support_input_t
    integer :: n_mounts = 0
    character(len=16) :: mount_joint(max_mounts) = ''
    real(dp) :: mount_mass(3, max_mounts) = 0.0_dp
    real(dp) :: mount_stiffness(3, max_mounts) = 0.0_dp
    real(dp) :: mount_damping(3, max_mounts) = 0.0_dp
  end type general_support_input_t

  character(len=*), parameter :: g = 'general_support'

  ! staging variables of the namelist group
  integer :: n_mounts
  character(len=16) :: mount_joint(max_mounts)
  real(dp) :: mount_mass(3, max_mounts), mount_stiffness(3, max_mounts), mount_damping(3, max_mounts)
  namelist /general_support/ n_mounts, mount_joint, mount_mass, mount_stiffness, mount_damping

contains

  !> Read &general_support (optional: no mounts) and check it against the mechanism.
  subroutine read_general_support(deck, mech, s, found, err)
    type(deck_t), intent(inout) :: deck
    type(general_mechanism_t), intent(in) :: mech
    type(general_support_input_t), intent(out) :: s
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    call stage_from(s)
    call deck%read_group(g, general_support_group, .false., found, err)
    if (err%failed()) return
    s = general_support_input_t(n_mounts, mount_joint, mount_mass, mount_stiffness, mount_damping)
    call validate(deck, mech, s, err)
  end subroutine read_general_support

  subroutine stage_from(s)
    type(general_support_input_t), intent(in) :: s
    n_mounts = s%n_mounts
    mount_joint = s%mount_joint
    mount_mass = s%mount_mass
    mount_stiffness = s%mount_stiffness
    mount_damping = s%mount_damping
  end subroutine stage_from

  !> Each mount under a ground joint of the mechanism, once; m >= 0, k > 0, c >= 0.
  subroutine validate(deck, mech, s, err)
    type(deck_t), intent(in) :: deck
    type(general_mechanism_t), intent(in) :: mech
    type(general_support_input_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    integer :: k, d, j
    call check_integer(deck, g, 'n_mounts', s%n_mounts, err, at_least=0, at_most=max_mounts)
    if (err%failed()) return
    do k = 1, s%n_mounts
      j = joint_number(mech, s%mount_joint(k))
      if (j == 0) then
        call invalid_value(deck, g, 'mount_joint('//str(k)//')', ''''//trim(s%mount_joint(k))//'''', &
                           'no joint of &general_mechanism has this name', err)
      else if (mech%joints(j)%member(1) /= 0) then
        call invalid_value(deck, g, 'mount_joint('//str(k)//')', ''''//trim(s%mount_joint(k))//'''', &
                           'the joint is not on the ground (joint_ground): only a ground joint sits on a mount', err)
      else if (any(s%mount_joint(1:k - 1) == s%mount_joint(k))) then
        call invalid_value(deck, g, 'mount_joint('//str(k)//')', ''''//trim(s%mount_joint(k))//'''', &
                           'the joint has a mount already', err)
      end if
      if (err%failed()) return
    end do
    do d = 1, 3
      call check_reals(deck, g, 'mount_mass('//str(d)//',:)', s%mount_mass(d, 1:s%n_mounts), err, &
                       at_least=0.0_dp, at_most=1.0e12_dp)
      call check_reals(deck, g, 'mount_stiffness('//str(d)//',:)', s%mount_stiffness(d, 1:s%n_mounts), err, &
                       above=0.0_dp, at_most=1.0e20_dp, why='a mount is a spring to the rigid ground in every direction')
      call check_reals(deck, g, 'mount_damping('//str(d)//',:)', s%mount_damping(d, 1:s%n_mounts), err, &
                       at_least=0.0_dp, at_most=1.0e15_dp)
    end do
  end subroutine validate

  !> The number of the joint named name (0: none).
  integer function joint_number(mech, name) result(j)
    type(general_mechanism_t), intent(in) :: mech
    character(len=*), intent(in) :: name
    integer :: k
    j = 0
    do k = 1, mech%n_joints
      if (mech%joints(k)%name == name .and. len_trim(name) > 0) j = k
    end do
  end function joint_number

  !> The mounts of the model (module support_mounts).
  function build_mounts(s, mech) result(mounts)
    type(general_support_input_t), intent(in) :: s
    type(general_mechanism_t), intent(in) :: mech
    type(support_mount_t), allocatable :: mounts(:)
    integer :: k
    allocate(mounts(s%n_mounts))
    do k = 1, s%n_mounts
      mounts(k)%joint_name = s%mount_joint(k)
      mounts(k)%joint = joint_number(mech, s%mount_joint(k))
      mounts(k)%mass = s%mount_mass(:, k)
      mounts(k)%stiffness = s%mount_stiffness(:, k)
      mounts(k)%damping = s%mount_damping(:, k)
    end do
  end function build_mounts

  !> Echo the effective values into an output's header.
  subroutine echo_general_support(s, out)
    type(general_support_input_t), intent(in) :: s
    type(table_t), intent(inout) :: out
    call stage_from(s)
    call out%echo_group(general_support_group)
  end subroutine echo_general_support

  !> The group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine general_support_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=general_support, delim='apostrophe')
    else
      read(r%unit, nml=general_support, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine general_support_group
end module general_support_settings
