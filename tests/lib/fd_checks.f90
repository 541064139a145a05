!> Finite-difference references for the derivative checks of the suites:
!> the gradient of a scalar function and the Jacobian of a vector function
!> by fourth-order central differences (truncation ~h^4).  The function is usually an internal
!> procedure of the test holding the element or model it differentiates.
module fd_checks
  use kinds, only: dp
  implicit none
  private
  public :: scalar_fn, vector_fn, fd_gradient4, fd_jacobian4

  abstract interface
    real(dp) function scalar_fn(x)
      import :: dp
      real(dp), intent(in) :: x(:)
    end function scalar_fn

    subroutine vector_fn(x, f)
      import :: dp
      real(dp), intent(in) :: x(:)
      real(dp), intent(out) :: f(:)
    end subroutine vector_fn
  end interface

contains

  !> (E(x - 2e) - 8 E(x - e) + 8 E(x + e) - E(x + 2e))/(12 h), e = h e_j.
  function fd_gradient4(energy, x, h) result(g)
    procedure(scalar_fn) :: energy
    real(dp), intent(in) :: x(:), h
    real(dp) :: g(size(x)), e(size(x))
    integer :: j
    do j = 1, size(x)
      e = 0.0_dp
      e(j) = h
      g(j) = (energy(x - 2*e) - 8*energy(x - e) + 8*energy(x + e) - energy(x + 2*e))/(12*h)
    end do
  end function fd_gradient4

  !> Column j: (f(x - 2e) - 8 f(x - e) + 8 f(x + e) - f(x + 2e))/(12 h).
  subroutine fd_jacobian4(fun, x, h, jac)
    procedure(vector_fn) :: fun
    real(dp), intent(in) :: x(:), h
    real(dp), intent(out) :: jac(:, :)
    real(dp) :: e(size(x)), fp(size(jac, 1)), fm(size(jac, 1)), fp2(size(jac, 1)), fm2(size(jac, 1))
    integer :: j
    do j = 1, size(x)
      e = 0.0_dp
      e(j) = h
      call fun(x + e, fp)
      call fun(x - e, fm)
      call fun(x + 2*e, fp2)
      call fun(x - 2*e, fm2)
      jac(:, j) = (fm2 - 8*fm + 8*fp - fp2)/(12*h)
    end do
  end subroutine fd_jacobian4
end module fd_checks
