!> The one door to ODEPACK's DLSODE.
!>
!> A model extends `ode_system_t` and implements `rhs` (and `jacobian` if it
!> wants MF = 21 or 24).  An `lsode_t` owns DLSODE's work arrays, the method
!> flag and tolerances, advances the model to output points, returns the work
!> counters and decodes every negative ISTATE into a sentence.
!>
!> DLSODE keeps its state in COMMON /DLS001/: it is not re-entrant, so only one
!> integration may be in progress at a time in a process (run independent
!> analyses in separate processes).  The model reaches the F77 callback through
!> a module-level pointer that is set for the duration of each DLSODE call.
!>
!> BDF with a user Jacobian (MF = 21, 24) on a model that supplies its own
!> Newton matrix (`has_newton_matrix`, `newton_factor`, `newton_solve`: e.g.
!> the mechanism model's banded elimination of I - h*el0*J) never forms J:
!> DLSODE's DPREPJ and DSOLSY are ours (module lsode_newton) and call the
!> model; DLSODE is then handed MF = 23 only so that its work array WM is N + 2
!> long.  `structured = .false.` in init forces DLSODE's own dense/banded J.
!>
!> A model whose RHS fails (e.g. mass matrix not positive definite) records the
!> error in `self%err` and returns; the shim then returns zero derivatives until
!> the current DLSODE call ends, and `integrate_to` reports the model's error.
module lsode_solver
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use name_table, only: name_of
  use lsode_messages, only: take_lsode_messages, clear_lsode_messages
  implicit none
  private
  public :: ode_system_t, lsode_t, lsode_counters_t
  public :: mf_adams, mf_bdf_full_user, mf_bdf_full_fd, mf_bdf_band_user, mf_bdf_band_fd
  public :: istate_sentence, mf_from_method, method_names
  public :: active, active_newton_is_model
  public :: max_steps_ceiling, max_steps_reason
  public :: rhs_f77, jac_f77

  !> Method names accepted in decks, and the DLSODE method flag each means.
  character(len=*), parameter :: method_names = 'adams (MF=10), bdf (21), bdf_fd (22), bdf_band (24), bdf_band_fd (25)'

  integer, parameter :: mf_adams = 10          !< nonstiff, Adams, functional iteration
  integer, parameter :: mf_bdf_full_user = 21  !< stiff, BDF, user full Jacobian
  integer, parameter :: mf_bdf_full_fd = 22    !< stiff, BDF, finite-difference full Jacobian
  integer, parameter :: mf_bdf_band_user = 24  !< stiff, BDF, user banded Jacobian
  integer, parameter :: mf_bdf_band_fd = 25    !< stiff, BDF, finite-difference banded Jacobian

  !> The largest step limit per output interval (MXSTEP) a deck may ask for:
  !> 1e7 steps are minutes of CPU for the smallest model (3 us per step), and
  !> a run that needs more is stiff for its method or needs shorter intervals.
  integer, parameter :: max_steps_ceiling = 10000000
  character(len=*), parameter :: max_steps_reason = 'DLSODE steps per output interval; beyond 1e7 a '// &
    'run is stiff for its method (use bdf) or needs a shorter output interval'

  !> A first-order system y' = f(t, y).  Extend it to carry the model.
  !> The system's own Newton matrix (has_newton_matrix, newton_factor,
  !> newton_solve) may set how long DLSODE keeps one: jacobian_steps, the most
  !> steps with one matrix (DLSODE's MSBP, set by our DPREPJ; 0: DLSODE's 20;
  !> a system whose Jacobian ages fast, as a turning mechanism's, asks for
  !> fewer), and jacobian_contraction, the contraction factor of the chord
  !> iteration the matrix may reach before it is re-formed (0: the age limit
  !> alone; when positive our DPREPJ/DSOLSY measure the contraction and
  !> shorten the age limit, jacobian_steps being then the longest age; module
  !> lsode_newton).  A model sets both when it is built.
  type, abstract :: ode_system_t
    type(error_t) :: err          !< set by rhs/jacobian when the model cannot go on
    real(dp) :: t_failed = 0.0_dp !< time at which err was first set
    integer :: jacobian_steps = 0
    real(dp) :: jacobian_contraction = 0.0_dp
  contains
    procedure(rhs_interface), deferred :: rhs
    procedure :: jacobian => jacobian_not_provided
    procedure :: has_newton_matrix
    procedure :: newton_factor => newton_factor_not_provided
    procedure :: newton_solve => newton_solve_not_provided
    procedure :: fail
    procedure :: stop_time
  end type ode_system_t

  abstract interface
    subroutine rhs_interface(self, t, y, ydot)
      import :: ode_system_t, dp
      class(ode_system_t), intent(inout) :: self
      real(dp), intent(in) :: t, y(:)
      real(dp), intent(out) :: ydot(:)
    end subroutine rhs_interface
  end interface

  !> Work done so far (DLSODE's IWORK(11:14)), plus CPU seconds in DLSODE calls.
  type :: lsode_counters_t
    integer :: steps = 0
    integer :: rhs_evals = 0
    integer :: jac_evals = 0
    integer :: lu_factorizations = 0  !< one per Jacobian evaluation for BDF, none for Adams
    integer :: order_last = 0
    real(dp) :: step_last = 0.0_dp
    real(dp) :: cpu_seconds = 0.0_dp
    logical :: model_newton = .false. !< the system's own Newton matrix stood in for DLSODE's
  end type lsode_counters_t

  type :: lsode_t
    integer :: neq = 0
    integer :: mf = mf_adams
    integer :: ml = 0, mu = 0          !< half-bandwidths for MF = 24/25
    logical :: structured = .true.     !< use the system's own Newton matrix when it has one (MF 21/24)
    logical :: model_newton = .false.  !< this integration uses it (decided at each fresh start)
    integer, private :: mf_dlsode = mf_adams    !< the MF DLSODE is handed (23 for the model's Newton matrix)
    integer :: max_steps = 20000       !< per output interval (DLSODE's MXSTEP)
    integer, private :: max_order = 0  !< DLSODE's MAXORD (0: its default); kept across work reallocations
    real(dp) :: rtol = 1.0e-6_dp
    real(dp), allocatable :: atol(:)
    real(dp) :: t = 0.0_dp             !< current time
    integer :: istate = 1
    real(dp), allocatable, private :: rwork(:)   !< DLSODE's work arrays, sized for mf_dlsode
    integer, allocatable, private :: iwork(:)
    real(dp) :: cpu_seconds = 0.0_dp
    integer, private :: done_before(3) = 0      !< steps, RHS and Jacobian evaluations before the last restart
  contains
    procedure :: init
    procedure :: limit_order
    procedure :: integrate_to
    procedure :: counters
    procedure :: restart
    procedure :: dense_output
  end type lsode_t

  !> ODEPACK's F77 callbacks: the right-hand side and the Jacobian (DLSODE's
  !> F and JAC, passed on to DPREPJ and DSOLSY, module lsode_newton).
  abstract interface
    subroutine rhs_f77(neq, t, y, ydot)
      import :: dp
      integer, intent(in) :: neq(*)
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(out) :: ydot(*)
    end subroutine rhs_f77
    subroutine jac_f77(neq, t, y, ml, mu, pd, nrowpd)
      import :: dp
      integer, intent(in) :: neq(*), ml, mu, nrowpd
      real(dp), intent(in) :: t, y(*)
      real(dp), intent(inout) :: pd(nrowpd, *)
    end subroutine jac_f77
  end interface

  interface
    subroutine dlsode(f, neq, y, t, tout, itol, rtol, atol, itask, istate, iopt, &
                      rwork, lrw, iwork, liw, jac, mf)
      import :: dp, rhs_f77, jac_f77
      procedure(rhs_f77) :: f
      procedure(jac_f77) :: jac
      integer, intent(in) :: neq(*), itol, itask, iopt, lrw, liw, mf
      real(dp), intent(inout) :: y(*), t
      real(dp), intent(in) :: tout, rtol(*), atol(*)
      integer, intent(inout) :: istate, iwork(liw)
      real(dp), intent(inout) :: rwork(lrw)
    end subroutine dlsode
    !> DLSODE's interpolant of the last step (K-th derivative at t; YH = RWORK(21), NYH = NEQ)
    subroutine dintdy(t, k, yh, nyh, dky, iflag)
      import :: dp
      integer, intent(in) :: k, nyh
      real(dp), intent(in) :: t, yh(nyh, *)
      real(dp), intent(out) :: dky(*)
      integer, intent(out) :: iflag
    end subroutine dintdy
  end interface

  !> The system DLSODE is integrating (set for the duration of each call), and
  !> whether its own Newton matrix stands in for J (read by lsode_newton).
  class(ode_system_t), pointer, protected :: active => null()
  logical, protected :: active_newton_is_model = .false.

contains

  ! ------------------------------------------------------------------ model side

  ! The defaults below refuse: the arguments the binding's interface gives
  ! them and they do not need are named in an empty associate block (the
  ! project's idiom for an argument a fixed interface imposes: no warning,
  ! no code).

  !> Default: a model that does not supply an analytic Jacobian.
  subroutine jacobian_not_provided(self, t, y, ml, mu, pd)
    class(ode_system_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    associate (unused_y => y, unused_ml => ml, unused_mu => mu, unused_pd => pd)
    end associate
    call self%fail(t, 'this model supplies no analytic Jacobian; use MF = 22 or 25')
  end subroutine jacobian_not_provided

  !> Default: no Newton matrix of its own (DLSODE forms I - h*el0*J from J).
  logical function has_newton_matrix(self)
    class(ode_system_t), intent(in) :: self
    associate (unused_self => self)
    end associate
    has_newton_matrix = .false.
  end function has_newton_matrix

  !> Form and factor P = I - hl0 J at (t, y), hl0 = h*el0 of DLSODE's step;
  !> ok = .false. when P is singular (DLSODE then cuts the step).
  subroutine newton_factor_not_provided(self, t, y, hl0, ok)
    class(ode_system_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:), hl0
    logical, intent(out) :: ok
    associate (unused_y => y, unused_hl0 => hl0)
    end associate
    ok = .false.
    call self%fail(t, 'this model supplies no Newton matrix of its own')
  end subroutine newton_factor_not_provided

  !> x := P^-1 x with the P of the last newton_factor.
  subroutine newton_solve_not_provided(self, x)
    class(ode_system_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    x = 0.0_dp
    call self%fail(0.0_dp, 'this model supplies no Newton matrix of its own')
  end subroutine newton_solve_not_provided

  !> Record the first failure of the model at time t.
  subroutine fail(self, t, message)
    class(ode_system_t), intent(inout) :: self
    real(dp), intent(in) :: t
    character(len=*), intent(in) :: message
    if (self%err%failed()) return
    call self%err%set('', message)
    self%t_failed = t
  end subroutine fail

  !> Where a run that failed stopped: the model's own failure carries its
  !> time; a stop of DLSODE's is at the solver's time t_solver.
  pure real(dp) function stop_time(self, t_solver)
    class(ode_system_t), intent(in) :: self
    real(dp), intent(in) :: t_solver
    stop_time = merge(self%t_failed, t_solver, self%err%failed())
  end function stop_time

  ! ------------------------------------------------------------------ F77 shims

  subroutine rhs_shim(neq, t, y, ydot)
    integer, intent(in) :: neq(*)
    real(dp), intent(in) :: t, y(*)
    real(dp), intent(out) :: ydot(*)
    if (active%err%failed()) then
      ydot(1:neq(1)) = 0.0_dp
      return
    end if
    call active%rhs(t, y(1:neq(1)), ydot(1:neq(1)))
    if (active%err%failed()) ydot(1:neq(1)) = 0.0_dp
  end subroutine rhs_shim

  subroutine jac_shim(neq, t, y, ml, mu, pd, nrowpd)
    integer, intent(in) :: neq(*), ml, mu, nrowpd
    real(dp), intent(in) :: t, y(*)
    real(dp), intent(inout) :: pd(nrowpd, *)
    if (active%err%failed()) return
    call active%jacobian(t, y(1:neq(1)), ml, mu, pd(1:nrowpd, 1:neq(1)))
  end subroutine jac_shim

  ! ------------------------------------------------------------------ solver side

  !> Prepare for a new problem of `neq` equations starting at t0.  `atol` is a
  !> scalar or a vector of length neq.
  subroutine init(self, neq, t0, mf, rtol, atol, err, ml, mu, max_steps, structured)
    class(lsode_t), intent(inout) :: self
    integer, intent(in) :: neq, mf
    real(dp), intent(in) :: t0, rtol, atol(:)
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: ml, mu, max_steps
    logical, intent(in), optional :: structured
    if (neq < 1) then
      call err%set('lsode init', 'number of equations must be positive, got '//str(neq))
      return
    end if
    if (all(mf /= [10, 21, 22, 24, 25])) then
      call err%set('lsode init', 'method flag MF must be 10, 21, 22, 24 or 25, got '//str(mf))
      return
    end if
    if (.not. (rtol >= 0.0_dp) .or. any(.not. (atol >= 0.0_dp)) .or. (rtol <= 0.0_dp .and. all(atol <= 0.0_dp))) then
      call err%set('lsode init', 'tolerances must be non-negative and not all zero (rtol = '//str(rtol)//')')
      return
    end if
    if (size(atol) /= 1 .and. size(atol) /= neq) then
      call err%set('lsode init', 'atol must have 1 or '//str(neq)//' entries, got '//str(size(atol)))
      return
    end if
    self%neq = neq
    self%mf = mf
    self%rtol = rtol
    self%atol = atol
    self%ml = 0
    self%mu = 0
    if (present(ml)) self%ml = ml
    if (present(mu)) self%mu = mu
    if (present(max_steps)) self%max_steps = max_steps
    if ((mf == 24 .or. mf == 25) .and. (self%ml < 0 .or. self%mu < 0 .or. self%ml >= neq .or. self%mu >= neq)) then
      call err%set('lsode init', 'band half-widths must satisfy 0 <= ml, mu < neq, got ml = ' &
                   //str(self%ml)//', mu = '//str(self%mu))
      return
    end if
    if (present(structured)) self%structured = structured
    self%model_newton = .false.
    if (allocated(self%rwork)) deallocate(self%rwork, self%iwork)   ! a new problem: no optional inputs kept
    call allocate_work(self, mf)
    self%t = t0
    self%istate = 1
    self%cpu_seconds = 0.0_dp
    self%done_before = 0
  end subroutine init

  !> DLSODE's work arrays for the method flag it will be handed (sizes from
  !> the DLSODE documentation: LRW = 20 + 16 NEQ for MF = 10, 22 + 9 NEQ + LWM
  !> with LWM = NEQ**2, NEQ or (2 ML + MU + 1) NEQ for MITER = 1-2, 3, 4-5).
  subroutine allocate_work(self, mf_dlsode)
    type(lsode_t), intent(inout) :: self
    integer, intent(in) :: mf_dlsode
    integer :: lrw, liw, neq, iopt_int(3)
    real(dp) :: iopt_real(3)
    neq = self%neq
    ! DLSODE's optional inputs (IWORK(5:7) MAXORD, MXSTEP, MXHNIL; RWORK(5:7)
    ! H0, HMAX, HMIN), which a caller may have set, survive a reallocation
    iopt_int = 0
    iopt_real = 0.0_dp
    if (allocated(self%iwork)) then
      iopt_int = self%iwork(5:7)
      iopt_real = self%rwork(5:7)
    end if
    select case (mod(mf_dlsode, 10))
    case (0)
      lrw = 20 + 16*neq
      liw = 20
    case (1, 2)
      lrw = 22 + 9*neq + neq**2
      liw = 20 + neq
    case (3)
      lrw = 22 + 10*neq
      liw = 20
    case default
      lrw = 22 + 10*neq + (2*self%ml + self%mu)*neq
      liw = 20 + neq
    end select
    self%mf_dlsode = mf_dlsode
    if (allocated(self%rwork)) deallocate(self%rwork, self%iwork)
    allocate(self%rwork(lrw), self%iwork(liw))
    self%rwork = 0.0_dp
    self%iwork = 0
    self%iwork(1) = self%ml
    self%iwork(2) = self%mu
    self%iwork(5:7) = iopt_int
    self%rwork(5:7) = iopt_real
    self%iwork(6) = self%max_steps
    if (self%max_order > 0) self%iwork(5) = self%max_order
  end subroutine allocate_work

  !> DLSODE's MAXORD (its optional input IWORK(5)) for this and every later
  !> integration of the problem set up by init; 0 restores DLSODE's default.
  subroutine limit_order(self, max_order)
    class(lsode_t), intent(inout) :: self
    integer, intent(in) :: max_order
    self%max_order = max_order
    if (allocated(self%iwork)) self%iwork(5) = max_order
  end subroutine limit_order

  !> Start afresh from the current (t, y) on the next call, e.g. after a
  !> discontinuity in the model.  DLSODE's counters restart from zero; counters()
  !> adds those of the integrations before.
  subroutine restart(self)
    class(lsode_t), intent(inout) :: self
    if (self%istate /= 1 .and. allocated(self%iwork)) self%done_before = self%done_before + self%iwork(11:13)
    self%istate = 1
  end subroutine restart

  !> The solution at t within the last step (DLSODE's interpolant, DINTDY
  !> with K = 0): dense output for locating events.
  subroutine dense_output(self, t, y, err)
    class(lsode_t), intent(in) :: self
    real(dp), intent(in) :: t
    real(dp), intent(out) :: y(:)
    type(error_t), intent(inout) :: err
    integer :: iflag
    ! DLSODE's Nordsieck history starts at RWORK(21), NYH = NEQ (its documentation)
    call dintdy(t, 0, self%rwork(21:), self%neq, y, iflag)
    if (iflag /= 0) call err%set('DLSODE dense output', 't = '//str(t)//' is outside the last step')
  end subroutine dense_output

  !> Advance `sys` from the current time to `tout`; y holds the state in and out.
  !> With one_step, DLSODE takes one step towards tout and never passes it
  !> (ITASK = 5, TCRIT = tout): the caller examines every step (events).
  subroutine integrate_to(self, sys, y, tout, err, one_step)
    class(lsode_t), intent(inout) :: self
    class(ode_system_t), intent(inout), target :: sys
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: tout
    type(error_t), intent(inout) :: err
    logical, intent(in), optional :: one_step
    class(ode_system_t), pointer :: previous
    logical :: previous_model_newton
    integer :: itol, neq(1), itask
    real(dp) :: cpu0, cpu1
    if (.not. allocated(self%rwork)) then
      call err%set('lsode', 'integrate_to called before init')
      return
    end if
    if (size(y) /= self%neq) then
      call err%set('lsode', 'state has '//str(size(y))//' entries, solver was set up for '//str(self%neq))
      return
    end if
    itol = 1
    if (size(self%atol) > 1) itol = 2
    neq(1) = self%neq
    if (self%istate == 1) then
      ! a fresh start: the Newton matrix's route may change (its work array with it)
      self%model_newton = self%structured .and. (self%mf == mf_bdf_full_user .or. self%mf == mf_bdf_band_user) &
                          .and. sys%has_newton_matrix()
      if (self%model_newton .and. self%mf_dlsode /= 23) call allocate_work(self, 23)
      if (.not. self%model_newton .and. self%mf_dlsode /= self%mf) call allocate_work(self, self%mf)
    end if
    call clear_lsode_messages()
    previous => active
    previous_model_newton = active_newton_is_model
    active => sys
    active_newton_is_model = self%model_newton
    call cpu_time(cpu0)
    itask = 1
    if (present(one_step)) then
      if (one_step) then
        itask = 5
        self%rwork(1) = tout
      end if
    end if
    ! IOPT = 1 so that MXSTEP (iwork(6)) is honoured.
    call dlsode(rhs_shim, neq, y, self%t, tout, itol, [self%rtol], self%atol, itask, self%istate, 1, &
                self%rwork, size(self%rwork), self%iwork, size(self%iwork), jac_shim, self%mf_dlsode)
    call cpu_time(cpu1)
    active => previous
    active_newton_is_model = previous_model_newton
    self%cpu_seconds = self%cpu_seconds + (cpu1 - cpu0)
    if (sys%err%failed()) then
      call err%set('', sys%err%text()//' (at t = '//str(sys%t_failed)//')')
      return
    end if
    if (self%istate < 0) then
      call err%set('DLSODE', istate_sentence(self%istate, self%mf)//' (at t = '//str(self%t)// &
                   '; LSODE says: '//take_lsode_messages()//')', code=self%istate)
    end if
  end subroutine integrate_to

  function counters(self) result(c)
    class(lsode_t), intent(in) :: self
    type(lsode_counters_t) :: c
    if (.not. allocated(self%iwork)) return
    c%steps = self%done_before(1) + self%iwork(11)
    c%rhs_evals = self%done_before(2) + self%iwork(12)
    c%jac_evals = self%done_before(3) + self%iwork(13)
    c%order_last = self%iwork(14)
    c%step_last = self%rwork(11)
    if (self%mf /= mf_adams) c%lu_factorizations = c%jac_evals
    c%cpu_seconds = self%cpu_seconds
    c%model_newton = self%model_newton
  end function counters

  !> Method flag for a deck's method name; 0 when the name is unknown.
  pure integer function mf_from_method(name) result(mf)
    character(len=*), intent(in) :: name
    select case (trim(name))
    case ('adams')
      mf = mf_adams
    case ('bdf')
      mf = mf_bdf_full_user
    case ('bdf_fd')
      mf = mf_bdf_full_fd
    case ('bdf_band')
      mf = mf_bdf_band_user
    case ('bdf_band_fd')
      mf = mf_bdf_band_fd
    case default
      mf = 0
    end select
  end function mf_from_method

  !> DLSODE's ISTATE on return, as a sentence a user can act on.
  function istate_sentence(istate, mf) result(s)
    integer, intent(in) :: istate, mf
    character(len=:), allocatable :: s
    ! ISTATE = -6 .. 2 (0 is never returned)
    character(len=*), parameter :: sentences(9) = [character(len=122) :: &
      'a component of the error weight vanished (pure relative error control, atol = 0, ' &   ! -6
      //'on a solution component that became zero)', &
      'repeated corrector convergence failures on one step: the Jacobian may be wrong or ' &   ! -5
      //'the tolerances inappropriate', &
      'repeated error-test failures on one step: the solution may have a singularity or ' &    ! -4
      //'the model produced inaccurate derivatives', &
      'illegal input detected by DLSODE (see its message)', &                                  ! -3
      'excess accuracy requested: rtol/atol are too small for machine precision; loosen them', & ! -2
      'excess work done: the step limit for one output interval was reached before TOUT', &    ! -1
      '', &                                                                                    ! 0
      'nothing was done: TOUT equals T', &                                                     ! 1
      'integration successful']                                                                ! 2
    s = name_of(sentences, istate, -6, 'unknown ISTATE '//str(istate))
    if (istate /= -1) return
    if (mf == mf_adams) then
      s = s//'; the problem is probably stiff for the Adams method (MF=10): use a BDF method ' &
            //'(method = ''bdf'', MF=21, or ''bdf_fd'', MF=22)'
    else
      s = s//'; raise max_steps or shorten the output interval'
    end if
  end function istate_sentence
end module lsode_solver
