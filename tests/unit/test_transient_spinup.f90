!> The spin-up beam of Kane, Ryan & Banerjee (J. Guidance 10(2), 1987;
!> issue 10, verification 2): a cantilever clamped to a hub of zero radius,
!> L = 8 m, E = 6.9e10 Pa, rho = 2766.67 kg/m^3, A = 7.2968e-5 m^2,
!> I = 8.2189e-9 m^4, no gravity or damping, hub angle
!> theta = (Ws/Ts)(t^2/2 + (Ts/2 pi)^2 (cos(2 pi t/Ts) - 1)) for t < Ts = 15 s,
!> then constant Ws (the driver's 'spinup' profile).  Watched: the tip
!> transverse deflection in the rotating (link) frame over 0..20 s.
!>
!> What is checked: the consistent element converges with the mesh (the
!> minimum tip deflection at 4 and 8 elements within 1 % of each other and
!> of 16), it lies in the range of the published curves (about -0.5 m at
!> Ws = 4 rad/s), and Kear's element with exact stretching gives a much
!> smaller, mesh-dependent answer (locking).  The 32-element runs and the
!> Ws = 10 rad/s case are in inputs/spinup_*.nml (doc/verification_transient.md).
module test_transient_spinup_suite
  use kinds, only: dp
  use error_status, only: error_t
  use element_effects, only: element_effects_t
  use beam_element, only: beam_local_displacement
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: lsode_t, mf_bdf_full_user
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use transient_fixtures, only: state_atol, cantilever_input
  use assertions
  implicit none
  private
  public :: run_all, spinup_minimum

contains

  subroutine run_all()
    call run_test('spinup_beam_ws4_converges_with_mesh', test_convergence)
    call run_test('spinup_beam_kear_element_locks', test_kear_locks)
  end subroutine run_all

  function spinup_input(n, ws) result(inp)
    integer, intent(in) :: n
    real(dp), intent(in) :: ws
    type(mechanism_input_t) :: inp
    inp = cantilever_input(n, ws)
    inp%link_length(1) = 8.0_dp
    inp%link_section(1) = 'general'
    inp%link_area(1) = 7.2968e-5_dp
    inp%link_c(1) = 0.0183824_dp
    inp%link_inertia(1) = 8.2189e-9_dp
    inp%link_e1(1) = 6.9e10_dp
    inp%link_e2(1) = 0.0_dp
    inp%link_rho(1) = 2766.67_dp
    inp%profile = 'spinup'
    inp%spinup_time = 15.0_dp
  end function spinup_input

  !> Minimum over 0..t_end of the tip transverse deflection in the rotating
  !> frame (sampled every 0.02 s, refined by a parabola through the three
  !> samples around the smallest), and the time of the minimum.
  subroutine spinup_minimum(n, ws, formulation, t_end, w_min, t_min, ok)
    integer, intent(in) :: n
    real(dp), intent(in) :: ws, t_end
    character(len=*), intent(in) :: formulation
    real(dp), intent(out) :: w_min, t_min
    logical, intent(out) :: ok
    type(mechanism_model_t), target :: model
    type(mechanism_t) :: mech
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:), w(:)
    real(dp), parameter :: dt = 0.02_dp
    real(dp) :: uw(2), a, b, c
    integer :: k, nk, kmin
    w_min = 0.0_dp
    t_min = 0.0_dp
    call build_mechanism(spinup_input(n, ws), mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, element_effects_t(stretching=.true., curvature=.true., &
                                                      coupling=.true.), formulation, 0.0_dp, err, table_points=720)
    ok = .not. err%failed()
    call assert_true(ok, 'model: '//err%text())
    if (.not. ok) return
    allocate(y(model%state_size()))
    y = 0.0_dp
    nk = nint(t_end/dt)
    allocate(w(0:nk))
    w = 0.0_dp
    ! rtol 1e-6 (the minimum moves by 6e-4 relative to rtol 1e-8); BDF of
    ! order <= 2 (A-stable): the undamped axial modes (omega ~ 1e3..1e6 rad/s)
    ! sit on the imaginary axis where BDF 3-5 are unstable, and DLSODE then
    ! crawls at h ~ 1e-5 s (measured: 1.6e6 steps instead of 3e3)
    call ode%init(size(y), 0.0_dp, mf_bdf_full_user, 1.0e-6_dp, state_atol(size(y), 1.0e-7_dp, 1.0e-4_dp), err, &
                  max_steps=500000)
    call ode%limit_order(2)
    do k = 1, nk
      call ode%integrate_to(model, y, k*dt, err)
      if (err%failed()) exit
      call model%set_time(k*dt)
      uw = beam_local_displacement(model%el(n), model%table%gather(n, y(1::2)), model%rb(n)%phi, 1.0_dp)
      w(k) = uw(2)
    end do
    ok = .not. err%failed()
    call assert_true(ok, 'integration: '//err%text())
    if (.not. ok) return
    kmin = max(1, min(nk - 1, minloc(w, 1) - 1))
    a = w(kmin - 1)
    b = w(kmin)
    c = w(kmin + 1)
    t_min = kmin*dt
    w_min = b
    if (a - 2*b + c > 0.0_dp) then
      t_min = t_min + 0.5_dp*dt*(a - c)/(a - 2*b + c)
      w_min = b - 0.125_dp*(a - c)**2/(a - 2*b + c)
    end if
  end subroutine spinup_minimum

  !> Ws = 4 rad/s, consistent element (the default with stretching on):
  !> minima at 4, 8, 16 elements.  Issue 10 asks 8 and 16 within 1 % of each
  !> other and of 32; measured (release, rtol 1e-6): -0.533499, -0.533451,
  !> -0.533425 m, and -0.533429 m at 32 elements (doc/verification_transient.md),
  !> so 8 vs 16 and 4 vs 16 are held to 1e-3 and the 16-element value to
  !> 1e-3 of the 32-element one (the integrator's own error at rtol 1e-6 is
  !> 6e-4: rtol 1e-8 gives -0.533153).  Time of the minimum 6.76 s.
  subroutine test_convergence()
    integer, parameter :: meshes(3) = [4, 8, 16]
    real(dp), parameter :: w32 = -0.533429_dp
    real(dp) :: w_min(3), t_min(3)
    logical :: ok
    integer :: k
    do k = 1, 3
      call spinup_minimum(meshes(k), 4.0_dp, 'default', 20.0_dp, w_min(k), t_min(k), ok)
      if (.not. ok) return
      write(*, '(4x,a,i3,a,f10.6,a,f7.3,a)') 'consistent, ', meshes(k), ' elements: min tip w = ', w_min(k), &
        ' m at t = ', t_min(k), ' s'
    end do
    call assert_rel_close(w_min(2), w_min(3), 1.0e-3_dp, '8 vs 16 elements')
    call assert_rel_close(w_min(1), w_min(3), 1.0e-3_dp, '4 vs 16 elements')
    call assert_rel_close(w_min(3), w32, 1.0e-3_dp, '16 vs 32 elements')
    call assert_close(t_min(3), 6.76_dp, 0.05_dp, 'time of the minimum')
  end subroutine test_convergence

  !> Kear's printed interpolation with exact stretching ('exact'), 4
  !> elements: minimum -0.243 m, 54 % smaller than the converged -0.533 m
  !> (issue 10's measurement; 39 % at 8 and 23 % at 16 elements): held to
  !> less than 60 % of the consistent element's 8-element value.
  subroutine test_kear_locks()
    real(dp) :: w_kear, w_cons, t_min
    logical :: ok
    call spinup_minimum(4, 4.0_dp, 'exact', 20.0_dp, w_kear, t_min, ok)
    if (.not. ok) return
    call spinup_minimum(8, 4.0_dp, 'consistent', 20.0_dp, w_cons, t_min, ok)
    if (.not. ok) return
    write(*, '(4x,a,f10.5,a,f10.5)') 'Kear 4 elements: ', w_kear, ', consistent 8 elements: ', w_cons
    call assert_true(abs(w_kear) < 0.6_dp*abs(w_cons), 'Kear element locked')
  end subroutine test_kear_locks
end module test_transient_spinup_suite

program test_transient_spinup
  use test_transient_spinup_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_spinup')
end program test_transient_spinup
