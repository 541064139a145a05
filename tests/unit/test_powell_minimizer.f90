!> Tests of Powell's conjugate-direction method (module powell_minimizer).
module test_powell_minimizer_suite
  use kinds, only: dp
  use powell_minimizer, only: powell_function_t, powell_options_t, powell_result_t, powell_minimize
  use assertions
  implicit none
  private
  public :: run_all

  !> f = 1/2 (x - c)^T Q (x - c) + f0, Q rotated and ill-conditioned (1 : 1e4).
  type, extends(powell_function_t) :: quadratic_t
    real(dp) :: q(3, 3) = 0.0_dp, c(3) = 0.0_dp, f0 = 0.0_dp
  contains
    procedure :: value => quadratic_value
  end type quadratic_t

  !> Rosenbrock's banana function.
  type, extends(powell_function_t) :: banana_t
    integer :: calls = 0
  contains
    procedure :: value => banana_value
  end type banana_t

  !> |x|^2 + 1 where x1 > -0.5; elsewhere "undefined" (large value, as GNLC's
  !> H returns where G + Sum lambda A is singular).  Minimum at x = 0.
  type, extends(powell_function_t) :: walled_t
    real(dp) :: wall = -0.5_dp
  contains
    procedure :: value => walled_value
  end type walled_t

contains

  subroutine run_all()
    call run_test('rotated_ill_conditioned_quadratic_minimum_found', test_quadratic)
    call run_test('rosenbrock_banana_minimum_found', test_banana)
    call run_test('f_target_stops_early', test_target)
    call run_test('undefined_region_is_avoided', test_walled)
  end subroutine run_all

  function quadratic_value(self, x) result(f)
    class(quadratic_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: f
    real(dp) :: d(size(x))
    d = x - self%c
    f = 0.5_dp*dot_product(d, matmul(self%q, d)) + self%f0
  end function quadratic_value

  function banana_value(self, x) result(f)
    class(banana_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: f
    self%calls = self%calls + 1
    f = 100.0_dp*(x(2) - x(1)**2)**2 + (1.0_dp - x(1))**2
  end function banana_value

  function walled_value(self, x) result(f)
    class(walled_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: f
    if (x(1) <= self%wall) then
      f = 1.0e30_dp
    else
      f = sum(x**2) + 1.0_dp
    end if
  end function walled_value

  subroutine test_quadratic()
    type(quadratic_t) :: fun
    type(powell_options_t) :: opts
    type(powell_result_t) :: res
    real(dp) :: r(3, 3), x(3), c, s
    ! rotation about z then x by 30 degrees; eigenvalues 1, 100, 1e4
    c = cos(0.5235987755982988_dp)
    s = sin(0.5235987755982988_dp)
    r = matmul(reshape([c, s, 0.0_dp, -s, c, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3]), &
               reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, c, s, 0.0_dp, -s, c], [3, 3]))
    fun%q = matmul(r, matmul(reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0e2_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
                                      1.0e4_dp], [3, 3]), transpose(r)))
    fun%c = [1.0_dp, -2.0_dp, 3.0_dp]
    fun%f0 = 5.0_dp
    x = 0.0_dp
    call powell_minimize(fun, x, opts, res)
    ! Powell's method is exact on quadratics up to the line-search tolerance
    ! (1e-10 relative in the step): x to 1e-6 despite the 1e4 condition number
    call assert_true(res%converged, 'converged on ftol')
    call assert_all_close(x, fun%c, 0.0_dp, 1.0e-6_dp, 'x = c')
    call assert_close(res%f, 5.0_dp, 1.0e-10_dp, 'f = f0')
  end subroutine test_quadratic

  subroutine test_banana()
    type(banana_t) :: fun
    type(powell_options_t) :: opts
    type(powell_result_t) :: res
    real(dp) :: x(2)
    x = [-1.2_dp, 1.0_dp]
    call powell_minimize(fun, x, opts, res)
    ! the curved valley slows Powell's method but does not stop it
    call assert_all_close(x, [1.0_dp, 1.0_dp], 0.0_dp, 1.0e-5_dp, 'x = (1, 1)')
    call assert_true(res%f < 1.0e-10_dp, 'f < 1e-10')
    call assert_equal(res%evaluations, fun%calls, 'evaluations counted')
  end subroutine test_banana

  subroutine test_target()
    type(banana_t) :: fun
    type(powell_options_t) :: opts
    type(powell_result_t) :: res, full
    real(dp) :: x(2)
    x = [-1.2_dp, 1.0_dp]
    call powell_minimize(fun, x, opts, full)
    x = [-1.2_dp, 1.0_dp]
    opts%f_target = 1.0_dp
    call powell_minimize(fun, x, opts, res)
    call assert_true(res%converged .and. res%f <= 1.0_dp, 'stopped with f <= f_target')
    call assert_true(res%f > 1.0e-6_dp, 'stopped before the minimum')
    call assert_true(res%evaluations < full%evaluations, 'fewer evaluations than the full minimisation')
  end subroutine test_target

  subroutine test_walled()
    type(walled_t) :: fun
    type(powell_options_t) :: opts
    type(powell_result_t) :: res
    real(dp) :: x(2)
    x = [2.0_dp, -3.0_dp]
    opts%initial_step = 10.0_dp        ! the first trial steps land in the wall
    call powell_minimize(fun, x, opts, res)
    call assert_all_close(x, [0.0_dp, 0.0_dp], 0.0_dp, 1.0e-6_dp, 'minimum at 0 found across the wall')
    call assert_close(res%f, 1.0_dp, 1.0e-10_dp, 'f = 1')
  end subroutine test_walled
end module test_powell_minimizer_suite

program test_powell_minimizer
  use test_powell_minimizer_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_powell_minimizer')
end program test_powell_minimizer
