!> The pieces of lsode_solver that event location uses (clearance joints,
!> doc/clearance.md): one DLSODE step at a time that never passes the output
!> time, dense output inside the last step, and counters that add up over
!> restarts.  The system y' = -y, y(0) = 1, with y = exp(-t) to compare.
module test_lsode_events_suite
  use kinds, only: dp
  use error_status, only: error_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_adams, mf_bdf_full_fd
  use assertions
  use ode_problems, only: decay_t
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('one_step_mode_lands_on_the_output_time', test_one_step)
    call run_test('dense_output_inside_the_last_step_is_the_solution', test_dense_output)
    call run_test('counters_add_up_over_restarts', test_restart_counters)
  end subroutine run_all

  !> Every call advances (one step), never past tout, and the last lands on
  !> it exactly; the state there is exp(-1) to the tolerance (rtol 1e-9:
  !> global error ~1e-8).
  subroutine test_one_step()
    type(decay_t), target :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(1), t_prev
    integer :: calls
    type(lsode_counters_t) :: c
    y = 1.0_dp
    call ode%init(1, 0.0_dp, mf_adams, 1.0e-9_dp, [1.0e-12_dp], err)
    calls = 0
    do while (ode%t < 1.0_dp)
      t_prev = ode%t
      call ode%integrate_to(sys, y, 1.0_dp, err, one_step=.true.)
      call assert_true(.not. err%failed(), err%text())
      if (err%failed()) return
      calls = calls + 1
      call assert_true(ode%t > t_prev .and. ode%t <= 1.0_dp, 'one step forward, not past tout')
    end do
    call assert_close(ode%t, 1.0_dp, 0.0_dp, 'lands on tout')
    call assert_rel_close(y(1), exp(-1.0_dp), 1.0e-7_dp, 'y(1)')
    c = ode%counters()
    call assert_equal(calls, c%steps, 'one step per call')
  end subroutine test_one_step

  !> Inside the last step the interpolant is the solution to the local
  !> tolerance; outside it, an error.
  subroutine test_dense_output()
    type(decay_t), target :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(1), yi(1), t0, t1
    integer :: k
    type(lsode_counters_t) :: c
    y = 1.0_dp
    call ode%init(1, 0.0_dp, mf_bdf_full_fd, 1.0e-9_dp, [1.0e-12_dp], err)
    do k = 1, 30
      call ode%integrate_to(sys, y, 2.0_dp, err, one_step=.true.)
    end do
    c = ode%counters()
    t1 = ode%t
    t0 = t1 - c%step_last
    call ode%dense_output(0.5_dp*(t0 + t1), yi, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_rel_close(yi(1), exp(-0.5_dp*(t0 + t1)), 1.0e-7_dp, 'mid-step value')
    call ode%dense_output(t1, yi, err)
    call assert_close(yi(1), y(1), 1.0e-15_dp, 'the step''s end is the state')
    call ode%dense_output(t0 - 1.0_dp, yi, err)
    call assert_true(err%failed(), 'before the last step: refused')
  end subroutine test_dense_output

  !> Steps and RHS evaluations before a restart are kept in the counters.
  subroutine test_restart_counters()
    type(decay_t), target :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    type(lsode_counters_t) :: c1, c2
    real(dp) :: y(1)
    y = 1.0_dp
    call ode%init(1, 0.0_dp, mf_adams, 1.0e-8_dp, [1.0e-12_dp], err)
    call ode%integrate_to(sys, y, 1.0_dp, err)
    c1 = ode%counters()
    call ode%restart()
    call ode%integrate_to(sys, y, 2.0_dp, err)
    c2 = ode%counters()
    call assert_true(c1%steps > 0 .and. c2%steps > c1%steps, 'steps add up')
    call assert_true(c2%rhs_evals > c1%rhs_evals, 'RHS evaluations add up')
    call assert_rel_close(y(1), exp(-2.0_dp), 1.0e-6_dp, 'the restarted run continues the solution')
  end subroutine test_restart_counters
end module test_lsode_events_suite

program test_lsode_events
  use test_lsode_events_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_lsode_events')
end program test_lsode_events
