!> Tests of DLSODE's banded Newton matrix for second-order systems (module
!> second_order_newton): P^-1 x against a dense LU of the explicitly formed
!> 2N x 2N P = I - hl0 J, J = [[0, I], [-M^-1 K, -beta M^-1 K]] (interleaved),
!> for a symmetric K (Cholesky route) and a non-symmetric one (LU route).
module test_second_order_newton_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: solve_linear
  use second_order_newton, only: second_order_newton_t
  use assertions
  implicit none
  private
  public :: run_all

  integer, parameter :: n = 9, kd = 2

contains

  subroutine run_all()
    call run_test('symmetric_k_cholesky_equals_dense_p', test_symmetric)
    call run_test('nonsymmetric_k_lu_equals_dense_p', test_nonsymmetric)
  end subroutine run_all

  !> Banded M (SPD, diagonally dominant) and K (symmetric or not), dense.
  subroutine matrices(symmetric, m, k)
    logical, intent(in) :: symmetric
    real(dp), intent(out) :: m(n, n), k(n, n)
    integer :: i, j
    m = 0.0_dp
    k = 0.0_dp
    do j = 1, n
      do i = max(1, j - kd), min(n, j + kd)
        m(i, j) = 0.1_dp*cos(real(i + j, dp)) + merge(2.0_dp, 0.0_dp, i == j)
        k(i, j) = 1.0e3_dp*(sin(real(i + 2*j, dp)) + sin(real(j + 2*i, dp)) + merge(5.0_dp, 0.0_dp, i == j))
        if (.not. symmetric) k(i, j) = k(i, j) + 3.0e2_dp*real(i - j, dp)
      end do
    end do
  end subroutine matrices

  !> The banded solve against the dense P; tolerance 1e-10 relative (P's
  !> condition is moderate: hl0^2 |K| / |M| ~ 1e-1).
  subroutine check(symmetric, expect_cholesky)
    logical, intent(in) :: symmetric, expect_cholesky
    type(second_order_newton_t) :: nm
    type(error_t) :: err
    real(dp) :: m(n, n), k(n, n), minv_k(n, n), p(2*n, 2*n), x(2*n), xd(2*n)
    real(dp), parameter :: hl0 = 3.0e-3_dp, beta = 2.0e-2_dp
    integer :: i, j
    logical :: ok
    call matrices(symmetric, m, k)
    call nm%size_for(n, kd)
    nm%mass = 0.0_dp
    nm%stiff = 0.0_dp
    do j = 1, n
      do i = max(1, j - kd), min(n, j + kd)
        nm%stiff(kd + 1 + i - j, j) = k(i, j)
        if (i >= j) nm%mass(1 + i - j, j) = m(i, j)
      end do
    end do
    call nm%factor(hl0, beta, ok)
    call assert_true(ok, 'factored')
    call assert_true(nm%cholesky .eqv. expect_cholesky, 'route (Cholesky for symmetric K)')
    minv_k = k
    do j = 1, n
      call solve_linear(m, minv_k(:, j), err)
    end do
    p = 0.0_dp
    do i = 1, 2*n
      p(i, i) = 1.0_dp
    end do
    do j = 1, n
      p(2*j - 1, 2*j) = -hl0
      do i = 1, n
        p(2*i, 2*j - 1) = hl0*minv_k(i, j)
        p(2*i, 2*j) = p(2*i, 2*j) + hl0*beta*minv_k(i, j)
      end do
    end do
    x = [(sin(real(5*i, dp)), i = 1, 2*n)]
    xd = x
    call solve_linear(p, xd, err)
    call nm%solve(x, err)
    call assert_true(.not. err%failed(), 'solve')
    call assert_all_close(x, xd, 0.0_dp, 1.0e-10_dp*maxval(abs(xd)), 'P^-1 x')
  end subroutine check

  subroutine test_symmetric()
    call check(.true., .true.)
  end subroutine test_symmetric

  subroutine test_nonsymmetric()
    call check(.false., .false.)
  end subroutine test_nonsymmetric
end module test_second_order_newton_suite

program test_second_order_newton
  use assertions, only: finish_suite
  use test_second_order_newton_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_second_order_newton')
end program test_second_order_newton
