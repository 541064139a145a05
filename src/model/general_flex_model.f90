!> The flexible general mechanism (doc/general_mechanism.md, "Flexible
!> analysis"): every link of a &general_mechanism a chain of spatial beam
!> elements (module spatial_beam) vibrating about the rigid-body motion of
!> general_kinematics, M(q, t) q'' = F(q, q', t).  The model is the spatial
!> four-bar's (module spatial_model: its element loop, banded mass, Newton
!> matrix, energies, static state and stresses work on any element list and
!> correlation table) with the four-bar's rigid motion and joint rules
!> replaced by the general ones.
!>
!> Element axes: x along the link from its first joint to its second; z the
!> axis of a revolute joint at one of its ends (normal to x), else the
!> global Z (Y when the link is along Z) made normal to x, which is the
!> plane of the idle-spin rule of the kinematics; y = z x x.  They turn with
!> the link's frame.
!>
!> Joint rules at a link end, generalising spatial_model's (doc/spatial.md,
!> "Joints"); a member on the ground holds what it shares at zero:
!>  weld, and a driven revolute: translations and the three rotations
!>      (global components) shared, curvatures free (the moment passes);
!>      with the ground this is a clamp, the driven joint's elastic rotation
!>      about its axis held;
!>  revolute with the ground: translations zero, rotation = s a (one unknown
!>      per link), no moment about a: curvature about a (v_xx, z = a) zero;
!>  revolute between links (plane, a = Z): translations and the rotations
!>      about X and Y shared, the rotation about Z and w_xx per link, v_xx
!>      zero;
!>  spherical: translations shared, each end's own rotation triple in its
!>      element axes (local), no moment (both curvatures zero); a link
!>      spinning idly between two spherical joints has its twist held at its
!>      first end;
!>  free end: every node DOF its own.
!> A ground joint on a lumped mount (module support_mounts) keeps its
!> rotation rule but its translations are the mount's displacement, shared
!> by the link ends there, as at a joint between links.
!> The axial slope and curvature of the consistent element (u_x, u_xx) are
!> each node's own.  Prismatic, slider and universal joints and a passive
!> revolute between two links in space are refused (code 2).
module general_flex_model
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use element_effects, only: element_effects_t
  use spatial_beam, only: spatial_beam_init, spatial_formulation_consistent
  use spatial_model, only: spatial_model_t, spatial_link_t
  use spatial_correlation, only: spatial_table_t
  use motion_profile, only: motion_value
  use general_mechanism, only: gjoint_revolute, gjoint_spherical, gjoint_weld, gjoint_free, gjoint_names, &
    unit_or_zero
  use general_kinematics, only: general_kinematics_t
  use linalg, only: solve_linear
  use support_mounts, only: support_mounts_t, support_mount_t
  implicit none
  private
  public :: general_flex_model_t, unsupported_joint

  character(len=4), parameter :: slot_names(10) = ['UX  ', 'UY  ', 'UZ  ', 'RX  ', 'RY  ', 'RZ  ', 'vxx ', 'wxx ', &
                                                   'ux  ', 'uxx ']

  type, extends(spatial_model_t) :: general_flex_model_t
    type(general_kinematics_t) :: gk
    type(spatial_link_t), allocatable :: glinks(:)   !< section, material, elements and length of every link
    real(dp), allocatable :: frame0(:, :, :)        !< (3, 3, link): element axes in the link frame (columns x, y, z)
    integer, allocatable :: joint_dofs(:, :)        !< (3, joint): global unknowns of its elastic translation (0: zero)
    type(support_mounts_t) :: support                !< lumped mounts under ground joints (none: the rigid ground)
    real(dp) :: t_support = -huge(1.0_dp)            !< time of the mass factor the mounts' update was made for
  contains
    procedure :: init_general
    procedure :: set_time => general_set_time
    procedure :: crank_angle => driver_angle
    procedure :: accelerations => mounted_accelerations
    procedure :: assemble_band => mounted_band
    procedure :: assemble_dense => mounted_dense
    procedure :: energies => mounted_energies
    procedure :: static_state => mounted_static_state
  end type general_flex_model_t

  !> The node table while it is numbered (slots UX UY UZ RX RY RZ vxx wxx ux uxx).
  type :: gnodes_t
    integer, allocatable :: map(:, :, :)       !< (10, 0:max elements, link) global unknown, 0 = held at zero
    real(dp), allocatable :: coef(:, :, :)
    integer, allocatable :: trans(:, :), rot(:, :)   !< (3, joint) shared translations and rotations
    logical :: axial_slopes = .false.
  end type gnodes_t

