!> Tests of the multiplier equations and steps (module multiplier_equations):
!> the closed forms of Paradis & Willmert, B10/B11 solved by Newton at a
!> known optimum, the Powell fallback when B11 has no solution, and Potter's
!> actual constraints.
module test_multiplier_equations_suite
  use kinds, only: dp
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  use multiplier_equations, only: multiplier_system_t, multiplier_result_t, multiplier_system, gauss_step, &
                                  linear_multipliers
  use assertions
  implicit none
  private
  public :: run_all

  !> g1 = exp(x1) - x2 (general), for Potter's actual-constraint residual.
  type, extends(opt_problem_t) :: exp_constraint_t
  contains
    procedure :: general_constraint => exp_constraint
  end type exp_constraint_t

contains

  subroutine run_all()
    call run_test('gauss_step_solves_linear_least_squares_in_one_step', test_gauss_step)
    call run_test('linear_multipliers_match_paradis_willmert_P16_P17', test_p17)
    call run_test('newton_recovers_rosen_suzuki_multipliers_at_optimum', test_rosen_suzuki_newton)
    call run_test('newton_agrees_with_closed_form_for_linear_constraints', test_newton_linear)
    call run_test('no_solution_falls_back_to_powell_minimum_of_H', test_powell_fallback)
    call run_test('potter_actual_constraint_in_B11', test_potter_actual)
  end subroutine run_all

  subroutine exp_constraint(self, i, x, g, err)
    class(exp_constraint_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = exp(x(1)) - x(2)
    if (.false.) call err%set(self%name, repeat('x', i))
  end subroutine exp_constraint

  !> Linear residuals phi = A^T x - y: one Gauss step (B12) from anywhere
  !> lands on the least-squares solution of A^T x = y (normal equations).
  subroutine test_gauss_step()
    real(dp) :: a(2, 4), y(4), x0(2), phi(4), s(2), g(2, 2), xls(2), n(2, 2), rhs(2), det
    type(error_t) :: err
    a = reshape([1.0_dp, 0.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 2.0_dp, 1.0_dp, 3.0_dp], [2, 4])
    y = [1.0_dp, 2.0_dp, 2.0_dp, 4.0_dp]
    x0 = [5.0_dp, -7.0_dp]
    phi = matmul(transpose(a), x0) - y
    g = 2.0_dp*matmul(a, transpose(a))
    call gauss_step(g, 2.0_dp*matmul(a, phi), s, err)
    ! normal equations by Cramer's rule, independent of LAPACK
    n = matmul(a, transpose(a))
    rhs = matmul(a, y)
    det = n(1, 1)*n(2, 2) - n(1, 2)*n(2, 1)
    xls = [rhs(1)*n(2, 2) - rhs(2)*n(1, 2), n(1, 1)*rhs(2) - n(2, 1)*rhs(1)]/det
    call assert_all_close(x0 + s, xls, 0.0_dp, 1.0e-12_dp, 'x0 + s = least-squares solution')
    call assert_true(.not. err%failed(), 'no error')
  end subroutine test_gauss_step

  !> P17: x_{k+1} = x_k - [I - (JJ^T)^{-1} B (B^T (JJ^T)^{-1} B)^{-1} B^T] (JJ^T)^{-1} J phi,
  !> P16: lambda = -[B^T (2JJ^T)^{-1} B]^{-1} B^T (2JJ^T)^{-1} 2 J phi, written out
  !> with explicit inverses (2x2 blocks by Cramer's rule) and compared.
  subroutine test_p17()
    real(dp) :: jac(3, 4), phi(4), b(3, 2), g(3, 3), gradf(3), lam(2), s(3)
    real(dp) :: ginv(3, 3), k(2, 2), kinv(2, 2), p(3, 3), s17(3), lam16(2), eye(3, 3)
    type(error_t) :: err
    integer :: i
    jac = reshape([1.0_dp, 0.2_dp, 0.0_dp, 0.3_dp, 1.0_dp, 0.1_dp, 0.0_dp, 0.4_dp, 2.0_dp, 0.5_dp, 0.5_dp, 0.5_dp], &
                  [3, 4])
    phi = [0.3_dp, -1.0_dp, 0.7_dp, 2.0_dp]
    b = reshape([1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp], [3, 2])
    g = 2.0_dp*matmul(jac, transpose(jac))
    gradf = 2.0_dp*matmul(jac, phi)
    call linear_multipliers(g, gradf, b, [0.0_dp, 0.0_dp], lam, s, err)
    call assert_true(.not. err%failed(), 'no error')
    ginv = inverse3(matmul(jac, transpose(jac)))      ! (JJ^T)^{-1}
    k = matmul(transpose(b), matmul(ginv, b))
    kinv = reshape([k(2, 2), -k(2, 1), -k(1, 2), k(1, 1)], [2, 2])/(k(1, 1)*k(2, 2) - k(1, 2)*k(2, 1))
    eye = 0.0_dp
    do i = 1, 3
      eye(i, i) = 1.0_dp
    end do
    p = eye - matmul(ginv, matmul(b, matmul(kinv, transpose(b))))
    s17 = -matmul(p, matmul(ginv, matmul(jac, phi)))
    lam16 = -matmul(2.0_dp*kinv, matmul(transpose(b), matmul(0.5_dp*ginv, gradf)))   ! (2JJ^T)^{-1} = ginv/2
    call assert_all_close(s, s17, 0.0_dp, 1.0e-12_dp, 'step = P17')
    call assert_all_close(lam, lam16, 0.0_dp, 1.0e-12_dp, 'multipliers = P16')
    call assert_all_close(matmul(transpose(b), s), [0.0_dp, 0.0_dp], 0.0_dp, 1.0e-13_dp, 'B^T s = 0: stays on the constraints')
  end subroutine test_p17

  pure function inverse3(a) result(inv)
    real(dp), intent(in) :: a(3, 3)
    real(dp) :: inv(3, 3), det
    inv(1, 1) = a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)
    inv(1, 2) = a(1, 3)*a(3, 2) - a(1, 2)*a(3, 3)
    inv(1, 3) = a(1, 2)*a(2, 3) - a(1, 3)*a(2, 2)
    inv(2, 1) = a(2, 3)*a(3, 1) - a(2, 1)*a(3, 3)
    inv(2, 2) = a(1, 1)*a(3, 3) - a(1, 3)*a(3, 1)
    inv(2, 3) = a(1, 3)*a(2, 1) - a(1, 1)*a(2, 3)
    inv(3, 1) = a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1)
    inv(3, 2) = a(1, 2)*a(3, 1) - a(1, 1)*a(3, 2)
    inv(3, 3) = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
    det = a(1, 1)*inv(1, 1) + a(1, 2)*inv(2, 1) + a(1, 3)*inv(3, 1)
    inv = inv/det
  end function inverse3

  !> Rosen-Suzuki data (FORMULATION.md §10.1) at a start on g1 = g3 = 0
  !> would take one iteration; at x* itself B11 with S = {1, 3} must return
  !> lambda = (1, 2) and a zero step (the KKT point of §10.1).
  subroutine test_rosen_suzuki_newton()
    type(multiplier_system_t) :: msys
    type(multiplier_result_t) :: res
    type(error_t) :: err
    class(opt_problem_t), pointer :: none => null()
    real(dp) :: g(4, 4), x(4), gradf(4), a(4, 4, 2), c(4, 2), lam(2), gval(2)
    g = diag4([2.0_dp, 2.0_dp, 4.0_dp, 2.0_dp])
    x = [0.0_dp, 1.0_dp, 2.0_dp, -1.0_dp]
    gradf = matmul(g, x) + [-5.0_dp, -5.0_dp, -21.0_dp, 7.0_dp]
    a(:, :, 1) = diag4([2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp])
    a(:, :, 2) = diag4([4.0_dp, 2.0_dp, 2.0_dp, 0.0_dp])
    c(:, 1) = matmul(a(:, :, 1), x) + [1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp]
    c(:, 2) = matmul(a(:, :, 2), x) + [2.0_dp, -1.0_dp, 0.0_dp, -1.0_dp]
    gval = [0.0_dp, 0.0_dp]
    msys = multiplier_system(g, gradf, x, [1, 3], gval, c, a, [.false., .false.], none)
    lam = [0.0_dp, 0.0_dp]
    call msys%solve(lam, 1.0e-12_dp, 30, res, err)
    call assert_true(res%solved .and. res%how == 'newton', 'solved by Newton')
    call assert_all_close(lam, [1.0_dp, 2.0_dp], 0.0_dp, 1.0e-12_dp, 'lambda = (1, 2)')
    call assert_all_close(msys%s, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], 0.0_dp, 1.0e-12_dp, 'zero step at x*')
    ! from a point off the optimum the same active set gives x* in one step
    ! (quadratic F and constraints: the design aim of B10)
    x = [0.3_dp, 0.8_dp, 1.7_dp, -1.4_dp]
    gradf = matmul(g, x) + [-5.0_dp, -5.0_dp, -21.0_dp, 7.0_dp]
    c(:, 1) = matmul(a(:, :, 1), x) + [1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp]
    c(:, 2) = matmul(a(:, :, 2), x) + [2.0_dp, -1.0_dp, 0.0_dp, -1.0_dp]
    gval(1) = 0.5_dp*dot_product(x, matmul(a(:, :, 1), x)) + dot_product([1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp], x) - 8.0_dp
    gval(2) = 0.5_dp*dot_product(x, matmul(a(:, :, 2), x)) + dot_product([2.0_dp, -1.0_dp, 0.0_dp, -1.0_dp], x) - 5.0_dp
    msys = multiplier_system(g, gradf, x, [1, 3], gval, c, a, [.false., .false.], none)
    lam = [0.0_dp, 0.0_dp]
    call msys%solve(lam, 1.0e-12_dp, 30, res, err)
    call assert_all_close(x + msys%s, [0.0_dp, 1.0_dp, 2.0_dp, -1.0_dp], 0.0_dp, 1.0e-10_dp, &
                          'one B10 step from any point reaches x* when S = {1, 3}')
    call assert_all_close(lam, [1.0_dp, 2.0_dp], 0.0_dp, 1.0e-10_dp, 'lambda = (1, 2) from any point')
    call assert_true(.not. err%failed(), 'no error')
  end subroutine test_rosen_suzuki_newton

  pure function diag4(v) result(a)
    real(dp), intent(in) :: v(4)
    real(dp) :: a(4, 4)
    integer :: i
    a = 0.0_dp
    do i = 1, 4
      a(i, i) = v(i)
    end do
  end function diag4

  !> With A_j = 0 the Newton solution of B11 equals the closed form.
  subroutine test_newton_linear()
    type(multiplier_system_t) :: msys
    type(multiplier_result_t) :: res
    type(error_t) :: err
    class(opt_problem_t), pointer :: none => null()
    real(dp) :: g(3, 3), gradf(3), c(3, 2), a(3, 3, 2), lam(2), lam_cf(2), s_cf(3), x(3), gval(2)
    g = reshape([4.0_dp, 1.0_dp, 0.0_dp, 1.0_dp, 3.0_dp, 0.5_dp, 0.0_dp, 0.5_dp, 2.0_dp], [3, 3])
    gradf = [1.0_dp, -2.0_dp, 0.5_dp]
    c = reshape([1.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, -1.0_dp, 1.0_dp], [3, 2])
    a = 0.0_dp
    x = [0.1_dp, 0.2_dp, 0.3_dp]
    gval = [-0.4_dp, 0.25_dp]        ! off the constraints: the general form of P16
    msys = multiplier_system(g, gradf, x, [1, 2], gval, c, a, [.false., .false.], none)
    lam = [5.0_dp, -5.0_dp]
    call msys%solve(lam, 1.0e-13_dp, 30, res, err)
    call linear_multipliers(g, gradf, c, gval, lam_cf, s_cf, err)
    call assert_true(res%newton_iterations <= 2, 'Newton exact in one step for linear equations')
    call assert_all_close(lam, lam_cf, 0.0_dp, 1.0e-12_dp, 'lambda: Newton = closed form')
    call assert_all_close(msys%s, s_cf, 0.0_dp, 1.0e-12_dp, 'step: Newton = closed form')
    call assert_all_close(gval + matmul(transpose(c), s_cf), [0.0_dp, 0.0_dp], 0.0_dp, 1.0e-13_dp, &
                          'the step lands on both constraints')
  end subroutine test_newton_linear

  !> Three circles with no common point (three_circles problem at its start):
  !> B11 has no solution, Newton fails, Powell minimises H; the result must be
  !> a local minimum of H (no coordinate perturbation lowers it) with H > 0.
  subroutine test_powell_fallback()
    type(multiplier_system_t) :: msys
    type(multiplier_result_t) :: res
    type(error_t) :: err
    class(opt_problem_t), pointer :: none => null()
    real(dp) :: g(2, 2), x(2), gradf(2), a(2, 2, 3), c(2, 3), gval(3), lam(3), centres(2, 3), h0, hp, dl(3)
    integer :: j, sgn
    g = reshape([2.0_dp, 0.0_dp, 0.0_dp, 2.0_dp], [2, 2])
    x = [1.0_dp, 5.0_dp]                         ! F = |x - (1, 5)|^2 at its minimum
    gradf = 0.0_dp
    centres = reshape([0.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, 0.0_dp], [2, 3])
    do j = 1, 3
      a(:, :, j) = g
      c(:, j) = 2.0_dp*(x - centres(:, j))
      gval(j) = sum((x - centres(:, j))**2) - 4.0_dp
    end do
    msys = multiplier_system(g, gradf, x, [1, 2, 3], gval, c, a, [.false., .false., .false.], none)
    lam = 0.0_dp
    call msys%solve(lam, 1.0e-10_dp, 30, res, err)
    call assert_true(.not. err%failed(), 'no error')
    call assert_true(len(res%newton_failure) > 0, 'Newton failure recorded: '//res%newton_failure)
    call assert_true(index(res%how, 'powell') == 1, 'Powell used')
    call assert_true(.not. res%solved .and. res%residual > 0.1_dp, 'no solution: H > 0 remains')
    h0 = msys%value(lam)
    do j = 1, 3
      do sgn = -1, 1, 2
        dl = 0.0_dp
        dl(j) = sgn*1.0e-3_dp*max(1.0_dp, abs(lam(j)))
        hp = msys%value(lam + dl)
        call assert_true(hp >= h0*(1.0_dp - 1.0e-9_dp), 'H at Powell''s lambda is a local minimum')
      end do
    end do
  end subroutine test_powell_fallback

  !> Potter §9.5 item 2: B11 uses the actual constraint g(x_k + s), so the
  !> solved step lands exactly on exp(x1) = x2, not on its quadratic model.
  subroutine test_potter_actual()
    type(exp_constraint_t), target :: p
    class(opt_problem_t), pointer :: pp
    type(multiplier_system_t) :: msys
    type(multiplier_result_t) :: res
    type(error_t) :: err
    real(dp) :: g(2, 2), x(2), gradf(2), a(2, 2, 1), c(2, 1), lam(1), gval(1), xn(2)
    call p%init_problem('exp', 2, 0, 1)
    call p%set_general_constraint(1)
    pp => p
    g = reshape([2.0_dp, 0.0_dp, 0.0_dp, 2.0_dp], [2, 2])
    x = [0.0_dp, 2.0_dp]                         ! F = |x - (1, 0)|^2: target below the curve
    gradf = 2.0_dp*(x - [1.0_dp, 0.0_dp])
    gval(1) = exp(x(1)) - x(2)
    c(:, 1) = [exp(x(1)), -1.0_dp]
    a(:, :, 1) = reshape([exp(x(1)), 0.0_dp, 0.0_dp, 0.0_dp], [2, 2])   ! re-approximation at x_k (P24)
    msys = multiplier_system(g, gradf, x, [1], gval, c, a, [.true.], pp)
    lam = 0.0_dp
    call msys%solve(lam, 1.0e-12_dp, 50, res, err)
    xn = x + msys%s
    call assert_true(res%solved, 'B11 with the actual constraint solved')
    call assert_close(exp(xn(1)) - xn(2), 0.0_dp, 1.0e-12_dp, 'new point exactly on the actual constraint')
    call assert_true(p%count%constraint_evals >= 2, 'actual constraint evaluations counted')
    call assert_true(lam(1) > 0.0_dp, 'positive multiplier: the constraint holds the step back')
  end subroutine test_potter_actual
end module test_multiplier_equations_suite

program test_multiplier_equations
  use test_multiplier_equations_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_multiplier_equations')
end program test_multiplier_equations
