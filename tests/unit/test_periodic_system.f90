!> Tests of the periodic-system interface (module periodic_system): the
!> period of the crank and the counters of a minimal extension.
module test_periodic_system_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use periodic_system, only: periodic_system_t, nonlinear_info_t
  use assertions
  implicit none
  private
  public :: run_all

  type, extends(periodic_system_t) :: constant_t
  contains
    procedure :: set_time => c_set_time
    procedure :: linear_terms => c_linear
    procedure :: nonlinear_terms => c_nonlinear
    procedure :: is_nonlinear => c_is_nonlinear
  end type constant_t

contains

  subroutine run_all()
    call run_test('period_is_two_pi_over_omega', test_period)
  end subroutine run_all

  subroutine c_set_time(self, t, err)
    class(constant_t), intent(inout) :: self
    real(dp), intent(in) :: t
    type(error_t), intent(inout) :: err
    if (.false.) call err%set('', 'unused'//repeat(' ', int(t)))
    self%n_linear_evaluations = self%n_linear_evaluations + 0
  end subroutine c_set_time

  subroutine c_linear(self, mass, damp, stiff, force, velocity_terms)
    class(constant_t), intent(inout) :: self
    real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: velocity_terms
    self%n_linear_evaluations = self%n_linear_evaluations + 1
    mass = 1.0_dp
    damp = merge(1.0_dp, 0.0_dp, velocity_terms)
    stiff = 1.0_dp
    force = 0.0_dp
  end subroutine c_linear

  subroutine c_nonlinear(self, q, fn, info, secant, tangent)
    class(constant_t), intent(inout) :: self
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: fn(:)
    type(nonlinear_info_t), intent(out) :: info
    real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    fn = 0.0_dp*q
    info%n_points = 0
    if (present(secant)) secant = 0.0_dp
    if (present(tangent)) tangent = 0.0_dp
    self%n_nonlinear_evaluations = self%n_nonlinear_evaluations + 1
  end subroutine c_nonlinear

  logical function c_is_nonlinear(self)
    class(constant_t), intent(in) :: self
    c_is_nonlinear = self%n < 0
  end function c_is_nonlinear

  !> T = 2 pi / omega exactly (1e-15 relative): 150 rad/s -> 0.0418879 s.
  subroutine test_period()
    type(constant_t) :: sys
    real(dp) :: m(1, 1), c(1, 1), k(1, 1), f(1)
    sys%n = 1
    sys%omega = 150.0_dp
    call assert_rel_close(sys%period(), 2.0_dp*pi/150.0_dp, 1.0e-15_dp, 'period')
    call sys%linear_terms(m, c, k, f, .false.)
    call assert_equal(sys%n_linear_evaluations, 1, 'counter')
    call assert_true(.not. sys%is_nonlinear(), 'linear')
  end subroutine test_period
end module test_periodic_system_suite

program test_periodic_system
  use assertions, only: finish_suite
  use test_periodic_system_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_periodic_system')
end program test_periodic_system