contains

  !> Elements, joint rules and the correlation table of the mechanism of gk
  !> (initialised: its mobility checked) with links(:) (section, material,
  !> elements) for every link, and mounts under ground joints if given.
  !> Unsupported joints, a mount on a joint not on the ground: err%code = 2.
  subroutine init_general(self, gk, links, effects, beta, err, formulation, mounts)
    class(general_flex_model_t), intent(inout) :: self
    type(general_kinematics_t), intent(in) :: gk
    type(spatial_link_t), intent(in) :: links(:)
    type(element_effects_t), intent(in) :: effects
    real(dp), intent(in) :: beta
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: formulation
    type(support_mount_t), intent(in), optional :: mounts(:)
    integer :: l, i, e, ne
    logical :: loc(2)
    self%formulation = spatial_formulation_consistent
    if (present(formulation)) self%formulation = formulation
    self%gk = gk
    self%glinks = links
    if (allocated(self%support%mounts)) deallocate(self%support%mounts)
    if (present(mounts)) self%support%mounts = mounts
    self%t_support = -huge(1.0_dp)
    associate (m => self%gk%mech)
      call check_joints(self, err)
      if (err%failed()) return
      do i = 1, self%support%count()
        if (m%joints(self%support%mounts(i)%joint)%member(1) /= 0) then
          call err%set('general flexible model', 'joint '''//trim(m%joints(self%support%mounts(i)%joint)%name)// &
                       ''' is not on the ground: only a ground joint sits on a mount')
          err%code = 2
          return
        end if
      end do
      if (allocated(self%frame0)) deallocate(self%frame0)
      allocate(self%frame0(3, 3, m%n_links))
      do l = 1, m%n_links
        self%glinks(l)%length = norm2(m%links(l)%end2)
        self%frame0(:, :, l) = element_axes(self, l)
      end do
      call check_revolute_axes(self, err)
      if (err%failed()) return
      ne = sum(self%glinks%n_elements)
      if (allocated(self%el)) deallocate(self%el, self%rb, self%link_of, self%index_in_link, self%mass_as_previous, &
                                         self%matrices_as_previous)
      allocate(self%el(ne), self%rb(ne), self%link_of(ne), self%index_in_link(ne), self%mass_as_previous(ne), &
               self%matrices_as_previous(ne))
      ! (every element assembles its own matrices: no sharing between neighbours)
      self%mass_as_previous = .false.
      self%matrices_as_previous = .false.
      call self%err%clear()
      e = 0
      do l = 1, m%n_links
        self%glinks(l)%first_element = e + 1
        do i = 1, self%glinks(l)%n_elements
          e = e + 1
          self%link_of(e) = l
          self%index_in_link(e) = i
          ! rotations at a spherical end are the element's own, in its axes
          loc(1) = i == 1 .and. m%joints(m%links(l)%joint(1))%kind == gjoint_spherical
          loc(2) = i == self%glinks(l)%n_elements .and. m%joints(m%links(l)%joint(2))%kind == gjoint_spherical
          associate (lk => self%glinks(l))
            call spatial_beam_init(self%el(e), lk%length/lk%n_elements, lk%sec, lk%material, lk%shear_modulus, &
                                   effects, err, damping_beta=beta, local_rotation=loc, formulation=self%formulation)
          end associate
          if (err%failed()) then
            call err%add_context('link '''//trim(m%links(l)%name)//''' element '//str(i))
            return
          end if
        end do
      end do
    end associate
    self%omega = 0.0_dp       ! the first driver's rate: the static start's step (spatial_run_steps)
    if (self%gk%mech%n_drivers > 0) self%omega = abs(self%gk%mech%drivers(1)%motion%rate)
    self%t_states = -huge(1.0_dp)
    self%t_mass = -huge(1.0_dp)
    call self%set_time(0.0_dp)
    if (self%err%failed()) then
      call err%set('general flexible model', self%err%text())
      return
    end if
    call build_table(self)
    call self%size_state(self%table%n_unknowns(), self%table%band())
    do i = 1, self%support%count()
      self%support%mounts(i)%dofs = self%joint_dofs(:, self%support%mounts(i)%joint)
    end do
    call self%support%newton_dampers(beta, self%newton%damper, self%newton%damper_dofs)
  end subroutine init_general

  !> Joint i sits on a mount.
  logical function mounted(self, i)
    type(general_flex_model_t), intent(in) :: self
    integer, intent(in) :: i
    integer :: k
    mounted = .false.
    do k = 1, self%support%count()
      if (self%support%mounts(k)%joint == i) mounted = .true.
    end do
  end function mounted

  !> The rigid states at t from the general kinematics (.false.: they
  !> failed).  The parent's procedures called on the parent component
  !> (self%spatial_model_t%...) would set them by the four-bar's set_time:
  !> set here first, they find them current.
  logical function rigid_motion_at(self, t) result(ok)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    call self%set_time(t)
    ok = .not. self%err%failed()
  end function rigid_motion_at

  !> q'' of the links and the mounts: the links' (spatial_model), then the
  !> mounts' forces and masses (module support_mounts: its Woodbury update of
  !> the links' factored mass matrix, renewed when that is).
  subroutine mounted_accelerations(self, t, q, qd, qdd)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out), contiguous :: qdd(:)
    type(error_t) :: err
    qdd = 0.0_dp
    if (.not. rigid_motion_at(self, t)) return
    call self%spatial_model_t%accelerations(t, q, qd, qdd)
    if (self%support%count() == 0 .or. self%err%failed()) return
    if (self%t_support < self%t_mass .or. self%t_support > self%t_mass) then
      call self%support%factor_update(self%mass_band, self%kd, err)
      self%t_support = self%t_mass
    end if
    call self%support%solve_update(qdd, err, self%support%forces(q, qd, self%gravity))
    if (err%failed()) call self%fail(t, 'the mounts'' mass update: '//err%text())
  end subroutine mounted_accelerations

  !> The joints the flexible analysis models (the rules above); code 2 otherwise.
  subroutine check_joints(self, err)
    type(general_flex_model_t), intent(in) :: self
    type(error_t), intent(inout) :: err
    integer :: i
    character(len=:), allocatable :: why
    call unsupported_joint(self%gk, i, why)
    if (i > 0) then
      call err%set('general flexible model', why)
      err%code = 2
    end if
  end subroutine check_joints

  !> The first joint of the mechanism the flexible analysis does not model
  !> (0: none) and why.
  subroutine unsupported_joint(gk, i, why)
    type(general_kinematics_t), intent(in) :: gk
    integer, intent(out) :: i
    character(len=:), allocatable, intent(out) :: why
    integer :: k
    logical :: driven_k
    i = 0
    why = ''
    associate (m => gk%mech)
      do k = 1, m%n_joints
        driven_k = .false.
        if (m%n_drivers > 0) driven_k = any(m%drivers%joint == k)
        associate (jt => m%joints(k))
          if (all(jt%kind /= [gjoint_revolute, gjoint_spherical, gjoint_weld, gjoint_free])) then
            why = 'joint '''//trim(jt%name)//''' is '//trim(gjoint_names(jt%kind))// &
              ': the flexible analysis models revolute, spherical, weld and free joints'
          else if (jt%kind == gjoint_revolute .and. m%spatial .and. jt%member(1) /= 0 .and. .not. driven_k) then
            why = 'joint '''//trim(jt%name)//''' is a passive revolute joint between two moving links in '// &
              'space, whose axis turns: the flexible analysis takes it in the plane, on the ground or driven '// &
              '(a spherical joint otherwise)'
          end if
        end associate
        if (len(why) > 0) then
          i = k
          return
        end if
      end do
    end associate
  end subroutine unsupported_joint

  !> A passive revolute joint with the ground holds the moment about its
  !> axis through v_xx: the axis must be the element's z there.
  subroutine check_revolute_axes(self, err)
    type(general_flex_model_t), intent(in) :: self
    type(error_t), intent(inout) :: err
    integer :: l, k, i
    associate (m => self%gk%mech)
      do l = 1, m%n_links
        do k = 1, 2
          i = m%links(l)%joint(k)
          associate (jt => m%joints(i))
            if (jt%kind /= gjoint_revolute .or. jt%member(1) /= 0 .or. driven(self, i)) cycle
            if (abs(dot_product(jt%axis, self%frame0(:, 3, l))) < 1.0_dp - 1.0e-9_dp) then
              call err%set('general flexible model', 'link '''//trim(m%links(l)%name)//''' is not normal to the '// &
                'axis of its ground revolute joint '''//trim(jt%name)//''' (or its two revolute joints'' axes '// &
                'differ): the flexible analysis needs the joint axis normal to the link')
              err%code = 2
              return
            end if
          end associate
        end do
      end do
    end associate
  end subroutine check_revolute_axes

  logical function driven(self, i)
    type(general_flex_model_t), intent(in) :: self
    integer, intent(in) :: i
    driven = .false.
    if (self%gk%mech%n_drivers > 0) driven = any(self%gk%mech%drivers%joint == i)
  end function driven

  !> The element axes of link l in its frame (the drawing), as columns x, y, z.
  function element_axes(self, l) result(r)
    type(general_flex_model_t), intent(in) :: self
    integer, intent(in) :: l
    real(dp) :: r(3, 3)
    real(dp) :: x(3), z(3)
    integer :: k
    associate (m => self%gk%mech)
      x = unit_or_zero(m%links(l)%end2)
      z = 0.0_dp
      if (.not. m%spatial) then
        z = [0.0_dp, 0.0_dp, 1.0_dp]
      else
        do k = 1, 2
          associate (jt => m%joints(m%links(l)%joint(k)))
            if (jt%kind == gjoint_revolute .and. .not. norm2(z) > 0.0_dp) &
              z = unit_or_zero(jt%axis - dot_product(jt%axis, x)*x)
          end associate
        end do
        if (.not. norm2(z) > 0.0_dp) z = unit_or_zero([0.0_dp, 0.0_dp, 1.0_dp] - x(3)*x)
        if (norm2(z) < 1.0e-6_dp) z = unit_or_zero([0.0_dp, 1.0_dp, 0.0_dp] - x(2)*x)
      end if
      r(:, 1) = x
      r(:, 2) = [z(2)*x(3) - z(3)*x(2), z(3)*x(1) - z(1)*x(3), z(1)*x(2) - z(2)*x(1)]
      r(:, 3) = z
    end associate
  end function element_axes

  !> Rigid states of every element at time t from the general kinematics.
  subroutine general_set_time(self, t)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t) :: err
    integer :: e, l
    real(dp) :: a(3, 3), s(3), x(3), v(3), acc(3)
    if (.not. (t < self%t_states .or. t > self%t_states)) return
    call follow_motion(self, t, err)
    if (err%failed()) then
      call self%fail(t, err%text())
      return
    end if
    do e = 1, size(self%el)
      l = self%link_of(e)
      a = self%gk%body_rotation(l)
      associate (rb => self%rb(e))
        rb%rot = matmul(a, self%frame0(:, :, l))
        s = real(self%index_in_link(e) - 1, dp)*self%el(e)%length*self%frame0(:, 1, l)
        call self%gk%point(l, s, x, v, acc)
        rb%x1 = x
        rb%x1_d = v
        ! gravity: the body force -rho A (a - g), as an acceleration -g of the frame
        rb%x1_dd = acc - self%gravity
        call self%gk%body_motion(l, rb%omega, rb%alpha)
      end associate
    end do
    self%t_states = t
  end subroutine general_set_time

  !> The kinematics solved at t, marching from the last solution in steps
  !> that turn no link and move no driven joint by more than about 2 degrees (Newton's start is
  !> extrapolated from the last solution: a far jump, such as the return to
  !> the start after the solver's settings looked at the whole run, could
  !> land on the other assembly branch).
  subroutine follow_motion(self, t, err)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t), intent(inout) :: err
    real(dp), parameter :: max_turn = 0.035_dp
    real(dp) :: w(3), al(3), rate, t_from, v0, v1, vd, vdd
    integer :: l, k, n
    n = 1
    if (self%gk%assembled) then
      rate = 0.0_dp
      do l = 1, self%gk%mech%n_links
        call self%gk%body_motion(l, w, al)
        rate = max(rate, norm2(w) + sqrt(norm2(al)))
      end do
      n = max(1, min(100000, ceiling(abs(t - self%gk%t)*rate/max_turn)))
      ! and no driver moving by more than that (from rest, the rates above are zero)
      do k = 1, self%gk%mech%n_drivers
        call motion_value(self%gk%mech%drivers(k)%motion, t, v1, vd, vdd)
        call motion_value(self%gk%mech%drivers(k)%motion, self%gk%t, v0, vd, vdd)
        n = max(n, min(100000, ceiling(abs(v1 - v0)/max_turn)))
      end do
    end if
    t_from = self%gk%t
    do k = 1, n
      if (k < n) then
        call self%gk%solve(t_from + (t - t_from)*real(k, dp)/real(n, dp), err)
      else
        call self%gk%solve(t, err)
      end if
      self%n_kinematics = self%n_kinematics + 1
      if (err%failed()) return
    end do
  end subroutine follow_motion

  !> The first driver's joint coordinate (rad, or a slide) at time t.
  real(dp) function driver_angle(self, t) result(theta)
    class(general_flex_model_t), intent(in) :: self
    real(dp), intent(in) :: t
    real(dp) :: vd, vdd
    theta = 0.0_dp
    if (self%gk%mech%n_drivers > 0) call motion_value(self%gk%mech%drivers(1)%motion, t, theta, vd, vdd)
  end function driver_angle

  !> Node rules link by link; a link whose second joint is numbered already
  !> and first is not is walked from its second end (a narrow band along a loop).
  subroutine build_table(self)
    type(general_flex_model_t), intent(inout) :: self
    type(gnodes_t) :: nodes
    logical :: seen(self%gk%mech%n_joints)
    integer :: l, jj, j, n, nmax, nl, i
    nl = self%gk%mech%n_links
    nmax = maxval(self%glinks%n_elements)
    allocate(nodes%map(10, 0:nmax, nl), nodes%coef(10, 0:nmax, nl))
    allocate(nodes%trans(3, self%gk%mech%n_joints), nodes%rot(3, self%gk%mech%n_joints))
    nodes%map = 0
    nodes%coef = 0.0_dp
    nodes%trans = 0
    nodes%rot = 0
    nodes%axial_slopes = self%formulation == spatial_formulation_consistent
    call self%table%init(size(self%el))
    if (allocated(self%joint_dofs)) deallocate(self%joint_dofs)
    allocate(self%joint_dofs(3, self%gk%mech%n_joints))
    self%joint_dofs = 0
    seen = .false.
    do l = 1, nl
      n = self%glinks(l)%n_elements
      associate (jl => self%gk%mech%links(l)%joint)
        do jj = 0, n
          j = merge(n - jj, jj, seen(jl(2)) .and. .not. seen(jl(1)))
          if (j == 0 .or. j == n) then
            i = jl(merge(1, 2, j == 0))
            call joint_end(self, nodes, l, j, i)
            if (self%joint_dofs(1, i) == 0) self%joint_dofs(:, i) = nodes%map(1:3, j, l)
          else
            call interior(self%table, nodes, self%gk%mech%links(l)%name, l, j)
          end if
        end do
        seen(jl) = .true.
      end associate
    end do
    do l = 1, nl
      associate (n_l => self%glinks(l)%n_elements)
        call self%table%join_nodes(self%glinks(l)%first_element, nodes%map(:, 0:n_l, l), nodes%coef(:, 0:n_l, l))
      end associate
    end do
    call self%table%finish_band()
  end subroutine build_table

  subroutine own_dof(table, nodes, name, link, node, slot)
    type(spatial_table_t), intent(inout) :: table
    type(gnodes_t), intent(inout) :: nodes
    character(len=*), intent(in) :: name
    integer, intent(in) :: link, node, slot
    nodes%map(slot, node, link) = table%new_unknown(trim(name)//' N'//str(node)//' '//trim(slot_names(slot)))
    nodes%coef(slot, node, link) = 1.0_dp
  end subroutine own_dof

  subroutine interior(table, nodes, name, link, node)
    type(spatial_table_t), intent(inout) :: table
    type(gnodes_t), intent(inout) :: nodes
    character(len=*), intent(in) :: name
    integer, intent(in) :: link, node
    integer :: s
    do s = 1, merge(10, 8, nodes%axial_slopes)
      call own_dof(table, nodes, name, link, node, s)
    end do
  end subroutine interior

  !> The end node of link l at joint i (the rules in the module's head).
  subroutine joint_end(self, nodes, l, node, i)
    type(general_flex_model_t), intent(inout) :: self
    type(gnodes_t), intent(inout) :: nodes
    integer, intent(in) :: l, node, i
    integer :: s, k
    logical :: ground
    character(len=16) :: jn
    associate (jt => self%gk%mech%joints(i), tb => self%table, ln => self%gk%mech%links(l)%name)
      if (jt%kind == gjoint_free) then
        call interior(tb, nodes, ln, l, node)
        return
      end if
      jn = jt%name
      ground = jt%member(1) == 0
      if (.not. ground .or. mounted(self, i)) then
        call tb%shared_unknowns(nodes%trans(:, i), [(trim(jn)//' '//trim(slot_names(k)), k = 1, 3)])
        nodes%map(1:3, node, l) = nodes%trans(:, i)
        nodes%coef(1:3, node, l) = 1.0_dp
      end if
      if (nodes%axial_slopes) then
        call own_dof(tb, nodes, ln, l, node, 9)
        call own_dof(tb, nodes, ln, l, node, 10)
      end if
      if (jt%kind == gjoint_weld .or. (jt%kind == gjoint_revolute .and. driven(self, i))) then
        ! rotations shared (held on the ground), the moment passes
        if (.not. ground) then
          call tb%shared_unknowns(nodes%rot(:, i), [(trim(jn)//' '//trim(slot_names(k)), k = 4, 6)])
          nodes%map(4:6, node, l) = nodes%rot(:, i)
          nodes%coef(4:6, node, l) = 1.0_dp
        end if
        call own_dof(tb, nodes, ln, l, node, 7)
        call own_dof(tb, nodes, ln, l, node, 8)
      else if (jt%kind == gjoint_revolute .and. ground) then
        ! rotation s a, no moment about a (v_xx = 0)
        s = tb%new_unknown(trim(ln)//' N'//str(node)//' R_'//trim(jn))
        do k = 1, 3
          if (abs(jt%axis(k)) > 0.0_dp) then
            nodes%map(3 + k, node, l) = s
            nodes%coef(3 + k, node, l) = jt%axis(k)
          end if
        end do
        call own_dof(tb, nodes, ln, l, node, 8)
      else if (jt%kind == gjoint_revolute) then
        ! in the plane: rotations about X, Y shared, about Z and w_xx the link's own
        call tb%shared_unknowns(nodes%rot(1:2, i), [trim(jn)//' RX', trim(jn)//' RY'])
        nodes%map(4:5, node, l) = nodes%rot(1:2, i)
        nodes%coef(4:5, node, l) = 1.0_dp
        call own_dof(tb, nodes, ln, l, node, 6)
        call own_dof(tb, nodes, ln, l, node, 8)
      else
        ! spherical: local rotation triple (tx twist, ty, tz), no moment; an idle link's twist held at its first end
        do s = 4, 6
          if (s == 4 .and. node == 0 .and. self%gk%idle(l)) cycle
          call own_dof(tb, nodes, ln, l, node, s)
        end do
      end if
    end associate
  end subroutine joint_end

  !> The Newton matrix's M and K_t (band storage): the links' and the mounts'.
  subroutine mounted_band(self, q, mass, stiff)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    call self%spatial_model_t%assemble_band(q, mass, stiff)
    call self%support%add_band(self%kd, mass, stiff)
  end subroutine mounted_band

  !> Dense M and K_t: the links' and the mounts'.
  subroutine mounted_dense(self, q, mass, stiff)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    call self%spatial_model_t%assemble_dense(q, mass, stiff)
    call self%support%add_dense(mass, stiff)
  end subroutine mounted_dense

  !> Kinetic and strain energy of the links with the mounts' kinetic and
  !> spring energy.
  subroutine mounted_energies(self, t, q, qd, kinetic, strain)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out) :: kinetic, strain
    real(dp) :: km, sm
    kinetic = 0.0_dp
    strain = 0.0_dp
    if (.not. rigid_motion_at(self, t)) return
    call self%spatial_model_t%energies(t, q, qd, kinetic, strain)
    call self%support%energies(q, qd, km, sm)
    kinetic = kinetic + km
    strain = strain + sm
  end subroutine mounted_energies

  !> The static elastic state at t with the mounts (spatial_model's without):
  !> F(q, 0, t) of the links and the mounts = 0 by Newton's method on the
  !> elastic tangent and the mounts' springs, q holding the start guess.
  subroutine mounted_static_state(self, t, q, err)
    class(general_flex_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    real(dp), intent(inout) :: q(:)
    type(error_t), intent(inout) :: err
    real(dp) :: mass(self%n, self%n), stiff(self%n, self%n), f(self%n), zero(self%n)
    real(dp) :: scale
    integer :: it
    if (.not. rigid_motion_at(self, t)) then
      call err%set('general flexible model', self%err%text())
      return
    end if
    if (self%support%count() == 0) then
      call self%spatial_model_t%static_state(t, q, err)
      return
    end if
    zero = 0.0_dp
    scale = 0.0_dp
    do it = 1, 100
      call self%spatial_model_t%accelerations(t, q, zero, f)     ! the links' F in self%force
      if (self%err%failed()) then
        call err%set('general flexible model', self%err%text())
        return
      end if
      f = self%force
      call self%support%add_forces(q, zero, self%gravity, f)
      call self%assemble_dense(q, mass, stiff)
      call solve_linear(stiff, f, err)
      if (err%failed()) return
      q = q + f
      scale = max(scale, maxval(abs(q)))
      if (maxval(abs(f)) <= 1.0e-12_dp*scale) return
    end do
    call err%set('general flexible model', 'the static state with the mounts at t = '//str(t)// &
                 ' did not converge in 100 Newton steps')
  end subroutine mounted_static_state
end module general_flex_model
