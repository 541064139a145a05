!> The `general_transient` analysis (doc/general_mechanism.md, "Flexible
!> analysis"): vibration of the links of a &general_mechanism, spatial beam
!> elements with the sections and meshes of &general_links, about the
!> rigid-body motion its drivers prescribe, integrated by DLSODE (module
!> transient_integration) from the rigid-body, static or modal state.
!> &transient gives the integrator, the time span (revolutions of the
!> first driver turning at a constant rate, or t_end) and the damping,
!> &effects the element's effects, &spatial_loads gravity and the static
!> start, &general_support lumped mounts under ground joints.  Rows at
!> equal time steps: the elastic translations of the joints that move
!> (global; a mounted joint's is its mount's displacement), the forces the
!> mounts carry, each link's end-2 deflections and rotations in its
!> rigid-body axes, its end-1 resultants and every element's largest
!> |stress|; then the peaks, the final energies and the cost.
module general_transient_analysis
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, input_error_in
  use table_output, only: table_t
  use progress, only: progress_t
  use lsode_solver, only: lsode_t
  use transient_integration, only: start_integrator, write_start_frequencies
  use element_effects, only: effects_summary
  use transient_settings, only: transient_settings_t, read_transient_settings, echo_transient_settings
  use spatial_beam, only: spatial_stress_t, spatial_to_local, spatial_formulation_consistent
  use spatial_correlation, only: sdofs
  use spatial_model, only: spatial_link_t
  use spatial_external_loads, only: spatial_loads_input_t, spatial_point_load_t
  use spatial_loads_settings, only: read_spatial_loads, echo_spatial_loads
  use spatial_run_steps, only: initial_state, write_cost, write_loads, spatial_formulation_of, choose_settings
  use restart_file, only: write_restart_file
  use revolution_peaks, only: element_peaks_t
  use motion_profile, only: motion_constant
  use general_mechanism, only: general_mechanism_t, gjoint_revolute
  use general_kinematics, only: general_kinematics_t
  use general_deck, only: read_general_mechanism, echo_general_mechanism
  use general_links_settings, only: general_links_input_t, read_general_links, echo_general_links, &
    build_general_links
  use general_flex_model, only: general_flex_model_t, unsupported_joint
  use general_support_settings, only: general_support_input_t, read_general_support, echo_general_support, &
    build_mounts
  implicit none
  private
  public :: run_general_transient

contains

  subroutine run_general_transient(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(general_mechanism_t) :: mech
    type(general_kinematics_t) :: kin
    type(general_links_input_t) :: link_input
    type(spatial_link_t), allocatable :: links(:)
    type(transient_settings_t) :: s
    type(spatial_loads_input_t) :: loads
    type(spatial_point_load_t), allocatable :: no_loads(:)
    type(general_support_input_t) :: support
    logical :: has_loads, has_support
    type(general_flex_model_t), target :: model
    type(lsode_t) :: ode
    type(progress_t) :: bar
    type(element_peaks_t) :: stress_peaks
    real(dp), allocatable :: y(:), omega_n(:)
    real(dp) :: t_end, dt_out, t, t0, cpu0, cpu1, ke, se, gravity(3), rate
    integer :: k, n_out
    character(len=32), allocatable :: names(:)
    character(len=48), allocatable :: labels(:)

    call read_general_mechanism(deck, mech, kin, err)
    if (err%failed()) return
    call read_general_links(deck, mech%n_links, link_input, err)
    if (err%failed()) return
    call read_transient_settings(deck, s, err)
    if (err%failed()) return
    call read_spatial_loads(deck, loads, has_loads, err)
    if (err%failed()) return
    call read_general_support(deck, mech, support, has_support, err)
    if (err%failed()) return
    rate = constant_rate(mech)
    block   ! a joint the flexible model does not take: named with its line
      integer :: j
      character(len=:), allocatable :: why
      call unsupported_joint(kin, j, why)
      if (j > 0) then
        call invalid_value(deck, 'general_mechanism', 'joint_kind('//str(j)//')', ''''// &
                           trim(mech%input%joint_kind(j))//'''', why, err)
        return
      end if
    end block
    call check_supported(deck, s, loads, rate, err)
    if (err%failed()) return
    call echo_general_mechanism(mech, out)
    call echo_general_links(link_input, out)
    call echo_transient_settings(out)
    if (has_loads) call echo_spatial_loads(loads, out)
    if (has_support) call echo_general_support(support, out)
    call build_general_links(deck, link_input, mech%n_links, links, err)
    if (err%failed()) return
    call model%init_general(kin, links, s%effects, s%damping_beta, err, formulation=spatial_formulation_of(s), &
                            mounts=build_mounts(support, mech))
    if (err%failed()) then
      call input_error_in(deck, 'general_mechanism', err)
      return
    end if
    gravity = 0.0_dp
    if (loads%gravity_g > 0.0_dp) gravity = loads%gravity_g*loads%gravity_direction/norm2(loads%gravity_direction)
    allocate(no_loads(0))
    call model%set_loads(gravity, no_loads)
    call write_header(out, s, model)
    call write_loads(out, gravity, no_loads)

    allocate(omega_n(model%n))
    call model%linear_modes(omega_n, err)
    if (err%failed()) return
    call write_start_frequencies(out, omega_n)
    if (s%damping_beta > 0.0_dp) call out%comment('stiffness-proportional damping beta = '// &
      str(s%damping_beta)//' s: zeta_1 = '//str(0.5_dp*s%damping_beta*omega_n(1), 6))

    allocate(y(model%state_size()))
    call initial_state(deck, out, s, loads%initial_static, model, t0, y, err)
    if (err%failed()) return
    if (s%t_end > 0.0_dp) then
      t_end = t0 + s%t_end
      dt_out = s%output_step_t
    else
      t_end = t0 + s%revolutions*two_pi/rate
      dt_out = s%output_step_deg*pi/180.0_dp/rate
    end if
    n_out = max(1, nint((t_end - t0)/dt_out))
    dt_out = (t_end - t0)/n_out
    call choose_settings(out, s, model, y, t0, t_end, max(rate, two_pi/(t_end - t0)), err)   ! those the deck left out
    if (err%failed()) return
    call start_integrator(out, s, model%kd, t0, size(y), ode, err)
    if (err%failed()) return

    call write_columns(out, model, names)
    allocate(labels(size(model%el)))
    do k = 1, size(labels)     ! the summary names elements by their links
      labels(k) = trim(mech%links(model%link_of(k))%name)//' (element '//str(k)//')'
    end do
    call stress_peaks%init(labels, .true., model%crank_angle(t0)*180.0_dp/pi)
    call bar%start('general_transient', t0, t_end)
    call cpu_time(cpu0)
    call record_row(out, model, t0, y, stress_peaks, size(names), err)
    do k = 1, n_out
      t = t0 + k*dt_out
      if (k == n_out) t = max(t, t_end)
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      call record_row(out, model, t, y, stress_peaks, size(names), err)
      if (err%failed()) exit
      call bar%update(t)
    end do
    call bar%finish()
    call cpu_time(cpu1)
    if (err%failed()) call model%name_stop_angle('general_transient analysis', ode%t, err)

    call stress_peaks%write(out, 'last')
    call stress_peaks%write(out, 'whole')
    call model%energies(ode%t, y(1::2), y(2::2), ke, se)
    call out%summary('final kinetic energy (rigid and elastic motion)', str(ke, 8)//' lb in')
    call out%summary('final elastic strain energy', str(se, 8)//' lb in')
    if (.not. err%failed() .and. len_trim(s%restart_out) > 0) then
      call write_restart_file(s%restart_out, ode%t, y, err)
      if (.not. err%failed()) call out%comment('final state saved to restart file '//trim(s%restart_out))
    end if
    model%kin%total_iterations = model%gk%total_iterations   ! (the footer reads the kinematics' Newton count there)
    call write_cost(out, s, ode, model, cpu1 - cpu0, max(0.0_dp, (ode%t - t0)*rate/two_pi))
  end subroutine run_general_transient

  !> The first driver's constant rate (rad/s or length/s), 0 if it has none.
  real(dp) function constant_rate(mech) result(rate)
    type(general_mechanism_t), intent(in) :: mech
    rate = 0.0_dp
    if (mech%n_drivers == 0) return
    if (mech%drivers(1)%motion%kind == motion_constant .and. .not. allocated(mech%drivers(1)%motion%t)) &
      rate = abs(mech%drivers(1)%motion%rate)
  end function constant_rate

  !> The time span and what the analysis does not take from the shared groups.
  subroutine check_supported(deck, s, loads, rate, err)
    type(deck_t), intent(in) :: deck
    type(transient_settings_t), intent(in) :: s
    type(spatial_loads_input_t), intent(in) :: loads
    real(dp), intent(in) :: rate
    type(error_t), intent(inout) :: err
    if (.not. (s%t_end > 0.0_dp .or. rate > 0.0_dp)) then
      call invalid_value(deck, 'transient', 't_end', str(s%t_end), 'the first driver does not turn at a constant '// &
                         'rate: give the time span t_end > 0 (and output_step_t)', err)
    else if (s%t_end > 0.0_dp .and. .not. s%output_step_t > 0.0_dp) then
      call invalid_value(deck, 'transient', 'output_step_t', str(s%output_step_t), &
                         'the output step (s) of a run over t_end must be > 0', err)
    else if (all(s%formulation /= [character(len=16) :: 'exact', 'consistent', 'default'])) then
      call invalid_value(deck, 'effects', 'formulation', ''''//trim(s%formulation)//'''', &
                         'the spatial element has the formulations ''consistent'' (quintic u) and ''exact'' '// &
                         '(Kear''s linear u); ''default'' is consistent with stretching on, else exact', err)
    else if (loads%n_loads > 0) then
      call invalid_value(deck, 'spatial_loads', 'n_loads', str(loads%n_loads), 'the general_transient analysis '// &
                         'takes gravity and the static start from &spatial_loads, no point loads', err)
    else if (loads%initial_static .and. s%initial /= 'rigid') then
      call invalid_value(deck, 'spatial_loads', 'initial_static', 'T', 'the static start replaces the '// &
                         'rigid-body start: it needs initial = ''rigid'' in &transient, not '''//trim(s%initial)//'''', err)
    else if (loads%initial_static .and. .not. rate > 0.0_dp) then
      call invalid_value(deck, 'spatial_loads', 'initial_static', 'T', 'the static start''s rate is taken over '// &
                         '1e-3 of a turn of the first driver, which needs a constant rate', err)
    end if
  end subroutine check_supported

  !> The row at time tt: joints' elastic translations, link ends, link roots'
  !> resultants, element stresses (with the element peaks).
  subroutine record_row(out, model, tt, y, stress_peaks, n_columns, err)
    type(table_t), intent(inout) :: out
    type(general_flex_model_t), target, intent(inout) :: model
    real(dp), intent(in) :: tt, y(:)
    type(element_peaks_t), intent(inout) :: stress_peaks
    integer, intent(in) :: n_columns
    type(error_t), intent(inout) :: err
    type(spatial_stress_t) :: stress(size(model%el))
    real(dp) :: row(n_columns), q(model%n), p(sdofs), drive
    integer :: kk, i, ee
    call model%set_time(tt)
    if (model%err%failed()) then
      call err%set('', model%err%text())
      return
    end if
    q = y(1::2)
    drive = driver_value(model, tt)
    call model%element_stresses(q, stress)
    row(1) = tt
    row(2) = drive
    kk = 2
    do i = 1, model%gk%mech%n_joints
      if (all(model%joint_dofs(:, i) == 0)) cycle
      row(kk + 1:kk + 3) = q(model%joint_dofs(:, i))
      kk = kk + 3
    end do
    do i = 1, model%support%count()
      row(kk + 1:kk + 3) = model%support%carried_force(i, q, y(2::2))
      kk = kk + 3
    end do
    do i = 1, size(model%glinks)
      ee = model%glinks(i)%first_element + model%glinks(i)%n_elements - 1
      p = spatial_to_local(model%rb(ee)%rot, model%table%gather(ee, q), model%el(ee)%local_rotation)
      row(kk + 1:kk + 6) = p(11:16)
      kk = kk + 6
    end do
    do i = 1, size(model%glinks)
      ee = model%glinks(i)%first_element
      row(kk + 1:kk + 4) = [stress(ee)%axial_force(1), stress(ee)%moment_y(1), stress(ee)%moment_z(1), &
                            stress(ee)%torque(1)]
      kk = kk + 4
    end do
    row(kk + 1:kk + size(stress)) = stress%max_abs_stress
    call stress_peaks%note(row(kk + 1:kk + size(stress)), drive)
    call out%row(row)
  end subroutine record_row

  !> The first driver's coordinate at t: deg for a revolute joint, else its slide.
  real(dp) function driver_value(model, t) result(v)
    type(general_flex_model_t), intent(in) :: model
    real(dp), intent(in) :: t
    v = model%crank_angle(t)
    if (model%gk%mech%n_drivers > 0) then
      if (model%gk%mech%joints(model%gk%mech%drivers(1)%joint)%kind == gjoint_revolute) v = v*180.0_dp/pi
    end if
  end function driver_value

  subroutine write_header(out, s, model)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(in) :: s
    type(general_flex_model_t), intent(in) :: model
    character(len=160), allocatable :: lines(:)
    integer :: l
    character(len=:), allocatable :: text
    text = 'flexible general mechanism: '//trim(merge('spatial', 'planar ', model%gk%mech%spatial))//', '// &
           str(model%gk%mech%n_links)//' links, '//str(model%gk%mech%n_joints)//' joints, '// &
           str(model%gk%mech%n_drivers)//' drivers; elements per link'
    do l = 1, size(model%glinks)
      text = text//' '//str(model%glinks(l)%n_elements)
    end do
    call out%comment(text)
    call out%comment('effects on: '//effects_summary(s%effects)//' (torsional inertia always; twist linear, '// &
                     'St. Venant, warping neglected)')
    if (model%formulation == spatial_formulation_consistent) then
      call out%comment('element formulation: consistent (u quintic with nodal u_x, u_xx: no membrane locking)')
    else
      call out%comment('element formulation: exact (Kear''s interpolation, u linear)')
    end if
    call out%comment('rigid-body motion: the general kinematics (Newton on the constraints) at every time '// &
                     'the integrator asks for')
    call model%table%describe(lines)
    call out%comments(lines)
    do l = 1, model%support%count()
      associate (mt => model%support%mounts(l))
        call out%comment('mount under ground joint '''//trim(mt%joint_name)//''' (global X, Y, Z): mass '// &
          str(mt%mass(1), 6)//', '//str(mt%mass(2), 6)//', '//str(mt%mass(3), 6)//' lb s^2/in; stiffness '// &
          str(mt%stiffness(1), 6)//', '//str(mt%stiffness(2), 6)//', '//str(mt%stiffness(3), 6)//' lb/in; '// &
          'damping '//str(mt%damping(1), 6)//', '//str(mt%damping(2), 6)//', '//str(mt%damping(3), 6)// &
          ' lb s/in; its displacement is the joint''s translation, its rigid-body position the nominal one')
      end associate
    end do
  end subroutine write_header

  subroutine write_columns(out, model, names)
    type(table_t), intent(inout) :: out
    type(general_flex_model_t), intent(in) :: model
    character(len=32), allocatable, intent(out) :: names(:)
    integer :: i, e
    character(len=3), parameter :: local(6) = ['u  ', 'v  ', 'w  ', 'tx ', 'ty ', 'tz ']
    character(len=3), parameter :: res(4) = ['N  ', 'My ', 'Mz ', 'T  ']
    character(len=2), parameter :: comp(3) = ['UX', 'UY', 'UZ'], force(3) = ['FX', 'FY', 'FZ']
    character(len=:), allocatable :: mounts
    names = [character(len=32) :: 't', 'drive']
    associate (m => model%gk%mech)
      do i = 1, m%n_joints
        if (all(model%joint_dofs(:, i) == 0)) cycle
        names = [character(len=32) :: names, (trim(m%joints(i)%name)//'_'//comp(e), e = 1, 3)]
      end do
      do i = 1, model%support%count()
        names = [character(len=32) :: names, (trim(model%support%mounts(i)%joint_name)//'_'//force(e), e = 1, 3)]
      end do
      do i = 1, m%n_links
        names = [character(len=32) :: names, (trim(m%links(i)%name)//'_'//trim(local(e))//'_end', e = 1, 6)]
      end do
      do i = 1, m%n_links
        names = [character(len=32) :: names, (trim(m%links(i)%name)//'_'//trim(res(e))//'_root', e = 1, 4)]
      end do
    end associate
    do e = 1, size(model%el)
      names = [character(len=32) :: names, 'sigma_max_e'//str(e)]
    end do
    mounts = ''
    if (model%support%count() > 0) mounts = '<joint>_F* = force its mount carries to the rigid ground, k u + c u'' '// &
      '(global, lb); '
    call out%comment('columns: t (s); drive = the first driver''s joint coordinate (deg, or the slide); '// &
      '<joint>_U* = elastic translation of each joint that moves along global X, Y, Z (in); '//mounts// &
      '<link>_u/v/w_end = elastic displacement of the link''s end 2 in its rigid-body axes (in); '// &
      '<link>_tx/ty/tz_end = its small rotation (tx twist, ty = -w_x, tz = v_x; rad); <link>_N/My/Mz/T_root '// &
      '= axial force (lb), bending moments (lb in) and St. Venant torque (lb in) at the link''s end 1; '// &
      'sigma_max_e<k> = largest |normal stress| in element k over its extreme fibres (psi)')
    call out%columns(names)
  end subroutine write_columns
end module general_transient_analysis
