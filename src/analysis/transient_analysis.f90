!> The `transient` analysis (Kear 1986-87): the vibration of a flexible
!> linkage about its known rigid-body motion, integrated by DLSODE from the
!> rigid-body state (or a mode shape, or a restart file) over a number of crank
!> revolutions.  Output rows at equal crank-angle increments: elastic
!> displacements of the joints, local deformations at each link's end 2, and
!> the maximum |stress| of every element.
module transient_analysis
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, input_error_in, input_error_code
  use table_output, only: table_t
  use progress, only: progress_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_adams
  use transient_integration, only: start_integrator, write_start_frequencies, write_integration_cost, &
                                   choose_solver_settings, static_load_t
  use mechanism_report, only: write_mechanism_header, joint_moves, joint_carrier, response_column_names, &
                              response_columns_text, link_point_name
  use linkage, only: mechanism_t, driver_angle
  use planar_element, only: stress_report_t
  use element_effects, only: effects_summary
  use beam_element, only: beam_local_displacement
  use mechanism_model, only: mechanism_model_t
  use external_loads, only: loads_input_t, point_load_t, resolve_loads
  use transient_deck, only: read_transient_deck, echo_transient_deck
  use transient_settings, only: transient_settings_t, max_points, check_mode_number
  use transient_response, only: link_point_t, link_point_response, section_values_t, element_stresses_and_sections
  use joint_reactions, only: joint_reactions_t
  use revolution_peaks, only: element_peaks_t
  use revolution_rows, only: revolution_rows_t
  use linkage, only: joint_clamp
  use plausibility, only: warn_materials, warn_strength, crank_speed_warning
  use clearance_run, only: clearance_monitor_t
  use joint_clearance, only: clearance_joint_t
  use restart_file, only: write_restart_file, start_from_restart
  implicit none
  private
  public :: run_transient


  !> The optional response columns of a run (each off = not computed).
  type :: responses_t
    logical :: sections = .false.                 !< bending, axial stress, M, N of every element
    type(link_point_t), allocatable :: points(:)  !< link points
    character(len=24), allocatable :: point_label(:)
    logical :: reactions = .false.
    type(joint_reactions_t) :: jr
    integer, allocatable :: react_end(:)          !< jr%ends written (force on the link end)
    integer, allocatable :: react_joint(:)        !< joints whose ground/guide force is written
  end type responses_t

  !> What the run's rows are made of and go into: the optional responses,
  !> the revolution rows and the element stress peaks.
  type :: transient_record_t
    type(responses_t) :: resp
    type(revolution_rows_t) :: rows
    type(element_peaks_t) :: peaks
  contains
    procedure :: record_row
  end type transient_record_t

