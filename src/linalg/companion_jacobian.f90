!> The Jacobian DLSODE asks of a second-order model written in first order,
!> y = (q1, q1_dot, q2, q2_dot, ...) with q'' = -A q - beta A q_dot + ...,
!> A = M^-1 K_t: d(q_i)'/d(q_dot_i) = 1, d(q_dot_i)'/d(q_j) = -A(i, j) and
!> d(q_dot_i)'/d(q_dot_j) = -beta A(i, j).  One fill for every model (the
!> planar and the spatial transient models), in DLSODE's full storage
!> (ml = mu = 0 and 2n rows) or its band storage pd(i - j + mu + 1, j).
module companion_jacobian
  use kinds, only: dp
  implicit none
  private
  public :: fill_companion_jacobian

contains

  subroutine fill_companion_jacobian(a, beta, ml, mu, pd)
    real(dp), intent(in) :: a(:, :)          !< M^-1 K_t, n x n
    real(dp), intent(in) :: beta             !< stiffness-proportional damping (0: none)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    integer :: i, j, n
    logical :: banded
    n = size(a, 1)
    banded = .not. (ml == 0 .and. mu == 0 .and. size(pd, 1) == 2*n)
    do j = 1, n
      call put(2*j - 1, 2*j, 1.0_dp)
      do i = 1, n
        call put(2*i, 2*j - 1, -a(i, j))
        if (beta > 0.0_dp) call put(2*i, 2*j, -beta*a(i, j))
      end do
    end do
  contains
    subroutine put(row, col, value)
      integer, intent(in) :: row, col
      real(dp), intent(in) :: value
      if (banded) then
        if (row - col > ml .or. col - row > mu) return
        pd(row - col + mu + 1, col) = value
      else
        pd(row, col) = value
      end if
    end subroutine put
  end subroutine fill_companion_jacobian
end module companion_jacobian
