!> Tests of the built-in problems (module problem_library): every stored
!> optimum is a KKT point with the stored multipliers and objective value,
!> and every analytic Jacobian agrees with central differences.
module test_problem_library_suite
  use kinds, only: dp
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t, create_problem
  use assertions
  implicit none
  private
  public :: run_all

  character(len=24), parameter :: all_names(17) = [character(len=24) :: 'rosen_suzuki', 'fourbar_path', &
    'fourbar_path_13', 'fourbar_path_offset', 'fourbar_path_13_offset', 'rosenbrock', 'helical_valley', &
    'powell_singular', 'bard', 'hs15', 'hs21', 'hs28', 'hs35', 'hs65', 'general_convex', 'three_circles', &
    'potter_cycling']

contains

  subroutine run_all()
    call run_test('every_problem_is_created_with_a_start', test_create_all)
    call run_test('stored_optima_are_kkt_points', test_kkt)
    call run_test('analytic_jacobians_match_central_differences', test_jacobians)
    call run_test('unknown_problem_is_an_input_error', test_unknown)
  end subroutine run_all

  subroutine test_create_all()
    class(opt_problem_t), allocatable :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    integer :: k
    do k = 1, size(all_names)
      call create_problem(trim(all_names(k)), prob, info, err)
      call assert_true(.not. err%failed(), trim(all_names(k))//' created: '//err%text())
      call assert_equal(size(info%x0), prob%n, trim(all_names(k))//' start has n entries')
      call assert_equal(prob%name, trim(all_names(k)), trim(all_names(k))//' name')
      if (info%has_optimum) call assert_equal(size(info%x_star), prob%n, trim(all_names(k))//' x* has n entries')
    end do
  end subroutine test_create_all

  !> grad F(x*) + Sum lambda_i grad g_i(x*) = 0, g(x*) <= 0, lambda >= 0,
  !> lambda_i g_i = 0 and F(x*) = F*.  Tolerances: 1e-9 relative to the
  !> gradient scale for exact data; the printed (rounded) optima of Bard and
  !> the four-bar's Table 3 design are exact by construction here.
  subroutine test_kkt()
    class(opt_problem_t), allocatable :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    real(dp), allocatable :: phi(:), grad(:), jac(:, :), g(:), dg(:, :), r(:)
    real(dp) :: f, scale
    integer :: k, mt
    do k = 1, size(all_names)
      call create_problem(trim(all_names(k)), prob, info, err)
      if (.not. info%has_optimum) cycle
      mt = prob%n_constraints()
      allocate(phi(prob%n_residuals), grad(prob%n), jac(prob%n, prob%n_residuals), g(mt), dg(prob%n, mt), r(prob%n))
      call prob%analyse(info%x_star, f, phi, err)
      call prob%objective_derivatives(info%x_star, f, phi, grad, jac, err)
      call prob%constraint_values(info%x_star, g, err)
      call prob%constraint_gradients(info%x_star, g, dg, err)
      call assert_true(.not. err%failed(), trim(all_names(k))//': evaluations: '//err%text())
      if (trim(all_names(k)) == 'bard' .or. trim(all_names(k)) == 'hs65') then
        call assert_rel_close(f, info%f_star, 1.0e-6_dp, trim(all_names(k))//' F(x*) = F* (printed digits)')
      else
        call assert_close(f, info%f_star, 1.0e-12_dp*max(1.0_dp, abs(info%f_star)), trim(all_names(k))//' F(x*) = F*')
      end if
      if (mt > 0) call assert_true(all(g(1:prob%m) <= 1.0e-7_dp), trim(all_names(k))//' x* feasible')
      if (allocated(info%lambda_star)) then
        scale = max(1.0_dp, maxval(abs(grad)))
        r = grad + matmul(dg, info%lambda_star)
        call assert_true(maxval(abs(r)) <= 1.0e-9_dp*scale, trim(all_names(k))//' stationarity with lambda*')
        call assert_true(all(info%lambda_star(1:prob%m) >= 0.0_dp), trim(all_names(k))//' lambda* >= 0')
        call assert_true(maxval(abs(info%lambda_star*g)) <= 1.0e-9_dp*scale, &
                         trim(all_names(k))//' complementarity')
      else if (mt == 0 .and. trim(all_names(k)) /= 'bard') then
        call assert_true(maxval(abs(grad)) <= 1.0e-12_dp, trim(all_names(k))//' grad F(x*) = 0')
      end if
      deallocate(phi, grad, jac, g, dg, r)
    end do
  end subroutine test_kkt

  subroutine test_jacobians()
    class(opt_problem_t), allocatable :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    real(dp), allocatable :: x(:), phi(:), jac(:, :), num(:, :), pp(:), pm(:)
    real(dp) :: h
    integer :: k, j
    do k = 1, size(all_names)
      call create_problem(trim(all_names(k)), prob, info, err)
      if (.not. prob%is_least_squares() .or. index(all_names(k), 'fourbar') > 0) cycle
      allocate(phi(prob%n_residuals), pp(prob%n_residuals), pm(prob%n_residuals))
      allocate(jac(prob%n, prob%n_residuals), num(prob%n, prob%n_residuals))
      x = info%x0 + 0.1_dp*[(real(j, dp), j=1, prob%n)]
      call prob%residuals(x, phi, err)
      call prob%jacobian(x, phi, jac, err)
      do j = 1, prob%n
        h = 1.0e-5_dp*max(1.0_dp, abs(x(j)))
        x(j) = x(j) + h
        call prob%residuals(x, pp, err)
        x(j) = x(j) - 2.0_dp*h
        call prob%residuals(x, pm, err)
        x(j) = x(j) + h
        num(j, :) = (pp - pm)/(2.0_dp*h)
      end do
      ! central differences: error ~ h^2 |phi'''| ~ 1e-9 for these functions
      call assert_all_close(reshape(jac, [size(jac)]), reshape(num, [size(num)]), 1.0e-7_dp, 1.0e-7_dp, &
                            trim(all_names(k))//' analytic J')
      call assert_true(.not. err%failed(), trim(all_names(k))//' no error')
      deallocate(phi, pp, pm, jac, num)
    end do
  end subroutine test_jacobians

  subroutine test_unknown()
    class(opt_problem_t), allocatable :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    call create_problem('rosen_suzki', prob, info, err)
    call assert_error(err, 2, 'rosen_suzuki', 'input error listing the valid names')
  end subroutine test_unknown
end module test_problem_library_suite

program test_problem_library
  use test_problem_library_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_problem_library')
end program test_problem_library
