!> The design problem of a spatial four-bar (doc/design.md, "Spatial
!> mechanisms"): the link sections of the spatial model (module
!> spatial_model) sized for the least mass of the links subject to the peak
!> stress of each link over the periodic revolution and, optionally, a lower
!> bound on the first natural frequency, each analysis the spatial transient
!> model run to its periodic state (module periodic_transient) from the
!> previous design's state.
!>
!> Variables x = ln(size / scale) of a link's radius (circular section) or
!> depth or width (rectangular).  Objective F = mass / initial mass
!> (explicit: no analysis).  Constraints, general (Potter's case of GNLC):
!>   g_l = ln(peak |stress| of link l over the revolution / allowable) <= 0,
!>         the peak the largest of the samples (read between them with
!>         peak_interpolation = 'parabola') or their KS aggregate in ln
!>         (design_problem's sample_peaks and ks_peak);
!>   g_f = ln(frequency_factor x omega / omega_1) <= 0, omega_1 the lowest
!>         natural frequency of the linearised structure at the start.
!> Their gradients are forward differences of whole analyses with the
!> relative step fd_rel_step (set by the caller from the periodicity
!> tolerance); their Hessians are taken as zero: a stress or frequency ratio
!> is nearly a power of the sizes, so its logarithm is nearly linear in x
!> (the second differences of analyses converged to 1e-6 would be noise).
!>
!> One analysis is one distinct design: every design analysed is kept
!> (analysed(1:n_analyses), in order), so the constraints and the difference
!> neighbours asked one by one cost one analysis each.
module spatial_design_problem
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
  use, intrinsic :: iso_fortran_env, only: int64
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use strings, only: str
  use optim_problem, only: opt_problem_t
  use element_effects, only: element_effects_t
  use spatial_section, only: spatial_section_init, section_circular, section_rectangular
  use spatial_beam, only: spatial_stress_t
  use spatial_kinematics, only: spatial_fourbar_t
  use spatial_model, only: spatial_model_t, spatial_link_t
  use periodic_transient, only: periodic_transient_settings_t, periodic_transient_report_t, transient_to_periodic
  use design_problem, only: design_variable_t, ks_peak, sample_peaks
  implicit none
  private
  public :: spatial_design_problem_t, spatial_eval_t, spatial_var_depth, spatial_var_width, spatial_var_radius

  !> the section size a variable sets (design_variable_t%kind)
  integer, parameter :: spatial_var_depth = 1, spatial_var_width = 2, spatial_var_radius = 3

  !> One analysed design.
  type :: spatial_eval_t
    logical :: ok = .false.
    character(len=:), allocatable :: reason     !< why the analysis failed
    real(dp), allocatable :: x(:)
    real(dp) :: mass = 0.0_dp
    real(dp), allocatable :: sample_stress(:, :)   !< (samples, 3) largest |stress| of each link at each sample
    real(dp), allocatable :: g(:)                  !< the analysis constraints
    real(dp) :: omega_1 = 0.0_dp                   !< lowest natural frequency at the start (frequency_factor > 0)
    integer :: revolutions = 0                     !< integrated to the periodic state
    integer :: index = 0                           !< its place among the analyses (1, 2, ...)
  end type spatial_eval_t

  type, extends(opt_problem_t) :: spatial_design_problem_t
    ! the mechanism
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    integer :: joint_b = 0, joint_c = 0, formulation = 0
    real(dp) :: omega = 0.0_dp, theta0 = 0.0_dp, beta = 0.0_dp
    type(element_effects_t) :: effects
    real(dp) :: length(3) = 0.0_dp               !< link lengths (from the base model)
    ! the problem
    type(design_variable_t), allocatable :: var(:)
    real(dp) :: stress_allowable = 0.0_dp, frequency_factor = 0.0_dp   !< 0: off
    integer :: samples = 72
    character(len=16) :: peak_stress = 'max', peak_interpolation = 'none'
    real(dp) :: ks_rho = 200.0_dp
    type(periodic_transient_settings_t) :: transient
    integer :: n_stress = 0, i_frequency = 0
    real(dp) :: mass0 = 1.0_dp
    ! state and counters
    real(dp), allocatable :: y_warm(:)           !< the last analysed design's periodic state at t = 0
    type(spatial_eval_t), allocatable :: analysed(:)   !< every design analysed, 1..n_analyses
    integer :: n_analyses = 0, n_failed = 0, n_revolutions = 0
    real(dp) :: cpu_analyses = 0.0_dp
    character(len=:), allocatable :: last_failure
  contains
    procedure :: setup
    procedure :: n_analysis_constraints
    procedure :: links_at
    procedure :: mass_at
    procedure :: evaluate
    procedure :: objective => spatial_objective
    procedure :: general_constraint => spatial_constraint
    procedure :: general_constraint_hessian => spatial_constraint_hessian
  end type spatial_design_problem_t

contains

  !> Size the optimization problem: the analysis constraints (general) and the
  !> variables' bounds; the lengths and the initial mass from the start x0.
  subroutine setup(self, name, x0, err)
    class(spatial_design_problem_t), intent(inout) :: self
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x0(:)
    type(error_t), intent(inout) :: err
    type(spatial_model_t) :: model
    integer :: i
    self%n_stress = merge(3, 0, self%stress_allowable > 0.0_dp)
    self%i_frequency = merge(self%n_stress + 1, 0, self%frequency_factor > 0.0_dp)
    call self%init_problem(name, size(x0), 0, self%n_analysis_constraints())
    do i = 1, self%m
      call self%set_general_constraint(i)
    end do
    call self%set_bounds([(self%var(i)%to_x(self%var(i)%lower), i=1, size(x0))], &
                         [(self%var(i)%to_x(self%var(i)%upper), i=1, size(x0))])
    call model%init(self%kin, self%omega, self%theta0, self%joint_b, self%joint_c, self%links_at(x0), &
                    self%effects, self%beta, err, formulation=self%formulation)
    if (err%failed()) return
    self%length = model%links%length
    self%mass0 = 1.0_dp
    self%mass0 = self%mass_at(x0)
    if (allocated(self%analysed)) deallocate(self%analysed)
    allocate(self%analysed(16))
    self%n_analyses = 0
    self%n_failed = 0
    self%n_revolutions = 0
    self%cpu_analyses = 0.0_dp
  end subroutine setup

  integer pure function n_analysis_constraints(self)
    class(spatial_design_problem_t), intent(in) :: self
    n_analysis_constraints = self%n_stress + merge(1, 0, self%i_frequency > 0)
  end function n_analysis_constraints

  !> The links with the sections of design x (values as given: a difference
  !> step past a bound is analysed as it is).
  function links_at(self, x) result(links)
    class(spatial_design_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    type(spatial_link_t) :: links(3)
    type(error_t) :: err
    real(dp) :: depth(3), width(3), radius(3)
    integer :: i, l
    links = self%links
    depth = links%sec%depth_y
    width = links%sec%width_z
    radius = links%sec%radius
    do i = 1, size(self%var)
      l = self%var(i)%index
      select case (self%var(i)%kind)
      case (spatial_var_depth)
        depth(l) = self%var(i)%value(x(i))
      case (spatial_var_width)
        width(l) = self%var(i)%value(x(i))
      case default
        radius(l) = self%var(i)%value(x(i))
      end select
    end do
    do l = 1, 3
      if (links(l)%sec%shape == section_circular) then
        call spatial_section_init(links(l)%sec, section_circular, [radius(l)], links(l)%material, err)
      else
        call spatial_section_init(links(l)%sec, section_rectangular, [depth(l), width(l)], links(l)%material, err)
      end if
    end do
  end function links_at

  !> Mass of the three links of design x.
  real(dp) function mass_at(self, x) result(mass)
    class(spatial_design_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    type(spatial_link_t) :: links(3)
    links = self%links_at(x)
    mass = sum(links%material%rho*links%sec%area*self%length)
  end function mass_at

  !> The analysis of design x: as analysed before, or the spatial model run to
  !> its periodic state from the last design's, then the link stresses at
  !> the samples and the constraints.
  subroutine evaluate(self, x, ev)
    class(spatial_design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    type(spatial_eval_t), intent(out) :: ev
    integer :: k
    real(dp) :: cpu0, cpu1
    type(spatial_eval_t), allocatable :: grown(:)
    do k = 1, self%n_analyses
      if (same_bits(self%analysed(k)%x, x)) then
        ev = self%analysed(k)
        return
      end if
    end do
    call cpu_time(cpu0)
    call analyse_design(self, x, ev)
    call cpu_time(cpu1)
    self%cpu_analyses = self%cpu_analyses + (cpu1 - cpu0)
    self%n_revolutions = self%n_revolutions + ev%revolutions
    if (.not. ev%ok) then
      self%n_failed = self%n_failed + 1
      self%last_failure = ev%reason
    end if
    if (self%n_analyses == size(self%analysed)) then
      allocate(grown(2*size(self%analysed)))
      grown(1:self%n_analyses) = self%analysed
      call move_alloc(grown, self%analysed)
    end if
    self%n_analyses = self%n_analyses + 1
    ev%index = self%n_analyses
    self%analysed(self%n_analyses) = ev
  end subroutine evaluate

  subroutine analyse_design(self, x, ev)
    class(spatial_design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    type(spatial_eval_t), intent(inout) :: ev
    type(spatial_model_t), target :: model
    type(periodic_transient_report_t) :: rep
    type(periodic_transient_settings_t) :: settle
    type(spatial_stress_t), allocatable :: stress(:)
    type(error_t) :: err
    real(dp), allocatable :: y(:), q(:, :), times(:), omega_n(:)
    integer :: k, l
    ev%x = x
    ev%mass = self%mass_at(x)
    call model%init(self%kin, self%omega, self%theta0, self%joint_b, self%joint_c, self%links_at(x), &
                    self%effects, self%beta, err, formulation=self%formulation)
    if (.not. err%failed() .and. self%i_frequency > 0) then
      allocate(omega_n(model%n))
      call model%linear_modes(omega_n, err)
      if (.not. err%failed()) ev%omega_1 = omega_n(1)
    end if
    if (err%failed()) then
      ev%reason = 'design '//design_text(self, x)//': '//err%text()
      return
    end if
    allocate(y(model%state_size()))
    y = 0.0_dp                                      ! the rigid-body state
    if (allocated(self%y_warm)) then
      if (size(self%y_warm) == size(y)) y = self%y_warm
    end if
    times = [((k - 1)*(two_pi/self%omega)/self%samples, k=1, self%samples)]
    allocate(q(model%n, self%samples), stress(size(model%el)), ev%sample_stress(self%samples, 3))
    call transient_to_periodic(model, self%transient, y, times, q, rep, err, omega=self%omega)
    ev%revolutions = rep%revolutions
    if (.not. err%failed()) then
      ! two revolutions more (the samples of the second): the test above is
      ! decided by the noisiest unknowns; these take the stresses a further
      ! factor rho^2 (about 0.1 on the RSSR) towards the periodic orbit
      settle = self%transient
      settle%tolerance = huge(1.0_dp)
      settle%max_revolutions = 2
      call transient_to_periodic(model, settle, y, times, q, rep, err, omega=self%omega)
      ev%revolutions = ev%revolutions + rep%revolutions
    end if
    if (err%failed()) then
      ev%reason = 'design '//design_text(self, x)//': '//err%text()
      return
    end if
    self%y_warm = y
    do k = 1, self%samples
      call model%set_time(times(k))
      if (model%err%failed()) then
        ev%reason = 'design '//design_text(self, x)//': '//model%err%text()
        return
      end if
      call model%element_stresses(q(:, k), stress)
      do l = 1, 3
        associate (first => model%links(l)%first_element)
          ev%sample_stress(k, l) = maxval(stress(first:first + model%links(l)%n_elements - 1)%max_abs_stress)
        end associate
      end do
    end do
    ev%g = constraints_of(self, ev)
    ev%ok = .true.
  end subroutine analyse_design

  !> The analysis constraints of an analysed design: each link's stress
  !> peak, then the frequency bound.
  function constraints_of(self, ev) result(g)
    class(spatial_design_problem_t), intent(in) :: self
    type(spatial_eval_t), intent(in) :: ev
    real(dp) :: g(self%n_analysis_constraints())
    real(dp) :: p(self%samples)
    integer :: l
    do l = 1, self%n_stress
      p = sample_peaks(ev%sample_stress(:, l), self%peak_interpolation)
      if (self%peak_stress == 'ks') then
        g(l) = ks_peak(log(max(p, tiny(1.0_dp))), self%ks_rho) - log(self%stress_allowable)
      else
        g(l) = log(max(maxval(p), tiny(1.0_dp))/self%stress_allowable)
      end if
    end do
    if (self%i_frequency > 0) then
      if (ev%omega_1 > 0.0_dp) then
        g(self%i_frequency) = log(self%frequency_factor*self%omega/ev%omega_1)
      else
        g(self%i_frequency) = ieee_value(1.0_dp, ieee_quiet_nan)
      end if
    end if
  end function constraints_of

  !> The design's sizes as text (failure messages).
  function design_text(self, x) result(text)
    class(spatial_design_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    character(len=:), allocatable :: text
    integer :: i
    text = ''
    do i = 1, size(x)
      if (i > 1) text = text//', '
      text = text//trim(self%var(i)%name)//' = '//str(self%var(i)%value(x(i)), 6)
    end do
  end function design_text

  !> F = mass / initial mass (no analysis).
  subroutine spatial_objective(self, x, f, err)
    class(spatial_design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    if (err%failed()) return
    f = self%mass_at(x)/self%mass0
  end subroutine spatial_objective

  !> Analysis constraint i at x (NaN when the analysis failed: a failed trial
  !> for the optimizer).
  subroutine spatial_constraint(self, i, x, g, err)
    class(spatial_design_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    type(spatial_eval_t) :: ev
    if (err%failed()) return
    call self%evaluate(x, ev)
    if (ev%ok) then
      g = ev%g(i)
    else
      g = ieee_value(g, ieee_quiet_nan)
    end if
  end subroutine spatial_constraint

  !> Zero: the constraints are logarithms of ratios nearly linear in the
  !> logarithms of the sizes (see the module's header).
  subroutine spatial_constraint_hessian(self, i, x, hess, err)
    class(spatial_design_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    if (.false.) print *, self%n, i, x, err%failed()   ! (the binding's interface)
    hess = 0.0_dp
  end subroutine spatial_constraint_hessian

  !> The same design, bit for bit (the key of analysed designs).
  logical pure function same_bits(a, b)
    real(dp), intent(in) :: a(:), b(:)
    same_bits = size(a) == size(b)
    if (same_bits) same_bits = all(transfer(a, 1_int64, size(a)) == transfer(b, 1_int64, size(b)))
  end function same_bits
end module spatial_design_problem
