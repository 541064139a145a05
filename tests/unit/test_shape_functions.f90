!> Tests of the K26/K27 interpolation (module shape_functions).
module test_shape_functions_suite
  use kinds, only: dp
  use shape_functions, only: quintic_hermite, linear_lagrange
  use assertions
  implicit none
  private
  public :: run_all

  real(dp), parameter :: ell = 2.7_dp     !< not 1, so that missing l-scalings show

contains

  subroutine run_all()
    call run_test('hermite_nodal_values_slopes_curvatures_are_kronecker', test_kronecker)
    call run_test('derivatives_agree_with_finite_differences', test_derivatives_fd)
    call run_test('quintic_polynomials_reproduced_exactly', test_reproduction)
    call run_test('linear_functions_partition_unity', test_linear)
  end subroutine run_all

  !> At e = 0 and 1, (h, h_x, h_xx) of function i equal the unit vector of
  !> its DOF: h1/h4 value, h2/h5 slope, h3/h6 second derivative (section 4).
  subroutine test_kronecker()
    real(dp) :: h(6), hx(6), hxx(6), expect(6, 3)
    integer :: node, i
    character(len=60) :: msg
    do node = 1, 2
      call quintic_hermite(real(node - 1, dp), ell, h, hx, hxx)
      expect = 0.0_dp
      do i = 1, 3
        expect(3*(node - 1) + i, i) = 1.0_dp
      end do
      write(msg, '(a,i0)') 'values at node ', node
      call assert_all_close(h, expect(:, 1), 0.0_dp, 1.0e-14_dp, trim(msg))
      write(msg, '(a,i0)') 'slopes at node ', node
      call assert_all_close(hx, expect(:, 2), 0.0_dp, 1.0e-14_dp, trim(msg))
      write(msg, '(a,i0)') 'second derivatives at node ', node
      call assert_all_close(hxx, expect(:, 3), 0.0_dp, 1.0e-14_dp, trim(msg))
    end do
  end subroutine test_kronecker

  !> Central differences (step 1e-5 in x, error ~ 1e-10 relative to the
  !> O(1..10) derivative values) against the analytic x-derivatives.
  subroutine test_derivatives_fd()
    real(dp), parameter :: dx = 1.0e-5_dp
    real(dp) :: e, hp(6), hm(6), hxp(6), hxm(6), hxxp(6), hxxm(6), h(6), hx(6), hxx(6), hxxx(6)
    integer :: k
    do k = 1, 7
      e = real(k, dp)/8.0_dp
      call quintic_hermite(e, ell, h, hx, hxx, hxxx)
      call quintic_hermite(e + dx/ell, ell, hp, hxp, hxxp)
      call quintic_hermite(e - dx/ell, ell, hm, hxm, hxxm)
      call assert_all_close(hx, (hp - hm)/(2.0_dp*dx), 1.0e-8_dp, 1.0e-9_dp, 'h_x vs FD')
      call assert_all_close(hxx, (hxp - hxm)/(2.0_dp*dx), 1.0e-8_dp, 1.0e-9_dp, 'h_xx vs FD')
      call assert_all_close(hxxx, (hxxp - hxxm)/(2.0_dp*dx), 1.0e-8_dp, 1.0e-9_dp, 'h_xxx vs FD')
    end do
  end subroutine test_derivatives_fd

  !> Any quintic w(x) is reproduced from its nodal values, slopes and second
  !> derivatives (the six functions span the quintics): error at round-off.
  subroutine test_reproduction()
    real(dp), parameter :: c(0:5) = [0.3_dp, -1.1_dp, 0.7_dp, 0.25_dp, -0.4_dp, 0.09_dp]
    real(dp) :: dofs(6), h(6), x, e
    integer :: k
    dofs = [poly(0.0_dp, 0), poly(0.0_dp, 1), poly(0.0_dp, 2), poly(ell, 0), poly(ell, 1), poly(ell, 2)]
    do k = 0, 10
      e = real(k, dp)/10.0_dp
      x = e*ell
      call quintic_hermite(e, ell, h)
      call assert_close(dot_product(h, dofs), poly(x, 0), 1.0e-12_dp, 'quintic reproduced')
    end do
  contains
    real(dp) function poly(x, d)
      real(dp), intent(in) :: x
      integer, intent(in) :: d
      integer :: j
      poly = 0.0_dp
      do j = d, 5
        poly = poly + c(j)*x**(j - d)*real(fact(j)/fact(j - d), dp)
      end do
    end function poly
    integer function fact(n)
      integer, intent(in) :: n
      integer :: j
      fact = 1
      do j = 2, n
        fact = fact*j
      end do
    end function fact
  end subroutine test_reproduction

  !> n1 + n2 = 1, n1 x1 + n2 x2 = x, slopes -1/l and 1/l; and h1 + h4 = 1.
  subroutine test_linear()
    real(dp) :: n(2), nx(2), h(6), e
    integer :: k
    do k = 0, 4
      e = real(k, dp)/4.0_dp
      call linear_lagrange(e, ell, n, nx)
      call quintic_hermite(e, ell, h)
      call assert_close(sum(n), 1.0_dp, 1.0e-15_dp, 'n1 + n2 = 1')
      call assert_close(n(2)*ell, e*ell, 1.0e-14_dp, 'x reproduced')
      call assert_all_close(nx, [-1.0_dp, 1.0_dp]/ell, 0.0_dp, 1.0e-15_dp, 'slopes')
      call assert_close(h(1) + h(4), 1.0_dp, 1.0e-14_dp, 'h1 + h4 = 1')
    end do
  end subroutine test_linear
end module test_shape_functions_suite

program test_shape_functions
  use test_shape_functions_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_shape_functions')
end program test_shape_functions
