!> The flexible planar mechanism M(q, t) q_dd = F(q, q_d, t) about its known
!> rigid-body motion (K30-K34), as a second-order model for DLSODE (module
!> second_order_model: state interleaving, Jacobian, Newton matrix).  One
!> right-hand side takes the rigid motion at t, evaluates every element
!> (Kear's or the consistent element, through the beam_element contract)
!> through the variable correlation table, assembles M in band storage and
!> F, factors M by the project's banded Cholesky (band_kernels: cost linear
!> in the number of elements) and solves for the accelerations.
!>
!> The model of a linkage is finished in one step, `init_mechanism`
!> (elements, joint masses and counterweights, loads, the rigid motion's
!> table, the start modes and the clearance joints).
!>
!> The rigid-body motion depends on the crank angle only, so by default it is
!> tabulated once over a revolution (`build_motion_table`, module
!> rigid_motion_table): this takes the kinematic Newton solves out of the
!> right-hand side.  When every element's M and K_t are constant in its frame
!> the global ones are tabulated as functions of the element angles (module
!> frame_band_table).
!>
!> A link sliding through a sleeve (slider_link) is Tennant's element with
!> the moving integration limit and the sleeve's angle-dependent map (module
!> sliding_link); its Kear element in el(e) is kept for the element count
!> and the end displacements but left out of the equations.
!>
!> A structure that does not move (beam tests) is modelled with fixed element
!> rigid states instead of kinematics (`init_fixed`).
module mechanism_model
  use frame_band_table, only: frame_table_t, frame_matrix, angle_basis
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use band_kernels, only: band_cholesky_inplace, band_cholesky_substitute
  use linalg, only: sym_generalized_eig, solve_linear
  use second_order_model, only: second_order_model_t
  use correlation_table, only: correlation_table_t, link_end_t
  use element_effects, only: element_effects_t
  use planar_element, only: rigid_state_t, element_eval_info_t, stress_report_t
  use beam_element, only: beam_element_init, beam_element_eval, &
                          beam_strain_energy, beam_kinetic_energy, beam_stress_recovery, beam_point_load, &
                          resolve_formulation, planar_element_t, beam_linear_strain, beam_mass_constant_in_q
  use external_loads, only: point_load_t, load_factor_at
  use material_law, only: ramberg_osgood_t
  use linkage, only: mechanism_t, driver_angle
  use kinematics, only: kinematics_t, motion_t
  use joint_clearance, only: clearance_joint_t, split_journal, add_contact_forces, contact_blocks, add_pair_block, &
                             pair_dofs
  use rigid_motion_table, only: motion_table_t
  use lumped_masses, only: joint_masses_t, counterweights_t, place_joint_masses, place_counterweights
  use linkage_model_setup, only: start_linkage_model
  use sliding_link, only: sliding_link_t, sliding_link_init, sliding_link_set_state, &
                          sliding_link_add, sliding_link_matrices, sliding_link_element_q, sliding_link_stress, &
                          sliding_link_energies
  use tennant_element, only: tennant_info_t
  implicit none
  private
  public :: mechanism_model_t, element_spec_t, counterweight_arm

  !> DLSODE's Newton matrix of a turning mechanism: at most this many steps
  !> old, and re-formed earlier when the chord iteration's measured
  !> contraction factor would pass newton_contraction (set_newton_ageing).
  integer, parameter :: newton_age_limit = 5
  real(dp), parameter :: newton_contraction = 0.2_dp

  !> What an element needs besides its rigid state (for init_fixed).
  type :: element_spec_t
    real(dp) :: length = 0.0_dp, width = 0.0_dp, depth = 0.0_dp
    type(ramberg_osgood_t) :: material
  end type element_spec_t

  type, extends(second_order_model_t) :: mechanism_model_t
    logical :: moving = .true.                    !< rigid motion from kinematics (else fixed states)
    type(kinematics_t) :: kin
    type(correlation_table_t) :: table
    class(planar_element_t), allocatable :: el(:) !< one dynamic type: resolve_formulation's mold
    character(len=16) :: formulation = ''         !< the element formulation in effect (resolved 'default')
    type(rigid_state_t), allocatable :: rb(:)     !< current rigid state of each element
    ! element work arrays of the right-hand side and the Newton matrix (automatic
    ! arrays of run-time size are heap-allocated by gfortran)
    real(dp), allocatable :: work_me(:, :), work_ke(:, :), work_fe(:), work_qe(:), work_qde(:)
    ! element M and K_t constant in the element frame (Kear's element, linear strains): their global
    ! band entries are tabulated once as functions of the elements' angles (build_frame_tables)
    logical :: frame_tables = .false.
    logical :: frame_symmetric = .false.          !< every element's frame K_t is symmetric (so every global one)
    type(frame_table_t) :: frame_mass, frame_stiff
    real(dp), allocatable :: frame_basis(:, :)   !< (4, element): cos phi, sin phi, cos 2phi, sin 2phi
    logical :: mass_constant_in_q = .false.       !< M depends on t only (see accelerations)
    logical :: mass_factored = .false.            !< mass_band holds the factor of M at t_mass
    real(dp) :: t_mass = 0.0_dp
    ! tabulated rigid-body motion over one crank revolution (see build_motion_table)
    logical :: tabulated = .false.
    type(motion_table_t) :: motion
    type(motion_t), allocatable :: work_motion(:)  !< the elements' motion at a time, from the table
    type(joint_masses_t) :: joint_mass           !< lumped masses at joints (slider blocks, sleeves)
    type(counterweights_t) :: cw                  !< counterweights on arms clamped at ground pivots
    ! external loads (src/model/external_loads.f90): gravity acceleration and point forces/moments
    real(dp) :: gravity(2) = 0.0_dp               !< global (X, Y) acceleration of gravity
    type(point_load_t), allocatable :: loads(:)
    real(dp) :: load_scale = 1.0_dp               !< multiplies every point load (static load stepping)
    ! pin joints with radial clearance (doc/clearance.md): none unless add_clearance was called
    logical :: has_clearance = .false.
    type(clearance_joint_t), allocatable :: clearance(:)
    type(correlation_table_t) :: pinned_table     !< the table before the clearance split (linkage_table)
    ! links sliding through a sleeve (module sliding_link): their element replaces el(e) in the equations
    type(sliding_link_t), allocatable :: slide(:)
  contains
    procedure :: init_mechanism
    procedure :: linkage_table
    procedure :: init_fixed
    procedure :: newton_factor => model_newton_factor
    procedure :: damping_beta
    procedure :: crank_angle
    procedure :: assemble_band
    procedure :: set_time
    procedure, private :: build_motion_table
    procedure :: accelerations
    procedure :: assemble_dense
    procedure :: linear_modes
    procedure :: energies
    procedure :: element_stresses
    procedure, private :: set_loads
    procedure :: static_equilibrium
    procedure :: element_joint_force
    procedure, private :: add_clearance
    procedure, private :: clearance_spin
    procedure :: element_q
  end type mechanism_model_t

contains

  ! ------------------------------------------------------------------ set-up

  !> The model of a linkage, finished in this one step: kinematics,
  !> correlation table from the joints, one element of the formulation per
  !> link segment, joint masses and counterweights; then, as asked, its
  !> loads (gravity and point loads, both or neither), the rigid motion
  !> tabulated at table_points crank angles per revolution (when the crank
  !> turns and table_points > 0), the natural frequencies and M-normalised
  !> mode shapes at the start position (omega, shapes: linear_modes), and
  !> the clearance joints (add_clearance).  The start modes and the table
  !> in the output header (linkage_table) are those of the pinned linkage:
  !> the clearance's journal unknowns are added after them.  elements_refused:
  !> the failure (err) is the linkage's elements' (an input error of the
  !> mechanism), not one of the later steps.
  subroutine init_mechanism(self, mech, effects, formulation, beta, err, gravity, point_loads, table_points, &
                            clearance, omega, shapes, elements_refused)
    class(mechanism_model_t), intent(inout) :: self
    type(mechanism_t), intent(in) :: mech
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: formulation
    real(dp), intent(in) :: beta
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: gravity(2)
    type(point_load_t), intent(in), optional :: point_loads(:)
    integer, intent(in), optional :: table_points
    type(clearance_joint_t), intent(in), optional :: clearance(:)
    real(dp), allocatable, intent(out), optional :: omega(:), shapes(:, :)
    logical, intent(out), optional :: elements_refused
    if (present(elements_refused)) elements_refused = .true.
    call init_elements(self, mech, effects, formulation, beta, err)
    if (err%failed()) return
    if (present(elements_refused)) elements_refused = .false.
    if (present(gravity) .and. present(point_loads)) call self%set_loads(gravity, point_loads)
    if (present(table_points)) then
      if (table_points > 0 .and. mech%driver%omega > 0.0_dp) call self%build_motion_table(table_points, err)
      if (err%failed()) return
    end if
    if (present(omega) .and. present(shapes)) then
      allocate(omega(self%n), shapes(self%n, self%n))
      call self%linear_modes(omega, shapes, err)
      if (err%failed()) return
    end if
    if (present(clearance)) then
      if (size(clearance) > 0) then
        self%pinned_table = self%table
        call self%add_clearance(clearance, err)
      end if
    end if
  end subroutine init_mechanism

  !> The table of the linkage's pinned joints: the one in the output header
  !> (with clearance joints, the table before their journals were split).
  function linkage_table(self) result(table)
    class(mechanism_model_t), intent(in) :: self
    type(correlation_table_t) :: table
    if (self%has_clearance) then
      table = self%pinned_table
    else
      table = self%table
    end if
  end function linkage_table

  !> The elements of a linkage (init_mechanism's first step).
  subroutine init_elements(self, mech, effects, formulation, beta, err)
    type(mechanism_model_t), intent(inout) :: self
    type(mechanism_t), intent(in) :: mech
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: formulation
    real(dp), intent(in) :: beta
    type(error_t), intent(inout) :: err
    integer :: k, e
    class(planar_element_t), allocatable :: mold
    character(len=:), allocatable :: resolved
    type(motion_t) :: m

    self%moving = .true.
    call set_newton_ageing(self, abs(mech%driver%omega) > 0.0_dp)
    call resolve_formulation(formulation, effects, mold, resolved, err)
    if (err%failed()) return
    self%formulation = resolved
    call start_linkage_model(mech, self%table, self%kin, err, reduce_band=.true., &
                             axial_dofs=mold%axial_dofs())
    if (err%failed()) return

    allocate(self%el(self%table%n_elements()), source=mold)
    allocate(self%rb(self%table%n_elements()))
    do k = 1, mech%n_links
      associate (lk => mech%links(k))
        do e = lk%first_element, lk%first_element + lk%n_elements - 1
          m = self%kin%element_motion_global(e)
          call beam_element_init(self%el(e), m%length, lk%b, lk%h, &
                                 ramberg_osgood_t(lk%e1, lk%e2, lk%m, lk%rho), effects, err, &
                                 damping_beta=beta, fibre_distance=lk%fibre)
          if (err%failed()) then
            call err%add_context('link '''//trim(lk%name)//''' element '//str(e))
            return
          end if
        end do
      end associate
    end do
    allocate(self%slide(0))
    do k = 1, mech%n_links
      if (.not. mech%links(k)%sliding) cycle
      m = self%kin%element_motion_global(mech%links(k)%first_element)
      block
        type(sliding_link_t) :: sl
        call sliding_link_init(sl, mech, k, m%length, effects, beta, self%table%node_dofs(), err)
        if (err%failed()) return
        if (sl%carrier_element > 0) sl%carrier_length = self%el(sl%carrier_element)%length
        self%slide = [self%slide, sl]
      end block
    end do
    call allocate_work(self)
    allocate(self%loads(0))
    ! joint masses ride on the elastic translation of their node: kinetic
    ! energy m/2 |r_rigid' + (U', W')|^2 (module lumped_masses)
    call place_joint_masses(mech, self%joint_mass)
    call place_counterweights(mech, self%cw, err)
    if (err%failed()) return
    call self%set_time(0.0_dp)
  end subroutine init_elements

  !> The counterweights in Lagrange's equation of their link's end slope
  !> w_x: J on the mass diagonal; J (-phi_dd) and the weight's moment
  !> g . d/dpsi (R(psi) m c), psi = phi + w_x, on the right.  A clamped end
  !> (no slope unknown) takes them through the rigid motion alone.
  subroutine add_counterweights(self, q, new_mass)
    type(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    logical, intent(in) :: new_mass
    integer :: k, e, g
    real(dp) :: c, arm(2)
    if (new_mass) call add_counterweight_mass(self, self%mass_band, .true.)
    do k = 1, self%cw%count()
      e = self%cw%element(k)
      g = self%table%unknown(3, e)
      if (g == 0) cycle
      c = self%table%coefficient(3, e)
      arm = counterweight_arm(self, k, self%rb(e)%phi + c*q(g))
      self%force(g) = self%force(g) + c*(-self%cw%inertia(k)*self%rb(e)%phi_dd - self%gravity(1)*arm(2) + &
                                         self%gravity(2)*arm(1))
    end do
  end subroutine add_counterweights

  !> m R(psi) c: the counterweight's first moment about its pivot at angle psi.
  pure function counterweight_arm(self, k, psi) result(arm)
    type(mechanism_model_t), intent(in) :: self
    integer, intent(in) :: k
    real(dp), intent(in) :: psi
    real(dp) :: arm(2), mc(2)
    mc = self%cw%moment(k)
    arm = [cos(psi)*mc(1) - sin(psi)*mc(2), sin(psi)*mc(1) + cos(psi)*mc(2)]
  end function counterweight_arm

  !> J on the slope's diagonal: dense (band = F) or lower band storage.
  subroutine add_counterweight_mass(self, mass, band)
    type(mechanism_model_t), intent(in) :: self
    real(dp), intent(inout) :: mass(:, :)
    logical, intent(in) :: band
    integer :: k, e, g
    do k = 1, self%cw%count()
      e = self%cw%element(k)
      g = self%table%unknown(3, e)
      if (g == 0) cycle
      if (band) then
        mass(1, g) = mass(1, g) + self%cw%inertia(k)*self%table%coefficient(3, e)**2
      else
        mass(g, g) = mass(g, g) + self%cw%inertia(k)*self%table%coefficient(3, e)**2
      end if
    end do
  end subroutine add_counterweight_mass

  !> Rigid-body acceleration of node `node` (1 = x = 0, 2 = x = l) of element e.
  pure function node_acceleration(rb, length, node) result(a)
    type(rigid_state_t), intent(in) :: rb
    real(dp), intent(in) :: length
    integer, intent(in) :: node
    real(dp) :: a(2), c, s
    a = [rb%x1_dd, rb%y1_dd]
    if (node == 2) then
      c = cos(rb%phi)
      s = sin(rb%phi)
      a = a + length*[-rb%phi_dd*s - rb%phi_d**2*c, rb%phi_dd*c - rb%phi_d**2*s]
    end if
  end function node_acceleration

  !> Global unknowns and coefficients of the X and Y translations of a node.
  pure subroutine node_translation_dofs(self, e, node, g, c)
    type(mechanism_model_t), intent(in) :: self
    integer, intent(in) :: e, node
    integer, intent(out) :: g(2)
    real(dp), intent(out) :: c(2)
    integer :: first
    first = 1 + self%table%node_dofs()*(node - 1)
    g = self%table%unknowns_of([first, first + 1], e)
    c = self%table%coefficients_of([first, first + 1], e)
  end subroutine node_translation_dofs

  !> A structure at rest: elements with given rigid states and a table built
  !> from the given link ends (beam verification tests), with its loads
  !> (gravity and point loads, both or neither).
  subroutine init_fixed(self, specs, states, n_elem, ends, effects, formulation, beta, err, gravity, point_loads)
    class(mechanism_model_t), intent(inout) :: self
    type(element_spec_t), intent(in) :: specs(:)
    type(rigid_state_t), intent(in) :: states(:)
    integer, intent(in) :: n_elem(:)
    type(link_end_t), intent(in) :: ends(:, :)
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: formulation
    real(dp), intent(in) :: beta
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: gravity(2)
    type(point_load_t), intent(in), optional :: point_loads(:)
    integer :: e
    class(planar_element_t), allocatable :: mold
    character(len=:), allocatable :: resolved
    self%moving = .false.
    call set_newton_ageing(self, .false.)
    allocate(self%loads(0), self%slide(0))
    call resolve_formulation(formulation, effects, mold, resolved, err)
    if (err%failed()) return
    self%formulation = resolved
    call self%table%build(n_elem, ends, err, axial_dofs=mold%axial_dofs())
    if (err%failed()) return
    if (size(specs) /= self%table%n_elements() .or. size(states) /= self%table%n_elements()) then
      call err%set('flexible model', 'need one element spec and rigid state per element')
      return
    end if
    allocate(self%el(self%table%n_elements()), source=mold)
    self%rb = states
    do e = 1, self%table%n_elements()
      call beam_element_init(self%el(e), specs(e)%length, specs(e)%width, specs(e)%depth, specs(e)%material, &
                             effects, err, damping_beta=beta)
      if (err%failed()) return
    end do
    call allocate_work(self)
    if (present(gravity) .and. present(point_loads)) call self%set_loads(gravity, point_loads)
  end subroutine init_fixed

  subroutine allocate_work(self)
    type(mechanism_model_t), intent(inout) :: self
    integer :: e
    ! (add_clearance renumbers the unknowns and calls this again)
    call self%size_state(self%table%n_unknowns(), self%table%band())
    if (allocated(self%work_me)) deallocate(self%work_me, self%work_ke, self%work_fe, self%work_qe, self%work_qde)
    if (allocated(self%frame_basis)) deallocate(self%frame_basis)
    associate(nd => self%table%element_dofs())
      allocate(self%work_me(nd, nd), self%work_ke(nd, nd), self%work_fe(nd), self%work_qe(nd), self%work_qde(nd))
    end associate
    self%mass_constant_in_q = all([(beam_mass_constant_in_q(self%el(e)), e = 1, size(self%el))])
    self%mass_factored = .false.
    call build_frame_tables(self)
  end subroutine allocate_work

  !> When every element is Kear's with linear strains and a mass independent
  !> of q, its M_e and K_t are constant in the element frame: tabulate the
  !> global M and K_t as functions of the element angles (module
  !> frame_band_table).
  subroutine build_frame_tables(self)
    type(mechanism_model_t), intent(inout) :: self
    real(dp), dimension(8, 8) :: ml, kl
    real(dp) :: fe(8), zero(8)
    type(element_eval_info_t) :: info
    integer :: e
    logical :: symmetric
    self%frame_tables = .false.
    symmetric = .true.
    if (self%table%element_dofs() /= 8 .or. .not. self%mass_constant_in_q) return
    do e = 1, size(self%el)
      if (.not. beam_linear_strain(self%el(e))) return
    end do
    call self%frame_mass%start(self%kd + 1, self%n, size(self%el))
    call self%frame_stiff%start(2*self%kd + 1, self%n, size(self%el))
    zero = 0.0_dp
    do e = 1, size(self%el)
      if (self%table%is_sleeve_element(e)) cycle
      ! phi = 0: the element-frame matrices (T = I)
      call beam_element_eval(self%el(e), zero, zero, rigid_state_t(), ml, fe, info, tangent=kl, force_wanted=.false.)
      call self%frame_mass%add_element(self%table, e, ml, self%kd, .true.)
      call self%frame_stiff%add_element(self%table, e, kl, self%kd, .false.)
      symmetric = symmetric .and. maxval(abs(kl - transpose(kl))) <= 1.0e-10_dp*maxval(abs(kl))
    end do
    call self%frame_mass%finish()
    call self%frame_stiff%finish()
    self%frame_symmetric = symmetric        ! T^T L T is symmetric at every angle when L is
    allocate(self%frame_basis(4, size(self%el)))
    self%frame_tables = .true.
  end subroutine build_frame_tables

  !> [cos phi, sin phi, cos 2phi, sin 2phi] of every element at the current rigid states.
  subroutine set_frame_basis(self)
    type(mechanism_model_t), intent(inout) :: self
    integer :: e
    do e = 1, size(self%el)
      self%frame_basis(:, e) = angle_basis(self%rb(e)%phi)
    end do
  end subroutine set_frame_basis

  !> Rigid-body states of all elements at time t (no-op for a fixed structure).
  subroutine set_time(self, t)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t) :: err
    integer :: e
    if (.not. self%moving) return
    ! DLSODE evaluates the RHS several times at one t (corrector iterations):
    ! the rigid motion is the same, so solve the kinematics once per time.
    if (.not. (t < self%t_states .or. t > self%t_states)) return   ! t equals t_states
    if (self%tabulated) then
      call tabulated_states(self, t)
      self%t_states = t
      call sliding_states(self)
      return
    end if
    call self%kin%solve(t, err)
    self%n_kinematics = self%n_kinematics + 1
    if (err%failed()) then
      call self%fail(t, 'rigid-body kinematics: '//err%text())
      return
    end if
    do e = 1, size(self%el)
      self%rb(e) = rigid_state(self%kin%element_motion_global(e))
    end do
    self%t_states = t
    call sliding_states(self)
  end subroutine set_time

  !> Frame states and sleeve maps of the sliding links at the current rigid states.
  subroutine sliding_states(self)
    type(mechanism_model_t), intent(inout) :: self
    integer :: k
    do k = 1, size(self%slide)
      call sliding_link_set_state(self%slide(k), self%table, self%rb, self%slide(k)%carrier_length)
    end do
  end subroutine sliding_states

  !> Element e's DOFs from the global vector q at the current time (a sleeve
  !> element's map depends on its link's angle).
  function element_q(self, e, q) result(qe)
    class(mechanism_model_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:)
    real(dp) :: qe(self%table%element_dofs())
    integer :: k
    do k = 1, size(self%slide)
      if (self%slide(k)%element /= e) cycle
      qe = sliding_link_element_q(self%slide(k), q)
      return
    end do
    qe = self%table%gather(e, q)
  end function element_q

  !> Tabulate the rigid-body motion of every element over one crank
  !> revolution at n_points equally spaced crank angles (module
  !> rigid_motion_table).  Fails (err) where the kinematics fails, naming the
  !> crank angle.
  subroutine build_motion_table(self, n_points, err)
    class(mechanism_model_t), intent(inout) :: self
    integer, intent(in) :: n_points
    type(error_t), intent(inout) :: err
    if (.not. self%moving) return
    call self%motion%build(self%kin, size(self%el), n_points, err)
    if (err%failed()) return
    if (allocated(self%work_motion)) deallocate(self%work_motion)
    allocate(self%work_motion(size(self%el)))
    self%tabulated = .true.
    self%t_states = -huge(1.0_dp)
    self%mass_factored = .false.            ! the table's rigid states differ from the solved ones by round-off
  end subroutine build_motion_table

  !> Rigid states at time t from the table.
  subroutine tabulated_states(self, t)
    type(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    integer :: e
    call self%motion%motion_at(self%kin%mech%driver, t, self%work_motion)
    do e = 1, size(self%el)
      self%rb(e) = rigid_state(self%work_motion(e))
    end do
  end subroutine tabulated_states

  !> An element's rigid state from its motion.
  pure function rigid_state(m) result(rb)
    type(motion_t), intent(in) :: m
    type(rigid_state_t) :: rb
    rb = rigid_state_t(m%x1, m%y1, m%phi, m%x1_d, m%y1_d, m%phi_d, m%x1_dd, m%y1_dd, m%phi_dd)
  end function rigid_state

  ! ------------------------------------------------------------------ equations of motion

  !> q_dd from M(q,t) q_dd = F(q, q_d, t).  Fails (self%err) when M is not
  !> positive definite or a strain passes the material's peak.  Unless the
  !> section angle of the rotary inertia is nonlinear (rotary inertia with
  !> exact curvature), M depends on the rigid state only: its factor is then
  !> kept while t is unchanged (DLSODE's corrector iterations), which is
  !> exact -- the same M, factored once.
  subroutine accelerations(self, t, q, qd, qdd)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out), contiguous :: qdd(:)
    type(element_eval_info_t) :: info
    integer :: e, kd, info_chol
    logical :: new_mass
    call self%set_time(t)
    qdd = 0.0_dp
    if (self%err%failed()) return
    kd = self%kd
    ! a sliding link's mass depends on where it slides (q): M is then formed every call
    new_mass = .not. self%mass_factored .or. t < self%t_mass .or. t > self%t_mass .or. &
               .not. self%mass_constant_in_q .or. size(self%slide) > 0
    if (new_mass) self%mass_band = 0.0_dp
    self%force = 0.0_dp
    associate(me => self%work_me, fe => self%work_fe, qe => self%work_qe, qde => self%work_qde)
    do e = 1, size(self%el)
      if (self%table%is_sleeve_element(e)) cycle        ! (add_sliding_links)
      call self%table%gather_pair(e, q, qd, qe, qde)
      call beam_element_eval(self%el(e), qe, qde, loaded_state(self, e), me, fe, info, &
                             mass_wanted=new_mass .and. .not. self%frame_tables, peak_wanted=.false.)
      self%n_nonlinear_points = self%n_nonlinear_points + info%n_nonlinear_points
      if (info%beyond_peak .and. self%stop_beyond_peak) then
        call self%fail(t, 'strain '//str(info%max_abs_strain, 6)//' in element '//str(e)//' (x/l = '// &
          str(info%x_over_l_max_strain, 3)//') is past the peak of the Ramberg-Osgood curve, eps* = '// &
          str(self%el(e)%eps_star, 6)//': the material law has no stable meaning beyond it')
        return
      end if
      call self%table%scatter_add(e, fe, self%force)
      if (new_mass .and. .not. self%frame_tables) call self%table%add_lower_band(e, me, self%mass_band)
    end do
    end associate
    if (new_mass .and. self%frame_tables) then       ! (nothing was added to mass_band yet)
      call set_frame_basis(self)
      call frame_matrix(self%frame_mass, self%frame_basis, self%mass_band)
    end if
    call add_point_masses(self, new_mass)
    call add_counterweights(self, q, new_mass)
    if (size(self%slide) > 0) call add_sliding_links(self, t, q, qd)
    if (self%err%failed()) return
    if (size(self%loads) > 0) call add_point_loads(self, t, q, self%force)
    if (self%has_clearance) call add_clearance_forces(self, q, qd)
    if (new_mass) then
      self%mass_factored = .false.
      call band_cholesky_inplace(self%mass_band, kd, info_chol)
      self%n_mass_factorizations = self%n_mass_factorizations + 1
      if (info_chol /= 0) then
        call self%fail(t, 'mass matrix: not positive definite (leading minor of order '//str(info_chol)// &
                       ' is not positive)')
        return
      end if
      self%mass_factored = .true.
      self%t_mass = t
    end if
    qdd = self%force
    call band_cholesky_substitute(self%mass_band, kd, qdd)
  end subroutine accelerations

  !> The sliding links' mass and generalized forces (module sliding_link).
  subroutine add_sliding_links(self, t, q, qd)
    type(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    type(tennant_info_t) :: info
    integer :: k
    do k = 1, size(self%slide)
      call sliding_link_add(self%slide(k), q, qd, self%gravity, self%kd, self%mass_band, self%force, &
                            self%n_nonlinear_points, info)
      if (info%beyond_peak .and. self%stop_beyond_peak) then
        call self%fail(t, 'strain '//str(info%max_abs_strain, 6)//' in sliding element '//str(self%slide(k)%element)// &
          ' is past the peak of the Ramberg-Osgood curve, eps* = '//str(self%slide(k)%el%eps_star, 6))
        return
      end if
    end do
  end subroutine add_sliding_links

  !> Dense (or, with kd >= 0, band) blocks of the sliding links: mass and
  !> elastic tangent stiffness at q.
  subroutine add_sliding_matrices(self, q, mass, stiff, kd)
    type(mechanism_model_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(inout) :: mass(:, :), stiff(:, :)
    integer, intent(in) :: kd
    real(dp) :: mg(10, 10), kg(10, 10)   ! (8 element DOFs + the sleeve's U_s, W_s)
    integer :: k, i, j, gi, gj
    do k = 1, size(self%slide)
      call sliding_link_matrices(self%slide(k), q, mg, kg)
      do j = 1, self%slide(k)%ng
        gj = self%slide(k)%glob(j)
        do i = 1, self%slide(k)%ng
          gi = self%slide(k)%glob(i)
          if (kd < 0) then
            mass(gi, gj) = mass(gi, gj) + mg(i, j)
            stiff(gi, gj) = stiff(gi, gj) + kg(i, j)
          else
            stiff(kd + 1 + gi - gj, gj) = stiff(kd + 1 + gi - gj, gj) + kg(i, j)
            if (gi >= gj) mass(1 + gi - gj, gj) = mass(1 + gi - gj, gj) + mg(i, j)
          end if
        end do
      end do
    end do
  end subroutine add_sliding_matrices

  !> Point masses: m on the diagonal of each translation they ride on, and
  !> the rigid-body inertia load -m a_rigid.
  subroutine add_point_masses(self, new_mass)
    type(mechanism_model_t), intent(inout) :: self
    logical, intent(in) :: new_mass
    integer :: k, i, g(2), e
    real(dp) :: c(2), a(2), m
    do k = 1, self%joint_mass%count()
      e = self%joint_mass%element(k)
      m = self%joint_mass%mass(k)
      call node_translation_dofs(self, e, self%joint_mass%node(k), g, c)
      a = node_acceleration(self%rb(e), self%el(e)%length, self%joint_mass%node(k)) - self%gravity
      do i = 1, 2
        if (g(i) == 0) cycle
        if (new_mass) self%mass_band(1, g(i)) = self%mass_band(1, g(i)) + m*c(i)**2
        self%force(g(i)) = self%force(g(i)) - m*c(i)*a(i)
      end do
    end do
  end subroutine add_point_masses

  !> Dense global mass matrix at (q, current time) and elastic tangent stiffness.
  subroutine assemble_dense(self, q, mass, stiff)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    real(dp), dimension(self%table%element_dofs(), self%table%element_dofs()) :: me, ke
    integer :: e, i, g(2)
    real(dp) :: c(2)
    mass = 0.0_dp
    stiff = 0.0_dp
    do e = 1, size(self%el)
      if (self%table%is_sleeve_element(e)) cycle
      call element_mass_stiffness(self, e, q, me, ke)
      call self%table%scatter_add_matrix(e, me, mass)
      call self%table%scatter_add_matrix(e, ke, stiff)
    end do
    call add_sliding_matrices(self, q, mass, stiff, -1)
    do e = 1, self%joint_mass%count()
      call node_translation_dofs(self, self%joint_mass%element(e), self%joint_mass%node(e), g, c)
      do i = 1, 2
        if (g(i) > 0) mass(g(i), g(i)) = mass(g(i), g(i)) + self%joint_mass%mass(e)*c(i)**2
      end do
    end do
    call add_counterweight_mass(self, mass, .false.)
  end subroutine assemble_dense

  !> Element e's mass matrix and elastic tangent stiffness (global element
  !> DOFs) at the global displacements q and the current rigid state.
  subroutine element_mass_stiffness(self, e, q, me, ke)
    type(mechanism_model_t), intent(inout) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: me(:, :), ke(:, :)
    type(element_eval_info_t) :: info
    self%work_qde = 0.0_dp
    self%work_qe = self%table%gather(e, q)
    call beam_element_eval(self%el(e), self%work_qe, self%work_qde, self%rb(e), me, self%work_fe, info, &
                           tangent=ke, force_wanted=.false.)   ! = beam_tangent_stiffness
  end subroutine element_mass_stiffness

  !> M (lower band storage, kd+1 rows) and K_t (general band storage,
  !> k(kd+1+i-j, j) = K(i, j), 2kd+1 rows) at (q, current time): O(N).
  subroutine assemble_band(self, q, mass, stiff)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    real(dp) :: c(2)
    integer :: e, i, kd, g(2)
    kd = self%kd
    mass = 0.0_dp
    stiff = 0.0_dp
    if (self%frame_tables) then
      call set_frame_basis(self)
      call frame_matrix(self%frame_mass, self%frame_basis, mass)
      call frame_matrix(self%frame_stiff, self%frame_basis, stiff)
    end if
    do e = 1, size(self%el)
      if (self%table%is_sleeve_element(e) .or. self%frame_tables) cycle
      call element_mass_stiffness(self, e, q, self%work_me, self%work_ke)
      call self%table%add_newton_bands(e, self%work_me, self%work_ke, kd, mass, stiff)
    end do
    call add_sliding_matrices(self, q, mass, stiff, kd)
    do e = 1, self%joint_mass%count()
      call node_translation_dofs(self, self%joint_mass%element(e), self%joint_mass%node(e), g, c)
      do i = 1, 2
        if (g(i) > 0) mass(1, g(i)) = mass(1, g(i)) + self%joint_mass%mass(e)*c(i)**2
      end do
    end do
    call add_counterweight_mass(self, mass, .true.)
  end subroutine assemble_band

  ! ------------------------------------------------------------------ Newton matrix

  !> DLSODE's Newton matrix (second_order_model): M and K_t, the clearance
  !> contacts as pair dampers (add_clearance_terms) and, from the frame
  !> tables, the symmetry of K_t (the check costs a fifth of a factorization).
  subroutine model_newton_factor(self, t, y, hl0, ok)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:), hl0
    logical, intent(out) :: ok
    real(dp) :: beta
    call self%newton_fill(t, y, ok)
    if (.not. ok) return
    beta = self%damping_beta()
    if (self%has_clearance) call add_clearance_terms(self, y, beta)
    if (self%frame_tables .and. .not. self%has_clearance .and. size(self%slide) == 0) then
      call self%newton%factor(hl0, beta, ok, self%frame_symmetric)
    else
      call self%newton%factor(hl0, beta, ok)
    end if
  end subroutine model_newton_factor

  !> The elements' stiffness-proportional damping coefficient (one for all).
  real(dp) function damping_beta(self) result(beta)
    class(mechanism_model_t), intent(in) :: self
    beta = 0.0_dp
    if (size(self%el) > 0) beta = self%el(1)%beta
  end function damping_beta

  !> The driver's crank angle (rad) at time t.
  real(dp) function crank_angle(self, t) result(theta)
    class(mechanism_model_t), intent(in) :: self
    real(dp), intent(in) :: t
    real(dp) :: theta_d, theta_dd
    call driver_angle(self%kin%mech%driver, t, theta, theta_d, theta_dd)
  end function crank_angle

  !> A moving mechanism's M and K_t turn with the links, and the chord
  !> iteration's contraction factor with a Newton matrix k steps old grows as
  !> k and, from 8 elements per link on, as the number of elements (0.05 at
  !> 2 elements per link after four steps of 35 us, 0.33 at 32;
  !> doc/transient.md).  DLSODE's fixed limit of 20 steps per matrix made most
  !> Jacobians at 32 elements per link retries after a failed iteration; a
  !> fixed 5 still let the iteration fail at 32.  So the age limit adapts: at
  !> most `newton_age_limit` steps, fewer when the measured contraction would
  !> pass `newton_contraction` (ode_system_t's jacobian_steps and
  !> jacobian_contraction, module lsode_newton).  A longer limit (10) saves
  !> matrices on coarse meshes but costs 8-17 % more steps with the rates in
  !> the error test (atol_rate = atol, the deck default).  A structure that
  !> does not turn keeps DLSODE's 20.
  subroutine set_newton_ageing(self, turning)
    type(mechanism_model_t), intent(inout) :: self
    logical, intent(in) :: turning
    self%jacobian_steps = merge(newton_age_limit, 0, turning)
    self%jacobian_contraction = merge(newton_contraction, 0.0_dp, turning)
  end subroutine set_newton_ageing

  ! ------------------------------------------------------------------ clearance joints

  !> Give every joint in `joints` its clearance: the journal's translations
  !> become their own unknowns (joint_clearance%split_journal) and the
  !> contact force acts between journal and bearing.  init_mechanism's last
  !> step; the work arrays follow the new size and band.
  subroutine add_clearance(self, joints, err)
    class(mechanism_model_t), intent(inout) :: self
    type(clearance_joint_t), intent(in) :: joints(:)
    type(error_t), intent(inout) :: err
    integer :: k, m, p
    if (size(joints) == 0) return
    if (size(self%slide) > 0) then
      ! (split_journal renumbers the map, not a sleeve element's own globals)
      call err%set('clearance', 'joint clearances are not modelled in a mechanism with a link sliding '// &
                   'through a sleeve (slider_link)', 2)
      return
    end if
    self%clearance = joints
    do k = 1, size(joints)
      call split_journal(self%table, self%clearance(k)%element_journal, self%clearance(k)%journal_node, &
                         self%clearance(k), err)
      if (err%failed()) return
      p = self%clearance(k)%journal(1) - 1
      do m = 1, k - 1
        where (self%clearance(m)%bearing > p) self%clearance(m)%bearing = self%clearance(m)%bearing + 2
        where (self%clearance(m)%journal > p) self%clearance(m)%journal = self%clearance(m)%journal + 2
      end do
    end do
    do k = 1, self%cw%count()
      ! a counterweight turns about a fixed pivot (register_counterweights)
      if (any(self%table%unknowns_of([1, 2], self%cw%element(k)) > 0)) then
        call err%set('clearance', 'a joint clearance at a counterweight''s pivot is not modelled (the '// &
                     'counterweight turns about a fixed pivot)', 2)
        return
      end if
    end do
    call allocate_work(self)
    allocate(self%newton%damper(2, 2, size(joints)), self%newton%damper_dofs(4, size(joints)))
    do k = 1, size(joints)
      self%newton%damper_dofs(:, k) = pair_dofs(self%clearance(k))
    end do
    self%has_clearance = .true.
  end subroutine add_clearance

  !> Rigid rotation rate of clearance joint k's journal link minus its
  !> bearing's (the rotational part of the sliding speed).
  pure real(dp) function clearance_spin(self, k) result(spin)
    class(mechanism_model_t), intent(in) :: self
    integer, intent(in) :: k
    spin = 0.0_dp
    if (self%clearance(k)%element_journal > 0) spin = self%rb(self%clearance(k)%element_journal)%phi_d
    if (self%clearance(k)%element_bearing > 0) spin = spin - self%rb(self%clearance(k)%element_bearing)%phi_d
  end function clearance_spin

  !> Contact forces of the clearance joints; with friction and a journal
  !> radius r, the friction force F_t acting on the pin's surface also turns
  !> each link end: r F_t on the journal's, -r F_t on the bearing's (moments
  !> working through the section angle, like a point load's).
  subroutine add_clearance_forces(self, q, qd)
    type(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:), qd(:)
    integer :: k
    real(dp) :: fn, ft, moment
    do k = 1, size(self%clearance)
      associate (cj => self%clearance(k))
        call add_contact_forces(cj, q, qd, self%clearance_spin(k), self%force, fn, ft)
        if (.not. (cj%journal_radius > 0.0_dp .and. abs(ft) > 0.0_dp)) cycle
        moment = cj%journal_radius*ft
        call add_end_moment(self, cj%element_journal, cj%journal_node, q, moment)
        if (cj%element_bearing > 0) call add_end_moment(self, cj%element_bearing, cj%bearing_node, q, -moment)
      end associate
    end do
  end subroutine add_clearance_forces

  !> force += generalized force of a moment at node `node` of element e.
  subroutine add_end_moment(self, e, node, q, moment)
    type(mechanism_model_t), intent(inout) :: self
    integer, intent(in) :: e, node
    real(dp), intent(in) :: q(:), moment
    real(dp) :: gen(self%table%element_dofs())
    call beam_point_load(self%el(e), self%table%gather(e, q), self%rb(e)%phi, real(node - 1, dp), [0.0_dp, 0.0_dp], &
                         moment, gen)
    call self%table%scatter_add(e, gen, self%force)
  end subroutine add_end_moment

  !> Contact stiffness into K_t of the Newton matrix; the contact damps by its
  !> own C, not in proportion to K (with the elements' beta): it enters as the
  !> Newton matrix's pair damper C - beta K.
  subroutine add_clearance_terms(self, y, beta)
    type(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: y(:), beta
    real(dp) :: kc(2, 2), cc(2, 2)
    integer :: k
    do k = 1, size(self%clearance)
      call contact_blocks(self%clearance(k), y(1::2), y(2::2), self%clearance_spin(k), kc, cc)
      call add_pair_block(self%clearance(k), kc, 1.0_dp, self%newton%stiff, self%kd + 1, .false.)
      self%newton%damper(:, :, k) = cc - beta*kc
    end do
  end subroutine add_clearance_terms

  !> Natural frequencies (rad/s, ascending) and M-normalised mode shapes of
  !> the linearised structure at the current rigid position: K_t(q=0) x = w^2 M x.
  subroutine linear_modes(self, omega, shapes, err)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(out) :: omega(:)
    real(dp), intent(out) :: shapes(:, :)
    type(error_t), intent(inout) :: err
    real(dp) :: mass(self%n, self%n), stiff(self%n, self%n), q0(self%n)
    q0 = 0.0_dp
    call self%assemble_dense(q0, mass, stiff)
    call sym_generalized_eig(stiff, mass, omega, err, shapes)
    if (err%failed()) return
    omega = sign(sqrt(abs(omega)), omega)
  end subroutine linear_modes

  !> Kinetic energy of the elastic-plus-rigid motion and strain energy, summed
  !> over elements, at time t.
  subroutine energies(self, t, q, qd, kinetic, strain)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, q(:), qd(:)
    real(dp), intent(out) :: kinetic, strain
    integer :: e
    real(dp) :: qe(self%table%element_dofs()), ke_s, se_s
    call self%set_time(t)
    kinetic = 0.0_dp
    strain = 0.0_dp
    do e = 1, size(self%slide)
      call sliding_link_energies(self%slide(e), q, qd, ke_s, se_s)
      kinetic = kinetic + ke_s
      strain = strain + se_s
    end do
    do e = 1, size(self%el)
      if (self%table%is_sleeve_element(e)) cycle
      qe = self%table%gather(e, q)
      kinetic = kinetic + beam_kinetic_energy(self%el(e), qe, self%table%gather(e, qd), self%rb(e))
      strain = strain + beam_strain_energy(self%el(e), qe, self%rb(e)%phi)
    end do
    do e = 1, self%joint_mass%count()
      block
        integer :: g(2), i
        real(dp) :: c(2), v(2), cph, sph
        type(rigid_state_t) :: r
        call node_translation_dofs(self, self%joint_mass%element(e), self%joint_mass%node(e), g, c)
        r = self%rb(self%joint_mass%element(e))
        v = [r%x1_d, r%y1_d]
        if (self%joint_mass%node(e) == 2) then
          cph = cos(r%phi)
          sph = sin(r%phi)
          v = v + self%el(self%joint_mass%element(e))%length*r%phi_d*[-sph, cph]
        end if
        do i = 1, 2
          if (g(i) > 0) v(i) = v(i) + c(i)*qd(g(i))
        end do
        kinetic = kinetic + 0.5_dp*self%joint_mass%mass(e)*sum(v**2)
      end block
    end do
  end subroutine energies

  !> Stress report of every element for the global displacements q (rigid
  !> states must be current: call set_time first).
  subroutine element_stresses(self, q, reports)
    class(mechanism_model_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    type(stress_report_t), intent(out) :: reports(:)
    integer :: e
    do e = 1, size(self%el)
      if (self%table%is_sleeve_element(e)) cycle
      reports(e) = beam_stress_recovery(self%el(e), self%table%gather(e, q), self%rb(e)%phi)
    end do
    do e = 1, size(self%slide)
      reports(self%slide(e)%element) = sliding_link_stress(self%slide(e), q)
    end do
  end subroutine element_stresses

  ! ------------------------------------------------------------------ external loads

  !> Gravity (global acceleration vector) and point loads (already resolved
  !> to elements, src/model/external_loads.f90).
  subroutine set_loads(self, gravity, point_loads)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: gravity(2)
    type(point_load_t), intent(in) :: point_loads(:)
    self%gravity = gravity
    self%loads = point_loads
  end subroutine set_loads

  !> Rigid state of element e as the element sees it: gravity g acts on every
  !> mass like a frame acceleration -g (rho A int B^T g = -rho A int B^T (-g)).
  pure function loaded_state(self, e) result(rb)
    type(mechanism_model_t), intent(in) :: self
    integer, intent(in) :: e
    type(rigid_state_t) :: rb
    rb = self%rb(e)
    rb%x1_dd = rb%x1_dd - self%gravity(1)
    rb%y1_dd = rb%y1_dd - self%gravity(2)
  end function loaded_state

  !> f += generalized forces of the point loads at time t (times load_scale);
  !> optionally jac += their Jacobian d/dq (moments work through the section angle).
  subroutine add_point_loads(self, t, q, f, jac)
    type(mechanism_model_t), intent(in) :: self
    real(dp), intent(in) :: t, q(:)
    real(dp), intent(inout) :: f(:)
    real(dp), intent(inout), optional :: jac(:, :)
    real(dp) :: gen(self%table%element_dofs()), dgen(self%table%element_dofs(), self%table%element_dofs()), fac
    integer :: k, e
    do k = 1, size(self%loads)
      e = self%loads(k)%element
      fac = self%load_scale*load_factor_at(self%loads(k), t)
      call beam_point_load(self%el(e), self%table%gather(e, q), self%rb(e)%phi, self%loads(k)%x_over_l, &
                           fac*self%loads(k)%force, fac*self%loads(k)%moment, gen, dgen)
      call self%table%scatter_add(e, gen, f)
      if (present(jac)) call self%table%scatter_add_matrix(e, dgen, jac)
    end do
  end subroutine add_point_loads

  !> Static equilibrium of a structure at rest (init_fixed) under its loads
  !> at time t: F(q, 0, t) + Q(q, t) = 0, by Newton's method with the tangent
  !> -K_t + dQ/dq, the point loads applied in n_steps equal increments
  !> (natural-parameter continuation).  q holds the start and the result.
  subroutine static_equilibrium(self, t, q, n_steps, err, iterations)
    class(mechanism_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    real(dp), intent(inout) :: q(:)
    integer, intent(in) :: n_steps
    type(error_t), intent(inout) :: err
    integer, intent(out), optional :: iterations
    real(dp) :: r(self%n), jac(self%n, self%n), mass(self%n, self%n), zero(self%n), qdd(self%n), scratch(self%n)
    real(dp) :: scale0
    integer :: step, it, n_it
    logical :: converged
    scale0 = self%load_scale
    zero = 0.0_dp
    n_it = 0
    do step = 1, n_steps
      self%load_scale = scale0*real(step, dp)/real(n_steps, dp)
      converged = .false.
      do it = 1, 50
        n_it = n_it + 1
        call self%accelerations(t, q, zero, qdd)      ! fills self%force = F + Q
        if (self%err%failed()) then
          err = self%err
          exit
        end if
        r = self%force
        call self%assemble_dense(q, mass, jac)
        jac = -jac
        scratch = 0.0_dp
        call add_point_loads(self, t, q, scratch, jac)
        call solve_linear(jac, r, err)                ! r := J^-1 R
        if (err%failed()) exit
        q = q - r
        if (maxval(abs(r)) <= 1.0e-12_dp*max(1.0_dp, maxval(abs(q)))) then
          converged = .true.
          exit
        end if
      end do
      if (err%failed()) exit
      if (.not. converged) then
        call err%set('static equilibrium', 'Newton did not converge at load step '//str(step)//' of '// &
                     str(n_steps)//'; use more steps')
        exit
      end if
    end do
    self%load_scale = scale0
    if (present(iterations)) iterations = n_it
  end subroutine static_equilibrium

  ! ------------------------------------------------------------------ joint forces

  !> The generalized force that the rest of the mechanism (its joints and
  !> neighbours) exerts on element e, in the element's global DOFs:
  !>     r_e = M_e q_dd_e - F_e(q, q_d, t) - Q_e(q, t)
  !> (F_e: elastic, damping, rigid-body inertia and gravity loads; Q_e: the
  !> point loads on e).  Its node-translation rows are the global X, Y forces
  !> on the element's ends, its slope rows the moments (src/model/joint_reactions.f90).
  !> The rigid states must be current (set_time(t)); q, qd, qdd global.
  subroutine element_joint_force(self, e, t, q, qd, qdd, r)
    class(mechanism_model_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: t, q(:), qd(:), qdd(:)
    real(dp), intent(out) :: r(:)
    real(dp) :: me(self%table%element_dofs(), self%table%element_dofs()), fe(self%table%element_dofs()), qe(size(r))
    real(dp) :: gen(self%table%element_dofs()), dgen(self%table%element_dofs(), self%table%element_dofs()), fac
    type(element_eval_info_t) :: info
    integer :: k
    qe = self%table%gather(e, q)
    call beam_element_eval(self%el(e), qe, self%table%gather(e, qd), loaded_state(self, e), me, fe, info)
    r = matmul(me, self%table%gather(e, qdd)) - fe
    do k = 1, size(self%loads)
      if (self%loads(k)%element /= e) cycle
      fac = self%load_scale*load_factor_at(self%loads(k), t)
      call beam_point_load(self%el(e), qe, self%rb(e)%phi, self%loads(k)%x_over_l, fac*self%loads(k)%force, &
                           fac*self%loads(k)%moment, gen, dgen)
      r = r - gen
    end do
  end subroutine element_joint_force
end module mechanism_model
