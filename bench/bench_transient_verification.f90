!> The verification cases of doc/verification_transient.md as tables: beam
!> frequencies and periods against elements per beam, the large-amplitude
!> frequency ratio of the hinged beam against the exact Duffing value, the
!> spinning cantilever's stretch and in-plane Southwell coefficient (mesh,
!> slenderness, coupling), energy drift against rtol, the rigid limit.  The
!> unit tests (tests/unit/test_transient_*.f90) check the same cases with
!> tolerances; this program prints the numbers behind them, with the same
!> fixtures (tests/lib/transient_fixtures.f90, linked into the benchmarks).
program bench_transient_verification
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t
  use element_effects, only: element_effects_t
  use beam_element, only: beam_local_displacement
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: lsode_t, mf_adams, mf_bdf_full_user
  use transient_fixtures   ! the verification tests' own fixtures (tests/lib)
  implicit none
  character(len=16), parameter :: ends(2) = [character(len=16) :: 'ground_pin', 'clamp']
  integer, parameter :: ns(4) = [1, 2, 4, 8]
  real(dp), parameter :: a_over_r(4) = [0.5_dp, 1.0_dp, 1.5_dp, 2.0_dp]
  real(dp), parameter :: speeds(3) = [100.0_dp, 300.0_dp, 500.0_dp]
  real(dp), parameter :: rtols(7) = [1.0e-4_dp, 1.0e-5_dp, 1.0e-6_dp, 1.0e-7_dp, 1.0e-8_dp, 1.0e-9_dp, 1.0e-10_dp]
  integer :: ie, i, k, j
  real(dp) :: theory_h(2), rayleigh(2)
  real(dp) :: bl(2, 2), theory(2), omega_fe(2), period(2), t_lin, ratio, cpu0, cpu1, drift, coefficient, k1
  logical :: ok

  bl(:, 1) = [pi, 2*pi]
  bl(:, 2) = bl_clamped
  theory_h = [euler_bernoulli(pi, beam_length), euler_bernoulli(2*pi, beam_length)]
  rayleigh = theory_h/sqrt(1.0_dp + (radius_gyration*[pi, 2*pi]/beam_length)**2)

  ! ---- 1. beams
  print '(a)', '## 1. Beams with immovable ends: frequency (eigenvalue) and period (transient) errors against'
  print '(a)', 'Euler-Bernoulli (all effects on except rotary inertia; 1e-3 in from rest, 3 periods, Adams rtol 1e-9)'
  print '(a)', ''
  print '(a)', '| ends | elements | omega_1 error | omega_2 error | T_1 error (transient) | T_2 error (transient) |'
  print '(a)', '|---|---|---|---|---|---|'
  do ie = 1, 2
    theory = [euler_bernoulli(bl(1, ie), beam_length), euler_bernoulli(bl(2, ie), beam_length)]
    do i = 1, size(ns)
      do k = 1, 2
        call beam_period(ends(ie), ns(i), k, theory(k), .false., omega_fe(k), period(k))
      end do
      print '(a,a,a,i0,4(a,es10.2),a)', '| ', trim(ends(ie)), ' | ', ns(i), ' | ', omega_fe(1)/theory(1) - 1.0_dp, ' | ', &
        omega_fe(2)/theory(2) - 1.0_dp, ' | ', period(1)*theory(1)/two_pi - 1.0_dp, ' | ', &
        period(2)*theory(2)/two_pi - 1.0_dp, ' |'
    end do
  end do
  print '(a)', ''
  print '(a)', 'With rotary inertia on: hinged beam against Rayleigh''s beam, omega^2 = EI k^4/(rho A (1 + r^2 k^2)):'
  print '(a)', ''
  print '(a)', '| elements | T_1 error vs Rayleigh | T_2 error vs Rayleigh | T_1 vs Euler-Bernoulli | T_2 vs Euler-Bernoulli |'
  print '(a)', '|---|---|---|---|---|'
  do i = 2, size(ns)
    do k = 1, 2
      call beam_period('ground_pin', ns(i), k, theory_h(k), .true., omega_fe(k), period(k))
    end do
    print '(a,i0,4(a,es10.2),a)', '| ', ns(i), ' | ', period(1)*rayleigh(1)/two_pi - 1.0_dp, ' | ', &
      period(2)*rayleigh(2)/two_pi - 1.0_dp, ' | ', period(1)*theory_h(1)/two_pi - 1.0_dp, ' | ', &
      period(2)*theory_h(2)/two_pi - 1.0_dp, ' |'
  end do
  print '(a)', ''

  ! ---- 2. large amplitude
  print '(a)', '## 2. Hinged beam, immovable ends, stretching on: omega_NL/omega_L against a/r'
  print '(a)', ''
  print '(a)', '| a/r | exact Duffing | sqrt(1 + 3/16 (a/r)^2) | 4 elements | 8 elements | 16 elements | error at 8 | error at 16 |'
  print '(a)', '|---|---|---|---|---|---|---|---|'
  block
    real(dp) :: r4(4), r8(4), r16(4), tl(3)
    integer, parameter :: nl(3) = [4, 8, 16]
    do j = 1, 3
      call hinged_period(nl(j), 1.0e-3_dp, tl(j), ok)
    end do
    do i = 1, size(a_over_r)
      call hinged_period(4, a_over_r(i), t_lin, ok)
      r4(i) = tl(1)/t_lin
      call hinged_period(8, a_over_r(i), t_lin, ok)
      r8(i) = tl(2)/t_lin
      call hinged_period(16, a_over_r(i), t_lin, ok)
      r16(i) = tl(3)/t_lin
      ratio = duffing_frequency_ratio(a_over_r(i))
      print '(a,f4.2,6(a,f8.5),2(a,es9.2),a)', '| ', a_over_r(i), ' | ', ratio, ' | ', &
        sqrt(1.0_dp + 3.0_dp/16.0_dp*a_over_r(i)**2), ' | ', r4(i), ' | ', r8(i), ' | ', r16(i), ' | ', &
        r8(i)/ratio - 1.0_dp, ' | ', r16(i)/ratio - 1.0_dp, ' |'
    end do
  end block
  print '(a)', ''

  ! ---- 3. rotating cantilever
  print '(a)', '## 3a. Spinning cantilever (L = 20, h = 1 in, 2 elements, stretching on): steady tip stretch'
  print '(a)', ''
  print '(a)', '| Omega (rad/s) | FE u(L) (in) | rho Omega^2 L^3/(3E) | tan(kL)/k - L | error vs leading | error vs tan |'
  print '(a)', '|---|---|---|---|---|---|'
  do i = 1, size(speeds)
    block
      real(dp) :: u_tip, leading, exact, kl
      call tip_stretch(speeds(i), u_tip)
      leading = rho*speeds(i)**2*beam_length**3/(3.0_dp*e1)
      kl = speeds(i)*beam_length*sqrt(rho/e1)
      exact = beam_length*(tan(kl)/kl - 1.0_dp)
      print '(a,f5.0,3(a,es12.5),2(a,es9.2),a)', '| ', speeds(i), ' | ', u_tip, ' | ', leading, ' | ', exact, ' | ', &
        u_tip/leading - 1.0_dp, ' | ', u_tip/exact - 1.0_dp, ' |'
    end block
  end do
  print '(a)', ''
  k1 = southwell_rayleigh()
  print '(a,f7.4,a)', '## 3b. In-plane Southwell coefficient at lambda = 1 (Rayleigh K1 = ', k1, &
    '; in-plane target K1 - 1)'
  print '(a)', ''
  print '(a)', '| h (in) | L/r | coupling | elements | (omega^2 - omega0^2)/Omega^2 | vs K1 - 1 |'
  print '(a)', '|---|---|---|---|---|---|'
  block
    real(dp), parameter :: hs(2) = [1.0_dp, 0.25_dp]
    integer, parameter :: nsw(3) = [2, 4, 8]
    logical :: coupling
    integer :: ih, ic, in
    do ih = 1, 2
      do ic = 1, 2
        coupling = ic == 2
        do in = 1, 3
          if (ih == 2 .and. in == 3 .and. .not. coupling) cycle
          call southwell_coefficient(hs(ih), nsw(in), .true., coupling, coefficient, ok)
          print '(a,f4.2,a,f5.0,a,l1,a,i0,a,f8.5,a,es9.2,a)', '| ', hs(ih), ' | ', beam_length*sqrt(12.0_dp)/hs(ih), &
            ' | ', coupling, ' | ', nsw(in), ' | ', coefficient, ' | ', coefficient/(k1 - 1.0_dp) - 1.0_dp, ' |'
        end do
      end do
    end do
    call southwell_coefficient(0.25_dp, 4, .false., .false., coefficient, ok)
    print '(a,f8.5,a)', '| 0.25 | 277 | F (stretching off) | 4 | ', coefficient, ' | (target -1) |'
  end block
  print '(a)', ''

  ! ---- 4. energy
  print '(a)', '## 4. Four-bar, driver stopped (crank at 60 deg), all effects on, 100 periods undamped: energy drift'
  print '(a)', ''
  print '(a)', '| rtol | max relative drift of KE + SE | drift / rtol | CPU s |'
  print '(a)', '|---|---|---|---|'
  do i = 1, size(rtols)
    call cpu_time(cpu0)
    call energy_drift(rtols(i), drift, ok)
    call cpu_time(cpu1)
    print '(a,es7.0,a,es10.3,a,f8.2,a,f7.2,a)', '| ', rtols(i), ' | ', drift, ' | ', drift/rtols(i), ' | ', cpu1 - cpu0, ' |'
  end do
  print '(a)', ''

  ! ---- 5. rigid limit
  print '(a)', '## 5. Rigid limit: four-bar at 15 rad/s, linear, largest joint deformation in the second turn x E/E0'
  print '(a)', ''
  print '(a)', '| E / E0 | largest joint deformation x E/E0 (in) | ratio to E0 |'
  print '(a)', '|---|---|---|'
  block
    real(dp) :: d0, d
    real(dp), parameter :: scales(3) = [1.0_dp, 1.0e2_dp, 1.0e4_dp]
    do i = 1, 3
      call quasi_static_peak(scales(i), d)
      if (i == 1) d0 = d
      print '(a,es7.0,a,es12.5,a,f9.6,a)', '| ', scales(i), ' | ', d*scales(i), ' | ', d*scales(i)/d0, ' |'
    end do
  end block

