!> The &transient and &effects groups of a transient-analysis deck: how to
!> integrate (DLSODE method, tolerances, span, output increment, damping,
!> initial state) and which physical effects to simulate.
module transient_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  use lsode_solver, only: max_steps_ceiling, max_steps_reason, mf_from_method, method_names
  use element_effects, only: element_effects_t
  use fast_format, only: min_digits, max_digits
  implicit none
  private
  public :: transient_settings_t, read_transient_settings, echo_transient_settings, max_points, check_mode_number

  integer, parameter :: max_points = 20          !< link points a deck can name
  integer, parameter, public :: max_shape_points = 16    !< intervals per element of the drawn shape
  !> rtol when a deck leaves it out: peaks to about 0.1 %, well inside the 1 %
  !> the default settings promise (doc/transient.md, "Default solver settings")
  real(dp), parameter, public :: default_rtol = 1.0e-6_dp

  !> The settings of a run; the default initialisation is the documented
  !> defaults (doc/decks.md).
  type :: transient_settings_t
    character(len=16) :: method = 'auto' !< 'auto': chosen from the model (transient_integration)
    integer :: mf = 0                    !< 0 while method = 'auto'
    real(dp) :: rtol = default_rtol
    real(dp) :: atol = -1.0_dp           !< < 0: from the model (transient_integration)
    real(dp) :: atol_rate = -1.0_dp      !< absolute tolerance of the rates; < 0: from the model, or atol
                                         !< when the deck gives atol
    real(dp) :: revolutions = 1.0_dp
    real(dp) :: output_step_deg = 5.0_dp
    real(dp) :: t_end = 0.0_dp           !< used when the driver does not turn (omega = 0)
    real(dp) :: output_step_t = 0.0_dp
    real(dp) :: damping_beta = 0.0_dp    !< stiffness-proportional damping, seconds
    character(len=16) :: initial = 'rigid'
    integer :: mode_number = 1
    real(dp) :: mode_amplitude = 0.0_dp
    character(len=256) :: restart_in = ''
    character(len=256) :: restart_out = ''
    integer :: max_steps = 200000
    integer :: max_order = -1            !< DLSODE's MAXORD; 0: its default (12 Adams, 5 BDF); < 0: from the model
    character(len=16) :: kinematics = 'table'   !< rigid motion: 'table' (per revolution) or 'direct'
    integer :: table_points = 720        !< crank angles per revolution in the table
    type(element_effects_t) :: effects   !< the papers' tracing constants; its defaults: all off = linear
    character(len=16) :: formulation = 'default'   !< element: 'default' (consistent with stretching on, else
                                         !< exact), 'consistent', 'exact', 'kear1987' (doc/element.md)
    character(len=16) :: output_rows = 'all'   !< rows written: 'all', 'last_revolution' or 'none'
    ! optional response columns (off: not computed; doc/transient.md, "Output")
    character(len=16) :: stress_columns = 'outer'   !< 'outer' (sigma_max only) or 'all' (+ bending, axial, M, N)
    logical :: link_points = .false.     !< columns of link points (u, w, deflection from the chord)
    character(len=16) :: point_link(max_points) = ''   !< links of the points; none named: every link's mid-span
    real(dp) :: point_at(max_points) = 0.5_dp   !< position along the link, 0 (end 1) .. 1 (end 2)
    integer :: shape_points = 0          !< > 0: link points every 1/shape_points of each element (drawn shapes)
    logical :: reactions = .false.       !< columns of joint reaction forces
    real(dp) :: stop_when_periodic = 0.0_dp   !< > 0: stop when successive revolutions' peaks agree to this
    integer :: output_digits = 0         !< significant digits of the rows: 0 = 16, or 3..12 (fast, narrow)
  end type transient_settings_t

  ! staging variables of the namelist groups
  character(len=16) :: method, initial, formulation, kinematics, output_rows, stress_columns
  real(dp) :: rtol, atol, atol_rate, revolutions, output_step_deg, t_end, output_step_t, damping_beta, mode_amplitude
  logical :: link_points, reactions
  character(len=16) :: point_link(max_points)
  real(dp) :: point_at(max_points), stop_when_periodic
  integer :: mode_number, max_steps, table_points, max_order, output_digits, shape_points
  character(len=256) :: restart_in, restart_out
  logical :: stretching, curvature, material, rotary_inertia, coupling
  namelist /transient/ method, rtol, atol, atol_rate, revolutions, output_step_deg, t_end, output_step_t, &
    damping_beta, initial, mode_number, mode_amplitude, restart_in, restart_out, max_steps, kinematics, &
    table_points, max_order, output_rows, stress_columns, link_points, point_link, point_at, reactions, &
    stop_when_periodic, output_digits, shape_points
  namelist /effects/ stretching, curvature, material, rotary_inertia, coupling, formulation

