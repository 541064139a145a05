!> The &design group of the `design` analysis (doc/design.md, doc/decks.md):
!> the design variables and their bounds, the objective and the
!> constraints, the evaluator and the design loop's settings.  The type
!> carries the documented defaults; read_design_settings stages them, reads
!> the group, checks every value against the mechanism and echoes it.
module design_settings
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  use linkage, only: mechanism_t, profile_constant
  use shaking_force, only: shaking_supported
  implicit none
  private
  public :: design_settings_t, read_design_settings, read_design_group, echo_design_settings, unset_value

  integer, parameter :: max_vars = 20
  integer, parameter :: max_points = 72
  integer, parameter :: max_speeds = 8
  integer, parameter :: max_deflections = 8
  integer, parameter :: max_bearings = 8
  !> a value not given (bounds, speeds, target points: required or counted)
  real(dp), parameter :: unset = -huge(1.0_dp)
  real(dp), parameter :: unset_value = unset

  !> The group's values; the default initialisation is the documented
  !> defaults (doc/decks.md).
  type :: design_settings_t
    character(len=32) :: variables(max_vars) = ''
    real(dp) :: lower(max_vars) = unset, upper(max_vars) = unset
    real(dp) :: scale(max_vars) = 0.0_dp          !< 0: the initial value's magnitude
    character(len=32) :: objective = 'mass'
    character(len=16) :: evaluator = 'shooting'
    character(len=16) :: hessian = 'gauss'
    !> '' before the check: 'variational' with the shooting evaluator, else 'differences'
    character(len=16) :: derivatives = ''
    character(len=16) :: peak_stress = 'max'
    !> 'none': the peaks at the samples; 'parabola': read between them
    character(len=16) :: peak_interpolation = 'none'
    real(dp) :: ks_rho = 200.0_dp
    real(dp) :: stress_allowable = 0.0_dp, frequency_factor = 0.0_dp   !< 0: off
    real(dp) :: xtol = 1.0e-3_dp, feas_tol = 1.0e-3_dp, move_limit = 0.3_dp
    integer :: max_iterations = 30, samples = 72
    !> the transient evaluator: its periodicity test and revolution limit
    real(dp) :: stop_when_periodic = 1.0e-6_dp
    integer :: max_revolutions = 200
    !> operating speeds (none: the &mechanism omega); n_speeds given (after the check)
    real(dp) :: speeds(max_speeds) = unset
    integer :: objective_speed = 0
    integer :: n_speeds = 0
    !> path objectives: the coupler point and its targets
    integer :: path_link = 0
    real(dp) :: path_r = 0.0_dp, path_angle_deg = 0.0_dp
    real(dp) :: path_x(max_points) = unset, path_y(max_points) = unset, path_dgamma_deg(max_points) = unset
    !> deflection constraints: named link points and their limits
    integer :: deflection_link(max_deflections) = 0
    real(dp) :: deflection_at(max_deflections) = 0.5_dp, deflection_limit(max_deflections) = 0.0_dp
    character(len=8) :: deflection_from(max_deflections) = 'chord'
    !> movability: the transmission angle at a joint and its least value
    integer :: transmission_joint = 0
    real(dp) :: transmission_min_deg = 40.0_dp
    !> the joints of the bearing-force objectives
    integer :: bearing_joints(max_bearings) = 0
  end type design_settings_t

  ! staging variables of &design
  character(len=32) :: variables(max_vars), objective
  character(len=16) :: evaluator, hessian, derivatives, peak_stress, peak_interpolation
  real(dp) :: lower(max_vars), upper(max_vars), scale(max_vars), stress_allowable, frequency_factor
  real(dp) :: xtol, feas_tol, move_limit, ks_rho
  integer :: max_iterations, samples
  real(dp) :: stop_when_periodic
  integer :: max_revolutions
  real(dp) :: speeds(max_speeds)
  integer :: objective_speed
  integer :: path_link
  real(dp) :: path_r, path_angle_deg, path_x(max_points), path_y(max_points), path_dgamma_deg(max_points)
  integer :: deflection_link(max_deflections)
  real(dp) :: deflection_at(max_deflections), deflection_limit(max_deflections)
  character(len=8) :: deflection_from(max_deflections)
  integer :: transmission_joint
  real(dp) :: transmission_min_deg
  integer :: bearing_joints(max_bearings)
  namelist /design/ variables, lower, upper, scale, objective, evaluator, stress_allowable, &
                    frequency_factor, max_iterations, samples, xtol, feas_tol, move_limit, hessian, derivatives, &
                    speeds, objective_speed, stop_when_periodic, max_revolutions, &
                    path_link, path_r, path_angle_deg, path_x, path_y, path_dgamma_deg, peak_stress, ks_rho, peak_interpolation, &
                    deflection_link, deflection_at, deflection_limit, deflection_from, transmission_joint, &
                    transmission_min_deg, bearing_joints

