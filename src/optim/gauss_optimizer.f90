!> The Gauss family of optimizers (papers P and B; doc/optimization.md) as one class.
!>
!>   gauss              unconstrained Gauss method, no line search (B12, P2)
!>   gauss_constrained  linear constraints, closed-form multipliers (Paradis & Willmert, P16, P17)
!>   gnlc               quadratic constraints, B10 with B11 by Newton (Powell fallback),
!>                      step-back (B13); feasible start, every iterate feasible
!>   gnlc_ns            the same without step-back; any start (GNLC.NS)
!>   gnlc_general       general nonlinear constraints with Potter's modifications
!>                      (§9.5): quadratic re-approximation at every iterate, actual
!>                      constraints in B11; step-back as in gnlc
!>   gnlc_general_ns    the same without step-back (Potter's fix (b), tried by Boston)
!>
!> Every iteration costs one analysis (no line search), so NF = NI + 1; on
!> bounds-only problems a projected Newton point rejected by Armijo's test
!> costs one more (projected_point).
!>
!> Convergence (the papers state no test; ours, see doc/optimization.md): at
!> x_k, after the step s_k and the multipliers have been computed,
!>   (1) every constraint holds: max(g_i, |h_j|) <= feas_tol;
!>   (2) the multiplier equations hold to the feasibility tolerance
!>       (max |m_i| <= feas_tol) and every inequality multiplier is >= 0
!>       (drop rule, §9.4);
!>   (3) the step is small: ||s_k||_inf <= xtol (1 + ||x_k||_inf), or
!>   (3') F is resolved (f_resolved): with the exact model the step cannot
!>       change F measurably (Gill, Murray & Wright's U1-U3);
!>   (4) the predicted change of the Lagrangian is small:
!>       |(grad F + C lambda)^T s + s^T G s / 2| <= ftol (1 + |F(x_k)|).
!> (4) uses the Lagrangian, not F: at a constrained optimum grad F = -C lambda
!> is large, and grad F^T s would only measure how closely B11 was solved.
!> A zero step with solved multiplier equations is exactly the KKT system at
!> x_k, so the test costs no analysis beyond the one that produced x_k.
module gauss_optimizer
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower
  use name_table, only: name_of, code_of
  use linalg, only: lu_factor, lu_solve, cholesky_factor, symmetric_eigenvalues
  use optim_problem, only: opt_problem_t, con_linear, con_general, con_kind_name
  use multiplier_equations, only: multiplier_system_t, multiplier_result_t, multiplier_system, gauss_step, &
                                  linear_multipliers
  use feasibility_restoration, only: restore_feasibility
  implicit none
  private
  public :: gauss_optimizer_t, gauss_options_t, gauss_iterate_t
  public :: method_gauss, method_gauss_constrained, method_gnlc, method_gnlc_ns
  public :: method_gnlc_general, method_gnlc_general_ns, method_auto
  public :: method_from_name, method_name, method_names
  public :: hessian_auto, hessian_gauss, hessian_exact, hessian_bfgs, hessian_from_name, hessian_name
  public :: status_not_run, status_converged, status_max_iter, status_failed
  public :: glob_none, glob_filter, globalization_from_name, globalization_name, globalization_names
  public :: set_text, tolerance_band

  integer, parameter :: method_gauss = 1, method_gauss_constrained = 2, method_gnlc = 3, &
                        method_gnlc_ns = 4, method_gnlc_general = 5, method_gnlc_general_ns = 6, method_auto = 7
  character(len=*), parameter :: method_names = &
    "'auto', 'gauss', 'gauss_constrained', 'gnlc', 'gnlc_ns', 'gnlc_general', 'gnlc_general_ns'"
  integer, parameter :: hessian_auto = 0, hessian_gauss = 1, hessian_exact = 2, hessian_bfgs = 3
  !> the names of method_gauss .. method_auto and hessian_auto .. hessian_exact
  character(len=*), parameter :: method_table(7) = [character(len=17) :: 'gauss', 'gauss_constrained', 'gnlc', &
    'gnlc_ns', 'gnlc_general', 'gnlc_general_ns', 'auto']
  character(len=*), parameter :: hessian_table(4) = [character(len=5) :: 'auto', 'gauss', 'exact', 'bfgs']
  !> step acceptance: none (the papers' methods as printed) or the filter line search (step_acceptable)
  integer, parameter :: glob_none = 0, glob_filter = 1
  character(len=*), parameter :: globalization_table(2) = [character(len=6) :: 'none', 'filter']
  character(len=*), parameter :: globalization_names = "'filter', 'none'"
  integer, parameter :: max_backtracks = 3   !< halvings of a step the filter rejects before a shifted step
  integer, parameter :: max_shifts = 12      !< Levenberg shifts of G after rejected steps, x10 each
  real(dp), parameter :: filter_gamma = 1.0e-5_dp, armijo_eta = 1.0e-4_dp
  integer, parameter :: status_not_run = -1, status_converged = 0, status_max_iter = 1, status_failed = 2
  integer, parameter :: max_halvings = 60    !< of a step whose trial point gives a non-finite value
  !> outcomes of next_point
  integer, parameter :: found_trial = 0, found_converged = 1, found_limit = 2, found_projected = 3

  type :: gauss_options_t
    integer :: method = method_auto       !< auto: chosen from the problem (see check_setup); solve
                                          !< leaves the method used here
    integer :: hessian = hessian_auto     !< auto: 2JJ^T for sums of squares, exact otherwise;
                                          !< bfgs: the exact one at x_0, then damped BFGS updates
    integer :: max_iter = 50
    real(dp) :: xtol = 1.0e-8_dp          !< step test (3)
    real(dp) :: ftol = 1.0e-12_dp         !< predicted-change test (4)
    real(dp) :: feas_tol = 1.0e-8_dp      !< constraint tolerance: active |g| <= tol, violated g > tol
    real(dp) :: mult_tol = 1.0e-8_dp      !< drop if lambda_j |c_j| < -mult_tol |grad F|
    real(dp) :: rcond_min = 1.0e-13_dp    !< G with smaller reciprocal condition number is singular
    real(dp) :: regularization = 0.0_dp   !< > 0: add mu I to a singular G, mu = this * max |G_ii|
    logical :: auto_regularize = .true.   !< regularization = 0 and G singular: choose mu (see curvature);
                                          !< .false.: stop with the diagnosis
    integer :: newton_max_iter = 30       !< Newton iterations for B11 before Powell takes over
    logical :: potter_repeat = .true.     !< on step-back cycling repeat the step with the violated
                                          !< constraints active (Potter's fix (a)); else stop
    logical :: hold_bounds = .true.       !< simple bounds as bounds (held variables in the step); .false.:
                                          !< as unit-gradient linear constraints of the active set
    logical :: step_back_refine = .true.  !< step back to the boundary (farthest feasible point, P);
                                          !< .false.: one B13 interpolation, feasible side kept
    logical :: projected_newton = .true.  !< bounds only: Bertsekas' projected Newton point P(x + s_B) tried
                                          !< first, accepted by Armijo's test (see projected_point)
    integer :: globalization = glob_filter !< glob_none: every trial point accepted (the papers' methods)
    real(dp) :: stat_tol = 1.0e-4_dp      !< first-order test (5): |grad L|_inf <= stat_tol max(1, |grad F|_inf)
  end type gauss_options_t

  !> One row of the iteration log: the state after iteration k.
  type :: gauss_iterate_t
    integer :: k = 0
    integer :: nf = 0
    real(dp) :: f = 0.0_dp
    real(dp) :: max_violation = 0.0_dp
    real(dp) :: step = 0.0_dp                 !< ||x_k - x_{k-1}||_inf
    real(dp), allocatable :: x(:)
    real(dp), allocatable :: lambda(:)        !< multipliers of the step that produced x_k
    logical, allocatable :: active(:)         !< active set used for the next step
    character(len=:), allocatable :: events   !< drops, additions, step-back, Powell, ...
  end type gauss_iterate_t

  type :: gauss_optimizer_t
    type(gauss_options_t) :: opts
    ! ---- outcome
    integer :: status = status_not_run
    character(len=:), allocatable :: message
    integer :: iterations = 0                  !< NI
    real(dp) :: f = 0.0_dp
    real(dp), allocatable :: x(:)
    real(dp), allocatable :: g(:)              !< constraints at x (inequalities, then equalities)
    real(dp), allocatable :: lambda(:)         !< multipliers at x (0 off the active set)
    logical, allocatable :: active(:)
    real(dp) :: kkt_residual = 0.0_dp          !< ||grad F + Sum lambda_j c_j||_inf at x
    character(len=:), allocatable :: final_events   !< drops etc. during the final test
    logical :: have_best = .false.             !< a feasible iterate was seen
    real(dp), allocatable :: x_best(:)
    real(dp) :: f_best = 0.0_dp
    integer :: k_best = 0
    ! ---- event counts
    integer :: newton_solves = 0, powell_fallbacks = 0, drops = 0, additions = 0
    integer :: step_backs = 0, regularizations = 0, potter_repeats = 0, releases = 0
    integer :: restorations = 0                !< feasibility restorations (Gauss steps on the violation)
    integer :: backtracks = 0                  !< trial points rejected by the filter (each one analysis)
    integer :: kkt_refusals = 0                !< steps whose test passed but a first-order condition failed
    real(dp) :: stationarity = 0.0_dp          !< |grad F + C lambda|_inf / max(1, |grad F|_inf) at the end
    real(dp) :: min_multiplier = 0.0_dp        !< smallest scaled inequality multiplier lambda_i |c_i| / |grad F|
    ! ---- iteration log
    integer :: n_log = 0
    type(gauss_iterate_t), allocatable :: log(:)
    ! ---- working state at x_k
    real(dp), allocatable, private :: phi(:), gradf(:), jac(:, :), gm(:, :), dg(:, :), hess(:, :, :)
    logical, allocatable, private :: have_hess(:)
    character(len=:), allocatable, private :: ev
    logical, private :: last_solved = .true.    !< B11 of the previous step solved (multipliers meaningful)
    logical, private :: first_order_start = .false.  !< next B11 starts from least-squares multipliers
    logical, private :: restored_now = .false.  !< x_new is a restored point (no cycling test: it may be an iterate)
    logical, private :: off_chord = .false.     !< x_new is no fraction of s (restoration, Levenberg arc)
    logical :: quasi_newton = .false.          !< G is the damped BFGS matrix (set at the first curvature)
    integer :: bfgs_updates = 0                !< BFGS updates of G (damped ones included)
    real(dp), allocatable, private :: bq(:, :), xq(:), gq(:)   !< BFGS matrix, x and grad F of its last update
    real(dp), allocatable, private :: filter(:, :)   !< (F_j, h_j) pairs the filter holds
    integer, private :: n_filter = 0
    real(dp), private :: h_max = 0.0_dp         !< largest violation a trial point may have
  contains
    procedure :: solve
    procedure :: method_label
    procedure :: reset
    procedure, private :: check_setup
    procedure, private :: start
    procedure, private :: add_to_active
    procedure, private :: release_satisfied
    procedure, private :: curvature
    procedure, private :: start_bfgs
    procedure, private :: bfgs_update
    procedure, private :: model_rcond
    procedure, private :: rank_text
    procedure, private :: make_convex
    procedure, private :: compute_step
    procedure, private :: derivatives
    procedure, private :: finish
    procedure, private :: f_resolved
    procedure, private :: next_point
    procedure, private :: kkt_converged
    procedure, private :: trial_point
    procedure, private :: step_for_set
    procedure, private :: limit_violated
    procedure, private :: flip_released
    procedure, private :: restoration
    procedure, private :: arc_step
    procedure, private :: first_order_multipliers
    procedure, private :: note_b11
    procedure, private :: step_back
    procedure, private :: analyse_trial
    procedure, private :: check_cycling
    procedure, private :: append_log
    procedure, private :: note
    procedure, private :: projected_point
    procedure, private :: step_acceptable
    procedure, private :: first_order_ok
  end type gauss_optimizer_t

contains

  ! ================================================================ names

  !> 'gnlc.ns' (B's spelling) is read as 'gnlc_ns'; 0 for an unknown name.
  integer function method_from_name(name) result(method)
    character(len=*), intent(in) :: name
    if (lower(trim(adjustl(name))) == 'gnlc.ns') then
      method = method_gnlc_ns
    else
      method = code_of(method_table, name, method_gauss, 0)
    end if
  end function method_from_name

  function method_name(method) result(name)
    integer, intent(in) :: method
    character(len=:), allocatable :: name
    name = name_of(method_table, method, method_gauss, 'unknown')
  end function method_name

  !> A blank name is 'auto'; -1 for an unknown name.
  integer function hessian_from_name(name) result(h)
    character(len=*), intent(in) :: name
    if (len_trim(name) == 0) then
      h = hessian_auto
    else
      h = code_of(hessian_table, name, hessian_auto, -1)
    end if
  end function hessian_from_name

  !> 'none' or 'filter'; -1 for an unknown name, a blank name is 'filter'.
  integer function globalization_from_name(name) result(g)
    character(len=*), intent(in) :: name
    if (len_trim(name) == 0) then
      g = glob_filter
    else
      g = code_of(globalization_table, name, glob_none, -1)
    end if
  end function globalization_from_name

  function globalization_name(g) result(name)
    integer, intent(in) :: g
    character(len=:), allocatable :: name
    name = name_of(globalization_table, g, glob_none, 'unknown')
  end function globalization_name

  function hessian_name(h) result(name)
    integer, intent(in) :: h
    character(len=:), allocatable :: name
    name = name_of(hessian_table, h, hessian_auto, 'auto')
  end function hessian_name

  function method_label(self) result(name)
    class(gauss_optimizer_t), intent(in) :: self
    character(len=:), allocatable :: name
    name = method_name(self%opts%method)
  end function method_label

  !> "{1, 3}" for the true entries (1-based).
  function set_text(mask) result(s)
    logical, intent(in) :: mask(:)
    character(len=:), allocatable :: s
    integer :: i
    s = '{'
    do i = 1, size(mask)
      if (mask(i)) then
        if (len(s) > 1) s = s//', '
        s = s//str(i)
      end if
    end do
    s = s//'}'
  end function set_text

  ! ================================================================ driver

  !> Minimise prob from x0.  On return status, x, f, lambda, active and the
  !> log describe the run.  err is set (code 2 for inconsistent input, 1
  !> otherwise) when the run did not converge: the message says why, and the
  !> best feasible iterate stays in x_best / f_best.  err reports this run
  !> only: an error left in it by an earlier call is cleared first (it would
  !> otherwise reach the problem's procedures and be blamed on them).
  !> The outer iteration of Gauss/GNLC/GNLC.NS (B, P): derivatives at x_k,
  !> the step and its trial point (next_point: multipliers, drop or add,
  !> step-back, convergence test), the cycling checks, the analysis of x_{k+1}.
  subroutine solve(self, prob, x0, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout), target :: prob
    real(dp), intent(in) :: x0(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: s(:), x_new(:), g_new(:), gm_k(:, :)
    logical, allocatable :: active_k(:)
    integer :: n, mt, k, hess_kind, stalls, escapes, regs, outcome, shifts, i
    real(dp) :: xnorm, snorm, t, mu
    logical :: step_back_method, auto, exact_model, refused, restored
    character(len=:), allocatable :: stage

    call err%clear()
    call self%reset()
    auto = self%opts%method == method_auto
    call self%check_setup(prob, x0, hess_kind, err)
    if (err%failed()) then
      self%message = err%text()
      return
    end if
    n = prob%n
    mt = prob%m + prob%n_eq
    step_back_method = any(self%opts%method == [method_gauss_constrained, method_gnlc, method_gnlc_general])
    call self%start(prob, x0, step_back_method, auto, err)
    if (err%failed()) return
    allocate(s(n), x_new(n), g_new(mt), gm_k(n, n), active_k(size(self%active)))

    k = 0
    stalls = 0
    escapes = 0
    shifts = 0
    mu = 0.0_dp
    outcome = found_limit
    outer: do
      stage = 'iteration '//str(k + 1)
      if (shifts == 0) then
        ! ---- derivatives and curvature at x_k
        regs = self%regularizations
        call self%derivatives(prob, hess_kind, k, err)
        if (err%failed()) exit outer
        exact_model = hess_kind /= hessian_gauss .and. .not. self%quasi_newton .and. self%regularizations == regs
        gm_k = self%gm
        active_k = self%active
      else
        ! the working set of x_k: what the rejected trial added or dropped
        ! belongs to a point that was not accepted (HS 84: strictly satisfied
        ! members, added at rejected points, pulled to zero by B11, made
        ! every later trial worse)
        self%active = active_k
        ! ---- the filter rejected the step from x_k: G + mu I (Levenberg), mu x10 per rejection
        mu = merge(1.0e-2_dp*max(1.0_dp, maxval([(abs(gm_k(i, i)), i=1, n)])), 10.0_dp*mu, shifts == 1)
        self%gm = gm_k
        do i = 1, n
          self%gm(i, i) = self%gm(i, i) + mu
        end do
        self%regularizations = self%regularizations + 1
        exact_model = .false.
        call self%note('G + mu I after a rejected step, mu = '//str(mu, 3))
      end if
      self%have_hess = .false.
      xnorm = maxval(abs(self%x))

      call self%next_point(prob, k, exact_model, xnorm, step_back_method, s, snorm, x_new, g_new, t, outcome, err)
      if (err%failed() .or. outcome == found_converged .or. outcome == found_limit) exit outer
      if (outcome == found_projected) then       ! analysed already
        k = k + 1
        self%iterations = k
        call self%append_log(prob, k, maxval(abs(self%log(self%n_log)%x - self%x)))
        cycle outer
      end if

      ! ---- cycling and stalls (issue 11): a trial point that returns to one
      ! of the last iterates.  Back to an earlier one: damp the step (halved
      ! per detection, 3 times); then, or when the run keeps repeating x_k
      ! (3 steps below xtol in a row without convergence), stop with the
      ! diagnosis instead of spending analyses on the same designs
      call self%check_cycling(prob, x_new, g_new, t, xnorm, stalls, escapes, err)
      if (err%failed()) exit outer
      if (stalls > 0) then           ! no progress while infeasible: restoration
        if (self%restoration(prob, .true., step_back_method, x_new, g_new, t, err)) stalls = 0
        if (err%failed()) exit outer
      end if

      ! ---- accept x_{k+1}: one analysis; a non-finite F is a failed trial,
      ! never a value: step back to the midpoint and analyse again
      call self%analyse_trial(prob, x_new, g_new, t, snorm, step_back_method, refused, err)
      if (err%failed()) exit outer
      if (refused) then
        shifts = shifts + 1
        ! infeasible and no acceptable step: the restoration phase (once per run)
        restored = .false.
        if (shifts >= 3) restored = self%restoration(prob, .true., step_back_method, x_new, g_new, t, err)
        if (restored) then
          call self%analyse_trial(prob, x_new, g_new, t, snorm, step_back_method, refused, err)
          if (err%failed()) exit outer
          shifts = 0
          k = k + 1
          self%iterations = k
          call self%append_log(prob, k, t*snorm)
          cycle outer
        end if
        if (err%failed()) exit outer
        if (shifts <= max_shifts) cycle outer
        call err%set('filter', 'no acceptable point from x_k = '//vec_text(self%x)//': every trial point, '// &
          'also with G + mu I up to mu = '//str(mu, 3)//', increased F without reducing the violation enough (F(x_k) = ' &
          //str(self%f, 8)//', violation '//str(max_violation(self%g, prob%m), 3)//')')
        exit outer
      end if
      shifts = 0
      k = k + 1
      self%iterations = k
      call self%append_log(prob, k, t*snorm)
    end do outer

    if (err%failed()) then
      call err%add_context(self%method_label()//', '//stage)
      self%status = status_failed
      self%message = err%text()
      return
    end if
    call self%finish(k, outcome == found_converged, mt, err)
  end subroutine solve

  !> One iteration's step from x_k: B10/B11 for the step s and the
  !> multipliers, the convergence test (kkt_converged), then the trial point
  !> x_new = x_k + t s (trial_point: step-back, additions), or the restored
  !> point or the Levenberg arc's where the run is stuck.  A zero-length step
  !> (x_new = x_k bit for bit) costs no analysis: with a changed active set
  !> the step is recomputed at x_k; with the same set the next iteration
  !> would repeat this one exactly.  outcome: found_trial (x_new, g_new, t,
  !> snorm = |s|), found_converged, found_limit (max_iter reached), or
  !> found_projected (bounds only: Bertsekas' projected Newton point, already
  !> analysed, is x_{k+1}).  snorm keeps its value where a restoration at
  !> the start gives the point without a step.
  subroutine next_point(self, prob, k, exact_model, xnorm, step_back_method, s, snorm, x_new, g_new, t, outcome, &
                        err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout), target :: prob
    integer, intent(in) :: k
    logical, intent(in) :: exact_model
    real(dp), intent(in) :: xnorm
    logical, intent(inout) :: step_back_method
    real(dp), intent(inout), contiguous :: s(:)       !< contiguous as compute_step's: no copy in and out
    real(dp), intent(inout) :: snorm, x_new(:), g_new(:), t
    integer, intent(out) :: outcome
    type(error_t), intent(inout) :: err
    integer :: mt, repeats, jdrop, i
    real(dp) :: b11_res, maxviol, shift
    logical :: refused(prob%m + prob%n_eq)
    logical :: solved, same_point, again
    logical, allocatable :: active_before(:), active_iter(:)
    mt = prob%m + prob%n_eq
    outcome = found_trial
    repeats = 0
    refused = .false.
    shift = 0.0_dp
    allocate(active_iter, source=self%active)
    do
      if (k > 0 .and. repeats == 0) then     ! a violation no Newton step can reach
        if (self%restoration(prob, .false., step_back_method, x_new, g_new, t, err)) return
        if (err%failed()) return
      end if
      active_before = self%active
      call self%compute_step(prob, s, solved, b11_res, err)
      if (err%failed()) return
      self%last_solved = solved
      snorm = maxval(abs(s))
      maxviol = max_violation(self%g, prob%m)
      if (self%kkt_converged(s, snorm, xnorm, maxviol, b11_res, mt, exact_model)) then
        ! the first-order conditions (first_order_ok) before "converged": a
        ! negative multiplier leaves the set and the step is recomputed
        if (self%first_order_ok(prob, jdrop)) then
          outcome = found_converged
          return
        end if
        self%kkt_refusals = self%kkt_refusals + 1
        if (jdrop > 0 .and. repeats < 2*mt + 8) then
          repeats = repeats + 1
          self%active(jdrop) = .false.
          self%drops = self%drops + 1
          call self%note('first-order test: multiplier of '//str(jdrop)//' negative (lambda = '// &
                         str(self%lambda(jdrop), 4)//'): dropped, step recomputed')
          if (refused(jdrop)) then
            ! dropped before and taken back by the step: the model is not
            ! convex along the released direction; a Levenberg shift turns
            ! the step towards -grad L, into the feasible side
            shift = 10.0_dp*max(shift, 0.1_dp*max(1.0_dp, maxval([(abs(self%gm(i, i)), i=1, size(self%gm, 1))])))
            do i = 1, size(self%gm, 1)
              self%gm(i, i) = self%gm(i, i) + shift
            end do
            self%regularizations = self%regularizations + 1
            call self%note('released constraint taken back by the step: G + mu I, mu = '//str(shift, 3))
          end if
          refused(jdrop) = .true.
          cycle
        end if
        call self%note('first-order test failed (|grad L| / max(1, |grad F|) = '//str(self%stationarity, 3)// &
                       ', smallest scaled multiplier '//str(self%min_multiplier, 3)//'): iteration goes on')
      end if
      if (k >= self%opts%max_iter) then
        outcome = found_limit
        return
      end if
      ! bounds only: Bertsekas' projected Newton point first (an analysis)
      if (self%opts%projected_newton .and. .not. step_back_method .and. repeats == 0) then
        if (self%projected_point(prob, s, err)) then
          outcome = found_projected
          return
        end if
        if (err%failed()) return
      end if

      call self%trial_point(prob, s, snorm, xnorm, k, step_back_method, solved, x_new, g_new, t, repeats, &
                            again, err)
      if (err%failed()) return
      if (again) cycle
      same_point = maxval(abs(x_new - self%x)) <= 0.0_dp
      if (same_point .and. any(self%active .neqv. active_before) .and. repeats < 2*mt) then
        repeats = repeats + 1
        call self%note('zero-length step: recomputed at x_k with the new active set')
        cycle
      end if
      if (same_point) then
        if (self%arc_step(prob, step_back_method, active_iter, x_new, g_new, t, err)) return
        if (err%failed()) return
        if (self%restoration(prob, .true., step_back_method, x_new, g_new, t, err)) return
        if (err%failed()) return
        call err%set(self%method_label(), 'zero-length step at iteration '//str(k + 1)//' with the active set ' &
          //set_text(self%active)//' unchanged: the next iteration would repeat this one (max violation ' &
          //str(maxviol, 3)//', B11 residual '//str(b11_res, 3)//'); stopped without another analysis')
      end if
      return
    end do
  end subroutine next_point

  !> The convergence test at x_k (module header) for the step s just
  !> computed (snorm = ||s||_inf) and its multipliers: (1) feasible (maxviol,
  !> the largest violation at x_k), (2) B11 solved (residual b11_res), (4)
  !> the Lagrangian's predicted change small, and (3) the step small or (3')
  !> F resolved; mt constraints in all.
  logical function kkt_converged(self, s, snorm, xnorm, maxviol, b11_res, mt, exact_model) result(ok)
    class(gauss_optimizer_t), intent(in) :: self
    real(dp), intent(in) :: s(:), snorm, xnorm, maxviol, b11_res
    integer, intent(in) :: mt
    logical, intent(in) :: exact_model
    real(dp) :: pred
    pred = dot_product(self%gradf, s) + 0.5_dp*dot_product(s, matmul(self%gm, s))
    if (mt > 0) pred = pred + dot_product(matmul(self%dg, self%lambda), s)
    ok = maxviol <= self%opts%feas_tol .and. b11_res <= self%opts%feas_tol &
         .and. abs(pred) <= self%opts%ftol*(1.0_dp + abs(self%f)) &
         .and. (snorm <= self%opts%xtol*(1.0_dp + xnorm) .or. self%f_resolved(snorm, xnorm, exact_model) &
                .or. f_settled())
  contains
    !> (3''), with the filter only: F has settled, the last two accepted
    !> steps changed it by less than ftol (1 + |F|) and Gill, Murray &
    !> Wright's U3 holds.  A minimum where G is singular (HS 46: (x4 - 1)^4,
    !> (x5 - 1)^6) is approached linearly, the step stays far above xtol,
    !> and G is regularized so (3') never applies.
    logical function f_settled() result(done)
      real(dp) :: glag
      done = .false.
      if (self%opts%globalization == glob_none .or. self%n_log < 3) return
      if (abs(self%log(self%n_log - 2)%f - self%f) > self%opts%ftol*(1.0_dp + abs(self%f))) return
      glag = maxval(abs(self%gradf))
      if (size(self%lambda) > 0) glag = maxval(abs(self%gradf + matmul(self%dg, self%lambda)))
      done = glag <= self%opts%ftol**(1.0_dp/3.0_dp)*(1.0_dp + abs(self%f))
    end function f_settled
  end function kkt_converged

  !> The first-order conditions at x_k with the multipliers just computed
  !> (feasibility and the B11 residual are tested by kkt_converged): (5)
  !> stationarity |grad F + C lambda|_inf <= stat_tol max(1, |grad F|_inf),
  !> C the gradients of every constraint (bounds included), and (6) the sign
  !> of every active inequality and bound multiplier, lambda_i |c_i| >=
  !> -mult_tol |grad F| (the drop rule's threshold).  jdrop: the most
  !> negative one (0 if none).  Both measures stay in stationarity and
  !> min_multiplier for the summary.
  logical function first_order_ok(self, prob, jdrop) result(ok)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    integer, intent(out) :: jdrop
    real(dp) :: gnorm, crit, thresh
    integer :: i
    gnorm = maxval(abs(self%gradf))
    if (size(self%lambda) > 0) then
      self%stationarity = maxval(abs(self%gradf + matmul(self%dg, self%lambda)))/max(1.0_dp, gnorm)
    else
      self%stationarity = gnorm/max(1.0_dp, gnorm)
    end if
    thresh = self%opts%mult_tol*norm2(self%gradf)
    jdrop = 0
    self%min_multiplier = 0.0_dp
    do i = 1, prob%m
      if (.not. self%active(i)) cycle
      crit = self%lambda(i)*norm2(self%dg(:, i))
      if (crit < self%min_multiplier) then
        self%min_multiplier = crit
        if (crit < -thresh) jdrop = i
      end if
    end do
    self%min_multiplier = self%min_multiplier/max(1.0_dp, norm2(self%gradf))
    ok = jdrop == 0 .and. self%stationarity <= self%opts%stat_tol
  end function first_order_ok

  !> Test (3'), the alternative to the step test (3) (Gill, Murray & Wright,
  !> Practical Optimization (1981) §8.2.3, criteria U1-U3 with tau_F = ftol):
  !> F at x_k is converged when the next step cannot change it measurably.
  !> The caller has checked (1), (2) and (4) (the model's predicted change of
  !> the Lagrangian below ftol (1 + |F|), U1 for the step still to be taken);
  !> here U2, ||s||_inf <= sqrt(ftol) (1 + ||x||_inf), the resolution of x
  !> that F known to ftol allows, and U3, ||grad L||_inf <= ftol^(1/3)
  !> (1 + |F|), the first-order conditions.  Only with the exact model (G
  !> neither regularized nor convexified at x_k): a shifted G shortens the
  !> step and its prediction without x being near a solution.  HS 9 ended one
  !> analysis later at a step of 1.95e-6 > xtol (1 + |x|) = 1.33e-6 with F
  !> already optimal to 1.4e-13.
  logical function f_resolved(self, snorm, xnorm, exact_model) result(ok)
    class(gauss_optimizer_t), intent(in) :: self
    real(dp), intent(in) :: snorm, xnorm
    logical, intent(in) :: exact_model
    real(dp) :: glag
    ok = .false.
    if (.not. exact_model .or. snorm > sqrt(self%opts%ftol)*(1.0_dp + xnorm)) return
    if (size(self%lambda) > 0) then
      glag = maxval(abs(self%gradf + matmul(self%dg, self%lambda)))
    else
      glag = maxval(abs(self%gradf))
    end if
    ok = glag <= self%opts%ftol**(1.0_dp/3.0_dp)*(1.0_dp + abs(self%f))
  end function f_resolved

  !> Outcome of a run that did not fail: KKT residual, status and message
  !> (the iteration limit sets err with the best feasible iterate).
  subroutine finish(self, k, converged, mt, err)
    class(gauss_optimizer_t), intent(inout) :: self
    integer, intent(in) :: k, mt
    logical, intent(in) :: converged
    type(error_t), intent(inout) :: err
    self%final_events = self%ev                 ! events of the last step computation (the test)
    if (mt > 0) self%kkt_residual = maxval(abs(self%gradf + matmul(self%dg, self%lambda)))
    if (mt == 0) self%kkt_residual = maxval(abs(self%gradf))
    if (converged) then
      self%status = status_converged
      self%message = 'converged after '//str(k)//' iterations'
    else
      self%status = status_max_iter
      if (self%have_best) then
        self%message = 'iteration limit reached (max_iter = '//str(self%opts%max_iter)// &
          ') without convergence; best feasible iterate: k = '//str(self%k_best)//', F = '//str(self%f_best)
      else
        self%message = 'iteration limit reached (max_iter = '//str(self%opts%max_iter)// &
          ') without convergence; no feasible iterate was found'
      end if
      call err%set(self%method_label(), self%message)
    end if
  end subroutine finish

  !> Feasibility restoration (ours; the papers have none).  GNLC.NS is
  !> infeasible at x_k and stuck (stuck: a zero-length step with the same
  !> active set, or a stall), or a violated constraint is out of Newton's
  !> reach (HS 23 at the origin, where grad F = 0 and the violated circles
  !> have zero gradients).  The constraint violation is minimised by Gauss
  !> steps from the least violated iterate (module feasibility_restoration:
  !> constraint evaluations only, no analysis); from the feasible point the run
  !> continues with the step-back variant (GNLC, Potter's GNLC with general
  !> constraints), which keeps every iterate feasible and so cannot fall
  !> back onto the point it left.  Once per run.  .true.: x_new, g_new hold
  !> the restored point, to be analysed as x_{k+1}.
  logical function restoration(self, prob, stuck, step_back_method, x_new, g_new, t, err) result(done)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    logical, intent(in) :: stuck
    logical, intent(inout) :: step_back_method
    real(dp), intent(out) :: x_new(:), g_new(:), t
    type(error_t), intent(inout) :: err
    integer :: i, j, m, steps
    logical :: ok
    real(dp) :: maxviol, reach
    done = .false.
    m = prob%m
    maxviol = max_violation(self%g, m)
    if (step_back_method .or. maxviol <= self%opts%feas_tol .or. self%restorations > 0) return
    if (.not. stuck) then
      ! not stuck (yet): only a violated constraint whose linearised distance
      ! g / |grad g| exceeds 1e6 (1 + |x|) (a zero gradient: HS 23's circles at
      ! the origin), which no Newton-type step can reach; where the run then
      ! stops hangs on the last bits of x_k
      reach = 1.0e6_dp*(1.0_dp + maxval(abs(self%x)))
      if (.not. any([(self%g(i) > self%opts%feas_tol .and. self%g(i) > reach*norm2(self%dg(:, i)), i=1, m)])) return
    end if
    ! from the least violated iterate (the first on ties), not from the stuck
    ! point: where GNLC.NS stops can hang on the last bits (HS 23: the
    ! origin, or (-0.8, 1.8) after a round-off-sized x1 < 0 there)
    j = 1
    do i = 2, self%n_log
      if (self%log(i)%max_violation < self%log(j)%max_violation) j = i
    end do
    x_new = self%log(j)%x
    call restore_feasibility(prob, x_new, g_new, self%opts%feas_tol, 50, ok, steps, err)
    if (err%failed() .or. .not. ok) return
    self%restorations = self%restorations + 1
    self%opts%method = merge(method_gnlc_general, method_gnlc, self%opts%method == method_gnlc_general_ns)
    step_back_method = .true.
    t = 1.0_dp
    self%active(1:m) = abs(g_new(1:m)) <= self%opts%feas_tol
    where (.not. self%active) self%lambda = 0.0_dp
    self%restored_now = .true.
    self%off_chord = .true.
    call self%note('infeasible and stuck (max violation '//str(maxviol, 3)//', '//trim(merge('no progress ', &
      'out of reach', stuck))//'): feasibility restored from x_'// &
      str(self%log(j)%k)//' by '//str(steps)//' Gauss steps on the violation (no analysis); continuing with ' &
      //self%method_label()//' (step-back) from there, active '//set_text(self%active))
    done = .true.
  end function restoration

  !> Step-back along the Levenberg arc (ours).  The step-back methods cut the
  !> chord x_k -> x_k + s; with a non-convex active constraint the chord
  !> leaves its feasible side and the step-back ends at x_k (Potter §9.5
  !> item 3; fix (a) did not help).  The arc x_k + s(mu), s(mu) from B10/B11
  !> with G + mu d I (d = max(1, max G_ii)) and the active set of x_k, keeps
  !> the active constraints satisfied at every point (B11 holds at each end
  !> point) and shrinks to x_k as mu grows.  The largest feasible step on it
  !> is found by bisection in log mu (constraint evaluations only, no
  !> analysis); the constraints it reaches join the set.  HS 23 after the
  !> restoration: on x1 = x2^2 with S = {5} the step goes to the origin, the
  !> chord is infeasible at once, the arc follows the parabola down to (1, 1)
  !> where x2 = x1^2 joins.  .true.: x_new, g_new hold the point.
  logical function arc_step(self, prob, step_back_method, active0, x_new, g_new, t, err) result(done)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    logical, intent(in) :: step_back_method, active0(:)
    real(dp), intent(out) :: x_new(:), g_new(:), t
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: gm0(:, :), lam0(:), s(:), x_t(:), g_t(:)
    character(len=:), allocatable :: ev0
    real(dp) :: d, lo, hi, mid, tol
    integer :: i, m, it
    logical :: feasible
    done = .false.
    if (.not. step_back_method .or. prob%m + prob%n_eq == 0) return
    m = prob%m
    tol = self%opts%feas_tol
    ! explicit shapes: gfortran's -Wmaybe-uninitialized misreads an
    ! allocate-on-assignment array that a contained procedure uses
    allocate(gm0(size(self%gm, 1), size(self%gm, 2)), lam0(size(self%lambda)))
    gm0 = self%gm
    lam0 = self%lambda
    ev0 = self%ev
    allocate(s(prob%n), x_t(prob%n), g_t(size(g_new)))
    d = max(1.0_dp, maxval([(abs(gm0(i, i)), i=1, prob%n)]))
    hi = 0.0_dp                           ! log10 mu: find a feasible end point
    do it = 1, 13
      call end_point(hi)
      if (err%failed() .or. feasible) exit
      hi = hi + 1.0_dp
    end do
    if (.not. err%failed() .and. feasible) then
      x_new = x_t
      g_new = g_t
      lo = hi - 16.0_dp
      do it = 1, 60
        mid = 0.5_dp*(lo + hi)
        call end_point(mid)
        if (err%failed()) exit
        if (feasible) then
          hi = mid
          x_new = x_t
          g_new = g_t
          if (any(.not. active0(1:m) .and. g_t(1:m) >= -tol)) exit      ! on a new boundary
        else
          lo = mid
        end if
      end do
      done = .not. err%failed() .and. maxval(abs(x_new - self%x)) > self%opts%xtol*(1.0_dp + maxval(abs(self%x)))
    end if
    self%gm = gm0
    self%ev = ev0
    self%active = active0
    if (.not. done) return
    self%active(1:m) = active0(1:m) .or. abs(g_new(1:m)) <= tol
    t = 1.0_dp
    self%step_backs = self%step_backs + 1
    self%first_order_start = .true.      ! the arc's multipliers belong to G + mu d I, not to G
    self%off_chord = .true.
    call self%note('step-back along the Levenberg arc (mu = '//str(d*10.0_dp**hi, 3)//'): the chord leaves the ' &
      //'feasible side of active '//set_text(active0)//'; now active '//set_text(self%active))
  contains
    subroutine end_point(log_mu)
      real(dp), intent(in) :: log_mu
      logical :: solved
      real(dp) :: res
      self%gm = gm0
      do i = 1, prob%n
        self%gm(i, i) = self%gm(i, i) + d*10.0_dp**log_mu
      end do
      self%active = active0
      call self%step_for_set(prob, lam0, s, solved, res, err)
      feasible = .false.
      if (err%failed()) return
      x_t = self%x + s
      if (prob%n_bounds > 0) x_t = prob%project_to_bounds(x_t)
      call prob%constraint_values(x_t, g_t, err)
      if (err%failed()) return
      if (.not. all(ieee_is_finite(g_t))) return
      feasible = all(g_t(1:m) <= tol)
      if (size(g_t) > m) feasible = feasible .and. maxval(abs(g_t(m + 1:))) <= tol
    end subroutine end_point
  end function arc_step

  !> Warm start of B11 after a Levenberg-arc step: the least-squares
  !> multipliers of grad F + C lambda = 0 at x_k for the active general
  !> constraints and equalities (kept if C is rank-deficient).  HS 23 at
  !> (1, 1), a vertex of x2 <= x1^2, x1 <= x2^2: they are (2, 2) exactly and
  !> B11 is solved by s = 0; from the arc's multipliers (about 0) Newton went
  !> to the other root, the origin (lambda = 0, grad F(0) = 0).
  subroutine first_order_multipliers(self, prob, m0, lam)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    integer, intent(in) :: m0
    real(dp), intent(inout) :: lam(:)
    real(dp), allocatable :: cc(:, :), rhs(:)
    integer, allocatable :: idx(:), p(:)
    real(dp) :: rc
    type(error_t) :: lerr
    integer :: i
    self%first_order_start = .false.
    idx = pack([(i, i=1, size(lam))], self%active .and. ([(i, i=1, size(lam))] <= m0 .or. &
                                                         [(i, i=1, size(lam))] > prob%m))
    if (size(idx) == 0) return
    cc = matmul(transpose(self%dg(:, idx)), self%dg(:, idx))
    rhs = -matmul(transpose(self%dg(:, idx)), self%gradf)
    allocate(p(size(idx)))
    call lu_factor(cc, p, lerr, rc)
    if (lerr%failed() .or. rc < 1.0e-12_dp) return
    call lu_solve(cc, p, rhs, lerr)
    if (.not. lerr%failed()) lam(idx) = rhs
  end subroutine first_order_multipliers

  !> grad F (and J), the constraint gradients and G at x_k; a non-finite
  !> derivative stops the run with the diagnosis.
  subroutine derivatives(self, prob, hess_kind, k, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    integer, intent(in) :: hess_kind, k
    type(error_t), intent(inout) :: err
    integer :: mt
    mt = prob%m + prob%n_eq
    call prob%objective_derivatives(self%x, self%f, self%phi, self%gradf, self%jac, err)
    if (.not. err%failed() .and. .not. (all(ieee_is_finite(self%gradf)) .and. all(ieee_is_finite(self%jac)))) &
      call err%set('objective derivatives', 'not finite at x_'//str(k)//' (grad F = '//vec_text(self%gradf)//')')
    if (err%failed()) return
    if (mt > 0) then
      call prob%constraint_gradients(self%x, self%g, self%dg, err)
      if (.not. err%failed() .and. .not. all(ieee_is_finite(self%dg))) &
        call err%set('constraint gradients', 'not finite at x_'//str(k))
      if (err%failed()) return
    end if
    call self%curvature(prob, hess_kind, k, err)
    if (err%failed()) return
  end subroutine derivatives

  !> Bertsekas' projected Newton point (D. P. Bertsekas, SIAM J. Control
  !> Optim. 20 (1982) 221-246), for problems whose only inequalities are
  !> simple bounds (his setting) and the NS variants.  Binding set: the
  !> variables at a bound whose gradient component points out of the box; a
  !> Newton step with the model G on the others (s_B = 0 on the binding
  !> ones); the point P(x_k + s_B) is analysed and accepted if it passes
  !> Armijo's test F(P) <= F(x_k) + 1e-4 grad F^T (P - x_k) (his rule at unit
  !> step).  Tried only where it differs from P(x_k + s), s our step: where
  !> the box-QP step of compute_step holds a variable whose gradient points
  !> into the box, or takes it along a bound it crossed.  .false.: rejected
  !> (one analysis spent) or not applicable; the usual step follows.
  !> HS 2 (sum of squares, G = 2 J J^T): at x_0 = (-2, 1.5) the Gauss step
  !> (3, -9.5) crosses x2 >= 1.5, whose gradient component -500 points into
  !> the box; our step holds x2 (the model's multiplier is +1.2) and ends at
  !> x1 = -1.37, in the basin of the other local minimum; P(x_0 + s_B) =
  !> (1, 1.5) has F = 25 < 634 and lies beyond the ridge F >= 226 at x1 = 0.
  logical function projected_point(self, prob, s, err) result(done)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: s(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: phi(:), gff(:, :), rhs(:), sb(:), x_new(:), g_new(:)
    integer, allocatable :: free(:), piv(:)
    logical, allocatable :: bind(:)
    type(error_t) :: lerr
    real(dp) :: f, rc, tol
    integer :: j, n
    done = .false.
    n = prob%n
    if (prob%m > prob%n_bounds .or. prob%n_eq > 0 .or. prob%n_bounds == 0 .or. .not. self%opts%hold_bounds) return
    allocate(bind(n), sb(n), g_new(prob%m), phi(size(self%phi)))
    tol = self%opts%feas_tol
    do j = 1, n
      bind(j) = (self%x(j) <= prob%xl(j) + tol .and. self%gradf(j) > 0.0_dp) .or. &
                (self%x(j) >= prob%xu(j) - tol .and. self%gradf(j) < 0.0_dp)
    end do
    free = pack([(j, j=1, n)], .not. bind)
    sb = 0.0_dp
    if (size(free) > 0) then
      gff = self%gm(free, free)
      rhs = -self%gradf(free)
      allocate(piv(size(free)))
      call lu_factor(gff, piv, lerr, rc)
      if (lerr%failed() .or. rc < self%opts%rcond_min) return
      call lu_solve(gff, piv, rhs, lerr)
      if (lerr%failed() .or. .not. all(ieee_is_finite(rhs))) return
      sb(free) = rhs
    end if
    x_new = prob%project_to_bounds(self%x + sb)
    if (maxval(abs(x_new - prob%project_to_bounds(self%x + s))) <= self%opts%xtol*(1.0_dp + maxval(abs(self%x)))) &
      return
    call prob%analyse(x_new, f, phi, err)
    if (err%failed()) return
    if (.not. (ieee_is_finite(f) .and. all(ieee_is_finite(phi)))) then
      call self%note('projected Newton point (Bertsekas): F not finite, rejected')
      return
    end if
    if (f > self%f + 1.0e-4_dp*dot_product(self%gradf, x_new - self%x)) then
      call self%note('projected Newton point (Bertsekas) '//vec_text(x_new)//' rejected by Armijo''s test (F = ' &
                     //str(f, 6)//')')
      return
    end if
    call prob%constraint_values(x_new, g_new, err)
    if (err%failed()) return
    self%active = abs(g_new) <= tol
    call self%note('projected Newton point (Bertsekas) accepted by Armijo''s test (F = '//str(f, 6)// &
                   '); active '//set_text(self%active))
    self%x = x_new
    self%g = g_new
    self%f = f
    self%phi = phi
    done = .true.
  end function projected_point

  !> The trial point x_k + s: constraints there (a non-finite value halves
  !> the step), the step-back of the step-back methods (B13, with Potter's
  !> cycling check: again = .true. asks for the step to be recomputed with
  !> the newly violated constraints active), the additions of §9.4 and the
  !> release rule.  On return x_new, g_new and t (the fraction of s taken).
  subroutine trial_point(self, prob, s, snorm, xnorm, k, step_back_method, solved, x_new, g_new, t, repeats, &
                         again, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(inout) :: s(:), snorm
    real(dp), intent(in) :: xnorm
    integer, intent(in) :: k
    logical, intent(in) :: step_back_method, solved
    real(dp), intent(out) :: x_new(:), g_new(:), t
    integer, intent(inout) :: repeats
    logical, intent(out) :: again
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: g_t(:)
    logical, allocatable :: violated(:), touched(:), limit(:)
    integer :: m, mt, halvings
    m = prob%m
    mt = prob%m + prob%n_eq
    again = .false.
    allocate(g_t(mt), violated(m), touched(m), limit(m))
    x_new = self%x + s
    ! a held variable lands on its bound exactly (not a rounding beyond it)
    if (prob%n_bounds > 0 .and. self%opts%hold_bounds) x_new = prob%project_to_bounds(x_new)
    t = 1.0_dp
    if (mt > 0) then
      call prob%constraint_values(x_new, g_new, err)
      if (err%failed()) return
      ! a non-finite constraint value is a failed trial: shorten the step
      halvings = 0
      do while (.not. all(ieee_is_finite(g_new)) .and. halvings < max_halvings)
        halvings = halvings + 1
        s = 0.5_dp*s
        x_new = self%x + s
        call prob%constraint_values(x_new, g_new, err)
        if (err%failed()) return
      end do
      if (halvings > 0) then
        snorm = maxval(abs(s))
        call self%note('constraints not finite at the trial point: step halved '//str(halvings)//' times')
      end if
      if (.not. all(ieee_is_finite(g_new))) then
        call err%set('constraints', 'not finite anywhere along the step (halved '//str(max_halvings)//' times)')
        return
      end if
      violated = g_new(1:m) > self%opts%feas_tol
      touched = (.not. self%active(1:m)) .and. (g_new(1:m) >= -self%opts%feas_tol)
      if (step_back_method .and. any(violated)) then
        ! ---- step back to the farthest feasible point of the segment (B13)
        call self%step_back(prob, s, g_new, t, g_t, limit, err)
        if (err%failed()) return
        if (t*snorm <= self%opts%xtol*(1.0_dp + xnorm) .and. .not. any(limit .and. .not. self%active(1:m))) then
          ! Potter §9.5 item 3: backing out of the new violation entered the
          ! violated region of an active constraint; the step-back ends at
          ! x_k with the same active set and would repeat the same design.
          if (self%opts%potter_repeat .and. any(violated .and. .not. self%active(1:m)) &
              .and. repeats < m) then
            repeats = repeats + 1
            self%potter_repeats = self%potter_repeats + 1
            call self%note('step-back cycling (Potter 9.5 item 3): limited by active ' &
              //set_text(limit)//' at t = '//str(t, 3)//'; step repeated with ' &
              //set_text(violated .and. .not. self%active(1:m))//' active (fix (a))')
            self%additions = self%additions + count(violated .and. .not. self%active(1:m))
            self%active(1:m) = self%active(1:m) .or. violated
            again = .true.
            return
          end if
          if (self%opts%potter_repeat) then
            ! fix (a) did not help: a zero-length step, for which solve tries
            ! the Levenberg arc (arc_step) before it stops
            call self%note('step-back cycling (Potter 9.5 item 3) not escaped by fix (a)')
            x_new = self%x
            g_new = self%g
            t = 0.0_dp
            return
          end if
          call err%set(self%method_label(), 'step-back cycling at iteration '//str(k + 1)// &
            ' (Potter, P24-P25, doc/optimization.md): backing out of violated constraint(s) ' &
            //set_text(violated .and. .not. self%active(1:m))//' entered the violated region of active ' &
            //set_text(limit)//'; the step-back returns to x_k with the same active set, so the ' &
            //'next iteration would reproduce the same design')
          return
        end if
        self%step_backs = self%step_backs + 1
        x_new = self%x + t*s
        g_new = g_t
        call self%note('step-back (B13) to t = '//str(t, 6)//', added '//set_text(limit .and. &
                       .not. self%active(1:m)))
        self%additions = self%additions + count(limit .and. .not. self%active(1:m))
        self%active(1:m) = self%active(1:m) .or. limit
        ! a bound the whole step crossed was held at it (compute_step); the
        ! cut point does not reach it, and kept in the set it would pull its
        ! variable onto the bound at the next step whatever the constraints
        ! that limited this one need (HS 93: x5 = x6 = 0 zeroes the active
        ! product constraint, B11 has no solution, and the run stopped)
        if (prob%n_bounds > 0 .and. self%opts%hold_bounds) then
          limit = .false.
          limit(m - prob%n_bounds + 1:m) = self%active(m - prob%n_bounds + 1:m) .and. &
                                           g_new(m - prob%n_bounds + 1:m) < -self%opts%feas_tol
          if (any(limit)) then
            call self%note('bound(s) '//set_text(limit)//' not reached at the step-back point: released')
            self%releases = self%releases + count(limit)
            self%active(1:m) = self%active(1:m) .and. .not. limit
          end if
        end if
      else
        call self%add_to_active(violated, touched, step_back_method)
      end if
      if (.not. solved) call self%release_satisfied(g_new(1:m))
    end if
  end subroutine trial_point

  !> GNLC.NS: a violated constraint is treated as an active one (§9.4); every
  !> method adds the constraints the step makes active (touched).
  subroutine add_to_active(self, violated, touched, step_back_method)
    class(gauss_optimizer_t), intent(inout) :: self
    logical, intent(in) :: violated(:), step_back_method
    logical, intent(inout) :: touched(:)
    integer :: m
    m = size(violated)
    if (.not. step_back_method) touched = touched .or. (violated .and. .not. self%active(1:m))
    if (.not. any(touched)) return
    call self%note('added '//set_text(touched))
    self%additions = self%additions + count(touched)
    self%active(1:m) = self%active(1:m) .or. touched
  end subroutine add_to_active

  !> Our rule (the papers are silent): when B11 had no solution the active
  !> set was inconsistent; members strictly satisfied at the new point leave
  !> it, so a Powell compromise cannot pin the set.  g: inequalities there.
  subroutine release_satisfied(self, g)
    class(gauss_optimizer_t), intent(inout) :: self
    real(dp), intent(in) :: g(:)
    logical :: leave(size(g))
    integer :: m
    m = size(g)
    leave = self%active(1:m) .and. g < -self%opts%feas_tol
    if (.not. any(leave)) return
    call self%note('released '//set_text(leave)//' (B11 unsolved; strictly satisfied at the new point)')
    self%releases = self%releases + count(leave)
    self%active(1:m) = self%active(1:m) .and. .not. leave
  end subroutine release_satisfied

  !> The start: working arrays, x0 (projected into the bounds for the NS
  !> variants), constraints and the initial active set (§9.4), the check of a
  !> step-back method's start (code 2 if infeasible), and the analysis at x0.
  subroutine start(self, prob, x0, step_back_method, auto, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x0(:)
    logical, intent(in) :: step_back_method, auto
    type(error_t), intent(inout) :: err
    logical, allocatable :: violated(:)
    integer :: n, m, mt
    n = prob%n
    m = prob%m
    mt = prob%m + prob%n_eq
    allocate(violated(m))
    allocate(self%x(n), self%g(mt), self%lambda(mt), self%active(mt), self%x_best(n))
    allocate(self%phi(prob%n_residuals), self%gradf(n), self%jac(n, prob%n_residuals), self%gm(n, n))
    allocate(self%dg(n, mt), self%hess(n, n, mt), self%have_hess(mt))
    self%hess = 0.0_dp
    allocate(self%log(16))
    self%x = x0
    self%lambda = 0.0_dp
    self%ev = ''
    if (auto) call self%note('method auto: '//self%method_label())
    if (.not. step_back_method .and. prob%n_bounds > 0) then
      self%x = prob%project_to_bounds(x0)
      if (maxval(abs(self%x - x0)) > 0.0_dp) call self%note('start projected onto the bounds')
    end if

    call prob%constraint_values(self%x, self%g, err)
    if (.not. err%failed() .and. .not. all(ieee_is_finite(self%g))) &
      call err%set('constraints', 'not finite at the start point: g = '//vec_text(self%g))
    if (err%failed()) then
      call err%add_context(self%method_label()//', at the start point')
      self%message = err%text()
      return
    end if
    violated = self%g(1:m) > self%opts%feas_tol
    ! step-back methods keep inequalities and linear equalities satisfied; a
    ! nonlinear equality cannot hold along a step and is restored by B11
    if (step_back_method .and. (any(violated) .or. any(abs(self%g(m + 1:mt)) > self%opts%feas_tol &
                                                       .and. prob%con_kind(m + 1:mt) == con_linear))) then
      call err%set(self%method_label(), 'the starting point is infeasible: constraint(s) ' &
        //set_text([violated, abs(self%g(m + 1:mt)) > self%opts%feas_tol .and. prob%con_kind(m + 1:mt) == con_linear]) &
        //' violated (max g = ' &
        //str(max_violation(self%g, m), 6)//'). Method '//self%method_label()// &
        ' steps back to keep every iterate feasible and needs a feasible start; use method = ''' &
        //ns_variant(self%opts%method)//''', which accepts any start', code=2)
      self%message = err%text()
      return
    end if
    ! initial active set: constraints at zero (within feas_tol), all equalities;
    ! the NS variants also take the violated ones (§9.4)
    self%active(1:m) = abs(self%g(1:m)) <= self%opts%feas_tol
    if (.not. step_back_method) self%active(1:m) = self%active(1:m) .or. violated
    self%active(m + 1:mt) = .true.
    self%h_max = 1.0e4_dp*max(1.0_dp, max_violation(self%g, m))

    call prob%analyse(self%x, self%f, self%phi, err)
    if (.not. err%failed() .and. .not. (ieee_is_finite(self%f) .and. all(ieee_is_finite(self%phi)))) &
      call err%set('objective', 'not finite at the start point (F = '//str(self%f)//')')
    if (err%failed()) then
      call err%add_context(self%method_label()//', at the start point')
      self%message = err%text()
      return
    end if
    call self%append_log(prob, 0, 0.0_dp)
  end subroutine start

  !> Forget the previous run (outcome, log, event counts); options stay.
  subroutine reset(self)
    class(gauss_optimizer_t), intent(inout) :: self
    type(gauss_options_t) :: opts
    opts = self%opts
    if (allocated(self%x)) deallocate(self%x)
    if (allocated(self%g)) deallocate(self%g)
    if (allocated(self%lambda)) deallocate(self%lambda)
    if (allocated(self%active)) deallocate(self%active)
    if (allocated(self%x_best)) deallocate(self%x_best)
    if (allocated(self%log)) deallocate(self%log)
    if (allocated(self%phi)) deallocate(self%phi)
    if (allocated(self%gradf)) deallocate(self%gradf)
    if (allocated(self%jac)) deallocate(self%jac)
    if (allocated(self%gm)) deallocate(self%gm)
    if (allocated(self%dg)) deallocate(self%dg)
    if (allocated(self%hess)) deallocate(self%hess)
    if (allocated(self%have_hess)) deallocate(self%have_hess)
    self%status = status_failed
    self%message = ''
    self%final_events = ''
    self%iterations = 0
    self%f = 0.0_dp
    self%kkt_residual = 0.0_dp
    self%have_best = .false.
    self%f_best = 0.0_dp
    self%k_best = 0
    self%newton_solves = 0
    self%powell_fallbacks = 0
    self%drops = 0
    self%additions = 0
    self%releases = 0
    self%step_backs = 0
    self%regularizations = 0
    self%potter_repeats = 0
    self%restorations = 0
    self%backtracks = 0
    self%kkt_refusals = 0
    self%stationarity = 0.0_dp
    self%min_multiplier = 0.0_dp
    self%n_filter = 0
    self%h_max = 0.0_dp
    self%n_log = 0
    self%ev = ''
    self%last_solved = .true.
    self%first_order_start = .false.
    self%restored_now = .false.
    self%off_chord = .false.
    self%quasi_newton = .false.
    self%bfgs_updates = 0
    if (allocated(self%bq)) deallocate(self%bq)
    self%opts = opts
  end subroutine reset

  !> Method/problem consistency and option checks (code 2: bad input).
  subroutine check_setup(self, prob, x0, hess_kind, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    real(dp), intent(in) :: x0(:)
    integer, intent(out) :: hess_kind
    type(error_t), intent(inout) :: err
    character(len=:), allocatable :: me
    integer :: i
    if (self%opts%method == method_auto) then
      ! any start is allowed: the NS variants; Potter's for general constraints
      if (prob%n_constraints() == 0) then
        self%opts%method = method_gauss
      else if (any(prob%con_kind == con_general)) then
        self%opts%method = method_gnlc_general_ns
      else
        self%opts%method = method_gnlc_ns
      end if
    end if
    me = self%method_label()
    hess_kind = self%opts%hessian
    if (hess_kind == hessian_auto) then
      hess_kind = hessian_exact
      if (prob%is_least_squares()) hess_kind = hessian_gauss
    end if
    if (size(x0) /= prob%n) then
      call err%set(me, 'the start point has '//str(size(x0))//' values; problem '//prob%name// &
                   ' has '//str(prob%n)//' variables', code=2)
    else if (.not. all(ieee_is_finite(x0))) then
      call err%set(me, 'the start point is not finite: x0 = '//vec_text(x0), code=2)
    else if (.not. all(ieee_is_finite([self%opts%xtol, self%opts%ftol, self%opts%feas_tol, self%opts%mult_tol, &
                                       self%opts%rcond_min, self%opts%regularization]))) then
      call err%set(me, 'invalid options: xtol, ftol, feas_tol, mult_tol, rcond_min and regularization must be ' &
                   //'finite', code=2)
    else if (me == 'unknown') then
      call err%set('gauss_optimizer', 'unknown method; expected one of '//method_names, code=2)
    else if (hess_kind == hessian_gauss .and. .not. prob%is_least_squares()) then
      call err%set(me, 'hessian = ''gauss'' (G = 2JJ^T) needs a sum-of-squares objective; problem '// &
                   prob%name//' has a general objective: use hessian = ''exact''', code=2)
    else if (self%opts%method == method_gauss .and. prob%n_constraints() > 0) then
      call err%set(me, 'method ''gauss'' is unconstrained but problem '//prob%name//' has '// &
                   str(prob%n_constraints())//' constraints: use ''gauss_constrained'' (linear) or ''gnlc''', code=2)
    else if (self%opts%method == method_gauss_constrained .and. any(prob%con_kind /= con_linear)) then
      i = findloc(prob%con_kind /= con_linear, .true., dim=1)
      call err%set(me, 'constraint '//str(i)//' of problem '//prob%name//' is '// &
                   con_kind_name(prob%con_kind(i))//'; gauss_constrained handles linear constraints only: use ''gnlc''', &
                   code=2)
    else if (any(self%opts%method == [method_gnlc, method_gnlc_ns]) .and. any(prob%con_kind == con_general)) then
      i = findloc(prob%con_kind == con_general, .true., dim=1)
      call err%set(me, 'constraint '//str(i)//' of problem '//prob%name//' is general (not quadratic); use '// &
                   '''gnlc_general'' or ''gnlc_general_ns'' (Potter''s re-approximation)', code=2)
    else if (self%opts%max_iter < 0 .or. self%opts%xtol <= 0.0_dp .or. self%opts%ftol <= 0.0_dp &
             .or. self%opts%feas_tol <= 0.0_dp .or. self%opts%mult_tol < 0.0_dp .or. self%opts%rcond_min <= 0.0_dp &
             .or. self%opts%regularization < 0.0_dp .or. self%opts%newton_max_iter < 1) then
      call err%set(me, 'invalid options: max_iter >= 0, xtol, ftol, feas_tol, rcond_min > 0, mult_tol, ' &
                   //'regularization >= 0 and newton_max_iter >= 1 are required', code=2)
    end if
  end subroutine check_setup

  !> G = 2 J J^T (B5) or the objective Hessian; a singular G is diagnosed
  !> (numerical rank of J) and either regularised or reported.
  subroutine curvature(self, prob, hess_kind, k, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    integer, intent(in) :: hess_kind, k
    type(error_t), intent(inout) :: err
    real(dp) :: rc, mu, gmax
    real(dp), allocatable :: glag(:)
    real(dp), parameter :: auto_factor = 1.0e-8_dp, auto_rcond = 1.4901161193847656e-8_dp
    logical :: auto_exact
    character(len=:), allocatable :: what, how
    integer :: i, n
    n = prob%n
    if (hess_kind == hessian_gauss) then
      self%gm = 2.0_dp*matmul(self%jac, transpose(self%jac))
      what = 'G = 2 J J^T'
    else if (self%quasi_newton) then
      call self%bfgs_update(n)
      self%gm = self%bq
      what = 'the BFGS matrix G'
    else
      call prob%objective_hessian(self%x, self%gm, err)
      if (.not. err%failed() .and. .not. all(ieee_is_finite(self%gm))) &
        call err%set('objective Hessian', 'not finite at x_'//str(k))
      if (err%failed()) return
      self%gm = 0.5_dp*(self%gm + transpose(self%gm))
      what = 'the objective Hessian G'
      ! quasi-Newton from here on where asked for (hessian = 'bfgs'; not the
      ! default: doc/optimization.md §8 gives what it costs and loses)
      if (hess_kind == hessian_bfgs) call self%start_bfgs(n)
      if (self%opts%auto_regularize .and. self%opts%regularization <= 0.0_dp) call self%make_convex(n)
    end if
    rc = self%model_rcond(prob)
    ! with the automatic choice (default) an objective Hessian is treated as
    ! singular below sqrt(eps): a difference Hessian is only good to ~1e-8
    ! relative, so smaller eigenvalues are noise, and M would be too
    ! ill-conditioned for B11 to be solved to feas_tol/100 (G = 2 J J^T is
    ! positive semi-definite by construction and keeps rcond_min)
    auto_exact = hess_kind /= hessian_gauss .and. .not. self%quasi_newton .and. self%opts%auto_regularize &
                 .and. self%opts%regularization <= 0.0_dp
    if (rc >= self%opts%rcond_min .and. .not. (auto_exact .and. rc < auto_rcond)) return
    if (self%opts%regularization > 0.0_dp .or. self%opts%auto_regularize) then
      gmax = maxval([(abs(self%gm(i, i)), i=1, n)])
      if (self%opts%regularization > 0.0_dp) then
        mu = self%opts%regularization*max(gmax, 1.0e-300_dp)
        how = ''
      else
        ! automatic (Levenberg): mu = 1e-8 max G_ii shifts the zero eigenvalues
        ! to 1e-8 of G's scale and leaves the others untouched to 8 digits;
        ! but at least |grad L|/max(1, |x|) (grad L = grad F + C lambda of the
        ! last solved step), which bounds a step along a null direction of G
        ! to about the design's own size (a trust region) and vanishes at a
        ! KKT point, so that the final convergence is not slowed
        allocate(glag(n))
        glag = self%gradf
        if (self%last_solved .and. size(self%lambda) > 0) glag = glag + matmul(self%dg, self%lambda)
        mu = max(merge(100.0_dp, 1.0_dp, auto_exact)*auto_factor*gmax, &
                 maxval(abs(glag))/max(1.0_dp, maxval(abs(self%x))), 1.0e-300_dp)
        how = ' (automatic, max('//merge('1e-6', '1e-8', auto_exact)//' max G_ii, |grad L|/max(1, |x|)))'
      end if
      do i = 1, n
        self%gm(i, i) = self%gm(i, i) + mu
      end do
      self%regularizations = self%regularizations + 1
      call self%note(what//' singular (rcond = '//str(rc, 3)//'): regularized with mu = '//str(mu, 3)//how)
      return
    end if
    call err%set('curvature', what//' at x_'//str(k)//' is singular or nearly singular (rcond = '//str(rc, 3) &
      //' < rcond_min = '//str(self%opts%rcond_min, 3)//')'//self%rank_text(prob, hess_kind)//'. The Gauss ' &
      //'step (B10/B12) is undefined; remove redundant variables, or set singular_g = ''regularize'' (the ' &
      //'default) or regularization > 0 in &optimize to add mu*I (Levenberg)')
  end subroutine curvature

  !> The quasi-Newton start: B_0 = the (difference) Hessian just computed at
  !> x_0, its eigenvalues raised to at least 1e-4 max(1, |lambda_max|)
  !> (positive definite, as the BFGS update keeps it).
  subroutine start_bfgs(self, n)
    class(gauss_optimizer_t), intent(inout) :: self
    integer, intent(in) :: n
    real(dp) :: ev(n), floor
    type(error_t) :: lerr
    integer :: i
    self%quasi_newton = .true.
    self%bq = self%gm
    call symmetric_eigenvalues(self%gm, ev, lerr)
    floor = 1.0e-4_dp*max(1.0_dp, maxval(abs(ev)))
    if (lerr%failed()) ev(1) = -floor
    if (ev(1) < floor) then
      do i = 1, n
        self%bq(i, i) = self%bq(i, i) + floor - ev(1)
      end do
    end if
    self%gm = self%bq
    self%xq = self%x
    self%gq = self%gradf
    call self%note('G: damped BFGS from here on, B_0 = the difference Hessian at x_0'// &
                   trim(merge(' shifted to positive definite', '                             ', ev(1) < floor)))
  end subroutine start_bfgs

  !> Powell's damped BFGS update of G (M. J. D. Powell, "A fast algorithm for
  !> nonlinearly constrained optimization calculations", Numerical Analysis
  !> Dundee 1977, LNM 630, 144-157; Nocedal & Wright, Numerical
  !> Optimization, 2nd ed., Procedure 18.2) from the last step s = x_k -
  !> x_q and the change of the objective gradient y = grad F(x_k) - grad
  !> F(x_q) (the constraints' curvature enters M through their own
  !> Hessians): r = theta y + (1 - theta) B s with theta = 1 if s^T y >=
  !> 0.2 s^T B s, else 0.8 s^T B s / (s^T B s - s^T y); B + r r^T / s^T r -
  !> B s s^T B / s^T B s stays positive definite.
  subroutine bfgs_update(self, n)
    class(gauss_optimizer_t), intent(inout) :: self
    integer, intent(in) :: n
    real(dp) :: sv(n), y(n), bs(n), r(n), sbs, sy, theta
    integer :: i
    sv = self%x - self%xq
    y = self%gradf - self%gq
    self%xq = self%x
    self%gq = self%gradf
    if (maxval(abs(sv)) <= 0.0_dp) return
    bs = matmul(self%bq, sv)
    sbs = dot_product(sv, bs)
    if (.not. sbs > 0.0_dp) return
    sy = dot_product(sv, y)
    theta = 1.0_dp
    if (sy < 0.2_dp*sbs) theta = 0.8_dp*sbs/(sbs - sy)
    r = theta*y + (1.0_dp - theta)*bs
    do i = 1, n
      self%bq(:, i) = self%bq(:, i) - bs*bs(i)/sbs + r*r(i)/dot_product(sv, r)
    end do
    self%bq = 0.5_dp*(self%bq + transpose(self%bq))
    self%bfgs_updates = self%bfgs_updates + 1
  end subroutine bfgs_update

  !> The reciprocal condition number (0: singular) of the matrix curvature
  !> judges: G, or with the default settings M = G + Sum lambda_j A_j +
  !> scale Sum_eq c c^T/|c|^2.  B10 needs M, not G, to be regular, and the
  !> step only on the tangent space of the equalities, which are active at
  !> every step (multipliers and constraint Hessians of the last solved
  !> step).  Where that is regular and G is not, no Levenberg shift slows
  !> the iteration: where M itself is singular, B10 in lambda fails and
  !> B10/B11 are solved together in (s, lambda) (HS 28, 2 residuals in 3
  !> variables and one linear equality: x* in one step; HS 27: f independent
  !> of x3, M regular through the equality's curvature).
  real(dp) function model_rcond(self, prob) result(rc)
    class(gauss_optimizer_t), intent(in) :: self
    class(opt_problem_t), intent(in) :: prob
    real(dp), allocatable :: lu(:, :)
    integer, allocatable :: ipiv(:)
    type(error_t) :: lerr
    integer :: i, j, n
    n = prob%n
    allocate(lu(n, n), ipiv(n))
    lu = self%gm
    if (self%opts%auto_regularize .and. self%opts%regularization <= 0.0_dp .and. self%last_solved) then
      do i = 1, size(self%lambda)
        if (self%active(i) .and. abs(self%lambda(i)) > 0.0_dp) lu = lu + self%lambda(i)*self%hess(:, :, i)
      end do
    end if
    do i = prob%m + 1, prob%m + prob%n_eq
      if (.not. self%opts%auto_regularize .or. self%opts%regularization > 0.0_dp) exit   ! the user's choice
      if (norm2(self%dg(:, i)) > 0.0_dp) lu = lu + max(maxval([(abs(self%gm(j, j)), j=1, n)]), 1.0_dp)* &
        spread(self%dg(:, i), 2, n)*spread(self%dg(:, i), 1, n)/norm2(self%dg(:, i))**2
    end do
    call lu_factor(lu, ipiv, lerr, rc)
    if (lerr%failed()) rc = 0.0_dp
  end function model_rcond

  !> For the diagnosis of a singular G: its eigenvalues (DSYGV with M = I)
  !> and numerical rank; for G = 2JJ^T they are 2 sigma_i^2 of the residual
  !> Jacobian.  '' if the eigenvalues cannot be computed.
  function rank_text(self, prob, hess_kind) result(text)
    class(gauss_optimizer_t), intent(in) :: self
    class(opt_problem_t), intent(in) :: prob
    integer, intent(in) :: hess_kind
    character(len=:), allocatable :: text
    real(dp), allocatable :: ev(:)
    type(error_t) :: lerr
    integer :: n, rank
    n = prob%n
    text = ''
    allocate(ev(n))
    call symmetric_eigenvalues(self%gm, ev, lerr)
    if (lerr%failed()) return
    rank = count(ev > self%opts%rcond_min*max(ev(n), tiny(1.0_dp)))
    text = '; eigenvalues of G from '//str(ev(1), 3)//' to '//str(ev(n), 3)//', numerical rank '// &
           str(rank)//' of '//str(n)
    if (hess_kind == hessian_gauss) then
      if (prob%n_residuals < n) then
        text = text//' (only '//str(prob%n_residuals)//' residuals for '//str(n)//' variables)'
      else
        text = text//' (rank-deficient residual Jacobian J)'
      end if
    end if
  end function rank_text

  !> An indefinite model (default settings): B10 minimises the Lagrangian
  !> model with M = G + Sum lambda_j A_j over the tangent space of the active
  !> constraints.  If the projection P M P (P onto that space; M with the
  !> multipliers and constraint Hessians of the previous iteration) has a
  !> negative eigenvalue lambda_min, B10 would step to a saddle or maximum.
  !> G + mu I with mu = 2 |lambda_min| mirrors that curvature; the fixed point
  !> (grad F + C lambda = 0) is unchanged, and near a solution satisfying the
  !> second-order conditions no shift is made (fast convergence kept).
  subroutine make_convex(self, n)
    class(gauss_optimizer_t), intent(inout) :: self
    integer, intent(in) :: n
    real(dp), allocatable :: c(:, :), ev(:), c_kept(:, :)
    type(error_t) :: lerr
    real(dp) :: mu
    integer :: i
    allocate(c(n, n), ev(n), c_kept(n, n))
    c = self%gm
    ! a Powell compromise's multipliers (often huge) describe no model
    if (self%last_solved) then
      do i = 1, size(self%lambda)
        if (self%active(i) .and. abs(self%lambda(i)) > 0.0_dp) c = c + self%lambda(i)*self%hess(:, :, i)
      end do
    end if
    if (count(self%active) >= n) return        ! no tangent space: nothing to convexify
    call project_tangent(c)
    c_kept = c
    call cholesky_factor(c, lerr)
    if (.not. lerr%failed()) return
    call lerr%clear()
    call symmetric_eigenvalues(c_kept, ev, lerr)
    if (lerr%failed()) return
    if (ev(1) >= -1.0e-8_dp*maxval(abs(ev))) return     ! singular, not indefinite: handled below
    mu = -2.0_dp*ev(1)
    do i = 1, n
      self%gm(i, i) = self%gm(i, i) + mu
    end do
    self%regularizations = self%regularizations + 1
    call self%note('model G + Sum lambda A indefinite (lambda_min = '//str(ev(1), 3)//'): G + mu I, mu = '// &
                   str(mu, 3)//' (automatic, 2 |lambda_min|)')
  contains
    !> c <- P c P, P = I - C (C^T C)^{-1} C^T for the active gradients C
    !> (unchanged if there are none, or they are dependent).
    subroutine project_tangent(c)
      real(dp), intent(inout) :: c(:, :)
      real(dp), allocatable :: cc(:, :), kk(:, :), w(:, :), pm(:, :)
      integer, allocatable :: piv(:)
      type(error_t) :: perr
      real(dp) :: rc
      integer :: l, j
      l = count(self%active)
      if (l == 0 .or. l >= n) return
      allocate(cc(n, l), kk(l, l), w(l, n), pm(n, n), piv(l))
      ! unit columns: the projector does not depend on their scale, but
      ! C^T C does; gradients of very different sizes (a bound's 1 beside an
      ! equality's 1e5: HS 109) made it look singular, the test then ran on
      ! the whole space and shifted G for a curvature the tangent space does
      ! not have (and the run converged linearly)
      l = 0
      do j = 1, size(self%active)
        if (.not. self%active(j) .or. .not. norm2(self%dg(:, j)) > 0.0_dp) cycle
        l = l + 1
        cc(:, l) = self%dg(:, j)/norm2(self%dg(:, j))
      end do
      if (l == 0) return
      cc = cc(:, 1:l)
      kk = kk(1:l, 1:l)
      w = w(1:l, :)
      piv = piv(1:l)
      kk = matmul(transpose(cc), cc)
      call lu_factor(kk, piv, perr, rc)
      if (perr%failed() .or. rc < 1.0e-12_dp) return
      w = transpose(cc)
      call lu_solve(kk, piv, w, perr)
      if (perr%failed()) return
      pm = -matmul(cc, w)
      do j = 1, n
        pm(j, j) = pm(j, j) + 1.0_dp
      end do
      c = matmul(pm, matmul(c, pm))
      ! the range directions have eigenvalue 0 now: lift them so only the
      ! tangent-space curvature can fail the test
      c = c + matmul(cc, transpose(cc))*maxval(abs(c))
    end subroutine project_tangent
  end subroutine make_convex

  !> Multipliers and step at x_k for the current active set, with the drop
  !> rule of §9.4 (most negative multiplier first, re-solve, repeat) and the
  !> simple bounds as bounds: an active bound holds its variable at the
  !> bound in the step (the multiplier system sees only the free variables),
  !> and a free variable whose step crosses its bound is held there and the
  !> step recomputed (no analysis).  A bound added here is not dropped in the
  !> same call (its sign is judged at the next iterate, on the bound), so
  !> the loop ends.
  subroutine compute_step(self, prob, s, solved, residual, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout), target :: prob
    real(dp), intent(out), contiguous :: s(:)
    logical, intent(out) :: solved
    real(dp), intent(out) :: residual          !< max |m_i| of B11 at the returned multipliers
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: lam_prev(:), xt(:), s_free(:), lam_free(:)
    logical, allocatable :: new_bound(:), hit(:), released(:), dropped(:), act_free(:)
    real(dp) :: crit, worst, thresh, res_free, t
    integer :: i, j, m0, mt, jdrop, round
    logical :: have_free
    mt = prob%m + prob%n_eq
    m0 = prob%m - merge(prob%n_bounds, 0, self%opts%hold_bounds)
    allocate(new_bound(mt), hit(mt), released(mt), dropped(mt), xt(prob%n), lam_prev(mt))
    allocate(s_free(prob%n), lam_free(mt), act_free(mt))
    have_free = .false.
    res_free = 0.0_dp
    lam_prev = self%lambda
    if (self%first_order_start) call self%first_order_multipliers(prob, m0, lam_prev)
    thresh = self%opts%mult_tol*norm2(self%gradf)
    new_bound = .false.
    released = .false.
    dropped = .false.
    do round = 1, 2*(mt + prob%n) + 2
      call self%limit_violated(prob)
      call self%step_for_set(prob, lam_prev, s, solved, residual, err)
      if (err%failed()) return
      if (.not. solved .and. have_free) then
        ! holding the bounds the solved step crossed left B11 without a
        ! solution (the active constraints' gradients lie in the held
        ! variables): the solved step instead, cut where it leaves the box
        t = box_fraction(prob, m0, self%x, s_free)
        if (t > 0.0_dp) then
          self%active = act_free
          self%lambda = lam_free
          s = t*s_free
          solved = .true.
          residual = res_free
          call self%note('holding the bounds left B11 unsolved: the solved step, cut at the box (t = '// &
                         str(t, 6)//')')
          return
        end if
      end if
      ! drop rule: the most negative multiplier of an inequality leaves the set
      jdrop = 0
      worst = 0.0_dp
      do i = 1, prob%m
        if (.not. self%active(i) .or. new_bound(i)) cycle
        crit = self%lambda(i)*norm2(self%dg(:, i))
        if (crit < -thresh .and. crit < worst) then
          worst = crit
          jdrop = i
        end if
      end do
      if (jdrop /= 0) then
        self%active(jdrop) = .false.
        released(jdrop) = jdrop > m0 .and. .not. any(dropped)
        dropped(jdrop) = .true.
        self%drops = self%drops + 1
        call self%note('dropped '//str(jdrop)//' (lambda = '//str(self%lambda(jdrop), 4)//')')
        cycle
      end if
      ! free variables whose step leaves the box: held at the bound, step recomputed
      xt = self%x + s
      hit = .false.
      do i = m0 + 1, prob%m
        j = abs(prob%bound_var(i - m0))
        if (self%active(i)) cycle
        if (prob%bound_var(i - m0) < 0) hit(i) = xt(j) < prob%xl(j)
        if (prob%bound_var(i - m0) > 0) hit(i) = xt(j) > prob%xu(j)
      end do
      if (.not. any(hit)) return
      ! only a lone release: with other drops the curvature argument fails
      if (count(dropped) == 1) call self%flip_released(prob, m0, released, hit, new_bound)
      if (.not. any(hit)) cycle
      if (solved .and. .not. have_free) then
        have_free = .true.
        s_free = s
        lam_free = self%lambda
        act_free = self%active
        res_free = residual
      end if
      call self%note('bound(s) '//set_text(hit)//' reached by the step: variables held there, step recomputed')
      self%additions = self%additions + count(hit)
      self%active = self%active .or. hit
      new_bound = new_bound .or. hit
    end do
  end subroutine compute_step

  !> The largest t in [0, 1] with x + t s inside the box of the bounds.
  pure real(dp) function box_fraction(prob, m0, x, s) result(t)
    class(opt_problem_t), intent(in) :: prob
    integer, intent(in) :: m0
    real(dp), intent(in) :: x(:), s(:)
    integer :: i, j
    t = 1.0_dp
    do i = m0 + 1, prob%m
      j = abs(prob%bound_var(i - m0))
      if (prob%bound_var(i - m0) < 0 .and. s(j) < 0.0_dp) t = min(t, max(0.0_dp, (prob%xl(j) - x(j))/s(j)))
      if (prob%bound_var(i - m0) > 0 .and. s(j) > 0.0_dp) t = min(t, max(0.0_dp, (prob%xu(j) - x(j))/s(j)))
    end do
  end function box_fraction

  !> A bound released for its multiplier's sign (the model decreases into the
  !> box) whose variable the recomputed step takes back across that same
  !> bound: with r the multiplier and c the curvature of the model along the
  !> variable (the other free variables re-minimised), the free step is
  !> -r/c, so it points out of the box only when c < 0.  The model then
  !> decreases all the way across the box, and its minimiser along the
  !> variable is the opposite bound: the variable is held there (if finite)
  !> instead of at the bound it left.  HS 20: x1 released from -0.5 with
  !> lambda = -3, c = -149; Newton's step went to the model's maximum at
  !> x1 = -0.51 and the run ended on the mirror minimum (-0.5, 0.866).
  subroutine flip_released(self, prob, m0, released, hit, new_bound)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    integer, intent(in) :: m0
    logical, intent(inout) :: released(:), hit(:), new_bound(:)
    integer :: i, i2
    do i = m0 + 1, prob%m
      if (.not. (hit(i) .and. released(i))) cycle
      do i2 = m0 + 1, prob%m
        if (prob%bound_var(i2 - m0) /= -prob%bound_var(i - m0)) cycle
        hit(i) = .false.
        released(i) = .false.
        self%active(i2) = .true.
        new_bound(i2) = .true.
        self%additions = self%additions + 1
        call self%note('bound '//str(i)//' released (negative multiplier) and crossed again by the step: ' &
          //'negative curvature along x'//str(abs(prob%bound_var(i - m0)))//', held at the opposite bound '//str(i2))
      end do
    end do
  end subroutine flip_released

  !> GNLC.NS makes every violated constraint active; with more active
  !> general constraints than free variables B11 has no solution (HS 18 from
  !> (2, 2): x1 held at its bound, both constraints violated; HS 23 at
  !> (0, 0): five in two variables) and Powell's compromise pins the set.
  !> The least violated (by g / |grad g|, the linearised distance) leave the
  !> set for this step until it is square; still violated at the next
  !> iterate, they rejoin.
  subroutine limit_violated(self, prob)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    integer :: i, m0, nfree, ngen, iout
    real(dp) :: dist, dmin
    logical, allocatable :: held(:), out(:)
    m0 = prob%m - merge(prob%n_bounds, 0, self%opts%hold_bounds)
    allocate(held(prob%n), out(size(self%active)))
    held = .false.
    do i = m0 + 1, prob%m
      if (self%active(i)) held(abs(prob%bound_var(i - m0))) = .true.
    end do
    nfree = count(.not. held)
    out = .false.
    do
      ngen = count(self%active(1:m0)) + count(self%active(prob%m + 1:))
      if (ngen <= nfree) exit
      iout = 0
      dmin = huge(1.0_dp)
      do i = 1, m0
        if (.not. self%active(i) .or. self%g(i) <= self%opts%feas_tol) cycle
        dist = self%g(i)/max(norm2(self%dg(:, i)), sqrt(epsilon(1.0_dp)))
        if (dist < dmin) then
          dmin = dist
          iout = i
        end if
      end do
      if (iout == 0) exit
      self%active(iout) = .false.
      out(iout) = .true.
    end do
    if (any(out)) call self%note('active set over-determined ('//str(ngen + count(out))//' for '//str(nfree)// &
      ' free variables): violated '//set_text(out)//' left out of this step')
  end subroutine limit_violated

  !> Multipliers and step for the current active set: general constraints
  !> and equalities through B10/B11 (or P16/P17), active bounds as fixed
  !> variables; the multiplier of a bound is the force it carries.
  subroutine step_for_set(self, prob, lam_prev, s, solved, residual, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout), target :: prob
    real(dp), intent(in) :: lam_prev(:)
    real(dp), intent(out), contiguous :: s(:)
    logical, intent(out) :: solved
    real(dp), intent(out) :: residual
    type(error_t), intent(inout) :: err
    type(multiplier_system_t) :: msys
    type(multiplier_result_t) :: mres
    class(opt_problem_t), pointer :: pprob
    integer, allocatable :: idx(:)
    real(dp), allocatable :: lam(:), s_fix(:), force(:)
    logical, allocatable :: actual(:), fixed(:), general(:)
    logical :: ok
    type(error_t) :: lerr
    real(dp) :: mu
    integer :: i, j, l, mt, m0, v
    mt = prob%m + prob%n_eq
    m0 = prob%m - merge(prob%n_bounds, 0, self%opts%hold_bounds)
    pprob => prob
    residual = 0.0_dp
    solved = .true.
    allocate(fixed(prob%n), s_fix(prob%n), general(mt))
    fixed = .false.
    s_fix = 0.0_dp
    general = .true.
    do i = m0 + 1, prob%m
      general(i) = .false.
      if (.not. self%active(i)) cycle
      v = prob%bound_var(i - m0)
      j = abs(v)
      if (fixed(j)) cycle                        ! both bounds active (lower = upper): the first holds
      fixed(j) = .true.
      s_fix(j) = merge(prob%xu(j), prob%xl(j), v > 0) - self%x(j)
    end do
    idx = pack([(i, i=1, mt)], self%active .and. general)
    l = size(idx)
    allocate(lam(l), actual(l))
    self%lambda = 0.0_dp
    if (l == 0 .and. .not. any(fixed)) then
      call gauss_step(self%gm, self%gradf, s, err)       ! B12
      return
    end if
    if (self%opts%method == method_gauss_constrained .and. .not. any(fixed)) then
      ! P16, P17; G singular off the equalities' tangent space (see curvature): as below
      call lerr%clear()
      call linear_multipliers(self%gm, self%gradf, self%dg(:, idx), self%g(idx), lam, s, lerr)
      if (.not. lerr%failed()) then
        self%lambda(idx) = lam
        return
      end if
    end if
    do j = 1, l
      i = idx(j)
      if (.not. self%have_hess(i)) then
        ! Potter §9.5 item 1: Hessians of general constraints re-evaluated at every iterate
        call prob%constraint_hessian(i, self%x, self%hess(:, :, i), err)
        if (err%failed()) return
        self%have_hess(i) = .true.
      end if
      actual(j) = prob%con_kind(i) == con_general
    end do
    msys = multiplier_system(self%gm, self%gradf, self%x, idx, self%g(idx), self%dg(:, idx), self%hess(:, :, idx), &
                             actual, pprob, nonneg=idx <= prob%m, fixed=fixed, s_fix=s_fix)
    if (l == 0) then
      call msys%evaluate_step(lam, ok)                   ! B12 on the free variables
      ! a vertex start or a bilinear objective: G on the free variables
      ! singular (HS 44 from x = 0, G_ii = 0); Levenberg: G + mu I, mu x10
      mu = 1.0e-2_dp*max(1.0_dp, maxval([(abs(self%gm(i, i)), i=1, prob%n)]))
      do j = 1, 12
        if (ok .or. .not. self%opts%auto_regularize) exit
        do i = 1, prob%n
          self%gm(i, i) = self%gm(i, i) + mu
        end do
        self%regularizations = self%regularizations + 1
        call self%note('G on the free variables singular (rcond = '//str(msys%m_rcond, 3)//'): G + mu I, mu = ' &
                       //str(mu, 3))
        msys = multiplier_system(self%gm, self%gradf, self%x, idx, self%g(idx), self%dg(:, idx), &
                                 self%hess(:, :, idx), actual, pprob, nonneg=idx <= prob%m, fixed=fixed, s_fix=s_fix)
        call msys%evaluate_step(lam, ok)
        mu = 10.0_dp*mu
      end do
      if (.not. ok) call err%set('gauss_step', 'G restricted to the free variables is singular (rcond = '// &
                                 str(msys%m_rcond, 3)//')')
      if (err%failed()) return
    else
      lam = lam_prev(idx)                               ! warm start from the previous iteration
      call msys%solve(lam, 0.01_dp*self%opts%feas_tol, self%opts%newton_max_iter, mres, err)
      ! no multiplier gives a usable step: M singular on the free variables,
      ! or a step 1e10 times |x| (a linear objective, G = 0 up to a tiny
      ! shift: HS 95 at -O3 -march=native); Levenberg as above, G + mu I,
      ! mu x10, which bounds the step
      mu = 1.0e-2_dp*max(1.0_dp, maxval([(abs(self%gm(i, i)), i=1, prob%n)]))
      do j = 1, 12
        if (.not. (err%failed() .and. mres%no_step .and. self%opts%auto_regularize)) exit
        call err%clear()
        do i = 1, prob%n
          self%gm(i, i) = self%gm(i, i) + mu
        end do
        self%regularizations = self%regularizations + 1
        call self%note('B11 on '//set_text(self%active .and. general)//': no multiplier gives a usable step (rcond = ' &
                       //str(msys%m_rcond, 3)//'): G + mu I, mu = '//str(mu, 3))
        msys = multiplier_system(self%gm, self%gradf, self%x, idx, self%g(idx), self%dg(:, idx), &
                                 self%hess(:, :, idx), actual, pprob, nonneg=idx <= prob%m, fixed=fixed, s_fix=s_fix)
        lam = lam_prev(idx)
        call msys%solve(lam, 0.01_dp*self%opts%feas_tol, self%opts%newton_max_iter, mres, err)
        mu = 10.0_dp*mu
      end do
      if (err%failed()) return
      self%newton_solves = self%newton_solves + 1
      solved = mres%solved
      residual = mres%residual
      call self%note_b11(mres)
      self%lambda(idx) = lam
    end if
    s = msys%s
    ! bound multipliers: lower = force_j, upper = -force_j
    force = msys%bound_multipliers(lam)
    do i = m0 + 1, prob%m
      if (.not. self%active(i)) cycle
      v = prob%bound_var(i - m0)
      self%lambda(i) = merge(-force(abs(v)), force(abs(v)), v > 0)
    end do
  end subroutine step_for_set

  !> Log how B11 was solved when Newton in lambda did not.
  subroutine note_b11(self, mres)
    class(gauss_optimizer_t), intent(inout) :: self
    type(multiplier_result_t), intent(in) :: mres
    if (mres%how == 'kkt') then
      call self%note('B11 on '//set_text(self%active)//': Newton in lambda failed ('//mres%newton_failure// &
        '); B10 and B11 solved together by Newton in (s, lambda)')
    else if (mres%how /= 'newton') then
      self%powell_fallbacks = self%powell_fallbacks + 1
      call self%note('B11 on '//set_text(self%active)//': Newton failed ('//mres%newton_failure// &
        '); Powell minimised H = Sum g^2 ('//str(mres%powell_evaluations)//' evaluations, '// &
        mres%how//'), max |g| = '//str(mres%residual, 3))
    end if
  end subroutine note_b11

  !> Farthest feasible point x_k + t s on the segment (P), located by B13's
  !> linear interpolation, repeated (Illinois regula falsi) until the
  !> limiting constraint is within feas_tol of zero; other constraints found
  !> violated at that point shrink the segment and the search repeats.
  !> limit: the constraints that stop the step (at zero at t, violated beyond).
  subroutine step_back(self, prob, s, g_new, t, g_t, limit, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: s(:), g_new(:)
    real(dp), intent(out) :: t, g_t(:)
    logical, intent(out) :: limit(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: g_lo(:), g_hi(:), g_c(:), g_a(:)
    real(dp) :: t_lo, t_hi, t_c, ti, a, b, fa, fb, tol
    integer :: i, ic, m, round, it, side
    m = prob%m
    tol = self%opts%feas_tol
    allocate(g_lo(size(g_new)), g_hi(size(g_new)), g_c(size(g_new)), g_a(size(g_new)))
    t_lo = 0.0_dp
    g_lo = self%g
    t_hi = 1.0_dp
    g_hi = g_new
    ic = 0
    do round = 1, 2*m + 2
      ! B13 for every constraint violated at t_hi; the first crossing wins
      t_c = t_hi
      ic = 0
      do i = 1, m
        if (g_hi(i) <= tol) cycle
        if (g_lo(i) >= 0.0_dp) then
          ti = t_lo
        else
          ti = t_lo + (t_hi - t_lo)*(-g_lo(i))/(g_hi(i) - g_lo(i))
        end if
        if (ti < t_c .or. ic == 0) then
          t_c = ti
          ic = i
        end if
      end do
      if (ic == 0) exit
      ! refine the crossing of ic inside [t_lo, t_hi]
      a = t_lo
      fa = g_lo(ic)
      g_a = g_lo
      b = t_hi
      fb = g_hi(ic)
      side = 0
      if (fa < -tol) then
        do it = 1, 60
          t_c = a + (b - a)*(-fa)/(fb - fa)
          call prob%constraint_values(self%x + t_c*s, g_c, err)
          if (err%failed()) return
          if (g_c(ic) > tol) then
            b = t_c
            fb = g_c(ic)
            if (side == 1) fa = 0.5_dp*fa       ! Illinois: halve the retained end
            side = 1
          else
            a = t_c
            fa = g_c(ic)
            g_a = g_c
            if (g_c(ic) >= -tol .or. .not. self%opts%step_back_refine) exit
            if (side == -1) fb = 0.5_dp*fb
            side = -1
          end if
          if (b - a <= 1.0e-15_dp) exit
        end do
      end if
      ! a is feasible for ic; is it feasible for all?
      if (all(g_a(1:m) <= tol)) then
        t_lo = a
        g_lo = g_a
        if (b < t_hi) then
          t_hi = b
          call prob%constraint_values(self%x + t_hi*s, g_hi, err)
          if (err%failed()) return
        end if
        exit
      end if
      t_hi = a                                      ! another constraint crossed earlier
      g_hi = g_a
    end do
    t = t_lo
    g_t = g_lo
    limit = g_lo(1:m) >= -tol .and. g_hi(1:m) > tol
    if (.not. any(limit) .and. ic > 0) limit(ic) = .true.
  end subroutine step_back

  !> Analyse x_new and make it x_{k+1}.  While F (or phi) is not finite, or a
  !> step-back method meets a violated constraint on the way back, the step
  !> is halved towards x_k: every analysis counts in NF, none gives a value.
  subroutine analyse_trial(self, prob, x_new, g_new, t, snorm, step_back_method, refused, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(inout) :: x_new(:), g_new(:), t
    real(dp), intent(in) :: snorm
    logical, intent(in) :: step_back_method
    logical, intent(out) :: refused         !< the filter rejected the step (x_k unchanged)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: phi(:)
    real(dp) :: f
    integer :: halvings, m, rejected
    logical :: ok, judge
    m = prob%m
    allocate(phi(size(self%phi)))
    halvings = 0
    rejected = 0
    refused = .false.
    ! a restored point is the remedy for a rejected step: it is not judged
    judge = self%opts%globalization == glob_filter .and. .not. self%restored_now
    do
      ok = .true.
      if ((halvings > 0 .or. rejected > 0) .and. size(g_new) > 0) then
        call prob%constraint_values(x_new, g_new, err)
        if (err%failed()) return
        ok = all(ieee_is_finite(g_new))
        if (ok .and. step_back_method .and. m > 0) ok = maxval(g_new(1:m)) <= self%opts%feas_tol
      end if
      if (ok) then
        call prob%analyse(x_new, f, phi, err)
        if (err%failed()) return
        ok = ieee_is_finite(f) .and. all(ieee_is_finite(phi))
        if (ok .and. judge) then
          if (self%step_acceptable(prob, x_new, f, g_new)) exit
          rejected = rejected + 1
          self%backtracks = self%backtracks + 1
          if (rejected > max_backtracks) then
            call self%note('filter: trial point rejected '//str(rejected)//' times along the step (F = '// &
                           str(f, 8)//'); step recomputed with a Levenberg shift of G')
            refused = .true.
            return
          end if
          t = 0.5_dp*t
          x_new = self%x + 0.5_dp*(x_new - self%x)
          cycle
        end if
        if (ok) exit
      end if
      halvings = halvings + 1
      if (halvings > max_halvings) then
        call err%set('objective', 'not finite (or the constraints not satisfied) anywhere along the step from x_k: ' &
          //'halved '//str(max_halvings)//' times towards x_k = '//vec_text(self%x))
        return
      end if
      t = 0.5_dp*t
      x_new = self%x + 0.5_dp*(x_new - self%x)
    end do
    if (halvings > 0) call self%note('objective not finite at the trial point: step halved '//str(halvings)// &
                                     ' times (t = '//str(t, 4)//', |s| = '//str(t*snorm, 3)//')')
    if (rejected > 0) call self%note('filter: trial point rejected, step halved '//str(rejected)//' times (t = ' &
                                     //str(t, 4)//', F = '//str(f, 8)//')')
    self%x = x_new
    self%g = g_new
    self%f = f
    self%phi = phi
  end subroutine analyse_trial

  !> The filter line search's acceptance test (Fletcher & Leyffer, Math.
  !> Program. 91 (2002) 239-269; the line-search form of Waechter & Biegler,
  !> Math. Program. 106 (2006) 25-57), with h = max violation.  A trial
  !> point (F+, h+) from (F, h) with d = x+ - x:
  !>  - h+ > h_max = 1e4 max(1, h(x_0)): rejected;
  !>  - an F-step (grad F^T d < 0 and -grad F^T d > h, the step a descent
  !>    direction that outweighs the violation): Armijo's test
  !>    F+ <= F + 1e-4 grad F^T d;
  !>  - otherwise an h-step: h+ <= (1 - gamma) h or F+ <= F - gamma h, and
  !>    (F, h) joins the filter if h > feas_tol (gamma = 1e-5);
  !> and in both cases no filter entry (F_j, h_j) dominates the trial point:
  !> h+ <= (1 - gamma) h_j or F+ <= F_j - gamma h_j.  A feasible x_k (h = 0)
  !> thus accepts only points that do not increase F.  Allowance on F:
  !> rounding, 10 eps (1 + |F|), and, where x_k and the trial point are both
  !> feasible to feas_tol, what moving the constraints inside that band
  !> costs (tolerance_band).
  logical function step_acceptable(self, prob, x_new, f_new, g_new) result(ok)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    real(dp), intent(in) :: x_new(:), f_new, g_new(:)
    real(dp), allocatable :: tmp(:, :)
    real(dp) :: h0, h1, gd, slack
    logical :: f_step
    integer :: j
    h0 = max_violation(self%g, prob%m)
    h1 = max_violation(g_new, prob%m)
    ok = h1 <= self%h_max
    if (.not. ok) return
    gd = dot_product(self%gradf, x_new - self%x)
    slack = 10.0_dp*epsilon(1.0_dp)*(1.0_dp + abs(self%f))
    if (max(h0, h1) <= self%opts%feas_tol) slack = slack + min(sqrt(epsilon(1.0_dp))*(1.0_dp + abs(self%f)), &
      tolerance_band(self%lambda, self%g, g_new, self%opts%feas_tol))
    f_step = gd < 0.0_dp .and. -gd > h0
    if (f_step) then
      ok = f_new <= self%f + armijo_eta*gd + slack
    else if (h0 <= self%opts%feas_tol) then      ! feasible x_k: F must not increase
      ok = f_new <= self%f + slack
    else
      ok = h1 <= (1.0_dp - filter_gamma)*h0 .or. f_new <= self%f - filter_gamma*h0 + slack
    end if
    do j = 1, self%n_filter
      if (.not. ok) exit
      ok = h1 <= (1.0_dp - filter_gamma)*self%filter(2, j) .or. &
           f_new <= self%filter(1, j) - filter_gamma*self%filter(2, j) + slack
    end do
    if (.not. ok .or. f_step .or. h0 <= self%opts%feas_tol) return
    if (.not. allocated(self%filter)) allocate(self%filter(2, 8))
    if (self%n_filter == size(self%filter, 2)) then
      allocate(tmp(2, 2*self%n_filter))
      tmp(:, 1:self%n_filter) = self%filter(:, 1:self%n_filter)
      call move_alloc(tmp, self%filter)
    end if
    self%n_filter = self%n_filter + 1
    self%filter(:, self%n_filter) = [self%f, h0]
  end function step_acceptable

  !> The change of F that moving the constraints inside the feasibility band
  !> |g_i| <= tol can cause, Sum_i |lambda_i| |clip(g_i) - clip(g+_i)| with
  !> clip to [-tol, tol] (lambda = 0 off the active set; at most 2 tol
  !> Sum |lambda_i|).  Two points feasible to tol are equally feasible for the
  !> convergence test, but near a constrained optimum F differs between them
  !> by lambda times their difference in g: the end point of a step lands on
  !> a curved active constraint only to the accuracy of B11's solution
  !> (feas_tol/100), on one side or the other by round-off, and F + lambda^T g
  !> (the Lagrangian, what the step decreases) changes by far less.  Without
  !> the allowance the sign of that round-off decided whether the filter
  !> accepted the last step (HS 18, the offset four-bar with 13
  !> constraints: NF 3 and 13 at -O2, 7 and 19 at -O3 -march=native).  The
  !> caller caps the allowance at sqrt(eps) (1 + |F|): multipliers of a
  !> nearly degenerate B11 reach 1e9 (HS 108) and say nothing about F.
  pure real(dp) function tolerance_band(lambda, g, g_new, tol) result(band)
    real(dp), intent(in) :: lambda(:), g(:), g_new(:), tol
    band = sum(abs(lambda)*abs(min(max(g, -tol), tol) - min(max(g_new, -tol), tol)))
  end function tolerance_band

  !> Does x_new repeat one of the last four iterates (within xtol (1 + |x|))?
  !> x_k itself: a stall (counted; the third in a row stops the run); an
  !> earlier one: a cycle, escaped by damping the step (x_new, t and g_new
  !> updated: halved, quartered, /8); the fourth stops the run.
  subroutine check_cycling(self, prob, x_new, g_new, t, xnorm, stalls, escapes, err)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(inout) :: x_new(:), g_new(:), t
    real(dp), intent(in) :: xnorm
    integer, intent(inout) :: stalls, escapes
    type(error_t), intent(inout) :: err
    integer :: j, hit, m
    real(dp) :: tol
    m = prob%m
    if (self%restored_now) return       ! a restored point may be an earlier (feasible) iterate
    tol = self%opts%xtol*(1.0_dp + xnorm)
    hit = 0
    do j = self%n_log, max(1, self%n_log - 3), -1
      if (maxval(abs(x_new - self%log(j)%x)) <= tol) then
        hit = j
        exit
      end if
    end do
    if (hit == self%n_log) then
      stalls = stalls + 1
      if (stalls >= 3) call err%set(self%method_label(), 'stalled at iteration '//str(self%log(hit)%k + 1)// &
        ': three steps in a row below xtol without convergence (max violation '// &
        str(max_violation(self%g, m), 3)//'); the iterates no longer move')
      return
    end if
    stalls = 0
    if (hit == 0) return
    escapes = escapes + 1
    if (escapes > 3) then
      call err%set(self%method_label(), 'cycling: iteration '//str(self%log(self%n_log)%k + 1)// &
        ' returns to the design of iteration '//str(self%log(hit)%k)//' again after 3 damped escapes')
      return
    end if
    call self%note('cycling: the step returns to the design of iteration '//str(self%log(hit)%k)// &
                   '; step damped by '//str(0.5_dp**escapes, 3))
    x_new = self%x + 0.5_dp**escapes*(x_new - self%x)
    t = t*0.5_dp**escapes
    if (size(g_new) > 0) call prob%constraint_values(x_new, g_new, err)
  end subroutine check_cycling

  !> Short text of a vector for messages.
  function vec_text(v) result(s)
    real(dp), intent(in) :: v(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, min(size(v), 8)
      if (i > 1) s = s//', '
      s = s//str(v(i), 4)
    end do
    if (size(v) > 8) s = s//', ...'
  end function vec_text

  subroutine note(self, text)
    class(gauss_optimizer_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    if (len(self%ev) > 0) then
      self%ev = self%ev//'; '//text
    else
      self%ev = text
    end if
  end subroutine note

  subroutine append_log(self, prob, k, step)
    class(gauss_optimizer_t), intent(inout) :: self
    class(opt_problem_t), intent(in) :: prob
    integer, intent(in) :: k
    real(dp), intent(in) :: step
    type(gauss_iterate_t), allocatable :: tmp(:)
    real(dp) :: viol
    if (self%n_log == size(self%log)) then
      allocate(tmp(2*size(self%log)))
      tmp(1:self%n_log) = self%log(1:self%n_log)
      call move_alloc(tmp, self%log)
    end if
    self%n_log = self%n_log + 1
    viol = max_violation(self%g, prob%m)
    associate (row => self%log(self%n_log))
      row%k = k
      row%nf = prob%count%analyses
      row%f = self%f
      row%max_violation = viol
      row%step = step
      ! a restoration or an arc step is no fraction of s: the distance moved
      if (self%n_log > 1 .and. self%off_chord) row%step = maxval(abs(self%x - self%log(self%n_log - 1)%x))
      row%x = self%x
      row%lambda = self%lambda
      row%active = self%active
      row%events = self%ev
    end associate
    self%ev = ''
    self%off_chord = .false.
    self%restored_now = .false.
    if (viol <= self%opts%feas_tol .and. (.not. self%have_best .or. self%f < self%f_best)) then
      self%have_best = .true.
      self%x_best = self%x
      self%f_best = self%f
      self%k_best = k
    end if
  end subroutine append_log

  !> max(0, g_i) over inequalities and |h_j| over equalities.
  pure real(dp) function max_violation(g, m)
    real(dp), intent(in) :: g(:)
    integer, intent(in) :: m
    max_violation = 0.0_dp
    if (m > 0) max_violation = max(0.0_dp, maxval(g(1:m)))
    if (size(g) > m) max_violation = max(max_violation, maxval(abs(g(m + 1:))))
  end function max_violation

  function ns_variant(method) result(name)
    integer, intent(in) :: method
    character(len=:), allocatable :: name
    if (method == method_gnlc_general) then
      name = 'gnlc_general_ns'
    else
      name = 'gnlc_ns'
    end if
  end function ns_variant
end module gauss_optimizer
