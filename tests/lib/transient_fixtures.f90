!> Shared fixtures of the transient-analysis verification tests
!> (tests/unit/test_transient_*.f90): the FORMULATION.md §8.1 section and
!> material, models built as the decks build them (build_mechanism +
!> init_mechanism, and the motion table when the crank turns), a
!> zero-crossing period meter and tolerance helpers.
module transient_fixtures
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use element_effects, only: element_effects_t
  use beam_element, only: beam_local_displacement
  use mechanism_model, only: mechanism_model_t
  use joint_clearance, only: clearance_joint_t
  use joint_reactions, only: joint_reactions_t
  use lsode_solver, only: lsode_t, mf_bdf_full_fd
  use assertions, only: assert_true
  use linalg, only: solve_linear
  use test_text, only: itoa, rtoa   ! re-exported: the transient suites take them from here
  use mechanism_fixtures, only: fourbar_abcd   ! re-exported likewise
  implicit none
  private
  public :: e1, rho, width, depth, area, inertia, radius_gyration, beam_length, bl_clamped, bl_cantilever
  public :: probe_t, probe_modal, probe_local_w
  public :: beam_input, cantilever_input, fourbar_abcd, fourbar_input, make_model, all_effects, euler_bernoulli
  public :: mode_start, modal_probe, probe_value, measure_period, settle, state_atol, itoa, rtoa
  public :: rigid_fourbar_forces, rigid_limit_state, fourbar_unknowns

  ! FORMULATION.md §8.1 section (b = 0.25, h = 1 in) and aluminium.
  real(dp), parameter :: e1 = 10.87e6_dp, rho = 2.536e-4_dp, width = 0.25_dp, depth = 1.0_dp
  real(dp), parameter :: area = width*depth, inertia = width*depth**3/12.0_dp
  real(dp), parameter :: radius_gyration = depth/sqrt(12.0_dp)
  real(dp), parameter :: beam_length = 20.0_dp
  ! Euler-Bernoulli eigenvalues beta_n L: hinged n pi; clamped-clamped
  ! cos(bL) cosh(bL) = 1; clamped-free cos(bL) cosh(bL) = -1.
  real(dp), parameter :: bl_clamped(2) = [4.730040744862704_dp, 7.853204624095838_dp]
  real(dp), parameter :: bl_cantilever = 1.875104068711961_dp

  !> What a period measurement watches: the modal coordinate c.q, or the
  !> local transverse displacement of an element at x/l = xi, minus offset.
  type :: probe_t
    integer :: kind = 1
    real(dp), allocatable :: c(:)
    integer :: element = 0
    real(dp) :: xi = 1.0_dp
    real(dp) :: offset = 0.0_dp
  end type probe_t

  integer, parameter :: probe_modal = 1, probe_local_w = 2

