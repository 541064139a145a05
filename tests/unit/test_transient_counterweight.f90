!> Counterweights in the planar transient model (mechanism_model's
!> register_counterweights/add_counterweights, joint_reactions'
!> add_counterweight):
!>  - the rigid limit: pin forces and the crank torque of Tennant's four-bar
!>    with counterweights on crank and rocker against the Newton-Euler
!>    equations of its three links and two point masses (a 9 x 9 system
!>    written here), and no moment at the rocker's ground pin;
!>  - the flexible four-bar at 100 rad/s with a counterweight on the rocker:
!>    the transient run to its periodic state equals the steady model's
!>    exact periodic solution (shooting) with the same counterweight, and the
!>    counterweight changes that solution by far more than the tolerance.
module test_transient_counterweight_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use element_effects, only: element_effects_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use mechanism_model, only: mechanism_model_t
  use joint_reactions, only: joint_reactions_t
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use periodic_shooting, only: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit
  use periodic_transient, only: periodic_transient_settings_t, periodic_transient_report_t, transient_to_periodic, &
                                matching_unknowns
  use transient_fixtures, only: fourbar_input, e1, rtoa, rigid_fourbar_forces, rigid_limit_state, fourbar_unknowns
  use assertions
  implicit none
  private
  public :: run_all

  !> counterweights: crank (at A, clamped) and rocker (at D, pinned), link frames
  real(dp), parameter :: m_cw(2) = [0.002_dp, 0.003_dp]
  real(dp), parameter :: c_crank(2) = [-2.0_dp, 0.5_dp], c_rocker(2) = [-4.0_dp, -0.3_dp]

