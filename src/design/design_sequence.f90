!> The design loop: sequential approximate problems solved by GNLC.
!>
!> A mechanism analysis costs milliseconds to seconds, the algebra of a
!> Gauss step microseconds; so, as in the approximation concepts of
!> structural optimization (Schmit & Farshi 1974; Vanderplaats 1984), each
!> design iteration k
!>   1. analyses the design x_k and its n forward-difference neighbours
!>      (n + 1 analyses: the constraints g and their gradients);
!>   2. poses the approximate problem: the exact mass (no analysis) plus a
!>      proximal term rho/2 |x - x_k|^2 (the move limit: steps of about
!>      |grad mass|/rho; x are logarithms of sizes, so a step is a relative
!>      size change) subject to the linearised analysis constraints
!>      g_k + grad g_k (x - x_k) <= 0 and the bounds, and solves it with
!>      GNLC.NS (module gauss_optimizer) at no analysis cost: a strongly
!>      convex objective with its exact Hessian and linear constraints, the
!>      class the Gauss step with multipliers (B10, B11) solves exactly;
!>   3. analyses the proposal: accepted when the analysis succeeds and the
!>      worst constraint violation falls, or stays within feas_tol while the
!>      mass falls; otherwise rho is quadrupled (shorter step) and step 2
!>      repeated; after an accepted step rho is halved.  (Structured
!>      residual objectives: a proposal that lowers F but breaks a
!>      constraint is first cut back along itself to where the constraints,
!>      interpolated, meet their aim - doc/design.md.)
!> It stops when the design is feasible and rho |x_try - x_k| (the Lagrangian
!> gradient of the linearised problem at x_k) is below xtol/move_limit.  Every analysis is counted
!> (design_problem).
!> Residual objectives (path, mean-square shaking) pose Gauss-Newton
!> approximate problems, with hessian = 'structured' a secant estimate of the
!> residuals' second-order term added; the minimax objective (peak shaking)
!> poses min tau subject to the linearised samples <= tau (doc/design.md).
module design_sequence
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use optim_problem, only: opt_problem_t
  use gauss_optimizer, only: gauss_optimizer_t, method_gnlc_ns
  use design_problem, only: design_problem_t, design_eval_t
  use linalg, only: symmetric_eigenvalues, identity
  use progress, only: progress_t
  implicit none
  private
  public :: design_sequence_t, design_step_t, step_back

  !> The approximate problem of one design iteration (explicit: no analysis).
  type, extends(opt_problem_t) :: approximate_problem_t
    type(design_problem_t), pointer :: design => null()
    real(dp), allocatable :: center(:)      !< x_k
    real(dp) :: rho = 1.0_dp                !< proximal weight: the move limit
  contains
    procedure :: objective => approximate_objective
  end type approximate_problem_t

  !> The approximate problem of a path objective: Gauss-Newton residuals
  !> (r_k + J_k^T (x - x_k))/sqrt(F0) and the proximal residuals
  !> sqrt(rho/2) (x - x_k), all linear (the Gauss matrix is exact).
  !> With hessian = 'structured' the model is the quadratic
  !> F_k + grad^T s + s^T B s / 2, B = V diag(lambda) V^T, as n linear residuals
  !> (sqrt(lambda) V^T s + V^T grad / sqrt(lambda)) / sqrt(2) (lmat = V
  !> diag(sqrt(lambda)), w = V^T grad / sqrt(lambda)): the same least-squares
  !> form, its Gauss matrix exact.
  type, extends(opt_problem_t) :: approximate_path_t
    real(dp), allocatable :: center(:), r(:), jac(:, :)   !< x_k, r_k, J_k (n x p)
    real(dp), allocatable :: lmat(:, :), w(:)             !< the quadratic model (structured)
    real(dp), allocatable :: shift(:)                     !< added to the proximal residuals (minimax)
    real(dp) :: rho = 1.0_dp, f0 = 1.0_dp
  contains
    procedure :: residuals => approximate_residuals
    procedure :: jacobian => approximate_jacobian
  end type approximate_path_t

  !> One accepted design (a row of the history).
  type :: design_step_t
    integer :: k = 0
    integer :: analyses = 0                 !< analyses so far
    real(dp) :: cpu = 0.0_dp                !< analysis CPU so far
    real(dp) :: mass = 0.0_dp
    real(dp) :: objective = 0.0_dp          !< scaled objective (mass / initial, or path error / initial)
    real(dp) :: path_error = 0.0_dp, rigid_path_error = 0.0_dp
    real(dp) :: peak_shaking = 0.0_dp, rms_shaking = 0.0_dp
    real(dp) :: peak_bearing = 0.0_dp, rms_bearing = 0.0_dp
    real(dp) :: max_violation = 0.0_dp
    real(dp) :: move_limit = 0.0_dp         !< 1/rho of the next approximate problem
    real(dp), allocatable :: x(:), g(:)
    character(len=:), allocatable :: events
  end type design_step_t

  type :: design_sequence_t
    integer :: max_iterations = 30
    real(dp) :: xtol = 1.0e-3_dp            !< step test on x (log sizes: relative)
    real(dp) :: feas_tol = 1.0e-3_dp        !< constraint test (log ratios: relative)
    real(dp) :: move_limit = 0.3_dp         !< initial rho = 1/move_limit
    !> residual objectives: 'gauss' (the Gauss-Newton matrix 2 J J^T / F0) or
    !> 'structured' (plus a secant estimate S of the residuals' second-order
    !> term, Dennis-Gay-Welsch, and the move limit set by the ratio of the
    !> actual to the predicted decrease)
    character(len=16) :: hessian = 'gauss'
    integer :: fd_analyses = 0              !< analyses spent on finite differences
    logical :: converged = .false.
    character(len=:), allocatable :: message
    integer :: iterations = 0
    integer :: rejections = 0
    real(dp), allocatable :: x(:)
    integer :: n_steps = 0
    type(design_step_t), allocatable :: steps(:)
  contains
    procedure :: solve => sequence_solve
    procedure, private :: next_design
    procedure, private :: record
    procedure, private :: start_history
    procedure, private :: propose
  end type design_sequence_t

