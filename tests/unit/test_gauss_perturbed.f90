!> Round-off robustness of the Gauss family (issue 8 item 1): every
!> optimizer case of test_gauss_optimizer is re-run with relative 1e-14
!> noise on x0 and on the problem data (constraint coefficients, quadratic
!> objective data, residual targets) over many seeds.  The outcome (status,
!> x*) must not depend on the last bits: a decision that flips on a
!> rounding difference shows up here as a failed or different run.
module test_gauss_perturbed_suite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t, create_problem, quadratic_problem_t, test_lsq_t
  use gauss_optimizer
  use assertions
  implicit none
  private
  public :: run_all

  real(dp), parameter :: noise = 1.0e-14_dp
  integer, parameter :: n_seeds = 200, n_cases = 24

  type :: case_t
    character(len=20) :: problem, method
    real(dp) :: x0(4) = 0.0_dp
    integer :: nx0 = 0                 !< 0: the library's start
    real(dp) :: regularization = 0.0_dp
  end type case_t

contains

  subroutine run_all()
    call run_test('optimizer_cases_converge_under_1e-14_noise', test_noise)
  end subroutine run_all

  subroutine get_cases(c)
    type(case_t), intent(out) :: c(n_cases)
    c = [case_t('rosen_suzuki', 'gnlc_ns', [0, 0, 0, 0], 4), case_t('rosen_suzuki', 'gnlc_ns', [1, 1, 1, 1], 4), &
         case_t('rosen_suzuki', 'gnlc_ns', [2, 2, 2, 2], 4), &
         case_t('rosen_suzuki', 'gnlc_ns', [0.0_dp, 0.0_dp, sqrt(5.0_dp), 0.0_dp], 4), &
         case_t('rosen_suzuki', 'gnlc', [0, 0, 0, 0], 4), &
         case_t('rosen_suzuki', 'gnlc', [0.0_dp, 0.0_dp, sqrt(5.0_dp), 0.0_dp], 4), &
         case_t('rosen_suzuki', 'gnlc', [1, 1, 1, 1], 4), &
         case_t('rosenbrock', 'gauss'), case_t('helical_valley', 'gauss'), case_t('bard', 'gauss'), &
         case_t('hs21', 'gauss_constrained'), case_t('hs35', 'gauss_constrained'), case_t('hs21', 'gnlc'), &
         case_t('hs35', 'gnlc'), case_t('hs28', 'gauss_constrained', regularization=1.0e-8_dp), &
         case_t('three_circles', 'gnlc_ns'), case_t('potter_cycling', 'gnlc'), &
         case_t('potter_cycling', 'gnlc_ns'), case_t('general_convex', 'gnlc_general'), &
         case_t('general_convex', 'gnlc_general_ns'), case_t('hs15', 'gnlc_ns'), case_t('hs65', 'gnlc_ns'), &
         ! singular G = 2JJ^T regular on the equality's tangent space: (s, lambda) Newton, no shift
         case_t('hs28', 'gauss_constrained'), case_t('hs28', 'gnlc_ns')]
  end subroutine get_cases

  !> Multiply every entry by (1 + noise u), u uniform in [-1, 1].
  subroutine jiggle(a)
    real(dp), intent(inout) :: a(:)
    real(dp), allocatable :: u(:)
    allocate(u(size(a)))
    call random_number(u)
    a = a*(1.0_dp + noise*(2.0_dp*u - 1.0_dp))
  end subroutine jiggle

  subroutine perturb_problem(prob)
    class(opt_problem_t), intent(inout) :: prob
    real(dp), allocatable :: v(:)
    integer :: i
    do i = 1, prob%m + prob%n_eq
      v = reshape(prob%con_a(:, :, i), [prob%n**2])
      call jiggle(v)
      prob%con_a(:, :, i) = reshape(v, [prob%n, prob%n])
      prob%con_a(:, :, i) = 0.5_dp*(prob%con_a(:, :, i) + transpose(prob%con_a(:, :, i)))
      call jiggle(prob%con_b(:, i))
    end do
    call jiggle(prob%con_d)
    select type (prob)
    type is (quadratic_problem_t)
      v = reshape(prob%q, [prob%n**2])
      call jiggle(v)
      prob%q = reshape(v, [prob%n, prob%n])
      prob%q = 0.5_dp*(prob%q + transpose(prob%q))
      call jiggle(prob%lin)
    type is (test_lsq_t)
      call jiggle(prob%target)
    end select
  end subroutine perturb_problem

  subroutine test_noise()
    type(case_t) :: c(n_cases)
    type(gauss_optimizer_t) :: opt
    class(opt_problem_t), allocatable :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    real(dp), allocatable :: x0(:)
    integer :: i, k, seed, n_seed, bad, worst_nf
    integer, allocatable :: put(:)
    real(dp) :: dx, worst_dx
    call random_seed(size=n_seed)
    allocate(put(n_seed))
    call get_cases(c)
    do k = 1, size(c)
      bad = 0
      worst_dx = 0.0_dp
      worst_nf = 0
      do seed = 1, n_seeds
        do i = 1, n_seed
          put(i) = seed*7919 + 104729*i
        end do
        call random_seed(put=put)
        call err%clear()
        call create_problem(trim(c(k)%problem), prob, info, err)
        x0 = info%x0
        if (c(k)%nx0 > 0) x0 = c(k)%x0(1:c(k)%nx0)
        call jiggle(x0)
        call perturb_problem(prob)
        opt%opts = gauss_options_t()
        opt%opts%method = method_from_name(c(k)%method)
        opt%opts%regularization = c(k)%regularization
        call opt%solve(prob, x0, err)
        dx = huge(1.0_dp)
        if (opt%status == status_converged) dx = maxval(abs(opt%x - info%x_star))
        if (opt%status /= status_converged .or. dx > 1.0e-6_dp) then
          bad = bad + 1
          if (bad <= 3) print '(a)', '   '//trim(c(k)%problem)//'/'//trim(c(k)%method)//' seed '//str(seed)// &
                                    ': '//opt%message//' x = '//str(opt%x(1))//' '//str(opt%x(size(opt%x)))
        else
          worst_dx = max(worst_dx, dx)
        end if
        worst_nf = max(worst_nf, prob%count%analyses)
      end do
      print '(a)', '   '//trim(c(k)%problem)//'/'//trim(c(k)%method)//': '//str(n_seeds - bad)//'/'// &
                   str(n_seeds)//' converged to x*, max |x - x*| = '//str(worst_dx, 3)//', max NF = '//str(worst_nf)
      call assert_equal(bad, 0, trim(c(k)%problem)//'/'//trim(c(k)%method)//': every perturbed run converges to x*')
    end do
  end subroutine test_noise
end module test_gauss_perturbed_suite

program test_gauss_perturbed
  use test_gauss_perturbed_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_gauss_perturbed')
end program test_gauss_perturbed
