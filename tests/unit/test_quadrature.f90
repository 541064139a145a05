!> Tests of the Gauss-Legendre rules (module quadrature).
module test_quadrature_suite
  use kinds, only: dp
  use quadrature, only: gauss_legendre, gauss_legendre_interval
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('low_order_rules_match_tabulated_nodes_and_weights', test_tabulated)
    call run_test('n_point_rule_exact_to_degree_2n_minus_1_and_not_2n', test_degree)
    call run_test('interval_rule_integrates_smooth_function', test_interval)
  end subroutine run_all

  !> n = 1, 2, 3 in closed form (Abramowitz & Stegun 25.4.29).
  subroutine test_tabulated()
    real(dp) :: x1(1), w1(1), x2(2), w2(2), x3(3), w3(3)
    call gauss_legendre(1, x1, w1)
    call assert_close(x1(1), 0.0_dp, 1.0e-15_dp, 'n=1 node')
    call assert_close(w1(1), 2.0_dp, 1.0e-15_dp, 'n=1 weight')
    call gauss_legendre(2, x2, w2)
    call assert_all_close(x2, [-1.0_dp, 1.0_dp]/sqrt(3.0_dp), 0.0_dp, 1.0e-15_dp, 'n=2 nodes')
    call assert_all_close(w2, [1.0_dp, 1.0_dp], 0.0_dp, 1.0e-15_dp, 'n=2 weights')
    call gauss_legendre(3, x3, w3)
    call assert_all_close(x3, [-sqrt(0.6_dp), 0.0_dp, sqrt(0.6_dp)], 0.0_dp, 1.0e-15_dp, 'n=3 nodes')
    call assert_all_close(w3, [5.0_dp, 8.0_dp, 5.0_dp]/9.0_dp, 0.0_dp, 1.0e-15_dp, 'n=3 weights')
  end subroutine test_tabulated

  !> integral_{-1}^{1} x^k = 2/(k+1) (k even): exact up to k = 2n-1 (round-off
  !> tolerance 1e-14), and x^(2n) is missed by exactly the Gauss error term
  !> E = 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2)  (A&S 25.4.30 with f^(2n) = (2n)!);
  !> E >= 1e-8 for n <= 12, so 1e-5 relative leaves room for round-off.
  subroutine test_degree()
    integer :: n, k
    real(dp), allocatable :: x(:), w(:)
    real(dp) :: exact
    character(len=80) :: msg
    do n = 1, 12
      allocate(x(n), w(n))
      call gauss_legendre(n, x, w)
      do k = 0, 2*n - 1
        exact = merge(2.0_dp/real(k + 1, dp), 0.0_dp, mod(k, 2) == 0)
        write(msg, '(a,i0,a,i0)') 'n = ', n, ', x^', k
        call assert_close(sum(w*x**k), exact, 1.0e-14_dp, trim(msg))
      end do
      write(msg, '(a,i0,a)') 'n = ', n, ' misses x^(2n) by the Gauss error term'
      call assert_rel_close(2.0_dp/real(2*n + 1, dp) - sum(w*x**(2*n)), &
                            2.0_dp**(2*n + 1)*gamma(real(n + 1, dp))**4 &
                            /(real(2*n + 1, dp)*gamma(real(2*n + 1, dp))**2), 1.0e-5_dp, trim(msg))
      deallocate(x, w)
    end do
  end subroutine test_degree

  !> integral_0^2.5 exp(x) = e^2.5 - 1 with 12 points: error below 1e-13
  !> relative (Gauss error ~ 2.5^25/24! ~ 1e-14 here).
  subroutine test_interval()
    real(dp) :: x(12), w(12)
    call gauss_legendre_interval(12, 0.0_dp, 2.5_dp, x, w)
    call assert_rel_close(sum(w*exp(x)), exp(2.5_dp) - 1.0_dp, 1.0e-13_dp, 'exp on [0, 2.5]')
    call assert_true(all(x > 0.0_dp .and. x < 2.5_dp), 'nodes inside the interval')
  end subroutine test_interval
end module test_quadrature_suite

program test_quadrature
  use test_quadrature_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_quadrature')
end program test_quadrature
