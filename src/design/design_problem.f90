!> Optimal design of a flexible mechanism with the nonlinear analysis in the
!> loop (paper L; doc/design.md): an optimization problem whose every
!> function evaluation is one steady-state analysis of the mechanism.
!>
!> Design variables are deck values of &mechanism named as in the deck
!> (link_b(i), link_h(i), link_length(i), joint_x(j), joint_y(j)); the optimizer
!> works on x = ln(value/scale) for sizes and lengths (positive whatever the
!> step; stresses go nearly as a power of the sizes, so their logarithms are
!> nearly linear in x) and on x = value/scale for coordinates.  The objective is the mass of the links (scaled by
!> the initial mass), a general objective whose exact Hessian the Gauss
!> family uses: in logarithmic sizes the mass sum c_i exp(x_i) is convex with
!> a positive Hessian, where in the sizes themselves it is linear (no
!> curvature for G) and a sum-of-squares form sqrt(m_i) would give a
!> Gauss-Newton model off by a factor 2 at the constrained optimum (the
!> residuals do not vanish there) and steps that cycle.  The constraints,
!> all g <= 0, are
!>   ln(peak |stress| over the steady revolution / allowable), per link;
!>   ln(factor omega / lowest frozen natural frequency over the revolution);
!> and the bounds of each variable.
!> An analysis that fails (the linkage does not assemble, resonance, an
!> unstable periodic orbit, a strain past the Ramberg-Osgood peak, a DLSODE
!> stop) makes its constraints NaN: the optimizer takes it as a failed trial
!> and steps back, and the reason is kept for the output.
!>
!> Every distinct design is analysed once (a cache of the last cache_size
!> designs, keyed by x): the objective and all constraints at one x cost one
!> analysis, and so does each finite-difference point, shared by every
!> constraint's gradient and Hessian.  n_analyses counts them all; the shooting start of
!> each analysis is the previous design's periodic state.
module design_problem
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: int64
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism, max_links
  use optim_problem, only: opt_problem_t
  use tennant_element, only: tennant_options_t, tennant_stress_t
  use steady_model, only: steady_model_t, link_sections_t
  use shaking_force, only: rigid_momentum_rate, elastic_first_moment, periodic_second_derivative, periodic_derivatives
  use joint_bearing, only: bearing_forces
  use harmonic_solver, only: harmonic_settings_t, harmonic_report_t, harmonic_solve, harmonic_diagnosis
  use periodic_shooting, only: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit, &
                               shooting_diagnosis, orbit_sensitivity
  use element_effects, only: element_effects_t
  use mechanism_model, only: mechanism_model_t
  use periodic_transient, only: periodic_transient_settings_t, periodic_transient_report_t, transient_to_periodic, &
                                matching_unknowns
  implicit none
  private
  public :: design_problem_t, design_variable_t, design_eval_t, parse_variable
  public :: var_link_b, var_link_h, var_link_length, var_joint_x, var_joint_y, var_theta0, var_path_r, &
            var_path_angle, var_cw_mass, var_cw_x, var_cw_y, coupler_point_of, ks_peak, sample_peaks

  integer, parameter :: cache_size = 256
  integer, parameter :: var_link_b = 1, var_link_h = 2, var_link_length = 3, var_joint_x = 4, var_joint_y = 5
  !> scalars without an index: the crank angle at t = 0 (B's x8, degrees) and
  !> the coupler point's distance and angle from its link's end 1 (B's x5, x7)
  integer, parameter :: var_theta0 = 6, var_path_r = 7, var_path_angle = 8
  !> counterweight of link i: mass, position along and across the link
  integer, parameter :: var_cw_mass = 9, var_cw_x = 10, var_cw_y = 11
  real(dp), parameter :: deg = atan(1.0_dp)/45.0_dp
  !> the indexed variables' deck names, in the order of their kinds
  !> (var_link_b .. var_joint_y, then var_cw_mass .. var_cw_y after the scalars)
  character(len=12), parameter :: indexed_names(11) = [character(len=12) :: 'link_b', 'link_h', 'link_length', &
    'joint_x', 'joint_y', '', '', '', 'link_cw_mass', 'link_cw_x', 'link_cw_y']

  !> One design variable: a deck value of &mechanism.
  type :: design_variable_t
    character(len=32) :: name = ''
    integer :: kind = 0
    integer :: index = 0
    real(dp) :: lower = 0.0_dp, upper = 0.0_dp, scale = 1.0_dp
    logical :: logarithmic = .false.   !< sizes and lengths: x = ln(value/scale)
  contains
    procedure :: value => variable_value
    procedure :: to_x => variable_to_x
  end type design_variable_t

  !> What one analysis of one design gives.
  type :: design_eval_t
    logical :: ok = .false.
    character(len=:), allocatable :: reason     !< why the analysis failed
    real(dp) :: mass = 0.0_dp
    real(dp), allocatable :: link_stress(:)     !< peak |stress| over the revolution, per link (largest over the speeds)
    real(dp) :: lowest_frequency = 0.0_dp       !< lowest frozen natural frequency over the revolution (and the speeds)
    real(dp), allocatable :: stress_at(:, :)    !< (link, speed) peak |stress| at each operating speed
    !> (sample, link, speed) the link's largest |stress| at each sample: stress_at is its maximum
    real(dp), allocatable :: sample_stress(:, :, :)
    real(dp), allocatable :: frequency_at(:)    !< (speed) lowest frozen natural frequency at each speed
    !> (sample, point, speed) elastic deflection of each named link point
    !> (deflection constraints): from the chord or from the rigid position
    real(dp), allocatable :: sample_deflection(:, :, :)
    !> (sample) |cos| of the transmission angle (movability constraint;
    !> rigid-body kinematics, the same at every speed)
    real(dp), allocatable :: sample_transmission(:)
    real(dp), allocatable :: residual(:)        !< coupler point - target, (x, y) per target point, elastic included
    real(dp), allocatable :: rigid_residual(:)  !< the same for the rigid-body coupler point
    real(dp) :: path_error = 0.0_dp             !< sum of residual^2 (B's F, with the deformation)
    real(dp) :: rigid_path_error = 0.0_dp       !< sum of rigid_residual^2 (B's F)
    real(dp) :: peak_shaking = 0.0_dp           !< largest |shaking force| over the samples (objective 'shaking')
    real(dp) :: rms_shaking = 0.0_dp            !< its root mean square over the revolution
    !> largest bearing force |F_j| over the samples and the named joints
    !> (objectives 'bearing' and 'bearing_peak'; module joint_bearing)
    real(dp) :: peak_bearing = 0.0_dp
    real(dp) :: rms_bearing = 0.0_dp            !< sqrt(mean over the samples of sum_j |F_j|^2)
    real(dp) :: cpu_seconds = 0.0_dp
    real(dp), allocatable :: y_periodic(:, :)   !< (2 n, speed) periodic state at t = 0 (shooting evaluator)
    !> (2 n, 2 n, speed) its monodromy matrix (shooting evaluator): the
    !> sensitivity solve at this design starts from it
    real(dp), allocatable :: monodromy(:, :, :)
    !> the Ramberg-Osgood analysis stopped at a strain past the law's peak:
    !> the results are the linear-material twin's (reason says where)
    logical :: past_peak = .false.
  end type design_eval_t

  type, extends(opt_problem_t) :: design_problem_t
    type(mechanism_input_t) :: base               !< the deck's mechanism
    type(design_variable_t), allocatable :: var(:)
    !> 'shooting' (exact periodic), 'harmonic' or 'transient' (the transient
    !> model run to its periodic state)
    character(len=16) :: evaluator = 'shooting'
    !> 'variational' (the periodic orbit's sensitivities, shooting evaluator)
    !> or 'differences' (forward differences of whole analyses)
    character(len=16) :: derivatives = 'differences'
    real(dp) :: variational_step = 1.0e-5_dp      !< relative step of the central differences in p (f_p, outputs)
    type(harmonic_settings_t) :: harmonic
    type(shooting_settings_t) :: shooting
    type(periodic_transient_settings_t) :: transient
    type(tennant_options_t) :: element
    type(link_sections_t) :: sections(max_links)
    integer :: samples = 72                       !< crank angles per revolution for stresses and frequencies
    !> how a link's stress constraint takes the samples: 'max' (the peak
    !> sample) or 'ks' (the Kreisselmeier-Steinhauser aggregate of
    !> ln(stress) with sharpness ks_rho: smooth in the design, above the
    !> peak by at most ln(samples)/ks_rho; function ks_peak)
    character(len=8) :: peak_stress = 'max'
    real(dp) :: ks_rho = 200.0_dp
    !> how the peaks (stress, deflection, transmission) read the samples:
    !> 'none' (at the samples only) or 'parabola' (between them too: the
    !> largest of each sample's parabola through it and its two periodic
    !> neighbours over half a sample spacing either side; function
    !> sample_peaks)
    character(len=8) :: peak_interpolation = 'none'
    real(dp) :: stress_allowable = 0.0_dp         !< 0: no stress constraints
    real(dp) :: frequency_factor = 0.0_dp         !< 0: no frequency constraint
    !> deflection constraints: point p on link deflection_link(p) at the
    !> fraction deflection_at(p) of its length from end 1; its elastic
    !> deflection from the chord (the line through the deformed ends, across
    !> it) or from the rigid position (the length of the elastic
    !> displacement), peak over the samples <= deflection_limit(p)
    integer, allocatable :: deflection_link(:)
    real(dp), allocatable :: deflection_at(:), deflection_limit(:)
    logical, allocatable :: deflection_chord(:)
    !> movability: the angle mu between the two links that meet at joint
    !> transmission_joint (the coupler and the output link of a four-bar)
    !> kept within [transmission_min, pi - transmission_min] at every sample:
    !> ln(peak |cos mu| / cos transmission_min) <= 0 (0: no such constraint)
    integer :: transmission_joint = 0
    real(dp) :: transmission_min = 0.0_dp
    real(dp) :: mass0 = 1.0_dp                    !< mass of the initial design
    !> 'mass', 'path' (elastic path error), 'path_rigid', 'shaking' (mean
    !> square shaking force), 'shaking_peak' (its peak: minimax), 'bearing'
    !> (mean square bearing force of the joints bearing_joints) or
    !> 'bearing_peak' (their peak: minimax)
    character(len=32) :: objective_kind = 'mass'
    integer, allocatable :: bearing_joints(:)     !< the joints of the bearing objectives
    real(dp) :: f0 = 1.0_dp                       !< objective of the initial design (the objective's scale)
    ! ---- the coupler point (path objectives): on a rigid arm clamped to
    !      link path_link at its end 1, at distance path_r and angle
    !      path_angle (rad) from the link's line; target points path_x/y at
    !      crank angles theta0 + path_dgamma (rad)
    integer :: path_link = 0
    real(dp) :: path_r = 0.0_dp, path_angle = 0.0_dp
    real(dp), allocatable :: path_x(:), path_y(:), path_dgamma(:)
    !> operating speeds (rad/s): every constraint holds at each; the
    !> objective's analysis results are summed over them (objective_speed =
    !> 0) or taken at speeds(objective_speed).  Default: the deck's omega.
    real(dp), allocatable :: speeds(:)
    integer :: objective_speed = 0
    !> constraint numbering: stress of link l at speed s is l + (s - 1)
    !> n_links (1..n_stress), then the frequency at each speed from i_frequency
    integer :: n_stress = 0, i_frequency = 0
    !> deflection of point p at speed s: i_deflection + (s - 1) n_points + p - 1
    integer :: i_deflection = 0
    integer :: i_transmission = 0                 !< the movability constraint's number (0: none)
    ! ---- bookkeeping
    integer :: n_analyses = 0, n_failed = 0
    integer :: n_revolutions = 0                  !< revolutions integrated by the transient evaluator
    integer :: n_sensitivity = 0                  !< sensitivity solves (each also counted as one analysis per speed)
    integer :: n_sensitivity_fallbacks = 0        !< sensitivity solves that failed: forward differences instead
    integer :: n_past_peak = 0                    !< designs past the Ramberg-Osgood peak (infeasible, analysed linear)
    character(len=:), allocatable :: last_past_peak
    real(dp) :: cpu_sensitivity = 0.0_dp          !< CPU of the sensitivity solves (also in cpu_analyses)
    integer :: sensitivity_rhs = 0                !< right-hand sides of the sensitivity flows (perturbed ones included)
    real(dp) :: cpu_analyses = 0.0_dp
    real(dp), allocatable :: cache_x(:, :)        !< designs analysed lately (ring of cache_size)
    type(design_eval_t), allocatable :: cache(:)
    integer :: cache_used = 0, cache_next = 1
    real(dp), allocatable :: y_warm(:, :)         !< last periodic state at each speed (shooting start)
    character(len=:), allocatable :: last_failure
  contains
    procedure :: setup
    procedure :: is_bearing
    procedure :: n_analysis_constraints
    procedure :: n_deflection_points
    procedure :: mechanism_at
    procedure :: point_at
    procedure :: is_path
    procedure :: is_shaking
    procedure :: is_minimax
    procedure :: has_residuals
    procedure :: n_residuals_design
    procedure :: evaluate
    procedure :: variational_applies
    procedure :: derivatives_at
    procedure :: constraints_of
    procedure :: constraints_at_peaks_of
    procedure :: neighbour_constraints
    procedure :: residuals_of
    procedure :: objective => design_objective
    procedure :: general_constraint => design_constraint
  end type design_problem_t

contains

  pure real(dp) function variable_value(v, x) result(value)
    class(design_variable_t), intent(in) :: v
    real(dp), intent(in) :: x
    if (v%logarithmic) then
      value = v%scale*exp(min(x, 700.0_dp))
    else
      value = v%scale*x
    end if
  end function variable_value

  pure real(dp) function variable_to_x(v, value) result(x)
    class(design_variable_t), intent(in) :: v
    real(dp), intent(in) :: value
    if (v%logarithmic) then
      x = log(value/v%scale)
    else
      x = value/v%scale
    end if
  end function variable_to_x

  !> 'link_h(2)' -> kind and index; ok = .false. for an unknown name.
  subroutine parse_variable(text, v, ok)
    character(len=*), intent(in) :: text
    type(design_variable_t), intent(inout) :: v
    logical, intent(out) :: ok
    integer :: open_at, close_at, ios
    character(len=32) :: word
    ok = .false.
    word = lower(adjustl(text))
    select case (word)
    case ('theta0_deg', 'path_r', 'path_angle_deg')
      v%kind = merge(var_theta0, merge(var_path_r, var_path_angle, word == 'path_r'), word == 'theta0_deg')
      v%index = 0
      v%name = word
      v%logarithmic = v%kind == var_path_r
      ok = .true.
      return
    end select
    open_at = index(word, '(')
    close_at = index(word, ')')
    if (open_at < 2 .or. close_at < open_at + 2) return
    v%kind = findloc(indexed_names, word(1:open_at - 1), dim=1)
    if (v%kind == 0) return
    read(word(open_at + 1:close_at - 1), *, iostat=ios) v%index
    if (ios /= 0) return
    v%name = word
    v%logarithmic = v%kind <= var_link_length
    ok = .true.
  end subroutine parse_variable

  !> Size the problem: n variables, the analysis constraints the settings ask
  !> for (the bounds stay with the variables: module design_sequence).
  subroutine setup(self, name, x_start)
    class(design_problem_t), intent(inout) :: self
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: x_start(:)
    integer :: n, i
    type(design_eval_t) :: ev
    n = size(self%var)
    if (.not. allocated(self%speeds)) self%speeds = [self%base%omega]
    if (size(self%speeds) == 0) self%speeds = [self%base%omega]
    self%n_stress = 0
    if (self%stress_allowable > 0.0_dp) self%n_stress = self%base%n_links*size(self%speeds)
    self%i_frequency = 0
    if (self%frequency_factor > 0.0_dp) self%i_frequency = self%n_stress + 1
    self%i_deflection = 0
    if (self%n_deflection_points() > 0) &
      self%i_deflection = self%n_stress + merge(size(self%speeds), 0, self%i_frequency > 0) + 1
    self%i_transmission = 0
    if (self%transmission_joint > 0) self%i_transmission = self%n_stress + &
      merge(size(self%speeds), 0, self%i_frequency > 0) + self%n_deflection_points()*size(self%speeds) + 1
    call self%init_problem(name, n, 0, self%n_analysis_constraints())
    do i = 1, self%m
      call self%set_general_constraint(i)
    end do
    self%n_analyses = 0
    self%n_failed = 0
    self%n_revolutions = 0
    self%n_sensitivity = 0
    self%n_sensitivity_fallbacks = 0
    self%cpu_sensitivity = 0.0_dp
    self%sensitivity_rhs = 0
    self%cpu_analyses = 0.0_dp
    if (allocated(self%cache_x)) deallocate(self%cache_x, self%cache)
    allocate(self%cache_x(n, cache_size), self%cache(cache_size))
    self%cache_used = 0
    self%cache_next = 1
    ! mass of the initial design, the objective's scale
    self%mass0 = 1.0_dp
    self%mass0 = max(design_mass(self%mechanism_at(x_start, .false.)), tiny(1.0_dp))
    self%f0 = 1.0_dp
    if (self%has_residuals()) then
      ! the initial objective scales it (its analysis is counted and
      ! cached: the design loop's first analysis)
      call self%evaluate(x_start, ev)
      if (ev%ok) self%f0 = max(objective_value(self, ev), 1.0e-12_dp)
    else
      self%f0 = self%mass0
    end if
  end subroutine setup

  logical pure function is_path(self)
    class(design_problem_t), intent(in) :: self
    is_path = self%objective_kind == 'path' .or. self%objective_kind == 'path_rigid'
  end function is_path

  !> The objective is the shaking force, its mean square or its peak.
  logical pure function is_shaking(self)
    class(design_problem_t), intent(in) :: self
    is_shaking = self%objective_kind == 'shaking' .or. self%objective_kind == 'shaking_peak'
  end function is_shaking

  !> The objective is the named joints' bearing force, its mean square or its peak.
  logical pure function is_bearing(self)
    class(design_problem_t), intent(in) :: self
    is_bearing = self%objective_kind == 'bearing' .or. self%objective_kind == 'bearing_peak'
  end function is_bearing

  !> The objective is the largest of the analysis results the residuals
  !> hold (|shaking force| or each joint's |bearing force| at each sample):
  !> min t subject to r_k <= t.
  logical pure function is_minimax(self)
    class(design_problem_t), intent(in) :: self
    is_minimax = self%objective_kind == 'shaking_peak' .or. self%objective_kind == 'bearing_peak'
  end function is_minimax

  !> The objective is made of analysis results r (the residuals): their sum
  !> of squares (Gauss-Newton) or, minimax, their largest.
  logical pure function has_residuals(self)
    class(design_problem_t), intent(in) :: self
    has_residuals = self%objective_kind /= 'mass'
  end function has_residuals

  !> Residuals of the objective: 2 per target point (path), 2 per sample
  !> (shaking force components / sqrt(samples)), 1 per sample (minimax:
  !> |shaking force|), the same per sample and named joint for the bearing
  !> force; none for the mass.
  integer pure function n_residuals_design(self)
    class(design_problem_t), intent(in) :: self
    n_residuals_design = 0
    if (self%is_path()) n_residuals_design = 2*size(self%path_x)
    if (self%objective_kind == 'shaking') n_residuals_design = 2*self%samples
    if (self%objective_kind == 'shaking_peak') n_residuals_design = self%samples
    if (self%objective_kind == 'bearing') n_residuals_design = 2*self%samples*size(self%bearing_joints)
    if (self%objective_kind == 'bearing_peak') n_residuals_design = self%samples*size(self%bearing_joints)
  end function n_residuals_design

  !> The coupler point's (distance, angle in rad) at design x (clamped).
  function point_at(self, x) result(ra)
    class(design_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: ra(2)
    integer :: i
    real(dp) :: value
    ra = [self%path_r, self%path_angle]
    do i = 1, size(self%var)
      if (self%var(i)%kind /= var_path_r .and. self%var(i)%kind /= var_path_angle) cycle
      value = min(max(self%var(i)%value(x(i)), self%var(i)%lower), self%var(i)%upper)
      if (self%var(i)%kind == var_path_r) then
        ra(1) = value
      else
        ra(2) = value*deg
      end if
    end do
  end function point_at

  integer pure function n_analysis_constraints(self)
    class(design_problem_t), intent(in) :: self
    n_analysis_constraints = self%n_stress + merge(size(self%speeds), 0, self%i_frequency > 0) + &
                             self%n_deflection_points()*size(self%speeds) + merge(1, 0, self%transmission_joint > 0)
  end function n_analysis_constraints

  !> Named link points whose deflection is constrained.
  integer pure function n_deflection_points(self)
    class(design_problem_t), intent(in) :: self
    n_deflection_points = 0
    if (allocated(self%deflection_link)) n_deflection_points = size(self%deflection_link)
  end function n_deflection_points

  !> The mechanism input with the design x put in; clamped: each value
  !> inside its bounds (a trial step past them, which the optimizer sees in
  !> the bound constraints, is analysed at the nearest admissible design).
  function mechanism_at(self, x, clamped) result(inp)
    class(design_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    logical, intent(in) :: clamped
    type(mechanism_input_t) :: inp
    integer :: i
    real(dp) :: value
    inp = self%base
    do i = 1, size(self%var)
      value = self%var(i)%value(x(i))
      if (clamped) value = min(max(value, self%var(i)%lower), self%var(i)%upper)
      select case (self%var(i)%kind)
      case (var_link_b)
        inp%link_b(self%var(i)%index) = value
      case (var_link_h)
        inp%link_h(self%var(i)%index) = value
      case (var_link_length)
        inp%link_length(self%var(i)%index) = value
      case (var_joint_x)
        inp%joint_x(self%var(i)%index) = value
      case (var_joint_y)
        inp%joint_y(self%var(i)%index) = value
      case (var_theta0)
        inp%theta0_deg = value
      case (var_cw_mass)
        inp%link_cw_mass(self%var(i)%index) = value
      case (var_cw_x)
        inp%link_cw_x(self%var(i)%index) = value
      case (var_cw_y)
        inp%link_cw_y(self%var(i)%index) = value
      end select
    end do
  end function mechanism_at

  !> Mass of each link (its length as given, or from the joint coordinates:
  !> build_mechanism decides); NaN for a design that is not a mechanism.
  function link_masses(inp) result(mass)
    type(mechanism_input_t), intent(in) :: inp
    real(dp) :: mass(inp%n_links)
    type(mechanism_t) :: mech
    type(error_t) :: err
    integer :: i
    call build_mechanism(inp, mech, err)
    if (err%failed()) then
      mass = ieee_value(1.0_dp, ieee_quiet_nan)
      return
    end if
    do i = 1, mech%n_links
      mass(i) = mech%links(i)%rho*mech%links(i)%area*mech%links(i)%length
    end do
  end function link_masses

  !> The links' and the counterweights' mass.
  real(dp) function design_mass(inp) result(mass)
    type(mechanism_input_t), intent(in) :: inp
    mass = sum(link_masses(inp)) + sum(inp%link_cw_mass(1:inp%n_links))
  end function design_mass

  !> The objective's unscaled value: sum of squares of the residuals.
  real(dp) pure function objective_value(self, ev) result(f)
    class(design_problem_t), intent(in) :: self
    type(design_eval_t), intent(in) :: ev
    select case (self%objective_kind)
    case ('path_rigid')
      f = ev%rigid_path_error
    case ('shaking')
      f = ev%rms_shaking**2
    case ('shaking_peak')
      f = ev%peak_shaking
    case ('bearing')
      f = ev%rms_bearing**2
    case ('bearing_peak')
      f = ev%peak_bearing
    case ('path')
      f = ev%path_error
    case default
      f = ev%mass
    end select
  end function objective_value

  !> Analyse design x (once: later calls at the same x read the cache).
  subroutine evaluate(self, x, ev)
    class(design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    type(design_eval_t), intent(out) :: ev
    real(dp) :: cpu0, cpu1
    integer :: k
    do k = 1, self%cache_used
      if (same_bits(self%cache_x(:, k), x)) then
        ev = self%cache(k)
        return
      end if
    end do
    call cpu_time(cpu0)
    call analyse_design(self, self%mechanism_at(x, .true.), x, ev)
    call cpu_time(cpu1)
    ev%cpu_seconds = cpu1 - cpu0
    ! one mechanism analysis per operating speed
    self%n_analyses = self%n_analyses + size(self%speeds)
    self%cpu_analyses = self%cpu_analyses + ev%cpu_seconds
    if (.not. ev%ok) then
      self%n_failed = self%n_failed + 1
      self%last_failure = ev%reason
    else if (ev%past_peak) then
      self%n_past_peak = self%n_past_peak + 1
      self%last_past_peak = ev%reason
    end if
    self%cache_x(:, self%cache_next) = x
    self%cache(self%cache_next) = ev
    self%cache_used = max(self%cache_used, self%cache_next)
    self%cache_next = modulo(self%cache_next, cache_size) + 1
  end subroutine evaluate

  !> The analyses of one design at every operating speed: the stresses and
  !> frequencies at each kept apart (each speed has its constraints), the
  !> objective's results joined over the objective's speeds (residuals one
  !> after another: sums of squares add; a mean square is averaged over the
  !> speeds; a peak is the largest).
  subroutine analyse_design(self, inp, x_design, ev)
    class(design_problem_t), intent(inout) :: self
    type(mechanism_input_t), intent(in) :: inp
    real(dp), intent(in) :: x_design(:)
    type(design_eval_t), intent(out) :: ev
    type(design_eval_t) :: one
    type(mechanism_input_t) :: at_speed
    integer :: s, ns, n_objective
    real(dp) :: mean_square
    ns = size(self%speeds)
    call start_join(self, inp%n_links, ev, n_objective, mean_square)
    do s = 1, ns
      at_speed = inp
      at_speed%omega = self%speeds(s)
      call analyse_speed(self, at_speed, x_design, s, one)
      if (.not. one%ok) then
        ev = one
        if (ns > 1) ev%reason = 'at '//str(self%speeds(s), 6)//' rad/s: '//one%reason
        return
      end if
      if (one%past_peak) then
        ev%past_peak = .true.
        ev%reason = one%reason
      end if
      if (allocated(one%y_periodic)) then
        if (.not. allocated(ev%y_periodic)) allocate(ev%y_periodic(size(one%y_periodic, 1), ns), &
                                                     ev%monodromy(size(one%y_periodic, 1), size(one%y_periodic, 1), ns))
        ev%y_periodic(:, s) = one%y_periodic(:, 1)
        ev%monodromy(:, :, s) = one%monodromy(:, :, 1)
      end if
      call join_speed(self, s, one, ev, n_objective, mean_square)
    end do
    call close_join(self, one%mass, ev, n_objective, mean_square)
  end subroutine analyse_design

  !> The joined results of the speeds, empty (analyse_design's order).
  subroutine start_join(self, n_links, ev, n_objective, mean_square)
    class(design_problem_t), intent(in) :: self
    integer, intent(in) :: n_links
    type(design_eval_t), intent(out) :: ev
    integer, intent(out) :: n_objective
    real(dp), intent(out) :: mean_square
    allocate(ev%stress_at(n_links, size(self%speeds)), ev%frequency_at(size(self%speeds)), ev%residual(0), &
             ev%rigid_residual(0), ev%sample_stress(self%samples, n_links, size(self%speeds)), &
             ev%sample_deflection(self%samples, self%n_deflection_points(), size(self%speeds)), &
             ev%sample_transmission(self%samples))
    ev%sample_transmission = 0.0_dp
    n_objective = 0
    mean_square = 0.0_dp
  end subroutine start_join

  !> Speed s's results joined: its constraints kept apart, the objective's
  !> results added when s is one of the objective's speeds.
  subroutine join_speed(self, s, one, ev, n_objective, mean_square)
    class(design_problem_t), intent(in) :: self
    integer, intent(in) :: s
    type(design_eval_t), intent(in) :: one
    type(design_eval_t), intent(inout) :: ev
    integer, intent(inout) :: n_objective
    real(dp), intent(inout) :: mean_square
    ev%stress_at(:, s) = one%link_stress
    ev%sample_stress(:, :, s) = one%sample_stress(:, :, 1)
    ev%sample_deflection(:, :, s) = one%sample_deflection(:, :, 1)
    if (s == 1) ev%sample_transmission = one%sample_transmission
    ev%frequency_at(s) = one%lowest_frequency
    if (self%objective_speed /= 0 .and. self%objective_speed /= s) return
    n_objective = n_objective + 1
    if (allocated(one%residual)) ev%residual = [ev%residual, one%residual]
    if (allocated(one%rigid_residual)) ev%rigid_residual = [ev%rigid_residual, one%rigid_residual]
    ev%path_error = ev%path_error + one%path_error
    ev%rigid_path_error = ev%rigid_path_error + one%rigid_path_error
    ev%peak_shaking = max(ev%peak_shaking, one%peak_shaking)
    ev%peak_bearing = max(ev%peak_bearing, one%peak_bearing)
    mean_square = mean_square + merge(one%rms_bearing, one%rms_shaking, self%is_bearing())**2
  end subroutine join_speed

  subroutine close_join(self, mass, ev, n_objective, mean_square)
    class(design_problem_t), intent(in) :: self
    real(dp), intent(in) :: mass
    type(design_eval_t), intent(inout) :: ev
    integer, intent(in) :: n_objective
    real(dp), intent(in) :: mean_square
    ev%ok = .true.
    ev%mass = mass
    ev%link_stress = maxval(ev%stress_at, dim=2)
    ev%lowest_frequency = minval(ev%frequency_at)
    if (self%is_bearing()) then
      ev%rms_bearing = sqrt(mean_square/max(n_objective, 1))
    else
      ev%rms_shaking = sqrt(mean_square/max(n_objective, 1))
    end if
    if (self%objective_kind == 'shaking' .or. self%objective_kind == 'bearing') &
      ev%residual = ev%residual/sqrt(real(max(n_objective, 1), dp))
  end subroutine close_join

  !> One steady-state analysis at one speed (s of self%speeds): build,
  !> periodic response, stresses and frozen frequencies at `samples` crank angles.
  !> A Ramberg-Osgood analysis that stops past the law's peak strain is not a
  !> failed analysis but an infeasible design: past_peak_twin.
  recursive subroutine analyse_speed(self, inp, x_design, s, ev)
    class(design_problem_t), intent(inout) :: self
    type(mechanism_input_t), intent(in) :: inp
    real(dp), intent(in) :: x_design(:)
    integer, intent(in) :: s
    type(design_eval_t), intent(out) :: ev
    type(mechanism_t) :: mech
    type(steady_model_t), target :: model
    type(error_t) :: err
    type(harmonic_report_t) :: hrep
    type(shooting_report_t) :: srep
    real(dp), allocatable :: times(:), q(:, :), qd(:, :), y0(:), mono(:, :)
    integer, allocatable :: at_sample(:), at_point(:)
    ev%ok = .false.
    ev%mass = design_mass(inp)
    allocate(ev%link_stress(inp%n_links))
    ev%link_stress = 0.0_dp
    call build_design_model(self, inp, mech, model, err)
    if (err%failed()) then
      ev%reason = 'the design is not a valid mechanism: '//err%text()
      return
    end if
    call merged_times(self, model%omega, times, at_sample, at_point)
    allocate(q(model%n, size(times)))
    if (self%evaluator == 'harmonic') then
      call harmonic_solve(model, self%harmonic, times, q, hrep, err)
      if (.not. err%failed()) call harmonic_diagnosis(self%harmonic, hrep, model%omega, .false., .false., err)
    else if (self%evaluator == 'transient') then
      call transient_samples(self, mech, model, s, times, q, err)
    else
      allocate(qd(model%n, size(times)), mono(2*model%n, 2*model%n))
      y0 = warm_start(self, 2*model%n, s)
      call shooting_solve(model, self%shooting, y0, srep, err, monodromy=mono)
      if (.not. err%failed()) call shooting_diagnosis(self%shooting, srep, model%omega, .false., err)
      if (.not. err%failed()) call periodic_orbit(model, self%shooting, y0, times, q, qd, srep, err)
      if (.not. err%failed()) then
        self%y_warm(:, s) = y0
        ev%y_periodic = reshape(y0, [size(y0), 1])
        ev%monodromy = reshape(mono, [size(y0), size(y0), 1])
      end if
    end if
    if (err%failed()) then
      ev%reason = err%text()
      if (abs(self%element%d_k) > 0.0_dp .and. index(ev%reason, 'peak of the Ramberg-Osgood law') > 0) &
        call past_peak_twin(self, inp, x_design, s, ev)
      return
    end if
    call design_results(self, mech, model, x_design, times, at_sample, at_point, q, ev)
  end subroutine analyse_speed

  !> A design whose material-nonlinear analysis passed the Ramberg-Osgood
  !> peak strain (where the law's stiffness changes sign and the analysis has
  !> no meaning) is an infeasible design, not a failed one: it is analysed
  !> with the material linear (d_k = 0), whose stresses, E1 times strains
  !> beyond the peak strain, exceed the law's peak stress and with it any
  !> allowable below that peak, so the loop sees violated stress constraints
  !> and steps back towards feasible designs.  No periodic state is kept (the
  !> twin's orbit is not this model's): derivatives there are differences.
  recursive subroutine past_peak_twin(self, inp, x_design, s, ev)
    class(design_problem_t), intent(inout) :: self
    type(mechanism_input_t), intent(in) :: inp
    real(dp), intent(in) :: x_design(:)
    integer, intent(in) :: s
    type(design_eval_t), intent(inout) :: ev
    real(dp) :: d_k
    character(len=:), allocatable :: why
    why = ev%reason
    d_k = self%element%d_k
    self%element%d_k = 0.0_dp
    call analyse_speed(self, inp, x_design, s, ev)
    self%element%d_k = d_k
    if (.not. ev%ok) then
      ev%reason = why
      return
    end if
    if (allocated(ev%y_periodic)) deallocate(ev%y_periodic)
    if (allocated(ev%monodromy)) deallocate(ev%monodromy)
    ev%past_peak = .true.
    ev%reason = 'infeasible (stresses of the linear-material twin): '//why
  end subroutine past_peak_twin

  !> The mechanism and its steady model of a design (one speed).
  subroutine build_design_model(self, inp, mech, model, err)
    class(design_problem_t), intent(in) :: self
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(out) :: mech
    type(steady_model_t), intent(inout) :: model
    type(error_t), intent(inout) :: err
    call build_mechanism(inp, mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, self%element, self%sections, err)
  end subroutine build_design_model

  !> What a design's periodic response q at the times gives: the coupler
  !> point at the target points, the peak stresses, the lowest frozen
  !> frequency and the shaking force at the samples (ev%mass and
  !> ev%link_stress allocated by the caller).
  subroutine design_results(self, mech, model, x_design, times, at_sample, at_point, q, ev)
    class(design_problem_t), intent(inout) :: self
    type(mechanism_t), intent(in) :: mech
    type(steady_model_t), intent(inout) :: model
    real(dp), intent(in) :: x_design(:), times(:), q(:, :)
    integer, intent(in) :: at_sample(:), at_point(:)
    type(design_eval_t), intent(inout) :: ev
    type(error_t) :: err
    real(dp), allocatable :: wn(:)
    type(tennant_stress_t), allocatable :: st(:)
    integer :: k, i, e, np
    real(dp) :: ra(2), rigid(2), flexible(2)
    real(dp), allocatable :: shake(:, :), moment(:, :), qs(:, :), qds(:, :), qdds(:, :), bear(:, :, :)
    logical :: shaking, bearing
    np = size(at_point)
    allocate(wn(model%n), st(size(model%el)))
    ev%lowest_frequency = huge(1.0_dp)
    if (np > 0) then
      ! the coupler point at the target crank angles, rigid and elastic
      allocate(ev%residual(2*np), ev%rigid_residual(2*np))
      ra = self%point_at(x_design)
      do k = 1, np
        call model%set_time(times(at_point(k)), err)
        if (err%failed()) then
          ev%reason = err%text()
          return
        end if
        call coupler_point_of(model, mech%links(self%path_link)%first_element, q(:, at_point(k)), ra(1), ra(2), &
                              rigid, flexible)
        ev%residual(2*k - 1:2*k) = flexible - [self%path_x(k), self%path_y(k)]
        ev%rigid_residual(2*k - 1:2*k) = rigid - [self%path_x(k), self%path_y(k)]
      end do
      ev%path_error = sum(ev%residual**2)
      ev%rigid_path_error = sum(ev%rigid_residual**2)
    end if
    shaking = self%is_shaking()
    if (shaking) allocate(shake(2, self%samples), moment(2, self%samples))
    bearing = self%is_bearing()
    if (bearing) then
      ! the rates at the samples by trigonometric interpolation (module joint_bearing)
      qs = q(:, at_sample)
      allocate(qds(model%n, self%samples), qdds(model%n, self%samples), &
               bear(2, size(self%bearing_joints), self%samples))
      call periodic_derivatives(qs, model%period(), qds, qdds)
    end if
    allocate(ev%sample_stress(self%samples, mech%n_links, 1), &
             ev%sample_deflection(self%samples, self%n_deflection_points(), 1), ev%sample_transmission(self%samples))
    ev%sample_transmission = 0.0_dp
    ev%sample_stress = 0.0_dp
    do k = 1, self%samples
      call model%set_time(times(at_sample(k)), err)
      if (.not. err%failed() .and. self%frequency_factor > 0.0_dp) call model%frozen_frequencies(wn, err)
      if (err%failed()) then
        ev%reason = err%text()
        return
      end if
      if (self%frequency_factor > 0.0_dp) ev%lowest_frequency = min(ev%lowest_frequency, wn(1))
      if (shaking) then
        shake(:, k) = rigid_momentum_rate(model, mech)
        moment(:, k) = elastic_first_moment(model, mech, q(:, at_sample(k)))
      end if
      if (bearing) bear(:, :, k) = bearing_forces(model, mech, self%bearing_joints, qs(:, k), qds(:, k), qdds(:, k))
      do i = 1, self%n_deflection_points()
        ev%sample_deflection(k, i, 1) = point_deflection(model, mech%links(self%deflection_link(i))%first_element, &
          mech%links(self%deflection_link(i))%n_elements, self%deflection_at(i), self%deflection_chord(i), &
          q(:, at_sample(k)))
      end do
      if (self%transmission_joint > 0) &
        ev%sample_transmission(k) = transmission_cosine(model, mech, self%transmission_joint)
      call model%stresses(q(:, at_sample(k)), st)
      do i = 1, mech%n_links
        do e = mech%links(i)%first_element, mech%links(i)%first_element + mech%links(i)%n_elements - 1
          ev%link_stress(i) = max(ev%link_stress(i), st(e)%max_abs_stress)
          ev%sample_stress(k, i, 1) = max(ev%sample_stress(k, i, 1), st(e)%max_abs_stress)
        end do
      end do
    end do
    if (shaking) then
      ! the deformation's share by trigonometric interpolation of its first
      ! moment over the revolution (module shaking_force)
      shake = shake + periodic_second_derivative(moment, model%period())
      ev%rms_shaking = sqrt(sum(shake**2)/self%samples)
      ev%peak_shaking = maxval(hypot(shake(1, :), shake(2, :)))
      if (self%is_minimax()) then
        ev%residual = hypot(shake(1, :), shake(2, :))
      else
        ev%residual = reshape(shake, [2*self%samples])/sqrt(real(self%samples, dp))
      end if
    end if
    if (bearing) then
      ev%rms_bearing = sqrt(sum(bear**2)/self%samples)
      ev%peak_bearing = maxval(hypot(bear(1, :, :), bear(2, :, :)))
      if (self%is_minimax()) then
        ev%residual = reshape(hypot(bear(1, :, :), bear(2, :, :)), [size(bear(1, :, :))])
      else
        ev%residual = reshape(bear, [size(bear)])/sqrt(real(self%samples, dp))
      end if
    end if
    ev%ok = ieee_is_finite(ev%mass) .and. all(ieee_is_finite(ev%link_stress)) .and. &
            all(ieee_is_finite(ev%sample_deflection)) .and. all(ieee_is_finite(ev%sample_transmission)) .and. &
            ieee_is_finite(ev%lowest_frequency) .and. ieee_is_finite(ev%path_error) .and. &
            ieee_is_finite(ev%rigid_path_error) .and. ieee_is_finite(ev%rms_shaking) .and. ieee_is_finite(ev%rms_bearing)
    if (.not. ev%ok) then
      ev%reason = 'the analysis gave a value that is not finite'
    else if (self%frequency_factor > 0.0_dp .and. .not. ev%lowest_frequency > 0.0_dp) then
      ! a negative omega^2 (signed) is a frozen configuration that buckles or
      ! diverges; its ln(factor omega / frequency) has no value (fuzz seed 13,
      ! case 2650: a bar 1e7 in long)
      ev%ok = .false.
      ev%reason = 'the lowest frozen natural frequency is not positive ('//str(ev%lowest_frequency)// &
                  ' rad/s): the frozen structure is unstable at this speed'
    end if
  end subroutine design_results

  !> The stress samples (k - 1) T / samples and the target points' times
  !> dgamma / omega (mod T), in one ascending list (the periodic orbit is
  !> integrated once through it).
  subroutine merged_times(self, omega, t, where_sample, where_point)
    class(design_problem_t), intent(in) :: self
    real(dp), intent(in) :: omega
    real(dp), allocatable, intent(out) :: t(:)
    integer, allocatable, intent(out) :: where_sample(:), where_point(:)
    real(dp), allocatable :: raw(:)
    integer, allocatable :: order(:)
    real(dp) :: tk, period
    integer :: j, m, ok_, np, nt
    np = 0
    if (self%is_path()) np = size(self%path_x)
    nt = self%samples + np
    period = 8.0_dp*atan(1.0_dp)/omega
    allocate(raw(nt), order(nt))
    do j = 1, self%samples
      raw(j) = real(j - 1, dp)*period/self%samples
    end do
    do j = 1, np
      raw(self%samples + j) = modulo(self%path_dgamma(j)/omega, period)
    end do
    ! insertion sort of the indices (nt is a few hundred at most)
    do j = 1, nt
      order(j) = j
    end do
    do j = 2, nt
      ok_ = order(j)
      tk = raw(ok_)
      m = j - 1
      do while (m >= 1)
        if (raw(order(m)) <= tk) exit
        order(m + 1) = order(m)
        m = m - 1
      end do
      order(m + 1) = ok_
    end do
    allocate(t(nt), where_sample(self%samples), where_point(np))
    do j = 1, nt
      t(j) = raw(order(j))
      if (order(j) <= self%samples) then
        where_sample(order(j)) = j
      else
        where_point(order(j) - self%samples) = j
      end if
    end do
  end subroutine merged_times

  !> The derivatives come from the periodic orbit's variational equations:
  !> asked for, and the evaluator is the exact periodic state.
  logical pure function variational_applies(self)
    class(design_problem_t), intent(in) :: self
    variational_applies = self%derivatives == 'variational' .and. self%evaluator == 'shooting'
  end function variational_applies

  !> Analysis constraints of an analysed design (analyse_design's order).
  function constraints_of(self, ev) result(g)
    class(design_problem_t), intent(in) :: self
    type(design_eval_t), intent(in) :: ev
    real(dp) :: g(self%n_analysis_constraints())
    g = self%constraints_at_peaks_of(ev, ev, pinned=.false.)
  end function constraints_of

  !> The analysis constraints of design ev.  pinned (the default): each
  !> peak (stress, deflection, transmission; peak_stress 'max' only) taken
  !> about the sample where base's is largest (at base itself: its peak): a
  !> forward difference from base then gives the derivative at base's
  !> largest sample, the one the variational derivative takes, not a chord
  !> across a switch of the largest sample.  Else the peaks of ev itself.
  !> Frequencies are the lowest over the samples either way.
  function constraints_at_peaks_of(self, ev, base, pinned) result(g)
    class(design_problem_t), intent(in) :: self
    type(design_eval_t), intent(in) :: ev, base
    logical, intent(in), optional :: pinned
    real(dp) :: g(self%n_analysis_constraints())
    logical :: pin
    integer :: i, l, s
    pin = self%peak_stress /= 'ks'              ! the KS aggregate is smooth: nothing to pin
    if (present(pinned)) pin = pin .and. pinned
    do i = 1, size(g)
      if (i == self%i_transmission) then
        g(i) = peak_constraint(ev%sample_transmission, base%sample_transmission, cos(self%transmission_min))
      else if (self%i_deflection > 0 .and. i >= self%i_deflection) then
        l = modulo(i - self%i_deflection, self%n_deflection_points()) + 1
        s = (i - self%i_deflection)/self%n_deflection_points() + 1
        g(i) = peak_constraint(ev%sample_deflection(:, l, s), base%sample_deflection(:, l, s), &
                               self%deflection_limit(l))
      else if (i <= self%n_stress) then
        l = modulo(i - 1, self%base%n_links) + 1
        s = (i - 1)/self%base%n_links + 1
        g(i) = peak_constraint(ev%sample_stress(:, l, s), base%sample_stress(:, l, s), self%stress_allowable)
      else if (ev%frequency_at(i - self%n_stress) > 0.0_dp) then
        g(i) = log(self%frequency_factor*abs(self%speeds(i - self%n_stress))/ev%frequency_at(i - self%n_stress))
      else
        g(i) = ieee_value(g(i), ieee_quiet_nan)   ! an unstable frozen structure (design_results refuses it)
      end if
    end do
  contains
    !> ln(peak of v / limit), the peak the largest of sample_peaks(v) (or
    !> the one about base's largest, pinned) or their KS aggregate in ln.
    real(dp) function peak_constraint(v, v_base, limit) result(gi)
      real(dp), intent(in) :: v(:), v_base(:), limit
      real(dp) :: p(size(v))
      p = sample_peaks(v, self%peak_interpolation)
      if (self%peak_stress == 'ks') then
        gi = ks_peak(log(max(p, tiny(1.0_dp))), self%ks_rho) - log(limit)
      else if (pin) then
        gi = log(max(p(maxloc(sample_peaks(v_base, self%peak_interpolation), dim=1)), tiny(1.0_dp))/limit)
      else
        gi = log(max(maxval(p), tiny(1.0_dp))/limit)
      end if
    end function peak_constraint
  end function constraints_at_peaks_of

  !> A forward difference from x to its neighbour xp: gp, the constraints at
  !> xp, with the transient evaluator's peak stresses taken at x's largest
  !> samples (constraints_at_peaks_of).  Its result is only within about
  !> 1e-6 of the orbit, so its step is 1e-3, long enough for the largest
  !> sample to switch often near an active constraint (example 1: a chord
  !> that is neither side's derivative; doc/design.md).  The other
  !> evaluators' differences keep the peak itself (steps 1e-4 and 1e-5).
  subroutine neighbour_constraints(self, x, xp, gp)
    class(design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), xp(:)
    real(dp), intent(inout) :: gp(:)
    type(design_eval_t) :: ev, evp
    if (self%evaluator /= 'transient') return
    call self%evaluate(x, ev)
    call self%evaluate(xp, evp)
    if (ev%ok .and. evp%ok) gp = self%constraints_at_peaks_of(evp, ev)
  end subroutine neighbour_constraints

  !> The peak of the periodic samples v > 0 (equally spaced over a
  !> revolution) about each sample.  'none': v itself.  'parabola': about
  !> sample k the largest, over half a spacing either side (t in
  !> [-1/2, 1/2] spacings), of the parabola through u = ln v at k-1, k, k+1
  !> (periodic wrap),
  !>     P(t) = u(k) + t (u(k+1) - u(k-1))/2 + t^2 (u(k-1) - 2 u(k) + u(k+1))/2,
  !> at its vertex t* = -P'(0)/P'' when concave and t* within the half
  !> spacings, else at the nearer end; returned as exp(P(t*)).  The largest
  !> of these is the peak of the piecewise-quadratic reading of ln v: at
  !> least the largest sample, exact for a Gaussian-shaped peak, and for a
  !> smooth peak at spacing d its error falls as d^4 (a symmetric peak)
  !> against the largest sample's d^2.  In ln because the constraints are
  !> ln(peak / limit) and a bump's logarithm is nearly a parabola (a peak
  !> exp(kappa (cos(theta) - 1)), kappa = 60, midway between 72 samples:
  !> the largest sample 5.6 % low, the parabola in v 1.2 %, in ln v 0.008 %).
  !> Each entry is continuous in the samples and, where the vertex reaches
  !> the end of its half spacing, differentiable (the slope is zero there),
  !> so the design derivative follows from the samples' by the chain rule.
  pure function sample_peaks(v, how) result(p)
    real(dp), intent(in) :: v(:)
    character(len=*), intent(in) :: how
    real(dp) :: p(size(v))
    real(dp) :: u(size(v)), slope, curvature, t
    integer :: k, n
    p = v
    if (how /= 'parabola' .or. size(v) < 3) return
    n = size(v)
    u = log(max(v, tiny(1.0_dp)))
    do k = 1, n
      slope = 0.5_dp*(u(modulo(k, n) + 1) - u(modulo(k - 2, n) + 1))
      curvature = u(modulo(k - 2, n) + 1) - 2.0_dp*u(k) + u(modulo(k, n) + 1)
      if (curvature < 0.0_dp) then
        t = max(-0.5_dp, min(0.5_dp, -slope/curvature))
      else
        t = sign(0.5_dp, slope)
      end if
      p(k) = exp(u(k) + t*(slope + 0.5_dp*curvature*t))
    end do
  end function sample_peaks

  !> |cos mu| at the current time, mu the angle between the rigid-body lines
  !> of the two links that meet at joint j (a four-bar's transmission angle
  !> at the coupler-rocker pin): |cos| leaves out which way each link points.
  real(dp) function transmission_cosine(model, mech, j) result(c)
    type(steady_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: j
    c = abs(cos(model%fs(mech%links(mech%joints(j)%link(1))%first_element)%phi - &
                model%fs(mech%links(mech%joints(j)%link(2))%first_element)%phi))
  end function transmission_cosine

  !> Elastic deflection, at the current time, of the point at the fraction
  !> at of a straight link (elements first .. first + n - 1) from its end 1:
  !> chord, the displacement across the link from the line through its
  !> deformed ends, |w(at) - (1 - at) w(0) - at w(1)| in the link's frame;
  !> else from the rigid position, |(u, w)(at)|.
  real(dp) function point_deflection(model, first, n, at, chord, q) result(d)
    type(steady_model_t), intent(in) :: model
    integer, intent(in) :: first, n
    real(dp), intent(in) :: at, q(:)
    logical, intent(in) :: chord
    real(dp) :: uwa(3), w1(3), w2(3), along
    integer :: e
    along = at*n
    e = min(int(along), n - 1)
    uwa = model%local_field(first + e, q, along - e)
    if (chord) then
      w1 = model%local_field(first, q, 0.0_dp)
      w2 = model%local_field(first + n - 1, q, 1.0_dp)
      d = abs(uwa(2) - (1.0_dp - at)*w1(2) - at*w2(2))
    else
      d = hypot(uwa(1), uwa(2))
    end if
  end function point_deflection

  !> The Kreisselmeier-Steinhauser aggregate of the values v over the samples,
  !>     KS = max v + ln(sum_k exp(rho (v_k - max v))) / rho,
  !> a smooth stand-in for max v (G. Kreisselmeier and R. Steinhauser,
  !> "Systematic control design by optimizing a vector performance index",
  !> IFAC Proc. 12 (1979) 113-117): max v <= KS <= max v + ln(N)/rho, the
  !> upper end when all N samples are equal; a peak that stands alone is
  !> overestimated by far less (samples within a few 1/rho of the peak count).
  !> Applied to v = ln(stress): a constraint KS <= ln(allowable) holds the
  !> peak stress under the allowable with a margin of at most ln(N)/rho.
  pure real(dp) function ks_peak(v, rho) result(ks)
    real(dp), intent(in) :: v(:), rho
    real(dp) :: vmax
    vmax = maxval(v)
    ks = vmax + log(sum(exp(rho*(v - vmax))))/rho
  end function ks_peak

  !> The objective's residuals of an analysed design (none for the mass).
  function residuals_of(self, ev) result(r)
    class(design_problem_t), intent(in) :: self
    type(design_eval_t), intent(in) :: ev
    real(dp), allocatable :: r(:)
    if (self%n_residuals_design() == 0) then
      allocate(r(0))
    else if (self%objective_kind == 'path_rigid') then
      r = ev%rigid_residual
    else
      r = ev%residual
    end if
  end function residuals_of

  !> Derivatives of the analysis constraints and of the objective's residuals
  !> with respect to x, dg(j, i) = dg_i/dx_j, dr(j, k) = dr_k/dx_j, from the
  !> sensitivities of the exact periodic orbit (module periodic_shooting,
  !> orbit_sensitivity) instead of differences of whole analyses: at each
  !> speed the design's periodic state (from its analysis, cached) and
  !> dq/dx_j along the orbit; then every result R(p, q) at the times is
  !> differentiated as the central difference
  !> (R(p + h_j, q + h_j dq_j) - R(p - h_j, q - h_j dq_j)) / (2 h_j), which
  !> re-evaluates no orbit (stresses, frequencies, shaking force, coupler
  !> point of the perturbed models only).  Counted as one analysis per speed
  !> (n_analyses; also n_sensitivity).  ok = .false. when the design cannot
  !> be analysed or a sensitivity solve fails (the caller then differences).
  subroutine derivatives_at(self, x, dg, dr, ok)
    class(design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), allocatable, intent(out) :: dg(:, :), dr(:, :)
    logical, intent(out) :: ok
    type(design_eval_t) :: ev
    type(design_eval_t), allocatable :: pm(:, :)
    real(dp), allocatable :: xc(:), h(:)
    integer, allocatable :: n_obj(:, :)
    real(dp), allocatable :: msq(:, :)
    integer :: j, side, s, nv
    real(dp) :: cpu0, cpu1
    nv = size(x)
    allocate(dg(nv, self%n_analysis_constraints()), dr(nv, self%n_residuals_design()))
    ok = .false.
    call self%evaluate(x, ev)
    if (.not. ev%ok .or. .not. allocated(ev%y_periodic) .or. ev%past_peak) return
    call cpu_time(cpu0)
    xc = clamped_x(self, x)
    h = self%variational_step*max(abs(xc), 1.0_dp)
    allocate(pm(2, nv), n_obj(2, nv), msq(2, nv))
    do j = 1, nv
      do side = 1, 2
        call start_join(self, self%base%n_links, pm(side, j), n_obj(side, j), msq(side, j))
      end do
    end do
    do s = 1, size(self%speeds)
      call speed_sensitivity(self, xc, h, s, ev%y_periodic(:, s), ev%monodromy(:, :, s), pm, n_obj, msq, ok)
      if (.not. ok) exit
    end do
    call cpu_time(cpu1)
    self%n_analyses = self%n_analyses + size(self%speeds)
    self%n_sensitivity = self%n_sensitivity + size(self%speeds)
    self%cpu_analyses = self%cpu_analyses + (cpu1 - cpu0)
    self%cpu_sensitivity = self%cpu_sensitivity + (cpu1 - cpu0)
    if (.not. ok) then
      self%n_sensitivity_fallbacks = self%n_sensitivity_fallbacks + 1
      return
    end if
    do j = 1, nv
      do side = 1, 2
        call close_join(self, ev%mass, pm(side, j), n_obj(side, j), msq(side, j))
      end do
      dg(j, :) = (self%constraints_of(pm(1, j)) - self%constraints_of(pm(2, j)))/(2.0_dp*h(j))
      dr(j, :) = (self%residuals_of(pm(1, j)) - self%residuals_of(pm(2, j)))/(2.0_dp*h(j))
    end do
    ok = all(ieee_is_finite(dg)) .and. all(ieee_is_finite(dr))
  end subroutine derivatives_at

  !> x with each variable's value inside its bounds (the design analysed).
  function clamped_x(self, x) result(xc)
    class(design_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: xc(size(x))
    integer :: i
    do i = 1, size(x)
      xc(i) = self%var(i)%to_x(min(max(self%var(i)%value(x(i)), self%var(i)%lower), self%var(i)%upper))
    end do
  end function clamped_x

  !> derivatives_at at speed s: the orbit's sensitivities (from the periodic
  !> state y0 and its monodromy matrix mono, both from the design's
  !> analysis), then the results of the perturbed designs pm(1, j) (x + h_j)
  !> and pm(2, j) (x - h_j) with q +- h_j dq_j, joined into the speeds'
  !> results.  A perturbed model of a variable that leaves the geometry
  !> alone (a section, a counterweight, the coupler point) takes its
  !> rigid-body frames from the design's model (steady_model's frames_of)
  !> instead of solving the same kinematics again.
  subroutine speed_sensitivity(self, xc, h, s, y0, mono, pm, n_obj, msq, ok)
    class(design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: xc(:), h(:), y0(:), mono(:, :)
    integer, intent(in) :: s
    type(design_eval_t), intent(inout) :: pm(:, :)
    integer, intent(inout) :: n_obj(:, :)
    real(dp), intent(inout) :: msq(:, :)
    logical, intent(out) :: ok
    type(mechanism_t) :: mech
    type(mechanism_t), allocatable :: mech_pm(:, :)
    type(steady_model_t), target :: model
    type(steady_model_t), allocatable, target :: plus(:), minus(:)
    type(shooting_report_t) :: rep
    type(error_t) :: err
    type(design_eval_t) :: one
    real(dp), allocatable :: times(:), q(:, :), dq(:, :, :), xs(:)
    integer, allocatable :: at_sample(:), at_point(:)
    integer :: j, side, nv
    ok = .false.
    nv = size(xc)
    allocate(plus(nv), minus(nv), mech_pm(2, nv))
    call build_design_model(self, at_speed(xc), mech, model, err)
    do j = 1, nv
      if (err%failed()) exit
      xs = xc
      xs(j) = xc(j) + h(j)
      call build_design_model(self, at_speed(xs), mech_pm(1, j), plus(j), err)
      xs(j) = xc(j) - h(j)
      if (.not. err%failed()) call build_design_model(self, at_speed(xs), mech_pm(2, j), minus(j), err)
    end do
    if (err%failed()) return
    do j = 1, nv
      if (.not. keeps_geometry(self%var(j))) cycle
      plus(j)%frames_of => model
      minus(j)%frames_of => model
    end do
    call merged_times(self, model%omega, times, at_sample, at_point)
    allocate(q(model%n, size(times)), dq(model%n, size(times), nv))
    call orbit_sensitivity(model, plus, minus, 2.0_dp*h, self%shooting, y0, times, q, dq, rep, err, monodromy=mono)
    self%sensitivity_rhs = self%sensitivity_rhs + rep%rhs_evaluations*(1 + 2*nv)
    if (err%failed()) return
    do j = 1, nv
      do side = 1, 2
        xs = xc
        xs(j) = xc(j) + merge(h(j), -h(j), side == 1)
        one = design_eval_t()
        one%mass = design_mass(at_speed(xs))
        allocate(one%link_stress(self%base%n_links))
        one%link_stress = 0.0_dp
        if (side == 1) then
          call design_results(self, mech_pm(1, j), plus(j), xs, times, at_sample, at_point, q + h(j)*dq(:, :, j), one)
        else
          call design_results(self, mech_pm(2, j), minus(j), xs, times, at_sample, at_point, q - h(j)*dq(:, :, j), one)
        end if
        if (.not. one%ok) return
        call join_speed(self, s, one, pm(side, j), n_obj(side, j), msq(side, j))
      end do
    end do
    ok = .true.
  contains
    !> The mechanism at design xs (values as given: a step past a bound is
    !> a step of the derivative) at speed s.
    function at_speed(xs) result(inp)
      real(dp), intent(in) :: xs(:)
      type(mechanism_input_t) :: inp
      inp = self%mechanism_at(xs, .false.)
      inp%omega = self%speeds(s)
    end function at_speed
  end subroutine speed_sensitivity

  !> A variable that changes no length, joint position or crank phase: the
  !> rigid-body motion of the linkage is the same with it changed.
  logical pure function keeps_geometry(v)
    type(design_variable_t), intent(in) :: v
    keeps_geometry = any(v%kind == [var_link_b, var_link_h, var_path_r, var_path_angle, var_cw_mass, var_cw_x, var_cw_y])
  end function keeps_geometry

  !> The previous design's periodic state at speed s (the start of this
  !> design's periodic solution), zeros at the first; n2 = 2 unknowns.
  function warm_start(self, n2, s) result(y0)
    class(design_problem_t), intent(inout) :: self
    integer, intent(in) :: n2, s
    real(dp) :: y0(n2)
    if (allocated(self%y_warm)) then
      if (size(self%y_warm, 1) /= n2) deallocate(self%y_warm)
    end if
    if (.not. allocated(self%y_warm)) then
      allocate(self%y_warm(n2, size(self%speeds)))
      self%y_warm = 0.0_dp
    end if
    y0 = self%y_warm(:, s)
  end function warm_start

  !> The transient evaluator: the planar transient model (Kear's element
  !> with the linear slender element's equations: rotary inertia as
  !> &tennant says, the coupling terms, the same damping) run to its
  !> periodic state from the previous design's (module periodic_transient);
  !> its unknowns, matched by name, returned in the steady model's order, so
  !> that stresses, frequencies, coupler point and shaking force are the
  !> steady model's for every evaluator.
  subroutine transient_samples(self, mech, model, s, times, q, err)
    class(design_problem_t), intent(inout) :: self
    type(mechanism_t), intent(in) :: mech
    type(steady_model_t), intent(in) :: model
    integer, intent(in) :: s
    real(dp), intent(in) :: times(:)
    real(dp), intent(out) :: q(:, :)
    type(error_t), intent(inout) :: err
    type(mechanism_model_t), target :: tmodel
    type(periodic_transient_report_t) :: rep
    real(dp), allocatable :: qt(:, :), y(:)
    integer :: to_steady(model%n)
    call tmodel%init_mechanism(mech, element_effects_t(rotary_inertia=self%element%rotary_inertia, coupling=.true.), &
                               'exact', self%element%damping_beta, err)
    if (err%failed()) return
    to_steady = 0
    if (tmodel%n == model%n) to_steady = matching_unknowns(tmodel%table%labels(), model%table%labels())
    if (any(to_steady == 0)) then
      call err%set('transient evaluator', 'the transient model''s unknowns do not match the steady model''s')
      return
    end if
    y = warm_start(self, 2*tmodel%n, s)
    allocate(qt(tmodel%n, size(times)))
    call transient_to_periodic(tmodel, self%transient, y, times, qt, rep, err)
    self%n_revolutions = self%n_revolutions + rep%revolutions
    if (err%failed()) return
    self%y_warm(:, s) = y
    q(to_steady, :) = qt
  end subroutine transient_samples

  !> The coupler point of a design: on a rigid, massless arm clamped to the
  !> link whose first element is e, at its end 1, at distance r and angle a
  !> from the element's line.  Rigid: from the rigid-body frame of the
  !> element at the current time; elastic: the end's translation (U, W,
  !> global) added and the arm turned by the end's slope w_x (T23).
  subroutine coupler_point_of(model, e, q, r, a, rigid, flexible)
    type(steady_model_t), intent(in) :: model
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:), r, a
    real(dp), intent(out) :: rigid(2), flexible(2)
    real(dp) :: qe(model%el(e)%nd), angle
    associate (fs => model%fs(e))
      angle = fs%phi + a
      rigid = [fs%x1 + r*cos(angle), fs%y1 + r*sin(angle)]
      qe = model%element_q(e, q)
      flexible = [fs%x1 + qe(1) + r*cos(angle + qe(3)), fs%y1 + qe(2) + r*sin(angle + qe(3))]
    end associate
  end subroutine coupler_point_of

  !> The same design, bit for bit (the cache key).
  logical pure function same_bits(a, b)
    real(dp), intent(in) :: a(:), b(:)
    same_bits = all(transfer(a, 1_int64, size(a)) == transfer(b, 1_int64, size(b)))
  end function same_bits

  !> F = mass / initial mass (no analysis needed), or the path error (sum of
  !> squared distances of the coupler point from the targets, elastic or
  !> rigid) / the initial one; NaN for a design that cannot be analysed (a
  !> failed trial for the optimizer).
  subroutine design_objective(self, x, f, err)
    class(design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    type(design_eval_t) :: ev
    if (err%failed()) return
    if (.not. self%has_residuals()) then
      f = design_mass(self%mechanism_at(x, .false.))/self%mass0
      return
    end if
    call self%evaluate(x, ev)
    if (.not. ev%ok) then
      f = ieee_value(f, ieee_quiet_nan)
    else
      f = objective_value(self, ev)/self%f0
    end if
  end subroutine design_objective

  !> Stress constraints, the frequency constraints, then the deflection
  !> constraints (NaN when the analysis failed).
  subroutine design_constraint(self, i, x, g, err)
    class(design_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    type(design_eval_t) :: ev
    if (err%failed()) return
    call self%evaluate(x, ev)
    if (.not. ev%ok) then
      g = ieee_value(g, ieee_quiet_nan)
    else
      block
        real(dp) :: all_g(self%n_analysis_constraints())
        all_g = self%constraints_of(ev)
        g = all_g(i)
      end block
    end if
  end subroutine design_constraint
end module design_problem
