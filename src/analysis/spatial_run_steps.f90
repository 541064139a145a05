!> The steps the spatial-element transient drivers share (spatial_analysis,
!> the four-bar; general_transient_analysis, the general mechanism), below
!> them in src/analysis: the element formulation a deck asks for, the loads'
!> header lines, the initial state (rigid-body, modal, restart or static
!> start) and the cost footer of a model of spatial beam elements
!> (spatial_model_t or an extension of it).
module spatial_run_steps
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use lsode_solver, only: lsode_t, lsode_counters_t
  use transient_integration, only: write_integration_cost, choose_solver_settings, static_load_t
  use transient_settings, only: transient_settings_t, check_mode_number
  use spatial_beam, only: spatial_to_local, spatial_formulation_kear, spatial_formulation_consistent
  use spatial_correlation, only: sdofs
  use restart_file, only: start_from_restart
  use spatial_model, only: spatial_model_t
  use spatial_external_loads, only: spatial_point_load_t
  implicit none
  private
  public :: initial_state, write_cost, write_loads, spatial_formulation_of, choose_settings

contains

  !> The solver settings the deck left out, from the model's static response
  !> over [t0, t_end] (transient_integration); rate: the driver's speed.
  subroutine choose_settings(out, s, model, y, t0, t_end, rate, err)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(inout) :: s
    class(spatial_model_t), intent(inout) :: model
    real(dp), intent(in) :: y(:), t0, t_end, rate
    type(error_t), intent(inout) :: err
    type(static_load_t) :: load
    real(dp) :: mass(model%n, model%n), stiff(model%n, model%n), t
    call load%start(model%n, y, t0, t_end)
    do while (load%next(t) .and. .not. err%failed())
      call model%set_time(t)
      call model%assemble_dense(0.0_dp*y(1::2), mass, stiff)
      call load%add(model, t, mass, stiff, err)
    end do
    call choose_solver_settings(out, s, load, rate, .false., err)
  end subroutine choose_settings

  !> The cost footer: CPU time, DLSODE's counters and the model's own work.
  subroutine write_cost(out, s, ode, model, cpu_seconds, revolutions_done)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(in) :: s
    type(lsode_t), intent(in) :: ode
    class(spatial_model_t), intent(in) :: model
    real(dp), intent(in) :: cpu_seconds, revolutions_done
    type(lsode_counters_t) :: c
    c = ode%counters()
    call write_integration_cost(out, s, c, cpu_seconds, revolutions_done, model%newton%n_factorizations, &
                                model%newton%n_lu, model%n_mass_factorizations)
    call out%cost('kinematics_solutions', str(model%n_kinematics))
    call out%cost('kinematics_newton_iterations', str(model%kin%total_iterations))
    call out%cost('nonlinear_integrand_evaluations', str(model%n_nonlinear_points))
  end subroutine write_cost

  !> The initial state and time: the rigid-body state at t = 0, a linear
  !> mode at the start position scaled to a largest transverse displacement
  !> (v, w in the element frames) of mode_amplitude at rest, a restart file
  !> (its time, so the crank angle continues), or the static start.
  subroutine initial_state(deck, out, s, static, model, t0, y, err)
    type(deck_t), intent(in) :: deck
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(in) :: s
    logical, intent(in) :: static   !< the static start of &spatial_loads instead of the rigid-body one
    class(spatial_model_t), intent(inout) :: model
    real(dp), intent(out) :: t0, y(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: om(:), shapes(:, :)
    real(dp) :: p(sdofs), wmax
    integer :: e
    t0 = 0.0_dp
    y = 0.0_dp
    select case (trim(s%initial))
    case ('mode')
      call check_mode_number(deck, s, model%n, err)
      if (err%failed()) return
      allocate(om(model%n), shapes(model%n, model%n))
      call model%linear_modes(om, err, shapes)
      if (err%failed()) return
      call model%set_time(0.0_dp)
      wmax = 0.0_dp
      do e = 1, size(model%el)
        p = spatial_to_local(model%rb(e)%rot, model%table%gather(e, shapes(:, s%mode_number)), &
                             model%el(e)%local_rotation)
        wmax = max(wmax, maxval(abs(p([2, 3, 12, 13]))))
      end do
      y(1::2) = s%mode_amplitude*shapes(:, s%mode_number)/wmax
      call out%comment('initial state: mode '//str(s%mode_number)//' ('//str(om(s%mode_number), 6)// &
                       ' rad/s) scaled to a largest transverse displacement of '//str(s%mode_amplitude)//', at rest')
    case ('restart')
      call start_from_restart(deck%path, s%restart_in, out, t0, y, err)
    case default
      if (static) then
        call static_start(out, model, y, err)
      else
        call out%comment('initial state: rigid-body motion, zero elastic deformation and rate')
      end if
    end select
  end subroutine initial_state

  !> The start on the static elastic state under the loads at t = 0 (the
  !> rigid motion's inertia loads, gravity, point loads), moving at the rate
  !> of that state (central difference over 1e-3 of a revolution): the
  !> quasi-static response, from which the rigid-body start differs by a
  !> step load that rings every mode, the consistent element's axial modes
  !> (~1e6 rad/s) too.  What remains is the dynamic part of the response,
  !> of order (omega/omega_n)^2 of the static one in mode n.
  subroutine static_start(out, model, y, err)
    type(table_t), intent(inout) :: out
    class(spatial_model_t), intent(inout) :: model
    real(dp), intent(inout) :: y(:)
    type(error_t), intent(inout) :: err
    real(dp) :: q0(model%n), qm(model%n), qp(model%n), h
    h = 1.0e-3_dp*two_pi/model%omega
    q0 = 0.0_dp
    call model%static_state(0.0_dp, q0, err)
    if (err%failed()) return
    qm = q0
    call model%static_state(-h, qm, err)
    if (err%failed()) return
    qp = q0
    call model%static_state(h, qp, err)
    if (err%failed()) return
    call model%set_time(0.0_dp)
    y(1::2) = q0
    y(2::2) = (qp - qm)/(2.0_dp*h)
    call out%comment('initial state: the static elastic state under the loads at the start (inertia of the '// &
                     'rigid motion, gravity, point loads), at its quasi-static rate; largest |q| = '// &
                     str(maxval(abs(q0)), 6))
  end subroutine static_start

  !> The loads the deck gives (none: no line).
  subroutine write_loads(out, gravity, point_loads)
    type(table_t), intent(inout) :: out
    real(dp), intent(in) :: gravity(3)
    type(spatial_point_load_t), intent(in) :: point_loads(:)
    integer :: k
    if (norm2(gravity) > 0.0_dp) call out%comment('gravity (global, in/s^2): '//str(gravity(1), 6)//', '// &
                                                   str(gravity(2), 6)//', '//str(gravity(3), 6))
    do k = 1, size(point_loads)
      associate (pl => point_loads(k))
        call out%comment('point load '//str(k)//' at element '//str(pl%element)//' end '//str(pl%node)// &
                         ': force (global, lb) '//str(pl%force(1), 6)//', '//str(pl%force(2), 6)//', '// &
                         str(pl%force(3), 6)//'; moment (global, lb in) '//str(pl%moment(1), 6)//', '// &
                         str(pl%moment(2), 6)//', '//str(pl%moment(3), 6))
      end associate
    end do
  end subroutine write_loads

  !> The element formulation a deck asks for: 'default' is the consistent
  !> element with stretching on (where Kear's linear u locks), Kear's otherwise
  !> (as the planar analysis' 'default').
  integer function spatial_formulation_of(s) result(f)
    type(transient_settings_t), intent(in) :: s
    f = spatial_formulation_kear
    if (s%formulation == 'consistent' .or. (s%formulation == 'default' .and. s%effects%stretching)) &
      f = spatial_formulation_consistent
  end function spatial_formulation_of
end module spatial_run_steps