contains

  !> Eigen frequency of mode k and the period measured from a release from
  !> it (all effects on, rotary inertia as given, 1e-3 in, 3 periods, Adams
  !> rtol 1e-9).
  subroutine beam_period(end_type, n, k, omega_theory, rotary, omega_k, period_k)
    character(len=*), intent(in) :: end_type
    integer, intent(in) :: n, k
    logical, intent(in) :: rotary
    real(dp), intent(in) :: omega_theory
    real(dp), intent(out) :: omega_k, period_k
    type(mechanism_model_t), target :: model
    real(dp), allocatable :: omega(:), shapes(:, :), y(:)
    type(probe_t) :: p
    type(error_t) :: err
    type(element_effects_t) :: fx
    logical :: okk
    fx = all_effects()
    fx%rotary_inertia = rotary
    call make_model(beam_input(end_type, n), fx, 0.0_dp, model, okk)
    allocate(omega(model%n), shapes(model%n, model%n), y(model%state_size()))
    call model%linear_modes(omega, shapes, err)
    omega_k = omega(k)
    y = 0.0_dp
    y(1::2) = 1.0e-3_dp*shapes(:, k)/maxval(abs(shapes(:, k)))
    p = modal_probe(model, shapes, k)
    call measure_period(model, y, 0.0_dp, two_pi/omega_theory, 3, mf_adams, 1.0e-9_dp, 1.0e-14_dp, p, period_k, okk)
  end subroutine beam_period

  pure real(dp) function duffing_frequency_ratio(a_r) result(ratio)
    real(dp), intent(in) :: a_r
    real(dp) :: e, k2, a, b, c
    integer :: i
    e = a_r**2/4.0_dp
    k2 = e/(2.0_dp*(1.0_dp + e))
    a = 1.0_dp
    b = sqrt(1.0_dp - k2)
    do i = 1, 40
      c = 0.5_dp*(a + b)
      b = sqrt(a*b)
      a = c
    end do
    ratio = pi*sqrt(1.0_dp + e)/(2.0_dp*(pi/(2.0_dp*a)))
  end function duffing_frequency_ratio

  subroutine hinged_period(n, a_r, period, okk)
    integer, intent(in) :: n
    real(dp), intent(in) :: a_r
    real(dp), intent(out) :: period
    logical, intent(out) :: okk
    type(mechanism_model_t), target :: model
    real(dp), allocatable :: omega(:), shapes(:, :), y(:)
    type(probe_t) :: p
    type(error_t) :: err
    integer :: mid
    call make_model(beam_input('ground_pin', n), element_effects_t(stretching=.true.), 0.0_dp, model, okk)
    allocate(omega(model%n), shapes(model%n, model%n), y(model%state_size()))
    call model%linear_modes(omega, shapes, err)
    mid = model%table%unknown(6, n/2)
    y = 0.0_dp
    y(1::2) = a_r*radius_gyration*shapes(:, 1)/shapes(mid, 1)
    p%kind = probe_modal
    allocate(p%c(model%n))
    p%c = 0.0_dp
    p%c(mid) = 1.0_dp
    call measure_period(model, y, 0.0_dp, two_pi/omega(1), 4, mf_adams, 1.0e-9_dp, 1.0e-13_dp, p, period, okk)
  end subroutine hinged_period

  subroutine tip_stretch(omega, u_tip)
    real(dp), intent(in) :: omega
    real(dp), intent(out) :: u_tip
    type(mechanism_model_t), target :: model
    real(dp), allocatable :: y(:)
    real(dp) :: uw(2)
    logical :: okk
    call make_model(cantilever_input(2, omega), element_effects_t(stretching=.true., coupling=.true.), 4.0e-3_dp, &
                    model, okk)
    allocate(y(model%state_size()))
    y = 0.0_dp
    call settle(model, y, 0.08_dp, okk)
    call model%set_time(0.08_dp)
    uw = beam_local_displacement(model%el(2), model%table%gather(2, y(1::2)), model%rb(2)%phi, 1.0_dp)
    u_tip = uw(1)
  end subroutine tip_stretch

  real(dp) function southwell_rayleigh() result(kk)
    integer, parameter :: m = 2000
    real(dp) :: x, b, sg, num, den, w, dphi, phi
    integer :: i
    b = bl_cantilever
    sg = (cosh(b) + cos(b))/(sinh(b) + sin(b))
    num = 0.0_dp
    den = 0.0_dp
    do i = 0, m
      x = real(i, dp)/m
      w = merge(1.0_dp, merge(4.0_dp, 2.0_dp, mod(i, 2) == 1), i == 0 .or. i == m)/(3.0_dp*m)
      phi = cosh(b*x) - cos(b*x) - sg*(sinh(b*x) - sin(b*x))
      dphi = b*(sinh(b*x) + sin(b*x) - sg*(cosh(b*x) - cos(b*x)))
      num = num + w*0.5_dp*(1.0_dp - x*x)*dphi**2
      den = den + w*phi**2
    end do
    kk = num/den
  end function southwell_rayleigh

  !> As tests/unit/test_transient_rotating.f90, for any depth, mesh and coupling.
  subroutine southwell_coefficient(h, n, stretching, coupling, coef, okk)
    real(dp), intent(in) :: h
    integer, intent(in) :: n
    logical, intent(in) :: stretching, coupling
    real(dp), intent(out) :: coef
    logical, intent(out) :: okk
    type(mechanism_model_t), target :: damped, model, at_rest
    type(element_effects_t) :: fx
    real(dp), allocatable :: y(:), omega_n(:), shapes(:, :)
    real(dp) :: big_omega, omega0, per, uw(2), ei, rho_a, t_settle
    type(probe_t) :: p
    type(error_t) :: err
    type(mechanism_input_t) :: inp
    coef = 0.0_dp
    fx = element_effects_t(stretching=stretching, coupling=coupling)
    ei = e1*width*h**3/12.0_dp
    rho_a = rho*width*h
    big_omega = sqrt(ei/(rho_a*beam_length**4))
    inp = cantilever_input(n, 0.0_dp)
    inp%link_h(1) = h
    call make_model(inp, fx, 0.0_dp, at_rest, okk)
    allocate(omega_n(at_rest%n), shapes(at_rest%n, at_rest%n))
    call at_rest%linear_modes(omega_n, shapes, err)
    omega0 = omega_n(1)
    t_settle = 32.0_dp/omega0
    inp%omega = big_omega
    call make_model(inp, fx, 1.0_dp/omega0, damped, okk)
    allocate(y(damped%state_size()))
    y = 0.0_dp
    call settle(damped, y, t_settle, okk)
    if (.not. okk) return
    call make_model(inp, fx, 0.0_dp, model, okk)
    call model%set_time(t_settle)
    call model%linear_modes(omega_n, shapes, err)
    p%kind = probe_local_w
    p%element = n
    p%xi = 1.0_dp
    p%offset = probe_value(p, model, t_settle, y)
    uw = beam_local_displacement(model%el(n), model%table%gather(n, shapes(:, 1)), model%rb(n)%phi, 1.0_dp)
    y(1::2) = y(1::2) + 1.0e-3_dp*shapes(:, 1)/uw(2)
    call measure_period(model, y, t_settle, two_pi/omega0, 4, mf_adams, 1.0e-9_dp, 1.0e-14_dp, p, per, okk)
    if (okk) coef = ((two_pi/per)**2 - omega0**2)/big_omega**2
  end subroutine southwell_coefficient

  subroutine energy_drift(rtol, drift_max, okk)
    real(dp), intent(in) :: rtol
    real(dp), intent(out) :: drift_max
    logical, intent(out) :: okk
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:), omega(:), shapes(:, :)
    real(dp) :: ke, se, e0, t_half
    integer :: kk
    call make_model(fourbar_input(1, 0.0_dp, 60.0_dp), all_effects(), 0.0_dp, model, okk)
    allocate(y(model%state_size()), omega(model%n), shapes(model%n, model%n))
    call model%linear_modes(omega, shapes, err)
    y = 0.0_dp
    y(1::2) = 0.02_dp*shapes(:, 1)/maxval(abs(shapes(:, 1)))
    call model%energies(0.0_dp, y(1::2), y(2::2), ke, se)
    e0 = ke + se
    call ode%init(size(y), 0.0_dp, mf_adams, rtol, [1.0e-5_dp*rtol], err, max_steps=1000000)
    t_half = pi/omega(1)
    drift_max = 0.0_dp
    do kk = 1, 200
      call ode%integrate_to(model, y, kk*t_half, err)
      if (err%failed()) exit
      call model%energies(kk*t_half, y(1::2), y(2::2), ke, se)
      drift_max = max(drift_max, abs(ke + se - e0)/e0)
    end do
    okk = .not. err%failed()
  end subroutine energy_drift

  subroutine quasi_static_peak(scale, dmax)
    real(dp), intent(in) :: scale
    real(dp), intent(out) :: dmax
    real(dp), parameter :: omega = 15.0_dp, t_spin = 0.2_dp
    type(mechanism_input_t) :: inp
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:)
    real(dp) :: t, qe(8)
    integer :: kk
    logical :: okk
    inp = fourbar_input(1, omega, 0.0_dp)
    inp%profile = 'spinup'
    inp%spinup_time = t_spin
    inp%link_e1(1:3) = scale*inp%link_e1(1:3)
    inp%link_e2(1:3) = scale*inp%link_e2(1:3)
    call make_model(inp, element_effects_t(), min(2.0e-5_dp, 2.0_dp/(1462.0_dp*sqrt(scale))), model, okk)
    allocate(y(model%state_size()))
    y = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_bdf_full_user, 1.0e-8_dp, state_atol(size(y), 1.0e-14_dp/scale, 1.0e-8_dp/scale), &
                  err, max_steps=200000)
    dmax = 0.0_dp
    do kk = 1, 72
      t = t_spin + two_pi/omega + kk*two_pi/omega/72.0_dp
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      qe = model%table%gather(1, y(1::2))
      dmax = max(dmax, maxval(abs(qe(5:6))))
      qe = model%table%gather(2, y(1::2))
      dmax = max(dmax, maxval(abs(qe(5:6))))
    end do
  end subroutine quasi_static_peak
end program bench_transient_verification
