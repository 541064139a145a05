!> Small periodic systems (periodic_system_t) shared by the steady-state
!> suites (test_periodic_shooting, test_periodic_system): a one-DOF forced
!> oscillator with a closed-form steady state that counts its evaluations.
module periodic_problems
  use kinds, only: dp
  use error_status, only: error_t
  use periodic_system, only: periodic_system_t, nonlinear_info_t
  implicit none
  private
  public :: oscillator_t

  !> m x'' + c x' + k (1 + eps cos(w t)) x + gamma x^3 = f1 cos(w t) + f2 sin(2 w t)
  type, extends(periodic_system_t) :: oscillator_t
    real(dp) :: m = 1.0_dp, c = 0.0_dp, k = 1.0_dp, eps = 0.0_dp, gamma = 0.0_dp
    real(dp) :: f1 = 0.0_dp, f2 = 0.0_dp, t = 0.0_dp
  contains
    procedure :: set_time => osc_set_time
    procedure :: linear_terms => osc_linear
    procedure :: nonlinear_terms => osc_nonlinear
    procedure :: is_nonlinear => osc_is_nonlinear
  end type oscillator_t

contains

  subroutine osc_set_time(self, t, err)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t), intent(inout) :: err
    self%t = t
    if (.false.) call err%clear()
  end subroutine osc_set_time

  subroutine osc_linear(self, mass, damp, stiff, force, velocity_terms)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: velocity_terms
    self%n_linear_evaluations = self%n_linear_evaluations + 1
    mass(1, 1) = self%m
    damp(1, 1) = merge(self%c, 0.0_dp, velocity_terms)
    stiff(1, 1) = self%k*(1.0_dp + self%eps*cos(self%omega*self%t))
    force(1) = self%f1*cos(self%omega*self%t) + self%f2*sin(2.0_dp*self%omega*self%t)
  end subroutine osc_linear

  subroutine osc_nonlinear(self, q, fn, info, secant, tangent)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: fn(:)
    type(nonlinear_info_t), intent(out) :: info
    real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    self%n_nonlinear_evaluations = self%n_nonlinear_evaluations + 1
    fn(1) = self%gamma*q(1)**3
    if (present(secant)) secant(1, 1) = self%gamma*q(1)**2
    if (present(tangent)) tangent(1, 1) = 3.0_dp*self%gamma*q(1)**2
    info%n_points = 0
  end subroutine osc_nonlinear

  logical function osc_is_nonlinear(self)
    class(oscillator_t), intent(in) :: self
    osc_is_nonlinear = abs(self%gamma) > 0.0_dp
  end function osc_is_nonlinear
end module periodic_problems
