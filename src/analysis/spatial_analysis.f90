!> The `spatial` analysis (paper E, El-Sawy, Willmert & Sathyamoorthy 1987):
!> vibration of a flexible spatial four-bar about its rigid-body motion,
!> integrated by DLSODE from the rigid-body state over a number of crank
!> revolutions.  Re-uses the &transient and &effects groups of the planar
!> analysis.  Output rows at equal crank-angle increments: elastic
!> translations of joints B and C (global), local deflections and rotations
!> of each link's end 2, end-1 resultants of each link (N, M_y, M_z, T) and
!> every element's maximum |stress|, the support forces; with &transient
!> shape_points = k, the elastic displacement (global) of k + 1 points per
!> element of every link, from the element's own shape functions (the drawn
!> shapes of `flexmech plot`).  doc/spatial.md.
module spatial_analysis
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use mechanism_report, only: link_point_name
  use deck_reader, only: deck_t, invalid_value, input_error_in
  use table_output, only: table_t
  use progress, only: progress_t
  use lsode_solver, only: lsode_t
  use transient_integration, only: start_integrator, write_start_frequencies
  use element_effects, only: effects_summary
  use transient_settings, only: transient_settings_t, read_transient_settings, echo_transient_settings
  use spatial_beam, only: spatial_stress_t, spatial_to_local, spatial_formulation_consistent
  use spatial_correlation, only: sdofs
  use restart_file, only: write_restart_file
  use revolution_peaks, only: element_peaks_t
  use revolution_rows, only: revolution_defect_t
  use spatial_kinematics, only: spatial_fourbar_t
  use spatial_model, only: spatial_model_t, spatial_link_t
  use spatial_settings, only: spatial_input_t, read_spatial_mechanism, spatial_mechanism_group, build_spatial
  use spatial_external_loads, only: spatial_loads_input_t, spatial_point_load_t, resolve_spatial_loads
  use spatial_loads_settings, only: read_spatial_loads, echo_spatial_loads
  use spatial_run_steps, only: initial_state, write_cost, write_loads, spatial_formulation_of, choose_settings
  implicit none
  private
  public :: run_spatial

  character(len=7), parameter :: link_names(3) = ['crank  ', 'coupler', 'rocker ']
  !> the deflection columns (joints B, C and the links' ends) whose periodicity is judged
  integer, parameter :: n_deflections = 24

contains

  !> Read, build, integrate row by row over the revolutions, then the summary and cost.
  subroutine run_spatial(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(spatial_input_t) :: inp
    type(transient_settings_t) :: s
    type(spatial_loads_input_t) :: loads
    type(spatial_point_load_t), allocatable :: point_loads(:)
    real(dp) :: gravity(3)
    logical :: has_loads
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(spatial_model_t), target :: model
    type(lsode_t) :: ode
    type(progress_t) :: bar
    type(element_peaks_t) :: stress_peaks
    type(revolution_defect_t) :: defect
    real(dp), allocatable :: y(:), omega_n(:)
    real(dp) :: t_end, dt_out, t, t0, cpu0, cpu1, ke, se
    integer :: k, n_out, jb, jc, link_elements(3), link_first(3)
    character(len=32), allocatable :: names(:)
    character(len=*), parameter :: link_name(3) = [character(len=7) :: 'crank', 'coupler', 'rocker']
    character(len=48), allocatable :: labels(:)

    call read_spatial_mechanism(deck, inp, err)
    if (err%failed()) return
    call read_transient_settings(deck, s, err)
    if (err%failed()) return
    call read_spatial_loads(deck, loads, has_loads, err)
    if (err%failed()) return
    call check_supported(deck, s, inp, err)
    if (err%failed()) return
    if (loads%initial_static .and. s%initial /= 'rigid') then
      call invalid_value(deck, 'spatial_loads', 'initial_static', 'T', 'the static start replaces the '// &
                         'rigid-body start: it needs initial = ''rigid'' in &transient, not '''//trim(s%initial)//'''', err)
      return
    end if
    call out%echo_group(spatial_mechanism_group)
    call echo_transient_settings(out)
    if (has_loads) call echo_spatial_loads(loads, out)
    call build_spatial(deck, inp, kin, links, jb, jc, err)
    if (err%failed()) return
    call model%init(kin, inp%omega, inp%theta0_deg*pi/180.0_dp, jb, jc, links, s%effects, s%damping_beta, err, &
                    formulation=spatial_formulation_of(s))
    if (err%failed()) then
      call input_error_in(deck, 'spatial_mechanism', err)
      return
    end if
    link_elements = model%links%n_elements        ! (contiguous copies for the dummies)
    link_first = model%links%first_element
    call resolve_spatial_loads(deck, loads, link_elements, link_first, gravity, point_loads, err)
    if (err%failed()) return
    call model%set_loads(gravity, point_loads)
    call write_header(out, inp, s, model)
    call write_loads(out, gravity, point_loads)

    allocate(omega_n(model%n))
    call model%linear_modes(omega_n, err)
    if (err%failed()) return
    call write_frequencies(out, inp, s, omega_n)

    allocate(y(model%state_size()))
    call initial_state(deck, out, s, loads%initial_static, model, t0, y, err)
    if (err%failed()) return
    dt_out = s%output_step_deg*pi/180.0_dp/inp%omega
    t_end = t0 + s%revolutions*two_pi/inp%omega
    n_out = max(1, nint((t_end - t0)/dt_out))
    call choose_settings(out, s, model, y, t0, t_end, inp%omega, err)   ! those the deck left out
    if (err%failed()) return
    call start_integrator(out, s, model%kd, t0, size(y), ode, err)
    if (err%failed()) return

    call write_columns(out, model, s%shape_points, names)
    allocate(labels(size(model%el)))
    do k = 1, size(labels)     ! the summary names elements by their links
      labels(k) = trim(link_name(model%link_of(k)))//' (element '//str(k)//')'
    end do
    call stress_peaks%init(labels, .true., inp%theta0_deg + inp%omega*t0*180.0_dp/pi)
    call defect%init(n_deflections, samples_per_revolution(s%output_step_deg), n_out)
    call bar%start('spatial', t0, t_end)
    call cpu_time(cpu0)
    call record_row(out, inp, model, 0, t0, y, stress_peaks, defect, s%shape_points, size(names), err)
    do k = 1, n_out
      t = t0 + k*dt_out
      if (k == n_out) t = max(t, t_end)
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      call record_row(out, inp, model, k, t, y, stress_peaks, defect, s%shape_points, size(names), err)
      if (err%failed()) exit
      call bar%update(t)
    end do
    call bar%finish()
    call cpu_time(cpu1)
    if (err%failed()) call model%name_stop_angle('spatial analysis', ode%t, err)

    call stress_peaks%write(out, 'last')
    call stress_peaks%write(out, 'whole')
    if (.not. err%failed()) call defect%write(out)
    call model%energies(ode%t, y(1::2), y(2::2), ke, se)
    call out%summary('final elastic strain energy', str(se, 8)//' lb in')
    if (.not. err%failed() .and. len_trim(s%restart_out) > 0) then
      call write_restart_file(s%restart_out, ode%t, y, err)
      if (.not. err%failed()) call out%comment('final state saved to restart file '//trim(s%restart_out))
    end if
    call write_cost(out, s, ode, model, cpu1 - cpu0, max(0.0_dp, (ode%t - t0)*inp%omega/two_pi))
  end subroutine run_spatial

  !> Output rows per revolution for the periodicity defect: the deflection
  !> columns one revolution apart, when the output step divides a revolution
  !> (else 0: no defect).
  integer function samples_per_revolution(step_deg) result(per_rev)
    real(dp), intent(in) :: step_deg
    per_rev = nint(360.0_dp/step_deg)
    if (abs(per_rev*step_deg - 360.0_dp) > 1.0e-9_dp) per_rev = 0
  end function samples_per_revolution

  !> The row of output step k at time tt (joints B, C; link ends; link roots'
  !> resultants; element stresses; support forces; the links' shape points),
  !> written, with the element
  !> peaks and the deflection columns' periodicity defect (k counts the output
  !> steps of this run: 0 at its start time, after a restart too).
  subroutine record_row(out, inp, model, k, tt, y, stress_peaks, defect, shape_points, n_columns, err)
    type(table_t), intent(inout) :: out
    type(spatial_input_t), intent(in) :: inp
    type(spatial_model_t), target, intent(inout) :: model
    integer, intent(in) :: k
    real(dp), intent(in) :: tt, y(:)
    type(element_peaks_t), intent(inout) :: stress_peaks
    type(revolution_defect_t), intent(inout) :: defect
    integer, intent(in) :: shape_points   !< intervals per element of the links' shape points (0: none)
    integer, intent(in) :: n_columns
    type(error_t), intent(inout) :: err
    type(spatial_stress_t) :: stress(size(model%el))
    real(dp) :: row(n_columns), q(model%n), p(sdofs), crank_deg
    integer :: kk, i, ee, j, n_shape
    call model%set_time(tt)
    if (model%err%failed()) then
      call err%set('', model%err%text())
      return
    end if
    q = y(1::2)
    crank_deg = inp%theta0_deg + inp%omega*tt*180.0_dp/pi
    call model%element_stresses(q, stress)
    row(1) = tt
    row(2) = crank_deg
    row(3:5) = q(model%b_dofs)
    row(6:8) = q(model%c_dofs)
    kk = 8
    do i = 1, 3
      ee = model%links(i)%first_element + model%links(i)%n_elements - 1
      p = spatial_to_local(model%rb(ee)%rot, model%table%gather(ee, q), model%el(ee)%local_rotation)
      row(kk + 1:kk + 6) = p(11:16)
      kk = kk + 6
    end do
    do i = 1, 3
      ee = model%links(i)%first_element
      row(kk + 1:kk + 4) = [stress(ee)%axial_force(1), stress(ee)%moment_y(1), stress(ee)%moment_z(1), &
                            stress(ee)%torque(1)]
      kk = kk + 4
    end do
    row(kk + 1:kk + size(stress)) = stress%max_abs_stress
    call stress_peaks%note(row(kk + 1:kk + size(stress)), crank_deg)   ! (a contiguous copy of the stresses)
    kk = kk + size(stress)
    call model%support_forces(tt, q, y(2::2), row(kk + 1:kk + 3), row(kk + 4:kk + 6))
    if (model%err%failed()) then
      call err%set('', model%err%text())
      return
    end if
    kk = kk + 6
    do i = 1, merge(3, 0, shape_points > 0)
      n_shape = shape_points*model%links(i)%n_elements
      do j = 0, n_shape
        row(kk + 1:kk + 3) = model%link_point_displacement(q, i, real(j, dp)/n_shape)
        kk = kk + 3
      end do
    end do
    call out%row(row)
    call defect%add(k, row(3:2 + n_deflections))
  end subroutine record_row

  !> The lowest natural frequencies at the start position, the crank speed
  !> against the first and the damping ratio beta gives it.
  subroutine write_frequencies(out, inp, s, omega_n)
    type(table_t), intent(inout) :: out
    type(spatial_input_t), intent(in) :: inp
    type(transient_settings_t), intent(in) :: s
    real(dp), intent(in) :: omega_n(:)
    call write_start_frequencies(out, omega_n)
    if (inp%omega > 0.0_dp) call out%comment('crank speed '//str(inp%omega, 6)//' rad/s = '// &
                                             str(inp%omega/omega_n(1), 6)//' of the first natural frequency')
    if (s%damping_beta > 0.0_dp) call out%comment('stiffness-proportional damping beta = '// &
      str(s%damping_beta)//' s: zeta_1 = '//str(0.5_dp*s%damping_beta*omega_n(1), 6))
  end subroutine write_frequencies

  !> What the spatial analysis does not (yet) take from the shared groups.
  subroutine check_supported(deck, s, inp, err)
    type(deck_t), intent(in) :: deck
    type(transient_settings_t), intent(in) :: s
    type(spatial_input_t), intent(in) :: inp
    type(error_t), intent(inout) :: err
    if (.not. inp%omega > 0.0_dp) then
      call invalid_value(deck, 'spatial_mechanism', 'omega', str(inp%omega), &
                         'the spatial analysis follows a turning crank: give omega > 0', err)
    else if (all(s%formulation /= [character(len=16) :: 'exact', 'consistent', 'default'])) then
      ! the spatial element's two interpolations of u (doc/spatial.md)
      call invalid_value(deck, 'effects', 'formulation', ''''//trim(s%formulation)//'''', &
                         'the spatial element has the formulations ''consistent'' (quintic u) and ''exact'' '// &
                         '(Kear''s linear u); ''default'' is consistent with stretching on, else exact', err)
    end if
  end subroutine check_supported

  subroutine write_header(out, inp, s, model)
    type(table_t), intent(inout) :: out
    type(spatial_input_t), intent(in) :: inp
    type(transient_settings_t), intent(in) :: s
    type(spatial_model_t), intent(in) :: model
    character(len=160), allocatable :: lines(:)
    call out%comment('spatial four-bar: joints B '//trim(inp%joint_b)//', C '//trim(inp%joint_c)// &
                     '; crank '//str(model%kin%crank_radius, 6)//', coupler '//str(model%kin%coupler_length, 6)// &
                     ', rocker '//str(model%kin%rocker_length, 6)//' in; elements per link '// &
                     str(inp%link_n_elements(1))//', '//str(inp%link_n_elements(2))//', '//str(inp%link_n_elements(3)))
    call out%comment('effects on: '//effects_summary(s%effects)//' (torsional inertia always; twist linear, '// &
                     'St. Venant, warping neglected)')
    if (model%formulation == spatial_formulation_consistent) then
      call out%comment('element formulation: consistent (u quintic with nodal u_x, u_xx: no membrane locking)')
    else
      call out%comment('element formulation: exact (Kear''s interpolation, u linear)')
    end if
    call out%comment('rigid-body motion: loop closure solved by Newton at every time the integrator asks for')
    call model%table%describe(lines)
    call out%comments(lines)
  end subroutine write_header

  subroutine write_columns(out, model, shape_points, names)
    type(table_t), intent(inout) :: out
    type(spatial_model_t), intent(in) :: model
    integer, intent(in) :: shape_points
    character(len=32), allocatable, intent(out) :: names(:)
    integer :: i, e, n_shape
    character(len=:), allocatable :: point
    character(len=3), parameter :: local(6) = ['u  ', 'v  ', 'w  ', 'tx ', 'ty ', 'tz ']
    character(len=3), parameter :: res(4) = ['N  ', 'My ', 'Mz ', 'T  ']
    names = [character(len=32) :: 't', 'crank_deg', 'B_UX', 'B_UY', 'B_UZ', 'C_UX', 'C_UY', 'C_UZ']
    do i = 1, 3
      do e = 1, 6
        names = [character(len=32) :: names, trim(link_names(i))//'_'//trim(local(e))//'_end']
      end do
    end do
    do i = 1, 3
      do e = 1, 4
        names = [character(len=32) :: names, trim(link_names(i))//'_'//trim(res(e))//'_root']
      end do
    end do
    do e = 1, size(model%el)
      names = [character(len=32) :: names, 'sigma_max_e'//str(e)]
    end do
    names = [character(len=32) :: names, 'A_FX', 'A_FY', 'A_FZ', 'D_FX', 'D_FY', 'D_FZ']
    call out%comment('columns: t (s); crank_deg (deg); B_U*, C_U* = elastic translation of joints B, C along '// &
      'global X, Y, Z (in); <link>_u/v/w_end = elastic displacement of the link''s end 2 in its rigid-body axes '// &
      '(in); <link>_tx/ty/tz_end = its small rotation (tx twist, ty = -w_x, tz = v_x; rad); <link>_N/My/Mz/T_root '// &
      '= axial force (lb), bending moments (lb in) and St. Venant torque (lb in) at the link''s end 1; '// &
      'sigma_max_e<k> = largest |normal stress| in element k over its extreme fibres (psi); A_F*, D_F* = force '// &
      'the crank shaft A and the rocker pivot D exert on the links, global X, Y, Z (lb)')
    do i = 1, merge(3, 0, shape_points > 0)
      n_shape = shape_points*model%links(i)%n_elements
      do e = 0, n_shape
        point = link_point_name(link_names(i), real(e, dp)/n_shape)
        names = [character(len=32) :: names, point//'_UX', point//'_UY', point//'_UZ']
      end do
    end do
    if (shape_points > 0) call out%comment('shape columns: <link>_s<x>_UX, _UY, _UZ = elastic translation of '// &
      'the link''s point at x times its length from its end 1, along global X, Y, Z (in), by the element''s own '// &
      'shape functions; '//str(shape_points + 0)//' intervals per element (shape_points)')
    call out%columns(names)
  end subroutine write_columns
end module spatial_analysis
