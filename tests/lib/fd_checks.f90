!> Finite-difference references for the derivative checks of the suites:
!> the gradient of a scalar function and the Jacobian of a vector function
!> by central differences of order 4 (the default: truncation ~h^4) or 2
!> (~h^2).  The function is usually an internal procedure of the test
!> holding the element or model it differentiates.
module fd_checks
  use kinds, only: dp
  implicit none
  private
  public :: scalar_fn, vector_fn, fd_gradient, fd_jacobian

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

  !> Order 4: (E(x - 2e) - 8 E(x - e) + 8 E(x + e) - E(x + 2e))/(12 h);
  !> order 2: (E(x + e) - E(x - e))/(2 h); e = h e_j.
  function fd_gradient(energy, x, h, order) result(g)
    procedure(scalar_fn) :: energy
    real(dp), intent(in) :: x(:), h
    integer, intent(in), optional :: order
    real(dp) :: g(size(x)), e(size(x))
    integer :: j
    do j = 1, size(x)
      e = 0.0_dp
      e(j) = h
      if (second_order(order)) then
        g(j) = (energy(x + e) - energy(x - e))/(2*h)
      else
        g(j) = (energy(x - 2*e) - 8*energy(x - e) + 8*energy(x + e) - energy(x + 2*e))/(12*h)
      end if
    end do
  end function fd_gradient

  !> Column j by the same differences of f.
  subroutine fd_jacobian(fun, x, h, jac, order)
    procedure(vector_fn) :: fun
    real(dp), intent(in) :: x(:), h
    real(dp), intent(out) :: jac(:, :)
    integer, intent(in), optional :: order
    real(dp) :: e(size(x)), fp(size(jac, 1)), fm(size(jac, 1)), fp2(size(jac, 1)), fm2(size(jac, 1))
    integer :: j
    do j = 1, size(x)
      e = 0.0_dp
      e(j) = h
      call fun(x + e, fp)
      call fun(x - e, fm)
      if (second_order(order)) then
        jac(:, j) = (fp - fm)/(2*h)
      else
        call fun(x + 2*e, fp2)
        call fun(x - 2*e, fm2)
        jac(:, j) = (fm2 - 8*fm + 8*fp - fp2)/(12*h)
      end if
    end do
  end subroutine fd_jacobian

  logical function second_order(order)
    integer, intent(in), optional :: order
    second_order = .false.
    if (present(order)) second_order = order == 2
  end function second_order
end module fd_checks
