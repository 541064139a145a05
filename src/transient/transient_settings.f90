!> The &transient and &effects groups of a transient-analysis deck: how to
!> integrate (DLSODE method, tolerances, span, output increment, damping,
!> initial state) and which physical effects to simulate.
module transient_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value
  use deck_checks, only: check_integer
  use table_output, only: table_t
  use lsode_solver, only: mf_from_method, method_names
  use kear_element, only: element_effects_t
  implicit none
  private
  public :: transient_settings_t, read_transient_settings, echo_transient_settings

  type :: transient_settings_t
    character(len=16) :: method = 'adams'
    integer :: mf = 10
    real(dp) :: rtol = 1.0e-6_dp
    real(dp) :: atol = 1.0e-9_dp
    real(dp) :: atol_rate = -1.0_dp                !< absolute tolerance of the rates; < 0: atol
    real(dp) :: revolutions = 1.0_dp
    real(dp) :: output_step_deg = 5.0_dp
    real(dp) :: t_end = 0.0_dp          !< used when the driver does not turn (omega = 0)
    real(dp) :: output_step_t = 0.0_dp
    real(dp) :: damping_beta = 0.0_dp   !< stiffness-proportional damping, seconds
    character(len=16) :: initial = 'rigid'
    integer :: mode_number = 1
    real(dp) :: mode_amplitude = 0.0_dp
    character(len=256) :: restart_in = ''
    character(len=256) :: restart_out = ''
    integer :: max_steps = 200000
    integer :: max_order = 0                       !< DLSODE's MAXORD; 0: its default (12 Adams, 5 BDF)
    character(len=16) :: kinematics = 'table'      !< rigid motion: 'table' (per revolution) or 'direct'
    integer :: table_points = 720                  !< crank angles per revolution in the table
    type(element_effects_t) :: effects             !< the papers' tracing constants, all off = linear
    character(len=16) :: formulation = 'default'   !< element: 'default' (consistent with stretching on, else
                                                   !< exact), 'consistent', 'exact', 'kear1987' (doc/element.md)
  end type transient_settings_t

  ! staging variables of the namelist groups
  character(len=16) :: method, initial, formulation, kinematics
  real(dp) :: rtol, atol, atol_rate, revolutions, output_step_deg, t_end, output_step_t, damping_beta, mode_amplitude
  integer :: mode_number, max_steps, table_points, max_order
  character(len=256) :: restart_in, restart_out
  logical :: stretching, curvature, material, rotary_inertia, coupling
  namelist /transient/ method, rtol, atol, atol_rate, revolutions, output_step_deg, t_end, output_step_t, &
    damping_beta, initial, mode_number, mode_amplitude, restart_in, restart_out, max_steps, kinematics, &
    table_points, max_order
  namelist /effects/ stretching, curvature, material, rotary_inertia, coupling, formulation

