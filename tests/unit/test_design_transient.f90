!> Tests of the design analysis' transient evaluator (module
!> periodic_transient, design_problem's 'transient' branch): on example 1
!> (Tennant's four-bar at 150 rad/s) its constraints agree with the exact
!> periodic state's (shooting) to the periodicity tolerance, from rest and
!> from the previous design's state; a transient that does not become
!> periodic in time is a failed analysis with its reason; its forward
!> differences take a peak stress at the base design's largest sample, as
!> the variational derivative does; bad values of the new deck variables are
!> input errors (code 2).
module test_design_transient_suite
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use kinds, only: dp
  use error_status, only: error_t
  use design_problem, only: design_problem_t, design_eval_t
  use design_analysis, only: run_design
  use design_fixtures, only: bar_deck, load_design_text, eval_reason
  use deck_runner, only: scratch_path, run_deck, line_length
  use assertions
  implicit none
  private
  public :: run_all

  character(len=:), allocatable :: scratch
  !> inputs/design_fourbar_mass_150.nml without its comments
  character(len=*), parameter :: example1 = '&run analysis = ''design'' /|&mechanism n_joints = 4, '// &
    'joint_name = ''A'', ''B'', ''C'', ''D'', joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin'', '// &
    'joint_x(1) = 0.0, joint_y(1) = 0.0, joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3, '// &
    'link_name = ''crank'', ''coupler'', ''rocker'', link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, '// &
    'link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, link_h = 3*1.0, link_n_elements = 3*1, driver_link = 1, '// &
    'omega = 150.0 /|&steady damping_beta = 1.0e-5, integrator = ''bdf'', rtol = 1.0e-7, atol = 1.0e-11 /|'// &
    '&tennant d_k = 0, d_b = 0, d_g = 0, shear = F /|&design variables = ''link_h(1)'', ''link_h(2)'', '// &
    '''link_h(3)'', lower = 3*0.2, upper = 3*4.0, stress_allowable = 20000.0, frequency_factor = 5.0, '

contains

  subroutine run_all()
    scratch = scratch_path('test_design_transient')
    call run_test('transient_evaluator_agrees_with_shooting_on_example_1', test_agrees_with_shooting)
    call run_test('transient_not_periodic_in_time_is_a_failed_analysis', test_not_periodic)
    call run_test('transient_differences_take_the_largest_sample_as_the_variational_derivative', &
                  test_derivative_at_largest_sample)
    call run_test('bad_transient_evaluator_values_are_input_errors', test_bad_values)
  end subroutine run_all

  !> The example-1 problem with `evaluator` and `extra` &design settings.
  subroutine load(evaluator, extra, prob, x0)
    character(len=*), intent(in) :: evaluator, extra
    type(design_problem_t), intent(out) :: prob
    real(dp), allocatable, intent(out) :: x0(:)
    type(error_t) :: err
    call load_design_text(scratch, example1//'evaluator = '''//evaluator//''''//extra//' /', prob, x0, err)
    call assert_true(.not. err%failed(), 'example 1 loads: '//err%text())
    call prob%setup('example 1', x0)
  end subroutine load

  !> Peak stresses (the constraints ln(stress/allowable)) at the initial
  !> design, the transient from rest, and at a second design (heights 0.6,
  !> 0.5, 0.45 in: stresses of another size), the transient from the first
  !> design's periodic state.  The transient stops at a change of 1e-6 per
  !> revolution (the default, 10 x rtol: the change per revolution does not
  !> fall below about 3 rtol); its distance from the orbit is about
  !> change rho/(1 - rho), rho ~ 0.7 per revolution here (damping 1e-5 s), and the shooting
  !> solution is exact to its Newton tolerance (1e-6 of the state) and both
  !> to the integration (rtol 1e-7): 1e-5 on ln(stress).  The frozen
  !> frequencies depend on the configuration only: the same to 1e-12.
  subroutine test_agrees_with_shooting()
    type(design_problem_t) :: ps, pt
    type(design_eval_t) :: es, et
    real(dp), allocatable :: x0(:)
    real(dp) :: x1(3), stress1
    integer :: pass, i
    call load('shooting', '', ps, x0)
    call load('transient', '', pt, x0)
    x1 = log([0.6_dp, 0.5_dp, 0.45_dp])
    do pass = 1, 2
      if (pass == 1) then
        call ps%evaluate(x0, es)
        call pt%evaluate(x0, et)
      else
        call ps%evaluate(x1, es)
        call pt%evaluate(x1, et)
      end if
      call assert_true(es%ok, 'shooting succeeds: '//eval_reason(es))
      call assert_true(et%ok, 'transient succeeds: '//eval_reason(et))
      if (.not. (es%ok .and. et%ok)) return
      do i = 1, 3
        call assert_close(log(et%link_stress(i)/es%link_stress(i)), 0.0_dp, 1.0e-5_dp, 'ln(stress) of link '// &
                          char(48 + i)//', design '//char(48 + pass))
      end do
      call assert_close(et%lowest_frequency/es%lowest_frequency, 1.0_dp, 1.0e-12_dp, 'lowest frozen frequency')
      call assert_close(et%mass/es%mass, 1.0_dp, 1.0e-14_dp, 'mass')
      if (pass == 1) stress1 = es%link_stress(1)
    end do
    call assert_true(abs(es%link_stress(1)/stress1 - 1.0_dp) > 0.1_dp, 'the two designs'' stresses differ')
  end subroutine test_agrees_with_shooting

  !> The crank's peak stress is the largest of 72 samples; at iteration 29 of
  !> the transient evaluator's example-1 run (doc/design.md) samples 2 and 3
  !> are nearly equal and a forward step of 1e-3 in ln h2 moves the largest
  !> from one to the other.  The loop's difference (neighbour_constraints)
  !> takes the neighbour's stress at the base design's largest sample, the
  !> sample the variational derivative of the shooting evaluator
  !> differentiates: they agree to 0.05 in d ln(stress)/d ln h2 (of -4.40;
  !> measured 0.004: the forward difference's truncation, step x half the
  !> curvature, and the transient's 1e-6 over the step, 1e-3).  The
  !> difference of the peak itself is a chord across the switch: -2.51,
  !> off by more than 1 (also asserted: the guard that this design does
  !> switch).
  subroutine test_derivative_at_largest_sample()
    type(design_problem_t) :: ps, pt
    type(design_eval_t) :: ev, evp
    real(dp), allocatable :: x0(:), dg(:, :), dr(:, :), g(:), gp(:), g_peak(:)
    real(dp) :: x(3), xp(3), h, d_sample, d_peak
    logical :: ok
    call load('shooting', '', ps, x0)
    call load('transient', '', pt, x0)
    x = log([0.9969892317644725_dp, 0.3990053092655687_dp, 0.3811180364377223_dp])
    call ps%derivatives_at(x, dg, dr, ok)
    call assert_true(ok, 'variational derivatives at the design')
    call pt%evaluate(x, ev)
    call assert_true(ev%ok, 'transient analysis at the design: '//eval_reason(ev))
    if (.not. (ok .and. ev%ok)) return
    g = pt%constraints_of(ev)
    h = pt%fd_rel_step*max(abs(x(2)), 1.0_dp)
    xp = x
    xp(2) = x(2) + h
    call pt%evaluate(xp, evp)
    call assert_true(evp%ok, 'transient analysis at the neighbour: '//eval_reason(evp))
    if (.not. evp%ok) return
    g_peak = pt%constraints_of(evp)
    gp = g_peak
    call pt%neighbour_constraints(x, xp, gp)
    d_sample = (gp(1) - g(1))/h
    d_peak = (g_peak(1) - g(1))/h
    call assert_true(maxloc(ev%sample_stress(:, 1, 1), dim=1) /= maxloc(evp%sample_stress(:, 1, 1), dim=1), &
                     'the largest crank sample switches within the step')
    call assert_close(d_sample, dg(2, 1), 0.05_dp, 'difference at the largest sample = variational derivative')
    call assert_true(abs(d_peak - dg(2, 1)) > 1.0_dp, 'the chord of the peak is neither side''s derivative')
    call assert_close(ev%sample_stress(maxloc(ev%sample_stress(:, 1, 1), dim=1), 1, 1), ev%link_stress(1), 0.0_dp, &
                      'the peak is its largest sample''s stress')
  end subroutine test_derivative_at_largest_sample

  !> Two revolutions from rest cannot meet 1e-6 (the contraction is about
  !> 0.7 per revolution): the analysis fails, the
  !> design is infeasible with the reason, nothing is NaN-accepted.
  subroutine test_not_periodic()
    type(design_problem_t) :: pt
    type(design_eval_t) :: et
    real(dp), allocatable :: x0(:)
    real(dp) :: g
    type(error_t) :: err
    call load('transient', ', max_revolutions = 2', pt, x0)
    call pt%evaluate(x0, et)
    call assert_true(.not. et%ok, 'the analysis fails')
    if (allocated(et%reason)) then
      call assert_true(index(et%reason, 'not periodic after 2 revolutions') > 0, 'reason: '//et%reason)
    else
      call assert_true(.false., 'a reason is given')
    end if
    call pt%general_constraint(1, x0, g, err)
    call assert_true(ieee_is_nan(g), 'its constraints are NaN (a failed trial)')
    call assert_equal(pt%n_failed, 1, 'counted as a failed analysis')
  end subroutine test_not_periodic

  subroutine test_bad_values()
    character(len=*), parameter :: ok = '&design variables = ''link_h(1)'', lower = 0.1, upper = 2, '// &
      'frequency_factor = 10, evaluator = ''transient'', '
    call bad(bar_deck, ok//'stop_when_periodic = 0.0 /', 'stop_when_periodic')
    call bad(bar_deck, ok//'stop_when_periodic = NaN /', 'stop_when_periodic')
    call bad(bar_deck, ok//'stop_when_periodic = 0.5 /', 'stop_when_periodic')
    call bad(bar_deck, ok//'max_revolutions = 1 /', 'max_revolutions')
    call bad(replace(bar_deck, 'damping_beta = 1.0e-4', 'damping_beta = 1.0e-4, rtol = 1.0e-6'), ok//'/', &
             'at least 10 x the integration''s rtol')
    call bad(replace(bar_deck, 'd_k = 0', 'd_k = 1'), ok//'/', 'the linear element only')
    call bad(replace(bar_deck, 'd_k = 0', 'shear = T, d_k = 0'), ok//'/', 'no shear angle')
  contains
    subroutine bad(base, design_group, fragment)
      character(len=*), intent(in) :: base, design_group, fragment
      type(error_t) :: err
      character(len=line_length), allocatable :: lines(:)
      call run_deck(run_design, scratch, base//design_group, err, lines)
      call assert_true(err%failed() .and. err%code == 2, fragment//': an input error')
      call assert_true(index(err%text(), fragment) > 0, 'message names '//fragment//': '//err%text())
      call assert_true(size(lines) == 0, fragment//': no output')
    end subroutine bad

    function replace(text, old, new) result(res)
      character(len=*), intent(in) :: text, old, new
      character(len=:), allocatable :: res
      integer :: at
      at = index(text, old)
      res = text(1:at - 1)//new//text(at + len(old):)
    end function replace
  end subroutine test_bad_values
end module test_design_transient_suite

program test_design_transient
  use test_design_transient_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_design_transient')
end program test_design_transient
