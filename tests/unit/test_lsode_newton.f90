!> Tests of DLSODE's Newton matrix (module lsode_newton, and the mechanism
!> model's banded elimination behind it): the banded solve equals an
!> independent dense solve of the 2N x 2N P = I - hl0 J; integrations through
!> the model's Newton matrix equal those through DLSODE-style dense P; bdf_band
!> (MF 24) is now the same iteration as bdf (MF 21), no truncated band; the
!> Newton matrix's age limit follows the measured contraction of the chord
!> iteration (a stiff system turning at a chosen rate, in closed form).
module test_lsode_newton_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: solve_linear
  use linkage, only: mechanism_t, build_mechanism
  use element_effects, only: element_effects_t
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_bdf_full_user, mf_bdf_band_user, ode_system_t
  use transient_fixtures, only: fourbar_input, make_model, all_effects, state_atol
  use assertions
  use ode_problems, only: decay_t => newton_decay_t
  use test_text, only: itoa, rtoa
  implicit none
  private
  public :: run_all

  !> y' = A(t) y with A = R(wt)^T diag(-a, -b) R(wt), R the rotation by wt
  !> (R = [[c, s], [-s, c]]): a stiff direction (a) and a slow one (b) that
  !> turn at the rate w, as a link's stiff axial and soft bending directions
  !> do.  In the turning frame z = R y the system is constant,
  !> z' = B z with B = [[-a, w], [-w, -b]], so y(t) = R(wt)^T exp(B t) y(0).
  !> Its Newton matrix P = I - hl0 A(t_f) is exact when formed and turns out
  !> of date at a rate proportional to w; it asks for at most 10 steps per
  !> matrix (jacobian_steps) and a contraction bound `theta`
  !> (jacobian_contraction; 0: the fixed limit alone).
  type, extends(ode_system_t) :: turning_t
    real(dp) :: w = 0.0_dp, a = 1.0e4_dp, b = 1.0_dp
    real(dp) :: p_inv(2, 2) = 0.0_dp
    integer :: n_factor = 0
  contains
    procedure :: rhs => turning_rhs
    procedure :: has_newton_matrix => turning_has_newton
    procedure :: newton_factor => turning_factor
    procedure :: newton_solve => turning_solve
  end type turning_t

