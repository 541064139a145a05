!> Feasibility restoration (module feasibility_restoration): Gauss steps on
!> the constraint violation reach a feasible point from where GNLC.NS gets
!> stuck, with constraint evaluations only, and decline where the violation
!> is stationary.
module test_feasibility_restoration_suite
  use kinds, only: dp
  use error_status, only: error_t
  use hs_collection, only: hs_problem_t, create_hs
  use problem_library, only: quadratic_problem_t
  use feasibility_restoration, only: restore_feasibility
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('hs23_restored_from_the_origin_without_analysis', test_hs23_origin)
    call run_test('stationary_violation_is_not_restored', test_stationary)
  end subroutine run_all

  !> HS 23 at the origin (where GNLC.NS lands from (3, 1)): x1 + x2 >= 1,
  !> x1^2 + x2^2 >= 1, 9 x1^2 + x2^2 >= 9 violated, the last two with zero
  !> gradients.  The first Gauss step follows x1 + x2 >= 1 alone (the
  !> minimum-norm step to (1/2, 1/2)); from there all gradients are nonzero.
  !> The restored point must satisfy every constraint to feas_tol (a
  !> feasibility statement independent of the path), with no analysis.
  subroutine test_hs23_origin()
    type(hs_problem_t) :: p
    real(dp), allocatable :: x0(:), xs(:), x(:), g(:)
    real(dp) :: fs
    type(error_t) :: err
    logical :: found, ok
    integer :: steps
    call create_hs(23, p, x0, xs, fs, found)
    x = [0.0_dp, 0.0_dp]
    allocate(g(p%m + p%n_eq))
    call restore_feasibility(p, x, g, 1.0e-8_dp, 50, ok, steps, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_true(ok, 'HS 23: restored')
    call assert_true(maxval(g(1:p%m)) <= 1.0e-8_dp, 'HS 23: every constraint holds at the restored point')
    call assert_true(steps >= 2 .and. steps <= 10, 'HS 23: a few Gauss steps (the first from (0, 0) alone is '// &
                     'not enough: x1^2 + x2^2 >= 1 still fails at (1/2, 1/2))')
    call assert_equal(p%count%analyses, 0, 'no analysis (objective evaluation) during the restoration')
  end subroutine test_hs23_origin

  !> x^2 + 1 <= 0 at x = 0: the violation V = (x^2 + 1)^2 is stationary (its
  !> gradient 2x is zero) and has no feasible point: not ok, x unchanged.
  subroutine test_stationary()
    type(quadratic_problem_t) :: q
    real(dp), allocatable :: x(:), g(:)
    type(error_t) :: err
    logical :: ok
    integer :: steps
    call q%init_problem('infeasible', 1, 0, 1)
    q%q = reshape([2.0_dp], [1, 1])
    q%lin = [0.0_dp]
    call q%set_quadratic_constraint(1, reshape([2.0_dp], [1, 1]), [0.0_dp], -1.0_dp)
    x = [0.0_dp]
    allocate(g(1))
    call restore_feasibility(q, x, g, 1.0e-8_dp, 50, ok, steps, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_true(.not. ok, 'no feasible point: not restored')
    call assert_close(x(1), 0.0_dp, 0.0_dp, 'x left where it was')
    call assert_close(g(1), 1.0_dp, 1.0e-15_dp, 'violation reported (g = 1)')
  end subroutine test_stationary
end module test_feasibility_restoration_suite

program test_feasibility_restoration
  use test_feasibility_restoration_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_feasibility_restoration')
end program test_feasibility_restoration