contains

  subroutine read_transient_settings(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(transient_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    logical :: found

    method = s%method
    rtol = s%rtol
    atol = s%atol
    atol_rate = s%atol_rate
    revolutions = s%revolutions
    output_step_deg = s%output_step_deg
    t_end = s%t_end
    output_step_t = s%output_step_t
    damping_beta = s%damping_beta
    initial = s%initial
    mode_number = s%mode_number
    mode_amplitude = s%mode_amplitude
    restart_in = s%restart_in
    restart_out = s%restart_out
    max_steps = s%max_steps
    kinematics = s%kinematics
    table_points = s%table_points
    max_order = s%max_order
    call deck%read_group('transient', read_transient_group, .false., found, err)
    if (err%failed()) return

    stretching = s%effects%stretching
    curvature = s%effects%curvature
    material = s%effects%material
    rotary_inertia = s%effects%rotary_inertia
    coupling = s%effects%coupling
    formulation = s%formulation
    call deck%read_group('effects', read_effects_group, .false., found, err)
    if (err%failed()) return

    s%method = method
    s%mf = mf_from_method(method)
    s%rtol = rtol
    s%atol = atol
    s%atol_rate = atol_rate
    if (.not. atol_rate > 0.0_dp) s%atol_rate = atol
    s%revolutions = revolutions
    s%output_step_deg = output_step_deg
    s%t_end = t_end
    s%output_step_t = output_step_t
    s%damping_beta = damping_beta
    s%initial = initial
    s%mode_number = mode_number
    s%mode_amplitude = mode_amplitude
    s%restart_in = restart_in
    s%restart_out = restart_out
    s%max_steps = max_steps
    s%kinematics = kinematics
    s%table_points = table_points
    s%max_order = max_order
    s%effects = element_effects_t(stretching, curvature, material, rotary_inertia, coupling)
    s%formulation = formulation
    call validate(deck, s, err)
    call check_integer(deck, 'transient', 'max_order', s%max_order, err, at_least=0, &
                       at_most=merge(12, 5, s%mf == 10), why='DLSODE''s orders: Adams 1..12, BDF 1..5 (0 = default)')
  end subroutine read_transient_settings

  subroutine validate(deck, s, err)
    type(deck_t), intent(in) :: deck
    type(transient_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'transient'
    if (s%mf == 0) then
      call invalid_value(deck, g, 'method', ''''//trim(s%method)//'''', 'must be one of '//method_names, err)
    else if (.not. (s%rtol > 0.0_dp .and. s%rtol < 0.1_dp)) then
      call invalid_value(deck, g, 'rtol', str(s%rtol), 'must lie in (0, 0.1)', err)
    else if (.not. (s%atol > 0.0_dp)) then
      call invalid_value(deck, g, 'atol', str(s%atol), 'must be > 0', err)
    else if (.not. (atol_rate > 0.0_dp .or. atol_rate < -0.5_dp)) then   ! the default is -1
      call invalid_value(deck, g, 'atol_rate', str(atol_rate), 'must be > 0 (or left out: then atol)', err)
    else if (.not. (s%revolutions > 0.0_dp .and. s%revolutions <= 1.0e4_dp)) then
      call invalid_value(deck, g, 'revolutions', str(s%revolutions), 'must lie in (0, 10000]', err)
    else if (.not. (s%output_step_deg > 0.0_dp .and. s%output_step_deg <= 360.0_dp)) then
      call invalid_value(deck, g, 'output_step_deg', str(s%output_step_deg), 'must lie in (0, 360]', err)
    else if (.not. (s%t_end >= 0.0_dp)) then
      call invalid_value(deck, g, 't_end', str(s%t_end), 'must be >= 0', err)
    else if (.not. (s%output_step_t >= 0.0_dp)) then
      call invalid_value(deck, g, 'output_step_t', str(s%output_step_t), 'must be >= 0', err)
    else if (s%output_step_t > 0.0_dp .and. s%t_end > 0.0_dp .and. s%t_end/s%output_step_t > 1.0e7_dp) then
      call invalid_value(deck, g, 'output_step_t', str(s%output_step_t), &
                         'gives more than 1e7 output rows over t_end = '//str(s%t_end), err)
    else if (.not. (s%damping_beta >= 0.0_dp .and. s%damping_beta < 1.0_dp)) then
      call invalid_value(deck, g, 'damping_beta', str(s%damping_beta), 'must lie in [0, 1) seconds', err)
    else if (all(s%initial /= [character(len=16) :: 'rigid', 'mode', 'restart'])) then
      call invalid_value(deck, g, 'initial', ''''//trim(s%initial)//'''', &
                         'must be ''rigid'', ''mode'' or ''restart''', err)
    else if (s%initial == 'mode' .and. s%mode_number < 1) then
      call invalid_value(deck, g, 'mode_number', str(s%mode_number), 'must be >= 1', err)
    else if (s%initial == 'restart' .and. len_trim(s%restart_in) == 0) then
      call invalid_value(deck, g, 'restart_in', '''''', 'initial = ''restart'' needs a restart file', err)
    else if (all(s%kinematics /= [character(len=16) :: 'table', 'direct'])) then
      call invalid_value(deck, g, 'kinematics', ''''//trim(s%kinematics)//'''', 'must be ''table'' or ''direct''', err)
    else if (s%table_points < 36 .or. s%table_points > 1000000) then
      call invalid_value(deck, g, 'table_points', str(s%table_points), 'must lie in 36..1000000', err)
    else if (s%max_steps < 1) then
      call invalid_value(deck, g, 'max_steps', str(s%max_steps), 'must be >= 1', err)
    else if (all(s%formulation /= [character(len=16) :: 'default', 'consistent', 'exact', 'kear1987'])) then
      call invalid_value(deck, 'effects', 'formulation', ''''//trim(s%formulation)//'''', &
                         'must be ''default'', ''consistent'', ''exact'' or ''kear1987''', err)
    end if
  end subroutine validate

  subroutine echo_transient_settings(out)
    type(table_t), intent(inout) :: out
    integer :: u
    u = out%echo_unit()
    write(u, nml=transient, delim='apostrophe')
    write(u, nml=effects, delim='apostrophe')
    call out%end_echo()
  end subroutine echo_transient_settings

  subroutine read_transient_group(unit, ios, iomsg)
    integer, intent(in) :: unit
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    read(unit, nml=transient, iostat=ios, iomsg=iomsg)
  end subroutine read_transient_group

  subroutine read_effects_group(unit, ios, iomsg)
    integer, intent(in) :: unit
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    read(unit, nml=effects, iostat=ios, iomsg=iomsg)
  end subroutine read_effects_group
end module transient_settings
