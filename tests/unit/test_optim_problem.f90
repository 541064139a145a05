!> Tests of the optimization problem type (module optim_problem): forward-
!> difference defaults against analytic derivatives, constraint data, counters.
module test_optim_problem_suite
  use kinds, only: dp
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t, con_linear, con_quadratic, con_general
  use assertions
  use test_text, only: itoa
  implicit none
  private
  public :: run_all

  !> phi = (x1^2 - x2, sin(x1) x3, exp(x2) - x3^3): residuals only, so the
  !> Jacobian comes from the forward-difference default.
  type, extends(opt_problem_t) :: residual_only_t
  contains
    procedure :: residuals => ro_residuals
  end type residual_only_t

  !> F = x1^4 + x1 x2^2 + exp(x3) (objective only); general constraint
  !> g1 = x1 x2 x3 - 1 (value only): everything else by differences.
  type, extends(opt_problem_t) :: objective_only_t
  contains
    procedure :: objective => oo_objective
    procedure :: general_constraint => oo_constraint
  end type objective_only_t

  !> Overrides nothing: every call must fail with a message.
  type, extends(opt_problem_t) :: empty_t
  end type empty_t

  !> One general inequality g1 = x1 + x2 - 2 (i = 1) and one general
  !> equality h1 = x1 x2 - 0.5, which the procedure knows as i = 2 (its own
  !> inequalities, then the equality), whatever bounds set_bounds adds.
  type, extends(opt_problem_t) :: numbered_t
  contains
    procedure :: objective => oo_objective_2
    procedure :: general_constraint => numbered_constraint
  end type numbered_t