contains

  subroutine read_transient_settings(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(transient_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    type(transient_settings_t) :: defaults
    logical :: found

    call stage_from(defaults)
    call deck%read_group('transient', transient_group, .false., found, err)
    if (err%failed()) return
    call deck%read_group('effects', effects_group, .false., found, err)
    if (err%failed()) return

    s = transient_settings_t(method=method, mf=mf_from_method(method), rtol=rtol, atol=atol, atol_rate=atol_rate, &
      revolutions=revolutions, output_step_deg=output_step_deg, t_end=t_end, output_step_t=output_step_t, &
      damping_beta=damping_beta, initial=initial, mode_number=mode_number, mode_amplitude=mode_amplitude, &
      restart_in=restart_in, restart_out=restart_out, max_steps=max_steps, max_order=max_order, &
      kinematics=kinematics, table_points=table_points, output_rows=output_rows, stress_columns=stress_columns, &
      link_points=link_points, point_link=point_link, point_at=point_at, shape_points=shape_points, reactions=reactions, &
      stop_when_periodic=stop_when_periodic, output_digits=output_digits, formulation=formulation, &
      effects=element_effects_t(stretching, curvature, material, rotary_inertia, coupling))
    call validate(deck, s, err)
    if (err%failed()) return
    if (s%atol_rate < 0.0_dp .and. s%atol > 0.0_dp) s%atol_rate = s%atol
    call check_integer(deck, 'transient', 'max_order', s%max_order, err, at_least=-1, &
                       at_most=merge(5, 12, s%mf > 10), why='DLSODE''s orders: Adams 1..12, BDF 1..5 (0 = '// &
                       'DLSODE''s default, -1 = chosen from the model)')
  end subroutine read_transient_settings

  !> The namelist variables of both groups from a settings value (the defaults
  !> before a read).
  subroutine stage_from(s)
    type(transient_settings_t), intent(in) :: s
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
    output_rows = s%output_rows
    stress_columns = s%stress_columns
    link_points = s%link_points
    point_link = s%point_link
    point_at = s%point_at
    shape_points = s%shape_points
    reactions = s%reactions
    stop_when_periodic = s%stop_when_periodic
    output_digits = s%output_digits
    stretching = s%effects%stretching
    curvature = s%effects%curvature
    material = s%effects%material
    rotary_inertia = s%effects%rotary_inertia
    coupling = s%effects%coupling
    formulation = s%formulation
  end subroutine stage_from

  !> One line per variable: the allowed range and why (doc/decks.md).
  subroutine validate(deck, s, err)
    type(deck_t), intent(in) :: deck
    type(transient_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'transient'
    if (s%mf == 0 .and. s%method /= 'auto') then
      call invalid_value(deck, g, 'method', ''''//trim(s%method)//'''', 'must be auto (the default: chosen '// &
                         'from the model) or one of '//method_names, err)
      return
    end if
    call check_real(deck, g, 'rtol', s%rtol, err, at_least=1.0e-14_dp, below=0.1_dp, &
                    why='a relative error tolerance; below 1e-14 DLSODE works at round-off')
    if (abs(s%atol + 1.0_dp) > 0.0_dp) call check_real(deck, g, 'atol', s%atol, err, at_least=1.0e-30_dp, at_most=1.0e10_dp, &
      why='an absolute error tolerance; below 1e-30 DLSODE''s error weights overflow (-1: from the model)')
    call check_real(deck, g, 'atol_rate', s%atol_rate, err, at_least=-1.0_dp, at_most=1.0e10_dp, &
                    why='an absolute error tolerance of the rates; leave it out (-1) to use atol, or '// &
                    'the model''s choice when atol is left out too')
    if (err%failed()) return
    if (s%atol_rate < 1.0e-30_dp .and. s%atol_rate > -1.0_dp) call invalid_value(deck, g, 'atol_rate', &
      str(s%atol_rate), 'must be >= 1e-30, or left out (-1)', err)
    call check_real(deck, g, 'revolutions', s%revolutions, err, at_least=1.0e-6_dp, at_most=1.0e4_dp, &
                    why='a millionth of a turn is shorter than any output step; 4.9e-324 made the span vanish')
    call check_real(deck, g, 'output_step_deg', s%output_step_deg, err, above=0.0_dp, at_most=360.0_dp)
    if (err%failed()) return
    if (s%revolutions*360.0_dp > 1.0e7_dp*s%output_step_deg) call invalid_value(deck, g, 'output_step_deg', &
      str(s%output_step_deg), 'gives more than 1e7 output rows over '//str(s%revolutions)//' revolutions', err)
    call check_real(deck, g, 't_end', s%t_end, err, at_least=0.0_dp, at_most=1.0e6_dp, &
                    why='seconds: the span of a run without a turning driver, or with output_step_t > 0 instead of revolutions')
    call check_real(deck, g, 'output_step_t', s%output_step_t, err, at_least=0.0_dp, at_most=1.0e6_dp)
    if (err%failed()) return
    if (s%output_step_t > 0.0_dp .and. s%t_end > 0.0_dp) then
      if (s%t_end > 1.0e7_dp*s%output_step_t) call invalid_value(deck, g, 'output_step_t', str(s%output_step_t), &
                                                     'gives more than 1e7 output rows over t_end = '//str(s%t_end), err)
    end if
    call check_real(deck, g, 'damping_beta', s%damping_beta, err, at_least=0.0_dp, below=1.0_dp, why='seconds')
    call check_choice(deck, g, 'initial', s%initial, [character(len=16) :: 'rigid', 'mode', 'restart'], err)
    call check_real(deck, g, 'mode_amplitude', s%mode_amplitude, err, at_least=-1.0e3_dp, at_most=1.0e3_dp, &
                    why='length units of the largest modal displacement')
    if (s%initial == 'mode') call check_integer(deck, g, 'mode_number', s%mode_number, err, at_least=1)
    if (err%failed()) return
    if (s%initial == 'restart' .and. len_trim(s%restart_in) == 0) &
      call invalid_value(deck, g, 'restart_in', '''''', 'initial = ''restart'' needs a restart file', err)
    call check_choice(deck, g, 'kinematics', s%kinematics, [character(len=16) :: 'table', 'direct'], err)
    call check_integer(deck, g, 'table_points', s%table_points, err, at_least=36, at_most=1000000)
    call check_integer(deck, g, 'max_steps', s%max_steps, err, at_least=1, at_most=max_steps_ceiling, &
                       why=max_steps_reason)
    call check_choice(deck, g, 'output_rows', s%output_rows, [character(len=16) :: 'all', 'last_revolution', 'none'], err)
    call check_choice(deck, g, 'stress_columns', s%stress_columns, [character(len=16) :: 'outer', 'all'], err)
    call check_reals(deck, g, 'point_at', s%point_at, err, at_least=0.0_dp, at_most=1.0_dp, &
                     why='a fraction of the link''s length from its end 1')
    call check_integer(deck, g, 'shape_points', s%shape_points, err, at_least=0, at_most=max_shape_points, &
                       why='intervals per element of the drawn shape (0 = none); '//str(max_shape_points)// &
                       ' draws any curvature a quintic can take')
    call check_real(deck, g, 'stop_when_periodic', s%stop_when_periodic, err, at_least=0.0_dp, below=1.0_dp, &
                    why='a relative change of the per-revolution peaks (0 = off); 1 or more would stop at once')
    call check_integer(deck, g, 'output_digits', s%output_digits, err, at_least=0, at_most=max_digits, &
                       why='significant digits of the rows: 0 (16, the default) or '//str(min_digits)//'..'// &
                       str(max_digits)//' (the fast formatter; beyond 12 its last digit is not reliable)')
    if (err%failed()) return
    if (s%output_digits > 0 .and. s%output_digits < min_digits) call invalid_value(deck, g, 'output_digits', &
      str(s%output_digits), 'must be 0 or '//str(min_digits)//'..'//str(max_digits), err)
    call check_choice(deck, 'effects', 'formulation', s%formulation, &
                      [character(len=16) :: 'default', 'consistent', 'exact', 'kear1987'], err)
  end subroutine validate

  subroutine echo_transient_settings(out)
    type(table_t), intent(inout) :: out
    call out%echo_group(transient_group)
    call out%echo_group(effects_group)
  end subroutine echo_transient_settings

  !> The &transient group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine transient_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=transient, delim='apostrophe')
    else
      read(r%unit, nml=transient, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine transient_group

  !> The &effects group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine effects_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=effects, delim='apostrophe')
    else
      read(r%unit, nml=effects, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine effects_group

  !> initial = 'mode': mode_number must be a mode of the model (known only once
  !> the model is built; the range check of the deck is in the settings above).
  subroutine check_mode_number(deck, s, n_modes, err)
    type(deck_t), intent(in) :: deck
    type(transient_settings_t), intent(in) :: s
    integer, intent(in) :: n_modes
    type(error_t), intent(inout) :: err
    if (s%mode_number > n_modes) call invalid_value(deck, 'transient', 'mode_number', str(s%mode_number), &
                                                    'the model has only '//str(n_modes)//' modes', err)
  end subroutine check_mode_number
end module transient_settings