contains

  subroutine run_all()
    call run_test('rigid_fourbar_with_counterweights_pin_forces_match_newton_euler', test_rigid_limit)
    call run_test('flexible_fourbar_counterweight_transient_equals_shooting_orbit', test_periodic)
  end subroutine run_all

  function fourbar_cw(omega) result(inp)
    real(dp), intent(in) :: omega
    type(mechanism_input_t) :: inp
    inp = fourbar_input(1, omega, 0.0_dp)
    inp%link_cw_mass(1) = m_cw(1)
    inp%link_cw_x(1) = c_crank(1)
    inp%link_cw_y(1) = c_crank(2)
    inp%link_cw_mass(3) = m_cw(2)
    inp%link_cw_x(3) = c_rocker(1)
    inp%link_cw_y(3) = c_rocker(2)
  end function fourbar_cw

  !> Links 1e6 times stiffer than aluminium, linear model, 150 rad/s, crank
  !> angles 0, 50, ..., 300 deg, the quasi-static elastic state (deflections
  !> ~1e-8 in): the reactions are the rigid-body ones to 1e-6 of the largest
  !> force (as test_joint_reactions without counterweights: the loads change
  !> with q by ~1e-8 relative).  The pin at D transmits no moment (1e-6 of
  !> the largest force times the rocker's length).
  subroutine test_rigid_limit()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(joint_reactions_t) :: jr
    type(error_t) :: err
    real(dp) :: expect(9), got(9), t, scale, omega, masses(3), acc_g(2, 3)
    real(dp), allocatable :: qq(:), zero(:)
    integer :: k
    omega = 150.0_dp
    inp = fourbar_cw(omega)
    inp%link_e1(1:3) = 1.0e6_dp*e1
    call build_mechanism(inp, mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, element_effects_t(), 'exact', 0.0_dp, err)
    call assert_true(.not. err%failed(), 'model with counterweights: '//err%text())
    if (err%failed()) return
    call jr%init(mech)
    allocate(qq(model%n), zero(model%n))
    zero = 0.0_dp
    do k = 0, 6
      call rigid_limit_state(model, omega, k, t, qq, err)
      if (.not. err%failed()) call jr%compute(model, t, qq, zero, err, qdd=zero)
      call assert_true(.not. err%failed(), 'equilibrium and reactions: '//err%text())
      if (err%failed()) return
      got = fourbar_unknowns(jr)
      call rigid_fourbar_forces(model, omega*t, omega, expect, masses, acc_g, m_cw, c_crank, c_rocker)
      scale = maxval(abs(expect))
      call assert_all_close(got, expect, 0.0_dp, 1.0e-6_dp*scale, 'reactions vs Newton-Euler at crank angle '// &
                            rtoa(50.0_dp*k)//' deg')
      call assert_close(jr%ends(6)%moment, 0.0_dp, 1.0e-6_dp*scale*10.5_dp, 'no moment at the rocker''s pin D')
      if (k == 0) write(*, '(4x,a,3es12.4,a,es10.2)') 'crank angle 0: F_A, T_A = ', expect(1:3), &
        '; largest difference ', maxval(abs(got - expect))
    end do
  end subroutine test_rigid_limit

  !> Tennant's four-bar (one element per link, linear, rotary inertia and
  !> coupling: the equations of the steady model's linear element) at
  !> 100 rad/s, damping 1e-5 s, the two counterweights.  The transient from
  !> rest to a change of 1e-7 per revolution (rtol 1e-9) against the
  !> shooting orbit (rtol 1e-9, Newton tolerance 1e-8) at 9 crank angles:
  !> 1e-5 of the largest displacement.  Without the counterweights the orbit
  !> moves by more than 1e-2 of it (the rocker must swing its counterweight).
  subroutine test_periodic()
    type(mechanism_t) :: mech, mech0
    type(steady_model_t), target :: model, model0
    type(mechanism_model_t), target :: tmodel
    type(link_sections_t) :: secs(3)
    type(shooting_settings_t) :: s
    type(shooting_report_t) :: rep
    type(periodic_transient_settings_t) :: ts
    type(periodic_transient_report_t) :: trep
    type(error_t) :: err
    real(dp), parameter :: w = 100.0_dp, beta = 1.0e-5_dp
    real(dp), allocatable :: y0(:), y(:), qs(:, :), qd(:, :), q0(:, :), qt(:, :)
    real(dp) :: times(9)
    integer :: j
    integer, allocatable :: to_steady(:)
    call build_mechanism(fourbar_cw(w), mech, err)
    if (.not. err%failed()) call build_mechanism(fourbar_input(1, w, 0.0_dp), mech0, err)
    if (.not. err%failed()) call model%init_mechanism(mech, tennant_options_t(damping_beta=beta), secs, err)
    if (.not. err%failed()) call model0%init_mechanism(mech0, tennant_options_t(damping_beta=beta), secs, err)
    if (.not. err%failed()) call tmodel%init_mechanism(mech, element_effects_t(rotary_inertia=.true., coupling=.true.), &
                                                       'exact', beta, err)
    call assert_true(.not. err%failed(), 'models: '//err%text())
    if (err%failed()) return
    do j = 1, 9
      times(j) = (j - 1)*(two_pi/w)/9
    end do
    s = shooting_settings_t(rtol=1.0e-9_dp, atol=1.0e-13_dp, newton_tol=1.0e-8_dp, bdf=.true.)
    allocate(y0(2*model%n), qs(model%n, 9), qd(model%n, 9), q0(model%n, 9), qt(tmodel%n, 9), y(2*tmodel%n))
    y0 = 0.0_dp
    call shooting_solve(model, s, y0, rep, err)
    if (.not. err%failed()) call periodic_orbit(model, s, y0, times, qs, qd, rep, err)
    y0 = 0.0_dp
    if (.not. err%failed()) call shooting_solve(model0, s, y0, rep, err)
    if (.not. err%failed()) call periodic_orbit(model0, s, y0, times, q0, qd, rep, err)
    call assert_true(.not. err%failed(), 'shooting: '//err%text())
    to_steady = matching_unknowns(tmodel%table%labels(), model%table%labels())
    call assert_true(all(to_steady > 0), 'every transient unknown has a steady counterpart')
    if (any(to_steady == 0) .or. err%failed()) return
    ts = periodic_transient_settings_t(tolerance=1.0e-7_dp, max_revolutions=400, rtol=1.0e-9_dp, atol=1.0e-13_dp)
    y = 0.0_dp
    call transient_to_periodic(tmodel, ts, y, times, qt, trep, err)
    call assert_true(.not. err%failed(), 'transient to periodic: '//err%text())
    if (err%failed()) return
    call assert_all_close(reshape(qt, [size(qt)]), reshape(qs(to_steady, :), [size(qs)]), 0.0_dp, &
                          1.0e-5_dp*maxval(abs(qs)), 'transient with counterweights = shooting orbit')
    call assert_true(maxval(abs(qs - q0)) > 1.0e-2_dp*maxval(abs(qs)), 'the counterweights change the orbit')
    write(*, '(4x,a,i0,a,es10.2,a,es10.2)') 'revolutions ', trep%revolutions, ', largest difference ', &
      maxval(abs(qt - qs(to_steady, :)))/maxval(abs(qs)), ' of the peak; counterweight effect ', &
      maxval(abs(qs - q0))/maxval(abs(qs))
  end subroutine test_periodic
end module test_transient_counterweight_suite

program test_transient_counterweight
  use test_transient_counterweight_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_counterweight')
end program test_transient_counterweight
