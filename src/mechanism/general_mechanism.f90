!> A general mechanism, in the plane or in space (doc/general_mechanism.md):
!> joints (revolute, prismatic, slider, spherical, universal, weld, free
!> end), some of them on the ground, links running between two joints, and
!> any number of prescribed joint motions.  Loops and open chains are not
!> declared: they follow from which links meet at which joints.
!>
!> The deck draws the mechanism: every joint has a position, and every link
!> is a rigid body whose frame is the global frame placed at its first
!> joint in the drawing.  Each member of a joint (the ground first, then the
!> links that end there, in link order) carries its own copy of the joint's
!> point and axes, fixed in it.  A link_length moves the link's second end
!> along the drawn direction to that distance: the drawing is then only the
!> guess the first assembly starts from (and chooses the branch by).
!>
!> The flat deck input (general_input_t, module general_deck) is validated
!> there; build_general turns it into this indexed form.
module general_mechanism
  use kinds, only: dp, pi
  use motion_profile, only: motion_profile_t, make_spline, motion_constant, motion_spinup
  implicit none
  private
  public :: max_gjoints, max_glinks, max_drivers, max_table
  public :: gjoint_revolute, gjoint_prismatic, gjoint_slider, gjoint_spherical, gjoint_universal, gjoint_weld, &
            gjoint_free, gjoint_names
  public :: general_input_t, general_mechanism_t, gjoint_t, glink_t, gdriver_t, build_general, unit_or_zero

  integer, parameter :: max_gjoints = 40, max_glinks = 40, max_drivers = 8, max_table = 100

  integer, parameter :: gjoint_revolute = 1, gjoint_prismatic = 2, gjoint_slider = 3, gjoint_spherical = 4, &
                        gjoint_universal = 5, gjoint_weld = 6, gjoint_free = 7
  character(len=10), parameter :: gjoint_names(7) = [character(len=10) :: 'revolute', 'prismatic', 'slider', &
    'spherical', 'universal', 'weld', 'free']

  !> The flat contents of &general_mechanism with the documented defaults.
  type :: general_input_t
    character(len=8) :: space = 'planar'
    integer :: n_joints = 0
    character(len=16) :: joint_name(max_gjoints) = ''
    character(len=10) :: joint_kind(max_gjoints) = ''
    logical :: joint_ground(max_gjoints) = .false.
    real(dp) :: joint_x(max_gjoints) = 0.0_dp, joint_y(max_gjoints) = 0.0_dp, joint_z(max_gjoints) = 0.0_dp
    real(dp) :: joint_axis(3, max_gjoints) = spread([0.0_dp, 0.0_dp, 1.0_dp], 2, max_gjoints)
    real(dp) :: joint_axis2(3, max_gjoints) = 0.0_dp
    integer :: n_links = 0
    character(len=16) :: link_name(max_glinks) = ''
    integer :: link_joint1(max_glinks) = 0, link_joint2(max_glinks) = 0
    real(dp) :: link_length(max_glinks) = 0.0_dp
    integer :: n_drivers = 0
    integer :: driver_joint(max_drivers) = 0
    character(len=8) :: driver_profile(max_drivers) = 'constant'
    real(dp) :: driver_start(max_drivers) = 0.0_dp
    real(dp) :: driver_rate(max_drivers) = 0.0_dp
    real(dp) :: driver_spinup_time(max_drivers) = 0.0_dp
    integer :: driver_n_table(max_drivers) = 0
    real(dp) :: driver_table_t(max_table, max_drivers) = 0.0_dp
    real(dp) :: driver_table_value(max_table, max_drivers) = 0.0_dp
    real(dp) :: toggle_rcond = 1.0e-7_dp
  end type general_input_t

  !> A joint and its members: member(1) is the ground (0) when the joint is
  !> grounded; point(:, k) and the axes are fixed in member k (its local frame).
  type :: gjoint_t
    character(len=16) :: name = ''
    integer :: kind = 0
    real(dp) :: drawn(3) = 0.0_dp           !< position in the drawing
    real(dp) :: axis(3) = [0.0_dp, 0.0_dp, 1.0_dp]   !< unit: revolute axis, slide direction, cross axis 1
    real(dp) :: axis2(3) = 0.0_dp           !< universal: cross axis 2 (in the second member)
    real(dp) :: f(3) = 0.0_dp, g(3) = 0.0_dp !< unit normals completing axis: (f, g, axis) right-handed
    integer, allocatable :: member(:)       !< link numbers, 0 = ground
    real(dp), allocatable :: point(:, :)    !< (3, members): the joint's point in each member's frame
  end type gjoint_t

  type :: glink_t
    character(len=16) :: name = ''
    integer :: joint(2) = 0
    real(dp) :: origin(3) = 0.0_dp          !< the frame's origin in the drawing (joint 1)
    real(dp) :: end2(3) = 0.0_dp            !< joint 2 in the link frame
  end type glink_t

  !> A prescribed motion of a joint's relative coordinate: the rotation of
  !> member 2 relative to member 1 about the axis since the drawing (rad), or
  !> the slide of member 2's point from member 1's along the direction.
  type :: gdriver_t
    integer :: joint = 0
    type(motion_profile_t) :: motion
  end type gdriver_t

  type :: general_mechanism_t
    logical :: spatial = .false.
    integer :: n_joints = 0, n_links = 0, n_drivers = 0
    type(gjoint_t), allocatable :: joints(:)
    type(glink_t), allocatable :: links(:)
    type(gdriver_t), allocatable :: drivers(:)
    real(dp) :: length_scale = 1.0_dp       !< mean link length (tolerances, scaling)
    real(dp) :: toggle_rcond = 1.0e-7_dp
    type(general_input_t) :: input          !< as given, for the echo
  end type general_mechanism_t

