!> Tests of the Gauss family (module gauss_optimizer): P's Table I for
!> Rosen-Suzuki, literature optima, and every bad case of the issue (infeasible
!> GNLC start, singular J J^T, B11 without solution, iteration limit, Potter's
!> step-back cycling, inconsistent method/problem pairs).
module test_gauss_optimizer_suite
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t, create_problem, quadratic_problem_t
  use strings, only: str
  use gauss_optimizer
  use assertions
  implicit none
  private
  public :: run_all

  !> phi = (log(x1/3), x2 - 1): outside x1 > 0 the residual is NaN
  !> (bad = 1) or +Inf (bad = 2), as a user's analysis may return when a
  !> design leaves its domain or overflows.  From x1 = 30 the Gauss step
  !> x1 - x1 log(x1/3) lands at x1 = -39.
  !> HS 6 with h = 10 (x2 - x1^2) = 0 as a general equality (value only:
  !> gradient and Hessian by differences).
  type, extends(quadratic_problem_t) :: hs6_general_t
  contains
    procedure :: general_constraint => hs6_h
  end type hs6_general_t

  type, extends(opt_problem_t) :: log_domain_t
    integer :: bad = 1
  contains
    procedure :: residuals => log_residuals
    procedure :: jacobian => log_jacobian
  end type log_domain_t

  !> The run under test of every test that solves a library problem through
  !> run_problem (the suite's fixture): the optimizer, the problem, the
  !> library's data for it and the run's error.  Tests that build their own
  !> problem declare their own.
  type(gauss_optimizer_t) :: opt
  class(opt_problem_t), allocatable :: prob
  type(problem_info_t) :: info
  type(error_t) :: err

contains

  subroutine run_all()
    call run_test('rosen_suzuki_table_I_gnlc_ns_and_gnlc', test_table_one)
    call run_test('rosen_suzuki_nf_equals_ni_plus_one', test_nf_ni)
    call run_test('plain_b13_step_back_lands_inside_and_converges', test_plain_b13)
    call run_test('gnlc_infeasible_start_suggests_gnlc_ns', test_infeasible_start)
    call run_test('unconstrained_gauss_mgh_problems', test_unconstrained)
    call run_test('gauss_constrained_hs21_hs35_agree_with_gnlc', test_linear_constraints)
    call run_test('one_iteration_when_start_on_optimal_active_set', test_one_iteration)
    call run_test('rank_deficient_JJt_reported_or_regularized', test_rank_deficient)
    call run_test('overdetermined_violated_set_made_square_and_converges', test_powell_fallback)
    call run_test('iteration_limit_reports_best_feasible_point', test_iteration_limit)
    call run_test('potter_step_back_cycling_reported_and_escaped', test_potter_cycling)
    call run_test('potter_general_constraints_converge', test_general_constraints)
    call run_test('gnlc_ns_from_infeasible_literature_starts', test_ns_infeasible_starts)
    call run_test('method_problem_mismatches_are_input_errors', test_mismatch)
    call run_test('non_finite_trial_is_a_failed_trial', test_non_finite_trial)
    call run_test('hs6_regularized_declares_convergence', test_hs6_regularized)
    call run_test('nonlinear_equality_hs6_with_defaults', test_hs6_equality)
    call run_test('released_bound_with_negative_curvature_goes_to_the_opposite_bound', test_bound_flip)
  end subroutine run_all

  !> F = -(x1 + 2)^2 + (x2 - x1)^2 on -1 <= x1 <= 1 (x2 free), from (-1, 0)
  !> with defaults.  With x2 re-minimised (x2 = x1) F = -(x1 + 2)^2: concave,
  !> decreasing across the whole box, so the minimum is the vertex x1 = 1,
  !> x2 = 1, F = -9.  At the start the lower bound carries lambda = -2 (the
  !> model decreases into the box) and is released; Newton's free step goes
  !> to the model's maximum x1 = -2, back across that bound.  Held there again
  !> the run stalled at (-1, -1); the released variable goes to its opposite
  !> bound instead (negative curvature), and x* is reached in one iteration.
  subroutine test_bound_flip()
    type(quadratic_problem_t) :: p
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    call p%init_problem('concave_box', 2, 0, 0)
    p%q = reshape([0.0_dp, -2.0_dp, -2.0_dp, 2.0_dp], [2, 2])
    p%lin = [-4.0_dp, 0.0_dp]
    p%const = -4.0_dp
    call p%set_bounds([-1.0_dp, -1.0e30_dp], [1.0_dp, 1.0e30_dp])
    call opt%solve(p, [-1.0_dp, 0.0_dp], err)
    call assert_true(opt%status == status_converged, 'concave box: converged '//err%text())
    ! a quadratic model is exact: x* to round-off (1e-12 relative)
    call assert_all_close(opt%x, [1.0_dp, 1.0_dp], 0.0_dp, 1.0e-12_dp, 'concave box: x* = (1, 1)')
    call assert_close(opt%f, -9.0_dp, 1.0e-12_dp, 'concave box: F* = -9')
    call assert_true(index(opt%log(2)%events, 'opposite bound') > 0 .or. index(opt%log(1)%events, &
                     'opposite bound') > 0, 'the flip is logged')
    call assert_true(p%count%analyses <= 3, 'concave box: at most 3 analyses, got '//str(p%count%analyses))
  end subroutine test_bound_flip

  !> HS 6 with its constraint as one quadratic equality (gnlc_ns) and as a
  !> general equality (gnlc_general_ns, Potter's re-approximation): first-class
  !> equalities, default settings (G = diag(2, 0) regularised automatically).
  !> HS: x* = (1, 1), f* = 0 from (-1.2, 1).
  subroutine test_hs6_equality()
    type(quadratic_problem_t) :: p
    type(hs6_general_t) :: pg
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    call p%init_problem('hs6', 2, 0, 0, n_eq=1)
    p%q = reshape([2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2])
    p%lin = [-2.0_dp, 0.0_dp]
    p%const = 1.0_dp
    call p%set_quadratic_equality(1, reshape([-20.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), [0.0_dp, 10.0_dp], 0.0_dp)
    opt%opts%method = method_gnlc_ns
    call opt%solve(p, [-1.2_dp, 1.0_dp], err)
    call assert_true(opt%status == status_converged, 'quadratic equality: converged '//err%text())
    call assert_all_close(opt%x, [1.0_dp, 1.0_dp], 0.0_dp, 2.0e-8_dp, 'quadratic equality: x* = (1, 1)')
    call assert_true(opt%powell_fallbacks == 0, 'no Powell fallback (one equality, not an opposite pair)')
    ! G = diag(2, 0): the automatic mu starts at |grad L|/max(1, |x|) = 3.7 (a
    ! trust region) and falls with grad L, so the tail is superlinear: NF = 8
    call assert_true(p%count%analyses <= 8, 'quadratic equality: at most 8 analyses')
    call pg%init_problem('hs6_general', 2, 0, 0, n_eq=1)
    pg%q = p%q
    pg%lin = p%lin
    pg%const = 1.0_dp
    call pg%set_general_equality(1)
    opt%opts%method = method_gnlc_general_ns
    call opt%solve(pg, [-1.2_dp, 1.0_dp], err)
    call assert_true(opt%status == status_converged, 'general equality: converged '//err%text())
    call assert_all_close(opt%x, [1.0_dp, 1.0_dp], 0.0_dp, 2.0e-8_dp, 'general equality: x* = (1, 1)')
    call assert_true(pg%count%constraint_hessians > 0, 'general equality re-approximated (Potter item 1)')
    ! GNLC (step-back) accepts a start off a nonlinear equality: B11 restores it
    opt%opts%method = method_gnlc_general
    call opt%solve(pg, [-1.2_dp, 1.0_dp], err)
    call assert_true(opt%status == status_converged, 'gnlc_general from off the equality: '//err%text())
    call assert_all_close(opt%x, [1.0_dp, 1.0_dp], 0.0_dp, 2.0e-8_dp, 'gnlc_general: x* = (1, 1)')
  end subroutine test_hs6_equality

  subroutine hs6_h(self, i, x, g, err)
    class(hs6_general_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = 10.0_dp*(x(2) - x(1)**2)
    if (i /= self%m + 1) call err%set('hs6_general', 'no constraint '//str(i))
  end subroutine hs6_h

  !> Issue 8 item 10: HS 6, min (1 - x1)^2 s.t. 10 (x2 - x1^2) = 0, posed as
  !> the pair h <= 0, -h <= 0 (opposite gradients: B11 singular when both are
  !> active) with the singular exact Hessian diag(2, 0) regularised.  It
  !> reached x* = (1, 1) and then re-analysed it to the iteration limit; now
  !> the stop test declares convergence within a few analyses.
  subroutine test_hs6_regularized()
    real(dp), parameter :: regs(3) = [1.0e-10_dp, 1.0e-6_dp, 1.0e-4_dp]
    type(quadratic_problem_t) :: p
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    integer :: k
    do k = 1, 3
      call p%init_problem('hs6_pair', 2, 0, 2)
      p%q = reshape([2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2])
      p%lin = [-2.0_dp, 0.0_dp]
      p%const = 1.0_dp
      call p%set_quadratic_constraint(1, reshape([-20.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), [0.0_dp, 10.0_dp], 0.0_dp)
      call p%set_quadratic_constraint(2, reshape([20.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], [2, 2]), [0.0_dp, -10.0_dp], 0.0_dp)
      opt%opts = gauss_options_t()
      opt%opts%method = method_gnlc_ns
      opt%opts%regularization = regs(k)
      call opt%solve(p, [-1.2_dp, 1.0_dp], err)
      call assert_true(opt%status == status_converged, 'regularization '//str(regs(k), 2)//': converged '//err%text())
      ! the step test stops within xtol (1 + |x|) = 2e-8 of x*
      call assert_all_close(opt%x, [1.0_dp, 1.0_dp], 0.0_dp, 2.0e-8_dp, 'x* = (1, 1)')
      call assert_true(p%count%analyses <= 6, 'at most 6 analyses (it took 50 before)')
      call err%clear()
    end do
  end subroutine test_hs6_regularized

  subroutine log_residuals(self, x, phi, err)
    class(log_domain_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    if (x(1) > 0.0_dp) then
      phi(1) = log(x(1)/3.0_dp)
    else if (self%bad == 1) then
      phi(1) = ieee_value(phi(1), ieee_quiet_nan)
    else
      phi(1) = ieee_value(phi(1), ieee_positive_inf)
    end if
    phi(2) = x(2) - 1.0_dp
    if (.false.) call err%clear()
  end subroutine log_residuals

  subroutine log_jacobian(self, x, phi, jac, err)
    class(log_domain_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), phi(:)
    real(dp), intent(out) :: jac(:, :)
    type(error_t), intent(inout) :: err
    jac = 0.0_dp
    jac(1, 1) = 1.0_dp/x(1)
    jac(2, 2) = 1.0_dp
    if (.false.) jac(1, 1) = phi(1) + self%bad
    if (.false.) call err%clear()
  end subroutine log_jacobian

  !> Issue 8 item 4: a trial point where F is NaN or Inf is a failed trial
  !> (the step is halved towards x_k), never a value; the run converges to
  !> x* = (3, 1) with every logged row finite, and every trial counts in NF.
  subroutine test_non_finite_trial()
    type(log_domain_t) :: prob
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    integer :: bad, r
    logical :: finite_rows
    do bad = 1, 2
      call prob%init_problem('log_domain', 2, 2, 0)
      prob%bad = bad
      opt%opts%method = method_gauss
      call opt%solve(prob, [30.0_dp, 0.0_dp], err)
      call assert_true(opt%status == status_converged, 'converged: '//err%text())
      ! the stop test accepts x_k when its step is <= xtol (1 + |x|) = 4e-8
      call assert_all_close(opt%x, [3.0_dp, 1.0_dp], 0.0_dp, 4.0e-8_dp, 'x* = (3, 1)')
      call assert_true(index(opt%log(2)%events, 'not finite') > 0, 'the failed trial is logged')
      finite_rows = .true.
      do r = 1, opt%n_log
        finite_rows = finite_rows .and. ieee_is_finite(opt%log(r)%f) .and. all(ieee_is_finite(opt%log(r)%x))
      end do
      call assert_true(finite_rows, 'no row holds NaN or Inf')
      ! from 30: trials at -39.1 and -4.5 fail, 12.7 is accepted: NF > NI + 1
      call assert_true(prob%count%analyses > opt%iterations + 1, 'failed trials are counted analyses')
      call err%clear()
    end do
    ! a start where F is not finite is a diagnosed stop, not a run from a NaN
    call prob%init_problem('log_domain', 2, 2, 0)
    call opt%solve(prob, [-1.0_dp, 0.0_dp], err)
    call assert_true(err%failed() .and. index(err%text(), 'not finite at the start') > 0, 'non-finite F(x0) diagnosed')
    call err%clear()
    call opt%solve(prob, [ieee_value(1.0_dp, ieee_positive_inf), 0.0_dp], err)
    call assert_true(err%code == 2 .and. index(err%text(), 'not finite') > 0, 'Inf in x0 is an input error')
  end subroutine test_non_finite_trial

  !> Solve library problem `name` with `method` from x0 (default: the library's).
  !> The run starts without an error (the fixture's err outlives a test).
  subroutine run_problem(name, method, opt, prob, info, err, x0, max_iter, regularization, potter_repeat, auto_reg)
    character(len=*), intent(in) :: name, method
    type(gauss_optimizer_t), intent(out) :: opt
    class(opt_problem_t), allocatable, target, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: x0(:), regularization
    integer, intent(in), optional :: max_iter
    logical, intent(in), optional :: potter_repeat, auto_reg
    call err%clear()
    call create_problem(name, prob, info, err)
    if (err%failed()) return
    opt%opts%method = method_from_name(method)
    opt%opts%globalization = glob_none            ! this suite checks the papers' methods as printed
    if (present(max_iter)) opt%opts%max_iter = max_iter
    if (present(regularization)) opt%opts%regularization = regularization
    if (present(potter_repeat)) opt%opts%potter_repeat = potter_repeat
    if (present(auto_reg)) opt%opts%auto_regularize = auto_reg
    if (present(x0)) then
      call opt%solve(prob, x0, err)
    else
      call opt%solve(prob, info%x0, err)
    end if
  end subroutine run_problem

  !> P Table I (FORMULATION.md §10.1): x* = [0, 1, 2, -1] within 1e-6 from
  !> every start, with NI and NF no larger than the paper's.
  subroutine test_table_one()
    real(dp), parameter :: r5 = 2.23606797749979_dp
    real(dp) :: starts(4, 7)
    character(len=8) :: methods(7)
    integer :: ni_paper(7), nf_paper(7), k
    character(len=80) :: label
    starts = reshape([0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, &
                      0.0_dp, 0.0_dp, r5, 0.0_dp, 0.0_dp, 0.0_dp, r5, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
                      1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], [4, 7])
    methods = [character(len=8) :: 'gnlc_ns', 'gnlc_ns', 'gnlc_ns', 'gnlc_ns', 'gnlc', 'gnlc', 'gnlc']
    ni_paper = [2, 2, 2, 3, 3, 5, 5]
    nf_paper = [3, 3, 3, 4, 4, 6, 6]
    do k = 1, 7
      write(label, '(a,a,4f7.3,a)') trim(methods(k)), ' from [', starts(:, k), ']'
      call run_problem('rosen_suzuki', methods(k), opt, prob, info, err, x0=starts(:, k))
      call assert_true(.not. err%failed(), trim(label)//': '//err%text())
      call assert_true(opt%status == status_converged, trim(label)//' converged')
      call assert_all_close(opt%x, [0.0_dp, 1.0_dp, 2.0_dp, -1.0_dp], 0.0_dp, 1.0e-6_dp, trim(label)//' x*')
      call assert_close(opt%f, -44.0_dp, 1.0e-9_dp, trim(label)//' F* = -44')
      call assert_all_close(opt%lambda, [1.0_dp, 0.0_dp, 2.0_dp], 0.0_dp, 1.0e-6_dp, trim(label)//' lambda*')
      call assert_true(opt%iterations <= ni_paper(k), trim(label)//' NI <= paper')
      call assert_true(prob%count%analyses <= nf_paper(k), trim(label)//' NF <= paper')
      call err%clear()
    end do
  end subroutine test_table_one

  subroutine test_nf_ni()
    call run_problem('rosen_suzuki', 'gnlc', opt, prob, info, err, x0=[0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    ! no line search: one analysis per iteration plus the start (§9)
    call assert_equal(prob%count%analyses, opt%iterations + 1, 'NF = NI + 1')
    call assert_equal(prob%count%gradients, opt%iterations + 1, 'one gradient per iterate')
    call assert_equal(opt%n_log, opt%iterations + 1, 'one log row per iterate')
    call assert_true(opt%step_backs >= 1, 'GNLC stepped back (the unconstrained minimiser violates all three)')
    call assert_true(all(opt%log(1:opt%n_log)%max_violation <= opt%opts%feas_tol), 'every GNLC iterate feasible')
  end subroutine test_nf_ni

  !> step_back_refine = .false.: one B13 interpolation, as B prints it.  For
  !> Rosen-Suzuki's convex constraints the point lands strictly inside the
  !> crossed constraint, which joins S and is reached at the next step.
  subroutine test_plain_b13()
    type(gauss_optimizer_t) :: opt
    class(opt_problem_t), allocatable :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    real(dp) :: g(3), x1(4)
    call create_problem('rosen_suzuki', prob, info, err)
    opt%opts%method = method_gnlc
    opt%opts%step_back_refine = .false.
    call opt%solve(prob, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], err)
    call assert_true(opt%status == status_converged, 'converged: '//err%text())
    call assert_all_close(opt%x, [0.0_dp, 1.0_dp, 2.0_dp, -1.0_dp], 0.0_dp, 1.0e-6_dp, 'x*')
    call assert_true(opt%iterations <= 5 .and. prob%count%analyses <= 6, 'NI, NF <= paper (5, 6)')
    ! first step-back: x1 on the segment towards the unconstrained minimiser
    x1 = opt%log(2)%x
    call prob%constraint_values(x1, g, err)
    call assert_true(opt%log(2)%active(3) .and. g(3) < -opt%opts%feas_tol, 'g3 added, strictly inside (convex)')
    call assert_true(maxval(g) <= 0.0_dp, 'feasible')
    ! the refined step-back puts the same first point on the boundary
    call create_problem('rosen_suzuki', prob, info, err)
    opt%opts%step_back_refine = .true.
    call opt%solve(prob, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], err)
    call prob%constraint_values(opt%log(2)%x, g, err)
    call assert_close(g(3), 0.0_dp, opt%opts%feas_tol, 'refined: g3 = 0 at the first step-back')
  end subroutine test_plain_b13

  subroutine test_infeasible_start()
    call run_problem('rosen_suzuki', 'gnlc', opt, prob, info, err, x0=[2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp])
    call assert_true(err%failed() .and. err%code == 2, 'input error (code 2)')
    call assert_true(index(err%text(), 'infeasible') > 0, 'says the start is infeasible')
    call assert_true(index(err%text(), '{1, 2, 3}') > 0, 'names the violated constraints')
    call assert_true(index(err%text(), 'gnlc_ns') > 0, 'suggests gnlc_ns')
    call assert_equal(prob%count%analyses, 0, 'no analysis spent')
  end subroutine test_infeasible_start

  subroutine test_unconstrained()
    character(len=16), parameter :: names(3) = [character(len=16) :: 'rosenbrock', 'helical_valley', 'bard']
    integer :: k
    do k = 1, 3
      call run_problem(trim(names(k)), 'gauss', opt, prob, info, err)
      call assert_true(opt%status == status_converged, trim(names(k))//' converged: '//err%text())
      ! MGH optima: exact for 1 and 7; Bard's x* printed to 7 digits, F* to 6
      call assert_all_close(opt%x, info%x_star, 1.0e-6_dp, 1.0e-7_dp, trim(names(k))//' x*')
      call assert_close(opt%f, info%f_star, 1.0e-8_dp, trim(names(k))//' F*')
      call assert_equal(prob%count%analyses, opt%iterations + 1, trim(names(k))//' NF = NI + 1')
      call err%clear()
    end do
    call run_problem('rosenbrock', 'gauss', opt, prob, info, err)
    ! phi_2 = 1 - x1 is linear: the first Gauss step puts x1 = 1, the second x2 = 1
    call assert_equal(opt%iterations, 2, 'Rosenbrock residuals: 2 Gauss iterations')
  end subroutine test_unconstrained

  subroutine test_linear_constraints()
    character(len=8), parameter :: names(2) = [character(len=8) :: 'hs21', 'hs35']
    type(gauss_optimizer_t) :: opt2
    class(opt_problem_t), allocatable :: prob2
    integer :: k
    do k = 1, 2
      call run_problem(trim(names(k)), 'gauss_constrained', opt, prob, info, err)
      call assert_true(opt%status == status_converged, trim(names(k))//' converged: '//err%text())
      call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-8_dp, trim(names(k))//' x*')
      call assert_close(opt%f, info%f_star, 1.0e-10_dp, trim(names(k))//' F*')
      call assert_all_close(opt%lambda, info%lambda_star, 0.0_dp, 1.0e-8_dp, trim(names(k))//' lambda*')
      call run_problem(trim(names(k)), 'gnlc', opt2, prob2, info, err)
      call assert_all_close(opt2%x, opt%x, 0.0_dp, 1.0e-10_dp, trim(names(k))//': GNLC = Gauss constrained')
      call assert_equal(opt2%iterations, opt%iterations, trim(names(k))//': same iteration count')
    end do
  end subroutine test_linear_constraints

  !> B's design aim: one iteration when F is quadratic and the start already
  !> lies on the constraints active at the optimum.  HS35 from (1, 1, 0.5),
  !> on x1 + x2 + 2 x3 = 3; Rosen-Suzuki from a point on g1 = g3 = 0.
  subroutine test_one_iteration()
    real(dp) :: x0(4)
    call run_problem('hs35', 'gauss_constrained', opt, prob, info, err, x0=[1.0_dp, 1.0_dp, 0.5_dp])
    call assert_equal(opt%iterations, 1, 'HS35: one iteration')
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-12_dp, 'HS35: x* after one iteration')
    ! a point on g1 = g3 = 0 of Rosen-Suzuki: x = (0, 1, 2, -1) + t (d) with
    ! g1, g3 quadratic; x0 = (0, t1, t2, -1) solved by hand: x2 = 0.5, then
    ! g3: x2^2 + x3^2 - x2 - x4 - 5 = 0 and g1 fix x3 and x4 (computed below)
    x0 = on_g1_g3(0.5_dp)
    call run_problem('rosen_suzuki', 'gnlc', opt, prob, info, err, x0=x0)
    call assert_true(.not. err%failed(), 'feasible start accepted: '//err%text())
    call assert_equal(opt%iterations, 1, 'Rosen-Suzuki from g1 = g3 = 0: one iteration')
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-9_dp, 'Rosen-Suzuki: x* after one iteration')
  end subroutine test_one_iteration

  !> x = (0, x2, x3, x4) with g1 = g3 = 0: g3 - g1 gives x3^2 + ... eliminated
  !> by Newton on (x3, x4) for the given x2 (a 2x2 problem solved here).
  function on_g1_g3(x2) result(x)
    real(dp), intent(in) :: x2
    real(dp) :: x(4), r(2), jm(2, 2), d(2), det
    integer :: it
    x = [0.0_dp, x2, 1.5_dp, -1.5_dp]
    do it = 1, 50
      r(1) = sum(x**2) + x(1) - x(2) + x(3) - x(4) - 8.0_dp
      r(2) = 2.0_dp*x(1)**2 + x(2)**2 + x(3)**2 + 2.0_dp*x(1) - x(2) - x(4) - 5.0_dp
      jm = reshape([2.0_dp*x(3) + 1.0_dp, 2.0_dp*x(3), 2.0_dp*x(4) - 1.0_dp, -1.0_dp], [2, 2])
      det = jm(1, 1)*jm(2, 2) - jm(1, 2)*jm(2, 1)
      d = [jm(2, 2)*r(1) - jm(1, 2)*r(2), jm(1, 1)*r(2) - jm(2, 1)*r(1)]/det
      x(3:4) = x(3:4) - d
      if (maxval(abs(d)) < 1.0e-15_dp) exit
    end do
  end function on_g1_g3

  !> HS28: two residuals for three variables, so J J^T is singular everywhere.
  subroutine test_rank_deficient()
    call run_problem('hs28', 'gauss_constrained', opt, prob, info, err, auto_reg=.false.)
    call assert_true(err%failed() .and. opt%status == status_failed, 'singular G stops the run')
    call assert_true(index(err%text(), 'singular') > 0, 'diagnosis says singular')
    call assert_true(index(err%text(), 'numerical rank 2 of 3') > 0, 'numerical rank reported')
    call assert_true(index(err%text(), 'regularization') > 0, 'names the remedy')
    call err%clear()
    call run_problem('hs28', 'gauss_constrained', opt, prob, info, err, regularization=1.0e-8_dp)
    call assert_true(opt%status == status_converged, 'regularized run converges: '//err%text())
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-7_dp, 'HS28 x* with mu = 1e-8 max G_ii')
    call assert_true(opt%regularizations >= 1, 'regularization counted')
    call assert_true(index(opt%log(2)%events, 'regularized') > 0, 'regularization logged')
    ! Powell's singular function: J J^T becomes singular as x -> x* = 0
    call err%clear()
    call run_problem('powell_singular', 'gauss', opt, prob, info, err, auto_reg=.false.)
    call assert_true(err%failed() .and. index(err%text(), 'numerical rank 3 of 4') > 0, &
                     'Powell singular: rank loss at the solution detected')
    call assert_true(opt%have_best .and. opt%f_best < 1.0e-15_dp, 'best point near x* kept')
    ! default: G = 2 J J^T is singular, but not on the tangent space of the
    ! equality, so no shift: B10/B11 are solved together in (s, lambda), which
    ! for a quadratic F and a linear equality is the exact KKT step: x* in one
    ! iteration (NF = 2; 10 with the Levenberg shift before)
    call err%clear()
    call run_problem('hs28', 'gauss_constrained', opt, prob, info, err)
    call assert_true(opt%status == status_converged, 'HS28 with defaults converges: '//err%text())
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-7_dp, 'HS28 x* with defaults')
    call assert_true(index(opt%log(2)%events, '(s, lambda)') > 0, '(s, lambda) Newton logged')
    call assert_equal(opt%iterations, 1, 'HS28: x* in one iteration')
    call err%clear()
    call run_problem('powell_singular', 'gauss', opt, prob, info, err)
    call assert_true(opt%status == status_converged, 'Powell singular with defaults converges: '//err%text())
    call assert_true(opt%f < 1.0e-20_dp, 'Powell singular: F < 1e-20 (F* = 0, x* = 0 approached linearly)')
  end subroutine test_rank_deficient

  !> Three discs, GNLC.NS from (1, 5): all three constraints are violated,
  !> and three active constraints in two variables give B11 no solution
  !> (before: Newton failed, Powell's compromise, x* in 2 iterations).  The
  !> least violated leaves the set for that step (the set is made square),
  !> B11 is solved by Newton, and the step lands on x* (quadratic F and
  !> constraints): NI = 1, no Powell fallback.
  subroutine test_powell_fallback()
    call run_problem('three_circles', 'gnlc_ns', opt, prob, info, err)
    call assert_true(opt%status == status_converged, 'converged: '//err%text())
    call assert_equal(opt%powell_fallbacks, 0, 'no Powell fallback')
    call assert_equal(opt%iterations, 1, 'x* in one iteration')
    call assert_equal(prob%count%b11_constraint_evals, 0, 'no actual constraint in B11 for quadratic ones')
    call assert_equal(prob%count%jacobians, prob%count%gradients, 'sum of squares: one Jacobian per gradient')
    call assert_true(index(opt%log(2)%events, 'over-determined') > 0, 'left-out constraint logged with the iteration')
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-8_dp, 'x* = (1, sqrt 3)')
    call assert_all_close(opt%lambda, info%lambda_star, 0.0_dp, 1.0e-7_dp, 'lambda*')
  end subroutine test_powell_fallback

  subroutine test_iteration_limit()
    call run_problem('rosen_suzuki', 'gnlc', opt, prob, info, err, x0=[0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], max_iter=2)
    call assert_true(opt%status == status_max_iter, 'status: iteration limit')
    call assert_true(err%failed() .and. err%code /= 2, 'error set, not an input error')
    call assert_true(index(err%text(), 'best feasible') > 0, 'message gives the best feasible point')
    call assert_equal(opt%iterations, 2, 'stopped after max_iter')
    call assert_true(opt%have_best .and. opt%f_best <= minval(opt%log(1:opt%n_log)%f) + 1.0e-12_dp, &
                     'best feasible = lowest F over the (all feasible) GNLC iterates')
  end subroutine test_iteration_limit

  !> Potter §9.5 item 3 on potter_cycling: from (0, 1) on |x| = 1 the step to
  !> x* of the active set {1} violates x2 >= -1/2; backing out along the chord
  !> enters |x| < 1 and ends back at x_k with the same active set.
  subroutine test_potter_cycling()
    call run_problem('potter_cycling', 'gnlc', opt, prob, info, err, potter_repeat=.false.)
    call assert_true(err%failed() .and. opt%status == status_failed, 'cycling stops the run when not escaped')
    call assert_true(index(err%text(), 'cycling') > 0 .and. index(err%text(), 'Potter') > 0, &
                     'diagnosis names the step-back cycling (Potter)')
    call assert_equal(prob%count%analyses, 1, 'detected before any repeated analysis')
    call err%clear()
    call run_problem('potter_cycling', 'gnlc', opt, prob, info, err)
    call assert_true(opt%status == status_converged, 'fix (a) escapes: '//err%text())
    call assert_equal(opt%potter_repeats, 1, 'one repeated step')
    call assert_true(index(opt%log(2)%events, 'fix (a)') > 0, 'escape logged')
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-9_dp, 'x* = (sqrt 3/2, -1/2)')
    call assert_all_close(opt%lambda, info%lambda_star, 0.0_dp, 1.0e-8_dp, 'lambda*')
    call assert_true(all(opt%log(1:opt%n_log)%max_violation <= opt%opts%feas_tol), 'iterates stay feasible')
  end subroutine test_potter_cycling

  subroutine test_general_constraints()
    call run_problem('general_convex', 'gnlc_general', opt, prob, info, err)
    call assert_true(opt%status == status_converged, 'gnlc_general converged: '//err%text())
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-8_dp, 'x* = (1, 1)')
    call assert_all_close(opt%lambda, info%lambda_star, 0.0_dp, 1.0e-6_dp, 'lambda* = (1, 1/2)')
    call assert_true(prob%count%constraint_hessians > 0, 'constraint Hessians re-evaluated (Potter item 1)')
    call assert_true(prob%count%b11_constraint_evals > 0 .and. &
                     prob%count%constraint_evals >= prob%count%b11_constraint_evals, &
                     'actual constraints in B11 counted, within the constraint evaluations')
    call assert_true(all(opt%log(1:opt%n_log)%max_violation <= opt%opts%feas_tol), 'iterates feasible')
    call run_problem('general_convex', 'gnlc_general_ns', opt, prob, info, err)
    call assert_true(opt%status == status_converged, 'gnlc_general_ns converged')
    call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-8_dp, 'NS: x* = (1, 1)')
  end subroutine test_general_constraints

  !> HS 15 (non-convex quadratic constraints) and HS 65 from their infeasible
  !> literature starts: only GNLC.NS applies.
  subroutine test_ns_infeasible_starts()
    character(len=8), parameter :: names(2) = [character(len=8) :: 'hs15', 'hs65']
    integer :: k
    do k = 1, 2
      call run_problem(trim(names(k)), 'gnlc_ns', opt, prob, info, err)
      call assert_true(opt%status == status_converged, trim(names(k))//' converged: '//err%text())
      ! stored optima to 11 digits (HS 65: the KKT point, not HS's rounded print)
      call assert_all_close(opt%x, info%x_star, 0.0_dp, 1.0e-9_dp, trim(names(k))//' x*')
      ! grad F = -C lambda is O(|lambda|) (1751 for HS 15); B11 is solved to
      ! 1e-10, which leaves a KKT residual of that relative size
      call assert_true(opt%kkt_residual < 1.0e-10_dp*(1.0_dp + maxval(abs(opt%lambda))), &
                       trim(names(k))//' KKT residual < 1e-10 (1 + |lambda|)')
      call assert_close(opt%f, info%f_star, 1.0e-8_dp, trim(names(k))//' F*')
      call assert_true(opt%iterations <= 5, trim(names(k))//' few iterations')
    end do
  end subroutine test_ns_infeasible_starts

  subroutine test_mismatch()
    call run_problem('rosen_suzuki', 'gauss', opt, prob, info, err)
    call assert_true(err%code == 2 .and. index(err%text(), 'unconstrained') > 0, 'gauss on a constrained problem')
    call err%clear()
    call run_problem('rosen_suzuki', 'gauss_constrained', opt, prob, info, err)
    call assert_true(err%code == 2 .and. index(err%text(), 'linear constraints only') > 0, &
                     'gauss_constrained on quadratic constraints')
    call err%clear()
    call run_problem('general_convex', 'gnlc', opt, prob, info, err)
    call assert_true(err%code == 2 .and. index(err%text(), 'gnlc_general') > 0, 'gnlc on general constraints')
    call err%clear()
    call create_problem('rosen_suzuki', prob, info, err)
    opt%opts%method = method_gnlc
    opt%opts%hessian = hessian_gauss
    call opt%solve(prob, info%x0, err)
    call assert_true(err%code == 2 .and. index(err%text(), 'sum-of-squares') > 0, 'G = 2JJ^T needs least squares')
    call err%clear()
    opt%opts%hessian = hessian_auto
    call opt%solve(prob, [1.0_dp, 2.0_dp], err)
    call assert_true(err%code == 2 .and. index(err%text(), 'variables') > 0, 'start of the wrong length')
    ! issue 11: an error left from an earlier call must not reach this run
    ! (it was blamed on "constraint 1" of the next problem)
    call create_problem('general_convex', prob, info, err)
    opt%opts%method = method_gnlc_general
    call opt%solve(prob, info%x0, err)
    call assert_true(opt%status == status_converged .and. .not. err%failed(), 'stale error cleared: '//err%text())
  end subroutine test_mismatch
end module test_gauss_optimizer_suite

program test_gauss_optimizer
  use test_gauss_optimizer_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_gauss_optimizer')
end program test_gauss_optimizer