contains

  !> Read &design (required) and check every value against the mechanism:
  !> the choices and limits, what the objective needs, the operating speeds,
  !> the deflection points and the movability joint.  The variables' names,
  !> bounds and initial values are checked where they are parsed
  !> (design_analysis).
  subroutine read_design_settings(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(design_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    call read_design_group(deck, s, err)
    if (err%failed()) return
    call check_objective(deck, mech, s, err)
    if (err%failed()) return
    call check_deflections(deck, mech, s, err)
    if (err%failed()) return
    call check_transmission(deck, mech, s, err)
  end subroutine read_design_settings

  !> Read &design (required): the variables named one after another and the
  !> checks that need no mechanism (check_settings; the spatial design's
  !> checks follow in its own module).
  subroutine read_design_group(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    logical :: found
    integer :: n
    call stage_from(s)        ! (intent(out): the defaults)
    call deck%read_group('design', design_group, .true., found, err)
    if (err%failed()) return
    call staged(s)
    n = count(len_trim(s%variables) > 0)
    if (n == 0 .or. any(len_trim(s%variables(1:n)) == 0)) then
      call invalid_value(deck, 'design', 'variables', str(n)//' given', 'name one or more design variables, '// &
                         'one after another (e.g. ''link_h(1)'', ''link_b(2)'', ''joint_x(4)'')', err)
      return
    end if
    call check_settings(deck, s, err)
  end subroutine read_design_group

  !> Echo the group into the output header.
  subroutine echo_design_settings(s, out)
    type(design_settings_t), intent(in) :: s
    type(table_t), intent(inout) :: out
    call stage_from(s)
    call out%echo_group(design_group)
  end subroutine echo_design_settings

  !> The namelist variables from a settings value (the defaults before a read).
  subroutine stage_from(s)
    type(design_settings_t), intent(in) :: s
    variables = s%variables
    lower = s%lower
    upper = s%upper
    scale = s%scale
    objective = s%objective
    evaluator = s%evaluator
    hessian = s%hessian
    derivatives = s%derivatives
    peak_stress = s%peak_stress
    peak_interpolation = s%peak_interpolation
    ks_rho = s%ks_rho
    stress_allowable = s%stress_allowable
    frequency_factor = s%frequency_factor
    xtol = s%xtol
    feas_tol = s%feas_tol
    move_limit = s%move_limit
    max_iterations = s%max_iterations
    samples = s%samples
    stop_when_periodic = s%stop_when_periodic
    max_revolutions = s%max_revolutions
    speeds = s%speeds
    objective_speed = s%objective_speed
    path_link = s%path_link
    path_r = s%path_r
    path_angle_deg = s%path_angle_deg
    path_x = s%path_x
    path_y = s%path_y
    path_dgamma_deg = s%path_dgamma_deg
    deflection_link = s%deflection_link
    deflection_at = s%deflection_at
    deflection_limit = s%deflection_limit
    deflection_from = s%deflection_from
    transmission_joint = s%transmission_joint
    transmission_min_deg = s%transmission_min_deg
    bearing_joints = s%bearing_joints
  end subroutine stage_from

  !> The settings value from the namelist variables (after a read).
  subroutine staged(s)
    type(design_settings_t), intent(inout) :: s
    s%variables = variables
    s%lower = lower
    s%upper = upper
    s%scale = scale
    s%objective = objective
    s%evaluator = evaluator
    s%hessian = hessian
    s%derivatives = derivatives
    s%peak_stress = peak_stress
    s%peak_interpolation = peak_interpolation
    s%ks_rho = ks_rho
    s%stress_allowable = stress_allowable
    s%frequency_factor = frequency_factor
    s%xtol = xtol
    s%feas_tol = feas_tol
    s%move_limit = move_limit
    s%max_iterations = max_iterations
    s%samples = samples
    s%stop_when_periodic = stop_when_periodic
    s%max_revolutions = max_revolutions
    s%speeds = speeds
    s%objective_speed = objective_speed
    s%path_link = path_link
    s%path_r = path_r
    s%path_angle_deg = path_angle_deg
    s%path_x = path_x
    s%path_y = path_y
    s%path_dgamma_deg = path_dgamma_deg
    s%deflection_link = deflection_link
    s%deflection_at = deflection_at
    s%deflection_limit = deflection_limit
    s%deflection_from = deflection_from
    s%transmission_joint = transmission_joint
    s%transmission_min_deg = transmission_min_deg
    s%bearing_joints = bearing_joints
  end subroutine staged

  !> The &design group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine design_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=design, delim='apostrophe')
    else
      read(r%unit, nml=design, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine design_group
  !> The one-line checks of &design's choices, tolerances and limits.
  subroutine check_settings(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    call check_choice(deck, g, 'objective', s%objective, [character(len=32) :: 'mass', 'path', 'path_rigid', &
                      'shaking', 'shaking_peak', 'bearing', 'bearing_peak'], err)
    call check_choice(deck, g, 'evaluator', s%evaluator, [character(len=16) :: 'shooting', 'harmonic', 'transient'], err)
    call check_real(deck, g, 'stop_when_periodic', s%stop_when_periodic, err, at_least=1.0e-10_dp, at_most=1.0e-2_dp, &
                    why='largest relative change of the sampled response per revolution (transient evaluator); '// &
                    'below 1e-10 it is integration noise')
    call check_integer(deck, g, 'max_revolutions', s%max_revolutions, err, at_least=2, at_most=100000, &
                       why='revolutions the transient evaluator may take to its periodic state (two to compare)')
    call check_choice(deck, g, 'hessian', s%hessian, [character(len=16) :: 'gauss', 'structured'], err)
    call check_choice(deck, g, 'peak_stress', s%peak_stress, [character(len=16) :: 'max', 'ks'], err)
    call check_choice(deck, g, 'peak_interpolation', s%peak_interpolation, &
                      [character(len=16) :: 'none', 'parabola'], err)
    call check_real(deck, g, 'ks_rho', s%ks_rho, err, at_least=10.0_dp, at_most=1.0e5_dp, &
                    why='sharpness of the KS aggregate of ln(stress) over the samples: it lies above the '// &
                    'largest by at most ln(samples)/ks_rho')
    ! the periodic orbit's sensitivities by default where they apply (the
    ! exact periodic state); the other evaluators difference their analyses
    if (len_trim(s%derivatives) == 0) s%derivatives = merge('variational', 'differences', s%evaluator == 'shooting')
    call check_choice(deck, g, 'derivatives', s%derivatives, [character(len=16) :: 'variational', 'differences'], err)
    if (.not. err%failed() .and. s%derivatives == 'variational' .and. s%evaluator /= 'shooting') &
      call invalid_value(deck, g, 'derivatives', '''variational''', 'the sensitivities of the periodic orbit need '// &
                         'evaluator = ''shooting'' (the exact periodic state); use ''differences''', err)
    ! the constraints are logarithms of ratios to these: a subnormal one made
    ! the ratio 0 or infinite (fuzz seed 12, case 1990: log(0) trapped)
    call check_real(deck, g, 'stress_allowable', s%stress_allowable, err, at_least=1.0e-3_dp, at_most=1.0e12_dp, &
                    why='0 = no stress constraint', or_zero=.true.)
    call check_real(deck, g, 'frequency_factor', s%frequency_factor, err, at_least=1.0e-3_dp, at_most=1.0e3_dp, &
                    why='lowest natural frequency >= factor x crank speed; 0 = no frequency constraint', or_zero=.true.)
    call check_integer(deck, g, 'max_iterations', s%max_iterations, err, at_least=1, at_most=1000)
    call check_integer(deck, g, 'samples', s%samples, err, at_least=8, at_most=3600, &
                       why='crank angles per revolution where stresses and frequencies are taken')
    call check_real(deck, g, 'xtol', s%xtol, err, at_least=1.0e-8_dp, below=1.0_dp, &
                    why='design step test, relative change of sizes; below 1e-8 it is analysis noise')
    call check_real(deck, g, 'feas_tol', s%feas_tol, err, at_least=1.0e-8_dp, below=1.0_dp, &
                    why='allowed ln(stress/allowable) etc.: a relative violation')
    call check_real(deck, g, 'move_limit', s%move_limit, err, at_least=1.0e-3_dp, at_most=2.0_dp, &
                    why='initial largest change of ln(size) per design iteration; its inverse weighs the step')
  end subroutine check_settings

  !> What the objective needs (the shaking force's model, a path's targets,
  !> a constraint for the least mass), the operating speeds (n_speeds given)
  !> and a crank turning at constant speed.
  subroutine check_objective(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    if (s%objective == 'shaking' .or. s%objective == 'shaking_peak') then
      if (len(shaking_supported(mech)) > 0) then
        call invalid_value(deck, g, 'objective', ''''//trim(s%objective)//'''', 'the shaking force is not built when '// &
                           shaking_supported(mech), err)
        return
      end if
    else if (s%objective == 'bearing' .or. s%objective == 'bearing_peak') then
      call check_bearings(deck, mech, s, err)
      if (err%failed()) return
    else if (s%objective /= 'mass') then
      call check_path(deck, mech, s, err)
      if (err%failed()) return
    else if (.not. (s%stress_allowable > 0.0_dp .or. s%frequency_factor > 0.0_dp .or. any(s%deflection_link /= 0) .or. &
                    s%transmission_joint /= 0)) then
      call invalid_value(deck, g, 'stress_allowable', '0', 'a minimum-mass design needs a stress, a '// &
                         'frequency or a deflection constraint (else the minimum is the lower bounds)', err)
      return
    end if
    call check_speeds(deck, s, err)
    if (err%failed()) return
    if (s%frequency_factor > 0.0_dp .and. .not. abs(mech%driver%omega) > 0.0_dp) then
      call invalid_value(deck, g, 'frequency_factor', str(s%frequency_factor), 'needs a turning crank (omega > 0)', err)
      return
    end if
    if (.not. mech%driver%omega > 0.0_dp .or. mech%driver%profile /= profile_constant) &
      call invalid_value(deck, 'mechanism', 'omega', str(mech%driver%omega), 'a design at the steady state '// &
                         'needs a crank turning at constant speed > 0', err)
  end subroutine check_objective

  !> The operating speeds given (n_speeds; none: the deck's omega) and the
  !> objective's speed.
  subroutine check_speeds(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    integer :: n_speeds
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    integer :: i
    logical :: given(max_speeds)
    ! given: not the sentinel (a NaN counts as given, and check_reals names it)
    do i = 1, max_speeds
      given(i) = .not. ieee_is_finite(s%speeds(i))
      if (.not. given(i)) given(i) = s%speeds(i) > 0.5_dp*unset
    end do
    n_speeds = count(given)
    if (n_speeds > 0) then
      if (.not. all(given(1:n_speeds))) then
        call invalid_value(deck, g, 'speeds', str(n_speeds)//' given, then a gap', 'give the operating speeds '// &
                           'one after another, speeds(1), speeds(2), ...', err)
        return
      end if
    end if
    s%n_speeds = n_speeds
    call check_reals(deck, g, 'speeds', s%speeds(1:n_speeds), err, at_least=1.0e-6_dp, at_most=1.0e5_dp, &
                     why='crank speeds (rad/s) the design must satisfy; > 0: a steady state needs a turning crank')
    call check_integer(deck, g, 'objective_speed', s%objective_speed, err, at_least=0, at_most=n_speeds, &
                       why='0 = the objective summed over the speeds; i = at speeds(i) only')
  end subroutine check_speeds

  !> The coupler point and its target points (path objectives).
  subroutine check_path(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    integer :: np, k
    call check_integer(deck, g, 'path_link', s%path_link, err, at_least=1, at_most=mech%n_links, &
                       why='the link that carries the coupler point')
    call check_real(deck, g, 'path_r', s%path_r, err, at_least=0.0_dp, at_most=1.0e3_dp*mech%length_scale, &
                    why='distance of the coupler point from the link''s end 1; within 1000 mean link lengths')
    call check_real(deck, g, 'path_angle_deg', s%path_angle_deg, err, at_least=-360.0_dp, at_most=360.0_dp, &
                    why='angle of the coupler point from the link''s line, degrees')
    if (err%failed()) return
    np = count(s%path_x > 0.5_dp*unset)
    if (np == 0 .or. any(s%path_x(1:np) <= 0.5_dp*unset)) then
      call invalid_value(deck, g, 'path_x', str(np)//' given', 'a path objective needs target points '// &
                         'path_x(i), path_y(i), path_dgamma_deg(i), i = 1, 2, ... one after another', err)
      return
    end if
    do k = 1, np
      if (.not. s%path_y(k) > 0.5_dp*unset) then
        call invalid_value(deck, g, 'path_y('//str(k)//')', 'not given', 'every target point needs path_x, '// &
                           'path_y and path_dgamma_deg', err)
        return
      end if
      if (.not. s%path_dgamma_deg(k) > 0.5_dp*unset) then
        call invalid_value(deck, g, 'path_dgamma_deg('//str(k)//')', 'not given', 'every target point needs '// &
                           'path_x, path_y and path_dgamma_deg', err)
        return
      end if
      call check_real(deck, g, 'path_x('//str(k)//')', s%path_x(k), err, at_least=-1.0e8_dp, at_most=1.0e8_dp, &
                      why='target point coordinate')
      call check_real(deck, g, 'path_y('//str(k)//')', s%path_y(k), err, at_least=-1.0e8_dp, at_most=1.0e8_dp, &
                      why='target point coordinate')
      call check_real(deck, g, 'path_dgamma_deg('//str(k)//')', s%path_dgamma_deg(k), err, at_least=-360.0_dp, &
                      at_most=360.0_dp, why='crank angle of target point k from theta0_deg, degrees')
      if (err%failed()) return
    end do
    if (any(s%path_x(np + 1:) > 0.5_dp*unset) .or. any(s%path_y(np + 1:) > 0.5_dp*unset) .or. &
        any(s%path_dgamma_deg(np + 1:) > 0.5_dp*unset)) then
      call invalid_value(deck, g, 'path_y', 'more values than path_x', 'give x, y and the crank angle of '// &
                         'every target point', err)
      return
    end if
  end subroutine check_path

  !> The named link points of the deflection constraints: given one after
  !> another, each on a link, at a fraction of its length, with a limit.
  subroutine check_deflections(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    integer :: np, k
    np = count(s%deflection_link /= 0)
    if (np == 0) return
    if (any(s%deflection_link(1:np) == 0)) then
      call invalid_value(deck, g, 'deflection_link', str(np)//' given, then a gap', 'give the deflection points '// &
                         'one after another, deflection_link(1), deflection_link(2), ...', err)
      return
    end if
    do k = 1, np
      call check_integer(deck, g, 'deflection_link('//str(k)//')', s%deflection_link(k), err, at_least=1, &
                         at_most=mech%n_links, why='the link that carries deflection point '//str(k))
      call check_real(deck, g, 'deflection_at('//str(k)//')', s%deflection_at(k), err, at_least=0.0_dp, &
                      at_most=1.0_dp, why='the point''s distance from the link''s end 1 as a fraction of its length')
      call check_real(deck, g, 'deflection_limit('//str(k)//')', s%deflection_limit(k), err, &
                      at_least=1.0e-8_dp*mech%length_scale, at_most=1.0e3_dp*mech%length_scale, &
                      why='largest elastic deflection of the point (the constraint is ln(deflection / limit) <= 0)')
      call check_choice(deck, g, 'deflection_from('//str(k)//')', s%deflection_from(k), &
                        [character(len=8) :: 'chord', 'rigid'], err)
      if (err%failed()) return
    end do
    if (count(s%deflection_link /= 0) /= np) call invalid_value(deck, g, 'deflection_link', 'more than '//str(np), &
      'at most '//str(max_deflections)//' points, given one after another', err)
  end subroutine check_deflections

  !> The joints of the bearing-force objectives: given one after another,
  !> each a joint of the mechanism; no link sliding through a sleeve (its
  !> end forces are not a node's).
  subroutine check_bearings(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    integer :: nj, k
    nj = count(s%bearing_joints /= 0)
    if (nj == 0 .or. any(s%bearing_joints(1:nj) == 0)) then
      call invalid_value(deck, g, 'bearing_joints', str(nj)//' given', 'the objective '''//trim(s%objective)// &
                         ''' needs the joints whose bearing force it takes, one after another: bearing_joints = 1, 4', &
                         err)
      return
    end if
    do k = 1, nj
      call check_integer(deck, g, 'bearing_joints('//str(k)//')', s%bearing_joints(k), err, at_least=1, &
                         at_most=mech%n_joints, why='a joint whose bearing force the objective takes')
      if (err%failed()) return
    end do
    if (len(shaking_supported(mech)) > 0) call invalid_value(deck, g, 'objective', ''''//trim(s%objective)//'''', &
      'the bearing forces are not built when '//shaking_supported(mech), err)
  end subroutine check_bearings

  !> The movability constraint: a joint where exactly two links meet, and
  !> the least transmission angle there.
  subroutine check_transmission(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(design_settings_t), intent(inout) :: s
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    call check_integer(deck, g, 'transmission_joint', s%transmission_joint, err, at_least=0, at_most=mech%n_joints, &
                       why='the joint where the transmission angle is taken; 0 = no movability constraint')
    if (err%failed() .or. s%transmission_joint == 0) return
    if (mech%joints(s%transmission_joint)%n_links /= 2) then
      call invalid_value(deck, g, 'transmission_joint', str(s%transmission_joint), 'the transmission angle is '// &
                         'the angle between the two links that meet at the joint; '// &
                         str(mech%joints(s%transmission_joint)%n_links)//' meet there', err)
      return
    end if
    call check_real(deck, g, 'transmission_min_deg', s%transmission_min_deg, err, above=0.0_dp, below=90.0_dp, &
                    why='the least transmission angle, degrees: mu kept in [min, 180 - min]')
  end subroutine check_transmission
end module design_settings
