!> Tests of the DLSODE wrapper (module lsode_solver).
module test_lsode_solver_suite
  use kinds, only: dp
  use error_status, only: error_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_adams, mf_bdf_full_user, &
                          mf_bdf_full_fd, mf_bdf_band_fd
  use assertions
  use ode_problems, only: kinetics_t, oscillator_t, failing_t
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('stiff_kinetics_matches_lsode_documentation', test_stiff_kinetics)
    call run_test('stiff_kinetics_fd_jacobian_agrees_with_analytic', test_kinetics_fd_jacobian)
    call run_test('adams_oscillator_matches_closed_form', test_oscillator_adams)
    call run_test('banded_bdf_oscillator_matches_closed_form', test_oscillator_banded)
    call run_test('error_decreases_with_rtol', test_error_decreases_with_rtol)
    call run_test('adams_on_stiff_problem_reports_excess_work', test_excess_work_message)
    call run_test('model_failure_is_reported_with_time', test_model_failure)
    call run_test('bad_settings_are_rejected', test_bad_settings)
  end subroutine run_all

  !> DLSODE's prologue: MF = 21, rtol = 1e-4, atol = (1e-6, 1e-10, 1e-6),
  !> output at t = 0.4 * 10^k.  The documented output (Cray-1, 64-bit
  !> single precision, printed to 7 digits) is reproduced to 2e-6 relative for
  !> t <= 4e5, and the documented work, 330 steps, 405 f-s and 69 J-s, exactly
  !> (the same algorithm in IEEE double takes the same step sequence).
  subroutine test_stiff_kinetics()
    type(kinetics_t) :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    type(lsode_counters_t) :: c
    real(dp) :: y(3), tout
    real(dp), parameter :: y1_doc(7) = [9.851726e-01_dp, 9.055142e-01_dp, 7.158050e-01_dp, &
      4.504846e-01_dp, 1.831701e-01_dp, 3.897016e-02_dp, 4.935213e-03_dp]
    real(dp), parameter :: y2_doc(7) = [3.386406e-05_dp, 2.240418e-05_dp, 9.184616e-06_dp, &
      3.222434e-06_dp, 8.940379e-07_dp, 1.621193e-07_dp, 1.983756e-08_dp]
    real(dp), parameter :: y3_doc(7) = [1.479357e-02_dp, 9.446344e-02_dp, 2.841858e-01_dp, &
      5.495122e-01_dp, 8.168290e-01_dp, 9.610297e-01_dp, 9.950648e-01_dp]
    integer :: k
    y = [1.0_dp, 0.0_dp, 0.0_dp]
    call ode%init(3, 0.0_dp, mf_bdf_full_user, 1.0e-4_dp, [1.0e-6_dp, 1.0e-10_dp, 1.0e-6_dp], err)
    tout = 0.4_dp
    do k = 1, 12
      call ode%integrate_to(sys, y, tout, err)
      call assert_true(.not. err%failed(), 'integration failed: '//err%text())
      if (err%failed()) return
      if (k <= size(y1_doc)) call check_documented(k)
      call assert_close(sum(y), 1.0_dp, 1.0e-6_dp, 'mass conservation y1+y2+y3 = 1')
      tout = tout*10.0_dp
    end do
    call assert_close(y(3), 1.0_dp, 1.0e-6_dp, 'y3 at t = 4e10')
    call check_counters()
  contains
    subroutine check_documented(i)
      integer, intent(in) :: i
      call assert_rel_close(y(1), y1_doc(i), 2.0e-6_dp, 'y1 vs documented value')
      call assert_rel_close(y(2), y2_doc(i), 2.0e-6_dp, 'y2 vs documented value')
      call assert_rel_close(y(3), y3_doc(i), 2.0e-6_dp, 'y3 vs documented value')
    end subroutine check_documented
    subroutine check_counters()
      c = ode%counters()
      call assert_equal(c%steps, 330, 'documented number of steps')
      call assert_equal(c%rhs_evals, 405, 'documented number of f evaluations')
      call assert_equal(c%jac_evals, 69, 'documented number of Jacobian evaluations')
      call assert_equal(c%lu_factorizations, c%jac_evals, 'one LU per Jacobian for MF=21')
    end subroutine check_counters
  end subroutine test_stiff_kinetics

  subroutine test_kinetics_fd_jacobian()
    type(kinetics_t) :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y_user(3), y_fd(3)
    y_user = [1.0_dp, 0.0_dp, 0.0_dp]
    y_fd = y_user
    call ode%init(3, 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, [1.0e-10_dp, 1.0e-14_dp, 1.0e-10_dp], err)
    call ode%integrate_to(sys, y_user, 40.0_dp, err)
    call ode%init(3, 0.0_dp, mf_bdf_full_fd, 1.0e-8_dp, [1.0e-10_dp, 1.0e-14_dp, 1.0e-10_dp], err)
    call ode%integrate_to(sys, y_fd, 40.0_dp, err)
    call assert_true(.not. err%failed(), 'integration failed: '//err%text())
    call assert_all_close(y_fd, y_user, 1.0e-6_dp, 1.0e-12_dp, 'MF=22 vs MF=21 at t = 40')
  end subroutine test_kinetics_fd_jacobian

  subroutine integrate_oscillator(mf, rtol, periods, y, err, ode)
    integer, intent(in) :: mf
    real(dp), intent(in) :: rtol, periods
    real(dp), intent(out) :: y(2)
    type(error_t), intent(inout) :: err
    type(lsode_t), intent(inout) :: ode
    type(oscillator_t) :: sys
    real(dp) :: t_end
    y = [1.0_dp, 0.0_dp]
    t_end = periods*2.0_dp*acos(-1.0_dp)/sys%omega
    call ode%init(2, 0.0_dp, mf, rtol, [rtol*1.0e-3_dp], err, ml=1, mu=1)
    call ode%integrate_to(sys, y, t_end, err)
  end subroutine integrate_oscillator

  subroutine test_oscillator_adams()
    type(lsode_t) :: ode
    type(error_t) :: err
    type(lsode_counters_t) :: c
    real(dp) :: y(2)
    call integrate_oscillator(mf_adams, 1.0e-10_dp, 10.0_dp, y, err, ode)
    call assert_true(.not. err%failed(), 'integration failed: '//err%text())
    ! after 10 periods y = (1, 0)
    call assert_close(y(1), 1.0_dp, 1.0e-7_dp, 'y(10 T) = cos(2 pi 10)')
    call assert_close(y(2), 0.0_dp, 3.0e-7_dp, 'y''(10 T) = 0')
    c = ode%counters()
    call assert_equal(c%lu_factorizations, 0, 'Adams does no factorizations')
  end subroutine test_oscillator_adams

  subroutine test_oscillator_banded()
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(2)
    call integrate_oscillator(mf_bdf_band_fd, 1.0e-9_dp, 2.0_dp, y, err, ode)
    call assert_true(.not. err%failed(), 'integration failed: '//err%text())
    call assert_close(y(1), 1.0_dp, 1.0e-5_dp, 'banded BDF y(2 T)')
  end subroutine test_oscillator_banded

  !> Global error after 5 periods falls as rtol falls (sanity of the tolerance path).
  subroutine test_error_decreases_with_rtol()
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(2), e_loose, e_tight
    call integrate_oscillator(mf_adams, 1.0e-4_dp, 5.0_dp, y, err, ode)
    e_loose = abs(y(1) - 1.0_dp) + abs(y(2))
    call integrate_oscillator(mf_adams, 1.0e-9_dp, 5.0_dp, y, err, ode)
    e_tight = abs(y(1) - 1.0_dp) + abs(y(2))
    call assert_true(e_tight < 1.0e-2_dp*e_loose, 'tightening rtol by 1e5 cuts the error by 100x or more')
  end subroutine test_error_decreases_with_rtol

  subroutine test_excess_work_message()
    type(kinetics_t) :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(3)
    y = [1.0_dp, 0.0_dp, 0.0_dp]
    call ode%init(3, 0.0_dp, mf_adams, 1.0e-6_dp, [1.0e-10_dp], err, max_steps=500)
    call ode%integrate_to(sys, y, 4.0e5_dp, err)
    call assert_true(err%failed(), 'Adams on the stiff kinetics problem must stop')
    call assert_equal(err%code, -1, 'ISTATE = -1')
    call assert_true(index(err%text(), 'stiff') > 0 .and. index(err%text(), 'bdf') > 0, &
                     'message suggests a BDF method: '//err%text())
  end subroutine test_excess_work_message

  subroutine test_model_failure()
    type(failing_t) :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(1)
    y = 1.0_dp
    call ode%init(1, 0.0_dp, mf_adams, 1.0e-6_dp, [1.0e-8_dp], err)
    call ode%integrate_to(sys, y, 1.0_dp, err)
    call assert_true(err%failed(), 'model failure must surface')
    call assert_true(index(err%text(), 'not positive definite') > 0, 'model message kept: '//err%text())
    call assert_true(sys%t_failed > 0.5_dp .and. sys%t_failed < 0.6_dp, 'failure time recorded near 0.5')
  end subroutine test_model_failure

  subroutine test_bad_settings()
    type(lsode_t) :: ode
    type(error_t) :: err
    call ode%init(2, 0.0_dp, 13, 1.0e-6_dp, [1.0e-8_dp], err)
    call assert_true(err%failed() .and. index(err%text(), 'MF') > 0, 'MF = 13 rejected')
    call err%clear()
    call ode%init(2, 0.0_dp, 10, 0.0_dp, [0.0_dp], err)
    call assert_true(err%failed(), 'all-zero tolerances rejected')
    call err%clear()
    call ode%init(2, 0.0_dp, 10, 1.0e-6_dp, [1.0_dp, 2.0_dp, 3.0_dp], err)
    call assert_true(err%failed(), 'atol of wrong length rejected')
  end subroutine test_bad_settings
end module test_lsode_solver_suite

program test_lsode_solver
  use test_lsode_solver_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_lsode_solver')
end program test_lsode_solver
