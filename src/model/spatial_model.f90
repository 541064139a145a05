!> The flexible spatial four-bar as a first-order system for DLSODE:
!> M(q, t) q_dd = F(q, q_d, t) about the rigid-body motion of
!> spatial_kinematics, spatial beam elements assembled through the spatial
!> correlation table, M in band storage, banded Cholesky (cost linear in the
!> number of elements).  A second-order model (module second_order_model,
!> as the planar mechanism_model): state interleaving, Jacobian and Newton
!> matrix are the parent's.
!>
!> Joint rules (doc/spatial.md, "Joints"):
!>  A  clamp to the driving shaft: translations and rotations zero;
!>  D  ground revolute about d: translations zero, rotation = s d (one
!>     unknown), curvature about d (v_xx, the rocker's z = d) zero;
!>  B, C spherical: translations shared; each link end keeps its own rotation
!>     triple in local components; both curvatures zero (no moment); the
!>     coupler's twist is held at B (its spin about BC is idle);
!>  B, C revolute (planar linkage, axis a along a global axis): translations
!>     and the two rotations normal to a shared, rotation about a and w_xx
!>     per link, v_xx zero;
!>  B or C universal (RUSR, RSUR; the kinematics fix the coupler's spin): as
!>     spherical, but the coupler's twist is held at the universal joint (the
!>     torque about the coupler goes into the rigid motion; doc/spatial.md).
!>     One universal joint at most, not with a revolute one.
module spatial_model
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use linalg, only: sym_generalized_eig, cross, solve_linear
  use band_kernels, only: band_cholesky_inplace, band_cholesky_substitute
  use second_order_model, only: second_order_model_t
  use material_law, only: ramberg_osgood_t
  use element_effects, only: element_effects_t
  use spatial_section, only: spatial_section_t
  use spatial_beam, only: spatial_beam_t, spatial_rigid_t, spatial_eval_info_t, spatial_stress_t, &
                          spatial_beam_init, spatial_beam_eval, spatial_tangent_stiffness, spatial_strain_energy, &
                          spatial_beam_matrices, spatial_tangent_is_constant, &
                          spatial_kinetic_energy, spatial_stress_recovery, spatial_to_local, &
                          spatial_local_displacement, spatial_formulation_consistent
  use spatial_kinematics, only: spatial_fourbar_t, spatial_pose_t, spatial_fourbar_solve, &
                                link_crank, link_coupler, link_rocker
  use spatial_correlation, only: spatial_table_t, sdofs
  use spatial_mass, only: spatial_mass_t
  use spatial_external_loads, only: spatial_point_load_t
  implicit none
  private
  public :: spatial_model_t, spatial_link_t, spatial_joint_spherical, spatial_joint_revolute, spatial_joint_universal

  integer, parameter :: spatial_joint_spherical = 1, spatial_joint_revolute = 2, spatial_joint_universal = 3
  character(len=7), parameter :: link_names(3) = ['crank  ', 'coupler', 'rocker ']

  type :: spatial_link_t
    integer :: n_elements = 1
    type(spatial_section_t) :: sec
    type(ramberg_osgood_t) :: material
    real(dp) :: shear_modulus = 0.0_dp
    real(dp) :: length = 0.0_dp          !< set by the model from the geometry
    integer :: first_element = 0
  end type spatial_link_t

  !> The spatial table while it is numbered: the node DOFs of every link's
  !> nodes 0..n (slots UX UY UZ RX RY RZ vxx wxx ux uxx), joined into
  !> elements at the end (correlation_base_t%join_nodes).
  type :: spatial_nodes_t
    integer, allocatable :: map(:, :, :)       !< (10, 0:max elements, link) global unknown, 0 = held at zero
    real(dp), allocatable :: coef(:, :, :)
    integer :: ax = 0                          !< the global axis of revolute joints at B, C (0: none)
    logical :: axial_slopes = .false.          !< consistent formulation: ux, uxx own at every node
  end type spatial_nodes_t

  type, extends(second_order_model_t) :: spatial_model_t
    type(spatial_fourbar_t) :: kin
    real(dp) :: omega = 0.0_dp, theta0 = 0.0_dp
    integer :: joint_b = spatial_joint_spherical, joint_c = spatial_joint_spherical
    integer :: formulation = spatial_formulation_consistent   !< of every element (spatial_beam)
    type(spatial_link_t) :: links(3)
    type(spatial_beam_t), allocatable :: el(:)
    type(spatial_rigid_t), allocatable :: rb(:)
    integer, allocatable :: link_of(:), index_in_link(:)
    logical, allocatable :: mass_as_previous(:)   !< element e's global mass equals e-1's (same link, M_p, flags)
    logical, allocatable :: matrices_as_previous(:)   !< and its tangent too (linear, same K)
    type(spatial_table_t) :: table
    integer :: b_dofs(3) = 0, c_dofs(3) = 0     !< global unknowns of the joint translations
    type(spatial_pose_t) :: pose
    real(dp) :: t_mass = -huge(1.0_dp)           !< time of the factored mass_band (M depends on t only)
    type(spatial_mass_t) :: cmass                  !< M(t) solves through a constant factor (spatial_mass)
    real(dp) :: gravity(3) = 0.0_dp                !< gravity acceleration, global (in/s^2; spatial_loads)
    type(spatial_point_load_t), allocatable :: point_loads(:)
  contains
    procedure :: init => model_init
    procedure :: damping_beta
    procedure :: crank_angle
    procedure :: assemble_band
    procedure :: set_time
    procedure :: accelerations
    procedure :: assemble_dense
    procedure :: linear_modes
    procedure :: energies
    procedure :: element_stresses
    procedure :: link_point_displacement
    procedure :: support_forces
    procedure :: set_loads
    procedure :: static_state
  end type spatial_model_t

contains

  !> Elements, joint rules and the correlation table.  kin must be
  !> initialised; links(:) carry section, material and element counts.
  subroutine model_init(self, kin, omega, theta0, joint_b, joint_c, links, effects, beta, err, formulation)
    class(spatial_model_t), intent(inout) :: self
    type(spatial_fourbar_t), intent(in) :: kin
    real(dp), intent(in) :: omega, theta0, beta
    integer, intent(in) :: joint_b, joint_c
    type(spatial_link_t), intent(in) :: links(3)
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: formulation   !< spatial_formulation_* (default: consistent)
    integer :: k, i, e, ne
    logical :: loc(2), ball_b, ball_c
    if (joint_b == spatial_joint_universal .or. joint_c == spatial_joint_universal) then
      if (joint_b == spatial_joint_revolute .or. joint_c == spatial_joint_revolute .or. joint_b == joint_c) then
        call err%set('spatial model', 'one universal joint, at B or C, with a spherical joint at the other')
        err%code = 2
        return
      end if
      if (kin%universal_link /= merge(link_crank, link_rocker, joint_b == spatial_joint_universal)) then
        call err%set('spatial model', 'the kinematics have no universal joint at '// &
                     merge('B', 'C', joint_b == spatial_joint_universal))
        return
      end if
    end if
    ball_b = joint_b == spatial_joint_spherical .or. joint_b == spatial_joint_universal
    ball_c = joint_c == spatial_joint_spherical .or. joint_c == spatial_joint_universal
    self%formulation = spatial_formulation_consistent
    if (present(formulation)) self%formulation = formulation
    self%kin = kin
    self%omega = omega
    self%theta0 = theta0
    self%joint_b = joint_b
    self%joint_c = joint_c
    self%links = links
    self%links(link_crank)%length = kin%crank_radius
    self%links(link_coupler)%length = kin%coupler_length
    self%links(link_rocker)%length = kin%rocker_length
    ne = sum(self%links%n_elements)
    if (allocated(self%el)) deallocate(self%el, self%rb, self%link_of, self%index_in_link, self%mass_as_previous, &
                                       self%matrices_as_previous)
    call self%err%clear()
    allocate(self%el(ne), self%rb(ne), self%link_of(ne), self%index_in_link(ne), self%mass_as_previous(ne), &
             self%matrices_as_previous(ne))
    e = 0
    do k = 1, 3
      self%links(k)%first_element = e + 1
      do i = 1, self%links(k)%n_elements
        e = e + 1
        self%link_of(e) = k
        self%index_in_link(e) = i
        loc = .false.
        ! unshared rotations at spherical ends are local (the coupler's twist is held there)
        if (i == self%links(k)%n_elements) then
          loc(2) = (k == link_crank .and. ball_b) .or. (k /= link_crank .and. ball_c)
        end if
        if (i == 1 .and. k == link_coupler) loc(1) = ball_b
        associate (lk => self%links(k))
          call spatial_beam_init(self%el(e), lk%length/lk%n_elements, lk%sec, lk%material, lk%shear_modulus, &
                                 effects, err, damping_beta=beta, local_rotation=loc, formulation=self%formulation)
        end associate
        if (err%failed()) then
          call err%add_context(trim(link_names(k))//' element '//str(i))
          return
        end if
      end do
    end do
    self%mass_as_previous = .false.
    do e = 2, ne
      self%mass_as_previous(e) = self%link_of(e) == self%link_of(e - 1) .and. &
        all(self%el(e)%local_rotation .eqv. self%el(e - 1)%local_rotation) .and. &
        maxval(abs(self%el(e)%mass0 - self%el(e - 1)%mass0)) <= 0.0_dp
    end do
    self%matrices_as_previous = .false.
    do e = 2, ne
      self%matrices_as_previous(e) = self%mass_as_previous(e) .and. spatial_tangent_is_constant(self%el(e)) .and. &
        spatial_tangent_is_constant(self%el(e - 1)) .and. maxval(abs(self%el(e)%k_lin - self%el(e - 1)%k_lin)) <= 0.0_dp
    end do
    self%t_states = -huge(1.0_dp)
    self%t_mass = -huge(1.0_dp)
    call self%set_time(0.0_dp)
    if (self%err%failed()) then
      call err%set('spatial model', self%err%text())
      return
    end if
    call build_table(self, err)
    if (err%failed()) return
    call self%size_state(self%table%n_unknowns(), self%table%band())
    call self%cmass%init(self%table, self%el, self%link_of, self%n, self%kd)
  end subroutine model_init

  !> Node rules in chain order A -> B -> C -> D (narrow band).
  subroutine build_table(self, err)
    type(spatial_model_t), intent(inout) :: self
    type(error_t), intent(inout) :: err
    integer :: nmax, k, j
    type(spatial_nodes_t) :: nodes
    integer :: b_rot(2), c_rot(2)
    nmax = maxval(self%links%n_elements)
    allocate(nodes%map(10, 0:nmax, 3), nodes%coef(10, 0:nmax, 3))
    nodes%map = 0
    nodes%coef = 0.0_dp
    nodes%axial_slopes = self%formulation == spatial_formulation_consistent
    call self%table%init(size(self%el))
    if (self%joint_b == spatial_joint_revolute .or. self%joint_c == spatial_joint_revolute) then
      call revolute_axis(self, nodes%ax, err)
      if (err%failed()) return
    end if
    b_rot = 0
    c_rot = 0
    ! crank: A (clamp), interior, B
    do j = 0, self%links(link_crank)%n_elements
      if (j == 0) then
        call own_dof(self%table, nodes, 1, j, 7)
        call own_dof(self%table, nodes, 1, j, 8)
        call axial_slopes(self%table, nodes, 1, j)
      else if (j == self%links(link_crank)%n_elements) then
        call joint_end(self%table, nodes, 1, j, self%joint_b, self%b_dofs, b_rot, 'B', .false.)
      else
        call interior(self%table, nodes, 1, j)
      end if
    end do
    ! coupler: B, interior, C; its twist is held at B, or at the universal joint
    do j = 0, self%links(link_coupler)%n_elements
      if (j == 0) then
        call joint_end(self%table, nodes, 2, j, self%joint_b, self%b_dofs, b_rot, 'B', &
                       self%joint_c /= spatial_joint_universal)
      else if (j == self%links(link_coupler)%n_elements) then
        call joint_end(self%table, nodes, 2, j, self%joint_c, self%c_dofs, c_rot, 'C', &
                       self%joint_c == spatial_joint_universal)
      else
        call interior(self%table, nodes, 2, j)
      end if
    end do
    ! rocker from C down to D
    do j = self%links(link_rocker)%n_elements, 0, -1
      if (j == self%links(link_rocker)%n_elements) then
        call joint_end(self%table, nodes, 3, j, self%joint_c, self%c_dofs, c_rot, 'C', .false.)
      else if (j == 0) then
        call ground_revolute(self%table, nodes, self%kin%d_axis)
      else
        call interior(self%table, nodes, 3, j)
      end if
    end do
    do k = 1, 3
      associate (n_k => self%links(k)%n_elements)
        call self%table%join_nodes(self%links(k)%first_element, nodes%map(:, 0:n_k, k), nodes%coef(:, 0:n_k, k))
      end associate
    end do
    call self%table%finish_band()
  end subroutine build_table

  !> The global axis of a planar linkage with revolute joints at B or C (an
  !> input error if the linkage is not planar about one).
  subroutine revolute_axis(self, ax, err)
    type(spatial_model_t), intent(in) :: self
    integer, intent(out) :: ax
    type(error_t), intent(inout) :: err
    real(dp) :: a(3)
    a = self%kin%a_axis
    ax = maxloc(abs(a), 1)
    if (abs(abs(a(ax)) - 1.0_dp) > 1.0e-12_dp .or. abs(abs(dot_product(a, self%kin%d_axis)) - 1.0_dp) > 1.0e-12_dp &
        .or. abs(dot_product(a, self%pose%rot(:, 1, link_coupler))) > 1.0e-9_dp) then
      call err%set('spatial model', 'revolute joints at B or C need a planar linkage: crank and rocker axes '// &
                   'parallel to one global axis and the coupler normal to it (use spherical joints otherwise)')
      err%code = 2
    end if
  end subroutine revolute_axis

  !> Node DOF slot of a link node as an own unknown, labelled by link, node and slot.
  subroutine own_dof(table, nodes, link, node, slot)
    type(spatial_table_t), intent(inout) :: table
    type(spatial_nodes_t), intent(inout) :: nodes
    integer, intent(in) :: link, node, slot
    character(len=4), parameter :: names(10) = ['UX  ', 'UY  ', 'UZ  ', 'RX  ', 'RY  ', 'RZ  ', 'vxx ', 'wxx ', &
                                                'ux  ', 'uxx ']
    nodes%map(slot, node, link) = table%new_unknown(trim(link_names(link))//' N'//str(node)//' '//trim(names(slot)))
    nodes%coef(slot, node, link) = 1.0_dp
  end subroutine own_dof

  subroutine interior(table, nodes, link, node)
    type(spatial_table_t), intent(inout) :: table
    type(spatial_nodes_t), intent(inout) :: nodes
    integer, intent(in) :: link, node
    integer :: s
    do s = 1, 8
      call own_dof(table, nodes, link, node, s)
    end do
    call axial_slopes(table, nodes, link, node)
  end subroutine interior

  !> u's slope and curvature DOFs (consistent formulation): free at every
  !> node, local to the link (axial strain and its rate are not transmitted
  !> by a joint); held in Kear's formulation, whose u is linear.
  subroutine axial_slopes(table, nodes, link, node)
    type(spatial_table_t), intent(inout) :: table
    type(spatial_nodes_t), intent(inout) :: nodes
    integer, intent(in) :: link, node
    if (.not. nodes%axial_slopes) return
    call own_dof(table, nodes, link, node, 9)
    call own_dof(table, nodes, link, node, 10)
  end subroutine axial_slopes

  !> The rocker at D, a ground revolute about d: rotation = s d, no moment about d.
  subroutine ground_revolute(table, nodes, d_axis)
    type(spatial_table_t), intent(inout) :: table
    type(spatial_nodes_t), intent(inout) :: nodes
    real(dp), intent(in) :: d_axis(3)
    integer :: s, i
    s = table%new_unknown('rocker N0 R_d')
    do i = 1, 3
      if (abs(d_axis(i)) > 0.0_dp) then
        nodes%map(3 + i, 0, 3) = s
        nodes%coef(3 + i, 0, 3) = d_axis(i)
      end if
    end do
    call own_dof(table, nodes, 3, 0, 8)
    call axial_slopes(table, nodes, 3, 0)
  end subroutine ground_revolute

  !> A link end at joint B or C; trans/rot: the joint's shared unknowns
  !> (created at the first visit).
  subroutine joint_end(table, nodes, link, node, kind, trans, rot, jname, hold_twist)
    type(spatial_table_t), intent(inout) :: table
    type(spatial_nodes_t), intent(inout) :: nodes
    integer, intent(in) :: link, node, kind
    integer, intent(inout) :: trans(3), rot(2)
    character(len=1), intent(in) :: jname
    logical, intent(in) :: hold_twist
    integer :: s, others(2)
    character(len=4) :: labels(3)
    labels = [jname//' UX', jname//' UY', jname//' UZ']
    call table%shared_unknowns(trans, labels)
    nodes%map(1:3, node, link) = trans
    nodes%coef(1:3, node, link) = 1.0_dp
    call axial_slopes(table, nodes, link, node)
    if (kind /= spatial_joint_revolute) then
      ! spherical or universal: local rotation triple (tx = twist, ty, tz); no moment: curvatures zero
      do s = 4, 6
        if (s == 4 .and. hold_twist) cycle
        call own_dof(table, nodes, link, node, s)
      end do
    else
      associate (ax => nodes%ax)
        others = pack([1, 2, 3], [1, 2, 3] /= ax)
        labels(1:2) = [jname//' R'//achar(iachar('X') + others(1) - 1), jname//' R'//achar(iachar('X') + others(2) - 1)]
        call table%shared_unknowns(rot, labels(1:2))
        nodes%map(3 + others, node, link) = rot
        nodes%coef(3 + others, node, link) = 1.0_dp
        call own_dof(table, nodes, link, node, 3 + ax)
        call own_dof(table, nodes, link, node, 8)         ! w_xx: out-of-plane moment passes the pin
      end associate
    end if
  end subroutine joint_end

  !> Gravity (global, in/s^2) and point loads (spatial_loads); the rigid
  !> states are recomputed with them at the next time asked for.
  subroutine set_loads(self, gravity, point_loads)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: gravity(3)
    type(spatial_point_load_t), intent(in) :: point_loads(:)
    self%gravity = gravity
    self%point_loads = point_loads
    self%t_states = -huge(1.0_dp)
    self%t_mass = -huge(1.0_dp)
  end subroutine set_loads

  !> f := f + the point loads' generalized forces: the force on the node's
  !> translations (global), the moment on its rotations (global, or in the
  !> element axes at an end whose rotations are local).
  subroutine add_point_loads(self, f)
    class(spatial_model_t), intent(in) :: self
    real(dp), intent(inout) :: f(:)
    real(dp) :: fe(sdofs)
    integer :: k, base
    if (.not. allocated(self%point_loads)) return
    do k = 1, size(self%point_loads)
      associate (pl => self%point_loads(k))
        fe = 0.0_dp
        base = 10*(pl%node - 1)
        fe(base + 1:base + 3) = pl%force
        if (self%el(pl%element)%local_rotation(pl%node)) then
          fe(base + 4:base + 6) = matmul(pl%moment, self%rb(pl%element)%rot)      ! R^T m
        else
          fe(base + 4:base + 6) = pl%moment
        end if
        call self%table%scatter_add(pl%element, fe, f)
      end associate
    end do
  end subroutine add_point_loads

  !> The static elastic state q at time t under the loads of the rigid
  !> motion there (its inertia loads, gravity, point loads), q_d = 0:
  !> F(q, 0, t) = 0 by Newton's method on the elastic tangent (the inertial
  !> stiffness is left out of the matrix, so the iteration converges
  !> linearly, by about (omega/omega_1)^2 a step).  q holds the start guess.
  subroutine static_state(self, t, q, err)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    real(dp), intent(inout) :: q(:)
    type(error_t), intent(inout) :: err
    real(dp) :: stiff(self%n, self%n), f(self%n), zero(sdofs), me(sdofs, sdofs), fe(sdofs), ke(sdofs, sdofs)
    type(spatial_eval_info_t) :: info
    integer :: it, e
    real(dp) :: scale
    call self%set_time(t)
    zero = 0.0_dp
    scale = 0.0_dp
    do it = 1, 100
      stiff = 0.0_dp
      f = 0.0_dp
      do e = 1, size(self%el)
        call spatial_beam_eval(self%el(e), self%table%gather(e, q), zero, self%rb(e), me, fe, info, tangent=ke, &
                               mass_wanted=.false.)
        call self%table%scatter_add(e, fe, f)
        call self%table%scatter_add_matrix(e, ke, stiff)
      end do
      call add_point_loads(self, f)
      call solve_linear(stiff, f, err)
      if (err%failed()) return
      q = q + f
      scale = max(scale, maxval(abs(q)))
      if (maxval(abs(f)) <= 1.0e-12_dp*scale) return
    end do
    call err%set('spatial model', 'the static state at t = '//str(t)//' did not converge in 100 Newton steps '// &
                 '(last correction '//str(maxval(abs(f)))//' of '//str(scale)//')')
  end subroutine static_state

  !> The elements' stiffness-proportional damping coefficient (one for all).
  real(dp) function damping_beta(self) result(beta)
    class(spatial_model_t), intent(in) :: self
    beta = self%el(1)%beta
  end function damping_beta

  !> The crank angle (rad) at time t.
  real(dp) function crank_angle(self, t) result(theta)
    class(spatial_model_t), intent(in) :: self
    real(dp), intent(in) :: t
    theta = self%theta0 + self%omega*t
  end function crank_angle

  !> Rigid states of all elements at time t (crank angle theta0 + omega t).
  subroutine set_time(self, t)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t) :: err
    integer :: e, k
    real(dp) :: r(3), x(3)
    if (.not. (t < self%t_states .or. t > self%t_states)) return
    call spatial_fourbar_solve(self%kin, self%theta0 + self%omega*t, self%omega, 0.0_dp, self%pose, err)
    self%n_kinematics = self%n_kinematics + 1
    if (err%failed()) then
      call self%fail(t, err%text())
      return
    end if
    do e = 1, size(self%el)
      k = self%link_of(e)
      associate (rb => self%rb(e), ps => self%pose)
        rb%rot = ps%rot(:, :, k)
        x = rb%rot(:, 1)
        r = real(self%index_in_link(e) - 1, dp)*self%el(e)%length*x
        rb%x1 = ps%origin(:, k) + r
        rb%omega = ps%omega(:, k)
        rb%alpha = ps%alpha(:, k)
        rb%x1_d = ps%origin_d(:, k) + cross(rb%omega, r)
        ! gravity: the body force -rho A (a - g), as an acceleration -g of the frame
        rb%x1_dd = ps%origin_dd(:, k) + cross(rb%alpha, r) + cross(rb%omega, cross(rb%omega, r)) - self%gravity
      end associate
    end do
    self%t_states = t
  end subroutine set_time

  !> q_dd from M q_dd = F: by the banded Cholesky factor of M, or through
  !> spatial_mass (M(t)^-1 by the constant factor and the joint unknowns' Schur
  !> complement) when that is active.  M depends on the rigid state only (the
  !> element's M_p is constant): its factor is reused while t is unchanged
  !> (DLSODE's corrector iterations), which is exact.
  subroutine accelerations(self, t, q, qd, qdd)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out), contiguous :: qdd(:)
    real(dp) :: me(sdofs, sdofs), fe(sdofs), qe(sdofs), qde(sdofs)
    type(spatial_eval_info_t) :: info
    integer :: e, minor
    logical :: new_mass, band_mass, ok
    call self%set_time(t)
    qdd = 0.0_dp
    if (self%err%failed()) return
    new_mass = t < self%t_mass .or. t > self%t_mass
    band_mass = new_mass .and. .not. self%cmass%active     ! the banded M is assembled at this time
    if (band_mass) self%mass_band = 0.0_dp
    self%force = 0.0_dp
    do e = 1, size(self%el)
      call self%table%gather_pair(e, q, qd, qe, qde)
      ! consecutive elements of a link with equal M_p share one global mass (same rotation)
      call spatial_beam_eval(self%el(e), qe, qde, self%rb(e), me, fe, info, &
                             mass_wanted=band_mass .and. .not. self%mass_as_previous(e))
      self%n_nonlinear_points = self%n_nonlinear_points + info%n_nonlinear_points
      if (info%beyond_peak .and. self%stop_beyond_peak) then
        call self%fail(t, 'strain '//str(info%max_abs_strain, 6)//' in element '//str(e)// &
                       ' is past the peak of the Ramberg-Osgood curve, eps* = '//str(self%el(e)%eps_star, 6))
        return
      end if
      call self%table%scatter_add(e, fe, self%force)
      if (band_mass) call self%table%add_lower_band(e, me, self%mass_band)
    end do
    call add_point_loads(self, self%force)
    if (new_mass) then
      self%t_mass = huge(1.0_dp)                ! invalid until factored
      if (self%cmass%active) then
        call self%cmass%update(self%rb, ok)
      else
        call band_cholesky_inplace(self%mass_band, self%kd, minor)
        ok = minor == 0
      end if
      self%n_mass_factorizations = self%n_mass_factorizations + 1
      if (.not. ok) then
        call self%fail(t, 'mass matrix is not positive definite')
        return
      end if
      self%t_mass = t
    end if
    qdd = self%force
    if (self%cmass%active) then
      call self%cmass%solve(self%rb, qdd)
    else
      call band_cholesky_substitute(self%mass_band, self%kd, qdd)
    end if
  end subroutine accelerations

  !> M (lower band storage, kd+1 rows) and K_t (general band storage,
  !> kb(kd+1+i-j, j) = K(i, j), 2kd+1 rows) at q (current rigid states): O(N).
  subroutine assemble_band(self, q, mass, stiff)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    real(dp) :: me(sdofs, sdofs), ke(sdofs, sdofs)
    integer :: e
    mass = 0.0_dp
    stiff = 0.0_dp
    do e = 1, size(self%el)
      ! consecutive linear elements of a link with equal M_p and K share the global matrices
      if (.not. self%matrices_as_previous(e)) &
        call spatial_beam_matrices(self%el(e), self%table%gather(e, q), self%rb(e), me, ke)
      call self%table%add_newton_bands(e, me, ke, self%kd, mass, stiff)
    end do
  end subroutine assemble_band

  !> Dense M and elastic tangent K at q (current rigid states).
  subroutine assemble_dense(self, q, mass, stiff)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    real(dp) :: me(sdofs, sdofs), fe(sdofs), ke(sdofs, sdofs)
    type(spatial_eval_info_t) :: info
    integer :: e, i
    mass = 0.0_dp
    stiff = 0.0_dp
    do e = 1, size(self%el)
      call spatial_beam_eval(self%el(e), self%table%gather(e, q), [(0.0_dp, i=1, sdofs)], self%rb(e), me, fe, info, &
                             tangent=ke)
      call self%table%scatter_add_matrix(e, me, mass)
      call self%table%scatter_add_matrix(e, ke, stiff)
    end do
  end subroutine assemble_dense

  !> Natural frequencies (rad/s) of the linearised structure at the current
  !> position and, if asked, the M-normalised mode shapes (columns).
  subroutine linear_modes(self, omega, err, shapes)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(out) :: omega(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: shapes(:, :)
    real(dp) :: mass(self%n, self%n), stiff(self%n, self%n), q0(self%n)
    q0 = 0.0_dp
    call self%assemble_dense(q0, mass, stiff)
    if (present(shapes)) then
      call sym_generalized_eig(stiff, mass, omega, err, shapes)
    else
      call sym_generalized_eig(stiff, mass, omega, err)
    end if
    if (err%failed()) return
    omega = sign(sqrt(abs(omega)), omega)
  end subroutine linear_modes

  !> Kinetic energy (rigid plus elastic motion) and strain energy at time t.
  subroutine energies(self, t, q, qd, kinetic, strain)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out) :: kinetic, strain
    integer :: e
    real(dp) :: qe(sdofs)
    call self%set_time(t)
    kinetic = 0.0_dp
    strain = 0.0_dp
    do e = 1, size(self%el)
      qe = self%table%gather(e, q)
      kinetic = kinetic + spatial_kinetic_energy(self%el(e), qe, self%table%gather(e, qd), self%rb(e))
      strain = strain + spatial_strain_energy(self%el(e), spatial_to_local(self%rb(e)%rot, qe, &
                                                                            self%el(e)%local_rotation))
    end do
  end subroutine energies

  !> Forces (global, lb) the supports exert on the structure at A (crank
  !> shaft) and D (rocker pivot): the constrained rows of the element
  !> equations, r = M_e q_dd - F_e at the node on the support, with q_dd from
  !> the equations of motion.  Internal forces cancel in the sum over the
  !> structure, so f_A + f_D is the rate of change of its linear momentum.
  subroutine support_forces(self, t, q, qd, fa, fd)
    class(spatial_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out) :: fa(3), fd(3)
    real(dp) :: qdd(self%n), me(sdofs, sdofs), fe(sdofs), r(sdofs)
    type(spatial_eval_info_t) :: info
    integer :: k, e
    call self%accelerations(t, q, qd, qdd)
    do k = 1, 2
      e = self%links(merge(link_crank, link_rocker, k == 1))%first_element
      call spatial_beam_eval(self%el(e), self%table%gather(e, q), self%table%gather(e, qd), self%rb(e), me, fe, info)
      r = matmul(me, self%table%gather(e, qdd)) - fe
      if (k == 1) then
        fa = r(1:3)
      else
        fd = r(1:3)
      end if
    end do
  end subroutine support_forces

  !> Stress report of every element (rigid states must be current).
  subroutine element_stresses(self, q, reports)
    class(spatial_model_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    type(spatial_stress_t), intent(out) :: reports(:)
    integer :: e
    do e = 1, size(self%el)
      reports(e) = spatial_stress_recovery(self%el(e), self%table%gather(e, q), self%rb(e)%rot)
    end do
  end subroutine element_stresses

  !> Elastic displacement (global X, Y, Z) of the point at s times the length
  !> of link `link` (s in [0, 1] from its end 1), by the shape functions of the
  !> element that holds it (an interior element end: the element before).
  !> Rigid states must be current.
  function link_point_displacement(self, q, link, s) result(d)
    class(spatial_model_t), intent(in) :: self
    real(dp), intent(in) :: q(:), s
    integer, intent(in) :: link
    real(dp) :: d(3)
    integer :: n, k, e
    real(dp) :: xi, rot(3, 3), p(sdofs), local(3)
    n = self%links(link)%n_elements
    k = min(n - 1, max(0, ceiling(s*n - 1.0e-9_dp) - 1))
    xi = min(1.0_dp, max(0.0_dp, s*n - k))
    e = self%links(link)%first_element + k
    rot = self%rb(e)%rot
    p = spatial_to_local(rot, self%table%gather(e, q), self%el(e)%local_rotation)
    local = spatial_local_displacement(self%el(e), p, xi)
    d = matmul(rot, local)
  end function link_point_displacement
end module spatial_model
