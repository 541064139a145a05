!> Tests of the `optimize` analysis (module optimize_analysis): decks in,
!> iteration table and summary out, input errors with code 2, diagnoses kept
!> with the output.
module test_optimize_analysis_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_runner, only: start_suite, run_text, has_line, summary_value, line_length
  use optimize_analysis, only: run_optimize, check_problem_derivatives
  use optim_problem, only: opt_problem_t
  use assertions
  implicit none
  private
  public :: run_all

  !> F = x1^2 + 3 x2^2 with a gradient that is right (wrong = .false.) or
  !> has the factor 3 of x2 forgotten (a typical slip).
  type, extends(opt_problem_t) :: slip_problem_t
    logical :: wrong = .false.
  contains
    procedure :: objective => slip_objective
    procedure :: gradient => slip_gradient
  end type slip_problem_t

contains

  subroutine run_all()
    call start_suite('test_optimize_analysis', run_optimize)
    call run_test('rosen_suzuki_deck_gives_table_and_summary', test_good_deck)
    call run_test('bad_values_are_input_errors', test_bad_values)
    call run_test('gnlc_infeasible_start_is_an_input_error', test_infeasible)
    call run_test('iteration_limit_keeps_table_and_best_point', test_iteration_limit)
    call run_test('deck_posed_quadratic_problem_with_equality', test_deck_problem)
    call run_test('check_derivatives_finds_a_wrong_gradient', test_check_derivatives)
  end subroutine run_all

  subroutine slip_objective(self, x, f, err)
    class(slip_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    f = x(1)**2 + 3.0_dp*x(2)**2
    if (err%failed() .and. self%wrong) return
  end subroutine slip_objective

  subroutine slip_gradient(self, x, f, grad, err)
    class(slip_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    grad = [2.0_dp*x(1), merge(2.0_dp, 6.0_dp, self%wrong)*x(2)]
    if (err%failed() .and. f > 0.0_dp) return
  end subroutine slip_gradient

  !> check_derivatives: the right gradient passes (relative error ~1e-10),
  !> the slipped one (2 x2 for 6 x2: error 4/6 at x = (1, 1)) is an input
  !> error (code 2) that names the objective gradient; the check's own
  !> evaluations leave the problem's counts as they were; and a deck with
  !> check_derivatives = T prints the table before the run.
  subroutine test_check_derivatives()
    type(slip_problem_t) :: p
    character(len=160), allocatable :: table(:)
    character(len=line_length), allocatable :: lines(:)
    type(error_t) :: err
    call p%init_problem('slip', 2, 0, 0)
    call check_problem_derivatives(p, [1.0_dp, 1.0_dp], table, err)
    call assert_true(.not. err%failed(), 'right gradient accepted: '//err%text())
    call assert_true(any(index(table, 'objective gradient') > 0), 'the table names the objective gradient')
    call assert_equal(p%count%analyses, 0, 'the check leaves the counts unchanged')
    p%wrong = .true.
    call check_problem_derivatives(p, [1.0_dp, 1.0_dp], table, err)
    call assert_true(err%failed() .and. err%code == 2, 'wrong gradient: input error, code 2')
    call assert_true(index(err%text(), 'objective gradient 0.667') > 0, 'names it with its error: '//err%text())
    call err%clear()
    call run_text("&run analysis='optimize' /|&optimize problem='hs63', check_derivatives = T /", err, lines)
    call assert_true(.not. err%failed(), 'HS 63 derivatives consistent: '//err%text())
    call assert_true(has_line(lines, '# derivative check at x0'), 'table printed')
    call assert_true(has_line(lines, '#   objective Hessian:'), 'Hessian checked')
  end subroutine test_check_derivatives

  !> HS 6 posed by coefficients (issue 11): F = (1 - x1)^2 = 1/2 x^T diag(2, 0) x
  !> - 2 x1 + 1, h = 1/2 x^T diag(-20, 0) x + 10 x2 = 0 (a quadratic equality),
  !> from (-1.2, 1) with default settings: x* = (1, 1), F* = 0 (HS).
  subroutine test_deck_problem()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text("&run analysis='optimize' /|&optimize problem='deck', x0 = -1.2, 1 /|" // &
                  "&problem_data n = 2, f_q(1,1) = 2, f_c = -2, 0, f_0 = 1, n_eq = 1, h_q(1,1,1) = -20, " // &
                  "h_a(1,2) = 10, h_b(1) = 0, f_star = 0, x_star = 1, 1 /", err, lines)
    call assert_true(.not. err%failed(), 'no error: '//err%text())
    call assert_true(has_line(lines, '# summary: status = converged'), 'converged')
    call assert_true(has_line(lines, 'h3 quadratic equality') .or. has_line(lines, 'h1 quadratic equality'), &
                     'the equality is recognised as quadratic')
    ! the step test stops within xtol (1 + |x|) = 2e-8 of x*
    call assert_true(summary_value(lines, '# summary: |x - x*|_inf =') < 2.0e-8_dp, '|x - x*| < 2e-8')
    ! a bound above its upper bound is an input error naming both
    call run_text("&run analysis='optimize' /|&optimize problem='deck' /|" // &
                  "&problem_data n = 1, f_q(1,1) = 2, lower = 2, upper = 1 /", err, lines)
    call assert_true(err%code == 2 .and. index(err%text(), 'upper(1)') > 0, 'lower > upper rejected')
  end subroutine test_deck_problem

  subroutine test_good_deck()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    real(dp) :: row(6 + 4 + 3 + 3)
    integer :: i, n_rows
    call run_text("&run analysis='optimize' /|&optimize problem='rosen_suzuki', method='gnlc_ns', " // &
                  "x0 = 0, 0, 0, 0 /", err, lines)
    call assert_true(.not. err%failed(), 'no error: '//err%text())
    call assert_true(has_line(lines, '# summary: status = converged'), 'status converged')
    call assert_true(has_line(lines, '# summary: NI = 2'), 'NI = 2 (Table I: 2)')
    call assert_true(has_line(lines, '# summary: NF = 3'), 'NF = 3 (Table I: 3)')
    call assert_true(has_line(lines, 'active constraints (|g| <= feas_tol) = {1, 3}'), 'active set {1, 3}')
    call assert_true(has_line(lines, '# cost: analyses NF'), 'cost lines')
    n_rows = 0
    do i = 1, size(lines)
      if (lines(i)(1:1) == '#') cycle
      n_rows = n_rows + 1
      read(lines(i), *) row
    end do
    call assert_equal(n_rows, 3, 'one row per iterate (k = 0, 1, 2)')
    call assert_close(row(1), 2.0_dp, 0.0_dp, 'last row k = 2')
    call assert_close(row(2), 3.0_dp, 0.0_dp, 'last row NF = 3')
    call assert_close(row(3), -44.0_dp, 1.0e-9_dp, 'F = -44')
    call assert_all_close(row(7:10), [0.0_dp, 1.0_dp, 2.0_dp, -1.0_dp], 0.0_dp, 1.0e-9_dp, 'x*')
    call assert_all_close(row(11:13), [1.0_dp, 0.0_dp, 2.0_dp], 0.0_dp, 1.0e-9_dp, 'multipliers')
    call assert_all_close(row(14:16), [1.0_dp, 0.0_dp, 1.0_dp], 0.0_dp, 0.0_dp, 'active flags')
  end subroutine test_good_deck

  subroutine test_bad_values()
    character(len=line_length), allocatable :: lines(:)
    call bad("problem='rosen_suzuki', method='gnlc_xx'", 'method', 'unknown method named')
    call bad("problem='nope'", 'rosen_suzuki', 'unknown problem: valid names listed')
    call bad("problem='rosen_suzuki', x0 = 1, 2", '4 variables', 'x0 of the wrong length')
    call bad('xtol = -1', 'xtol', 'negative xtol')
    call bad("potter_fix = 'b'", 'potter_fix', 'unknown potter_fix')
    call bad("step_back = 'half'", 'step_back', 'unknown step_back')
    call assert_equal(size(lines), 0, 'no output kept for input errors')
  contains
    !> &optimize `group` is an input error naming `fragment`.
    subroutine bad(group, fragment, message)
      character(len=*), intent(in) :: group, fragment, message
      type(error_t) :: err
      call run_text("&run analysis='optimize' /|&optimize "//group//' /', err, lines)
      call assert_error(err, 2, fragment, message)
    end subroutine bad
  end subroutine test_bad_values

  subroutine test_infeasible()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text("&run analysis='optimize' /|&optimize problem='rosen_suzuki', method='gnlc', x0 = 2, 2, 2, 2 /", &
                  err, lines)
    call assert_error(err, 2, 'infeasible', 'input error: says infeasible, suggests gnlc_ns', 'gnlc_ns')
  end subroutine test_infeasible

  subroutine test_iteration_limit()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_text("&run analysis='optimize' /|&optimize problem='rosen_suzuki', method='gnlc', max_iter = 1 /", &
                  err, lines)
    call assert_true(err%failed() .and. err%code /= 2, 'a diagnosis, not an input error')
    call assert_true(has_line(lines, '# summary: status = iteration limit reached'), 'status line')
    call assert_true(has_line(lines, '# summary: best feasible F'), 'best feasible point reported')
  end subroutine test_iteration_limit
end module test_optimize_analysis_suite

program test_optimize_analysis
  use test_optimize_analysis_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_optimize_analysis')
end program test_optimize_analysis