contains

  pure function turning_matrix(self, t) result(m)
    class(turning_t), intent(in) :: self
    real(dp), intent(in) :: t
    real(dp) :: m(2, 2), r(2, 2)
    r = reshape([cos(self%w*t), -sin(self%w*t), sin(self%w*t), cos(self%w*t)], [2, 2])
    m = matmul(transpose(r), matmul(reshape([-self%a, 0.0_dp, 0.0_dp, -self%b], [2, 2]), r))
  end function turning_matrix

  subroutine turning_rhs(self, t, y, ydot)
    class(turning_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    real(dp) :: m(2, 2)
    m = turning_matrix(self, t)
    ydot(1) = m(1, 1)*y(1) + m(1, 2)*y(2)
    ydot(2) = m(2, 1)*y(1) + m(2, 2)*y(2)
  end subroutine turning_rhs

  logical function turning_has_newton(self)
    class(turning_t), intent(in) :: self
    turning_has_newton = .not. self%err%failed()
  end function turning_has_newton

  subroutine turning_factor(self, t, y, hl0, ok)
    class(turning_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:), hl0
    logical, intent(out) :: ok
    real(dp) :: p(2, 2), det
    p = -hl0*turning_matrix(self, t)
    p(1, 1) = p(1, 1) + 1.0_dp
    p(2, 2) = p(2, 2) + 1.0_dp
    det = p(1, 1)*p(2, 2) - p(1, 2)*p(2, 1)
    self%p_inv = reshape([p(2, 2), -p(2, 1), -p(1, 2), p(1, 1)], [2, 2])/det
    self%n_factor = self%n_factor + 1
    ok = size(y) == 2
  end subroutine turning_factor

  subroutine turning_solve(self, x)
    class(turning_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    real(dp) :: x1
    x1 = x(1)
    x(1) = self%p_inv(1, 1)*x1 + self%p_inv(1, 2)*x(2)
    x(2) = self%p_inv(2, 1)*x1 + self%p_inv(2, 2)*x(2)
  end subroutine turning_solve

  subroutine run_all()
    call run_test('banded_newton_solve_equals_dense_solve_linear_model', test_solve_linear_model)
    call run_test('banded_newton_solve_equals_dense_solve_all_effects', test_solve_all_effects)
    call run_test('banded_newton_solve_equals_dense_solve_kear1987_lu', test_solve_kear1987)
    call run_test('integration_through_model_newton_matrix_equals_dense', test_integration_routes)
    call run_test('bdf_band_is_the_bdf_iteration', test_bdf_band_equals_bdf)
    call run_test('model_newton_matrix_route_matches_closed_form', test_decay_closed_form)
    call run_test('model_failure_ends_a_run_through_its_newton_matrix', test_decay_failure)
    call run_test('optional_inputs_survive_the_switch_to_the_model_route', test_max_order_kept)
    call run_test('newton_matrix_age_follows_its_contraction', test_age_follows_contraction)
  end subroutine run_all

  !> A four-bar model (2 elements per link, 150 rad/s, beta = 1e-5 s).
  subroutine fourbar_model(effects, formulation, model, ok)
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: formulation
    type(mechanism_model_t), intent(out) :: model
    logical, intent(out) :: ok
    type(mechanism_t) :: mech
    type(error_t) :: err
    call build_mechanism(fourbar_input(2, 150.0_dp, 0.0_dp), mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, effects, formulation, 1.0e-5_dp, err)
    call assert_true(.not. err%failed(), 'model: '//err%text())
    ok = .not. err%failed()
  end subroutine fourbar_model

  !> A deformed state (displacements ~1e-3 in, slopes, curvatures; rates ~0.1 in/s).
  subroutine deformed_state(n2, y)
    integer, intent(in) :: n2
    real(dp), intent(out) :: y(n2)
    integer :: k
    do k = 1, n2/2
      y(2*k - 1) = 1.0e-3_dp*sin(1.7_dp*k)
      y(2*k) = 0.1_dp*cos(0.3_dp*k)
    end do
  end subroutine deformed_state

  !> x_band from the model's banded Newton matrix against x_dense from the
  !> dense P = I - hl0 J (J from model%jacobian in full storage: dense M^-1 K_t
  !> by LU) solved by LU, for hl0 from a small to a large BDF step.  The two
  !> share only the element matrices.  Tolerance: P's 1-norm condition number
  !> reaches ~1e7 at hl0 = 1e-3 s (hl0^2 omega_max^2); both solves are
  !> backward stable, so they agree to ~cond * eps = 1e-9 of |x|: 1e-8 allows
  !> a factor 10.  A wrong term (beta, a sign, hl0 for hl0^2) changes x by
  !> 1e-3 or more.  Also the residual |P x_band - b| <= 1e-12 |P| |x_band|.
  subroutine check_solve(effects, formulation, expect_cholesky)
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: formulation
    logical, intent(in) :: expect_cholesky
    type(mechanism_model_t) :: model
    real(dp), allocatable :: y(:), pd(:, :), p(:, :), b(:), x_dense(:), x_band(:)
    real(dp), parameter :: hl0s(3) = [1.0e-6_dp, 3.0e-5_dp, 1.0e-3_dp], t = 2.0e-3_dp
    type(error_t) :: err
    logical :: ok
    integer :: n2, k, i
    call fourbar_model(effects, formulation, model, ok)
    if (.not. ok) return
    n2 = model%state_size()
    allocate(y(n2), pd(n2, n2), p(n2, n2), b(n2), x_dense(n2), x_band(n2))
    call deformed_state(n2, y)
    do i = 1, n2
      b(i) = cos(0.7_dp*i) + 0.1_dp
    end do
    do k = 1, size(hl0s)
      pd = 0.0_dp
      call model%jacobian(t, y, 0, 0, pd)
      p = -hl0s(k)*pd
      do i = 1, n2
        p(i, i) = p(i, i) + 1.0_dp
      end do
      x_dense = b
      call solve_linear(p, x_dense, err)
      call assert_true(.not. err%failed(), 'dense solve: '//err%text())
      call model%newton_factor(t, y, hl0s(k), ok)
      call assert_true(ok, 'banded Newton matrix factored')
      x_band = b
      call model%newton_solve(x_band)
      call assert_true(.not. model%err%failed(), 'model: '//model%err%text())
      call assert_all_close(x_band, x_dense, 0.0_dp, 1.0e-8_dp*maxval(abs(x_dense)), &
                            'banded = dense solve at hl0 = '//trim(rtoa(hl0s(k))))
      call assert_true(maxval(abs(matmul(p, x_band) - b)) <= 1.0e-12_dp*maxval(sum(abs(p), dim=2))* &
                       maxval(abs(x_band)), 'residual of the banded solve at hl0 = '//trim(rtoa(hl0s(k))))
      call assert_true(model%newton%cholesky .eqv. expect_cholesky, 'factorization: Cholesky expected '// &
                       merge('yes', 'no ', expect_cholesky))
    end do
  end subroutine check_solve

  subroutine test_solve_linear_model()
    call check_solve(element_effects_t(), 'exact', .true.)
  end subroutine test_solve_linear_model

  !> All effects on: K_t and M depend on q (exact strains, R-O material, rotary inertia).
  subroutine test_solve_all_effects()
    call check_solve(all_effects(), 'exact', .true.)
  end subroutine test_solve_all_effects

  !> Kear's printed simplifications: K_t is not symmetric, S goes through banded LU.
  subroutine test_solve_kear1987()
    call check_solve(all_effects(), 'kear1987', .false.)
  end subroutine test_solve_kear1987

  !> One run of the damped four-bar (1 element per link) over a quarter turn.
  subroutine run_quarter_turn(mf, structured, y, c, newton_factorizations)
    integer, intent(in) :: mf
    logical, intent(in) :: structured
    real(dp), allocatable, intent(out) :: y(:)
    type(lsode_counters_t), intent(out) :: c
    integer, intent(out) :: newton_factorizations
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    logical :: ok
    integer :: ml
    call make_model(fourbar_input(1, 150.0_dp, 0.0_dp), element_effects_t(), 1.0e-5_dp, model, ok)
    allocate(y(model%state_size()))
    y = 0.0_dp
    newton_factorizations = 0
    if (.not. ok) return
    ml = min(2*model%kd + 1, size(y) - 1)
    call ode%init(size(y), 0.0_dp, mf, 1.0e-6_dp, state_atol(size(y), 1.0e-9_dp, 1.0e-6_dp), err, ml=ml, mu=ml, &
                  structured=structured)
    call ode%integrate_to(model, y, 0.25_dp*2.0_dp*acos(-1.0_dp)/150.0_dp, err)
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    c = ode%counters()
    newton_factorizations = model%newton%n_factorizations
  end subroutine run_quarter_turn

  !> The model's Newton matrix solves the same linear systems as DLSODE's dense
  !> P, so the two runs take the same steps up to round-off in the solves;
  !> the states agree to the integration error (rtol 1e-6: 1e-4 of the
  !> largest component allows a hundredfold margin over rtol; a wrong Newton
  !> matrix would instead show as many more steps or a failed corrector).
  subroutine test_integration_routes()
    real(dp), allocatable :: y_model(:), y_dense(:)
    type(lsode_counters_t) :: c_model, c_dense
    integer :: nf_model, nf_dense
    call run_quarter_turn(mf_bdf_full_user, .true., y_model, c_model, nf_model)
    call run_quarter_turn(mf_bdf_full_user, .false., y_dense, c_dense, nf_dense)
    call assert_true(c_model%model_newton .and. .not. c_dense%model_newton, 'routes taken')
    call assert_equal(nf_model, c_model%jac_evals, 'one banded factorization per Jacobian')
    call assert_equal(nf_dense, 0, 'dense route does not use the model''s Newton matrix')
    call assert_all_close(y_model, y_dense, 0.0_dp, 1.0e-4_dp*maxval(abs(y_dense)), 'same state after a quarter turn')
    call assert_true(abs(c_model%steps - c_dense%steps) <= c_dense%steps/20, 'steps within 5 %: '// &
                     trim(itoa(c_model%steps))//' vs '//trim(itoa(c_dense%steps)))
  end subroutine test_integration_routes

  !> MF 24 used to hand DLSODE d(q_dd)/dq truncated to a band; it now takes
  !> the same route as MF 21: identical steps and states.
  subroutine test_bdf_band_equals_bdf()
    real(dp), allocatable :: y_full(:), y_band(:)
    type(lsode_counters_t) :: c(2)      ! full, band
    integer :: nf(2)
    call run_quarter_turn(mf_bdf_full_user, .true., y_full, c(1), nf(1))
    call run_quarter_turn(mf_bdf_band_user, .true., y_band, c(2), nf(2))
    call assert_equal(c(2)%steps, c(1)%steps, 'same steps')
    call assert_equal(nf(2), nf(1), 'same Newton matrices')
    call assert_all_close(y_band, y_full, 0.0_dp, 1.0e-12_dp*maxval(abs(y_full)), 'same state')
  end subroutine test_bdf_band_equals_bdf

  !> The decay system from y = 1 to t = 1 through its own Newton matrix (BDF,
  !> rtol 1e-8); the counters after the run.
  subroutine decay_to_one(sys, y, c, err, max_steps)
    type(decay_t), intent(inout), target :: sys
    real(dp), intent(out) :: y(3)
    type(lsode_counters_t), intent(out) :: c
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: max_steps
    type(lsode_t) :: ode
    y = 1.0_dp
    call ode%init(3, 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, [1.0e-12_dp], err, max_steps=max_steps)
    call ode%integrate_to(sys, y, 1.0_dp, err)
    c = ode%counters()
  end subroutine decay_to_one

  !> Any system with its own Newton matrix goes through it: y_k = exp(-k t)
  !> at t = 1 within the tolerance (rtol 1e-8: 1e-6 relative allows the
  !> global error's growth over the run), one factorization per Jacobian.
  subroutine test_decay_closed_form()
    type(decay_t), target :: sys
    type(error_t) :: err
    type(lsode_counters_t) :: c
    real(dp) :: y(3)
    integer :: k
    call decay_to_one(sys, y, c, err)
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    do k = 1, 3
      call assert_rel_close(y(k), exp(-real(k, dp)), 1.0e-6_dp, 'y_'//trim(itoa(k))//'(1) = exp(-k)')
    end do
    call assert_true(c%model_newton, 'the model''s Newton matrix was used')
    call assert_equal(sys%n_factor, c%jac_evals, 'one factorization per Jacobian')
  end subroutine test_decay_closed_form

  !> A model that stops mid-run (RHS error) ends the DLSODE call with the
  !> model's message, promptly: the Newton routines report a recoverable
  !> failure, never DSTODE's KFLAG = -3 (which DLSODE would retry forever: with
  !> IERSL = -1 this call never returns).
  subroutine test_decay_failure()
    type(decay_t), target :: sys
    type(error_t) :: err
    type(lsode_counters_t) :: c
    real(dp) :: y(3)
    sys%t_fail = 0.5_dp
    call decay_to_one(sys, y, c, err, max_steps=100000)
    call assert_true(err%failed() .and. index(err%text(), 'past t_fail') > 0, 'model error reported: '//err%text())
    call assert_true(c%steps < 1000, 'stopped promptly: '//trim(itoa(c%steps))//' steps')
  end subroutine test_decay_failure

  !> The model route re-sizes DLSODE's work arrays at the first call; an
  !> optional input set after init (MAXORD = 2 in IWORK(5), as the transient
  !> analysis's max_order does) must survive it: the order never exceeds 2
  !> (BDF would reach 5 on this smooth decay).
  subroutine test_max_order_kept()
    type(decay_t), target :: sys
    type(lsode_t) :: ode, free
    type(error_t) :: err
    type(lsode_counters_t) :: c
    real(dp) :: y(3)
    y = 1.0_dp
    call ode%init(3, 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, [1.0e-12_dp], err)
    call ode%limit_order(2)
    call ode%integrate_to(sys, y, 1.0_dp, err)
    c = ode%counters()
    call assert_true(.not. err%failed() .and. c%model_newton, 'integration through the model route')
    call assert_true(c%order_last <= 2, 'order limited to 2, got '//trim(itoa(c%order_last)))
    y = 1.0_dp
    call free%init(3, 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, [1.0e-12_dp], err)
    call free%integrate_to(sys, y, 1.0_dp, err)
    c = free%counters()
    call assert_true(c%order_last > 2, 'without the limit the order exceeds 2: '//trim(itoa(c%order_last)))
  end subroutine test_max_order_kept

  !> The turning system from y = (1, 1) to t = 2 (BDF, rtol 1e-6, atol
  !> 1e-9): the state against the closed form, the counters, the corrector
  !> iterations per step (RHS evaluations per step; one of them predicts).
  subroutine turn(w, theta, c, rhs_per_step)
    real(dp), intent(in) :: w, theta
    type(lsode_counters_t), intent(out) :: c
    real(dp), intent(out) :: rhs_per_step
    type(turning_t), target :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(2), z(2), b(2, 2), mu, delta, t
    sys%w = w
    sys%jacobian_steps = 10
    sys%jacobian_contraction = theta
    y = 1.0_dp
    t = 2.0_dp
    call ode%init(2, 0.0_dp, mf_bdf_full_user, 1.0e-6_dp, [1.0e-9_dp], err)
    call ode%integrate_to(sys, y, t, err)
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    c = ode%counters()
    rhs_per_step = real(c%rhs_evals, dp)/c%steps
    ! closed form: z = exp(B t) z0, z0 = R(0) y0 = y0, with the eigenvalues
    ! l1 > l2 of B: exp(B t) = (e^(l1 t) (B - l2 I) - e^(l2 t) (B - l1 I)) / (l1 - l2)
    b = reshape([-sys%a, -w, w, -sys%b], [2, 2])
    mu = -0.5_dp*(sys%a + sys%b)
    delta = sqrt(0.25_dp*(sys%a - sys%b)**2 - w**2)
    z = exp((mu + delta)*t)*(matmul(b, [1.0_dp, 1.0_dp]) - (mu - delta)) - &
        exp((mu - delta)*t)*(matmul(b, [1.0_dp, 1.0_dp]) - (mu + delta))
    z = z/(2.0_dp*delta)
    z = [cos(w*t)*z(1) - sin(w*t)*z(2), sin(w*t)*z(1) + cos(w*t)*z(2)]     ! y = R^T z
    ! rtol 1e-6 per step over up to ten turns and 2,000 steps: the global
    ! error measured is 1.5e-4 of the largest component (the same with either
    ! age rule); 1e-3 leaves a sixfold margin, and a stale matrix that misled
    ! the corrector would show as a phase error of the turning components
    call assert_all_close(y, z, 0.0_dp, 1.0e-3_dp*maxval(abs(z)), 'closed form at t = 2, w = '//rtoa(w))
  end subroutine turn

  !> The age limit adapts to how fast the Newton matrix turns out of date:
  !> turning fast (w = 30 rad/s, about ten turns in the run), the run forms
  !> at least twice as many matrices per step as turning slowly (w = 0.01
  !> rad/s; measured 0.50 and 0.19: in the slow run the bound acts only where
  !> h*el0 changed since the matrix), and the corrector then needs fewer
  !> iterations per step than with the fixed limit of 10 steps alone
  !> (theta = 0), whose stale matrix contracts slowly (measured 1.2 against
  !> 2.0 right-hand sides per step).  Every run against the closed form.
  subroutine test_age_follows_contraction()
    type(lsode_counters_t) :: slow, fast, fast_fixed
    real(dp) :: r_slow, r_fast, r_fast_fixed, per_step_slow, per_step_fast
    call turn(0.01_dp, 0.2_dp, slow, r_slow)
    call turn(30.0_dp, 0.2_dp, fast, r_fast)
    call turn(30.0_dp, 0.0_dp, fast_fixed, r_fast_fixed)
    per_step_slow = real(slow%jac_evals, dp)/slow%steps
    per_step_fast = real(fast%jac_evals, dp)/fast%steps
    call assert_true(per_step_fast >= 2.0_dp*per_step_slow, 'matrices per step: fast turn '//rtoa(per_step_fast)// &
                     ', slow turn '//rtoa(per_step_slow))
    call assert_true(r_fast < 0.8_dp*r_fast_fixed, 'fast turn: RHS per step with the bound '//rtoa(r_fast)// &
                     ' against the fixed limit''s '//rtoa(r_fast_fixed))
  end subroutine test_age_follows_contraction
end module test_lsode_newton_suite

program test_lsode_newton
  use assertions, only: finish_suite
  use test_lsode_newton_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_lsode_newton')
end program test_lsode_newton
