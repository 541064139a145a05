!> Verification of the transient analysis on linkages (issue 3, items 4, 5
!> and 7): conservation of energy with the driver stopped, bound scaling with
!> rtol; the rigid limit (deformation ~ 1/E in the quasi-static regime); a
!> slow slider-crank against rigid-body statics.  Setups, sources and
!> measured values: doc/verification_transient.md.
module test_transient_mechanism_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use element_effects, only: element_effects_t
  use planar_element, only: stress_report_t
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: lsode_t, mf_adams, mf_bdf_full_user
  use linkage, only: mechanism_input_t
  use transient_fixtures
  use mechanism_fixtures, only: slider_crank_input
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('energy_conserved_with_driver_stopped_bound_scales_with_rtol', test_energy_driver_stopped)
    call run_test('rigid_limit_deformation_scales_with_inverse_modulus', test_rigid_limit)
    call run_test('slow_slider_crank_stresses_match_rigid_body_statics', test_slider_crank_statics)
  end subroutine run_all

  ! ------------------------------------------------------------------ 4. energy

  !> The §8.1 four-bar with the driver stopped (omega = 0, crank clamped at
  !> 60 deg), all effects on, released undamped from its first mode with a
  !> largest transverse displacement of 0.02 in (a strongly nonlinear
  !> state), over 100 periods: the relative drift of kinetic + strain
  !> energy stays below 100 rtol and falls with rtol (by more than 30x from
  !> rtol = 1e-6 to 1e-8; measured 5e-5 and 8e-8 in the release build).
  subroutine test_energy_driver_stopped()
    real(dp) :: drift(2)
    logical :: ok
    integer :: i
    real(dp), parameter :: rtols(2) = [1.0e-6_dp, 1.0e-8_dp]
    do i = 1, 2
      call energy_drift(rtols(i), drift(i), ok)
      if (.not. ok) return
      call assert_true(drift(i) < 100.0_dp*rtols(i), 'energy drift '//rtoa(drift(i))//' < 100 rtol at rtol = '// &
                       rtoa(rtols(i)))
    end do
    call assert_true(drift(2) < drift(1)/30.0_dp, 'drift falls with rtol: '//rtoa(drift(1))//' -> '//rtoa(drift(2)))
    ! the consistent element: the same conservation at rtol 1e-6, over 20 periods of mode 1 instead
    ! of 100 (Adams follows its axial modes at their stability limit: 200 half-periods took 3/4 of
    ! this suite's CPU; the drift grows with time, so the shorter run is no looser a bound)
    call energy_drift(1.0e-6_dp, drift(1), ok, 'consistent', half_periods=40)
    if (.not. ok) return
    write(*, '(4x,a,es10.3)') 'consistent element: energy drift at rtol 1e-6: ', drift(1)
    call assert_true(drift(1) < 100.0_dp*1.0e-6_dp, 'consistent element: energy drift '//rtoa(drift(1))// &
                     ' < 100 rtol at rtol = 1e-6')
  end subroutine test_energy_driver_stopped

  subroutine energy_drift(rtol, drift, ok, formulation, half_periods)
    real(dp), intent(in) :: rtol
    real(dp), intent(out) :: drift
    logical, intent(out) :: ok
    character(len=*), intent(in), optional :: formulation
    integer, intent(in), optional :: half_periods   !< of mode 1 integrated (200)
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:), omega(:), shapes(:, :)
    real(dp) :: ke, se, e0, t, t_half
    integer :: k, n_half
    n_half = 200
    if (present(half_periods)) n_half = half_periods
    drift = huge(1.0_dp)
    call make_model(fourbar_input(1, 0.0_dp, 60.0_dp), all_effects(), 0.0_dp, model, ok, formulation=formulation)
    if (.not. ok) return
    call mode_start(model, 1, 0.02_dp, omega, shapes, y, err)
    call model%energies(0.0_dp, y(1::2), y(2::2), ke, se)
    e0 = ke + se
    call ode%init(size(y), 0.0_dp, mf_adams, rtol, [1.0e-5_dp*rtol], err, max_steps=1000000)
    t_half = pi/omega(1)
    drift = 0.0_dp
    do k = 1, n_half
      t = k*t_half
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      call model%energies(t, y(1::2), y(2::2), ke, se)
      drift = max(drift, abs(ke + se - e0)/e0)
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    ok = .not. err%failed()
  end subroutine energy_drift

  ! ------------------------------------------------------------------ 5. rigid limit

  !> The §8.1 four-bar at 15 rad/s (0.01 of its first natural frequency),
  !> spun up over 0.2 s, damped (zeta_1 = 1.5 % at E, critically damped at
  !> 1e4 E: the damping lag omega beta is 2e-4 there), all effects on: in the
  !> quasi-static regime the elastic deformation is the static response to the
  !> rigid-body inertia loads, so E1, E2 -> 1e4 E1, 1e4 E2 (the whole law
  !> scaled) divides it by 1e4 (the nonlinear terms are of the order of the
  !> strains, 1e-5 and 1e-9).  Compared: the elastic joint displacements of B
  !> and C at 12 crank angles of the second turn, to 0.5 % of their largest
  !> value (the dynamic part is (h omega/omega_1)^2 for crank harmonic h;
  !> measured 0.3 %).
  subroutine test_rigid_limit()
    real(dp) :: d_soft(4, 12), d_stiff(4, 12)
    logical :: ok
    call quasi_static_joints(1.0_dp, d_soft, ok)
    if (.not. ok) return
    call quasi_static_joints(1.0e4_dp, d_stiff, ok)
    if (.not. ok) return
    call assert_all_close(1.0e4_dp*reshape(d_stiff, [48]), reshape(d_soft, [48]), 0.0_dp, &
                          5.0e-3_dp*maxval(abs(d_soft)), 'deformation x 1e4 at 1e4 E = deformation at E')
    call assert_true(maxval(abs(d_soft)) > 1.0e-6_dp, 'deformations are not trivially zero')
  end subroutine test_rigid_limit

  subroutine quasi_static_joints(scale, d, ok)
    real(dp), intent(in) :: scale
    real(dp), intent(out) :: d(:, :)
    logical, intent(out) :: ok
    real(dp), parameter :: omega = 15.0_dp, t_spin = 0.2_dp
    type(mechanism_input_t) :: inp
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:)
    real(dp) :: t, t_turn, qe(8)
    integer :: k
    d = 0.0_dp
    inp = fourbar_input(1, omega, 0.0_dp)
    inp%profile = 'spinup'
    inp%spinup_time = t_spin
    inp%link_e1(1:3) = scale*inp%link_e1(1:3)
    inp%link_e2(1:3) = scale*inp%link_e2(1:3)
    call make_model(inp, all_effects(), min(2.0e-5_dp, 2.0_dp/(1462.0_dp*sqrt(scale))), model, ok)
    if (.not. ok) return
    allocate(y(model%state_size()))
    y = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, state_atol(size(y), 1.0e-14_dp/scale, 1.0e-8_dp/scale), &
                  err, max_steps=200000)
    ! the crank turns omega t_spin / 2 during the spin-up; then a full turn
    t_turn = two_pi/omega
    do k = 1, 12
      t = t_spin + t_turn + k*t_turn/12.0_dp
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      qe = model%table%gather(1, y(1::2))
      d(1:2, k) = qe(5:6)                          ! joint B: end 2 of the crank
      qe = model%table%gather(2, y(1::2))
      d(3:4, k) = qe(5:6)                          ! joint C: end 2 of the coupler
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    ok = .not. err%failed()
  end subroutine quasi_static_joints

  ! ------------------------------------------------------------------ 7. slider-crank

  !> Crank AB = 5 clamped at A = (0, 0) turning at 15 rad/s, coupler BC = 11,
  !> C on a block of mass 3.5e-4 lb s^2/in (half the coupler's) sliding on
  !> the X axis (the §8.1 crank and coupler with a slider;
  !> inputs/slidercrank_*.nml at speed), one element per link, linear model,
  !> damped, spun up.  At 0.005 of the first natural frequency the stresses
  !> are those of rigid-body statics: the coupler is a beam pinned at B and
  !> pinned at C to the block, which the frictionless guide pushes along Y
  !> only, under the d'Alembert loads -rho A a(s) of its rigid motion and the
  !> block's -m a_C; the crank is a cantilever loaded at B by the coupler and
  !> stretched by its own centripetal inertia.  Compared: the largest |sigma| = |N|/A + |M| c/I
  !> over each link at 24 crank angles of one turn, to 2 % of the largest
  !> (N is element-wise constant in the model: linear axial shape functions).
  subroutine test_slider_crank_statics()
    real(dp), parameter :: omega = 15.0_dp, t_spin = 0.2_dp, r = 5.0_dp, l = 11.0_dp
    real(dp), parameter :: m_block = 3.5e-4_dp       ! half the coupler's mass
    integer, parameter :: n = 1, n_angles = 24
    type(mechanism_input_t) :: inp
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    type(stress_report_t), allocatable :: rep(:)
    real(dp), allocatable :: y(:)
    real(dp) :: t, theta, fe(2, n_angles), st(2, n_angles)
    integer :: k
    logical :: ok
    inp = slider_crank_input(r, l, 0.0_dp)
    inp%link_n_elements(1:2) = n
    inp%joint_mass(3) = m_block
    inp%omega = omega
    inp%profile = 'spinup'
    inp%spinup_time = t_spin
    call make_model(inp, element_effects_t(), 1.0e-4_dp, model, ok)
    if (.not. ok) return
    allocate(y(model%state_size()), rep(size(model%el)))
    y = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, state_atol(size(y), 1.0e-14_dp, 1.0e-8_dp), err, &
                  max_steps=200000)
    do k = 1, n_angles
      ! crank angle after the spin-up: omega t_spin/2 + omega (t - t_spin)
      theta = k*two_pi/n_angles
      t = t_spin + (theta + two_pi - 0.5_dp*omega*t_spin)/omega
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      call model%set_time(t)
      call model%element_stresses(y(1::2), rep)
      fe(1, k) = maxval(rep(1:n)%max_abs_stress)
      fe(2, k) = maxval(rep(n + 1:2*n)%max_abs_stress)
      st(:, k) = statics_peak_stress(r, l, omega, theta + two_pi, n, m_block)
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    if (err%failed()) return
    call assert_all_close(fe(1, :), st(1, :), 0.0_dp, 2.0e-2_dp*maxval(st(1, :)), 'crank peak stress vs statics')
    call assert_all_close(fe(2, :), st(2, :), 0.0_dp, 2.0e-2_dp*maxval(st(2, :)), 'coupler peak stress vs statics')
  end subroutine test_slider_crank_statics

  !> Largest |N|/A + |M| c/I in the crank (1) and the coupler (2) of a
  !> slider-crank (crank r at the origin turning at constant omega, coupler l,
  !> block of mass m_block on the X axis ahead of the crank pin) from
  !> rigid-body statics with d'Alembert loads; no rotary inertia (as in the
  !> linear model).  Each link
  !> is cut into n equal elements and N is averaged over each: the model's
  !> axial field is linear per element, so its element force is the element
  !> mean of the exact N (nodally exact bar elements); M is exact (the
  !> quintic element holds the quintic deflection of a linear load).
  function statics_peak_stress(r, l, omega, theta, n, m_block) result(s)
    real(dp), intent(in) :: r, l, omega, theta, m_block
    integer, intent(in) :: n
    real(dp) :: s(2)
    integer, parameter :: m = 480
    real(dp) :: phi, phid, phidd, e(2), ep(2), ab(2), a0_perp, a0_par, mu, x(0:m), qp(0:m), qa(0:m)
    real(dp) :: r_perp, r_par, big_m(0:m), big_n(0:m), c, total(2), pin(2), u(2), up(2), p_perp, p_par, h
    real(dp) :: a_cx, r_y, f_c(2)
    real(dp) :: n_mean, xs
    integer :: i, j, k, lo, hi
    mu = rho*area
    c = 0.5_dp*depth
    ! coupler angle from B to C, and its rates (C on the X axis: r sin(theta) + l sin(phi) = 0)
    phi = asin(-r*sin(theta)/l)
    phid = -r*omega*cos(theta)/(l*cos(phi))
    phidd = (r*omega**2*sin(theta)/l + phid**2*sin(phi))/cos(phi)
    e = [cos(phi), sin(phi)]
    ep = [-sin(phi), cos(phi)]
    ab = -r*omega**2*[cos(theta), sin(theta)]
    a0_perp = dot_product(ab, ep)
    a0_par = dot_product(ab, e)
    ! d'Alembert loads per unit length along the coupler (linear in x)
    h = l/m
    do i = 0, m
      x(i) = i*h
      qp(i) = -mu*(a0_perp + x(i)*phidd)
      qa(i) = -mu*(a0_par - x(i)*phid**2)
    end do
    ! moments about B fix the normal component r_perp of the force F_C of the
    ! block on the coupler; the block (mass m_block, acceleration a_C along X)
    ! is pushed by the guide along Y only: F_C = (-m_block a_C, R_y)
    r_perp = -(0.5_dp*mu*(-a0_perp)*l**2 + mu*(-phidd)*l**3/3.0_dp)/l   ! = -int x qp dx / l
    a_cx = -r*omega**2*cos(theta) - l*phidd*sin(phi) - l*phid**2*cos(phi)
    r_y = (r_perp - m_block*a_cx*sin(phi))/cos(phi)
    f_c = [-m_block*a_cx, r_y]
    r_par = dot_product(f_c, e)
    ! N and M at each station from the part [x, l] (trapezoid rule, fine grid)
    do i = 0, m
      big_m(i) = (l - x(i))*r_perp
      big_n(i) = r_par
      do j = i, m - 1
        big_m(i) = big_m(i) + 0.5_dp*h*((x(j) - x(i))*qp(j) + (x(j + 1) - x(i))*qp(j + 1))
        big_n(i) = big_n(i) + 0.5_dp*h*(qa(j) + qa(j + 1))
      end do
    end do
    s(2) = 0.0_dp
    do k = 1, n
      lo = (k - 1)*m/n
      hi = k*m/n
      n_mean = (sum(big_n(lo:hi)) - 0.5_dp*(big_n(lo) + big_n(hi)))/(hi - lo)
      s(2) = max(s(2), abs(n_mean)/area + maxval(abs(big_m(lo:hi)))*c/inertia)
    end do
    ! force of the coupler on the crank at B: the resultant of its loads and the guide reaction
    total = [0.5_dp*h*sum(qp(0:m - 1) + qp(1:m))*ep(1) + 0.5_dp*h*sum(qa(0:m - 1) + qa(1:m))*e(1), &
             0.5_dp*h*sum(qp(0:m - 1) + qp(1:m))*ep(2) + 0.5_dp*h*sum(qa(0:m - 1) + qa(1:m))*e(2)]
    pin = total + r_perp*ep + r_par*e
    u = [cos(theta), sin(theta)]
    up = [-sin(theta), cos(theta)]
    p_perp = dot_product(pin, up)
    p_par = dot_product(pin, u)
    ! crank at constant speed: centripetal inertia only (axial, N = p_par + mu omega^2 (r^2 - s^2)/2);
    ! bending M = p_perp (r - s), largest at the root in the first element
    xs = r/n
    n_mean = p_par + 0.5_dp*mu*omega**2*(r**2 - xs**2/3.0_dp)
    s(1) = abs(n_mean)/area + abs(p_perp*r)*c/inertia
  end function statics_peak_stress
end module test_transient_mechanism_suite

program test_transient_mechanism
  use test_transient_mechanism_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_mechanism')
end program test_transient_mechanism