contains

  ! ------------------------------------------------------------------ models

  !> A beam of n elements between two ground points (no driver).
  function beam_input(end_type, n) result(inp)
    character(len=*), intent(in) :: end_type
    integer, intent(in) :: n
    type(mechanism_input_t) :: inp
    inp%n_joints = 2
    inp%joint_type(1:2) = [character(len=16) :: end_type, end_type]
    inp%joint_x(1:2) = [0.0_dp, beam_length]
    inp%joint_y(1:2) = [0.0_dp, 0.0_dp]
    inp%n_links = 1
    inp%link_joint1(1) = 1
    inp%link_joint2(1) = 2
    inp%link_n_elements(1) = n
    inp%driver_link = 0
  end function beam_input

  !> A cantilever clamped to a shaft turning at omega about its root.
  function cantilever_input(n, omega) result(inp)
    integer, intent(in) :: n
    real(dp), intent(in) :: omega
    type(mechanism_input_t) :: inp
    inp%n_joints = 2
    inp%joint_type(1:2) = [character(len=16) :: 'clamp', 'free']
    inp%joint_x(1) = 0.0_dp
    inp%joint_y(1) = 0.0_dp
    inp%n_links = 1
    inp%link_joint1(1) = 1
    inp%link_joint2(1) = 2
    inp%link_length(1) = beam_length
    inp%link_n_elements(1) = n
    inp%omega = omega
  end function cantilever_input

  !> The four-bar of FORMULATION.md §8.1 (crank 5, coupler 11, rocker 10.5,
  !> D = (10, 0)) with n elements per link.
  function fourbar_input(n, omega, theta0_deg) result(inp)
    integer, intent(in) :: n
    real(dp), intent(in) :: omega, theta0_deg
    type(mechanism_input_t) :: inp
    inp = fourbar_abcd(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%link_n_elements(1:3) = n
    inp%omega = omega
    inp%theta0_deg = theta0_deg
  end function fourbar_input

  subroutine make_model(inp, effects, beta, model, ok, table, formulation, clearance)
    type(mechanism_input_t), intent(in) :: inp
    type(element_effects_t), intent(in) :: effects
    real(dp), intent(in) :: beta
    type(mechanism_model_t), intent(out) :: model
    logical, intent(out) :: ok
    logical, intent(in), optional :: table     !< tabulate a turning crank's motion (default yes)
    character(len=*), intent(in), optional :: formulation   !< default 'exact' (Kear's element)
    type(clearance_joint_t), intent(in), optional :: clearance(:)   !< clearance joints (default none)
    type(mechanism_t) :: mech
    type(error_t) :: err
    logical :: tabulate
    integer :: points
    type(clearance_joint_t), allocatable :: cj(:)
    tabulate = .true.
    if (present(table)) tabulate = table
    ! as the decks do (&transient kinematics = 'table'): the rigid motion of a
    ! turning crank tabulated once per revolution at 720 crank angles
    points = merge(720, 0, tabulate)
    allocate(cj(0))
    if (present(clearance)) cj = clearance
    call build_mechanism(inp, mech, err)
    if (.not. err%failed()) then
      if (present(formulation)) then
        call model%init_mechanism(mech, effects, formulation, beta, err, table_points=points, clearance=cj)
      else
        call model%init_mechanism(mech, effects, 'exact', beta, err, table_points=points, clearance=cj)
      end if
    end if
    call assert_true(.not. err%failed(), 'model: '//err%text())
    ok = .not. err%failed()
  end subroutine make_model

  function all_effects() result(fx)
    type(element_effects_t) :: fx
    fx = element_effects_t(.true., .true., .true., .true., .true.)
  end function all_effects

  !> Euler-Bernoulli frequency for eigenvalue beta L (length `l`).
  pure real(dp) function euler_bernoulli(beta_l, l)
    real(dp), intent(in) :: beta_l, l
    euler_bernoulli = (beta_l/l)**2*sqrt(e1*inertia/(rho*area))
  end function euler_bernoulli

  !> The linear modes of `model` (omega, shapes: allocated here) and a state
  !> at rest displaced along mode `mode`, scaled so that its largest entry,
  !> or with `at` its entry at DOF at, is `amplitude`: the start of the
  !> free-vibration, period and energy tests.
  subroutine mode_start(model, mode, amplitude, omega, shapes, y, err, at)
    type(mechanism_model_t), intent(inout) :: model
    integer, intent(in) :: mode
    real(dp), intent(in) :: amplitude
    real(dp), allocatable, intent(out) :: omega(:), shapes(:, :), y(:)
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: at
    allocate(omega(model%n), shapes(model%n, model%n), y(model%state_size()))
    call model%linear_modes(omega, shapes, err)
    y = 0.0_dp
    if (present(at)) then
      y(1::2) = amplitude*shapes(:, mode)/shapes(at, mode)
    else
      y(1::2) = amplitude*shapes(:, mode)/maxval(abs(shapes(:, mode)))
    end if
  end subroutine mode_start

  !> Probe on the modal coordinate of mode k: c = M0 x_k, so that c.q is the
  !> amplitude of mode k (M-orthonormal modes of the structure at rest).
  function modal_probe(model, shapes, k) result(p)
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: shapes(:, :)
    integer, intent(in) :: k
    type(probe_t) :: p
    real(dp) :: mass(model%n, model%n), stiff(model%n, model%n), q0(model%n)
    q0 = 0.0_dp
    call model%assemble_dense(q0, mass, stiff)
    p%kind = probe_modal
    allocate(p%c(model%n))
    p%c = matmul(mass, shapes(:, k))
  end function modal_probe

  real(dp) function probe_value(p, model, t, y) result(v)
    type(probe_t), intent(in) :: p
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: t, y(:)
    real(dp) :: uw(2), q(size(y)/2)
    q = y(1::2)
    if (p%kind == probe_modal) then
      v = dot_product(p%c, q)
    else
      call model%set_time(t)
      uw = beam_local_displacement(model%el(p%element), model%table%gather(p%element, q), &
                                   model%rb(p%element)%phi, p%xi)
      v = uw(2)
    end if
    v = v - p%offset
  end function probe_value

  !> Period from the zero crossings of the probe over n_periods periods,
  !> sampled every t_guess/100 (linear interpolation between samples: its
  !> error is third order in the sample step at a crossing of a sine).
  subroutine measure_period(model, y, t0, t_guess, n_periods, mf, rtol, atol, p, period, ok)
    type(mechanism_model_t), intent(inout), target :: model
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: t0, t_guess, rtol, atol
    integer, intent(in) :: n_periods, mf
    type(probe_t), intent(in) :: p
    real(dp), intent(out) :: period
    logical, intent(out) :: ok
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: dt, t, a, a_prev, first, last
    integer :: k, n_cross
    period = 0.0_dp
    dt = t_guess/100.0_dp
    call ode%init(size(y), t0, mf, rtol, [atol], err, max_steps=1000000)
    a_prev = probe_value(p, model, t0, y)
    n_cross = 0
    first = 0.0_dp
    last = 0.0_dp
    do k = 1, 300*(n_periods + 1)
      t = t0 + k*dt
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      a = probe_value(p, model, t, y)
      if (a*a_prev < 0.0_dp) then
        n_cross = n_cross + 1
        last = t - dt*a/(a - a_prev)
        if (n_cross == 1) first = last
        if (n_cross == 2*n_periods + 1) exit
      end if
      a_prev = a
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    ok = n_cross == 2*n_periods + 1 .and. .not. err%failed()
    call assert_true(ok, 'found '//itoa(2*n_periods + 1)//' zero crossings')
    if (ok) period = (last - first)/n_periods
  end subroutine measure_period

  !> Absolute tolerances for the interleaved state: atol_q on displacements,
  !> atol_qd on their rates.  The rates of the stiff (high-frequency,
  !> overdamped) components are pure round-off of M^-1 (F - K q); a rate
  !> tolerance as small as the displacement one makes BDF's corrector fail
  !> on that noise (measured: 30000+ order-1 steps instead of 4000).
  pure function state_atol(n_state, atol_q, atol_qd) result(a)
    integer, intent(in) :: n_state
    real(dp), intent(in) :: atol_q, atol_qd
    real(dp) :: a(n_state)
    a(1::2) = atol_q
    a(2::2) = atol_qd
  end function state_atol



  !> Integrate a damped system from the rigid state at t = 0 to t_end (BDF
  !> with DLSODE's finite-difference full Jacobian: the model's analytic one
  !> leaves out the damping term beta phi_dot K T^T J_b T, which is not small
  !> here (beta phi_dot ~ 0.5); see the doc, "known issues").
  subroutine settle(model, y, t_end, ok)
    type(mechanism_model_t), intent(inout), target :: model
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: t_end
    logical, intent(out) :: ok
    type(lsode_t) :: ode
    type(error_t) :: err
    call ode%init(size(y), 0.0_dp, mf_bdf_full_fd, 1.0e-9_dp, state_atol(size(y), 1.0e-12_dp, 1.0e-8_dp), err, &
                  max_steps=200000)
    call ode%integrate_to(model, y, t_end, err)
    call assert_true(.not. err%failed(), 'settling run: '//err%text())
    ok = .not. err%failed()
  end subroutine settle

  !> The rigid-limit tests of the joint-reaction and counterweight suites:
  !> crank angle 50 k deg (k = 0..6) of the crank turning at omega, its time
  !> t, and the quasi-static elastic state there, F(q, 0, t) = 0 from q = 0
  !> (one load step: deflections ~1e-8 in with links 1e6 times stiffer than
  !> aluminium).
  subroutine rigid_limit_state(model, omega, k, t, qq, err)
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: omega
    integer, intent(in) :: k
    real(dp), intent(out) :: t
    real(dp), intent(out) :: qq(:)
    type(error_t), intent(inout) :: err
    t = (50.0_dp*k*pi/180.0_dp)/omega
    qq = 0.0_dp
    call model%static_equilibrium(t, qq, 1, err)
  end subroutine rigid_limit_state

  !> rigid_fourbar_forces' unknowns read from the four-bar's link-end
  !> reactions (ends A, B, B, C, C, D in deck order): F_A, T_A on the crank,
  !> F_B on the coupler, F_C on the rocker, F_D on the rocker.
  function fourbar_unknowns(jr) result(x)
    type(joint_reactions_t), intent(in) :: jr
    real(dp) :: x(9)
    x = [jr%ends(1)%force, jr%ends(1)%moment, jr%ends(3)%force, jr%ends(5)%force, jr%ends(6)%force]
  end function fourbar_unknowns

  !> A cantilever of in-plane depth h turning at omega about its clamped root.
  !> The rigid §8.1 four-bar's Newton-Euler equations at crank angle th
  !> (crank turning at w, no angular acceleration), from closed-form
  !> position, velocity and acceleration loops on the branch of the model's
  !> coupler; slender-rod inertias m L^2/12 (the linear model has no rotary
  !> inertia).  Unknowns x = [F_A(2), T_A, F_B(2), F_C(2), F_D(2)]: F_B crank
  !> on coupler, F_C coupler on rocker, F_A, F_D ground on crank, rocker;
  !> moments about each link's centre.  m: link masses; a_g: their centres'
  !> accelerations.  With m_cw, c_crank, c_rocker: point counterweights
  !> turning with the crank about A and the rocker about D (local offsets).
  !> The reference of the joint-reaction and counterweight suites.
  subroutine rigid_fourbar_forces(model, th, w, x, m, a_g, m_cw, c_crank, c_rocker)
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: th, w
    real(dp), intent(out) :: x(9), m(3), a_g(2, 3)
    real(dp), intent(in), optional :: m_cw(2), c_crank(2), c_rocker(2)
    real(dp), parameter :: r2 = 5.0_dp, r3 = 11.0_dp, r4 = 10.5_dp, d(2) = [10.0_dp, 0.0_dp]
    real(dp) :: a(9, 9), b(2), c(2), e3(2), e4(2), n3(2), n4(2), e2(2), n2(2), w3, w4, al3, al4
    real(dp) :: mat(2, 2), rhs(2), g2(2), g3(2), g4(2), ig(3), dist, h, base(2), perp(2), c_alt(2), a_b(2)
    real(dp) :: p2(2), p4(2), f2(2), f4(2)
    type(error_t) :: err
    e2 = [cos(th), sin(th)]
    n2 = [-e2(2), e2(1)]
    b = r2*e2
    ! C on both circles; the branch of the model's coupler
    dist = norm2(d - b)
    h = (r3**2 - r4**2 + dist**2)/(2.0_dp*dist)
    base = b + h*(d - b)/dist
    perp = [-(d(2) - b(2)), d(1) - b(1)]/dist*sqrt(r3**2 - h**2)
    c = base + perp
    c_alt = base - perp
    if (abs(angle_diff(atan2(c_alt(2) - b(2), c_alt(1) - b(1)), model%rb(2)%phi)) < &
        abs(angle_diff(atan2(c(2) - b(2), c(1) - b(1)), model%rb(2)%phi))) c = c_alt
    e3 = (c - b)/r3
    e4 = (c - d)/r4
    n3 = [-e3(2), e3(1)]
    n4 = [-e4(2), e4(1)]
    ! velocities: r2 w n2 + r3 w3 n3 = r4 w4 n4
    mat(:, 1) = r3*n3
    mat(:, 2) = -r4*n4
    rhs = -r2*w*n2
    call solve_linear(mat, rhs, err)
    w3 = rhs(1)
    w4 = rhs(2)
    ! accelerations: -r2 w^2 e2 + r3 (al3 n3 - w3^2 e3) = r4 (al4 n4 - w4^2 e4)
    rhs = r2*w**2*e2 + r3*w3**2*e3 - r4*w4**2*e4
    call solve_linear(mat, rhs, err)
    al3 = rhs(1)
    al4 = rhs(2)
    a_b = -r2*w**2*e2
    a_g(:, 1) = 0.5_dp*a_b
    a_g(:, 2) = a_b + 0.5_dp*r3*(al3*n3 - w3**2*e3)
    a_g(:, 3) = 0.5_dp*r4*(al4*n4 - w4**2*e4)
    m = model%el(1)%material%rho*model%el(1)%area*[r2, r3, r4]
    ig = m*[r2, r3, r4]**2/12.0_dp
    g2 = 0.5_dp*b
    g3 = 0.5_dp*(b + c)
    g4 = 0.5_dp*(c + d)
    ! the counterweights and their inertia forces m a
    f2 = 0.0_dp
    f4 = 0.0_dp
    p2 = g2
    p4 = g4
    if (present(m_cw) .and. present(c_crank) .and. present(c_rocker)) then
      p2 = c_crank(1)*e2 + c_crank(2)*n2
      p4 = d + c_rocker(1)*e4 + c_rocker(2)*n4
      f2 = -m_cw(1)*w**2*p2
      f4 = m_cw(2)*(al4*[-(p4(2) - d(2)), p4(1) - d(1)] - w4**2*(p4 - d))
    end if
    a = 0.0_dp
    ! crank: F_A - F_B = m2 a2 (+ f2); T_A + (A - G2) x F_A - (B - G2) x F_B = (P2 - G2) x f2
    a(1, 1) = 1.0_dp; a(1, 4) = -1.0_dp
    a(2, 2) = 1.0_dp; a(2, 5) = -1.0_dp
    a(3, 3) = 1.0_dp
    a(3, 1:2) = cross_row(-g2)
    a(3, 4:5) = -cross_row(b - g2)
    ! coupler: F_B - F_C = m3 a3; (B - G3) x F_B - (C - G3) x F_C = I3 al3
    a(4, 4) = 1.0_dp; a(4, 6) = -1.0_dp
    a(5, 5) = 1.0_dp; a(5, 7) = -1.0_dp
    a(6, 4:5) = cross_row(b - g3)
    a(6, 6:7) = -cross_row(c - g3)
    ! rocker: F_C + F_D = m4 a4 (+ f4); (C - G4) x F_C + (D - G4) x F_D = I4 al4 + (P4 - G4) x f4
    a(7, 6) = 1.0_dp; a(7, 8) = 1.0_dp
    a(8, 7) = 1.0_dp; a(8, 9) = 1.0_dp
    a(9, 6:7) = cross_row(c - g4)
    a(9, 8:9) = cross_row(d - g4)
    x = [m(1)*a_g(:, 1) + f2, dot_product(cross_row(p2 - g2), f2), m(2)*a_g(:, 2), ig(2)*al3, &
         m(3)*a_g(:, 3) + f4, ig(3)*al4 + dot_product(cross_row(p4 - g4), f4)]
    call solve_linear(a, x, err)
    call assert_true(.not. err%failed(), 'Newton-Euler system: '//err%text())
  end subroutine rigid_fourbar_forces

  !> Coefficients of F in r x F = r(1) F(2) - r(2) F(1).
  pure function cross_row(r) result(c)
    real(dp), intent(in) :: r(2)
    real(dp) :: c(2)
    c = [-r(2), r(1)]
  end function cross_row

  pure real(dp) function angle_diff(a, b)
    real(dp), intent(in) :: a, b
    angle_diff = modulo(a - b + pi, two_pi) - pi
  end function angle_diff
end module transient_fixtures