contains

  !> Read, build, integrate row by row to the end (or to the periodic state), then the summary and cost.
  subroutine run_transient(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(mechanism_t) :: mech
    type(transient_settings_t) :: s
    type(loads_input_t) :: loads_in
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(progress_t) :: bar
    type(clearance_monitor_t) :: clearance       ! joints with clearance (&clearance; doc/clearance.md)
    type(lsode_counters_t) :: c
    real(dp), allocatable :: y(:), omega_n(:), shapes(:, :)
    real(dp) :: t0, t_end, dt_out, t, theta, cpu0, cpu1, revolutions_done
    integer :: k, n_out
    character(len=32), allocatable :: names(:)
    type(transient_record_t) :: rec

    call read_transient_deck(deck, mech, s, loads_in, clearance, err)
    if (err%failed()) return

    call echo_transient_deck(out, mech, loads_in, clearance)
    call warn_materials(out, mech)

    ! the model in one step, with the natural frequencies of the linearised
    ! structure at the start position (before the clearance joints' unknowns)
    call build_model(deck, mech, s, loads_in, clearance, model, omega_n, shapes, err)
    if (err%failed() .and. err%code == input_error_code) return
    if (.not. err%failed()) then
      call setup_responses(mech, s, rec%resp)
      if (size(model%slide) > 0) call refuse_on_sliding_links(deck, model, rec%resp, err)
      if (err%failed()) return
    end if
    call write_model_header(out, mech, s, model)
    if (err%failed()) return                  ! the rigid motion or the modes failed: the header is kept
    call describe_motion(out, mech, s)
    call write_frequency_header(out, mech, s, omega_n)
    if (len(crank_speed_warning(mech%driver%omega, omega_n(1), s%damping_beta)) > 0) &
      call out%warning(crank_speed_warning(mech%driver%omega, omega_n(1), s%damping_beta))
    call clearance%attach(model, mech, out)

    allocate(y(model%state_size()))
    call initial_state(deck, s, model, shapes, out, t0, y, err)
    if (err%failed()) return

    call output_times(mech, s, t0, dt_out, t_end, n_out)
    call choose_settings(out, s, model, y, t0, t_end, mech%driver%omega, clearance%active, err)
    if (err%failed()) return

    call start_integrator(out, s, model%kd, t0, size(y), ode, err)
    if (err%failed()) return

    call start_rows(out, mech, s, model, rec%resp, clearance, t0, dt_out, names, rec%rows)
    call rec%peaks%init(element_labels(mech, size(model%el)), mech%driver%omega > 0.0_dp, &
                        rec%rows%theta_start*180.0_dp/pi)

    call bar%start('transient', t0, t_end)
    call cpu_time(cpu0)
    call rec%record_row(out, t0, mech, model, clearance, y, theta, err)
    do k = 1, n_out
      t = t0 + k*dt_out
      if (k == n_out) t = max(t, t_end)
      if (clearance%active) then
        call clearance%integrate_to(ode, model, y, t, err)
      else
        call ode%integrate_to(model, y, t, err)
      end if
      if (err%failed()) exit
      call rec%record_row(out, t, mech, model, clearance, y, theta, err)
      if (err%failed()) exit
      call rec%rows%close_revolutions(out, theta)
      if (rec%rows%periodic) exit
      if (.not. bar%shown()) cycle             ! no terminal: the detail text is not built
      c = ode%counters()
      call bar%update(t, 'revolution '//str(max(1, ceiling(abs(theta)/(2.0_dp*pi) - 1.0e-9_dp)))// &
                      ', crank angle '//str(nint(theta*180.0_dp/pi))//' deg, '//str(c%steps)//' steps')
    end do
    call bar%finish()
    call cpu_time(cpu1)

    if (err%failed()) call model%name_stop_angle('transient analysis', ode%t, err)

    call rec%rows%write_last_revolution(out, names)
    ! summary (the last complete revolution first, then the whole run) and cost
    call rec%peaks%write(out, 'last')
    call rec%rows%write_peaks(out, names, 'last', 'sigma_max_e')
    call rec%peaks%write(out, 'whole')
    call rec%rows%write_peaks(out, names, 'whole', 'sigma_max_e')
    call warn_strength(out, mech, rec%peaks%pk%whole)
    call rec%rows%write_periodicity(out)
    c = ode%counters()
    revolutions_done = max(0.0_dp, (ode%t - t0)*max(mech%driver%omega, 0.0_dp)/two_pi)
    call write_cost(out, s, model, c, cpu1 - cpu0, revolutions_done)
    if (clearance%active) call clearance%report(out, revolutions_done, model, y, s%mf == mf_adams)
    if (.not. err%failed() .and. len_trim(s%restart_out) > 0) then
      call write_restart_file(s%restart_out, ode%t, y, err)
      if (.not. err%failed()) call out%comment('final state saved to restart file '//trim(s%restart_out))
    end if
  end subroutine run_transient

  !> 'crank 1; coupler 2-3; rocker 4': the elements of each link (its deck name).
  function link_elements(mech) result(text)
    type(mechanism_t), intent(in) :: mech
    character(len=:), allocatable :: text
    integer :: i, e
    text = ''
    e = 0
    do i = 1, mech%n_links
      if (i > 1) text = text//'; '
      text = text//trim(mech%links(i)%name)//' '//str(e + 1)
      if (mech%links(i)%n_elements > 1) text = text//'-'//str(e + mech%links(i)%n_elements)
      e = e + mech%links(i)%n_elements
    end do
  end function link_elements

  !> The summary's names of n elements: the deck's name of each element's
  !> link and the element's number, 'crank (element 1)'.
  function element_labels(mech, n) result(labels)
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: n
    character(len=48) :: labels(n)
    integer :: e, i, k
    e = 0
    do i = 1, mech%n_links
      do k = 1, mech%links(i)%n_elements
        e = e + 1
        if (e <= n) labels(e) = trim(mech%links(i)%name)//' (element '//str(e)//')'
      end do
    end do
    do k = e + 1, n
      labels(k) = 'element '//str(k)
    end do
  end function element_labels

  !> The rows' schedule, digits and columns, and the revolution rows that
  !> keep them (rows from t0; the crank angle there starts the revolutions).
  subroutine start_rows(out, mech, s, model, resp, clearance, t0, dt_out, names, rows)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    type(mechanism_model_t), intent(in) :: model
    type(responses_t), intent(in) :: resp
    type(clearance_monitor_t), intent(in) :: clearance
    real(dp), intent(in) :: t0, dt_out
    character(len=32), allocatable, intent(out) :: names(:)
    type(revolution_rows_t), intent(out) :: rows
    real(dp) :: t_rows, theta_start, theta_d, theta_dd
    logical :: buffered
    call row_schedule(out, mech, s, t0, dt_out, t_rows, buffered)
    if (s%output_digits > 0) call out%set_digits(s%output_digits)
    call write_columns(out, mech, model, resp, names, clearance%column_names())
    call driver_angle(mech%driver, t0, theta_start, theta_d, theta_dd)
    rows = revolution_rows_t(n_columns=size(names), t_rows=t_rows, buffered=buffered, stop_change=s%stop_when_periodic, &
                             turning=mech%driver%omega > 0.0_dp, theta_start=theta_start)
    call rows%start()
  end subroutine start_rows

  !> The row of output time tt (joints, link ends, element stresses, the
  !> optional responses, clearance columns) into the run's rows and peaks;
  !> theta: the crank angle at tt.
  subroutine record_row(self, out, tt, mech, model, clearance, y, theta, err)
    class(transient_record_t), intent(inout) :: self
    type(table_t), intent(inout) :: out
    real(dp), intent(in) :: tt
    type(mechanism_t), intent(in) :: mech
    type(mechanism_model_t), target, intent(inout) :: model
    type(clearance_monitor_t), intent(inout) :: clearance
    real(dp), intent(in) :: y(:)
    real(dp), intent(out) :: theta
    type(error_t), intent(inout) :: err
    type(stress_report_t) :: stress(size(model%el))
    type(section_values_t) :: sections(size(model%el))
    real(dp) :: row(self%rows%n_columns), q(model%n), crank_deg, theta_d, theta_dd
    integer :: j, i, kk, ee
    call driver_angle(mech%driver, tt, theta, theta_d, theta_dd)
    call model%set_time(tt)
    if (model%err%failed()) then
      call err%set('', model%err%text())
      return
    end if
    q = y(1::2)
    crank_deg = theta*180.0_dp/pi
    if (self%resp%sections) then            ! one evaluation of the station strains for both
      call element_stresses_and_sections(model, q, stress, sections)
    else
      call model%element_stresses(q, stress)
    end if
    row(1) = tt
    row(2) = crank_deg
    kk = 2
    do j = 1, mech%n_joints
      if (.not. joint_moves(mech, j)) cycle
      call joint_displacement(model, mech, j, q, row(kk + 1:kk + 2))
      kk = kk + 2
    end do
    do i = 1, mech%n_links
      ee = mech%links(i)%first_element + mech%links(i)%n_elements - 1
      row(kk + 1:kk + 2) = beam_local_displacement(model%el(ee), model%element_q(ee, q), model%rb(ee)%phi, 1.0_dp)
      kk = kk + 2
    end do
    row(kk + 1:kk + size(stress)) = stress%max_abs_stress
    call self%peaks%note(row(kk + 1:kk + size(stress)), crank_deg)   ! (a contiguous copy of the stresses)
    kk = kk + size(stress)
    call fill_responses(self%resp, model, mech, tt, y, sections, row, kk, err)
    if (err%failed()) return
    if (clearance%active) row(kk + 1:) = clearance%row_values(model, y)
    call self%rows%add(out, tt, row, crank_deg)
  end subroutine record_row


  !> Output step and end time: by crank angle and revolutions when the crank
  !> turns and no time span is given, else by time.
  subroutine output_times(mech, s, t0, dt_out, t_end, n_out)
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    real(dp), intent(in) :: t0
    real(dp), intent(out) :: dt_out, t_end
    integer, intent(out) :: n_out
    if (mech%driver%omega > 0.0_dp .and. .not. (s%t_end > 0.0_dp .and. s%output_step_t > 0.0_dp)) then
      dt_out = s%output_step_deg*pi/180.0_dp/mech%driver%omega
      t_end = t0 + time_to_turn(mech, s%revolutions*two_pi)
    else
      dt_out = s%output_step_t
      t_end = t0 + s%t_end
    end if
    n_out = max(1, nint((t_end - t0)/dt_out))
  end subroutine output_times

  !> The rigid-body motion: tabulated per revolution or solved on demand.
  subroutine describe_motion(out, mech, s)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    if (s%kinematics == 'table' .and. mech%driver%omega > 0.0_dp) then
      call out%comment('rigid-body motion: tabulated at '//str(s%table_points)//' crank angles per revolution, '// &
                       'quintic Hermite interpolation in the crank angle')
    else if (mech%driver%omega > 0.0_dp) then
      call out%comment('rigid-body motion: kinematics solved at every time the integrator asks for')
    end if
  end subroutine describe_motion

  !> The planar model of the mechanism in one step (mechanism_model's
  !> init_mechanism): its loads, clearance joints, the rigid motion
  !> tabulated as &transient asks, and the start modes (omega_n, shapes) of
  !> the pinned linkage.  A refusal of the model, the loads or the clearance
  !> joints is an input error of their group.
  subroutine build_model(deck, mech, s, loads_in, clearance, model, omega_n, shapes, err)
    type(deck_t), intent(in) :: deck
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    type(loads_input_t), intent(in) :: loads_in
    type(clearance_monitor_t), intent(in) :: clearance
    type(mechanism_model_t), target, intent(inout) :: model
    real(dp), allocatable, intent(out) :: omega_n(:), shapes(:, :)
    type(error_t), intent(inout) :: err
    real(dp) :: gravity(2)
    type(point_load_t), allocatable :: point_loads(:)
    type(clearance_joint_t), allocatable :: cj(:)
    logical :: refused
    allocate(point_loads(0))
    call resolve_loads(loads_in, mech, gravity, point_loads, err)
    if (err%failed()) then
      call input_error_in(deck, 'loads', err)
      return
    end if
    call clearance%joints(mech, cj, err)
    if (err%failed()) return
    call model%init_mechanism(mech, s%effects, s%formulation, s%damping_beta, err, gravity=gravity, &
                              point_loads=point_loads, table_points=merge(s%table_points, 0, s%kinematics == 'table'), &
                              clearance=cj, omega=omega_n, shapes=shapes, elements_refused=refused)
    if (err%failed() .and. refused) call input_error_in(deck, 'mechanism', err)
  end subroutine build_model

  !> The initial state (&transient initial): a scaled mode at rest, a restart
  !> file, or the rigid-body motion.
  subroutine initial_state(deck, s, model, shapes, out, t0, y, err)
    type(deck_t), intent(in) :: deck
    type(transient_settings_t), intent(in) :: s
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: shapes(:, :)
    type(table_t), intent(inout) :: out
    real(dp), intent(out) :: t0, y(:)
    type(error_t), intent(inout) :: err
    t0 = 0.0_dp
    y = 0.0_dp
    select case (trim(s%initial))
    case ('mode')
      call check_mode_number(deck, s, model%n, err)
      if (err%failed()) return
      y(1::2) = s%mode_amplitude*shapes(:, s%mode_number)/max_transverse(model, shapes(:, s%mode_number))
      call out%comment('initial state: mode '//str(s%mode_number)//' scaled to a largest transverse '// &
                       'displacement of '//str(s%mode_amplitude)//', at rest')
    case ('restart')
      call start_from_restart(deck%path, s%restart_in, out, t0, y, err)
      if (err%failed()) return
    case default
      call out%comment('initial state: rigid-body motion, zero elastic deformation and rate')
    end select
  end subroutine initial_state

  !> The solver settings the deck left out, from the model's M, K and loads
  !> over the run (transient_integration).
  subroutine choose_settings(out, s, model, y, t0, t_end, crank_omega, contact, err)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(inout) :: s
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: y(:), t0, t_end, crank_omega
    logical, intent(in) :: contact
    type(error_t), intent(inout) :: err
    type(static_load_t) :: load
    real(dp) :: mass(model%n, model%n), stiff(model%n, model%n), t
    call load%start(model%n, y, t0, t_end, model%kd)
    do while (load%next(t) .and. .not. err%failed())
      call model%set_time(t)
      call model%assemble_dense(0.0_dp*y(1::2), mass, stiff)
      call load%add(model, t, mass, stiff, err)
    end do
    call choose_solver_settings(out, s, load, crank_omega, contact, err)
  end subroutine choose_settings

  !> Which output times are written as rows: from t_rows on (the summary's
  !> peaks are over every output time either way); buffer_rows: the rows of
  !> each revolution are kept until it is complete (stop_when_periodic with
  !> 'last_revolution').
  subroutine row_schedule(out, mech, s, t0, dt_out, t_rows, buffer_rows)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    real(dp), intent(in) :: t0, dt_out
    real(dp), intent(out) :: t_rows
    logical, intent(out) :: buffer_rows
    select case (trim(s%output_rows))
    case ('none')
      t_rows = huge(1.0_dp)
      call out%comment('output_rows = ''none'': no rows; the summary''s peaks are over every output time')
    case ('last_revolution')
      t_rows = t0
      if (mech%driver%omega > 0.0_dp .and. s%revolutions > 1.0_dp) &
        t_rows = t0 + time_to_turn(mech, (s%revolutions - 1.0_dp)*two_pi) - 0.5_dp*dt_out
      call out%comment('output_rows = ''last_revolution'': rows of the last crank revolution only; '// &
                       'the summary''s peaks are over every output time')
    case default
      t_rows = -huge(1.0_dp)
    end select
    ! stopping early, 'last_revolution' means the last complete one: its rows are kept until it is
    buffer_rows = s%output_rows == 'last_revolution' .and. s%stop_when_periodic > 0.0_dp
    if (buffer_rows) then
      t_rows = huge(1.0_dp)
      call out%comment('with stop_when_periodic: the rows of the last complete revolution')
    end if
    if (s%stop_when_periodic > 0.0_dp) call out%comment('stop_when_periodic = '//str(s%stop_when_periodic)// &
      ': the run stops at the end of the first revolution whose peaks of every column differ from the '// &
      'previous revolution''s by at most that fraction')
  end subroutine row_schedule

  !> The cost footer: DLSODE's counters and the model's own work.
  subroutine write_cost(out, s, model, c, cpu, revolutions_done)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(in) :: s
    type(mechanism_model_t), intent(in) :: model
    type(lsode_counters_t), intent(in) :: c
    real(dp), intent(in) :: cpu, revolutions_done
    call write_integration_cost(out, s, c, cpu, revolutions_done, model%newton%n_factorizations, model%newton%n_lu, &
                                model%n_mass_factorizations)
    call out%cost('last_method_order', str(c%order_last))
    call out%cost('kinematics_solutions', str(model%n_kinematics))
    call out%cost('kinematics_newton_iterations', str(model%kin%total_iterations))
    call out%cost('nonlinear_integrand_evaluations', str(model%n_nonlinear_points))
  end subroutine write_cost

  !> Global elastic (U, W) of joint j (mechanism_report%joint_carrier says where).
  subroutine joint_displacement(model, mech, j, q, uw)
    type(mechanism_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: j
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: uw(2)
    integer :: e, node
    real(dp) :: qe(model%table%element_dofs())
    call joint_carrier(mech, j, e, node)
    qe = model%table%gather(e, q)
    uw = qe(model%table%node_dofs()*(node - 1) + 1:model%table%node_dofs()*(node - 1) + 2)   ! 4 or 6 DOFs per node
  end subroutine joint_displacement

  subroutine write_columns(out, mech, model, resp, names, extra)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(mechanism_model_t), intent(in) :: model
    type(responses_t), intent(in) :: resp
    character(len=32), allocatable, intent(out) :: names(:)
    character(len=32), intent(in) :: extra(:)   !< clearance joints' columns (none without clearance)
    integer :: e, k, j, ne
    character(len=:), allocatable :: jn
    names = [character(len=32) :: 't', 'crank_deg', response_column_names(mech, size(model%el), '')]
    call out%comment('columns: t (s); crank_deg = crank angle (deg); '//response_columns_text// &
                     ' (the outer-fibre stress: axial + bending)')
    call out%comment('elements k of the columns *_e<k> by link: '//link_elements(mech))
    ne = size(model%el)
    if (resp%sections) then
      names = [character(len=32) :: names, ('sigma_b_e'//str(e), e = 1, ne), ('sigma_a_e'//str(e), e = 1, ne), &
               ('M_e'//str(e), e = 1, ne), ('N_e'//str(e), e = 1, ne)]
      call out%comment('sigma_b_e<k>, sigma_a_e<k> = bending and axial stress (psi; half the difference and the '// &
                       'mean of the outer-fibre stresses: M c/I and N/A for a linear material), M_e<k> = bending '// &
                       'moment (lb in), N_e<k> = axial force (lb); each the signed value of largest magnitude in '// &
                       'element k (ends and Gauss points)')
    end if
    do k = 1, size(resp%points)
      names = [character(len=32) :: names, trim(resp%point_label(k))//'_u', trim(resp%point_label(k))//'_w', &
               trim(resp%point_label(k))//'_chord']
    end do
    if (size(resp%points) > 0) call out%comment('<link>_s<x>_u, _w = elastic axial and transverse displacement '// &
      'of the point of the link at x times its length from end 1, in the link''s rigid-body axes (in); _chord = its '// &
      'transverse distance from the deformed chord through the link''s displaced ends (in, + to the left of '// &
      'end 1 -> end 2)')
    if (resp%reactions) then
      do k = 1, size(resp%react_end)
        associate (ef => resp%jr%ends(resp%react_end(k)))
          jn = trim(mech%joints(ef%joint)%name)//'_'//trim(mech%links(ef%link)%name)
          names = [character(len=32) :: names, jn//'_Fx', jn//'_Fy']
        end associate
      end do
      do k = 1, size(resp%react_joint)
        j = resp%react_joint(k)
        jn = trim(mech%joints(j)%name)
        names = [character(len=32) :: names, jn//'_Gx', jn//'_Gy']
        if (mech%joints(j)%kind == joint_clamp) names = [character(len=32) :: names, jn//'_Gm']
      end do
      call out%comment('<joint>_<link>_Fx, _Fy = force of the joint on that link''s end, global X, Y (lb; the '// &
        'other link end at a massless pin carries the opposite); <joint>_Gx, _Gy = force of the ground (or '// &
        'slider guide) on the mechanism at the joint (lb), _Gm its moment at a clamp (lb in: the driving torque)')
    end if
    names = [character(len=32) :: names, extra]
    if (size(extra) > 0) call out%comment('clearance columns: <joint>_ex, <joint>_ey = journal centre relative to '// &
      'the bearing centre along global X, Y (in); <joint>_Fn = normal contact force (lb); <joint>_mode = 0 free, '// &
      '1 in contact, 2 an impact since the previous row')
    call out%columns(names)
  end subroutine write_columns

  !> The optional response columns the deck asks for (a point's link exists:
  !> transient_deck checked it).
  subroutine setup_responses(mech, s, resp)
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    type(responses_t), intent(inout) :: resp
    integer :: k, i, j, n_keep, n_shape
    type(link_point_t) :: p
    resp%sections = s%stress_columns == 'all'
    allocate(resp%points(0), resp%point_label(0))
    if (s%link_points .or. any(len_trim(s%point_link) > 0)) then
      do k = 1, max_points
        if (len_trim(s%point_link(k)) == 0) cycle
        p%link = 0
        do i = 1, mech%n_links
          if (mech%links(i)%name == s%point_link(k)) p%link = i
        end do
        p%s = s%point_at(k)
        resp%points = [resp%points, p]
      end do
      if (size(resp%points) == 0) then
        do i = 1, mech%n_links
          resp%points = [resp%points, link_point_t(link=i, s=0.5_dp)]
        end do
      end if
    end if
    do i = 1, mech%n_links                 ! shape_points: the drawn shape of every link
      n_shape = s%shape_points*mech%links(i)%n_elements
      do k = 0, merge(n_shape, -1, n_shape > 0)
        p = link_point_t(link=i, s=real(k, dp)/n_shape)
        if (.not. any(resp%points(:)%link == i .and. abs(resp%points(:)%s - p%s) < 5.0e-5_dp)) &
          resp%points = [resp%points, p]
      end do
    end do
    do k = 1, size(resp%points)
      resp%point_label = [character(len=24) :: resp%point_label, point_label(mech, resp%points(k))]
    end do
    resp%reactions = s%reactions
    allocate(resp%react_end(0), resp%react_joint(0))
    if (.not. resp%reactions) return
    call resp%jr%init(mech)
    do j = 1, mech%n_joints
      if (resp%jr%supported(j)) then
        resp%react_joint = [resp%react_joint, j]
        cycle
      end if
      ! a massless joint's forces on its link ends sum to zero: the last is left out
      n_keep = count(resp%jr%ends(:)%joint == j)
      if (.not. mech%joints(j)%mass > 0.0_dp) n_keep = n_keep - 1
      do k = 1, size(resp%jr%ends)
        if (resp%jr%ends(k)%joint /= j .or. n_keep == 0) cycle
        resp%react_end = [resp%react_end, k]
        n_keep = n_keep - 1
      end do
    end do
  end subroutine setup_responses

  !> The outputs and loads that read an element as Kear's of fixed length
  !> are not built for a link sliding through a sleeve (doc/transient.md).
  subroutine refuse_on_sliding_links(deck, model, resp, err)
    type(deck_t), intent(in) :: deck
    type(mechanism_model_t), intent(in) :: model
    type(responses_t), intent(in) :: resp
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: why = 'is not built for a link sliding through a sleeve (slider_link; doc/transient.md)'
    integer :: k
    if (resp%sections) then
      call invalid_value(deck, 'transient', 'stress_columns', '''all''', why, err)
    else if (resp%reactions) then
      call invalid_value(deck, 'transient', 'reactions', 'T', why, err)
    else if (size(resp%points) > 0) then
      call invalid_value(deck, 'transient', 'link_points', 'T', why, err)
    end if
    if (err%failed()) return
    do k = 1, size(model%loads)
      if (model%table%is_sleeve_element(model%loads(k)%element)) then
        call invalid_value(deck, 'loads', 'load_link', 'a sliding link', 'a point load '//why, err)
        return
      end if
    end do
  end subroutine refuse_on_sliding_links

  !> '<link>_s<position>' (mechanism_report's link_point_name).
  function point_label(mech, p) result(label)
    type(mechanism_t), intent(in) :: mech
    type(link_point_t), intent(in) :: p
    character(len=24) :: label
    label = link_point_name(mech%links(p%link)%name, p%s)
  end function point_label

  !> The optional columns at time tt from the state y, into row(kk+1:).
  subroutine fill_responses(resp, model, mech, tt, y, sections, row, kk, err)
    type(responses_t), intent(inout) :: resp
    type(mechanism_model_t), intent(inout) :: model
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: tt, y(:)
    type(section_values_t), intent(in) :: sections(:)     !< with resp%sections: each element's peaks
    real(dp), intent(inout) :: row(:)
    integer, intent(inout) :: kk
    type(error_t), intent(inout) :: err
    integer :: e, ne, k, j
    ne = size(model%el)
    if (resp%sections) then
      do e = 1, ne
        row(kk + e) = sections(e)%bending_stress
        row(kk + ne + e) = sections(e)%axial_stress
        row(kk + 2*ne + e) = sections(e)%moment
        row(kk + 3*ne + e) = sections(e)%axial_force
      end do
      kk = kk + 4*ne
    end if
    do k = 1, size(resp%points)
      call link_point_response(model, mech, y(1::2), resp%points(k))
      row(kk + 1:kk + 3) = [resp%points(k)%u, resp%points(k)%w, resp%points(k)%chord]
      kk = kk + 3
    end do
    if (.not. resp%reactions) return
    call resp%jr%compute(model, tt, y(1::2), y(2::2), err)
    if (err%failed()) return
    do k = 1, size(resp%react_end)
      row(kk + 1:kk + 2) = resp%jr%ends(resp%react_end(k))%force
      kk = kk + 2
    end do
    do k = 1, size(resp%react_joint)
      j = resp%react_joint(k)
      row(kk + 1:kk + 2) = resp%jr%support(1:2, j)
      kk = kk + 2
      if (mech%joints(j)%kind == joint_clamp) then
        row(kk + 1) = resp%jr%support(3, j)
        kk = kk + 1
      end if
    end do
  end subroutine fill_responses

  subroutine write_model_header(out, mech, s, model)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    type(mechanism_model_t), intent(in) :: model
    call write_mechanism_header(out, mech, model%linkage_table())
    call out%comment('effects on: '//effects_summary(s%effects)//' formulation='//trim(model%formulation))
    if (.not. (s%effects%stretching .or. s%effects%curvature .or. s%effects%material .or. &
               s%effects%rotary_inertia .or. s%effects%coupling)) &
      call out%comment('(all effects off: the linear analysis)')
  end subroutine write_model_header

  subroutine write_frequency_header(out, mech, s, omega_n)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    real(dp), intent(in) :: omega_n(:)
    integer :: h
    real(dp) :: w
    call write_start_frequencies(out, omega_n)
    if (s%damping_beta > 0.0_dp) then
      call out%comment('stiffness-proportional damping beta = '//str(s%damping_beta)//' s: modal damping ratio '// &
                       'zeta_1 = beta*omega_1/2 = '//str(0.5_dp*s%damping_beta*omega_n(1), 6))
    else
      call out%comment('no damping: a transient started from the rigid-body state never settles')
    end if
    w = mech%driver%omega
    if (w > 0.0_dp) then
      call out%comment('crank speed '//str(w, 6)//' rad/s = '//str(w/omega_n(1), 6)//' of the first natural frequency')
      do h = 1, 8
        if (abs(h*w - omega_n(1)) < 0.05_dp*omega_n(1)) &
          call out%comment('warning: harmonic '//str(h)//' of the crank speed ('//str(h*w, 6)// &
                           ' rad/s) is within 5% of the first natural frequency: near resonance')
      end do
    end if
  end subroutine write_frequency_header

  !> Time for the crank to turn by `angle` from t = 0 (bisection on the driver
  !> profile, which is monotone).
  real(dp) function time_to_turn(mech, angle) result(t)
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: angle
    real(dp) :: lo, hi, th0, th, thd, thdd
    integer :: i
    call driver_angle(mech%driver, 0.0_dp, th0, thd, thdd)
    lo = 0.0_dp
    hi = angle/mech%driver%omega
    do
      call driver_angle(mech%driver, hi, th, thd, thdd)
      if (th - th0 >= angle) exit
      hi = 2.0_dp*hi
    end do
    do i = 1, 200
      t = 0.5_dp*(lo + hi)
      call driver_angle(mech%driver, t, th, thd, thdd)
      if (th - th0 < angle) then
        lo = t
      else
        hi = t
      end if
      if (hi - lo <= 1.0e-14_dp*hi) exit
    end do
    t = hi
  end function time_to_turn

  !> Largest local transverse displacement of a global displacement vector,
  !> sampled at 11 points per element (the scale of a mode shape).
  real(dp) function max_transverse(model, q) result(wmax)
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: q(:)
    integer :: e, i
    real(dp) :: uw(2)
    wmax = 0.0_dp
    do e = 1, size(model%el)
      do i = 0, 10
        uw = beam_local_displacement(model%el(e), model%element_q(e, q), model%rb(e)%phi, i/10.0_dp)
        wmax = max(wmax, abs(uw(2)))
      end do
    end do
    if (wmax <= 0.0_dp) wmax = 1.0_dp
  end function max_transverse

end module transient_analysis