contains

  pure function unit_or_zero(v) result(u)
    real(dp), intent(in) :: v(3)
    real(dp) :: u(3)
    u = 0.0_dp
    if (norm2(v) > 0.0_dp) u = v/norm2(v)
  end function unit_or_zero

  !> Index the validated input: members of every joint, each member's copy of
  !> the joint point, links' frames, drivers' motions (angles to rad).
  pure function build_general(inp) result(m)
    type(general_input_t), intent(in) :: inp
    type(general_mechanism_t) :: m
    integer :: i, l, k, n
    real(dp) :: d(3), total
    integer :: members(max_glinks + 1)
    m%input = inp
    m%spatial = inp%space == 'spatial'
    m%n_joints = inp%n_joints
    m%n_links = inp%n_links
    m%n_drivers = inp%n_drivers
    m%toggle_rcond = inp%toggle_rcond
    allocate(m%joints(m%n_joints), m%links(m%n_links), m%drivers(m%n_drivers))
    total = 0.0_dp
    do l = 1, m%n_links
      associate (lk => m%links(l))
        lk%name = inp%link_name(l)
        lk%joint = [inp%link_joint1(l), inp%link_joint2(l)]
        lk%origin = drawn(lk%joint(1))
        d = drawn(lk%joint(2)) - lk%origin
        if (inp%link_length(l) > 0.0_dp) d = inp%link_length(l)*unit_or_zero(d)
        lk%end2 = d
        total = total + norm2(d)
      end associate
    end do
    if (total > 0.0_dp) m%length_scale = total/m%n_links
    do i = 1, m%n_joints
      associate (j => m%joints(i))
        j%name = inp%joint_name(i)
        j%kind = findloc(gjoint_names, inp%joint_kind(i), 1)
        j%drawn = drawn(i)
        if (m%spatial .or. j%kind == gjoint_prismatic .or. j%kind == gjoint_slider) then
          j%axis = unit_or_zero(inp%joint_axis(:, i))
        end if
        if (.not. m%spatial) then
          j%axis(3) = 0.0_dp
          if (j%kind == gjoint_revolute .or. j%kind == gjoint_weld .or. j%kind == gjoint_free) &
            j%axis = [0.0_dp, 0.0_dp, 1.0_dp]
          j%axis = unit_or_zero(j%axis)
        end if
        j%axis2 = unit_or_zero(inp%joint_axis2(:, i))
        call normals(j%axis, j%f, j%g)
        n = 0
        if (inp%joint_ground(i)) then
          n = 1
          members(1) = 0
        end if
        do l = 1, m%n_links
          if (any(m%links(l)%joint == i)) then
            n = n + 1
            members(n) = l
          end if
        end do
        j%member = members(1:n)
        allocate(j%point(3, n))
        do k = 1, n
          l = members(k)
          if (l == 0) then
            j%point(:, k) = j%drawn
          else if (m%links(l)%joint(2) == i) then
            j%point(:, k) = m%links(l)%end2
          else
            j%point(:, k) = 0.0_dp
          end if
        end do
      end associate
    end do
    do k = 1, m%n_drivers
      m%drivers(k)%joint = inp%driver_joint(k)
      associate (p => m%drivers(k)%motion, rev => m%joints(inp%driver_joint(k))%kind == gjoint_revolute)
        n = inp%driver_n_table(k)
        select case (inp%driver_profile(k))
        case ('table')
          call make_spline(inp%driver_table_t(1:n, k), inp%driver_table_value(1:n, k)*merge(pi/180.0_dp, 1.0_dp, rev), p)
        case default
          p%kind = merge(motion_spinup, motion_constant, inp%driver_profile(k) == 'spinup')
          p%start = inp%driver_start(k)*merge(pi/180.0_dp, 1.0_dp, rev)
          p%rate = inp%driver_rate(k)
          p%spinup_time = inp%driver_spinup_time(k)
        end select
      end associate
    end do
  contains
    pure function drawn(i) result(x)
      integer, intent(in) :: i
      real(dp) :: x(3)
      x = [inp%joint_x(i), inp%joint_y(i), merge(inp%joint_z(i), 0.0_dp, inp%space == 'spatial')]
    end function drawn
  end function build_general

  !> Unit vectors f, g normal to the unit vector a with (f, g, a) right-handed.
  pure subroutine normals(a, f, g)
    real(dp), intent(in) :: a(3)
    real(dp), intent(out) :: f(3), g(3)
    real(dp) :: e(3)
    e = [1.0_dp, 0.0_dp, 0.0_dp]
    if (abs(a(1)) > 0.7_dp) e = [0.0_dp, 1.0_dp, 0.0_dp]
    f = unit_or_zero(e - dot_product(e, a)*a)
    g = [a(2)*f(3) - a(3)*f(2), a(3)*f(1) - a(1)*f(3), a(1)*f(2) - a(2)*f(1)]
  end subroutine normals
end module general_mechanism
