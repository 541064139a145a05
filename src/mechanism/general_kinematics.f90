!> Rigid-body kinematics of a general mechanism (module general_mechanism)
!> in body coordinates (Nikravesh 1988; Haug 1989): per link q_b = (x, y, theta) in the plane, or the
!> position of its frame's origin and its Euler parameters p = (e0, e) in
!> space, with the constraint p.p - 1 = 0.  A body-fixed point s is at
!> r + A(q_b) s.  Every joint constraint is built from three scalars of points
!> and body-fixed vectors, each carried with its Jacobian row and the part of
!> its second time derivative that does not multiply q'' ("rem"):
!>   point difference   P_j - P_i (per component)
!>   dot of vectors     u_i . w_j                       (Haug's dot-1)
!>   vector on a gap    u_i . (P_j - P_i)               (Haug's dot-2)
!> Joints (members i = the joint's first member, j = each other one):
!>   planar revolute 2 rows, prismatic 2 (gap on the normal, angles equal),
!>   slider 1 (point on the line), weld 3;
!>   spatial spherical 3, universal 4 (+ a_i . b_j), revolute 5 (+ f_i . h_j,
!>   g_i . h_j), prismatic 5 (f_i . h_j, g_i . h_j, f_i . g_j, gaps on f_i
!>   and g_i), slider 2 (gaps on f_i, g_i), weld 6; a link between two
!>   joints that leave its rotation free (spherical, slider) spins idly about
!>   its line: one row keeps its drawn normal b = (line x Z) normal to Z.
!> Drivers: planar angle theta_j - theta_i = psi(t); spatial rotation
!> cos(psi) g_i.f_j - sin(psi) f_i.f_j = 0; slide h_i.(P_j - P_i) = s(t).
!> Positions by Newton's method on Phi(q, t) = 0 with the analytic Jacobian,
!> started from the drawing and then from a second-order predictor;
!> velocities from Phi_q q' = -Phi_t, accelerations from Phi_q q'' = gamma.
!> Mobility (Kutzbach count and the Jacobian's rank in the drawing), under-
!> and over-driving, toggles (the scaled Jacobian's reciprocal condition, and
!> a sign change of its determinant between two solutions) and failures to
!> assemble are reported naming the joint, link or driver and the time.
module general_kinematics
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use linalg, only: lu_factor, lu_solve, cross, outer, identity
  use motion_profile, only: motion_value
  use general_mechanism, only: general_mechanism_t, gjoint_t, gjoint_revolute, gjoint_prismatic, gjoint_slider, &
    gjoint_spherical, gjoint_universal, gjoint_weld, gjoint_free, gjoint_names, unit_or_zero
  implicit none
  private
  public :: general_kinematics_t, scalar_t, joint_has_value

  integer, parameter :: max_newton = 40
  real(dp), parameter :: newton_tol = 1.0e-12_dp    !< scaled step at which Newton stops
  real(dp), parameter :: residual_tol = 1.0e-15_dp !< scaled residual that needs no further step
  real(dp), parameter :: rank_tol = 1.0e-8_dp       !< relative residual of a dependent Jacobian row

  !> A point or a body-fixed vector of one link: value, Jacobian, velocity
  !> and the q''-free part of its acceleration.
  type :: kin_vec_t
    integer :: body = 0
    real(dp) :: val(3) = 0.0_dp, vel(3) = 0.0_dp, quad(3) = 0.0_dp
    real(dp) :: jac(3, 7) = 0.0_dp
  end type kin_vec_t

  !> A scalar function of two bodies' coordinates (a constraint row).
  type :: scalar_t
    integer :: body(2) = 0
    real(dp) :: val = 0.0_dp, rate = 0.0_dp, rem = 0.0_dp, phit = 0.0_dp
    real(dp) :: jac(7, 2) = 0.0_dp
    logical :: length = .false.      !< has the dimension of a length (scaled by 1/L)
  end type scalar_t

  type :: general_kinematics_t
    type(general_mechanism_t) :: mech
    integer :: nqb = 3, n = 0, m = 0
    integer :: n_joint_rows = 0, n_idle = 0
    integer, allocatable :: row_joint(:)    !< joint of each row; -k driver k; 0 normalization or idle spin
    logical, allocatable :: idle(:)         !< link spinning idly between spherical or slider joints
    real(dp), allocatable :: col_scale(:), row_scale(:)
    integer :: mobility = 0, kutzbach = 0
    real(dp), allocatable :: q(:), qd(:), qdd(:), q0(:)
    real(dp) :: t = 0.0_dp, rcond = 0.0_dp
    integer :: det_sign = 0
    logical :: assembled = .false.
    integer :: iterations = 0, total_iterations = 0, n_solutions = 0
  contains
    procedure :: init => gk_init
    procedure :: solve => gk_solve
    procedure :: point => gk_point
    procedure :: joint_value
    procedure :: body_motion
    procedure :: body_rotation
  end type general_kinematics_t

contains

  pure logical function joint_has_value(j)
    type(gjoint_t), intent(in) :: j
    joint_has_value = size(j%member) == 2 .and. any(j%kind == [gjoint_revolute, gjoint_prismatic, gjoint_slider])
  end function joint_has_value

  ! ------------------------------------------------------------ primitives

  !> A body-fixed point (translate) or vector of link b (0: the ground).
  pure function body_vec(self, q, qd, b, s, translate) result(v)
    class(general_kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:), qd(:), s(3)
    integer, intent(in) :: b
    logical, intent(in) :: translate
    type(kin_vec_t) :: v
    integer :: o
    real(dp) :: c, sn, as(3), e0, e(3), de0, de(3)
    v%body = b
    if (b == 0) then
      v%val = s
      return
    end if
    o = (b - 1)*self%nqb
    if (.not. self%mech%spatial) then
      c = cos(q(o + 3))
      sn = sin(q(o + 3))
      as = [c*s(1) - sn*s(2), sn*s(1) + c*s(2), 0.0_dp]
      v%val = as
      v%jac(:, 3) = [-as(2), as(1), 0.0_dp]
      v%quad = -qd(o + 3)**2*as
      if (translate) then
        v%val(1:2) = v%val(1:2) + q(o + 1:o + 2)
        v%jac(1, 1) = 1.0_dp
        v%jac(2, 2) = 1.0_dp
      end if
      v%vel = matmul(v%jac(:, 1:3), qd(o + 1:o + 3))
    else
      e0 = q(o + 4)
      e = q(o + 5:o + 7)
      de0 = qd(o + 4)
      de = qd(o + 5:o + 7)
      ! A(p) s = (2 e0^2 - 1) s + 2 e (e.s) + 2 e0 e x s   (Nikravesh 1988)
      v%val = (2.0_dp*e0*e0 - 1.0_dp)*s + 2.0_dp*e*dot_product(e, s) + 2.0_dp*e0*cross(e, s)
      v%jac(:, 4) = 4.0_dp*e0*s + 2.0_dp*cross(e, s)
      v%jac(:, 5:7) = 2.0_dp*(dot_product(e, s)*identity(3) + outer(e, s)) - 2.0_dp*e0*skew(s)
      v%quad = 4.0_dp*de0*de0*s + 4.0_dp*de*dot_product(de, s) + 4.0_dp*de0*cross(de, s)
      if (translate) then
        v%val = v%val + q(o + 1:o + 3)
        v%jac(:, 1:3) = identity(3)
      end if
      v%vel = matmul(v%jac, qd(o + 1:o + 7))
    end if
  end function body_vec

  !> Component k of P_j - P_i.
  pure function diff_row(pi_, pj, k) result(r)
    type(kin_vec_t), intent(in) :: pi_, pj
    integer, intent(in) :: k
    type(scalar_t) :: r
    r%body = [pi_%body, pj%body]
    r%val = pj%val(k) - pi_%val(k)
    r%rate = pj%vel(k) - pi_%vel(k)
    r%rem = pj%quad(k) - pi_%quad(k)
    r%jac(:, 1) = -pi_%jac(k, :)
    r%jac(:, 2) = pj%jac(k, :)
    r%length = .true.
  end function diff_row

  !> u . w, u fixed in body i, w in body j.
  pure function dot_row(u, w) result(r)
    type(kin_vec_t), intent(in) :: u, w
    type(scalar_t) :: r
    r%body = [u%body, w%body]
    r%val = dot_product(u%val, w%val)
    r%rate = dot_product(u%vel, w%val) + dot_product(u%val, w%vel)
    r%rem = dot_product(u%quad, w%val) + dot_product(u%val, w%quad) + 2.0_dp*dot_product(u%vel, w%vel)
    r%jac(:, 1) = matmul(w%val, u%jac)
    r%jac(:, 2) = matmul(u%val, w%jac)
  end function dot_row

  !> u . (P_j - P_i), u and P_i fixed in body i, P_j in body j.
  pure function gap_row(u, pi_, pj) result(r)
    type(kin_vec_t), intent(in) :: u, pi_, pj
    type(scalar_t) :: r
    real(dp) :: d(3), dd(3)
    d = pj%val - pi_%val
    dd = pj%vel - pi_%vel
    r%body = [pi_%body, pj%body]
    r%val = dot_product(u%val, d)
    r%rate = dot_product(u%vel, d) + dot_product(u%val, dd)
    r%rem = dot_product(u%quad, d) + dot_product(u%val, pj%quad - pi_%quad) + 2.0_dp*dot_product(u%vel, dd)
    r%jac(:, 1) = matmul(d, u%jac) - matmul(u%val, pi_%jac)
    r%jac(:, 2) = matmul(u%val, pj%jac)
    r%length = .true.
  end function gap_row

  !> theta_j - theta_i (plane).
  pure function angle_row(q, qd, bi, bj) result(r)
    real(dp), intent(in) :: q(:), qd(:)
    integer, intent(in) :: bi, bj
    type(scalar_t) :: r
    r%body = [bi, bj]
    r%jac(3, :) = [-1.0_dp, 1.0_dp]
    r%val = at(q, bj) - at(q, bi)
    r%rate = at(qd, bj) - at(qd, bi)
  contains
    pure real(dp) function at(x, b)
      real(dp), intent(in) :: x(:)
      integer, intent(in) :: b
      at = 0.0_dp
      if (b > 0) at = x(3*b)
    end function at
  end function angle_row

  ! ------------------------------------------------------------ the constraint set

  !> Phi, Phi_q, Phi_t and gamma = -rem at (q, qd, t); row_joint and
  !> row_scale filled on the way (rows in the order of n_rows).
  subroutine evaluate(self, q, qd, t, phi, jac, phit, gamma)
    class(general_kinematics_t), intent(inout) :: self
    real(dp), intent(in) :: q(:), qd(:), t
    real(dp), intent(out) :: phi(:), jac(:, :), phit(:), gamma(:)
    integer :: r, i, k, l, b, o
    type(scalar_t) :: s
    real(dp) :: psi, psid, psidd, cp, sp
    type(scalar_t) :: c1, c2
    type(kin_vec_t) :: pi_, pj, ui, fi, gi, hj
    r = 0
    jac = 0.0_dp
    do i = 1, self%mech%n_joints
      associate (jt => self%mech%joints(i))
        if (jt%kind == gjoint_free) cycle
        do k = 2, size(jt%member)
          pi_ = body_vec(self, q, qd, jt%member(1), jt%point(:, 1), .true.)
          pj = body_vec(self, q, qd, jt%member(k), jt%point(:, k), .true.)
          if (.not. self%mech%spatial) then
            select case (jt%kind)
            case (gjoint_revolute)
              call put(diff_row(pi_, pj, 1), i)
              call put(diff_row(pi_, pj, 2), i)
            case (gjoint_weld)
              call put(diff_row(pi_, pj, 1), i)
              call put(diff_row(pi_, pj, 2), i)
              call put(angle_row(q, qd, jt%member(1), jt%member(k)), i)
            case (gjoint_prismatic, gjoint_slider)
              ui = body_vec(self, q, qd, jt%member(1), [-jt%axis(2), jt%axis(1), 0.0_dp], .false.)
              call put(gap_row(ui, pi_, pj), i)
              if (jt%kind == gjoint_prismatic) call put(angle_row(q, qd, jt%member(1), jt%member(k)), i)
            end select
          else
            fi = body_vec(self, q, qd, jt%member(1), jt%f, .false.)
            gi = body_vec(self, q, qd, jt%member(1), jt%g, .false.)
            hj = body_vec(self, q, qd, jt%member(k), jt%axis, .false.)
            select case (jt%kind)
            case (gjoint_spherical, gjoint_universal, gjoint_revolute, gjoint_weld)
              call put(diff_row(pi_, pj, 1), i)
              call put(diff_row(pi_, pj, 2), i)
              call put(diff_row(pi_, pj, 3), i)
              if (jt%kind == gjoint_universal) then
                ui = body_vec(self, q, qd, jt%member(1), jt%axis, .false.)
                call put(dot_row(ui, body_vec(self, q, qd, jt%member(k), jt%axis2, .false.)), i)
              else if (jt%kind /= gjoint_spherical) then
                call put(dot_row(fi, hj), i)
                call put(dot_row(gi, hj), i)
                if (jt%kind == gjoint_weld) &
                  call put(dot_row(fi, body_vec(self, q, qd, jt%member(k), jt%g, .false.)), i)
              end if
            case (gjoint_prismatic, gjoint_slider)
              if (jt%kind == gjoint_prismatic) then
                call put(dot_row(fi, hj), i)
                call put(dot_row(gi, hj), i)
                call put(dot_row(fi, body_vec(self, q, qd, jt%member(k), jt%g, .false.)), i)
              end if
              call put(gap_row(fi, pi_, pj), i)
              call put(gap_row(gi, pi_, pj), i)
            end select
          end if
        end do
      end associate
    end do
    ! the idle spin of a link between two joints that leave its rotation free
    do l = 1, self%mech%n_links
      if (.not. self%idle(l)) cycle
      associate (lk => self%mech%links(l))
        ui = body_vec(self, q, qd, l, idle_normal(lk%end2), .false.)
        call put(dot_row(ui, body_vec(self, q, qd, 0, [0.0_dp, 0.0_dp, 1.0_dp], .false.)), 0)
      end associate
    end do
    ! drivers
    do k = 1, self%mech%n_drivers
      associate (jt => self%mech%joints(self%mech%drivers(k)%joint))
        call motion_value(self%mech%drivers(k)%motion, t, psi, psid, psidd)
        pi_ = body_vec(self, q, qd, jt%member(1), jt%point(:, 1), .true.)
        pj = body_vec(self, q, qd, jt%member(2), jt%point(:, 2), .true.)
        if (jt%kind /= gjoint_revolute) then
          if (self%mech%spatial) then
            s = gap_row(body_vec(self, q, qd, jt%member(1), jt%axis, .false.), pi_, pj)
          else
            s = gap_row(body_vec(self, q, qd, jt%member(1), [jt%axis(1), jt%axis(2), 0.0_dp], .false.), pi_, pj)
          end if
          s%val = s%val - psi
          s%phit = -psid
          s%rem = s%rem - psidd
        else if (.not. self%mech%spatial) then
          s = angle_row(q, qd, jt%member(1), jt%member(2))
          s%val = s%val - psi
          s%phit = -psid
          s%rem = -psidd
        else
          call rotation_scalars(self, q, qd, jt, c1, c2)
          cp = cos(psi)
          sp = sin(psi)
          s = c1
          s%val = cp*c1%val - sp*c2%val
          s%jac = cp*c1%jac - sp*c2%jac
          s%phit = -psid*(sp*c1%val + cp*c2%val)
          s%rem = cp*c1%rem - sp*c2%rem - 2.0_dp*psid*(sp*c1%rate + cp*c2%rate) &
                  - psidd*(sp*c1%val + cp*c2%val) - psid*psid*(cp*c1%val - sp*c2%val)
        end if
        call put(s, -k)
      end associate
    end do
    ! Euler parameters
    if (self%mech%spatial) then
      do b = 1, self%mech%n_links
        o = 7*(b - 1)
        s = scalar_t()
        s%body = [0, b]
        s%val = dot_product(q(o + 4:o + 7), q(o + 4:o + 7)) - 1.0_dp
        s%jac(4:7, 2) = 2.0_dp*q(o + 4:o + 7)
        s%rem = 2.0_dp*dot_product(qd(o + 4:o + 7), qd(o + 4:o + 7))
        call put(s, 0)
      end do
    end if
  contains
    subroutine put(sc, owner)
      type(scalar_t), intent(in) :: sc
      integer, intent(in) :: owner
      integer :: c
      r = r + 1
      self%row_joint(r) = owner
      self%row_scale(r) = merge(1.0_dp/self%mech%length_scale, 1.0_dp, sc%length)
      phi(r) = sc%val
      phit(r) = sc%phit
      gamma(r) = -sc%rem
      do c = 1, 2
        if (sc%body(c) > 0) then
          jac(r, (sc%body(c) - 1)*self%nqb + 1:sc%body(c)*self%nqb) = &
            jac(r, (sc%body(c) - 1)*self%nqb + 1:sc%body(c)*self%nqb) + sc%jac(1:self%nqb, c)
        end if
      end do
    end subroutine put
  end subroutine evaluate

  !> cos and sin of a spatial revolute joint's rotation, as scalars:
  !> c1 = g_i . f_j (sin), c2 = f_i . f_j (cos).
  subroutine rotation_scalars(self, q, qd, jt, c1, c2)
    class(general_kinematics_t), intent(in) :: self
    real(dp), intent(in) :: q(:), qd(:)
    type(gjoint_t), intent(in) :: jt
    type(scalar_t), intent(out) :: c1, c2
    type(kin_vec_t) :: fj
    fj = body_vec(self, q, qd, jt%member(2), jt%f, .false.)
    c1 = dot_row(body_vec(self, q, qd, jt%member(1), jt%g, .false.), fj)
    c2 = dot_row(body_vec(self, q, qd, jt%member(1), jt%f, .false.), fj)
  end subroutine rotation_scalars

  !> The drawn normal of an idly spinning link: line x Z (line x Y when the
  !> link runs along Z).
  pure function idle_normal(line) result(b)
    real(dp), intent(in) :: line(3)
    real(dp) :: b(3)
    b = unit_or_zero(cross(line, [0.0_dp, 0.0_dp, 1.0_dp]))
    if (norm2(cross(unit_or_zero(line), [0.0_dp, 0.0_dp, 1.0_dp])) < 0.1_dp) &
      b = unit_or_zero(cross(line, [0.0_dp, 1.0_dp, 0.0_dp]))
  end function idle_normal

  ! ------------------------------------------------------------ set-up and mobility

  !> Coordinates in the drawing, rows counted, mobility checked against the
  !> drivers.  Errors are input errors (code 2) naming the joint, link or
  !> driver; `blame` and `blame_value`: the deck variable to change and its value.
  subroutine gk_init(self, mech, err, blame, blame_value)
    class(general_kinematics_t), intent(inout) :: self
    type(general_mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    character(len=:), allocatable, intent(out), optional :: blame, blame_value
    integer :: l, b, nb, dof, first_bad, rank_joints, free_col
    integer, allocatable :: perm(:)
    real(dp), allocatable :: phi(:), jac(:, :), phit(:), gam(:), zero(:)
    self%mech = mech
    nb = mech%n_links
    self%nqb = merge(7, 3, mech%spatial)
    dof = merge(6, 3, mech%spatial)
    self%n = nb*self%nqb
    allocate(self%q(self%n), self%qd(self%n), self%qdd(self%n), self%col_scale(self%n), self%idle(nb))
    self%q = 0.0_dp
    self%qd = 0.0_dp
    self%qdd = 0.0_dp
    self%col_scale = 1.0_dp
    do b = 1, nb
      associate (o => (b - 1)*self%nqb)
        self%q(o + 1:o + merge(3, 2, mech%spatial)) = mech%links(b)%origin(1:merge(3, 2, mech%spatial))
        self%col_scale(o + 1:o + merge(3, 2, mech%spatial)) = mech%length_scale
        if (mech%spatial) self%q(o + 4) = 1.0_dp
      end associate
    end do
    self%q0 = self%q
    self%idle = .false.
    if (mech%spatial) then
      do l = 1, nb
        self%idle(l) = all(mech%joints(mech%links(l)%joint)%kind == gjoint_spherical .or. &
                           mech%joints(mech%links(l)%joint)%kind == gjoint_slider)
      end do
    end if
    self%n_idle = count(self%idle)
    self%m = n_rows(self)
    allocate(self%row_joint(self%m), self%row_scale(self%m), phi(self%m), phit(self%m), gam(self%m), &
             jac(self%m, self%n))
    zero = 0.0_dp*self%q
    call evaluate(self, self%q, zero, 0.0_dp, phi, jac, phit, gam)
    self%n_joint_rows = count(self%row_joint > 0)
    ! Kutzbach: freedoms of the free bodies less the joints' constraints and idle spins
    self%kutzbach = dof*nb - self%n_joint_rows - self%n_idle
    do l = 1, self%m
      jac(l, :) = jac(l, :)*self%row_scale(l)*self%col_scale
    end do
    ! rank of the joints' rows (idle spins and Euler normalization included)
    call first_dependent(jac(pack([(l, l = 1, self%m)], self%row_joint >= 0), :), first_bad, rank_joints, free_col)
    self%mobility = self%n - rank_joints
    if (first_bad > 0) then
      call blame_on('joint_kind', joint_index(first_bad, self%row_joint >= 0))
      call err%set('', 'joint '''//trim(joint_of(first_bad, self%row_joint >= 0))// &
        ''' repeats a constraint of the joints before it (redundant constraints: the Kutzbach count gives '// &
        str(self%kutzbach)//' freedoms, the constraint Jacobian in the drawing '//str(self%mobility)// &
        '); use a joint that removes fewer freedoms (e.g. spherical or universal for revolute in a closed loop), '// &
        'or draw the mechanism away from a dead centre', 2)
      return
    end if
    ! the drivers, one by one, after every other row
    perm = [pack([(l, l = 1, self%m)], self%row_joint >= 0), pack([(l, l = 1, self%m)], self%row_joint < 0)]
    call first_dependent(jac(perm, :), first_bad, rank_joints, free_col)
    if (first_bad > 0) then
      associate (k => -self%row_joint(perm(first_bad)))
        call blame_on('driver_joint', k)
        if (mech%n_drivers > self%mobility) then
          call err%set('', 'the mechanism is over-driven: it has '//str(self%mobility)// &
            ' freedoms and '//str(mech%n_drivers)//' drivers; driver '//str(k)//' (joint '''// &
            trim(mech%joints(mech%drivers(k)%joint)%name)//''') prescribes a motion that the joints and the '// &
            'drivers before it already fix', 2)
        else
          call err%set('', 'driver '//str(k)//' (joint '''// &
            trim(mech%joints(mech%drivers(k)%joint)%name)//''') cannot move the mechanism in the drawing: the '// &
            'joints and the drivers before it fix its motion there (a dead centre: draw the mechanism away from '// &
            'it; or two drivers prescribe the same freedom)', 2)
        end if
      end associate
      return
    end if
    if (mech%n_drivers < self%mobility) then
      call blame_on('n_drivers', 0)
      call err%set('', 'the mechanism is under-driven: it has '//str(self%mobility)// &
        ' freedoms and '//str(mech%n_drivers)//' drivers; link '''// &
        trim(mech%links((free_col - 1)/self%nqb + 1)%name)// &
        ''' can still move with every driver held (add a driver or a joint in its loop or chain)', 2)
      return
    end if
  contains
    subroutine blame_on(variable, i)
      character(len=*), intent(in) :: variable
      integer, intent(in) :: i
      if (.not. present(blame) .or. (variable == 'joint_kind' .and. i == 0)) return
      blame = variable
      select case (variable)
      case ('joint_kind')
        blame = variable//'('//str(i)//')'
        blame_value = "'"//trim(gjoint_names(mech%joints(i)%kind))//"'"
      case ('driver_joint')
        blame = variable//'('//str(i)//')'
        blame_value = str(mech%drivers(i)%joint)
      case default
        blame_value = str(mech%n_drivers)
      end select
    end subroutine blame_on
    !> The joint owning the k-th row among the rows selected by mask (0: none).
    integer function joint_index(k, mask)
      integer, intent(in) :: k
      logical, intent(in) :: mask(:)
      integer :: r, seen
      seen = 0
      joint_index = 0
      do r = 1, size(mask)
        if (mask(r)) seen = seen + 1
        if (seen == k) then
          joint_index = max(self%row_joint(r), 0)
          return
        end if
      end do
    end function joint_index
    !> The joint owning the k-th row among the rows selected by mask.
    function joint_of(k, mask) result(name)
      integer, intent(in) :: k
      logical, intent(in) :: mask(:)
      character(len=:), allocatable :: name
      integer :: r, seen
      seen = 0
      name = 'idle spin or Euler parameters'
      do r = 1, size(mask)
        if (mask(r)) seen = seen + 1
        if (seen == k) then
          if (self%row_joint(r) > 0) name = trim(mech%joints(self%row_joint(r))%name)
          return
        end if
      end do
    end function joint_of
  end subroutine gk_init

  !> The number of constraint rows evaluate writes.
  pure integer function n_rows(self)
    class(general_kinematics_t), intent(in) :: self
    integer :: i, pairs
    integer, parameter :: planar_rows(7) = [2, 2, 1, 0, 0, 3, 0], spatial_rows(7) = [5, 5, 2, 3, 4, 6, 0]
    n_rows = 0
    do i = 1, self%mech%n_joints
      pairs = size(self%mech%joints(i)%member) - 1
      if (self%mech%spatial) then
        n_rows = n_rows + pairs*spatial_rows(self%mech%joints(i)%kind)
      else
        n_rows = n_rows + pairs*planar_rows(self%mech%joints(i)%kind)
      end if
    end do
    n_rows = n_rows + self%n_idle + self%mech%n_drivers
    if (self%mech%spatial) n_rows = n_rows + self%mech%n_links
  end function n_rows

  !> Rows of a orthogonalised in turn (modified Gram-Schmidt, twice): the
  !> first row that lies in the span of the rows before it (0: none), the
  !> rank, and the coordinate least fixed by all rows (a free direction).
  pure subroutine first_dependent(a, first, rank, free_col)
    real(dp), intent(in) :: a(:, :)
    integer, intent(out) :: first, rank, free_col
    real(dp) :: basis(size(a, 2), size(a, 1)), v(size(a, 2)), e(size(a, 2)), worst, res
    integer :: r, k, pass, c
    first = 0
    rank = 0
    do r = 1, size(a, 1)
      v = a(r, :)
      if (.not. norm2(v) > 0.0_dp) then
        if (first == 0) first = r
        cycle
      end if
      do pass = 1, 2
        do k = 1, rank
          v = v - dot_product(basis(:, k), v)*basis(:, k)
        end do
      end do
      if (norm2(v) <= rank_tol*norm2(a(r, :))) then
        if (first == 0) first = r
      else
        rank = rank + 1
        basis(:, rank) = v/norm2(v)
      end if
    end do
    free_col = 0
    worst = 0.0_dp
    do c = 1, size(a, 2)
      e = 0.0_dp
      e(c) = 1.0_dp
      do k = 1, rank
        e = e - dot_product(basis(:, k), e)*basis(:, k)
      end do
      res = norm2(e)
      if (res > worst + rank_tol) then
        worst = res
        free_col = c
      end if
    end do
  end subroutine first_dependent

  ! ------------------------------------------------------------ solution

  !> Positions, velocities and accelerations at time t.  Errors (code 3):
  !> no assembly, a toggle at t, or a toggle passed since the last solution.
  subroutine gk_solve(self, t, err)
    class(general_kinematics_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t), intent(inout) :: err
    real(dp) :: phi(self%m), jac(self%m, self%n), phit(self%m), gam(self%m), dq(self%n), dt
    real(dp) :: q_start(self%n)
    integer :: ipiv(self%n), it, sgn
    logical :: converged
    type(error_t) :: e
    if (self%assembled) then
      dt = t - self%t
      q_start = self%q + dt*self%qd + 0.5_dp*dt*dt*self%qdd
    else
      q_start = self%q0
    end if
    self%q = q_start
    converged = .false.
    do it = 1, max_newton
      call evaluate(self, self%q, self%qd*0.0_dp, t, phi, jac, phit, gam)
      if (maxval(abs(phi*self%row_scale)) < residual_tol) then
        converged = .true.
        exit
      end if
      call factor(jac, ipiv, e)
      if (e%failed()) exit
      dq = -phi*self%row_scale
      call lu_solve(jac, ipiv, dq, e)
      if (e%failed()) exit
      dq = dq*self%col_scale
      self%q = self%q + dq
      if (maxval(abs(dq/self%col_scale)) < newton_tol) then
        converged = .true.
        exit
      end if
    end do
    self%iterations = it
    self%total_iterations = self%total_iterations + min(it, max_newton)
    if (.not. converged) then
      call evaluate(self, self%q, self%qd*0.0_dp, t, phi, jac, phit, gam)
      call factor(jac, ipiv, e, self%rcond, sgn)
      if (e%failed() .or. .not. self%rcond >= self%mech%toggle_rcond) then
        call err%set('kinematics', 'toggle (singular constraint Jacobian) at t = '//str(t, 8)//' s: Newton''s '// &
          'method stalls where the reciprocal condition is '//str(self%rcond, 3)//' < toggle_rcond = '// &
          str(self%mech%toggle_rcond, 3)//'; the loop through '//trim(toggle_joints())//' loses its assembly', 3)
        return
      end if
      call evaluate(self, self%q, self%qd*0.0_dp, t, phi, jac, phit, gam)
      call err%set('kinematics', 'the mechanism does not assemble at t = '//str(t, 8)//' s'// &
        trim(from_text())//': Newton''s method did not converge (the largest constraint violation is at '// &
        trim(owner_text(maxloc(abs(phi*self%row_scale), 1)))//')', 3)
      return
    end if
    call evaluate(self, self%q, self%qd*0.0_dp, t, phi, jac, phit, gam)
    call factor(jac, ipiv, e, self%rcond, sgn)
    if (e%failed() .or. .not. self%rcond >= self%mech%toggle_rcond) then
      call err%set('kinematics', 'toggle (singular constraint Jacobian) at t = '//str(t, 8)//' s: reciprocal '// &
        'condition '//str(self%rcond, 3)//' < toggle_rcond = '//str(self%mech%toggle_rcond, 3)// &
        '; the loop through '//trim(toggle_joints())//' loses its assembly', 3)
      return
    end if
    if (self%assembled .and. sgn /= self%det_sign) then
      call err%set('kinematics', 'the mechanism passed a toggle (the constraint Jacobian''s determinant changed '// &
        'sign) between t = '//str(self%t, 8)//' and '//str(t, 8)//' s, in the loop through '// &
        trim(toggle_joints())//'; try smaller steps, or the drivers move it through a dead centre', 3)
      return
    end if
    self%det_sign = sgn
    ! velocities: Phi_q q' = -Phi_t;  accelerations: Phi_q q'' = gamma(q, q')
    self%qd = -phit*self%row_scale
    call lu_solve(jac, ipiv, self%qd, e)
    self%qd = self%qd*self%col_scale
    call evaluate(self, self%q, self%qd, t, phi, jac, phit, gam)
    call factor(jac, ipiv, e)
    self%qdd = gam*self%row_scale
    call lu_solve(jac, ipiv, self%qdd, e)
    self%qdd = self%qdd*self%col_scale
    self%t = t
    self%assembled = .true.
    self%n_solutions = self%n_solutions + 1
  contains
    function from_text() result(s)
      character(len=:), allocatable :: s
      s = ''
      if (self%assembled) then
        s = ' (last assembled at t = '//str(self%t, 8)//' s)'
      else
        s = ' (from the drawing)'
      end if
    end function from_text
    !> The joints whose rows carry the left null vector of the Jacobian (the
    !> directions of the constraint forces that grow without bound).
    function toggle_joints() result(s)
      character(len=:), allocatable :: s
      real(dp) :: y(self%m), a(self%m, self%n)
      integer :: r, piv(self%n)
      type(error_t) :: e2
      a = transpose(jac)
      do r = 1, self%m
        a(:, r) = a(:, r)*self%row_scale(r)
        a(r, :) = a(r, :)*self%col_scale(r)
      end do
      s = ''
      call lu_factor(a, piv, e2)
      y = 1.0_dp + [(0.1_dp*r/self%m, r = 1, self%m)]
      if (.not. e2%failed()) call lu_solve(a, piv, y, e2)
      if (e2%failed()) y = abs(phi) + 1.0_dp
      do r = 1, self%m
        if (abs(y(r)) >= 0.1_dp*maxval(abs(y)) .and. self%row_joint(r) /= 0) then
          if (index(s, ''''//trim(owner_name(r))//'''') == 0) then
            if (len(s) > 0) s = s//', '
            s = s//''''//trim(owner_name(r))//''''
          end if
        end if
      end do
      if (len(s) == 0) s = 'the drivers'
      s = 'joints '//s
    end function toggle_joints
    function owner_name(r) result(s)
      integer, intent(in) :: r
      character(len=:), allocatable :: s
      if (self%row_joint(r) > 0) then
        s = trim(self%mech%joints(self%row_joint(r))%name)
      else
        s = trim(self%mech%joints(self%mech%drivers(-self%row_joint(r))%joint)%name)
      end if
    end function owner_name
    function owner_text(r) result(s)
      integer, intent(in) :: r
      character(len=:), allocatable :: s
      if (self%row_joint(r) > 0) then
        s = 'joint '''//trim(self%mech%joints(self%row_joint(r))%name)//''''
      else if (self%row_joint(r) < 0) then
        s = 'the driver of joint '''//trim(owner_name(r))//''''
      else
        s = 'an Euler parameter normalization or idle spin'
      end if
    end function owner_text
    !> LU of the scaled Jacobian; with rc and sign, its reciprocal
    !> condition and the sign of its determinant.
    subroutine factor(a, piv, fe, rc, sign_det)
      real(dp), intent(inout) :: a(:, :)
      integer, intent(out) :: piv(:)
      type(error_t), intent(inout) :: fe
      real(dp), intent(out), optional :: rc
      integer, intent(out), optional :: sign_det
      integer :: r
      if (present(sign_det)) sign_det = 0
      do r = 1, self%m
        a(r, :) = a(r, :)*self%row_scale(r)*self%col_scale
      end do
      if (present(rc)) then
        call lu_factor(a, piv, fe, rc)
      else
        call lu_factor(a, piv, fe)
      end if
      if (present(sign_det) .and. .not. fe%failed()) then
        sign_det = 1
        do r = 1, self%n
          if (piv(r) /= r) sign_det = -sign_det
          if (a(r, r) < 0.0_dp) sign_det = -sign_det
        end do
      end if
    end subroutine factor
  end subroutine gk_solve

  ! ------------------------------------------------------------ results

  !> The position, velocity and acceleration of the point s of link b (0: ground).
  subroutine gk_point(self, b, s, x, v, a)
    class(general_kinematics_t), intent(in) :: self
    integer, intent(in) :: b
    real(dp), intent(in) :: s(3)
    real(dp), intent(out) :: x(3), v(3), a(3)
    type(kin_vec_t) :: p
    p = body_vec(self, self%q, self%qd, b, s, .true.)
    x = p%val
    v = p%vel
    a = p%quad
    if (b > 0) a = a + matmul(p%jac(:, 1:self%nqb), self%qdd((b - 1)*self%nqb + 1:b*self%nqb))
  end subroutine gk_point

  !> A joint's relative coordinate (joint_has_value): rotation (rad) or
  !> slide, and its first two time derivatives.  `previous`: the last value,
  !> to follow a spatial rotation past +-pi.
  subroutine joint_value(self, i, previous, v, vd, vdd)
    class(general_kinematics_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: previous
    real(dp), intent(out) :: v, vd, vdd
    type(scalar_t) :: s, c1, c2
    type(kin_vec_t) :: pi_, pj
    real(dp) :: sa, ca, sd, cd, sdd, cdd, r2
    associate (jt => self%mech%joints(i))
      if (jt%kind == gjoint_revolute .and. self%mech%spatial) then
        call rotation_scalars(self, self%q, self%qd, jt, c1, c2)
        sa = c1%val
        ca = c2%val
        sd = c1%rate
        cd = c2%rate
        sdd = acc(c1)
        cdd = acc(c2)
        r2 = sa*sa + ca*ca
        v = atan2(sa, ca)
        v = v + 2.0_dp*pi*nint((previous - v)/(2.0_dp*pi))
        vd = (ca*sd - sa*cd)/r2
        vdd = (ca*sdd - sa*cdd)/r2 - 2.0_dp*(ca*sd - sa*cd)*(ca*cd + sa*sd)/r2**2
        return
      end if
      if (jt%kind == gjoint_revolute) then
        s = angle_row(self%q, self%qd, jt%member(1), jt%member(2))
      else
        pi_ = body_vec(self, self%q, self%qd, jt%member(1), jt%point(:, 1), .true.)
        pj = body_vec(self, self%q, self%qd, jt%member(2), jt%point(:, 2), .true.)
        s = gap_row(body_vec(self, self%q, self%qd, jt%member(1), jt%axis, .false.), pi_, pj)
      end if
      v = s%val
      vd = s%rate
      vdd = acc(s)
    end associate
  contains
    real(dp) function acc(sc)
      type(scalar_t), intent(in) :: sc
      integer :: c
      acc = sc%rem
      do c = 1, 2
        if (sc%body(c) > 0) acc = acc + dot_product(sc%jac(1:self%nqb, c), &
          self%qdd((sc%body(c) - 1)*self%nqb + 1:sc%body(c)*self%nqb))
      end do
    end function acc
  end subroutine joint_value

  !> Link b's angular velocity and acceleration (global; the plane: about Z).
  !> Space: omega = 2 G p', alpha = 2 G p'' with G = [-e, e0 I + e~]
  !> (Nikravesh 1988).
  subroutine body_motion(self, b, omega, alpha)
    class(general_kinematics_t), intent(in) :: self
    integer, intent(in) :: b
    real(dp), intent(out) :: omega(3), alpha(3)
    real(dp) :: gm(3, 4), e0, e(3)
    integer :: o
    o = (b - 1)*self%nqb
    if (.not. self%mech%spatial) then
      omega = [0.0_dp, 0.0_dp, self%qd(o + 3)]
      alpha = [0.0_dp, 0.0_dp, self%qdd(o + 3)]
      return
    end if
    e0 = self%q(o + 4)
    e = self%q(o + 5:o + 7)
    gm(:, 1) = -e
    gm(:, 2:4) = e0*identity(3) + skew(e)
    omega = 2.0_dp*matmul(gm, self%qd(o + 4:o + 7))
    alpha = 2.0_dp*matmul(gm, self%qdd(o + 4:o + 7))
  end subroutine body_motion

  !> Link b's rotation matrix A (global components of its frame's axes as
  !> columns; the identity in the drawing).  Space: A = (2 e0^2 - 1) I +
  !> 2 (e e^T + e0 e~) (Nikravesh 1988).
  pure function body_rotation(self, b) result(a)
    class(general_kinematics_t), intent(in) :: self
    integer, intent(in) :: b
    real(dp) :: a(3, 3)
    real(dp) :: c, s, e0, e(3)
    integer :: o
    o = (b - 1)*self%nqb
    if (.not. self%mech%spatial) then
      c = cos(self%q(o + 3))
      s = sin(self%q(o + 3))
      a = reshape([c, s, 0.0_dp, -s, c, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
      return
    end if
    e0 = self%q(o + 4)
    e = self%q(o + 5:o + 7)
    a = (2.0_dp*e0*e0 - 1.0_dp)*identity(3) + 2.0_dp*(outer(e, e) + e0*skew(e))
  end function body_rotation

  ! ------------------------------------------------------------ small 3-vector algebra

  !> skew(a) b = a x b.
  pure function skew(a) result(s)
    real(dp), intent(in) :: a(3)
    real(dp) :: s(3, 3)
    s = reshape([0.0_dp, a(3), -a(2), -a(3), 0.0_dp, a(1), a(2), -a(1), 0.0_dp], [3, 3])
  end function skew

end module general_kinematics
