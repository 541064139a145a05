!> Optimal design with the analysis in the loop: the design decks' problems
!> through the design loop (sequential approximate problems solved by GNLC,
!> module design_sequence) and through NLopt's SLSQP (gradient-based SQP) and
!> COBYLA (derivative-free), from the same start, with the same analyses,
!> bounds and constraints.  SLSQP's gradients are the design loop's: the
!> periodic orbit's sensitivities where they apply (&design derivatives,
!> doc/design.md), else forward differences of the analysis; `slsqp_fd`
!> forces forward differences, `gnlc_fd` the design loop with them.
!>
!> Printed per run: NF (mechanism analyses of distinct designs, derivatives
!> included: the design problem's cache counts each design once whoever
!> asks), failed analyses, CPU of the analyses, the final objective (F / F at
!> the start), the largest constraint violation (ln ratio) and the final
!> design.  A benchmark: figures, not pass/fail.  Decks: the arguments, or
!> the design examples of doc/design.md.
module design_nlopt_glue
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, i8
  use nlopt_api
  use error_status, only: error_t
  use design_problem, only: design_problem_t, design_eval_t
  implicit none
  private
  public :: nlopt_design, alg_slsqp, alg_cobyla

  !> what a failed analysis returns to NLopt: a violation of e^10 and an
  !> objective ten times the start's (NLopt has no notion of a failed trial)
  real(dp), parameter :: failed_constraint = 10.0_dp, failed_objective = 10.0_dp


  ! NLopt's callbacks carry only an integer: the problem is module state for
  ! the duration of one nlopt_design
  type(design_problem_t), pointer :: current => null()
  integer, target, save :: ids(0:100) = 0
  !> the derivatives of the last design asked (the objective's and every
  !> constraint's gradient at one x cost one sensitivity solve)
  logical :: variational = .false.
  real(dp), allocatable :: at_x(:), at_dg(:, :), at_dr(:, :)

contains

  !> Minimise the design problem from x with NLopt's `alg`: bounds of the
  !> variables as NLopt bounds, each analysis constraint as an inequality;
  !> stops at |dx| < xtol (the design loop's step test) or a relative change
  !> of F below ftol (its stall test).
  subroutine nlopt_design(prob, alg, x, xtol, ftol, f, ires)
    type(design_problem_t), intent(inout), target :: prob
    integer, intent(in) :: alg
    real(dp), intent(inout) :: x(:)
    real(dp), intent(in) :: xtol, ftol
    real(dp), intent(out) :: f
    integer, intent(out) :: ires
    integer(i8) :: opt
    integer :: i, r
    real(dp) :: lb(size(x)), ub(size(x))
    current => prob
    variational = prob%variational_applies()
    if (allocated(at_x)) deallocate(at_x)
    do i = 0, size(ids) - 1
      ids(i) = i
    end do
    do i = 1, size(x)
      lb(i) = prob%var(i)%to_x(prob%var(i)%lower)
      ub(i) = prob%var(i)%to_x(prob%var(i)%upper)
    end do
    call nlo_create(opt, alg, size(x))
    call nlo_set_min_objective(r, opt, objective_cb, ids(0))
    call nlo_set_lower_bounds(r, opt, lb)
    call nlo_set_upper_bounds(r, opt, ub)
    do i = 1, prob%n_analysis_constraints()
      call nlo_add_inequality_constraint(r, opt, constraint_cb, ids(i), 0.0_dp)
    end do
    call nlo_set_xtol_abs1(r, opt, xtol)
    call nlo_set_ftol_rel(r, opt, ftol)
    call nlo_set_maxeval(r, opt, 3000)
    call nlo_optimize(ires, opt, x, f)
    call nlo_destroy(opt)
    current => null()
  end subroutine nlopt_design

  real(dp) function objective_at(x) result(f)
    real(dp), intent(in) :: x(:)
    type(error_t) :: err
    call current%objective(x, f, err)
    if (.not. ieee_is_finite(f)) f = failed_objective
  end function objective_at

  real(dp) function constraint_at(i, x) result(g)
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    type(error_t) :: err
    call current%general_constraint(i, x, g, err)
    if (.not. ieee_is_finite(g)) g = failed_constraint
  end function constraint_at

  !> Forward differences with the design loop's step (each neighbour one
  !> analysis, shared by the objective and every constraint via the cache).
  subroutine objective_cb(val, n, x, grad, need_gradient, f_data)
    real(dp), intent(out) :: val
    integer, intent(in) :: n
    real(dp), intent(in) :: x(n)
    real(dp), intent(inout) :: grad(n)
    integer, intent(in) :: need_gradient
    integer, intent(in) :: f_data
    real(dp) :: xp(n)
    integer :: j
    val = objective_at(x)
    if (need_gradient == 0 .or. f_data /= 0) return
    if (variational .and. current%has_residuals()) then
      if (derivatives_at(x)) then
        grad = objective_gradient(x)
        return
      end if
    end if
    do j = 1, n
      xp = x
      xp(j) = x(j) + current%fd_rel_step*max(abs(x(j)), 1.0_dp)
      grad(j) = (objective_at(xp) - val)/(xp(j) - x(j))
    end do
  end subroutine objective_cb

  subroutine constraint_cb(val, n, x, grad, need_gradient, f_data)
    real(dp), intent(out) :: val
    integer, intent(in) :: n
    real(dp), intent(in) :: x(n)
    real(dp), intent(inout) :: grad(n)
    integer, intent(in) :: need_gradient
    integer, intent(in) :: f_data
    real(dp) :: xp(n)
    integer :: j
    val = constraint_at(f_data, x)
    if (need_gradient == 0) return
    if (variational) then
      if (derivatives_at(x)) then
        grad = at_dg(:, f_data)
        return
      end if
    end if
    do j = 1, n
      xp = x
      xp(j) = x(j) + current%fd_rel_step*max(abs(x(j)), 1.0_dp)
      grad(j) = (constraint_at(f_data, xp) - val)/(xp(j) - x(j))
    end do
  end subroutine constraint_cb

  !> The sensitivities at x (once per design); .false. when they fail
  !> (forward differences then).
  logical function derivatives_at(x) result(ok)
    real(dp), intent(in) :: x(:)
    ok = .true.
    if (allocated(at_x)) then
      if (all(transfer(at_x, 1_i8, size(at_x)) == transfer(x, 1_i8, size(x)))) return
    end if
    call current%derivatives_at(x, at_dg, at_dr, ok)
    if (ok) then
      at_x = x
    else if (allocated(at_x)) then
      deallocate(at_x)
    end if
  end function derivatives_at

  !> Gradient of F = (sum of r^2, or the largest r) / F0 from dr/dx.
  function objective_gradient(x) result(grad)
    real(dp), intent(in) :: x(:)
    real(dp) :: grad(size(x))
    type(design_eval_t) :: ev
    call current%evaluate(x, ev)
    if (current%is_minimax()) then
      grad = at_dr(:, maxloc(ev%residual, dim=1))/current%f0
    else if (current%objective_kind == 'path_rigid') then
      grad = 2.0_dp*matmul(at_dr, ev%rigid_residual)/current%f0
    else
      grad = 2.0_dp*matmul(at_dr, ev%residual)/current%f0
    end if
  end function objective_gradient
end module design_nlopt_glue

program bench_design
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t
  use linkage, only: mechanism_t
  use design_problem, only: design_problem_t, design_eval_t
  use design_sequence, only: design_sequence_t
  use design_analysis, only: load_design
  use design_nlopt_glue, only: nlopt_design, alg_slsqp, alg_cobyla
  implicit none
  character(len=256), allocatable :: decks(:)
  character(len=256) :: arg
  character(len=64) :: methods
  integer :: i
  !> the design loop's accepted designs (analyses so far, F, worst
  !> violation): where it passes an NLopt run's final F
  integer, allocatable :: loop_nf(:)
  real(dp), allocatable :: loop_f(:), loop_viol(:)

  ! --methods=gnlc,slsqp,cobyla,gnlc_fd,slsqp_fd (default the first three)
  ! selects the optimizers
  ! (an NLopt run of example 3 costs minutes: the bench can run one of them)
  methods = 'gnlc,slsqp,cobyla'
  allocate(decks(0))
  do i = 1, command_argument_count()
    call get_command_argument(i, arg)
    if (index(arg, '--methods=') == 1) then
      methods = arg(11:)
    else
      decks = [character(len=256) :: decks, arg]
    end if
  end do
  if (size(decks) == 0) then
    decks = [character(len=256) :: 'inputs/design_bar_frequency.nml', 'inputs/design_fourbar_path_60.nml', &
             'inputs/design_fourbar_mass_150.nml', 'inputs/design_fourbar_counterweights.nml', &
             'inputs/design_fourbar_mass_150_nonlinear.nml', 'inputs/design_fourbar_mass_150_nonlinear_deflection.nml', &
             'inputs/design_fourbar_counterweights_bearing.nml', 'inputs/design_fourbar_counterweights_bearing_linear.nml', &
             'inputs/design_fourbar_path_60_nonlinear.nml']
  end if
  write(output_unit, '(a)') '# Design with the analysis in the loop: the design loop (GNLC on sequential '// &
    'approximate problems) beside NLopt SLSQP and COBYLA, same deck, start, analyses and constraints.'
  write(output_unit, '(a)') '# NF = mechanism analyses of distinct designs (derivatives included); F = objective '// &
    '/ its start value; viol = largest ln(value/limit) (<= 0 feasible); cpu = analysis CPU seconds.'
  write(output_unit, '(a)') '# gradients: the sensitivities of the periodic orbit where they apply (one solve '// &
    'counted as one analysis), else forward differences (_fd: always); sens = sensitivity solves, cpu_sens their CPU'
  write(output_unit, '(a)') '# NLopt: stops at '// &
    '|dx| < xtol or relative change of F < xtol/10 (the design loop''s tests), at most 3000 evaluations.'
  write(output_unit, '(a)') '# deck | method | NF | failed | cpu | cpu/analysis | sens | cpu_sens | F | viol | '// &
    'status | design'
  do i = 1, size(decks)
    call run_deck(trim(decks(i)))
  end do

