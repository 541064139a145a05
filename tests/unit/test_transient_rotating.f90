!> Verification of the transient analysis on a cantilever turning about its
!> clamped root (issue 3, item 3): the steady axial tip stretch against the
!> closed-form spinning bar, and the in-plane Southwell coefficient of the
!> first bending mode measured from a transient about the stretched state.
!> Setups, sources and measured values: doc/verification_transient.md.
module test_transient_rotating_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use element_effects, only: element_effects_t
  use beam_element, only: beam_local_displacement
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: mf_adams
  use linkage, only: mechanism_input_t
  use transient_fixtures
  use assertions
  implicit none
  private
  public :: run_all

  !> Southwell coefficient of the first flapwise mode of a uniform cantilever
  !> rotating about its root (zero hub radius), K1 = 1.1933 (Rayleigh's
  !> quotient with the non-rotating mode; the limit Omega -> 0 of the exact
  !> coefficient, e.g. Wright, Smith, Thresher & Wang, J. Appl. Mech. 49, 1982).
  real(dp), parameter :: southwell_flap = 1.1933_dp

contains

  subroutine run_all()
    call run_test('rotating_cantilever_steady_stretch', test_rotating_stretch)
    call run_test('rotating_cantilever_inplane_southwell_coefficient', test_southwell)
  end subroutine run_all

  function deep_cantilever(n, omega, h) result(inp)
    integer, intent(in) :: n
    real(dp), intent(in) :: omega, h
    type(mechanism_input_t) :: inp
    inp = cantilever_input(n, omega)
    inp%link_h(1) = h
  end function deep_cantilever

  !> Settled from the rigid state to 0.08 s: the local (u, w) at the tip of
  !> element n.
  subroutine settled_tip(model, n, uw, ok)
    type(mechanism_model_t), intent(inout), target :: model
    integer, intent(in) :: n
    real(dp), intent(out) :: uw(2)
    logical, intent(out) :: ok
    real(dp), allocatable :: y(:)
    allocate(y(model%state_size()))
    y = 0.0_dp
    uw = 0.0_dp
    call settle(model, y, 0.08_dp, ok)
    if (.not. ok) return
    call model%set_time(0.08_dp)
    uw = beam_local_displacement(model%el(n), model%table%gather(n, y(1::2)), model%rb(n)%phi, 1.0_dp)
  end subroutine settled_tip

  !> Steady axial tip displacement at Omega = 300 rad/s (stretching on, 2
  !> elements): the linear theory of a bar spinning about its root,
  !> u'' + k^2 (x + u) = 0, k = Omega sqrt(rho/E), u(0) = u'(L) = 0, gives
  !> u(L) = tan(kL)/k - L = rho Omega^2 L^3/(3E) (1 + 2/5 (kL)^2 + ...).
  !> Started at speed, damped (beta = 4e-3 s: the first bending mode
  !> critically damped, the axial modes overdamped, creeping at 1/beta), read
  !> at 0.08 s.  Measured within 0.5 % of the leading
  !> term (FORMULATION.md §8.3's check) and 1e-4 of the closed form (measured
  !> -1.7e-5: the linear axial elements' error for this Helmholtz-type
  !> equation, ~(kh)^2/12 with h = L/2).
  subroutine test_rotating_stretch()
    real(dp), parameter :: omega = 300.0_dp
    type(mechanism_model_t), target :: model
    real(dp) :: uw(2), kl, leading, exact
    logical :: ok
    integer, parameter :: n = 2
    call make_model(cantilever_input(n, omega), element_effects_t(stretching=.true., coupling=.true.), &
                    4.0e-3_dp, model, ok)
    if (.not. ok) return
    call settled_tip(model, n, uw, ok)
    if (.not. ok) return
    leading = rho*omega**2*beam_length**3/(3.0_dp*e1)
    kl = omega*beam_length*sqrt(rho/e1)
    exact = beam_length*(tan(kl)/kl - 1.0_dp)
    call assert_rel_close(uw(1), leading, 5.0e-3_dp, 'tip stretch vs rho Omega^2 L^3/(3E)')
    call assert_rel_close(uw(1), exact, 1.0e-4_dp, 'tip stretch vs tan(kL)/k - L')
    call assert_true(abs(uw(2)) < 1.0e-4_dp*uw(1), 'no steady transverse deflection: '//rtoa(uw(2)))
    ! the consistent element: quintic u holds the Helmholtz-type axial field far
    ! better than the linear u (measured relative error below)
    block
      type(mechanism_model_t), target :: cons
      call make_model(cantilever_input(n, omega), element_effects_t(stretching=.true., coupling=.true.), &
                      4.0e-3_dp, cons, ok, formulation='consistent')
      if (.not. ok) return
      call settled_tip(cons, n, uw, ok)
      if (.not. ok) return
      write(*, '(4x,a,es10.3)') 'consistent element: tip stretch relative error ', uw(1)/exact - 1.0_dp
      call assert_rel_close(uw(1), exact, 1.0e-7_dp, 'consistent element: tip stretch vs tan(kL)/k - L')
    end block
  end subroutine test_rotating_stretch

  !> Southwell's coefficient of the first mode of a uniform cantilever turning
  !> about its root (no hub): K1 = int T phi'^2 / (Omega^2 int rho A phi^2)
  !> with the centrifugal tension T = rho A Omega^2 (L^2 - x^2)/2 and the
  !> non-rotating mode phi (Rayleigh's quotient; exact as Omega -> 0).
  !> Simpson's rule on 2000 panels of the closed-form mode: 1.1933.
  real(dp) function southwell_rayleigh() result(k1)
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
    k1 = num/den
  end function southwell_rayleigh

  !> First in-plane bending frequency of a cantilever turning at Omega about
  !> its root.  The plane of the model is the plane of rotation, so the
  !> bending is in-plane (lead-lag): the centrifugal tension stiffens by
  !> K1 Omega^2 (Southwell; K1 = 1.1933, the flapwise coefficient) and the
  !> centrifugal field softens by Omega^2: omega^2 = omega0^2 + (K1 - 1) Omega^2.
  !> Slender beam (h = 0.25 in, L/r = 277: the Coriolis coupling with axial
  !> motion, -(2 Omega omega/omega_axial)^2, is 0.2 % of the shift), lambda =
  !> Omega/sqrt(EI/(rho A L^4)) = 1 (exact flapwise K1 there: 1.1919), 4
  !> elements, coupling off (with it on the coefficient converges only as h^2:
  !> +7 % at 4 elements, see doc/verification_transient.md).  Stretching on
  !> -> (K1 - 1) within 2 %; stretching off (no geometric stiffening) -> -1
  !> within 2 %.  Method: spin up, damp (first mode critically), perturb
  !> along the first mode, time the undamped tip oscillation over 3 periods.
  !> (Started at speed, beta = 1/omega0: the first mode decays at omega0/2,
  !> the overdamped axial modes creep at 1/beta; settled after 32/omega0.)
  subroutine test_southwell()
    real(dp) :: coefficient, k1
    logical :: ok
    k1 = southwell_rayleigh()
    call assert_rel_close(k1, southwell_flap, 1.0e-4_dp, 'Rayleigh-quotient Southwell coefficient K1')
    call southwell_coefficient(.true., 3, coefficient, ok)
    if (ok) call assert_rel_close(coefficient, k1 - 1.0_dp, 2.0e-2_dp, &
                                  'in-plane Southwell coefficient K1 - 1, stretching on')
    call southwell_coefficient(.false., 1, coefficient, ok)
    if (ok) call assert_rel_close(coefficient, -1.0_dp, 2.0e-2_dp, &
                                  'in-plane coefficient without stretching: centrifugal softening only')
  end subroutine test_southwell

  !> The coefficient measured over n_periods periods (one is plenty for the
  !> -1 of the case without stretching, a shift of 8 % in omega).
  subroutine southwell_coefficient(stretching, n_periods, coefficient, ok)
    logical, intent(in) :: stretching
    integer, intent(in) :: n_periods
    real(dp), intent(out) :: coefficient
    logical, intent(out) :: ok
    integer, parameter :: n = 4
    real(dp), parameter :: h = 0.25_dp
    real(dp) :: t_settle
    type(mechanism_model_t), target :: damped, model, at_rest
    type(element_effects_t) :: fx
    real(dp), allocatable :: y(:), omega_n(:), shapes(:, :)
    real(dp) :: big_omega, omega0, period, uw(2), ei, rho_a
    type(probe_t) :: p
    type(error_t) :: err
    coefficient = 0.0_dp
    fx = element_effects_t(stretching=stretching)
    ei = e1*width*h**3/12.0_dp
    rho_a = rho*width*h
    big_omega = sqrt(ei/(rho_a*beam_length**4))          ! lambda = 1
    ! omega0 of this mesh: the cantilever at rest
    call make_model(deep_cantilever(n, 0.0_dp, h), fx, 0.0_dp, at_rest, ok)
    if (.not. ok) return
    allocate(omega_n(at_rest%n), shapes(at_rest%n, at_rest%n))
    call at_rest%linear_modes(omega_n, shapes, err)
    omega0 = omega_n(1)
    call assert_rel_close(omega0, (bl_cantilever/beam_length)**2*sqrt(ei/rho_a), 1.0e-4_dp, 'cantilever omega0')
    ! steady state at Omega
    t_settle = 32.0_dp/omega0
    call make_model(deep_cantilever(n, big_omega, h), fx, 1.0_dp/omega0, damped, ok)
    if (.not. ok) return
    allocate(y(damped%state_size()))
    y = 0.0_dp
    call settle(damped, y, t_settle, ok)
    if (.not. ok) return
    ! undamped model, perturbed along the first mode at the current angle
    call make_model(deep_cantilever(n, big_omega, h), fx, 0.0_dp, model, ok)
    if (.not. ok) return
    call model%set_time(t_settle)
    call model%linear_modes(omega_n, shapes, err)
    p%kind = probe_local_w
    p%element = n
    p%xi = 1.0_dp
    p%offset = probe_value(p, model, t_settle, y)      ! the steady tip deflection (~0)
    call assert_true(abs(p%offset) < 1.0e-8_dp, 'settled: tip deflection '//rtoa(p%offset))
    uw = beam_local_displacement(model%el(n), model%table%gather(n, shapes(:, 1)), model%rb(n)%phi, 1.0_dp)
    y(1::2) = y(1::2) + 1.0e-3_dp*shapes(:, 1)/uw(2)
    call measure_period(model, y, t_settle, two_pi/omega0, n_periods, mf_adams, 1.0e-9_dp, 1.0e-14_dp, p, period, ok)
    if (.not. ok) return
    coefficient = ((two_pi/period)**2 - omega0**2)/big_omega**2
  end subroutine southwell_coefficient

end module test_transient_rotating_suite

program test_transient_rotating
  use test_transient_rotating_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_rotating')
end program test_transient_rotating
