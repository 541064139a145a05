!> Rigid-body kinematics of a single-degree-of-freedom planar linkage
!> (doc/kinematics.md).
!>
!> Coordinates q: the global position (X, Y) of every joint, the angle phi of
!> every link (from global X, end 1 to end 2), the active length of every link
!> that slides through a sleeve, and the slide coordinate of every joint on a
!> fixed guide.  Constraints Phi(q, theta) = 0: one vector loop per link,
!> P_end2 - P_end1 - l u(phi) = 0; ground points P - G = 0; guides
!> P - G - s g = 0; and the driving constraint phi_crank - theta(t) = 0.
!> Positions come from Newton's method with the analytic Jacobian Phi_q,
!> velocities from Phi_q qd = -Phi_t and accelerations from Phi_q qdd = gamma
!> (Haug's formulation).  The first assembly (and a fallback when Newton fails)
!> places the joints dyad by dyad in closed form on the branch chosen in the
!> deck; later solutions warm-start from the previous one.  A singular
!> Jacobian (toggle), a branch sign that flips between two solutions (a toggle
!> passed), or a dyad that cannot close stops with a message naming the crank
!> angle.
module kinematics
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use linalg, only: lu_factor, lu_solve
  use frame_motion, only: motion_t      ! (the rigid-body motion of a link or element)
  use linkage, only: mechanism_t, joint_slider_fixed, joint_slider_link, driver_angle
  implicit none
  private
  public :: kinematics_t, motion_t, crank_angle_text

  integer, parameter :: step_driver = 1         !< crank tip from the crank angle
  integer, parameter :: step_circle_circle = 2  !< RRR dyad: two circles
  integer, parameter :: step_circle_line = 3    !< RRP dyad: circle and guide line
  integer, parameter :: max_newton = 30
  real(dp), parameter :: newton_tol = 1.0e-11_dp  !< scaled step at which Newton stops
  real(dp), parameter :: residual_tol = 1.0e-14_dp !< scaled residual that needs no further step

  !> One step of the closed-form assembly: place `joint` from the known
  !> joints k1 (input side) and k2 through links link1 and link2.
  type :: assembly_step_t
    integer :: kind = 0
    integer :: joint = 0
    integer :: k1 = 0, k2 = 0
    integer :: link1 = 0, link2 = 0
    integer :: sign = 0          !< branch: sign of the dyad's orientation (+1 open)
  end type assembly_step_t

  type :: kinematics_t
    type(mechanism_t) :: mech
    integer :: n = 0                        !< number of coordinates (= constraints)
    integer, allocatable :: iphi(:)         !< q index of each link angle
    integer, allocatable :: ilen(:)         !< q index of each active length (0: fixed length)
    integer, allocatable :: islide(:)       !< q index of each guide slide (0: not on a guide)
    integer, allocatable :: row_point(:)    !< first of the two rows fixing a joint to ground/guide (0: none)
    integer :: row_driver = 0               !< 0 for a structure at rest (no driver)
    logical :: at_rest = .false.            !< no driver (driver_link = 0): the structure does not move
    real(dp), allocatable :: col_scale(:)   !< 1 for lengths, 1/L for angles: scaled Jacobian
    type(assembly_step_t), allocatable :: steps(:)
    integer :: n_steps = 0
    logical :: plan_complete = .false.      !< every joint is placed by a closed-form step
    logical, allocatable :: placed(:)       !< joint placed by the plan (or on the ground)
    ! state of the last accepted solution
    logical :: assembled = .false.
    logical :: time_driven = .false.
    real(dp) :: t = 0.0_dp, theta = 0.0_dp, theta_d = 0.0_dp, theta_dd = 0.0_dp
    real(dp), allocatable :: q(:), qd(:), qdd(:)
    real(dp), allocatable :: q_theta(:)     !< dq/dtheta, the Newton predictor
    real(dp) :: rcond = 0.0_dp              !< reciprocal condition of the scaled Jacobian
    integer :: iterations = 0               !< Newton iterations of the last solution
    integer :: total_iterations = 0
    integer :: n_solutions = 0
    integer :: n_reassemblies = 0           !< Newton failures rescued by the closed-form assembly
  contains
    procedure :: init => kin_init
    procedure :: reset => kin_reset
    procedure :: solve => kin_solve_time
    procedure :: solve_angle => kin_solve_angle
    procedure :: link_motion
    procedure :: element_motion
    procedure :: element_motion_global
    procedure :: point => link_point
    procedure :: joint_position
    procedure :: joint_velocity
    procedure :: joint_acceleration
    procedure :: slide
  end type kinematics_t

contains

  !> "123.45 deg" (and the angle modulo 360 when it differs), for messages.
  function crank_angle_text(theta) result(s)
    real(dp), intent(in) :: theta
    character(len=:), allocatable :: s
    real(dp) :: deg
    deg = theta*180.0_dp/pi
    s = 'crank angle '//str(deg, 10)//' deg'
    if (deg < 0.0_dp .or. deg >= 360.0_dp) s = s//' ('//str(modulo(deg, 360.0_dp), 10)//' deg modulo 360)'
  end function crank_angle_text

  pure function unit_vec(phi) result(u)
    real(dp), intent(in) :: phi
    real(dp) :: u(2)
    u = [cos(phi), sin(phi)]
  end function unit_vec

  pure function perp(u) result(v)
    real(dp), intent(in) :: u(2)
    real(dp) :: v(2)
    v = [-u(2), u(1)]
  end function perp

  pure real(dp) function cross2(a, b)
    real(dp), intent(in) :: a(2), b(2)
    cross2 = a(1)*b(2) - a(2)*b(1)
  end function cross2

  ! ------------------------------------------------------------------ set-up

  !> Index the coordinates and constraints and plan the closed-form assembly.
  subroutine kin_init(self, mech, err)
    class(kinematics_t), intent(inout) :: self
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    integer :: nj, nl, i, j, k, row
    character(len=:), allocatable :: missing

    self%mech = mech
    nj = mech%n_joints
    nl = mech%n_links
    if (allocated(self%iphi)) deallocate(self%iphi, self%ilen, self%islide, self%row_point, self%col_scale)
    allocate(self%iphi(nl), self%ilen(nl), self%islide(nj), self%row_point(nj))
    k = 2*nj
    do i = 1, nl
      k = k + 1
      self%iphi(i) = k
    end do
    self%ilen = 0
    do i = 1, nl
      if (mech%links(i)%sliding) then
        k = k + 1
        self%ilen(i) = k
      end if
    end do
    self%islide = 0
    do j = 1, nj
      if (mech%joints(j)%kind == joint_slider_fixed) then
        k = k + 1
        self%islide(j) = k
      end if
    end do
    self%n = k
    ! rows: 2 per link, 2 per ground or guided joint, then the driver
    row = 2*nl
    self%row_point = 0
    do j = 1, nj
      if (mech%joints(j)%grounded .or. mech%joints(j)%kind == joint_slider_fixed) then
        self%row_point(j) = row + 1
        row = row + 2
      end if
    end do
    self%at_rest = mech%driver%link == 0
    self%row_driver = row + 1
    if (self%at_rest) then
      ! no driving constraint; build_mechanism allowed mobility <= 0 only
      self%row_driver = 0
    else if (self%row_driver /= self%n) then
      ! build_mechanism's mobility count guarantees this
      call err%set('kinematics', str(self%n)//' coordinates but '//str(self%row_driver)//' constraints', code=2)
      return
    end if
    allocate(self%col_scale(self%n))
    self%col_scale = 1.0_dp
    self%col_scale(self%iphi) = 1.0_dp/mech%length_scale

    call plan_assembly(self)
    if (.not. self%plan_complete) then
      missing = ''
      do j = 1, nj
        if (.not. (self%placed(j) .or. mech%joints(j)%has_position)) &
          missing = missing//' '//trim(mech%joints(j)%name)
      end do
      if (len(missing) > 0) then
        call err%set('kinematics', 'the linkage is not built of dyads that can be placed in closed form; '// &
                     'give joint_x, joint_y (a rough initial position) for joints'//missing, code=2)
        return
      end if
    end if
    call self%reset()
  end subroutine kin_init

  !> Forget the current solution: the next solve assembles afresh.
  subroutine kin_reset(self)
    class(kinematics_t), intent(inout) :: self
    if (allocated(self%q)) deallocate(self%q, self%qd, self%qdd, self%q_theta)
    allocate(self%q(self%n), self%qd(self%n), self%qdd(self%n), self%q_theta(self%n))
    self%q = 0.0_dp
    self%qd = 0.0_dp
    self%qdd = 0.0_dp
    self%q_theta = 0.0_dp
    self%assembled = .false.
    self%iterations = 0
    self%total_iterations = 0
    self%n_solutions = 0
    self%n_reassemblies = 0
  end subroutine kin_reset

  !> Order in which the joints can be placed: the crank tip first, then any
  !> joint reached by two fixed-length links from placed joints (circle-circle)
  !> or a guided joint reached by one (circle-line).  The input side k1 is the
  !> placed joint of higher rank (farther from the ground along the chain).
  subroutine plan_assembly(self)
    class(kinematics_t), intent(inout) :: self
    integer :: rank(self%mech%n_joints), nj, j, k, i, other, found, cand_link(2), cand_joint(2)
    logical :: progress
    type(assembly_step_t) :: st
    nj = self%mech%n_joints
    if (allocated(self%steps)) deallocate(self%steps)
    allocate(self%steps(nj))
    self%n_steps = 0
    rank = -1
    do j = 1, nj
      if (self%mech%joints(j)%grounded) rank(j) = 0
    end do
    if (self%mech%driver%link > 0) then
      associate (dl => self%mech%links(self%mech%driver%link))
        st = assembly_step_t(step_driver, dl%joint(2), dl%joint(1), 0, self%mech%driver%link, 0, 0)
        call add(st)
        rank(dl%joint(2)) = 1
      end associate
    end if
    progress = .true.
    do while (progress)
      progress = .false.
      do j = 1, nj
        if (rank(j) >= 0) cycle
        associate (jt => self%mech%joints(j))
          found = 0
          cand_link = 0
          cand_joint = 0
          do k = 1, jt%n_links
            i = jt%link(k)
            if (self%mech%links(i)%sliding) cycle
            other = self%mech%links(i)%joint(3 - jt%link_end(k))
            if (rank(other) < 0) cycle
            if (found == 1) then
              if (cand_joint(1) == other) cycle
            end if
            found = found + 1
            cand_link(found) = i
            cand_joint(found) = other
            if (jt%kind == joint_slider_fixed .or. found == 2) exit
          end do
          if (jt%kind == joint_slider_fixed .and. found >= 1) then
            st = assembly_step_t(step_circle_line, j, cand_joint(1), 0, cand_link(1), 0, branch_sign(j))
          else if (jt%kind /= joint_slider_fixed .and. found == 2) then
            if (rank(cand_joint(2)) > rank(cand_joint(1))) then
              cand_joint = cand_joint([2, 1])
              cand_link = cand_link([2, 1])
            end if
            st = assembly_step_t(step_circle_circle, j, cand_joint(1), cand_joint(2), cand_link(1), cand_link(2), &
                                 branch_sign(j))
          else
            cycle
          end if
          call add(st)
          rank(j) = 1 + rank(st%k1)
          if (st%k2 > 0) rank(j) = 1 + max(rank(st%k1), rank(st%k2))
          progress = .true.
        end associate
      end do
    end do
    self%placed = rank >= 0
    self%plan_complete = all(self%placed)
  contains
    subroutine add(step)
      type(assembly_step_t), intent(in) :: step
      self%n_steps = self%n_steps + 1
      self%steps(self%n_steps) = step
    end subroutine add
    integer function branch_sign(joint)
      integer, intent(in) :: joint
      branch_sign = self%mech%joints(joint)%branch
      if (branch_sign == 0) branch_sign = self%mech%branch
    end function branch_sign
  end subroutine plan_assembly

  ! ------------------------------------------------------------------ constraints

  pure real(dp) function length_of(self, q, i)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    integer, intent(in) :: i
    if (self%ilen(i) > 0) then
      length_of = q(self%ilen(i))
    else
      length_of = self%mech%links(i)%length
    end if
  end function length_of

  !> Phi(q, theta).
  pure subroutine residual(self, q, theta, f)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:), theta
    real(dp), intent(out) :: f(:)
    integer :: i, j, a, b, r
    do i = 1, self%mech%n_links
      a = self%mech%links(i)%joint(1)
      b = self%mech%links(i)%joint(2)
      ! link loop: P_b - P_a - l u(phi) = 0
      f(2*i-1:2*i) = q(2*b-1:2*b) - q(2*a-1:2*a) - length_of(self, q, i)*unit_vec(q(self%iphi(i)))
    end do
    do j = 1, self%mech%n_joints
      r = self%row_point(j)
      if (r == 0) cycle
      associate (jt => self%mech%joints(j))
        f(r:r+1) = q(2*j-1:2*j) - [jt%x, jt%y]
        if (self%islide(j) > 0) f(r:r+1) = f(r:r+1) - q(self%islide(j))*jt%guide
      end associate
    end do
    if (self%row_driver > 0) f(self%row_driver) = q(self%iphi(self%mech%driver%link)) - theta
  end subroutine residual

  !> Phi_q, analytic.
  pure subroutine jacobian(self, q, jac)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: jac(:, :)
    integer :: i, j, a, b, r, k
    real(dp) :: u(2)
    jac = 0.0_dp
    do i = 1, self%mech%n_links
      a = self%mech%links(i)%joint(1)
      b = self%mech%links(i)%joint(2)
      r = 2*i - 1
      u = unit_vec(q(self%iphi(i)))
      do k = 0, 1
        jac(r+k, 2*b-1+k) = 1.0_dp
        jac(r+k, 2*a-1+k) = -1.0_dp
      end do
      jac(r:r+1, self%iphi(i)) = -length_of(self, q, i)*perp(u)
      if (self%ilen(i) > 0) jac(r:r+1, self%ilen(i)) = -u
    end do
    do j = 1, self%mech%n_joints
      r = self%row_point(j)
      if (r == 0) cycle
      jac(r, 2*j-1) = 1.0_dp
      jac(r+1, 2*j) = 1.0_dp
      if (self%islide(j) > 0) jac(r:r+1, self%islide(j)) = -self%mech%joints(j)%guide
    end do
    if (self%row_driver > 0) jac(self%row_driver, self%iphi(self%mech%driver%link)) = 1.0_dp
  end subroutine jacobian

  !> gamma = -(Phi_q qd)_q qd - Phi_tt, the right side of Phi_q qdd = gamma.
  pure subroutine accel_rhs(self, q, qd, theta_dd, g)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:), qd(:), theta_dd
    real(dp), intent(out) :: g(:)
    integer :: i
    real(dp) :: u(2), l, ld, phid
    g = 0.0_dp
    do i = 1, self%mech%n_links
      u = unit_vec(q(self%iphi(i)))
      l = length_of(self, q, i)
      ld = 0.0_dp
      if (self%ilen(i) > 0) ld = qd(self%ilen(i))
      phid = qd(self%iphi(i))
      ! d2/dt2 of l u(phi) = ldd u + l phidd u_perp + 2 ld phid u_perp - l phid^2 u
      g(2*i-1:2*i) = 2.0_dp*ld*phid*perp(u) - l*phid**2*u
    end do
    if (self%row_driver > 0) g(self%row_driver) = theta_dd
  end subroutine accel_rhs

  !> Factor the row- and column-scaled Jacobian R Phi_q C (R scales the driver
  !> row by L, C the angle columns by 1/L) so that rcond is dimensionless.
  subroutine factor_scaled(self, q, lu, ipiv, rcond, err)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: lu(:, :)
    integer, intent(out) :: ipiv(:)
    real(dp), intent(out), optional :: rcond
    type(error_t), intent(inout) :: err
    integer :: k
    call jacobian(self, q, lu)
    lu(self%row_driver, :) = lu(self%row_driver, :)*self%mech%length_scale
    do k = 1, self%n
      lu(:, k) = lu(:, k)*self%col_scale(k)
    end do
    call lu_factor(lu, ipiv, err, rcond)
  end subroutine factor_scaled

  !> Solve Phi_q x = rhs with the scaled factors.
  subroutine solve_scaled(self, lu, ipiv, rhs, x, err)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: lu(:, :), rhs(:)
    integer, intent(in) :: ipiv(:)
    real(dp), intent(out) :: x(:)
    type(error_t), intent(inout) :: err
    real(dp) :: y(self%n)
    y = rhs
    y(self%row_driver) = y(self%row_driver)*self%mech%length_scale
    call lu_solve(lu, ipiv, y, err)
    x = y*self%col_scale
  end subroutine solve_scaled

  !> Newton's method on Phi(q, theta) = 0 from the given q.
  subroutine newton(self, theta, q, converged, iterations)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: theta
    real(dp), intent(inout) :: q(:)
    logical, intent(out) :: converged
    integer, intent(out) :: iterations
    real(dp) :: lu(self%n, self%n), f(self%n), dq(self%n), step
    integer :: ipiv(self%n), it
    type(error_t) :: e
    converged = .false.
    iterations = 0
    do it = 1, max_newton
      call residual(self, q, theta, f)
      f(self%row_driver) = f(self%row_driver)*self%mech%length_scale
      ! A guess that already closes to rounding (an exact closed-form
      ! assembly, whose Jacobian may be singular at a toggle: the caller
      ! diagnoses that) needs no step.  Only the first iterate is accepted
      ! this way: near a singular point a small residual does not mean a
      ! small error (it is quadratic in the error along the null direction).
      if (it == 1 .and. maxval(abs(f)) <= residual_tol*self%mech%length_scale) then
        converged = .true.
        return
      end if
      f(self%row_driver) = f(self%row_driver)/self%mech%length_scale
      iterations = it
      ! no condition estimate inside Newton: the toggle test after convergence makes it
      call factor_scaled(self, q, lu, ipiv, err=e)
      if (e%failed()) return
      call solve_scaled(self, lu, ipiv, -f, dq, e)
      if (e%failed()) return
      q = q + dq
      ! step measured in lengths relative to the link scale and in radians
      step = maxval(abs(dq/self%col_scale))/self%mech%length_scale
      if (.not. step < 1.0e3_dp) return
      if (step <= newton_tol) then
        converged = .true.
        return
      end if
    end do
  end subroutine newton

  !> Place every joint the plan reaches in closed form at crank angle theta
  !> on the designated branches; the others stay at their deck reference
  !> positions.  On failure `reason` says which dyad cannot close.
  subroutine construct(self, theta, q, ok, reason)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: q(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: reason
    real(dp) :: p(2, self%mech%n_joints), c1(2), c2(2), r1, r2, d, a, h, e(2), w(2), b, disc, s
    integer :: k, j, i, m
    reason = ''
    ok = .false.
    q = 0.0_dp
    do j = 1, self%mech%n_joints
      p(:, j) = [self%mech%joints(j)%x, self%mech%joints(j)%y]
    end do
    do k = 1, self%n_steps
      associate (st => self%steps(k))
        j = st%joint
        select case (st%kind)
        case (step_driver)
          p(:, j) = p(:, st%k1) + self%mech%links(st%link1)%length*unit_vec(theta)
        case (step_circle_circle)
          c1 = p(:, st%k1)
          c2 = p(:, st%k2)
          r1 = self%mech%links(st%link1)%length
          r2 = self%mech%links(st%link2)%length
          d = norm2(c2 - c1)
          if (d > r1 + r2 .or. d < abs(r1 - r2) .or. .not. d > 0.0_dp) then
            reason = 'joint '//trim(self%mech%joints(j)%name)//' cannot be placed: joints '// &
                     trim(self%mech%joints(st%k1)%name)//' and '//trim(self%mech%joints(st%k2)%name)//' are '// &
                     str(d, 8)//' apart but links '//trim(self%mech%links(st%link1)%name)//' ('//str(r1, 8)// &
                     ') and '//trim(self%mech%links(st%link2)%name)//' ('//str(r2, 8)//') span only ['// &
                     str(abs(r1 - r2), 8)//', '//str(r1 + r2, 8)//']'
            return
          end if
          a = (r1**2 - r2**2 + d**2)/(2.0_dp*d)
          h = sqrt(max(r1**2 - a**2, 0.0_dp))
          e = (c2 - c1)/d
          ! cross(P - c1, P - c2) = d h sign: the sign picks the branch
          p(:, j) = c1 + a*e + real(st%sign, dp)*h*perp(e)
        case (step_circle_line)
          associate (jt => self%mech%joints(j))
            r1 = self%mech%links(st%link1)%length
            w = [jt%x, jt%y] - p(:, st%k1)
            b = dot_product(jt%guide, w)
            disc = b**2 - dot_product(w, w) + r1**2
            if (disc < 0.0_dp) then
              reason = 'joint '//trim(jt%name)//' cannot be placed: joint '//trim(self%mech%joints(st%k1)%name)// &
                       ' is '//str(abs(cross2(jt%guide, w)), 8)//' from the guide but link '// &
                       trim(self%mech%links(st%link1)%name)//' is only '//str(r1, 8)//' long'
              return
            end if
            ! guide . (P - K) = sign sqrt(disc)
            s = -b + real(st%sign, dp)*sqrt(disc)
            p(:, j) = [jt%x, jt%y] + s*jt%guide
          end associate
        end select
      end associate
    end do
    call coordinates_from_points(self, p, theta, q)
    do i = 1, self%mech%n_links
      m = self%ilen(i)
      if (m > 0) then
        if (.not. q(m) > 0.0_dp) then
          reason = 'link '//trim(self%mech%links(i)%name)//' has its end at its sleeve'
          return
        end if
      end if
    end do
    ok = .true.
  end subroutine construct

  !> q from joint positions: angles, active lengths and slides follow.
  subroutine coordinates_from_points(self, p, theta, q)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: p(:, :), theta
    real(dp), intent(out) :: q(:)
    integer :: i, j
    real(dp) :: v(2)
    q = 0.0_dp
    do j = 1, self%mech%n_joints
      q(2*j-1:2*j) = p(:, j)
      if (self%islide(j) > 0) q(self%islide(j)) = &
        dot_product(self%mech%joints(j)%guide, p(:, j) - [self%mech%joints(j)%x, self%mech%joints(j)%y])
    end do
    do i = 1, self%mech%n_links
      v = p(:, self%mech%links(i)%joint(2)) - p(:, self%mech%links(i)%joint(1))
      q(self%iphi(i)) = atan2(v(2), v(1))
      if (self%ilen(i) > 0) q(self%ilen(i)) = norm2(v)
    end do
    if (self%mech%driver%link > 0) q(self%iphi(self%mech%driver%link)) = theta
  end subroutine coordinates_from_points

  !> Sign of each dyad's orientation in configuration q (0 if degenerate).
  pure function dyad_signs(self, q) result(sg)
    class(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    integer :: sg(self%n_steps)
    integer :: k, j
    real(dp) :: v
    sg = 0
    do k = 1, self%n_steps
      associate (st => self%steps(k))
        j = st%joint
        select case (st%kind)
        case (step_circle_circle)
          v = cross2(q(2*j-1:2*j) - q(2*st%k1-1:2*st%k1), q(2*j-1:2*j) - q(2*st%k2-1:2*st%k2))
        case (step_circle_line)
          v = dot_product(self%mech%joints(j)%guide, q(2*j-1:2*j) - q(2*st%k1-1:2*st%k1))
        case default
          cycle
        end select
        if (v > 0.0_dp) sg(k) = 1
        if (v < 0.0_dp) sg(k) = -1
      end associate
    end do
  end function dyad_signs

  ! ------------------------------------------------------------------ solution

  !> Solve positions, velocities and accelerations at time t (crank angle from
  !> the driver profile).
  subroutine kin_solve_time(self, t, err)
    class(kinematics_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t), intent(inout) :: err
    real(dp) :: th, thd, thdd
    call driver_angle(self%mech%driver, t, th, thd, thdd)
    call self%solve_angle(th, thd, thdd, err)
    if (err%failed()) then
      call err%add_context('t = '//str(t, 10)//' s')
      return
    end if
    self%t = t
    self%time_driven = .true.
  end subroutine kin_solve_time

  !> Solve at crank angle theta (rad, unwrapped) with crank speed theta_d and
  !> acceleration theta_dd.  On failure the previous solution is kept.
  subroutine kin_solve_angle(self, theta, theta_d, theta_dd, err)
    class(kinematics_t), intent(inout) :: self
    real(dp), intent(in) :: theta, theta_d, theta_dd
    type(error_t), intent(inout) :: err
    real(dp) :: qn(self%n), qp(self%n), lu(self%n, self%n), rhs(self%n), qd(self%n), qdd(self%n), rc
    integer :: ipiv(self%n), its
    logical :: rescued
    type(error_t) :: e

    if (self%at_rest) then
      call solve_at_rest(self, theta, err)
      return
    end if
    call solve_positions(self, theta, qn, its, rescued, err)
    if (err%failed()) return
    call check_configuration(self, theta, qn, lu, ipiv, rc, err)
    if (err%failed()) return

    ! velocities: Phi_q qd = -Phi_t (only the driver row depends on t)
    rhs = 0.0_dp
    rhs(self%row_driver) = 1.0_dp
    call solve_scaled(self, lu, ipiv, rhs, qp, e)
    qd = qp*theta_d
    ! accelerations: Phi_q qdd = gamma
    call accel_rhs(self, qn, qd, theta_dd, rhs)
    call solve_scaled(self, lu, ipiv, rhs, qdd, e)
    if (e%failed()) then
      call err%set('kinematics', e%text()//' at '//crank_angle_text(theta))
      return
    end if

    self%q = qn
    self%q_theta = qp
    self%qd = qd
    self%qdd = qdd
    self%theta = theta
    self%theta_d = theta_d
    self%theta_dd = theta_dd
    self%rcond = rc
    self%iterations = its
    self%total_iterations = self%total_iterations + its
    self%n_solutions = self%n_solutions + 1
    if (rescued) self%n_reassemblies = self%n_reassemblies + 1
    self%assembled = .true.
    self%time_driven = .false.
  end subroutine kin_solve_angle

  !> Positions at theta: closed-form assembly and Newton the first time, then
  !> Newton from a first-order predictor, falling back to a fresh closed-form
  !> assembly (rescued) when the predictor does not converge.
  subroutine solve_positions(self, theta, qn, its, rescued, err)
    type(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: theta
    real(dp), intent(out) :: qn(self%n)
    integer, intent(out) :: its
    logical, intent(out) :: rescued
    type(error_t), intent(inout) :: err
    real(dp) :: qp(self%n)
    integer :: i, k
    logical :: ok
    character(len=:), allocatable :: reason

    rescued = .false.
    if (.not. self%assembled) then
      ! closed-form placement; joints the plan cannot reach keep the
      ! reference positions of the deck as Newton's starting point
      call construct(self, theta, qn, ok, reason)
      if (.not. ok) then
        call err%set('kinematics', 'the linkage cannot be assembled at '//crank_angle_text(theta)//': '//reason)
        return
      end if
      call newton(self, theta, qn, ok, its)
      if (.not. ok) then
        call err%set('kinematics', 'Newton did not converge when assembling the linkage at '// &
                     crank_angle_text(theta)//' (the linkage may not assemble there, or the given joint '// &
                     'positions are too far from an assembly)')
        return
      end if
    else
      ! warm start: first-order predictor along the solution curve
      qp = self%q + self%q_theta*(theta - self%theta)
      qn = qp
      call newton(self, theta, qn, ok, its)
      if (.not. ok) then
        if (.not. self%plan_complete) then
          call err%set('kinematics', 'Newton did not converge at '//crank_angle_text(theta)//' (from '// &
                       crank_angle_text(self%theta)//'): the linkage may not assemble there; try smaller steps')
          return
        end if
        call construct(self, theta, qn, ok, reason)
        if (.not. ok) then
          call err%set('kinematics', 'the linkage cannot be assembled at '//crank_angle_text(theta)//' (last '// &
                       'assembled at '//str(self%theta*180.0_dp/pi, 10)//' deg): '//reason)
          return
        end if
        ! keep angles continuous with the previous solution
        do i = 1, self%mech%n_links
          k = self%iphi(i)
          qn(k) = qp(k) + modulo(qn(k) - qp(k) + pi, two_pi) - pi
        end do
        call newton(self, theta, qn, ok, its)
        if (.not. ok) then
          call err%set('kinematics', 'Newton did not converge at '//crank_angle_text(theta)// &
                       ' even from the closed-form assembly (near a toggle?)')
          return
        end if
        rescued = .true.
      end if
    end if
  end subroutine solve_positions

  !> The solution at theta is usable: the constraint Jacobian is regular
  !> (factored here for the rates), no dyad flipped branch since the last
  !> solution, and every sliding link is inside its sleeve.
  subroutine check_configuration(self, theta, qn, lu, ipiv, rc, err)
    type(kinematics_t), intent(in) :: self
    real(dp), intent(in) :: theta, qn(self%n)
    real(dp), intent(out) :: lu(self%n, self%n), rc
    integer, intent(out) :: ipiv(self%n)
    type(error_t), intent(inout) :: err
    integer :: sg(self%n_steps), i, k
    type(error_t) :: e

    ! toggle: singular Jacobian
    call factor_scaled(self, qn, lu, ipiv, rc, e)
    if (e%failed() .or. .not. rc >= self%mech%toggle_rcond) then
      if (e%failed()) rc = 0.0_dp
      call err%set('kinematics', 'toggle (dead-centre) position at '//crank_angle_text(theta)// &
                   ': the constraint Jacobian is singular (reciprocal condition '//str(rc, 3)//' < toggle_rcond = '// &
                   str(self%mech%toggle_rcond, 3)//')')
      return
    end if
    ! toggle passed: a dyad's orientation flipped since the last solution
    sg = dyad_signs(self, qn)
    do k = 1, self%n_steps
      if (self%steps(k)%kind == step_driver) cycle
      if (sg(k) /= self%steps(k)%sign) then
        if (self%assembled) then
          call err%set('kinematics', 'the linkage passed a toggle (dead-centre) position at joint '// &
                       trim(self%mech%joints(self%steps(k)%joint)%name)//' between '// &
                       crank_angle_text(self%theta)//' and '//crank_angle_text(theta)// &
                       ': its dyad changed branch')
        else
          call err%set('kinematics', 'toggle (dead-centre) position at '//crank_angle_text(theta)//' at joint '// &
                       trim(self%mech%joints(self%steps(k)%joint)%name))
        end if
        return
      end if
    end do
    ! sliding links must stay in their sleeves
    do i = 1, self%mech%n_links
      k = self%ilen(i)
      if (k == 0) cycle
      if (.not. qn(k) > 1.0e-9_dp*self%mech%length_scale) then
        call err%set('kinematics', 'link '//trim(self%mech%links(i)%name)//' reaches its sleeve (active length '// &
                     str(qn(k), 6)//') at '//crank_angle_text(theta))
        return
      end if
      if (self%mech%links(i)%length > 0.0_dp .and. qn(k) > self%mech%links(i)%length) then
        call err%set('kinematics', 'link '//trim(self%mech%links(i)%name)//' slides out of its sleeve (active '// &
                     'length '//str(qn(k), 8)//' > link_length '//str(self%mech%links(i)%length, 8)//') at '// &
                     crank_angle_text(theta))
        return
      end if
    end do
  end subroutine check_configuration

  !> A structure without a driver: place it once (closed-form dyads from the
  !> ground, deck positions for the other joints), check that every link
  !> fits between its joints, and keep it at rest.
  subroutine solve_at_rest(self, theta, err)
    class(kinematics_t), intent(inout) :: self
    real(dp), intent(in) :: theta
    type(error_t), intent(inout) :: err
    real(dp) :: qn(self%n), d, l
    integer :: i, a, b
    logical :: ok
    character(len=:), allocatable :: reason
    if (.not. self%assembled) then
      call construct(self, theta, qn, ok, reason)
      if (.not. ok) then
        call err%set('kinematics', 'the structure cannot be assembled: '//reason)
        return
      end if
      do i = 1, self%mech%n_links
        if (self%ilen(i) > 0) cycle
        a = self%mech%links(i)%joint(1)
        b = self%mech%links(i)%joint(2)
        d = norm2(qn(2*b-1:2*b) - qn(2*a-1:2*a))
        l = self%mech%links(i)%length
        if (abs(d - l) > 1.0e-9_dp*self%mech%length_scale) then
          call err%set('kinematics', 'the structure does not fit together: link '// &
                       trim(self%mech%links(i)%name)//' is '//str(l, 10)//' long but its joints '// &
                       trim(self%mech%joints(a)%name)//' and '//trim(self%mech%joints(b)%name)//' are '// &
                       str(d, 10)//' apart')
          return
        end if
      end do
      self%q = qn
      self%qd = 0.0_dp
      self%qdd = 0.0_dp
      self%q_theta = 0.0_dp
      self%rcond = 1.0_dp
      self%assembled = .true.
    end if
    self%theta = theta
    self%theta_d = 0.0_dp
    self%theta_dd = 0.0_dp
    self%iterations = 0
    self%n_solutions = self%n_solutions + 1
    self%time_driven = .false.
  end subroutine solve_at_rest

  ! ------------------------------------------------------------------ results

  !> Motion of the point at fraction f of link i's (active) length.
  pure function motion_at_fraction(self, i, f, n) result(m)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: i, n
    real(dp), intent(in) :: f
    type(motion_t) :: m
    integer :: a
    real(dp) :: u(2), up(2), l, ld, ldd, phid, phidd, r(2), v(2), acc(2)
    a = self%mech%links(i)%joint(1)
    u = unit_vec(self%q(self%iphi(i)))
    up = perp(u)
    l = length_of(self, self%q, i)
    ld = 0.0_dp
    ldd = 0.0_dp
    if (self%ilen(i) > 0) then
      ld = self%qd(self%ilen(i))
      ldd = self%qdd(self%ilen(i))
    end if
    phid = self%qd(self%iphi(i))
    phidd = self%qdd(self%iphi(i))
    r = self%q(2*a-1:2*a) + f*l*u
    v = self%qd(2*a-1:2*a) + f*(ld*u + l*phid*up)
    acc = self%qdd(2*a-1:2*a) + f*(ldd*u + 2.0_dp*ld*phid*up + l*phidd*up - l*phid**2*u)
    m%x1 = r(1); m%y1 = r(2); m%phi = self%q(self%iphi(i))
    m%x1_d = v(1); m%y1_d = v(2); m%phi_d = phid
    m%x1_dd = acc(1); m%y1_dd = acc(2); m%phi_dd = phidd
    m%length = l/n; m%length_d = ld/n; m%length_dd = ldd/n
  end function motion_at_fraction

  !> Link i: end 1, angle of its reference line, (active) length, and rates.
  pure function link_motion(self, i) result(m)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: i
    type(motion_t) :: m
    m = motion_at_fraction(self, i, 0.0_dp, 1)
  end function link_motion

  !> Element k (1 = at end 1) of link i: its end 1, angle and length, with rates.
  !> The elements split the link's (active) length evenly.
  pure function element_motion(self, i, k) result(m)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: i, k
    type(motion_t) :: m
    integer :: n
    n = self%mech%links(i)%n_elements
    m = motion_at_fraction(self, i, real(k - 1, dp)/real(n, dp), n)
  end function element_motion

  !> Element by its global number (links in order, elements from end 1).
  pure function element_motion_global(self, e) result(m)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: e
    type(motion_t) :: m
    integer :: i
    do i = self%mech%n_links, 1, -1
      if (e >= self%mech%links(i)%first_element) exit
    end do
    m = self%element_motion(i, e - self%mech%links(i)%first_element + 1)
  end function element_motion_global

  !> Material point of link i at distance s from end 1 along the reference
  !> line and d to its left: global position, velocity, acceleration.
  pure subroutine link_point(self, i, s, d, r, v, a)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: s, d
    real(dp), intent(out) :: r(2)
    real(dp), intent(out), optional :: v(2), a(2)
    integer :: j
    real(dp) :: u(2), up(2), rel(2), phid, phidd
    j = self%mech%links(i)%joint(1)
    u = unit_vec(self%q(self%iphi(i)))
    up = perp(u)
    rel = s*u + d*up
    phid = self%qd(self%iphi(i))
    phidd = self%qdd(self%iphi(i))
    r = self%q(2*j-1:2*j) + rel
    if (present(v)) v = self%qd(2*j-1:2*j) + phid*perp(rel)
    if (present(a)) a = self%qdd(2*j-1:2*j) + phidd*perp(rel) - phid**2*rel
  end subroutine link_point

  pure function joint_position(self, j) result(p)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: j
    real(dp) :: p(2)
    p = self%q(2*j-1:2*j)
  end function joint_position

  pure function joint_velocity(self, j) result(p)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: j
    real(dp) :: p(2)
    p = self%qd(2*j-1:2*j)
  end function joint_velocity

  pure function joint_acceleration(self, j) result(p)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: j
    real(dp) :: p(2)
    p = self%qdd(2*j-1:2*j)
  end function joint_acceleration

  !> Slide of a joint on a fixed guide from its guide point, and its rates
  !> (zeros for other joints).
  pure function slide(self, j) result(s)
    class(kinematics_t), intent(in) :: self
    integer, intent(in) :: j
    real(dp) :: s(3)
    s = 0.0_dp
    if (self%islide(j) > 0) s = [self%q(self%islide(j)), self%qd(self%islide(j)), self%qdd(self%islide(j))]
  end function slide
end module kinematics
