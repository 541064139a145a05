!> The `kinematics` analysis: rigid-body kinematics of a general mechanism
!> (&general_mechanism, doc/general_mechanism.md) over a time span (&kinematics).
!> Per output time: every driven or passive joint coordinate (revolute: deg,
!> rad/s, rad/s^2; prismatic and slider: length and its rates), every
!> joint's position, and every link's origin velocity and acceleration with
!> its angular velocity and acceleration.
module kinematics_analysis
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, group_read_t, invalid_value
  use deck_checks, only: check_real, check_integer
  use table_output, only: table_t
  use general_mechanism, only: general_mechanism_t, gjoint_revolute
  use general_kinematics, only: general_kinematics_t, joint_has_value
  use general_deck, only: read_general_mechanism, echo_general_mechanism
  implicit none
  private
  public :: run_kinematics

  ! staging variables of &kinematics (defaults: set_defaults)
  real(dp) :: t_end
  integer :: n_steps
  namelist /kinematics/ t_end, n_steps

contains

  subroutine set_defaults()
    t_end = 1.0_dp
    n_steps = 100
  end subroutine set_defaults

  !> The &kinematics group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine kinematics_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=kinematics, delim='apostrophe')
    else
      read(r%unit, nml=kinematics, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine kinematics_group

  subroutine run_kinematics(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(general_mechanism_t) :: mech
    type(general_kinematics_t) :: kin
    logical :: found
    integer :: k, i, b, nd
    real(dp) :: t, cpu0, cpu1, x(3), v(3), a(3), w(3), al(3), jv, jvd, jvdd
    real(dp), allocatable :: row(:), last_value(:)
    character(len=32), allocatable :: names(:)

    call cpu_time(cpu0)
    call read_general_mechanism(deck, mech, kin, err)
    if (err%failed()) return
    call set_defaults()
    call deck%read_group('kinematics', kinematics_group, .false., found, err)
    if (err%failed()) return
    call check_real(deck, 'kinematics', 't_end', t_end, err, above=0.0_dp, at_most=1.0e9_dp, &
                    why='the end of the time span (s)')
    call check_integer(deck, 'kinematics', 'n_steps', n_steps, err, at_least=1, at_most=10000000, &
                       why='output intervals over [0, t_end]')
    if (err%failed()) return
    do k = 1, mech%n_drivers
      associate (p => mech%drivers(k)%motion)
        if (allocated(p%t)) then
          if (p%t(size(p%t)) < t_end) call invalid_value(deck, 'kinematics', 't_end', str(t_end), &
            'driver '//str(k)//'''s table ends at t = '//str(p%t(size(p%t)))//' s', err)
        end if
      end associate
    end do
    if (err%failed()) return
    call echo_general_mechanism(mech, out)
    call out%echo_group(kinematics_group)
    nd = merge(3, 2, mech%spatial)
    call out%comment('mechanism: '//trim(merge('spatial', 'planar ', mech%spatial))//', '//str(mech%n_links)//' links, '// &
      str(mech%n_joints)//' joints, '//str(mech%n_drivers)//' drivers; freedoms (Kutzbach) '//str(kin%kutzbach)// &
      ', (Jacobian rank) '//str(kin%mobility)//'; '//str(kin%n)//' coordinates, '//str(kin%m)//' constraint rows')

    ! columns
    allocate(names(0))
    names = [character(len=32) :: 't']
    do i = 1, mech%n_joints
      if (.not. joint_has_value(mech%joints(i))) cycle
      if (mech%joints(i)%kind == gjoint_revolute) then
        names = [character(len=32) :: names, trim(mech%joints(i)%name)//'_deg', trim(mech%joints(i)%name)//'_rate', &
                 trim(mech%joints(i)%name)//'_acc']
      else
        names = [character(len=32) :: names, trim(mech%joints(i)%name)//'_s', trim(mech%joints(i)%name)//'_rate', &
                 trim(mech%joints(i)%name)//'_acc']
      end if
    end do
    do i = 1, mech%n_joints
      names = [character(len=32) :: names, (trim(mech%joints(i)%name)//'_'//axis_name(k), k = 1, nd)]
    end do
    do b = 1, mech%n_links
      associate (n => mech%links(b)%name)
        names = [character(len=32) :: names, (trim(n)//'_v'//axis_name(k), k = 1, nd), &
                 (trim(n)//'_a'//axis_name(k), k = 1, nd)]
        if (mech%spatial) then
          names = [character(len=32) :: names, (trim(n)//'_w'//axis_name(k), k = 1, 3), &
                   (trim(n)//'_alpha'//axis_name(k), k = 1, 3)]
        else
          names = [character(len=32) :: names, trim(n)//'_w', trim(n)//'_alpha']
        end if
      end associate
    end do
    call out%columns(names)

    allocate(row(size(names)), last_value(mech%n_joints))
    last_value = 0.0_dp
    do k = 0, n_steps
      t = t_end*k/n_steps
      call kin%solve(t, err)
      if (err%failed()) exit
      row = 0.0_dp
      row(1) = t
      nrow: block
        integer :: c
        c = 1
        do i = 1, mech%n_joints
          if (.not. joint_has_value(mech%joints(i))) cycle
          call kin%joint_value(i, last_value(i), jv, jvd, jvdd)
          last_value(i) = jv
          if (mech%joints(i)%kind == gjoint_revolute) jv = jv*180.0_dp/pi
          row(c + 1:c + 3) = [jv, jvd, jvdd]
          c = c + 3
        end do
        do i = 1, mech%n_joints
          associate (jt => mech%joints(i))
            ! the joint's point on its first link (a ground point stays put)
            b = merge(2, 1, jt%member(1) == 0)
            call kin%point(jt%member(b), jt%point(:, b), x, v, a)
          end associate
          row(c + 1:c + nd) = x(1:nd)
          c = c + nd
        end do
        do b = 1, mech%n_links
          call kin%point(b, [0.0_dp, 0.0_dp, 0.0_dp], x, v, a)
          call kin%body_motion(b, w, al)
          row(c + 1:c + 2*nd) = [v(1:nd), a(1:nd)]
          c = c + 2*nd
          if (mech%spatial) then
            row(c + 1:c + 6) = [w, al]
            c = c + 6
          else
            row(c + 1:c + 2) = [w(3), al(3)]
            c = c + 2
          end if
        end do
      end block nrow
      call out%row(row)
    end do
    call cpu_time(cpu1)
    if (.not. err%failed()) call out%summary('steps solved', str(kin%n_solutions))
    call out%cost('cpu_seconds', str(cpu1 - cpu0, 4))
    call out%cost('position_solutions', str(kin%n_solutions))
    call out%cost('newton_iterations', str(kin%total_iterations))
  contains
    pure function axis_name(k) result(s)
      integer, intent(in) :: k
      character(len=1) :: s
      s = 'xyz'(k:k)
    end function axis_name
  end subroutine run_kinematics
end module kinematics_analysis
