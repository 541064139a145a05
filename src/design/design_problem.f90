!> Optimal design of a flexible mechanism with the nonlinear analysis in the
!> loop (paper L, FORMULATION.md §1): an optimization problem whose every
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
  use harmonic_solver, only: harmonic_settings_t, harmonic_report_t, harmonic_solve, harmonic_diagnosis
  use periodic_shooting, only: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit, &
                               shooting_diagnosis
  implicit none
  private
  public :: design_problem_t, design_variable_t, design_eval_t, parse_variable
  public :: var_link_b, var_link_h, var_link_length, var_joint_x, var_joint_y

  integer, parameter :: cache_size = 256
  integer, parameter :: var_link_b = 1, var_link_h = 2, var_link_length = 3, var_joint_x = 4, var_joint_y = 5

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
    real(dp), allocatable :: link_stress(:)     !< peak |stress| over the revolution, per link
    real(dp) :: lowest_frequency = 0.0_dp       !< lowest frozen natural frequency over the revolution
    real(dp) :: cpu_seconds = 0.0_dp
  end type design_eval_t

  type, extends(opt_problem_t) :: design_problem_t
    type(mechanism_input_t) :: base               !< the deck's mechanism
    type(design_variable_t), allocatable :: var(:)
    character(len=16) :: evaluator = 'shooting'   !< 'shooting' (exact periodic) or 'harmonic'
    type(harmonic_settings_t) :: harmonic
    type(shooting_settings_t) :: shooting
    type(tennant_options_t) :: element
    type(link_sections_t) :: sections(max_links)
    integer :: samples = 72                       !< crank angles per revolution for stresses and frequencies
    real(dp) :: stress_allowable = 0.0_dp         !< 0: no stress constraints
    real(dp) :: frequency_factor = 0.0_dp         !< 0: no frequency constraint
    real(dp) :: mass0 = 1.0_dp                    !< mass of the initial design
    integer :: n_stress = 0, i_frequency = 0      !< constraint numbering (stress 1..n_stress, then frequency)
    ! ---- bookkeeping
    integer :: n_analyses = 0, n_failed = 0
    real(dp) :: cpu_analyses = 0.0_dp
    real(dp), allocatable :: cache_x(:, :)        !< designs analysed lately (ring of cache_size)
    type(design_eval_t), allocatable :: cache(:)
    integer :: cache_used = 0, cache_next = 1
    real(dp), allocatable :: y_warm(:)            !< last periodic state (shooting start)
    character(len=:), allocatable :: last_failure
  contains
    procedure :: setup
    procedure :: n_analysis_constraints
    procedure :: mechanism_at
    procedure :: evaluate
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
    open_at = index(word, '(')
    close_at = index(word, ')')
    if (open_at < 2 .or. close_at < open_at + 2) return
    select case (word(1:open_at - 1))
    case ('link_b')
      v%kind = var_link_b
    case ('link_h')
      v%kind = var_link_h
    case ('link_length')
      v%kind = var_link_length
    case ('joint_x')
      v%kind = var_joint_x
    case ('joint_y')
      v%kind = var_joint_y
    case default
      return
    end select
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
    n = size(self%var)
    self%n_stress = 0
    if (self%stress_allowable > 0.0_dp) self%n_stress = self%base%n_links
    self%i_frequency = 0
    if (self%frequency_factor > 0.0_dp) self%i_frequency = self%n_stress + 1
    call self%init_problem(name, n, 0, self%n_analysis_constraints())
    do i = 1, self%m
      call self%set_general_constraint(i)
    end do
    self%n_analyses = 0
    self%n_failed = 0
    self%cpu_analyses = 0.0_dp
    if (allocated(self%cache_x)) deallocate(self%cache_x, self%cache)
    allocate(self%cache_x(n, cache_size), self%cache(cache_size))
    self%cache_used = 0
    self%cache_next = 1
    ! mass of the initial design, the objective's scale
    self%mass0 = 1.0_dp
    self%mass0 = max(design_mass(self%mechanism_at(x_start, .false.)), tiny(1.0_dp))
  end subroutine setup

  integer pure function n_analysis_constraints(self)
    class(design_problem_t), intent(in) :: self
    n_analysis_constraints = self%n_stress + merge(1, 0, self%i_frequency > 0)
  end function n_analysis_constraints

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

  real(dp) function design_mass(inp) result(mass)
    type(mechanism_input_t), intent(in) :: inp
    mass = sum(link_masses(inp))
  end function design_mass

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
    call analyse_design(self, self%mechanism_at(x, .true.), ev)
    call cpu_time(cpu1)
    ev%cpu_seconds = cpu1 - cpu0
    self%n_analyses = self%n_analyses + 1
    self%cpu_analyses = self%cpu_analyses + ev%cpu_seconds
    if (.not. ev%ok) then
      self%n_failed = self%n_failed + 1
      self%last_failure = ev%reason
    end if
    self%cache_x(:, self%cache_next) = x
    self%cache(self%cache_next) = ev
    self%cache_used = max(self%cache_used, self%cache_next)
    self%cache_next = modulo(self%cache_next, cache_size) + 1
  end subroutine evaluate

  !> One steady-state analysis: build, periodic response, stresses and frozen
  !> frequencies at `samples` crank angles.
  subroutine analyse_design(self, inp, ev)
    class(design_problem_t), intent(inout) :: self
    type(mechanism_input_t), intent(in) :: inp
    type(design_eval_t), intent(out) :: ev
    type(mechanism_t) :: mech
    type(steady_model_t), target :: model
    type(error_t) :: err
    type(harmonic_report_t) :: hrep
    type(shooting_report_t) :: srep
    real(dp), allocatable :: times(:), q(:, :), qd(:, :), y0(:), wn(:)
    type(tennant_stress_t), allocatable :: st(:)
    integer :: k, i, e
    ev%ok = .false.
    ev%mass = design_mass(inp)
    allocate(ev%link_stress(inp%n_links))
    ev%link_stress = 0.0_dp
    call build_mechanism(inp, mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, self%element, self%sections, err)
    if (err%failed()) then
      ev%reason = 'the design is not a valid mechanism: '//err%text()
      return
    end if
    allocate(times(self%samples), q(model%n, self%samples), wn(model%n), st(size(model%el)))
    do k = 1, self%samples
      times(k) = real(k - 1, dp)*model%period()/self%samples
    end do
    if (self%evaluator == 'harmonic') then
      call harmonic_solve(model, self%harmonic, times, q, hrep, err)
      if (.not. err%failed()) call harmonic_diagnosis(self%harmonic, hrep, model%omega, .false., .false., err)
    else
      allocate(qd(model%n, self%samples), y0(2*model%n))
      y0 = 0.0_dp
      if (allocated(self%y_warm)) then
        if (size(self%y_warm) == size(y0)) y0 = self%y_warm
      end if
      call shooting_solve(model, self%shooting, y0, srep, err)
      if (.not. err%failed()) call shooting_diagnosis(self%shooting, srep, model%omega, .false., err)
      if (.not. err%failed()) call periodic_orbit(model, self%shooting, y0, times, q, qd, srep, err)
      if (.not. err%failed()) self%y_warm = y0
    end if
    if (err%failed()) then
      ev%reason = err%text()
      return
    end if
    ev%lowest_frequency = huge(1.0_dp)
    do k = 1, self%samples
      call model%set_time(times(k), err)
      if (.not. err%failed() .and. self%frequency_factor > 0.0_dp) call model%frozen_frequencies(wn, err)
      if (err%failed()) then
        ev%reason = err%text()
        return
      end if
      if (self%frequency_factor > 0.0_dp) ev%lowest_frequency = min(ev%lowest_frequency, wn(1))
      call model%stresses(q(:, k), st)
      do i = 1, mech%n_links
        do e = mech%links(i)%first_element, mech%links(i)%first_element + mech%links(i)%n_elements - 1
          ev%link_stress(i) = max(ev%link_stress(i), st(e)%max_abs_stress)
        end do
      end do
    end do
    ev%ok = ieee_is_finite(ev%mass) .and. all(ieee_is_finite(ev%link_stress)) .and. &
            ieee_is_finite(ev%lowest_frequency)
    if (.not. ev%ok) ev%reason = 'the analysis gave a value that is not finite'
  end subroutine analyse_design

  !> The same design, bit for bit (the cache key).
  logical pure function same_bits(a, b)
    real(dp), intent(in) :: a(:), b(:)
    same_bits = all(transfer(a, 1_int64, size(a)) == transfer(b, 1_int64, size(b)))
  end function same_bits

  !> F = mass / initial mass (no analysis needed); NaN for a design that is
  !> not a mechanism (a failed trial for the optimizer).
  subroutine design_objective(self, x, f, err)
    class(design_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    if (err%failed()) return
    f = design_mass(self%mechanism_at(x, .false.))/self%mass0
  end subroutine design_objective

  !> Stress constraints, then the frequency constraint (NaN when the analysis failed).
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
    else if (i <= self%n_stress) then
      g = log(max(ev%link_stress(i), tiny(1.0_dp))/self%stress_allowable)
    else
      g = log(self%frequency_factor*abs(self%base%omega)/ev%lowest_frequency)
    end if
  end subroutine design_constraint
end module design_problem