contains

  subroutine run_deck(path)
    character(len=*), intent(in) :: path
    integer :: method, nf_gauss, nf_best
    real(dp) :: f_gauss
    nf_gauss = 0
    nf_best = huge(1)
    if (allocated(loop_nf)) deallocate(loop_nf, loop_f, loop_viol)
    f_gauss = huge(1.0_dp)
    do method = 1, 5
      if (index(','//trim(methods)//',', ','//trim(method_key(method))//',') == 0) cycle
      call run_method(path, method, nf_gauss, nf_best, f_gauss)
    end do
    if (nf_gauss > 0 .and. nf_best < huge(1)) then
      write(output_unit, '(a)') '# '//path//': NF_gnlc / min(NF_slsqp, NF_cobyla) = '// &
        str(real(nf_gauss, dp)/nf_best, 3)//' (NLopt runs that end feasible within 1 % of the design loop''s F)'
    else if (nf_gauss > 0) then
      write(output_unit, '(a)') '# '//path//': no NLopt run ends feasible within 1 % of the design loop''s F'
    end if
  end subroutine run_deck

  pure function method_key(method) result(key)
    integer, intent(in) :: method
    character(len=8) :: key
    character(len=8), parameter :: keys(5) = [character(len=8) :: 'gnlc', 'slsqp', 'cobyla', 'gnlc_fd', 'slsqp_fd']
    key = keys(method)
  end function method_key

  subroutine run_method(path, method, nf_gauss, nf_best, f_gauss)
    character(len=*), intent(in) :: path
    integer, intent(in) :: method
    integer, intent(inout) :: nf_gauss, nf_best
    real(dp), intent(inout) :: f_gauss      !< the design loop's final F (equal objective: within 1 %)
    type(deck_t) :: deck
    type(mechanism_t) :: mech
    type(design_problem_t), target :: prob
    type(design_sequence_t) :: seq
    type(design_eval_t) :: ev
    type(error_t) :: err
    real(dp), allocatable :: x0(:), x(:)
    real(dp) :: f, viol
    integer :: ires, k
    character(len=:), allocatable :: name, status, design
    call deck%open(path, err)
    if (.not. err%failed()) call load_design(deck, mech, prob, x0, seq, err)
    call deck%close()
    if (err%failed()) then
      write(output_unit, '(a)') '# '//path//': '//err%text()
      return
    end if
    if (method >= 4) prob%derivatives = 'differences'
    call prob%setup('design of '//path, x0)
    x = x0
    select case (method)
    case (1, 4)
      name = trim(merge('gnlc_sequence   ', 'gnlc_sequence_fd', method == 1))
      call seq%solve(prob, x0, err)
      if (allocated(seq%x)) x = seq%x
      status = trim(merge('converged    ', 'not converged', seq%converged .and. .not. err%failed()))
    case (2, 5)
      name = trim(merge('nlopt_slsqp   ', 'nlopt_slsqp_fd', method == 2))
      call nlopt_design(prob, alg_slsqp, x, seq%xtol, 0.1_dp*seq%xtol, f, ires)
      status = 'ires='//str(ires)
    case default
      name = 'nlopt_cobyla'
      call nlopt_design(prob, alg_cobyla, x, seq%xtol, 0.1_dp*seq%xtol, f, ires)
      status = 'ires='//str(ires)
    end select
    call prob%objective(x, f, err)
    call prob%evaluate(x, ev)
    viol = 0.0_dp
    do k = 1, prob%n_analysis_constraints()
      block
        real(dp) :: g
        call prob%general_constraint(k, x, g, err)
        viol = max(viol, g)
      end block
    end do
    design = ''
    do k = 1, size(x)
      design = design//' '//trim(prob%var(k)%name)//'='//str(prob%var(k)%value(x(k)), 6)
    end do
    write(output_unit, '(a)') path//' | '//name//' | '//str(prob%n_analyses)//' | '//str(prob%n_failed)//' | '// &
      str(prob%cpu_analyses, 4)//' | '//str(prob%cpu_analyses/max(1, prob%n_analyses), 3)//' | '// &
      str(prob%n_sensitivity)//' | '//str(prob%cpu_sensitivity, 4)//' | '//str(f, 6)// &
      ' | '//str(viol, 3)//' | '//status//' |'//design
    flush(output_unit)
    if (method == 1 .or. method == 4) then
      if (seq%converged) nf_gauss = prob%n_analyses
      f_gauss = f
      loop_nf = [(seq%steps(k)%analyses, k = 1, seq%n_steps)]
      loop_f = [(seq%steps(k)%objective, k = 1, seq%n_steps)]
      loop_viol = [(seq%steps(k)%max_violation, k = 1, seq%n_steps)]
      return
    end if
    if (viol <= seq%feas_tol .and. ires > 0 .and. f <= 1.01_dp*f_gauss) nf_best = min(nf_best, prob%n_analyses)
    if (.not. allocated(loop_nf) .or. viol > seq%feas_tol) return
    ! at equal objective: the loop's analyses to its first feasible design
    ! at least as good as this run's end
    do k = 1, size(loop_nf)
      if (loop_viol(k) <= seq%feas_tol .and. loop_f(k) <= f) then
        write(output_unit, '(a)') '# '//path//': the design loop reaches '//name//'''s final F ('//str(f, 4)// &
          ') after '//str(loop_nf(k))//' analyses, '//str(real(loop_nf(k), dp)/prob%n_analyses, 3)//' of its '// &
          str(prob%n_analyses)
        return
      end if
    end do
  end subroutine run_method
end program bench_design
