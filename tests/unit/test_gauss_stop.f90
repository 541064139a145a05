!> The stop tests of the Gauss optimizer (doc/optimization.md §5): the step
!> test (3) and its alternative (3'), F resolved to ftol by the exact model
!> (Gill, Murray & Wright, Practical Optimization §8.2.3).
module test_gauss_stop_suite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use optim_problem, only: opt_problem_t
  use gauss_optimizer
  use assertions
  implicit none
  private
  public :: run_all

  !> F = exp(x - 10) - (x - 10): minimum F* = 1 at x* = 10, with analytic
  !> gradient and Hessian.  Newton from x0 = 11 converges quadratically:
  !> errors 1, 0.368, 0.0601, 1.77e-3, 1.56e-6, 1.22e-12 (x_0 .. x_5).
  type, extends(opt_problem_t) :: exp_problem_t
  contains
    procedure :: objective => exp_objective
    procedure :: gradient => exp_gradient
    procedure :: hessian => exp_hessian
  end type exp_problem_t

contains

  subroutine run_all()
    call run_test('no_analysis_for_a_step_that_cannot_change_f', test_f_resolved)
  end subroutine run_all

  !> At x_4 (error e = 1.56e-6) the Newton step is 1.56e-6, above xtol (1 +
  !> |x|) = 1.1e-7 (test 3 fails), but its predicted change e^2/2 = 1.22e-12
  !> is below ftol (1 + |F|) = 2e-12, the step is below sqrt(ftol) (1 + |x|)
  !> = 1.1e-5 and the gradient 1.56e-6 below ftol^(1/3) (1 + |F|) = 2e-4:
  !> (3') holds and the run stops at x_4 with NF = 5 (before: 6), F optimal
  !> to 1.22e-12 <= ftol (1 + |F*|).  With ftol = 1e-14 the same step's
  !> prediction is no longer below the resolution asked for: the run takes
  !> it (NF = 6) and ends at x* to 1.2e-12 (test 3).  The margins (1.22 vs
  !> 2, 1e-12 vs 1.1e-7) are far above the round-off of any optimization
  !> level.
  subroutine test_f_resolved()
    type(exp_problem_t) :: p
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    call p%init_problem('exp', 1, 0, 0)
    call opt%solve(p, [11.0_dp], err)
    call assert_true(opt%status == status_converged, 'converged: '//opt%message)
    call assert_equal(p%count%analyses, 5, 'stopped at x_4 without analysing the step to x_5')
    call assert_true(abs(opt%f - 1.0_dp) <= 1.0e-12_dp*2.0_dp, 'F optimal to ftol (1 + |F*|): F - 1 = '// &
                     str(opt%f - 1.0_dp, 3))
    call assert_true(abs(opt%x(1) - 10.0_dp) > 1.0e-8_dp*11.0_dp, 'the step test alone would not have stopped')
    call p%reset_counters()
    opt%opts%ftol = 1.0e-14_dp
    call opt%solve(p, [11.0_dp], err)
    call assert_true(opt%status == status_converged, 'ftol = 1e-14: converged: '//opt%message)
    call assert_equal(p%count%analyses, 6, 'ftol = 1e-14: the step to x_5 is analysed')
    call assert_close(opt%x(1), 10.0_dp, 1.0e-8_dp*11.0_dp, 'ftol = 1e-14: x* to xtol (1 + |x|)')
  end subroutine test_f_resolved

  subroutine exp_objective(self, x, f, err)
    class(exp_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    f = exp(x(1) - 10.0_dp) - (x(1) - 10.0_dp)
    if (.false.) call err%clear()
    if (.false.) call self%reset_counters()
  end subroutine exp_objective

  subroutine exp_gradient(self, x, f, grad, err)
    class(exp_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    grad(1) = exp(x(1) - 10.0_dp) - 1.0_dp
    if (.false.) grad(1) = f
    if (.false.) call err%clear()
    if (.false.) call self%reset_counters()
  end subroutine exp_gradient

  subroutine exp_hessian(self, x, hess, err)
    class(exp_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    hess(1, 1) = exp(x(1) - 10.0_dp)
    if (.false.) call err%clear()
    if (.false.) call self%reset_counters()
  end subroutine exp_hessian
end module test_gauss_stop_suite

program test_gauss_stop
  use test_gauss_stop_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_gauss_stop')
end program test_gauss_stop
