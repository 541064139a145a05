!> Tests of the banded generalized eigensolver (linalg's band_generalized_eig)
!> against the dense one (sym_generalized_eig) on a small structure: a
!> clamped-free chain of masses and springs with consistent (banded) mass and
!> second-neighbour springs, half-bandwidth 2, and the same chain twice
!> uncoupled (every eigenvalue double: a cluster); and the chain with stiff
!> grounded springs that spread the spectrum over more than 1e8, as the curvature DOFs
!> of a beam model do (the low modes' shapes must not depend on the highest
!> eigenvalue).
!> Tolerances: both solvers are backward stable, so each eigenvalue is within
!> a few n eps ||K|| ||M^-1|| of the exact one; for these matrices (stiffness
!> ratio below 1e3) that is below 1e-12 of the largest eigenvalue, and 1e-10
!> leaves room for any optimization level.  An eigenvector of a simple
!> eigenvalue is within eps ||K|| / gap of the exact one (smallest relative gap
!> here 1e-2): 1e-8 on |phi_band^T M phi_dense| = 1 and on the residuals.
module test_band_eigen_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: sym_generalized_eig, band_generalized_eig
  use assertions
  implicit none
  private
  public :: run_all

  integer, parameter :: kd = 2

contains

  subroutine run_all()
    call run_test('eigenvalues_equal_dense', test_values)
    call run_test('vectors_equal_dense', test_vectors)
    call run_test('double_eigenvalues_orthonormal', test_cluster)
    call run_test('low_modes_of_a_wide_spectrum', test_wide_spectrum)
  end subroutine run_all

  !> The chain of n masses (K, M dense, half-bandwidth kd); `copies` uncoupled copies.
  subroutine chain(n, copies, k, m)
    integer, intent(in) :: n, copies
    real(dp), intent(out) :: k(n*copies, n*copies), m(n*copies, n*copies)
    integer :: c, i, o
    k = 0.0_dp
    m = 0.0_dp
    do c = 1, copies
      o = (c - 1)*n
      do i = 1, n
        m(o + i, o + i) = 4.0_dp + 0.5_dp*sin(real(i, dp))
        k(o + i, o + i) = 2.0_dp*(1.0_dp + 0.1_dp*i) + 0.5_dp
        if (i < n) then
          m(o + i, o + i + 1) = 1.0_dp
          k(o + i, o + i + 1) = -(1.0_dp + 0.1_dp*i)
        end if
        if (i < n - 1) k(o + i, o + i + 2) = -0.2_dp
      end do
      k(o + n, o + n) = 1.0_dp + 0.1_dp*n     ! free end
    end do
    k = k + transpose(k) - diag(k)
    m = m + transpose(m) - diag(m)
  end subroutine chain

  pure function diag(a) result(d)
    real(dp), intent(in) :: a(:, :)
    real(dp) :: d(size(a, 1), size(a, 2))
    integer :: i
    d = 0.0_dp
    do i = 1, size(a, 1)
      d(i, i) = a(i, i)
    end do
  end function diag

  subroutine test_values()
    integer, parameter :: n = 14
    real(dp) :: k(n, n), m(n, n), w_dense(n), w_band(n)
    type(error_t) :: err
    call chain(n, 1, k, m)
    call sym_generalized_eig(k, m, w_dense, err)
    call band_generalized_eig(k, m, kd, w_band, err)
    call assert_true(.not. err%failed(), 'solved')
    call assert_all_close(w_band, w_dense, 0.0_dp, 1.0e-10_dp*w_dense(n), 'eigenvalues')
  end subroutine test_values

  subroutine test_vectors()
    integer, parameter :: n = 14
    real(dp) :: k(n, n), m(n, n), w_dense(n), w_band(n), x_dense(n, n), x_band(n, n)
    type(error_t) :: err
    integer :: j
    call chain(n, 1, k, m)
    call sym_generalized_eig(k, m, w_dense, err, x_dense)
    call band_generalized_eig(k, m, kd, w_band, err, x_band)
    call assert_true(.not. err%failed(), 'solved')
    do j = 1, n
      call assert_close(abs(dot_product(x_band(:, j), matmul(m, x_dense(:, j)))), 1.0_dp, 1.0e-8_dp, &
                        'mode equals the dense one up to sign')
      call assert_all_close(matmul(k, x_band(:, j)), w_band(j)*matmul(m, x_band(:, j)), 0.0_dp, &
                            1.0e-8_dp*w_band(n), 'K x = w M x')
    end do
  end subroutine test_vectors

  subroutine test_cluster()
    integer, parameter :: n = 7
    real(dp) :: k(2*n, 2*n), m(2*n, 2*n), w(2*n), x(2*n, 2*n), gram(2*n, 2*n)
    type(error_t) :: err
    integer :: j
    call chain(n, 2, k, m)
    call band_generalized_eig(k, m, kd, w, err, x)
    call assert_true(.not. err%failed(), 'solved')
    call assert_close(w(2), w(1), 1.0e-10_dp, 'first eigenvalue double')
    gram = matmul(transpose(x), matmul(m, x))
    do j = 1, 2*n
      gram(j, j) = gram(j, j) - 1.0_dp
      call assert_all_close(matmul(k, x(:, j)), w(j)*matmul(m, x(:, j)), 0.0_dp, 1.0e-8_dp*w(2*n), 'K x = w M x')
    end do
    call assert_true(maxval(abs(gram)) < 1.0e-8_dp, 'M-orthonormal inside the double eigenvalues')
  end subroutine test_cluster

  !> Springs of 1e8 to ground at the last three masses: eigenvalues from
  !> about 6e-2 to 4e7.  The lowest six modes equal the dense solver's (the
  !> inverse iteration's shift is taken on each eigenvalue's own scale: on
  !> the largest one's it lands below the mode underneath and the shape is
  !> a mixture, |x_band^T M x_dense| far from 1).  Their relative gaps are
  !> above 0.1, so 1e-7 holds both solvers' round-off (eps 1e8 / gap).
  subroutine test_wide_spectrum()
    integer, parameter :: n = 14
    real(dp) :: k(n, n), m(n, n), w_dense(n), w_band(n), x_dense(n, n), x_band(n, n)
    type(error_t) :: err
    integer :: j
    call chain(n, 1, k, m)
    do j = n - 2, n
      k(j, j) = k(j, j) + 1.0e8_dp
    end do
    call sym_generalized_eig(k, m, w_dense, err, x_dense)
    call band_generalized_eig(k, m, kd, w_band, err, x_band)
    call assert_true(.not. err%failed(), 'solved')
    call assert_true(w_band(n) > 1.0e8_dp*w_band(1), 'spectrum spread over more than 1e8')
    do j = 1, 6
      call assert_close(abs(dot_product(x_band(:, j), matmul(m, x_dense(:, j)))), 1.0_dp, 1.0e-7_dp, &
                        'low mode equals the dense one up to sign')
    end do
  end subroutine test_wide_spectrum
end module test_band_eigen_suite

program test_band_eigen
  use assertions, only: finish_suite
  use test_band_eigen_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_band_eigen')
end program test_band_eigen