contains

  subroutine run_all()
    call run_test('fd_jacobian_matches_analytic', test_fd_jacobian)
    call run_test('fd_gradient_and_hessian_match_analytic', test_fd_gradient_hessian)
    call run_test('fd_constraint_gradient_and_hessian_match_analytic', test_fd_constraint)
    call run_test('linear_quadratic_and_equality_constraint_data', test_constraint_data)
    call run_test('analyses_and_gradients_are_counted', test_counters)
    call run_test('missing_procedures_are_reported', test_missing)
    call run_test('equality_numbering_does_not_shift_with_bounds', test_numbering)
  end subroutine run_all

  subroutine oo_objective_2(self, x, f, err)
    class(numbered_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    f = sum(x**2)
    if (.false.) call err%set(self%name, '')
  end subroutine oo_objective_2

  subroutine numbered_constraint(self, i, x, g, err)
    class(numbered_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    select case (i)
    case (1)
      g = x(1) + x(2) - 2.0_dp
    case (2)
      g = x(1)*x(2) - 0.5_dp
    case default
      g = 0.0_dp
      call err%set(self%name, 'no general constraint '//itoa(i))
    end select
  end subroutine numbered_constraint

  !> An equality given by a procedure keeps its number (m_own + j = 2 here)
  !> when set_bounds adds four bounds before or after it is declared: the
  !> values, the difference gradient and Hessian of the equality (internal
  !> column m + 1 = 6) are those of h1, and no call reaches the procedure
  !> with another number.  Before, the equality arrived as i = 6 once the
  !> bounds were added, and a procedure written for i = 2 failed.
  subroutine test_numbering()
    type(numbered_t) :: p, q
    type(error_t) :: err
    real(dp) :: x(2), g(6), dg(2, 6), hess(2, 2)
    x = [0.3_dp, 0.9_dp]
    call p%init_problem('numbered', 2, 0, 1, n_eq=1)
    call p%set_general_constraint(1)
    call p%set_general_equality(1)
    call p%set_bounds([0.0_dp, 0.0_dp], [1.0_dp, 1.0_dp])      ! bounds after the equality
    call q%init_problem('numbered', 2, 0, 1, n_eq=1)
    call q%set_bounds([0.0_dp, 0.0_dp], [1.0_dp, 1.0_dp])      ! bounds before it
    call q%set_general_constraint(1)
    call q%set_general_equality(1)
    call assert_equal(p%m, 5, 'four bounds after the general inequality')
    call p%constraint_values(x, g, err)
    call assert_close(g(1), x(1) + x(2) - 2.0_dp, 1.0e-15_dp, 'inequality 1')
    call assert_close(g(6), x(1)*x(2) - 0.5_dp, 1.0e-15_dp, 'equality 1 in column m + 1, from procedure number 2')
    call p%constraint_gradients(x, g, dg, err)
    call assert_all_close(dg(:, 6), [x(2), x(1)], 0.0_dp, 1.0e-7_dp, 'equality gradient by differences')
    call p%constraint_hessian(6, x, hess, err)
    call assert_all_close(reshape(hess, [4]), [0.0_dp, 1.0_dp, 1.0_dp, 0.0_dp], 0.0_dp, 1.0e-6_dp, &
                          'equality Hessian by differences')
    call assert_true(.not. err%failed(), 'every call numbered as the procedure expects: '//err%text())
    call q%constraint_values(x, g, err)
    call assert_close(g(6), x(1)*x(2) - 0.5_dp, 1.0e-15_dp, 'the same with the bounds set first')
    call assert_true(.not. err%failed(), 'no error with the bounds set first')
  end subroutine test_numbering

  subroutine ro_residuals(self, x, phi, err)
    class(residual_only_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    phi = [x(1)**2 - x(2), sin(x(1))*x(3), exp(x(2)) - x(3)**3]
    if (.false.) call err%set(self%name, '')
  end subroutine ro_residuals

  subroutine oo_objective(self, x, f, err)
    class(objective_only_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    f = x(1)**4 + x(1)*x(2)**2 + exp(x(3))
    if (.false.) call err%set(self%name, '')
  end subroutine oo_objective

  subroutine oo_constraint(self, i, x, g, err)
    class(objective_only_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = x(1)*x(2)*x(3) - 1.0_dp
    if (.false.) call err%set(self%name, itoa(i))
  end subroutine oo_constraint

  subroutine test_fd_jacobian()
    type(residual_only_t) :: p
    type(error_t) :: err
    real(dp) :: x(3), phi(3), jac(3, 3), exact(3, 3), f, grad(3)
    call p%init_problem('residual_only', 3, 3, 0)
    x = [0.7_dp, -0.3_dp, 1.2_dp]
    call p%analyse(x, f, phi, err)
    call p%objective_derivatives(x, f, phi, grad, jac, err)
    call assert_true(.not. err%failed(), 'no error')
    ! J(n, p): column i = grad phi_i (P3)
    exact(:, 1) = [2.0_dp*x(1), -1.0_dp, 0.0_dp]
    exact(:, 2) = [cos(x(1))*x(3), 0.0_dp, sin(x(1))]
    exact(:, 3) = [0.0_dp, exp(x(2)), -3.0_dp*x(3)**2]
    ! forward differences with h = sqrt(eps) max(|x|, 1): error ~ h |phi''| ~ 1e-7
    call assert_all_close(reshape(jac, [9]), reshape(exact, [9]), 0.0_dp, 3.0e-7_dp, 'J by differences')
    call assert_all_close(grad, 2.0_dp*matmul(exact, phi), 0.0_dp, 1.0e-6_dp, 'grad F = 2 J phi (B4)')
    call assert_close(f, sum(phi**2), 1.0e-15_dp, 'F = phi^T phi')
  end subroutine test_fd_jacobian

  subroutine test_fd_gradient_hessian()
    type(objective_only_t) :: p
    type(error_t) :: err
    real(dp) :: x(3), f, grad(3), hess(3, 3), exact(3, 3), phi(0), jac(3, 0)
    call p%init_problem('objective_only', 3, 0, 0)
    x = [1.1_dp, 0.4_dp, -0.5_dp]
    call p%analyse(x, f, phi, err)
    call p%objective_derivatives(x, f, phi, grad, jac, err)
    call assert_all_close(grad, [4.0_dp*x(1)**3 + x(2)**2, 2.0_dp*x(1)*x(2), exp(x(3))], 0.0_dp, 1.0e-6_dp, &
                          'forward-difference gradient (error ~ h |F''''| ~ 1e-7)')
    call p%objective_hessian(x, hess, err)
    exact = reshape([12.0_dp*x(1)**2, 2.0_dp*x(2), 0.0_dp, 2.0_dp*x(2), 2.0_dp*x(1), 0.0_dp, &
                     0.0_dp, 0.0_dp, exp(x(3))], [3, 3])
    ! central second differences, h = eps^(1/4): error O(h^2 F'''') + O(eps/h^2) ~ 1e-7
    call assert_all_close(reshape(hess, [9]), reshape(exact, [9]), 0.0_dp, 1.0e-6_dp, 'central-difference Hessian')
    call assert_true(.not. err%failed(), 'no error')
  end subroutine test_fd_gradient_hessian

  subroutine test_fd_constraint()
    type(objective_only_t) :: p
    type(error_t) :: err
    real(dp) :: x(3), g(1), dg(3, 1), hess(3, 3), exact(3, 3)
    call p%init_problem('objective_only', 3, 0, 1)
    call p%set_general_constraint(1)
    x = [1.1_dp, 0.4_dp, -0.5_dp]
    call p%constraint_values(x, g, err)
    call assert_close(g(1), x(1)*x(2)*x(3) - 1.0_dp, 1.0e-15_dp, 'general constraint value')
    call p%constraint_gradients(x, g, dg, err)
    call assert_all_close(dg(:, 1), [x(2)*x(3), x(1)*x(3), x(1)*x(2)], 0.0_dp, 1.0e-7_dp, 'gradient by differences')
    call p%constraint_hessian(1, x, hess, err)
    exact = reshape([0.0_dp, x(3), x(2), x(3), 0.0_dp, x(1), x(2), x(1), 0.0_dp], [3, 3])
    call assert_all_close(reshape(hess, [9]), reshape(exact, [9]), 0.0_dp, 1.0e-7_dp, 'Hessian by differences')
    call assert_equal(p%count%constraint_hessians, 1, 'one constraint Hessian counted')
    call assert_true(p%count%fd_constraint_evals == 3 + 2*9 + 1, 'differences counted: n + (2n^2 + 1)')
    call assert_true(.not. err%failed(), 'no error')
  end subroutine test_fd_constraint

  subroutine test_constraint_data()
    type(objective_only_t) :: p
    type(error_t) :: err
    real(dp) :: x(3), dg(3, 4), a(3, 3), hess(3, 3)
    real(dp), allocatable :: g(:)
    call p%init_problem('data', 3, 0, 3, n_eq=1)
    allocate(g(4))
    call p%set_linear_constraint(1, [1.0_dp, -2.0_dp, 0.5_dp], 3.0_dp)
    a = reshape([2.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 4.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, -2.0_dp], [3, 3])
    call p%set_quadratic_constraint(2, a, [1.0_dp, 0.0_dp, -1.0_dp], 2.0_dp)
    call p%set_general_constraint(3)
    call p%set_linear_equalities(reshape([1.0_dp, 1.0_dp, 1.0_dp], [3, 1]), [1.0_dp])
    call assert_true(all(p%con_kind == [con_linear, con_quadratic, con_general, con_linear]), 'kinds recorded')
    x = [0.5_dp, -1.0_dp, 2.0_dp]
    call p%constraint_values(x, g, err)
    call assert_close(g(1), 0.5_dp + 2.0_dp + 1.0_dp - 3.0_dp, 1.0e-15_dp, 'linear b^T x - d')
    call assert_close(g(2), 0.5_dp*dot_product(x, matmul(a, x)) + 0.5_dp - 2.0_dp - 2.0_dp, 1.0e-14_dp, &
                      'quadratic 1/2 x^T A x + b^T x - d (B3)')
    call assert_close(g(4), 0.5_dp, 1.0e-15_dp, 'equality D^T x - e, numbered m + 1')
    call p%constraint_gradients(x, g, dg, err)
    call assert_all_close(dg(:, 2), matmul(a, x) + [1.0_dp, 0.0_dp, -1.0_dp], 0.0_dp, 1.0e-14_dp, 'A x + b')
    call assert_all_close(dg(:, 4), [1.0_dp, 1.0_dp, 1.0_dp], 0.0_dp, 0.0_dp, 'equality gradient')
    call p%constraint_hessian(2, x, hess, err)
    call assert_all_close(reshape(hess, [9]), reshape(a, [9]), 0.0_dp, 0.0_dp, 'quadratic Hessian = A')
    call p%constraint_hessian(1, x, hess, err)
    call assert_true(all(abs(hess) <= 0.0_dp), 'linear Hessian = 0')
    ! linear inequalities given as a matrix (P4): B^T x - c <= 0
    call p%set_linear_inequalities(reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 1.0_dp], [3, 2]), &
                                   [1.0_dp, 2.0_dp], 2)
    call p%constraint_values(x, g, err)
    call assert_close(g(2), x(1) - 1.0_dp, 1.0e-15_dp, 'matrix row 1 -> constraint 2')
    call assert_close(g(3), x(2) + x(3) - 2.0_dp, 1.0e-15_dp, 'matrix row 2 -> constraint 3')
    call assert_true(all(p%con_kind(2:3) == con_linear), 'set as linear')
    call assert_true(.not. err%failed(), 'no error')
    ! simple bounds (issue 11): 0 <= x1, x3 <= 5 become constraints 4 and 5 after
    ! the three inequalities; the equality moves from 4 to 6 and keeps its data
    call p%set_bounds([0.0_dp, -1.0e30_dp, -1.0e30_dp], [1.0e30_dp, 1.0e30_dp, 5.0_dp])
    call assert_equal(p%m, 5, 'm = 3 inequalities + 2 bounds')
    call assert_equal(p%n_bounds, 2, 'two finite bounds')
    deallocate(g)
    allocate(g(6))
    call p%constraint_values(x, g, err)
    call assert_close(g(4), -x(1), 0.0_dp, 'lower bound 0 - x1 <= 0')
    call assert_close(g(5), x(3) - 5.0_dp, 0.0_dp, 'upper bound x3 - 5 <= 0')
    call assert_close(g(6), 0.5_dp, 1.0e-15_dp, 'the equality, now number m + 1 = 6')
    call assert_all_close(p%project_to_bounds([-1.0_dp, -7.0_dp, 9.0_dp]), [0.0_dp, -7.0_dp, 5.0_dp], 0.0_dp, 0.0_dp, &
                          'projection onto the box')
  end subroutine test_constraint_data

  subroutine test_counters()
    type(residual_only_t) :: p
    type(error_t) :: err
    real(dp) :: x(3), phi(3), jac(3, 3), f, grad(3)
    integer :: k
    call p%init_problem('residual_only', 3, 3, 0)
    x = [0.7_dp, -0.3_dp, 1.2_dp]
    do k = 1, 4
      call p%analyse(x, f, phi, err)
    end do
    call p%objective_derivatives(x, f, phi, grad, jac, err)
    call assert_equal(p%count%analyses, 4, 'NF counts analyses only')
    call assert_equal(p%count%gradients, 1, 'one gradient evaluation')
    call assert_equal(p%count%fd_analyses, 3, 'n residual evaluations in the difference Jacobian')
    call p%reset_counters()
    call assert_equal(p%count%analyses + p%count%fd_analyses, 0, 'reset')
  end subroutine test_counters

  subroutine test_missing()
    type(empty_t) :: p
    type(error_t) :: err
    real(dp) :: x(2), phi(1), f, g(1)
    call p%init_problem('empty', 2, 1, 1)
    call p%set_general_constraint(1)
    x = 0.0_dp
    call p%analyse(x, f, phi, err)
    call assert_true(err%failed() .and. index(err%text(), 'residuals') > 0, 'missing residuals named')
    call err%clear()
    call p%constraint_values(x, g, err)
    call assert_true(err%failed() .and. index(err%text(), 'general_constraint') > 0, 'missing constraint named')
  end subroutine test_missing
end module test_optim_problem_suite

program test_optim_problem
  use test_optim_problem_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_optim_problem')
end program test_optim_problem