contains

  subroutine approximate_objective(self, x, f, err)
    class(approximate_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    call self%design%objective(x, f, err)
    f = f + 0.5_dp*self%rho*sum((x - self%center)**2)
  end subroutine approximate_objective

  subroutine approximate_residuals(self, x, phi, err)
    class(approximate_path_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    integer :: p
    if (err%failed()) return
    if (allocated(self%lmat)) then
      p = size(self%w)
      phi(1:p) = (matmul(x - self%center, self%lmat) + self%w)/sqrt(2.0_dp)
    else
      p = size(self%r)
      phi(1:p) = (self%r + matmul(x - self%center, self%jac))/sqrt(self%f0)
    end if
    phi(p + 1:) = sqrt(0.5_dp*self%rho)*(x - self%center)
    if (allocated(self%shift)) phi(p + 1:) = phi(p + 1:) + self%shift
  end subroutine approximate_residuals

  subroutine approximate_jacobian(self, x, phi, jac, err)
    class(approximate_path_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), phi(:)
    real(dp), intent(out) :: jac(:, :)
    type(error_t), intent(inout) :: err
    integer :: p, j
    if (err%failed()) return
    if (.false.) jac(1, 1) = x(1) + phi(1)
    jac = 0.0_dp
    if (allocated(self%lmat)) then
      p = size(self%w)
      jac(:, 1:p) = self%lmat/sqrt(2.0_dp)
    else
      p = size(self%r)
      jac(:, 1:p) = self%jac/sqrt(self%f0)
    end if
    do j = 1, size(x)
      jac(j, p + j) = sqrt(0.5_dp*self%rho)
    end do
  end subroutine approximate_jacobian

  !> The design loop of the module header from x0: per iteration the
  !> derivatives at x_k, the proposal (next_design), the move limit of the
  !> next one (controlled_rho) and the stall test; the history in self%steps.
  subroutine sequence_solve(self, prob, x0, err)
    class(design_sequence_t), intent(inout) :: self
    type(design_problem_t), target, intent(inout) :: prob
    real(dp), intent(in) :: x0(:)
    type(error_t), intent(inout) :: err
    integer :: n, nc, k
    real(dp), allocatable :: g(:), dg(:, :), x_try(:), g_try(:), r(:), dr(:, :), r_try(:)
    real(dp) :: delta, viol, viol_try, mass, mass_try
    logical :: ok, accepted
    integer :: stalls, nf_before
    logical :: structured, have_old
    real(dp), allocatable :: smat(:, :), lmat(:, :), w(:), grad(:), x_old(:), dr_old(:, :)
    type(progress_t) :: bar
    character(len=:), allocatable :: events
    n = size(x0)
    nc = prob%n_analysis_constraints()
    call self%start_history(x0)
    delta = 1.0_dp/self%move_limit           ! rho of the proximal term
    stalls = 0
    events = ''
    structured = self%hessian == 'structured' .and. prob%has_residuals() .and. .not. prob%is_minimax()
    have_old = .false.
    allocate(smat(n, n), x_old(n), dr_old(n, 0), grad(n))
    grad = 0.0_dp
    smat = 0.0_dp
    x_old = x0
    ok = .false.
    viol_try = huge(1.0_dp)
    mass_try = huge(1.0_dp)
    call constraints_at(prob, self%x, g, r, ok)
    if (.not. ok) then
      call err%set('design', 'the initial design cannot be analysed: '//prob%last_failure)
      return
    end if
    mass = scaled_mass(prob, self%x)
    viol = max(0.0_dp, maxval([0.0_dp, g]))
    call self%record(prob, 0, 'initial design', mass, viol, delta, g)
    call bar%start('design iterations', 0.0_dp, real(self%max_iterations, dp), counts=.true.)
    do k = 1, self%max_iterations
      self%iterations = k
      call bar%update(real(k - 1, dp), str(prob%n_analyses)//' analyses, mass '//str(mass, 5)// &
                      ', violation '//str(viol, 3))
      nf_before = prob%n_analyses
      call gradients(prob, self%x, g, r, dg, dr, ok)
      self%fd_analyses = self%fd_analyses + prob%n_analyses - nf_before
      if (ok .and. structured) then
        if (have_old) call secant_update(smat, self%x - x_old, dr_old, dr, r, prob%f0)
        call structured_model(prob%f0, smat, dr, r, grad, lmat, w)
      end if
      if (.not. ok) then
        call err%set('design', 'iteration '//str(k)//': a finite-difference neighbour of the design cannot be '// &
                     'analysed: '//prob%last_failure)
        return
      end if
      call self%next_design(prob, structured, g, dg, r, dr, lmat, w, grad, viol, mass, delta, x_try, g_try, r_try, &
                            viol_try, mass_try, accepted, events)
      if (self%converged) then
        self%message = converged_message(structured, prob%has_residuals())
        exit
      end if
      if (.not. accepted) then
        self%message = 'no step is accepted however short (rho > 1e6)'
        exit
      end if
      if (structured .or. prob%is_minimax()) then
        delta = controlled_rho(prob, structured, delta, mass, mass_try, grad, lmat, x_try - self%x, r, dr)
        x_old = self%x
        dr_old = dr
        have_old = .true.
      else
        delta = max(0.5_dp*delta, 1.0e-3_dp)
      end if
      ! a stall: two accepted designs in a row that lower the mass by less
      ! than xtol/10 (the peak stress over sampled crank angles has kinks
      ! where the KKT test cannot be met to xtol)
      if (viol_try <= self%feas_tol .and. mass - mass_try < 0.1_dp*self%xtol*mass) then
        stalls = stalls + 1
      else
        stalls = 0
      end if
      self%x = x_try
      g = g_try
      r = r_try
      viol = viol_try
      mass = mass_try
      call self%record(prob, k, events, mass, viol, delta, g)
      if (stalls >= 2) then
        self%converged = .true.
        self%message = 'feasible, and the objective changed by less than xtol/10 twice in a row'
        exit
      end if
    end do
    call bar%finish()
    if (.not. allocated(self%message)) self%message = 'iteration limit reached'
  end subroutine sequence_solve

  !> No history yet, the design at x0.
  subroutine start_history(self, x0)
    class(design_sequence_t), intent(inout) :: self
    real(dp), intent(in) :: x0(:)
    self%x = x0
    self%converged = .false.
    self%n_steps = 0
    self%rejections = 0
    allocate(self%steps(0))
    self%fd_analyses = 0
  end subroutine start_history

  !> A row of the history: design kk (self%x, its objective, violation and
  !> constraints g), the move limit 1/delta of its next approximate problem.
  subroutine record(self, prob, kk, text, mass, viol, delta, g)
    class(design_sequence_t), intent(inout) :: self
    type(design_problem_t), intent(inout) :: prob
    integer, intent(in) :: kk
    character(len=*), intent(in) :: text
    real(dp), intent(in) :: mass, viol, delta, g(:)
    type(design_step_t) :: st
    st%k = kk
    st%analyses = prob%n_analyses
    st%cpu = prob%cpu_analyses
    call describe(prob, self%x, st)
    st%objective = mass
    st%max_violation = viol
    st%move_limit = 1.0_dp/delta
    st%x = self%x
    st%g = g
    st%events = trim(text)
    self%steps = [self%steps, st]
    self%n_steps = self%n_steps + 1
  end subroutine record

  !> The structured model of a residual objective at x_k: grad F = 2 J r / F0
  !> and B = 2 J J^T / F0 + S (S the secant estimate of the residuals'
  !> second-order term) as the linear residuals lmat, w (quadratic_model).
  subroutine structured_model(f0, smat, dr, r, grad, lmat, w)
    real(dp), intent(in) :: f0, smat(:, :), dr(:, :), r(:)
    real(dp), intent(inout) :: grad(:)
    real(dp), allocatable, intent(inout) :: lmat(:, :), w(:)
    real(dp), allocatable :: bmat(:, :)
    grad = 2.0_dp*matmul(dr, r)/f0
    bmat = 2.0_dp*matmul(dr, transpose(dr))/f0 + smat
    call quadratic_model(bmat, grad, lmat, w)
  end subroutine structured_model

  !> One design iteration's proposal: the approximate problem at x_k (rho =
  !> delta) solved and its solution analysed, until a proposal is accepted
  !> (accepted: x_try, g_try, r_try, viol_try, mass_try hold it), x_k passes
  !> the convergence test (self%converged; no analysis spent on it), or rho
  !> exceeds 1e6.  A rejected proposal is stepped back or answered by
  !> corrected linearisations once (structured), else by a larger rho.
  !> events: what happened, for the history.
  subroutine next_design(self, prob, structured, g, dg, r, dr, lmat, w, grad, viol, mass, delta, x_try, g_try, &
                         r_try, viol_try, mass_try, accepted, events)
    class(design_sequence_t), intent(inout) :: self
    type(design_problem_t), target, intent(inout) :: prob
    logical, intent(in) :: structured
    real(dp), intent(in) :: g(:), dg(:, :), r(:), dr(:, :), grad(:), viol, mass
    real(dp), allocatable, intent(in) :: lmat(:, :), w(:)     !< the structured model (allocated if structured)
    real(dp), intent(inout) :: delta, viol_try, mass_try
    real(dp), allocatable, intent(inout) :: x_try(:), g_try(:), r_try(:)
    logical, intent(out) :: accepted
    character(len=:), allocatable, intent(inout) :: events
    real(dp), allocatable :: g_lin(:)
    real(dp) :: step_len, t_back
    logical :: ok, small_step, corrected, retry, interpolated, shifted
    events = ''
    accepted = .false.
    corrected = .false.
    shifted = .false.
    interpolated = .false.
    retry = .false.
    g_lin = g
    do while (delta <= 1.0e6_dp)
      if (retry) then
        retry = .false.      ! x_try set by the step back below
      else
        call self%propose(prob, structured, g, g_lin, dg, r, dr, lmat, w, grad, mass, delta, x_try, events, small_step)
        if (small_step .and. viol <= self%feas_tol .and. .not. shifted) then
          self%converged = .true.
          exit
        end if
      end if
      call constraints_at(prob, x_try, g_try, r_try, ok)
      if (ok) then
        viol_try = max(0.0_dp, maxval([0.0_dp, g_try]))
        mass_try = scaled_mass(prob, x_try)
        accepted = viol_try < viol - 0.1_dp*self%feas_tol .or. &
                   (viol_try <= max(viol, self%feas_tol) .and. mass_try <= mass)
      end if
      if (accepted) exit
      step_len = maxval(abs(x_try - self%x))
      self%rejections = self%rejections + 1
      if (structured .and. ok .and. .not. (corrected .or. interpolated) .and. mass_try < mass) then
        ! F fell but a constraint's linearisation was wrong; once per
        ! iteration either step back along the proposal to where each
        ! violated constraint, interpolated quadratically between x_k
        ! (value and gradient) and the proposal, reaches the aim (the
        ! constraint interpolation of feasible-direction methods,
        ! Vanderplaats 1984), or, when that is less than a fifth of the
        ! step (an active constraint the step ran along), shift each
        ! underestimating linearised constraint by its error at the
        ! proposal and solve again (the second-order correction of SQP)
        t_back = step_back(g, matmul(x_try - self%x, dg), g_try, 0.5_dp*self%feas_tol)
        if (t_back >= 0.2_dp) then
          interpolated = .true.
          retry = .true.
          events = events//'rejected (violation '//str(viol_try, 3)//', objective '//str(mass_try, 6)// &
                   '): step back to '//str(t_back, 3)//' of it; '
          x_try = self%x + t_back*(x_try - self%x)
          cycle
        end if
        corrected = .true.
        shifted = .true.
        g_lin = g + max(0.0_dp, g_try - g - matmul(x_try - self%x, dg))
        events = events//'rejected (violation '//str(viol_try, 3)//', objective '//str(mass_try, 6)// &
                 '): linearised constraints corrected; '
        cycle
      end if
      ! the corrected problem's proposal failed too: back to the
      ! linearisation at x_k (the correction, right at the proposal, can
      ! make x_k itself look infeasible) with a shorter step
      g_lin = g
      shifted = .false.
      if (ok) then
        events = events//'rejected (violation '//str(viol_try, 3)//', objective '//str(mass_try, 6)//'); '
      else
        events = events//'rejected: '//prob%last_failure//'; '
      end if
      delta = 4.0_dp*delta
      ! structured: when rho is far below the model's curvature,
      ! quadrupling it hardly shortens the step; ask for a quarter of it
      if (structured) delta = max(delta, rho_for_step(prob, self%x, g_lin, dg, r, dr, 0.5_dp*self%feas_tol, &
                                                      lmat, w, 0.25_dp*step_len, delta))
    end do
  end subroutine next_design

  !> The solution x_try of the approximate problem at x_k (rho = delta;
  !> g_lin: the constraint values it linearises) and small_step, its part
  !> of the convergence test: no analysis is spent on either.
  subroutine propose(self, prob, structured, g, g_lin, dg, r, dr, lmat, w, grad, mass, delta, x_try, events, small_step)
    class(design_sequence_t), intent(in) :: self
    type(design_problem_t), target, intent(inout) :: prob
    logical, intent(in) :: structured
    real(dp), intent(in) :: g(:), g_lin(:), dg(:, :), r(:), dr(:, :), grad(:), mass, delta
    real(dp), allocatable, intent(in) :: lmat(:, :), w(:)     !< the structured model (allocated if structured)
    real(dp), allocatable, intent(inout) :: x_try(:)
    character(len=:), allocatable, intent(inout) :: events
    logical, intent(out) :: small_step
    if (prob%is_minimax()) then
      call minimax_step(prob, self%x, g, dg, r, dr, delta, 0.5_dp*self%feas_tol, x_try, events)
    else if (structured) then
      call approximate_step(prob, self%x, g_lin, dg, r, dr, delta, 0.5_dp*self%feas_tol, x_try, events, lmat, w)
    else
      call approximate_step(prob, self%x, g_lin, dg, r, dr, delta, 0.5_dp*self%feas_tol, x_try, events)
    end if
    ! mass: rho |step| is the size of the gradient of the Lagrangian of
    ! the linearised problem at x_k (the proximal term has no gradient
    ! there): small, and x_k feasible, is the KKT test.  Path objectives:
    ! the Gauss matrix 2 J^T J / F0 outweighs rho near the answer, so
    ! rho |step| underestimates the gradient; the test is the step itself
    ! (Gauss-Newton steps shrink with the distance to a zero-residual answer)
    if (prob%has_residuals()) then
      small_step = maxval(abs(x_try - self%x)) <= self%xtol
    else
      small_step = delta*self%move_limit*maxval(abs(x_try - self%x)) <= self%xtol
    end if
    ! structured: the model (exact curvature estimate, fresh derivatives)
    ! promises less than xtol/10 of F, the move limit not binding
    if (structured .and. .not. small_step .and. delta <= 1.0_dp/self%move_limit) &
      small_step = model_decrease(grad, lmat, x_try - self%x) <= 0.1_dp*self%xtol*mass
  end subroutine propose

  !> The message of a converged run (the test that passed).
  function converged_message(structured, residuals) result(text)
    logical, intent(in) :: structured, residuals
    character(len=:), allocatable :: text
    if (structured) then
      text = 'feasible, and the step of the approximate problem below xtol or its predicted '// &
             'decrease below xtol/10 of F'
    else if (residuals) then
      text = 'feasible, and the step of the approximate problem below xtol'
    else
      text = 'feasible, and the approximate problem''s KKT residual below xtol'
    end if
  end function converged_message

  !> rho of the next iteration after an accepted step s (structured and
  !> minimax objectives), by Levenberg-Marquardt control: the ratio of the
  !> actual to the model's decrease (the model with the floored B it
  !> minimised; for the minimax, the largest linearised r_k).
  real(dp) function controlled_rho(prob, structured, delta, mass, mass_try, grad, lmat, s, r, dr) result(rho)
    type(design_problem_t), intent(in) :: prob
    logical, intent(in) :: structured
    real(dp), intent(in) :: delta, mass, mass_try, grad(:), s(:), r(:), dr(:, :)
    real(dp), allocatable, intent(in) :: lmat(:, :)     !< the structured model (allocated if structured)
    real(dp) :: ratio
    if (structured) then
      ratio = (mass - mass_try)/max(model_decrease(grad, lmat, s), tiny(1.0_dp))
    else
      ratio = (mass - mass_try)/max(mass - max(0.0_dp, maxval(r + matmul(s, dr)))/prob%f0, tiny(1.0_dp))
    end if
    rho = delta
    if (ratio >= 0.75_dp) then
      rho = max(0.125_dp*delta, 1.0e-6_dp)
    else if (ratio >= 0.25_dp) then
      rho = max(0.5_dp*delta, 1.0e-6_dp)
    end if
  end function controlled_rho

  !> Mass and path errors of design x (from the cache: no new analysis).
  subroutine describe(prob, x, st)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:)
    type(design_step_t), intent(inout) :: st
    type(design_eval_t) :: ev
    call prob%evaluate(x, ev)
    st%mass = ev%mass
    st%path_error = ev%path_error
    st%rigid_path_error = ev%rigid_path_error
    st%peak_shaking = ev%peak_shaking
    st%rms_shaking = ev%rms_shaking
    st%peak_bearing = ev%peak_bearing
    st%rms_bearing = ev%rms_bearing
  end subroutine describe

  !> The analysis constraints at x and the objective's residuals (path
  !> objectives; ok = .false. when the analysis fails).
  subroutine constraints_at(prob, x, g, r, ok)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:)
    real(dp), allocatable, intent(out) :: g(:), r(:)
    logical, intent(out) :: ok
    type(error_t) :: err
    type(design_eval_t) :: ev
    integer :: i
    allocate(g(prob%n_analysis_constraints()), r(prob%n_residuals_design()))
    do i = 1, size(g)
      call prob%general_constraint(i, x, g(i), err)
    end do
    ok = all(ieee_is_finite(g)) .and. .not. err%failed()
    if (size(r) == 0) return
    call prob%evaluate(x, ev)
    ok = ok .and. ev%ok
    if (.not. ev%ok) return
    if (prob%objective_kind == 'path_rigid') then
      r = ev%rigid_residual
    else
      r = ev%residual
    end if
  end subroutine constraints_at

  !> Derivatives of the analysis constraints and of the objective's
  !> residuals: from the periodic orbit's sensitivities where they apply
  !> (one sensitivity solve, counted as one analysis per speed), else - or
  !> when that solve fails - forward differences: n analyses.
  subroutine gradients(prob, x, g, r, dg, dr, ok)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:), g(:), r(:)
    real(dp), allocatable, intent(out) :: dg(:, :), dr(:, :)
    logical, intent(out) :: ok
    real(dp) :: xp(size(x))
    real(dp), allocatable :: gp(:), rp(:)
    real(dp) :: h
    integer :: j
    if (prob%variational_applies()) then
      call prob%derivatives_at(x, dg, dr, ok)
      if (ok) return
      deallocate(dg, dr)
    end if
    allocate(dg(size(x), size(g)), dr(size(x), size(r)))
    ok = .true.
    do j = 1, size(x)
      xp = x
      h = prob%fd_rel_step*max(abs(x(j)), 1.0_dp)
      xp(j) = x(j) + h
      call constraints_at(prob, xp, gp, rp, ok)
      if (.not. ok) return
      call prob%neighbour_constraints(x, xp, gp)
      dg(j, :) = (gp - g)/(xp(j) - x(j))
      dr(j, :) = (rp - r)/(xp(j) - x(j))
    end do
  end subroutine gradients

  real(dp) function scaled_mass(prob, x) result(f)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:)
    type(error_t) :: err
    call prob%objective(x, f, err)
  end function scaled_mass

  !> Decrease of F the quadratic model grad^T s + |lmat^T s|^2 / 2 predicts.
  pure real(dp) function model_decrease(grad, lmat, s) result(d)
    real(dp), intent(in) :: grad(:), lmat(:, :), s(:)
    integer :: j
    d = -dot_product(grad, s)
    do j = 1, size(lmat, 2)
      d = d - 0.5_dp*dot_product(s, lmat(:, j))**2
    end do
  end function model_decrease

  !> Symmetric rank-one secant update of S, the estimate of the residuals'
  !> second-order term sum r_i Hess r_i (scaled, 2/F0) that the Gauss-Newton
  !> matrix leaves out (structured quasi-Newton, as in NL2SOL: J.E. Dennis,
  !> D.M. Gay and R.E. Welsch, ACM TOMS 7 (1981) 348-368, which uses a
  !> positive-curvature update instead): S s = y#, y# = 2 (J+ - J) r+ / F0
  !> (the change of the full gradient minus that of the Gauss-Newton part).
  !> Rank one may make S indefinite, as the term is where the residuals are
  !> large; skipped when the denominator is below 1e-8 |v| |s|.
  subroutine secant_update(smat, s, dr_old, dr, r, f0)
    real(dp), intent(inout) :: smat(:, :)
    real(dp), intent(in) :: s(:), dr_old(:, :), dr(:, :), r(:), f0
    real(dp) :: v(size(s)), den
    integer :: j
    v = -matmul(smat, s)
    do j = 1, size(r)
      v = v + 2.0_dp*(dr(:, j) - dr_old(:, j))*r(j)/f0
    end do
    den = dot_product(v, s)
    if (.not. abs(den) > 1.0e-8_dp*norm2(v)*norm2(s)) return
    do j = 1, size(s)
      smat(:, j) = smat(:, j) + v*v(j)/den
    end do
  end subroutine secant_update

  !> The quadratic model grad^T s + s^T B s / 2 as linear residuals: B =
  !> V diag(lambda) V^T with each eigenvalue replaced by its magnitude,
  !> floored at 1e-6 of the largest (a direction of negative curvature is
  !> then followed downhill by a Newton-sized step, not left to the move
  !> limit alone), lmat = V diag(sqrt(lambda)), w = V^T grad / sqrt(lambda).
  subroutine quadratic_model(bmat, grad, lmat, w)
    real(dp), intent(in) :: bmat(:, :), grad(:)
    real(dp), allocatable, intent(out) :: lmat(:, :), w(:)
    real(dp) :: lam(size(grad)), v(size(grad), size(grad)), floor
    type(error_t) :: err
    integer :: j, n
    n = size(grad)
    call symmetric_eigenvalues(0.5_dp*(bmat + transpose(bmat)), lam, err, v)
    if (err%failed()) then
      ! no decomposition: the identity scaled by the trace
      v = identity(n)
      lam = max(sum([(abs(bmat(j, j)), j = 1, n)])/n, tiny(1.0_dp))
    end if
    floor = max(1.0e-6_dp*maxval(abs(lam)), tiny(1.0_dp))
    lam = max(abs(lam), floor)
    allocate(lmat(n, n), w(n))
    do j = 1, n
      lmat(:, j) = v(:, j)*sqrt(lam(j))
      w(j) = dot_product(v(:, j), grad)/sqrt(lam(j))
    end do
  end subroutine quadratic_model

  !> The minimax approximate problem solved by GNLC.NS: r and dr are the
  !> samples' |shaking force| and their gradients.  In y = (x, tau): every
  !> linearised r_k(x)/F0 at most tau, tau >= 0; the objective
  !> tau + rho/2 |y - y_k|^2 is, up to a constant, the sum of squares of the
  !> linear residuals sqrt(rho/2) (y - y_k) + (0, .., 0, sqrt(1/(2 rho)))
  !> (an approximate_path_t without analysis residuals: its Gauss matrix exact).
  subroutine minimax_step(prob, x, g, dg, r, dr, delta, margin, x_try, events)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:), g(:), dg(:, :), r(:), dr(:, :), delta, margin
    real(dp), allocatable, intent(out) :: x_try(:)
    character(len=:), allocatable, intent(inout) :: events
    type(approximate_path_t) :: ap
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    real(dp) :: b(size(x) + 1), lower(size(x)), upper(size(x))
    integer :: i, n, nr, nc
    n = size(x)
    nr = size(r)
    nc = size(g)
    allocate(ap%center(n + 1))
    ap%center(1:n) = x
    ap%center(n + 1) = maxval(r)/prob%f0
    ap%rho = delta
    allocate(ap%r(0), ap%jac(n + 1, 0), ap%shift(n + 1))
    ap%shift = 0.0_dp
    ap%shift(n + 1) = sqrt(0.5_dp/ap%rho)
    call ap%init_problem('approximate minimax design problem', n + 1, n + 1, nr + 1 + nc + 2*n)
    do i = 1, nr
      b = [dr(:, i)/prob%f0, -1.0_dp]
      call ap%set_linear_constraint(i, b, dot_product(dr(:, i), x)/prob%f0 - r(i)/prob%f0)
    end do
    b = 0.0_dp
    b(n + 1) = -1.0_dp
    call ap%set_linear_constraint(nr + 1, b, 0.0_dp)
    do i = 1, nc
      call ap%set_linear_constraint(nr + 1 + i, [dg(:, i), 0.0_dp], dot_product(dg(:, i), x) - g(i) - margin)
    end do
    do i = 1, n
      lower(i) = prob%var(i)%to_x(prob%var(i)%lower)
      upper(i) = prob%var(i)%to_x(prob%var(i)%upper)
      b = 0.0_dp
      b(i) = -1.0_dp
      call ap%set_linear_constraint(nr + nc + 2*i, b, -lower(i))
      b(i) = 1.0_dp
      call ap%set_linear_constraint(nr + nc + 2*i + 1, b, upper(i))
    end do
    call set_gnlc_options(opt)
    call opt%solve(ap, [min(max(x, lower), upper), ap%center(n + 1)], err)
    ! its solution, or where GNLC stopped (the linearised peak constraints
    ! are degenerate where tau reaches 0; the analysis of the proposal judges it)
    if (allocated(opt%x)) then
      x_try = min(max(opt%x(1:n), lower), upper)
    else if (opt%have_best) then
      x_try = min(max(opt%x_best(1:n), lower), upper)
    else
      x_try = min(max(x, lower), upper)
    end if
    if (err%failed()) events = events//'approximate problem: '//err%text()//'; '
  end subroutine minimax_step

  !> The fraction t in (0, 1) of a step s at which every violated constraint,
  !> modelled as g(t) = g + a t + c t^2 (a = grad g . s, c from its value
  !> g_try at t = 1), first reaches -margin; 0 when some constraint is
  !> already there at t = 0 (an active one) or the model has no root.
  pure real(dp) function step_back(g, a, g_try, margin) result(t)
    real(dp), intent(in) :: g(:), a(:), g_try(:), margin
    real(dp) :: c, b0, disc, ti
    integer :: i
    t = 1.0_dp
    do i = 1, size(g)
      if (g_try(i) <= margin) cycle
      b0 = g(i) + margin
      if (b0 >= 0.0_dp) then
        t = 0.0_dp
        return
      end if
      c = g_try(i) - g(i) - a(i)
      if (abs(c) <= 1.0e-12_dp*abs(a(i))) then
        ti = -b0/a(i)
      else
        disc = a(i)**2 - 4.0_dp*c*b0
        if (disc < 0.0_dp) then
          t = 0.0_dp
          return
        end if
        ti = (-a(i) + sqrt(disc))/(2.0_dp*c)
        if (ti <= 0.0_dp .or. ti > 1.0_dp) ti = (-a(i) - sqrt(disc))/(2.0_dp*c)
      end if
      if (.not. (ti > 0.0_dp .and. ti < 1.0_dp)) then
        t = 0.0_dp
        return
      end if
      t = min(t, ti)
    end do
    if (t >= 1.0_dp) t = 0.0_dp
  end function step_back

  !> The smallest proximal weight rho >= rho_min (to a factor 1.1) whose
  !> approximate step changes no variable by more than step_max: bisection in
  !> ln rho, each trial an approximate problem (GNLC.NS, no analysis).
  real(dp) function rho_for_step(prob, x, g, dg, r, dr, margin, lmat, w, step_max, rho_min) result(rho)
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:), g(:), dg(:, :), r(:), dr(:, :), margin, lmat(:, :), w(:), step_max, rho_min
    real(dp), allocatable :: x_try(:)
    character(len=:), allocatable :: events
    real(dp) :: lo, hi
    integer :: it
    events = ''
    rho = rho_min
    if (.not. longer(rho)) return
    lo = log(rho_min)
    hi = lo
    do it = 1, 60
      hi = hi + log(16.0_dp)
      if (.not. longer(exp(hi))) exit
    end do
    do while (hi - lo > log(1.1_dp))
      if (longer(exp(0.5_dp*(lo + hi)))) then
        lo = 0.5_dp*(lo + hi)
      else
        hi = 0.5_dp*(lo + hi)
      end if
    end do
    rho = exp(hi)
  contains
    logical function longer(rho_try)
      real(dp), intent(in) :: rho_try
      call approximate_step(prob, x, g, dg, r, dr, rho_try, margin, x_try, events, lmat, w)
      longer = maxval(abs(x_try - x)) > step_max
    end function longer
  end function rho_for_step

  !> GNLC.NS, tight: an approximate problem costs no analysis.
  subroutine set_gnlc_options(opt)
    type(gauss_optimizer_t), intent(inout) :: opt
    opt%opts%method = method_gnlc_ns
    opt%opts%max_iter = 100
    opt%opts%xtol = 1.0e-7_dp
    opt%opts%feas_tol = 1.0e-7_dp
    opt%opts%ftol = 1.0e-10_dp
  end subroutine set_gnlc_options

  !> Solve the approximate problem within the move limit (GNLC.NS, no
  !> analysis); the proposal is its solution, or its last iterate.
  subroutine approximate_step(prob, x, g, dg, r, dr, delta, margin, x_try, events, lmat, w)
    type(design_problem_t), target, intent(inout) :: prob
    real(dp), intent(in) :: x(:), g(:), dg(:, :), delta     !< delta: rho of the proximal term
    real(dp), intent(in) :: r(:), dr(:, :)                  !< residuals and their Jacobian (path objectives)
    real(dp), intent(in) :: margin
    real(dp), intent(in), optional :: lmat(:, :), w(:)      !< the structured quadratic model (approximate_path_t)
    real(dp), allocatable, intent(out) :: x_try(:)
    character(len=:), allocatable, intent(inout) :: events
    type(approximate_problem_t), target :: ap_mass
    type(approximate_path_t), target :: ap_path
    class(opt_problem_t), pointer :: ap
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    real(dp) :: lower(size(x)), upper(size(x))
    integer :: i
    if (prob%has_residuals()) then
      ap_path%center = x
      ap_path%rho = delta
      ap_path%r = r
      ap_path%jac = dr
      ap_path%f0 = prob%f0
      ap => ap_path
      if (present(lmat)) then
        ap_path%lmat = lmat
        ap_path%w = w
        call ap%init_problem('approximate design problem', size(x), 2*size(x), size(g) + 2*size(x))
      else
        call ap%init_problem('approximate design problem', size(x), size(r) + size(x), size(g) + 2*size(x))
      end if
    else
      ap_mass%design => prob
      ap_mass%center = x
      ap_mass%rho = delta
      ap => ap_mass
      call ap%init_problem('approximate design problem', size(x), 0, size(g) + 2*size(x))
    end if
    do i = 1, size(g)
      ! aim inside by half the tolerance: the linearisation error at the
      ! boundary then does not push every proposal just outside it
      call ap%set_linear_constraint(i, dg(:, i), dot_product(dg(:, i), x) - g(i) - margin)
    end do
    do i = 1, size(x)
      lower(i) = prob%var(i)%to_x(prob%var(i)%lower)
      upper(i) = prob%var(i)%to_x(prob%var(i)%upper)
      call ap%set_linear_constraint(size(g) + 2*i - 1, unit(i, -1.0_dp), -lower(i))
      call ap%set_linear_constraint(size(g) + 2*i, unit(i, 1.0_dp), upper(i))
    end do
    call set_gnlc_options(opt)
    call opt%solve(ap, min(max(x, lower), upper), err)
    ! its solution; if GNLC stopped short, its best feasible iterate
    if (.not. err%failed() .and. allocated(opt%x)) then
      x_try = min(max(opt%x, lower), upper)
    else if (opt%have_best) then
      x_try = min(max(opt%x_best, lower), upper)
    else
      x_try = min(max(x, lower), upper)
    end if
    if (err%failed()) events = events//'approximate problem: '//err%text()//'; '
  contains
    pure function unit(j, v) result(e)
      integer, intent(in) :: j
      real(dp), intent(in) :: v
      real(dp) :: e(size(x))
      e = 0.0_dp
      e(j) = v
    end function unit
  end subroutine approximate_step
end module design_sequence
