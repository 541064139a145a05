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
  use linalg, only: solve_linear
  use kear_element, only: element_effects_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use mechanism_model, only: mechanism_model_t
  use joint_reactions, only: joint_reactions_t
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use periodic_shooting, only: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit
  use periodic_transient, only: periodic_transient_settings_t, periodic_transient_report_t, transient_to_periodic, &
                                matching_unknowns
  use transient_fixtures, only: fourbar_input, e1, rtoa
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
    real(dp) :: expect(9), got(9), t, scale, omega
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
      t = (50.0_dp*k*pi/180.0_dp)/omega
      qq = 0.0_dp
      call model%static_equilibrium(t, qq, 1, err)
      if (.not. err%failed()) call jr%compute(model, t, qq, zero, err, qdd=zero)
      call assert_true(.not. err%failed(), 'equilibrium and reactions: '//err%text())
      if (err%failed()) return
      got = [jr%ends(1)%force, jr%ends(1)%moment, jr%ends(3)%force, jr%ends(5)%force, jr%ends(6)%force]
      call newton_euler(model, omega*t, omega, expect)
      scale = maxval(abs(expect))
      call assert_all_close(got, expect, 0.0_dp, 1.0e-6_dp*scale, 'reactions vs Newton-Euler at crank angle '// &
                            rtoa(50.0_dp*k)//' deg')
      call assert_close(jr%ends(6)%moment, 0.0_dp, 1.0e-6_dp*scale*10.5_dp, 'no moment at the rocker''s pin D')
      if (k == 0) write(*, '(4x,a,3es12.4,a,es10.2)') 'crank angle 0: F_A, T_A = ', expect(1:3), &
        '; largest difference ', maxval(abs(got - expect))
    end do
  end subroutine test_rigid_limit

  !> The rigid four-bar with the two counterweights (point masses turning
  !> with crank and rocker about A and D), crank at constant speed w:
  !> closed-form loops for positions, velocities, accelerations; slender
  !> links (I = m L^2/12); unknowns [F_A(2), T_A, F_B(2), F_C(2), F_D(2)],
  !> F_B crank on coupler, F_C coupler on rocker, F_A, F_D ground on crank,
  !> rocker.  Moments about each link's centre.
  subroutine newton_euler(model, th, w, x)
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: th, w
    real(dp), intent(out) :: x(9)
    real(dp), parameter :: r2 = 5.0_dp, r3 = 11.0_dp, r4 = 10.5_dp, d(2) = [10.0_dp, 0.0_dp]
    real(dp) :: a(9, 9), b(2), c(2), e2(2), n2(2), e3(2), n3(2), e4(2), n4(2), w3, w4, al3, al4, mat(2, 2), rhs(2)
    real(dp) :: m(3), ig(3), g2(2), g3(2), g4(2), a2(2), a3(2), a4(2), p2(2), p4(2), f2(2), f4(2), dist, h, perp(2)
    type(error_t) :: err
    e2 = [cos(th), sin(th)]
    n2 = [-e2(2), e2(1)]
    b = r2*e2
    dist = norm2(d - b)
    h = (r3**2 - r4**2 + dist**2)/(2.0_dp*dist)
    perp = [-(d(2) - b(2)), d(1) - b(1)]/dist*sqrt(r3**2 - h**2)
    ! the branch of the model's coupler
    c = b + h*(d - b)/dist + perp
    if (abs(modulo(atan2(c(2) - b(2), c(1) - b(1)) - model%rb(2)%phi + pi, two_pi) - pi) > 1.0e-6_dp) &
      c = b + h*(d - b)/dist - perp
    e3 = (c - b)/r3
    e4 = (c - d)/r4
    n3 = [-e3(2), e3(1)]
    n4 = [-e4(2), e4(1)]
    mat(:, 1) = r3*n3
    mat(:, 2) = -r4*n4
    rhs = -r2*w*n2
    call solve_linear(mat, rhs, err)
    w3 = rhs(1)
    w4 = rhs(2)
    mat(:, 1) = r3*n3
    mat(:, 2) = -r4*n4
    rhs = r2*w**2*e2 + r3*w3**2*e3 - r4*w4**2*e4
    call solve_linear(mat, rhs, err)
    al3 = rhs(1)
    al4 = rhs(2)
    a2 = -0.5_dp*r2*w**2*e2
    a3 = -r2*w**2*e2 + 0.5_dp*r3*(al3*n3 - w3**2*e3)
    a4 = 0.5_dp*r4*(al4*n4 - w4**2*e4)
    m = model%el(1)%kear%material%rho*model%el(1)%kear%area*[r2, r3, r4]
    ig = m*[r2, r3, r4]**2/12.0_dp
    g2 = 0.5_dp*b
    g3 = 0.5_dp*(b + c)
    g4 = 0.5_dp*(c + d)
    ! the counterweights and their inertia forces m a
    p2 = c_crank(1)*e2 + c_crank(2)*n2
    p4 = d + c_rocker(1)*e4 + c_rocker(2)*n4
    f2 = -m_cw(1)*w**2*p2
    f4 = m_cw(2)*(al4*[-(p4(2) - d(2)), p4(1) - d(1)] - w4**2*(p4 - d))
    a = 0.0_dp
    a(1, 1) = 1.0_dp; a(1, 4) = -1.0_dp
    a(2, 2) = 1.0_dp; a(2, 5) = -1.0_dp
    a(3, 3) = 1.0_dp
    a(3, 1:2) = cross_row(-g2)
    a(3, 4:5) = -cross_row(b - g2)
    a(4, 4) = 1.0_dp; a(4, 6) = -1.0_dp
    a(5, 5) = 1.0_dp; a(5, 7) = -1.0_dp
    a(6, 4:5) = cross_row(b - g3)
    a(6, 6:7) = -cross_row(c - g3)
    a(7, 6) = 1.0_dp; a(7, 8) = 1.0_dp
    a(8, 7) = 1.0_dp; a(8, 9) = 1.0_dp
    a(9, 6:7) = cross_row(c - g4)
    a(9, 8:9) = cross_row(d - g4)
    x = [m(1)*a2 + f2, dot_product(cross_row(p2 - g2), f2), m(2)*a3, ig(2)*al3, m(3)*a4 + f4, &
         ig(3)*al4 + dot_product(cross_row(p4 - g4), f4)]
    call solve_linear(a, x, err)
    call assert_true(.not. err%failed(), 'Newton-Euler system: '//err%text())
  end subroutine newton_euler

  !> Coefficients of F in r x F = r(1) F(2) - r(2) F(1).
  pure function cross_row(r) result(c)
    real(dp), intent(in) :: r(2)
    real(dp) :: c(2)
    c = [-r(2), r(1)]
  end function cross_row

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
    to_steady = matching_unknowns(tmodel%table%label, model%table%label)
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
