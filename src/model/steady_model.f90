!> The flexible linkage of a steady-state analysis as a periodic system:
!> rigid-body kinematics (module kinematics), one Tennant element per link
!> segment, assembled through the variable correlation table of module
!> correlation_table into dense global M(t), C(t), K_e(t), F(t) and the
!> nonlinear force f_n(Q, t) of (T25).
!>
!> Most element DOFs equal one global unknown times a constant (pins, clamps,
!> guides); they are scattered directly.  The end of a link sliding through a
!> sleeve depends on the link angle, q_e = C(t) Q, and is assembled by virtual
!> work with q_e_d = C Q_d + C_d Q, q_e_dd = C Q_dd + 2 C_d Q_d + C_dd Q:
!>   M += C^T M_e C,  C += C^T (C_e C + 2 M_e C_d),  K += C^T (K_e C + C_e C_d + M_e C_dd).
module steady_model
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use linkage, only: mechanism_t
  use lumped_masses, only: joint_masses_t, counterweights_t, place_joint_masses, place_counterweights
  use kinematics, only: kinematics_t, motion_t
  use material_law, only: ramberg_osgood_t
  use tennant_element, only: tennant_element_t, tennant_options_t, tennant_section_t, frame_state_t, tennant_info_t, &
                             tennant_stress_t, tennant_element_init, tennant_linear_terms, tennant_nonlinear_terms, &
                             tennant_stress_recovery, tennant_local_field, tennant_max_sections, tennant_max_dof
  use correlation_table, only: correlation_table_t, link_end_t
  use linkage_model_setup, only: start_linkage_model
  use periodic_system, only: periodic_system_t, nonlinear_info_t
  use linalg, only: sym_generalized_eig
  implicit none
  private
  public :: steady_model_t, link_sections_t

  integer, parameter :: mx = tennant_max_dof + 2
  integer, parameter :: n_cache = 256                 !< frame states remembered (distinct times)
  real(dp), parameter :: deg = atan(1.0_dp)/45.0_dp
  real(dp), parameter :: max_kin_jump = 30.0_dp*deg   !< largest crank step tried in one kinematics solution
  real(dp), parameter :: kin_substep = 5.0_dp*deg     !< steps of the retry after a failed jump

  !> Sections of one link, as fractions of its length (T §3.4).
  type :: link_sections_t
    integer :: n = 0                     !< 0: one uniform section (link_b, link_h)
    real(dp) :: f1(tennant_max_sections) = 0.0_dp   !< end of section k (fraction of the link); start = end of k-1
    real(dp) :: b(tennant_max_sections) = 0.0_dp
    real(dp) :: h(tennant_max_sections) = 0.0_dp
  end type link_sections_t

  type, extends(periodic_system_t) :: steady_model_t
    logical :: moving = .true.
    type(kinematics_t) :: kin
    type(correlation_table_t) :: table
    type(tennant_element_t), allocatable :: el(:)
    type(frame_state_t), allocatable :: fs(:)
    real(dp) :: t_states = -huge(1.0_dp)
    real(dp), allocatable :: cm(:, :, :), cmd(:, :, :), cmdd(:, :, :)   !< maps of sleeve elements
    integer, allocatable :: ng(:)
    integer :: n_kinematics = 0
    logical :: nonlinear = .false.
    ! frame states of recently visited times (the solvers revisit the sample times)
    integer :: cache_used = 0, cache_next = 1
    real(dp) :: cache_t(n_cache) = 0.0_dp
    type(frame_state_t), allocatable :: cache_fs(:, :)
    real(dp) :: t_kin = 0.0_dp                           !< time of the last kinematics solution
    type(counterweights_t) :: cw                         !< counterweights (module lumped_masses)
    !> a model of the same geometry, joints, driver and speed (one that
    !> differs only in sections or masses) whose rigid-body frames this one
    !> takes at each time instead of solving its own kinematics
    type(steady_model_t), pointer :: frames_of => null()
  contains
    procedure :: init_mechanism
    procedure :: init_fixed
    procedure :: set_time => model_set_time
    procedure :: linear_terms => model_linear_terms
    procedure :: nonlinear_terms => model_nonlinear_terms
    procedure :: is_nonlinear => model_is_nonlinear
    procedure :: element_q
    procedure :: stresses
    procedure :: local_field
    procedure :: frozen_frequencies
  end type steady_model_t

