!> Gauss-Legendre quadrature.  An n-point rule integrates polynomials of
!> degree <= 2n-1 exactly; the element routines choose n from the degree of
!> their integrands (doc/element.md, "Quadrature").
module quadrature
  use kinds, only: dp, pi
  implicit none
  private
  public :: gauss_legendre, gauss_legendre_interval, max_gauss_points

  integer, parameter :: max_gauss_points = 64   !< Newton on P_n stays accurate well past this

contains

  !> Nodes x(1:n) (ascending) and weights w(1:n) on [-1, 1].
  !> Newton's method on the Legendre polynomial P_n from the Tricomi
  !> estimate; converges to round-off in a few steps for every n used here.
  pure subroutine gauss_legendre(n, x, w)
    integer, intent(in) :: n
    real(dp), intent(out) :: x(n), w(n)
    integer :: i, iter
    real(dp) :: z, pn, dpn, dz
    do i = 1, (n + 1)/2
      z = cos(pi*(real(i, dp) - 0.25_dp)/(real(n, dp) + 0.5_dp))
      do iter = 1, 100
        call legendre(n, z, pn, dpn)
        dz = pn/dpn
        z = z - dz
        if (abs(dz) <= 4.0_dp*epsilon(1.0_dp)) exit
      end do
      call legendre(n, z, pn, dpn)
      x(i) = -z
      x(n + 1 - i) = z
      w(i) = 2.0_dp/((1.0_dp - z*z)*dpn*dpn)
      w(n + 1 - i) = w(i)
    end do
    if (mod(n, 2) == 1) x((n + 1)/2) = 0.0_dp
  end subroutine gauss_legendre

  !> P_n(z) and P_n'(z) by the three-term recurrence (|z| < 1).
  pure subroutine legendre(n, z, pn, dpn)
    integer, intent(in) :: n
    real(dp), intent(in) :: z
    real(dp), intent(out) :: pn, dpn
    real(dp) :: p0, p1
    integer :: k
    p0 = 1.0_dp       ! P_{k-1}
    pn = z            ! P_k
    if (n == 0) pn = 1.0_dp
    do k = 2, n
      p1 = pn
      pn = (real(2*k - 1, dp)*z*p1 - real(k - 1, dp)*p0)/real(k, dp)
      p0 = p1
    end do
    ! here p0 = P_{n-1}
    if (n == 0) then
      dpn = 0.0_dp
    else
      dpn = real(n, dp)*(p0 - z*pn)/(1.0_dp - z*z)
    end if
  end subroutine legendre

  !> The n-point rule mapped to [a, b]: sum(w*f(x)) ~ integral_a^b f.
  pure subroutine gauss_legendre_interval(n, a, b, x, w)
    integer, intent(in) :: n
    real(dp), intent(in) :: a, b
    real(dp), intent(out) :: x(n), w(n)
    call gauss_legendre(n, x, w)
    x = 0.5_dp*(a + b) + 0.5_dp*(b - a)*x
    w = 0.5_dp*(b - a)*w
  end subroutine gauss_legendre_interval
end module quadrature
