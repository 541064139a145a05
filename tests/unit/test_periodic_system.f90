!> Tests of the periodic-system interface (module periodic_system): the
!> period of the crank and the counters of a minimal extension.
module test_periodic_system_suite
  use kinds, only: dp, pi
  use assertions
  use periodic_problems, only: oscillator_t
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('period_is_two_pi_over_omega', test_period)
  end subroutine run_all

  !> T = 2 pi / omega exactly (1e-15 relative): 150 rad/s -> 0.0418879 s;
  !> a linear extension (the unforced oscillator) counts its evaluations.
  subroutine test_period()
    type(oscillator_t) :: sys
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
