!> Lagrange's equations by finite differences of a kinetic energy T(q, qd, t):
!>   L(q) = d/dt (dT/dqd) - dT/dq
!> along the path q(s) = q0 + qd0 s + qdd0 s^2/2 through t0. The element
!> suites compare their inertial operators with it: an independent
!> reference that knows nothing of how an element assembles M and f.
module lagrange_check
  use kinds, only: dp
  implicit none
  private
  public :: kinetic_energy_fn, fd_lagrange

  abstract interface
    !> kinetic energy of an element at coordinates q, rates qd, time t
    real(dp) function kinetic_energy_fn(q, qd, t)
      import :: dp
      real(dp), intent(in) :: q(:), qd(:), t
    end function kinetic_energy_fn
  end interface

contains

  !> Fourth-order central differences: in time (step 1e-3) of dT/dqd, and in
  !> q (step 1e-4) of T; dT/dqd itself is exact by a central difference of
  !> any step because T is quadratic in the rates.
  function fd_lagrange(energy, q0, qd0, qdd0, t0) result(lag)
    procedure(kinetic_energy_fn) :: energy
    real(dp), intent(in) :: q0(:), qd0(:), qdd0(:), t0
    real(dp) :: lag(size(q0))
    real(dp), parameter :: ht = 1.0e-3_dp, hq = 1.0e-4_dp
    real(dp) :: pq(size(q0), -2:2), e(size(q0)), s
    integer :: i, j
    do i = -2, 2
      s = real(i, dp)*ht
      pq(:, i) = rate_gradient(q0 + qd0*s + 0.5_dp*qdd0*s*s, qd0 + qdd0*s, t0 + s)
    end do
    lag = (pq(:, -2) - 8*pq(:, -1) + 8*pq(:, 1) - pq(:, 2))/(12*ht)
    do j = 1, size(q0)
      e = 0.0_dp
      e(j) = hq
      lag(j) = lag(j) - (energy(q0 - 2*e, qd0, t0) - 8*energy(q0 - e, qd0, t0) &
                         + 8*energy(q0 + e, qd0, t0) - energy(q0 + 2*e, qd0, t0))/(12*hq)
    end do
  contains
    function rate_gradient(q, qd, t) result(g)
      real(dp), intent(in) :: q(:), qd(:), t
      real(dp) :: g(size(q)), d(size(q))
      integer :: k
      do k = 1, size(q)
        d = 0.0_dp
        d(k) = 0.5_dp
        g(k) = (energy(q, qd + d, t) - energy(q, qd - d, t))/(2*d(k))
      end do
    end function rate_gradient
  end function fd_lagrange

end module lagrange_check
