!> Rigid-body kinematics of a spatial single-loop four-bar (doc/spatial.md,
!> "Spatial mechanisms"): ground - revolute A (the driving shaft, axis a) -
!> crank AB - joint B - coupler BC - joint C - rocker CD - revolute D (axis d)
!> - ground.  With spherical joints at B and C it is the RSSR linkage; with
!> revolute joints whose axes are parallel to a and d (and a parallel to d)
!> it is the planar four-bar.  The loop closes through the coupler length:
!>
!>   g(psi, theta) = |C(psi) - B(theta)|^2 - L^2 = 0
!>   B = A + Rot(a, theta) (B0 - A),   C = D + rho (cos psi e1 + sin psi e2)
!>
!> solved for the rocker angle psi by Newton's method with the analytic
!> derivative g_psi, started from the previous solution (or the closed form
!> P cos psi + Q sin psi = S on the first call); velocities and accelerations
!> by differentiating g.  The branch is the sign of sin(psi - atan2(Q, P));
!> a toggle (g_psi = 0), a branch flip or a failure to assemble (|S| >
!> sqrt(P^2 + Q^2)) is an error naming the crank angle.
!>
!> Link frames (columns x, y, z of rot): crank x = (B - A)/r, z = a; rocker
!> x = (C - D)/rho, z = d; coupler x = (C - B)/L, z = the part of a normal to
!> x (the coupler's spin about its own axis is idle in the RSSR: this fixes
!> it, and gives the planar frame in the planar case).
!>
!> Universal joint at B or C (spatial_fourbar_set_universal: RUSR, RSUR): the
!> cross's first axis u is fixed in the crank (at B) or the rocker (at C), its
!> second axis is fixed in the coupler and normal to BC and to u; the joint
!> fixes the coupler's spin: coupler z = (x cross u)/|x cross u|.  It locks
!> when BC runs along u (an error naming the crank angle).
module spatial_kinematics
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use linalg, only: cross
  implicit none
  private
  public :: spatial_fourbar_t, spatial_pose_t, spatial_fourbar_init, spatial_fourbar_solve
  public :: spatial_fourbar_set_universal
  public :: rocker_angle_closed_form
  public :: link_crank, link_coupler, link_rocker

  integer, parameter :: link_crank = 1, link_coupler = 2, link_rocker = 3
  !> Crank-angle distance (rad) over which the last solution still seeds Newton.
  real(dp), parameter :: guess_reach = 0.25_dp

  type :: spatial_fourbar_t
    real(dp) :: a_pivot(3) = 0.0_dp, a_axis(3) = [0.0_dp, 0.0_dp, 1.0_dp], b0(3) = 0.0_dp
    real(dp) :: d_pivot(3) = 0.0_dp, d_axis(3) = [0.0_dp, 0.0_dp, 1.0_dp]
    real(dp) :: e1(3) = 0.0_dp, e2(3) = 0.0_dp    !< basis of the rocker plane: psi from e1 towards e2 = d x e1
    real(dp) :: crank_radius = 0.0_dp, rocker_length = 0.0_dp, coupler_length = 0.0_dp
    integer :: branch = 1                         !< sign of sin(psi - atan2(Q, P))
    real(dp) :: toggle_tol = 1.0e-6_dp            !< |sin(psi - atan2(Q,P))| below this: toggle
    !> universal joint: 0 none, link_crank (at B) or link_rocker (at C): the link carrying the cross's axis u
    integer :: universal_link = 0
    real(dp) :: u_local(3) = [0.0_dp, 0.0_dp, 1.0_dp]   !< u in that link's frame (unit)
    real(dp) :: lock_tol = 1.0e-6_dp              !< |x cross u| below this: the universal joint locks
    ! state of the Newton iteration
    logical :: have_guess = .false.
    real(dp) :: psi_guess = 0.0_dp
    real(dp) :: theta_guess = 0.0_dp               !< the crank angle psi_guess belongs to
    integer :: total_iterations = 0, n_solves = 0
  end type spatial_fourbar_t

  !> Positions and motion at one crank angle; frames of the three links.
  type :: spatial_pose_t
    real(dp) :: theta = 0.0_dp, theta_d = 0.0_dp, theta_dd = 0.0_dp
    real(dp) :: psi = 0.0_dp, psi_d = 0.0_dp, psi_dd = 0.0_dp
    real(dp) :: b(3) = 0.0_dp, b_d(3) = 0.0_dp, b_dd(3) = 0.0_dp
    real(dp) :: c(3) = 0.0_dp, c_d(3) = 0.0_dp, c_dd(3) = 0.0_dp
    real(dp) :: rot(3, 3, 3) = 0.0_dp             !< (:, :, link)
    real(dp) :: omega(3, 3) = 0.0_dp              !< (:, link) angular velocity, global
    real(dp) :: alpha(3, 3) = 0.0_dp              !< (:, link) angular acceleration, global
    real(dp) :: origin(3, 3) = 0.0_dp             !< (:, link) end 1 of each link: A, B, D
    real(dp) :: origin_d(3, 3) = 0.0_dp, origin_dd(3, 3) = 0.0_dp
    integer :: iterations = 0
    logical :: locked = .false.                   !< universal joint locked (coupler along the cross's axis)
  end type spatial_pose_t

contains

  !> Geometry: crank pivot and axis, crank pin at theta = 0, rocker pivot and
  !> axis, rocker and coupler lengths, branch (+1 or -1).  The crank pin must
  !> lie in the plane through A normal to a (the crank is normal to its axis).
  pure subroutine spatial_fourbar_init(m, a_pivot, a_axis, b0, d_pivot, d_axis, rocker_length, &
                                       coupler_length, branch, err)
    type(spatial_fourbar_t), intent(out) :: m
    real(dp), intent(in) :: a_pivot(3), a_axis(3), b0(3), d_pivot(3), d_axis(3), rocker_length, coupler_length
    integer, intent(in) :: branch
    type(error_t), intent(inout) :: err
    real(dp) :: r(3), x(3)
    if (.not. (norm2(a_axis) > 0.0_dp .and. norm2(d_axis) > 0.0_dp)) then
      call err%set('spatial four-bar', 'joint axes must be nonzero vectors'); return
    end if
    m%a_pivot = a_pivot
    m%a_axis = a_axis/norm2(a_axis)
    m%b0 = b0
    m%d_pivot = d_pivot
    m%d_axis = d_axis/norm2(d_axis)
    r = b0 - a_pivot
    m%crank_radius = norm2(r)
    if (.not. (m%crank_radius > 0.0_dp)) then
      call err%set('spatial four-bar', 'the crank pin coincides with the crank pivot'); return
    end if
    if (abs(dot_product(r, m%a_axis)) > 1.0e-9_dp*m%crank_radius) then
      call err%set('spatial four-bar', 'the crank pin is not in the plane through the pivot normal to the '// &
                   'crank axis (a.(B0-A) = '//str(dot_product(r, m%a_axis))//')'); return
    end if
    if (.not. (rocker_length > 0.0_dp .and. coupler_length > 0.0_dp)) then
      call err%set('spatial four-bar', 'rocker and coupler lengths must be positive'); return
    end if
    if (abs(branch) /= 1) then
      call err%set('spatial four-bar', 'branch must be +1 or -1, got '//str(branch)); return
    end if
    m%rocker_length = rocker_length
    m%coupler_length = coupler_length
    m%branch = branch
    ! rocker plane basis: e1 = the part of global X normal to d (Y if X is along d)
    x = [1.0_dp, 0.0_dp, 0.0_dp] - m%d_axis(1)*m%d_axis
    if (norm2(x) < 1.0e-6_dp) x = [0.0_dp, 1.0_dp, 0.0_dp] - m%d_axis(2)*m%d_axis
    m%e1 = x/norm2(x)
    m%e2 = cross(m%d_axis, m%e1)
  end subroutine spatial_fourbar_init

  !> A universal joint at B (at_c false) or C: the cross's axis fixed in the
  !> crank or the rocker, axis_local in that link's frame (x along the link
  !> from its pivot, z along the pivot axis); any nonzero vector.
  pure subroutine spatial_fourbar_set_universal(m, at_c, axis_local, err)
    type(spatial_fourbar_t), intent(inout) :: m
    logical, intent(in) :: at_c
    real(dp), intent(in) :: axis_local(3)
    type(error_t), intent(inout) :: err
    if (.not. (norm2(axis_local) > 0.0_dp)) then
      call err%set('spatial four-bar', 'the universal joint''s axis must be a nonzero vector'); return
    end if
    m%universal_link = merge(link_rocker, link_crank, at_c)
    m%u_local = axis_local/norm2(axis_local)
  end subroutine spatial_fourbar_set_universal

  !> Crank pin B, its derivatives with respect to theta (rotation about a).
  pure subroutine crank_pin(m, theta, b, b_t, b_tt)
    type(spatial_fourbar_t), intent(in) :: m
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: b(3), b_t(3), b_tt(3)
    b = m%a_pivot + rotate_about(m%a_axis, theta, m%b0 - m%a_pivot)
    b_t = cross(m%a_axis, b - m%a_pivot)
    b_tt = cross(m%a_axis, b_t)
  end subroutine crank_pin

  !> Closed form: P cos psi + Q sin psi = S,  psi = atan2(Q, P) + branch acos(S/R).
  !> status 0: assembled; 1: does not assemble (|S| > R).
  pure subroutine rocker_angle_closed_form(m, theta, psi, status)
    type(spatial_fourbar_t), intent(in) :: m
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: psi
    integer, intent(out) :: status
    real(dp) :: p, q, s, r, b(3), bt(3), btt(3)
    call closure_coefficients(m, theta, p, q, s, b, bt, btt)
    r = hypot(p, q)
    status = 0
    psi = 0.0_dp
    if (abs(s) > r) then
      status = 1
      return
    end if
    psi = atan2(q, p) + real(m%branch, dp)*acos(s/r)
  end subroutine rocker_angle_closed_form

  pure subroutine closure_coefficients(m, theta, p, q, s, b, bt, btt)
    type(spatial_fourbar_t), intent(in) :: m
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: p, q, s, b(3), bt(3), btt(3)
    real(dp) :: db(3)
    call crank_pin(m, theta, b, bt, btt)
    db = m%d_pivot - b
    p = 2.0_dp*m%rocker_length*dot_product(db, m%e1)
    q = 2.0_dp*m%rocker_length*dot_product(db, m%e2)
    s = m%coupler_length**2 - dot_product(db, db) - m%rocker_length**2
  end subroutine closure_coefficients

  !> Pose at crank angle theta with rates theta_d, theta_dd: Newton on g = 0
  !> from the previous solution, then the rates, then the link frames.
  subroutine spatial_fourbar_solve(m, theta, theta_d, theta_dd, pose, err)
    type(spatial_fourbar_t), intent(inout) :: m
    real(dp), intent(in) :: theta, theta_d, theta_dd
    type(spatial_pose_t), intent(out) :: pose
    type(error_t), intent(inout) :: err
    real(dp) :: p, q, s, r, b(3), bt(3), btt(3), c(3), cp(3), cpp(3), g, gp, dpsi, psi, side
    real(dp) :: g_t, g_p, g_tt, g_tp, g_pp
    integer :: it, status
    call closure_coefficients(m, theta, p, q, s, b, bt, btt)
    r = hypot(p, q)
    if (abs(s) > r) then
      ! R = 0 (the rocker circle seen edge-on from B, fuzz seed 11): no ratio to print
      if (r > 0.0_dp) then
        call err%set('spatial kinematics', 'the linkage does not assemble at '//where(theta)// &
                     ' (the coupler cannot reach the rocker circle: |S|/R = '//str(abs(s)/r, 8)//')')
      else
        call err%set('spatial kinematics', 'the linkage does not assemble at '//where(theta)// &
                     ' (the rocker circle degenerates as seen from B: R = 0, |S| = '//str(abs(s), 8)//')')
      end if
      return
    end if
    ! The previous solution is a guess on the same branch only nearby: the
    ! integrator may sample far from its last time, and Newton from a stale
    ! guess can converge to the other branch; there the closed form picks
    ! the deck's branch.
    if (m%have_guess .and. abs(theta - m%theta_guess) <= guess_reach) then
      psi = m%psi_guess
    else
      call rocker_angle_closed_form(m, theta, psi, status)
    end if
    do it = 1, 50
      g = p*cos(psi) + q*sin(psi) - s
      gp = -p*sin(psi) + q*cos(psi)                  ! analytic Jacobian dg/dpsi
      if (abs(gp) <= tiny(1.0_dp)) exit
      dpsi = -g/gp
      psi = psi + dpsi
      if (abs(dpsi) <= 1.0e-15_dp*max(1.0_dp, abs(psi))) exit
    end do
    pose%iterations = it
    m%total_iterations = m%total_iterations + it
    m%n_solves = m%n_solves + 1
    side = sin(psi - atan2(q, p))
    if (abs(side) < m%toggle_tol) then
      call err%set('spatial kinematics', 'toggle position at '//where(theta)//' (the coupler is tangent to the '// &
                   'rocker circle: the rocker velocity is undefined)')
      return
    end if
    if (nint(sign(1.0_dp, side)) /= m%branch .or. abs(p*cos(psi) + q*sin(psi) - s) > 1.0e-9_dp*r) then
      call err%set('spatial kinematics', 'Newton left assembly branch '//str(m%branch)//' at '//where(theta)// &
                   ' (a toggle was passed between two solutions: take smaller steps)')
      return
    end if
    m%psi_guess = psi
    m%theta_guess = theta
    m%have_guess = .true.

    ! rates: g(psi(t), theta(t)) = |C - B|^2 - L^2 = 0 differentiated twice
    c = m%d_pivot + m%rocker_length*(cos(psi)*m%e1 + sin(psi)*m%e2)
    cp = cross(m%d_axis, c - m%d_pivot)
    cpp = cross(m%d_axis, cp)
    g_t = -2.0_dp*dot_product(c - b, bt)
    g_p = 2.0_dp*dot_product(c - b, cp)
    g_tt = 2.0_dp*dot_product(bt, bt) - 2.0_dp*dot_product(c - b, btt)
    g_tp = -2.0_dp*dot_product(cp, bt)
    g_pp = 2.0_dp*dot_product(cp, cp) + 2.0_dp*dot_product(c - b, cpp)
    pose%theta = theta
    pose%theta_d = theta_d
    pose%theta_dd = theta_dd
    pose%psi = psi
    pose%psi_d = -g_t/g_p*theta_d
    pose%psi_dd = -(g_tt*theta_d**2 + 2.0_dp*g_tp*theta_d*pose%psi_d + g_pp*pose%psi_d**2 + g_t*theta_dd)/g_p
    pose%b = b
    pose%b_d = bt*theta_d
    pose%b_dd = btt*theta_d**2 + bt*theta_dd
    pose%c = c
    pose%c_d = cp*pose%psi_d
    pose%c_dd = cpp*pose%psi_d**2 + cp*pose%psi_dd
    call link_frames(m, pose)
    if (pose%locked) call err%set('spatial kinematics', 'the universal joint at '// &
      merge('C', 'B', m%universal_link == link_rocker)//' locks at '//where(theta)// &
      ' (the coupler runs along the cross''s axis)')
  end subroutine spatial_fourbar_solve

  !> The crank angle for messages (formatted only when one is written: an
  !> internal write per solve would cost more than the solve).
  function where(theta) result(w)
    real(dp), intent(in) :: theta
    character(len=:), allocatable :: w
    w = 'crank angle '//str(theta*180.0_dp/pi, 8)//' deg'
  end function where

  !> Frames, angular velocities and accelerations, and end-1 motion of the links.
  pure subroutine link_frames(m, pose)
    type(spatial_fourbar_t), intent(in) :: m
    type(spatial_pose_t), intent(inout) :: pose
    real(dp) :: x(3), xd(3), xdd(3), n(3), nd(3), ndd(3), z(3), zd(3), zdd(3), y(3), yd(3), ydd(3)
    real(dp) :: sn, snd, sndd, ll, u(3), ud(3), udd(3)
    integer :: k
    ! crank: rotation about a
    pose%rot(:, :, link_crank) = frame(pose%b - m%a_pivot, m%a_axis)
    pose%omega(:, link_crank) = pose%theta_d*m%a_axis
    pose%alpha(:, link_crank) = pose%theta_dd*m%a_axis
    pose%origin(:, link_crank) = m%a_pivot
    ! rocker: rotation about d
    pose%rot(:, :, link_rocker) = frame(pose%c - m%d_pivot, m%d_axis)
    pose%omega(:, link_rocker) = pose%psi_d*m%d_axis
    pose%alpha(:, link_rocker) = pose%psi_dd*m%d_axis
    pose%origin(:, link_rocker) = m%d_pivot
    ! coupler: x along BC, z = a - (a.x) x normalised; omega = 1/2 sum e_i x e_i'
    ll = m%coupler_length
    x = (pose%c - pose%b)/ll
    xd = (pose%c_d - pose%b_d)/ll
    xdd = (pose%c_dd - pose%b_dd)/ll
    if (m%universal_link == 0) then
      n = m%a_axis - dot_product(m%a_axis, x)*x
      nd = -dot_product(m%a_axis, xd)*x - dot_product(m%a_axis, x)*xd
      ndd = -dot_product(m%a_axis, xdd)*x - 2.0_dp*dot_product(m%a_axis, xd)*xd - dot_product(m%a_axis, x)*xdd
    else
      ! universal joint: the coupler's cross axis z is normal to x and to the link-fixed axis u
      k = m%universal_link
      u = matmul(pose%rot(:, :, k), m%u_local)
      ud = cross(pose%omega(:, k), u)
      udd = cross(pose%alpha(:, k), u) + cross(pose%omega(:, k), ud)
      n = cross(x, u)
      nd = cross(xd, u) + cross(x, ud)
      ndd = cross(xdd, u) + 2.0_dp*cross(xd, ud) + cross(x, udd)
      pose%locked = norm2(n) < m%lock_tol       ! |x cross u|: the coupler's spin is undefined
      if (pose%locked) return
    end if
    sn = norm2(n)
    z = n/sn
    snd = dot_product(z, nd)
    zd = (nd - snd*z)/sn
    sndd = dot_product(zd, nd) + dot_product(z, ndd)
    zdd = (ndd - sndd*z - 2.0_dp*snd*zd)/sn
    y = cross(z, x)
    yd = cross(zd, x) + cross(z, xd)
    ydd = cross(zdd, x) + 2.0_dp*cross(zd, xd) + cross(z, xdd)
    pose%rot(:, 1, link_coupler) = x
    pose%rot(:, 2, link_coupler) = y
    pose%rot(:, 3, link_coupler) = z
    pose%omega(:, link_coupler) = 0.5_dp*(cross(x, xd) + cross(y, yd) + cross(z, zd))
    pose%alpha(:, link_coupler) = 0.5_dp*(cross(x, xdd) + cross(y, ydd) + cross(z, zdd))
    pose%origin(:, link_coupler) = pose%b
    pose%origin_d(:, link_coupler) = pose%b_d
    pose%origin_dd(:, link_coupler) = pose%b_dd
  end subroutine link_frames

  !> Frame with x along `along` and z along `axis` (axis normal to along).
  pure function frame(along, axis) result(r)
    real(dp), intent(in) :: along(3), axis(3)
    real(dp) :: r(3, 3)
    r(:, 1) = along/norm2(along)
    r(:, 3) = axis
    r(:, 2) = cross(axis, r(:, 1))
  end function frame

  !> Rodrigues: v rotated by angle about the unit axis.
  pure function rotate_about(axis, angle, v) result(w)
    real(dp), intent(in) :: axis(3), angle, v(3)
    real(dp) :: w(3)
    w = v*cos(angle) + cross(axis, v)*sin(angle) + axis*dot_product(axis, v)*(1.0_dp - cos(angle))
  end function rotate_about
end module spatial_kinematics