contains

  ! ------------------------------------------------------------------ set-up

  !> The model of a linkage: table from the joints, kinematics, elements.
  subroutine init_mechanism(self, mech, opt, sections, err)
    class(steady_model_t), intent(out) :: self
    type(mechanism_t), intent(in) :: mech
    type(tennant_options_t), intent(in) :: opt
    type(link_sections_t), intent(in) :: sections(:)
    type(error_t), intent(inout) :: err
    type(motion_t) :: m
    type(tennant_section_t), allocatable :: es(:)
    real(dp) :: masses(2)
    type(joint_masses_t) :: pm
    integer :: k, e, i

    self%moving = .true.
    call start_linkage_model(mech, self%table, self%kin, err, shear_dofs=opt%shear)
    if (err%failed()) return
    self%omega = mech%driver%omega

    allocate(self%el(self%table%n_elements()), self%fs(self%table%n_elements()))
    call place_joint_masses(mech, pm)
    do k = 1, mech%n_links
      associate (lk => mech%links(k))
        do i = 1, lk%n_elements
          e = lk%first_element + i - 1
          m = self%kin%element_motion_global(e)
          call element_sections(sections(k), lk%b, lk%h, i, lk%n_elements, es, err)
          if (err%failed()) then
            call err%add_context('link '''//trim(lk%name)//'''')
            return
          end if
          masses(1) = pm%mass_at(e, 1)
          masses(2) = pm%mass_at(e, 2)
          call tennant_element_init(self%el(e), m%length, es, ramberg_osgood_t(lk%e1, lk%e2, lk%m, lk%rho), opt, &
                                    err, node_mass=masses, sliding=lk%sliding, fibre_ratio=lk%fibre/(0.5_dp*lk%h))
          if (err%failed()) then
            call err%add_context('link '''//trim(lk%name)//''' element '//str(e))
            return
          end if
        end do
      end associate
    end do
    call finish_init(self)
    ! a counterweight on an arm clamped to the link at its ground pivot
    ! turns with the end's angle phi + w_x: kinetic energy J (phi_d + w_x_d)^2 / 2
    call place_counterweights(mech, self%cw, err)
    if (err%failed()) return
    self%t_kin = 0.0_dp
    call self%set_time(0.0_dp, err)
  end subroutine init_mechanism

  !> A structure at rest with given element frames (verification tests).
  subroutine init_fixed(self, lengths, sections, materials, states, n_elem, ends, opt, err)
    class(steady_model_t), intent(out) :: self
    real(dp), intent(in) :: lengths(:)
    type(tennant_section_t), intent(in) :: sections(:)
    type(ramberg_osgood_t), intent(in) :: materials(:)
    type(frame_state_t), intent(in) :: states(:)
    integer, intent(in) :: n_elem(:)
    type(link_end_t), intent(in) :: ends(:, :)
    type(tennant_options_t), intent(in) :: opt
    type(error_t), intent(inout) :: err
    integer :: e
    self%moving = .false.
    call self%table%build(n_elem, ends, err, shear_dofs=opt%shear)
    if (err%failed()) return
    allocate(self%el(self%table%n_elements()))
    self%fs = states
    do e = 1, self%table%n_elements()
      call tennant_element_init(self%el(e), lengths(e), sections, materials(e), opt, err)
      if (err%failed()) return
    end do
    call finish_init(self)
    self%t_states = 0.0_dp
    call refresh_maps(self)
  end subroutine init_fixed

  subroutine finish_init(self)
    type(steady_model_t), intent(inout) :: self
    integer :: ne
    self%n = self%table%n_unknowns()
    ne = self%table%n_elements()
    allocate(self%cm(mx, mx, ne), self%cmd(mx, mx, ne), self%cmdd(mx, mx, ne), self%ng(ne))
    self%cm = 0.0_dp
    self%cmd = 0.0_dp
    self%cmdd = 0.0_dp
    self%ng = 0
    self%nonlinear = any(self%el%nonlinear)
    allocate(self%cache_fs(ne, n_cache))
  end subroutine finish_init


  !> Sections of element i of n of a link, in the element's own fractions.
  subroutine element_sections(ls, b, h, i, n, es, err)
    type(link_sections_t), intent(in) :: ls
    real(dp), intent(in) :: b, h
    integer, intent(in) :: i, n
    type(tennant_section_t), allocatable, intent(out) :: es(:)
    type(error_t), intent(inout) :: err
    real(dp) :: f0, f1, s0, s1, a, z
    integer :: k
    if (ls%n == 0) then
      es = [tennant_section_t(0.0_dp, 1.0_dp, b, h)]
      return
    end if
    f0 = real(i - 1, dp)/n
    f1 = real(i, dp)/n
    allocate(es(0))
    s0 = 0.0_dp
    do k = 1, ls%n
      s1 = ls%f1(k)
      a = max(s0, f0)
      z = min(s1, f1)
      if (z - a > 1.0e-12_dp) es = [es, tennant_section_t((a - f0)/(f1 - f0), (z - f0)/(f1 - f0), ls%b(k), ls%h(k))]
      s0 = s1
    end do
    if (size(es) > tennant_max_sections) then
      call err%set('sections', 'element '//str(i)//' would hold '//str(size(es))//' sections (at most '// &
                   str(tennant_max_sections)//')')
      return
    end if
    es(1)%e0 = 0.0_dp
    es(size(es))%e1 = 1.0_dp
  end subroutine element_sections

  ! ------------------------------------------------------------------ time

  !> Rigid-body state at time t.  The crank turns at constant speed, so the
  !> motion is periodic: the kinematics is solved at the equivalent time
  !> t + k T nearest the last solution, in one jump of at most 30 deg of
  !> crank (Newton's warm start, doc/kinematics.md) or, if that fails (a far
  !> predictor can land on the other branch), again from the last solution in
  !> steps of 5 deg; states of recently visited times are reused.
  recursive subroutine model_set_time(self, t, err)
    class(steady_model_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t), intent(inout) :: err
    integer :: e, i, n_steps
    real(dp) :: period, te, t0, dt_max, tol
    if (.not. self%moving) return
    tol = 1.0e-12_dp*self%period()         ! times that differ by round-off are the same time
    if (abs(t - self%t_states) <= tol) return
    if (associated(self%frames_of)) then
      call self%frames_of%set_time(t, err)
      if (err%failed()) return
      self%fs = self%frames_of%fs
      self%t_states = t
      call refresh_maps(self)
      return
    end if
    do i = 1, self%cache_used
      if (abs(t - self%cache_t(i)) <= tol) then
        self%fs = self%cache_fs(:, i)
        self%t_states = t
        call refresh_maps(self)
        return
      end if
    end do
    period = self%period()
    te = t + period*anint((self%t_kin - t)/period)
    t0 = self%t_kin
    dt_max = max_kin_jump/self%omega
    n_steps = max(1, ceiling(abs(te - t0)/dt_max))
    call march(n_steps, err)
    if (err%failed()) then
      call err%clear()
      call march(max(1, ceiling(abs(te - t0)*self%omega/kin_substep)), err)
      if (err%failed()) return
    end if
    self%t_kin = te
    do e = 1, size(self%el)
      self%fs(e) = self%kin%element_motion_global(e)
    end do
    self%t_states = t
    call refresh_maps(self)
    self%cache_t(self%cache_next) = t
    self%cache_fs(:, self%cache_next) = self%fs
    self%cache_used = max(self%cache_used, self%cache_next)
    self%cache_next = mod(self%cache_next, n_cache) + 1
  contains
    subroutine march(n, e_)
      integer, intent(in) :: n
      type(error_t), intent(inout) :: e_
      integer :: k
      do k = 1, n
        call self%kin%solve(t0 + (te - t0)*real(k, dp)/n, e_)
        self%n_kinematics = self%n_kinematics + 1
        if (e_%failed()) return
      end do
    end subroutine march
  end subroutine model_set_time

  subroutine refresh_maps(self)
    type(steady_model_t), intent(inout) :: self
    integer :: e
    do e = 1, size(self%el)
      if (.not. self%table%is_sleeve_element(e)) cycle
      call self%table%element_map(e, self%fs(e)%phi, self%fs(e)%phi_d, self%fs(e)%phi_dd, self%ng(e), &
                                  self%cm(:, :, e), self%cmd(:, :, e), self%cmdd(:, :, e))
    end do
  end subroutine refresh_maps

  ! ------------------------------------------------------------------ assembly

  subroutine model_linear_terms(self, mass, damp, stiff, force, velocity_terms)
    class(steady_model_t), intent(inout) :: self
    real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: velocity_terms
    real(dp) :: me(tennant_max_dof, tennant_max_dof), ce(tennant_max_dof, tennant_max_dof)
    real(dp) :: ke(tennant_max_dof, tennant_max_dof), fe(tennant_max_dof)
    integer :: e, nd
    self%n_linear_evaluations = self%n_linear_evaluations + 1
    mass = 0.0_dp
    damp = 0.0_dp
    stiff = 0.0_dp
    force = 0.0_dp
    do e = 1, size(self%el)
      nd = self%el(e)%nd
      call tennant_linear_terms(self%el(e), self%fs(e), me, ce, ke, fe, velocity_terms)
      if (self%table%is_sleeve_element(e)) then
        call sleeve_assembly(self, e, nd, me, ce, ke, fe, mass, damp, stiff, force, velocity_terms)
      else
        call self%table%scatter_add_matrix(e, me, mass)
        if (velocity_terms) call self%table%scatter_add_matrix(e, ce, damp)
        call self%table%scatter_add_matrix(e, ke, stiff)
        call self%table%scatter_add(e, fe, force)
      end if
    end do
    if (self%cw%count() > 0) call add_counterweights(self, mass, force)
  end subroutine model_linear_terms

  !> Lagrange's equation of the end slope w_x of a counterweight's link gets
  !> J w_x_dd on the left and -J phi_dd (the rigid rotation's inertia) on the
  !> right; the counterweight's translation reaches the ground pivot directly.
  subroutine add_counterweights(self, mass, force)
    type(steady_model_t), intent(in) :: self
    real(dp), intent(inout) :: mass(:, :), force(:)
    real(dp) :: me(tennant_max_dof, tennant_max_dof), fe(tennant_max_dof)
    integer :: k, e
    do k = 1, self%cw%count()
      e = self%cw%element(k)
      me = 0.0_dp
      fe = 0.0_dp
      me(3, 3) = self%cw%inertia(k)
      fe(3) = -self%cw%inertia(k)*self%fs(e)%phi_dd
      call self%table%scatter_add_matrix(e, me, mass)
      call self%table%scatter_add(e, fe, force)
    end do
  end subroutine add_counterweights


  subroutine sleeve_assembly(self, e, nd, me, ce, ke, fe, mass, damp, stiff, force, velocity_terms)
    type(steady_model_t), intent(in) :: self
    integer, intent(in) :: e, nd
    real(dp), intent(in) :: me(:, :), ce(:, :), ke(:, :), fe(:)
    real(dp), intent(inout) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: velocity_terms
    integer :: ng
    integer :: g(mx)
    ng = self%ng(e)
    g(1:ng) = self%table%globals_of(e)
    associate (c0 => self%cm(1:nd, 1:ng, e), c1 => self%cmd(1:nd, 1:ng, e), c2 => self%cmdd(1:nd, 1:ng, e), &
               m => me(1:nd, 1:nd), c => ce(1:nd, 1:nd), k => ke(1:nd, 1:nd))
      mass(g(1:ng), g(1:ng)) = mass(g(1:ng), g(1:ng)) + matmul(transpose(c0), matmul(m, c0))
      if (velocity_terms) damp(g(1:ng), g(1:ng)) = damp(g(1:ng), g(1:ng)) + &
                                                   matmul(transpose(c0), matmul(c, c0) + 2.0_dp*matmul(m, c1))
      stiff(g(1:ng), g(1:ng)) = stiff(g(1:ng), g(1:ng)) + matmul(transpose(c0), matmul(k, c0) + matmul(c, c1) &
                                                                 + matmul(m, c2))
      force(g(1:ng)) = force(g(1:ng)) + matmul(transpose(c0), fe(1:nd))
    end associate
  end subroutine sleeve_assembly

  !> Element DOF vector of element e from the global vector (current time).
  function element_q(self, e, q) result(qe)
    class(steady_model_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:)
    real(dp) :: qe(self%el(e)%nd)
    integer :: ng
    if (self%table%is_sleeve_element(e)) then
      ng = self%ng(e)
      qe = matmul(self%cm(1:self%el(e)%nd, 1:ng, e), q(self%table%globals_of(e)))
    else
      qe = self%table%gather(e, q)
    end if
  end function element_q

  subroutine model_nonlinear_terms(self, q, fn, info, secant, tangent)
    class(steady_model_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: fn(:)
    type(nonlinear_info_t), intent(out) :: info
    real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    real(dp) :: fe(tennant_max_dof), ks(tennant_max_dof, tennant_max_dof), kt(tennant_max_dof, tennant_max_dof)
    type(tennant_info_t) :: ei
    integer :: e, nd, ng
    integer :: g(mx)
    fn = 0.0_dp
    if (present(secant)) secant = 0.0_dp
    if (present(tangent)) tangent = 0.0_dp
    if (.not. self%nonlinear) return
    self%n_nonlinear_evaluations = self%n_nonlinear_evaluations + 1
    do e = 1, size(self%el)
      if (.not. self%el(e)%nonlinear) cycle
      nd = self%el(e)%nd
      if (present(secant) .and. present(tangent)) then
        call tennant_nonlinear_terms(self%el(e), self%element_q(e, q), self%fs(e), fe, ei, secant=ks, tangent=kt)
      else if (present(secant)) then
        call tennant_nonlinear_terms(self%el(e), self%element_q(e, q), self%fs(e), fe, ei, secant=ks)
      else if (present(tangent)) then
        call tennant_nonlinear_terms(self%el(e), self%element_q(e, q), self%fs(e), fe, ei, tangent=kt)
      else
        call tennant_nonlinear_terms(self%el(e), self%element_q(e, q), self%fs(e), fe, ei)
      end if
      info%n_points = info%n_points + ei%n_points
      if (ei%max_abs_strain > info%max_abs_strain) then
        info%max_abs_strain = ei%max_abs_strain
        info%element = e
      end if
      info%beyond_peak = info%beyond_peak .or. ei%beyond_peak
      if (self%table%is_sleeve_element(e)) then
        ng = self%ng(e)
        g(1:ng) = self%table%globals_of(e)
        associate (c0 => self%cm(1:nd, 1:ng, e), gg => g(1:ng))
          fn(gg) = fn(gg) + matmul(transpose(c0), fe(1:nd))
          if (present(secant)) secant(gg, gg) = secant(gg, gg) + matmul(transpose(c0), matmul(ks(1:nd, 1:nd), c0))
          if (present(tangent)) tangent(gg, gg) = tangent(gg, gg) + matmul(transpose(c0), matmul(kt(1:nd, 1:nd), c0))
        end associate
      else
        call self%table%scatter_add(e, fe, fn)
        if (present(secant)) call self%table%scatter_add_matrix(e, ks, secant)
        if (present(tangent)) call self%table%scatter_add_matrix(e, kt, tangent)
      end if
    end do
    self%n_nonlinear_points = self%n_nonlinear_points + info%n_points
  end subroutine model_nonlinear_terms

  logical function model_is_nonlinear(self)
    class(steady_model_t), intent(in) :: self
    model_is_nonlinear = self%nonlinear
  end function model_is_nonlinear

  ! ------------------------------------------------------------------ output

  !> Maximum stress of every element for the global displacements q (current time).
  subroutine stresses(self, q, reports)
    class(steady_model_t), intent(in) :: self
    real(dp), intent(in) :: q(:)
    type(tennant_stress_t), intent(out) :: reports(:)
    integer :: e
    do e = 1, size(self%el)
      reports(e) = tennant_stress_recovery(self%el(e), self%element_q(e, q), self%fs(e))
    end do
  end subroutine stresses

  !> Local (u, w, alpha) of element e at fraction x/Delta.
  function local_field(self, e, q, x_over_l) result(uwa)
    class(steady_model_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:), x_over_l
    real(dp) :: uwa(3)
    uwa = tennant_local_field(self%el(e), self%element_q(e, q), self%fs(e), x_over_l)
  end function local_field

  !> Natural frequencies (rad/s) of the structure frozen at the current time:
  !> K_e x = w^2 M x with the symmetric part of K_e (which includes the
  !> centrifugal stiffness of the rigid-body motion).
  subroutine frozen_frequencies(self, omega_n, err)
    class(steady_model_t), intent(inout) :: self
    real(dp), intent(out) :: omega_n(:)
    type(error_t), intent(inout) :: err
    real(dp) :: m(self%n, self%n), c(self%n, self%n), k(self%n, self%n), f(self%n)
    call self%linear_terms(m, c, k, f, .false.)
    k = 0.5_dp*(k + transpose(k))
    call sym_generalized_eig(k, m, omega_n, err)
    if (err%failed()) return
    omega_n = sign(sqrt(abs(omega_n)), omega_n)
  end subroutine frozen_frequencies
end module steady_model
