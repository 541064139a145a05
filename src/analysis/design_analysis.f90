!> The `design` analysis: optimal design of a flexible mechanism with its
!> steady-state analysis in the loop (paper L; module design_problem), solved
!> by the Gauss family (GNLC with general constraints, Potter's variant).
!>
!>     &run analysis = 'design' /
!>     &mechanism ... /                 the initial design
!>     &steady ... / &tennant ... /     how each design is analysed
!>     &design variables = 'link_h(1)', 'link_h(2)', lower = 0.2, 0.2, upper = 4, 4,
!>             stress_allowable = 20000, frequency_factor = 5 /
!>
!> Output: the design history (one row per iteration: analyses so far, CPU,
!> mass, the design, every constraint), the final design as a ready-to-run
!> deck OUT.design.nml, and the steady-state analyses of the initial and the
!> final design, OUT.initial.out and OUT.final.out.
module design_analysis
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use version, only: program_name, program_version
  use deck_reader, only: deck_t, invalid_value
  use deck_checks, only: check_real
  use table_output, only: table_t
  use linkage, only: mechanism_t, build_mechanism
  use linkage_deck, only: read_mechanism, echo_mechanism, write_mechanism_group
  use steady_settings, only: steady_settings_t, read_steady_settings, echo_steady_settings, write_steady_groups
  use steady_run, only: analyse_steady_deck
  use design_problem, only: design_problem_t, design_variable_t, design_eval_t, parse_variable, var_theta0, &
                            var_path_r, var_path_angle, var_cw_mass, var_cw_x, var_cw_y
  use design_sequence, only: design_sequence_t
  use periodic_transient, only: periodic_transient_settings_t
  use design_settings, only: design_settings_t, read_design_settings, echo_design_settings, unset_value
  implicit none
  private
  public :: run_design, load_design

  real(dp), parameter :: deg = atan(1.0_dp)/45.0_dp

contains

  subroutine run_design(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(mechanism_t) :: mech
    type(design_problem_t) :: prob
    type(design_sequence_t) :: opt
    type(error_t) :: run_err
    real(dp), allocatable :: x0(:)
    real(dp) :: cpu0, cpu1
    type(design_settings_t) :: ds

    call load_design(deck, mech, prob, x0, opt, err, ds)
    if (err%failed()) return
    call echo_all(out, mech, ds)
    call cpu_time(cpu0)
    call prob%setup('design of '//trim(deck%path), x0)
    call write_design_header(out, prob)
    if (prob%has_residuals() .and. opt%hessian == 'structured') then
      call out%comment('approximate problems: Gauss-Newton matrix 2 J J^T / F0 plus a Dennis-Gay-Welsch secant '// &
        'estimate of the second-order term; move limit from the ratio of actual to predicted decrease')
    else if (prob%has_residuals()) then
      call out%comment('approximate problems: Gauss-Newton matrix 2 J J^T / F0; move limit halved after each '// &
        'accepted step, quadrupled after a rejection')
    end if
    call opt%solve(prob, x0, run_err)
    call cpu_time(cpu1)

    call write_history(out, opt, prob)
    call write_results(out, opt, prob, cpu1 - cpu0)
    if (.not. run_err%failed() .and. .not. opt%converged) &
      call run_err%set('design', 'not converged: '//opt%message, 3)
    if (allocated(opt%x)) call write_final_design(out, deck, prob, opt%x, err)
    if (run_err%failed()) err = run_err
  end subroutine run_design

  !> Read a design deck: the mechanism, how each design is analysed, the
  !> &design group (the problem, not yet set up: prob%setup analyses the
  !> start of a path objective) and the design loop's settings.  Public for
  !> the benchmark that runs the same problems through other optimizers.
  subroutine load_design(deck, mech, prob, x0, opt, err, settings)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(out) :: mech
    type(design_problem_t), intent(out) :: prob
    real(dp), allocatable, intent(out) :: x0(:)
    type(design_sequence_t), intent(out) :: opt
    type(error_t), intent(inout) :: err
    !> the &design group as read (the echo)
    type(design_settings_t), intent(out), optional :: settings
    type(steady_settings_t) :: st
    type(design_settings_t) :: ds
    type(design_variable_t), allocatable :: var(:)
    call read_mechanism(deck, mech, err)
    if (err%failed()) return
    call read_steady_settings(deck, mech%n_links, st, err)
    if (err%failed()) return
    call read_design(deck, mech, ds, var, x0, err)
    if (err%failed()) return
    prob = design_problem_t(base=mech%input, var=var, objective_kind=ds%objective, evaluator=ds%evaluator, &
                            samples=ds%samples, stress_allowable=ds%stress_allowable, frequency_factor=ds%frequency_factor, &
                            speeds=ds%speeds(1:ds%n_speeds), objective_speed=ds%objective_speed, element=st%element, &
                            sections=st%sections, harmonic=st%harmonic, shooting=st%shooting, derivatives=ds%derivatives, &
                            transient=periodic_transient_settings_t(tolerance=ds%stop_when_periodic, &
                              max_revolutions=ds%max_revolutions, rtol=st%shooting%rtol, atol=st%shooting%atol, &
                              bdf=st%shooting%bdf, max_steps=st%shooting%max_steps), &
                            fd_rel_step=difference_step(ds%evaluator), peak_stress=ds%peak_stress, ks_rho=ds%ks_rho, &
                            peak_interpolation=ds%peak_interpolation)
    if (prob%is_path()) call set_path(ds, prob)
    if (prob%is_bearing()) prob%bearing_joints = pack(ds%bearing_joints, ds%bearing_joints > 0)
    call set_deflections(ds, prob)
    if (prob%is_shaking() .and. any(st%sections(1:mech%n_links)%n > 0)) then
      call invalid_value(deck, 'design', 'objective', ''''//trim(prob%objective_kind)//'''', &
                         'the shaking force takes uniform links (no &sections)', err)
      return
    end if
    if (ds%evaluator == 'transient') call check_transient_model(deck, mech, st, err)
    if (err%failed()) return
    if (ds%evaluator == 'transient' .and. ds%stop_when_periodic < 10.0_dp*st%shooting%rtol) then
      ! the change per revolution cannot fall below a few times the integration's rtol
      call invalid_value(deck, 'design', 'stop_when_periodic', str(ds%stop_when_periodic), 'must be at least 10 x '// &
                         'the integration''s rtol (&steady rtol = '//str(st%shooting%rtol)//'): below it the '// &
                         'change per revolution is integration noise', err)
      return
    end if
    if (present(settings)) settings = ds
    opt = design_sequence_t(max_iterations=ds%max_iterations, xtol=ds%xtol, feas_tol=ds%feas_tol, move_limit=ds%move_limit, &
                            hessian=ds%hessian)
  end subroutine load_design

  !> The deflection constraints read (check_deflections) into the problem.
  subroutine set_deflections(s, prob)
    type(design_settings_t), intent(in) :: s
    type(design_problem_t), intent(inout) :: prob
    integer :: np
    np = count(s%deflection_link > 0)
    prob%deflection_link = s%deflection_link(1:np)
    prob%deflection_at = s%deflection_at(1:np)
    prob%deflection_limit = s%deflection_limit(1:np)
    prob%deflection_chord = s%deflection_from(1:np) == 'chord'
    prob%transmission_joint = s%transmission_joint
    prob%transmission_min = s%transmission_min_deg*deg
  end subroutine set_deflections



  !> '1, 4': the joint numbers, comma separated.
  function joint_list(joints) result(text)
    integer, intent(in) :: joints(:)
    character(len=:), allocatable :: text
    integer :: k
    text = ''
    do k = 1, size(joints)
      text = text//merge(', ', '  ', k > 1)//str(joints(k))
    end do
    text = trim(adjustl(text))
  end function joint_list

  !> Finite-difference steps above the analysis' noise (doc/design.md).
  real(dp) function difference_step(evaluator) result(step)
    character(len=*), intent(in) :: evaluator
    select case (evaluator)
    case ('shooting')
      step = 1.0e-4_dp
    case ('transient')
      step = 1.0e-3_dp
    case default
      step = 1.0e-5_dp
    end select
  end function difference_step

  !> Read and check &design (design_settings) and the design variables var
  !> with x0 = their initial values/scale.
  subroutine read_design(deck, mech, s, var, x0, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(design_settings_t), intent(out) :: s
    type(design_variable_t), allocatable, intent(out) :: var(:)
    real(dp), allocatable, intent(out) :: x0(:)
    type(error_t), intent(inout) :: err
    integer :: n, i
    call read_design_settings(deck, mech, s, err)
    if (err%failed()) return
    n = count(len_trim(s%variables) > 0)
    allocate(var(n), x0(n))
    do i = 1, n
      call read_variable(deck, mech, s, i, var(i), x0(i), err)
      if (err%failed()) return
    end do
  end subroutine read_design



  !> Design variable i: its name, index, bounds and scale; x0 its initial
  !> value over the scale.
  subroutine read_variable(deck, mech, s, i, v, x0, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(design_settings_t), intent(in) :: s
    integer, intent(in) :: i
    type(design_variable_t), intent(inout) :: v
    real(dp), intent(out) :: x0
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    logical :: ok
    integer :: limit
    real(dp) :: value
    call parse_variable(s%variables(i), v, ok)
    if (.not. ok) then
      call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(s%variables(i))//'''', 'must be '// &
                         'link_b(i), link_h(i), link_length(i), joint_x(j) or joint_y(j)', err)
      return
    end if
    if ((v%kind == var_path_r .or. v%kind == var_path_angle) .and. .not. &
        (s%objective == 'path' .or. s%objective == 'path_rigid')) then
      call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(s%variables(i))//'''', 'the coupler '// &
                         'point is a variable of the path objectives only', err)
      return
    end if
    limit = merge(mech%n_joints, mech%n_links, v%kind >= 4)
    if (v%kind >= var_theta0) limit = 0
    if (v%kind >= var_cw_mass) limit = mech%n_links
    if ((v%index < 1 .and. limit > 0) .or. v%index > limit) then
      call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(s%variables(i))//'''', 'the index must '// &
                         'lie in 1..'//str(limit), err)
      return
    end if
    value = initial_value(mech, s, v)
    call check_real(deck, g, 'lower('//str(i)//')', s%lower(i), err, at_least=-1.0e8_dp, at_most=1.0e8_dp, &
                    why='every design variable needs bounds')
    call check_real(deck, g, 'upper('//str(i)//')', s%upper(i), err, at_least=-1.0e8_dp, at_most=1.0e8_dp, &
                    why='every design variable needs bounds')
    call check_real(deck, g, 'scale('//str(i)//')', s%scale(i), err, at_least=1.0e-8_dp, at_most=1.0e8_dp, &
                    why='0 = the initial value''s magnitude; values are divided by it', or_zero=.true.)
    if (err%failed()) return
    if (.not. (s%lower(i) < s%upper(i))) then
      call invalid_value(deck, g, 'upper('//str(i)//')', str(s%upper(i)), 'must exceed lower('//str(i)//') = '// &
                         str(s%lower(i)), err)
      return
    end if
    v%lower = s%lower(i)
    v%upper = s%upper(i)
    v%scale = s%scale(i)
    if (.not. s%scale(i) > 0.0_dp) v%scale = max(abs(value), 1.0e-3_dp*(s%upper(i) - s%lower(i)))
    if (v%logarithmic .and. .not. s%lower(i) > 0.0_dp) then
      call invalid_value(deck, g, 'lower('//str(i)//')', str(s%lower(i)), 'a size or length must stay > 0', err)
      return
    end if
    if (.not. (value >= s%lower(i) .and. value <= s%upper(i))) then
      call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(s%variables(i))//''' = '//str(value), &
                         'the initial design must lie within its bounds ['//str(s%lower(i))//', '//str(s%upper(i))//']', err)
      return
    end if
    x0 = v%to_x(value)
  end subroutine read_variable



  !> The coupler point and its targets (checked by check_path) into the
  !> problem, the angles in radians.
  subroutine set_path(s, prob)
    type(design_settings_t), intent(in) :: s
    type(design_problem_t), intent(inout) :: prob
    integer :: np
    np = count(s%path_x > 0.5_dp*unset_value)
    prob%path_link = s%path_link
    prob%path_r = s%path_r
    prob%path_angle = s%path_angle_deg*deg
    prob%path_x = s%path_x(1:np)
    prob%path_y = s%path_y(1:np)
    prob%path_dgamma = s%path_dgamma_deg(1:np)*deg
  end subroutine set_path

  !> The deck value a variable starts from (a link length from the joints
  !> when the deck gives none).
  real(dp) function initial_value(mech, s, v) result(value)
    type(mechanism_t), intent(in) :: mech
    type(design_settings_t), intent(in) :: s
    type(design_variable_t), intent(in) :: v
    select case (v%kind)
    case (var_theta0)
      value = mech%input%theta0_deg
    case (var_path_r)
      value = s%path_r
    case (var_path_angle)
      value = s%path_angle_deg
    case (var_cw_mass)
      value = mech%input%link_cw_mass(v%index)
    case (var_cw_x)
      value = mech%input%link_cw_x(v%index)
    case (var_cw_y)
      value = mech%input%link_cw_y(v%index)
    case (1)
      value = mech%input%link_b(v%index)
    case (2)
      value = mech%input%link_h(v%index)
    case (3)
      value = mech%links(v%index)%length
    case (4)
      value = mech%input%joint_x(v%index)
    case default
      value = mech%input%joint_y(v%index)
    end select
  end function initial_value

  !> The transient evaluator integrates Kear's element, which has the linear
  !> slender element's equations (doc/steady_state.md): the &tennant options
  !> beyond them and sections are refused.
  subroutine check_transient_model(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(steady_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    character(len=:), allocatable :: why
    why = ''
    if (max(abs(s%element%d_k), abs(s%element%d_b), abs(s%element%d_g)) > 0.0_dp) &
      why = 'the linear element only (&tennant d_k = d_b = d_g = 0)'
    if (s%element%shear) why = 'no shear angle (&tennant shear = F)'
    if (any(s%sections(1:mech%n_links)%n > 0)) why = 'uniform links (no &sections)'
    if (len(why) > 0) call invalid_value(deck, 'design', 'evaluator', '''transient''', 'the transient evaluator '// &
                                         'takes '//why, err)
  end subroutine check_transient_model

  subroutine echo_all(out, mech, ds)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(design_settings_t), intent(in) :: ds
    call echo_mechanism(mech, out)
    call echo_steady_settings(out)
    call echo_design_settings(ds, out)
  end subroutine echo_all

  subroutine write_design_header(out, prob)
    type(table_t), intent(inout) :: out
    type(design_problem_t), intent(in) :: prob
    integer :: i
    character(len=:), allocatable :: from, aggregate
    select case (prob%objective_kind)
    case ('path')
      call out%comment('design: least path error of the coupler point with the elastic deformation at the '// &
        'operating speed (F = sum of squared distances to the '//str(size(prob%path_x))// &
        ' targets / its initial value '//str(prob%f0, 8)//'); the rigid-body path error beside it')
    case ('path_rigid')
      call out%comment('design: least rigid-body path error of the coupler point (F = sum of squared distances '// &
        'to the '//str(size(prob%path_x))//' targets / its initial value '//str(prob%f0, 8)// &
        '); the path error with the elastic deformation beside it')
    case ('shaking')
      call out%comment('design: least mean square shaking force over the steady revolution (rate of the '// &
        'total linear momentum of every moving mass, elastic motion included, at '//str(prob%samples)// &
        ' crank angles; F = mean |F_shake|^2 / its initial value '//str(prob%f0, 8)//')')
    case ('shaking_peak')
      call out%comment('design: least peak shaking force over the steady revolution (minimax: min t subject to '// &
        '|F_shake(theta_k)| <= t at '//str(prob%samples)//' crank angles, elastic motion included; F = peak / '// &
        'its initial value '//str(prob%f0, 8)//')')
    case ('bearing', 'bearing_peak')
      call out%comment('design: least '//trim(merge('mean square', 'peak       ', prob%objective_kind == 'bearing'))// &
        ' bearing force of joints '//joint_list(prob%bearing_joints)//' over the steady revolution (the force each '// &
        'pin carries, rigid and elastic, at '//str(prob%samples)//' crank angles; '// &
        trim(merge('F = mean sum |F_j|^2', 'minimax: F = peak   ', prob%objective_kind == 'bearing'))// &
        ' / its initial value '//str(prob%f0, 8)//')')
    case default
      call out%comment('design: minimum mass of the links (F = mass / initial mass '//str(prob%mass0, 8)//')')
    end select
    if (prob%is_path()) call out%comment('coupler point on a rigid arm clamped to link '//str(prob%path_link)// &
      ' at its end 1, turned by the end''s elastic slope; initial distance '//str(prob%path_r, 6)// &
      ', angle '//str(prob%path_angle/deg, 6)//' deg from the link''s line')
    do i = 1, size(prob%var)
      call out%comment('variable x'//str(i)//' = '//trim(merge('ln(', '   ', prob%var(i)%logarithmic))// &
                       trim(prob%var(i)%name)//' / '//str(prob%var(i)%scale, 6)//trim(merge(')', ' ', prob%var(i)%logarithmic))// &
                       ', bounds ['//str(prob%var(i)%lower, 6)//', '//str(prob%var(i)%upper, 6)//']')
    end do
    call write_speeds(out, prob)
    if (prob%n_stress > 0) call out%comment('constraints g1-g'//str(prob%n_stress)//': peak |stress| of each link '// &
      'over the steady revolution: ln(stress / '//str(prob%stress_allowable, 6)//') <= 0; link l at speed s: '// &
      'g(l + (s - 1) n_links)')
    if (prob%n_stress > 0 .and. prob%peak_stress == 'ks') call out%comment('the peak taken as the KS aggregate '// &
      'of ln(stress) over the '//str(prob%samples)//' samples, rho = '//str(prob%ks_rho, 6)// &
      ': above the largest sample by at most ln(samples)/rho = '//str(log(real(prob%samples, dp))/prob%ks_rho, 3))
    if (prob%i_frequency > 0) call out%comment('constraints g'//str(prob%i_frequency)//'-g'// &
      str(prob%i_frequency + size(prob%speeds) - 1)//': ln('//str(prob%frequency_factor, 4)//' x crank speed / lowest frozen '// &
      'natural frequency over the revolution) <= 0, one per speed')
    if (prob%i_transmission > 0) call out%comment('constraint g'//str(prob%i_transmission)//': movability, '// &
      'ln(peak |cos mu|'//trim(merge(' (the KS aggregate)', '                   ', prob%peak_stress == 'ks'))// &
      ' / cos '//str(prob%transmission_min/deg, 6)//' deg) <= 0, mu the transmission angle between the links at joint '// &
      str(prob%transmission_joint)//' (rigid-body kinematics): within [min, 180 - min] at every sample')
    do i = 1, prob%n_deflection_points()
      from = 'from the rigid position'
      if (prob%deflection_chord(i)) from = 'from the chord'
      aggregate = ''
      if (prob%peak_stress == 'ks') aggregate = ' (the KS aggregate)'
      call out%comment('constraint g'//str(prob%i_deflection + i - 1)//': deflection of link '// &
        str(prob%deflection_link(i))//' at '//str(prob%deflection_at(i), 4)//' of its length from end 1, '// &
        from//': ln(peak'//aggregate//' / '//str(prob%deflection_limit(i), 6)//') <= 0; at speed s: g'// &
        str(prob%i_deflection + i - 1)//' + (s - 1) x '//str(prob%n_deflection_points()))
    end do
    call out%comment('bounds as linear constraints after them; each analysis: '//trim(evaluator_text(prob%evaluator))// &
      ' with stresses and frequencies at '//str(prob%samples)// &
      ' crank angles; '//trim(derivatives_text(prob)))
  end subroutine write_design_header

  function derivatives_text(prob) result(text)
    type(design_problem_t), intent(in) :: prob
    character(len=:), allocatable :: text
    if (prob%variational_applies()) then
      text = 'derivatives from the sensitivities of the periodic orbit (variational equations; f_p and the '// &
        'results by central differences in the design, relative step '//str(prob%variational_step, 3)// &
        '), one sensitivity solve per iteration and speed, counted as one analysis'
    else
      text = 'forward-difference derivatives, relative step '//str(prob%fd_rel_step, 3)
    end if
  end function derivatives_text

  !> The operating speeds, when the design has several.
  subroutine write_speeds(out, prob)
    type(table_t), intent(inout) :: out
    type(design_problem_t), intent(in) :: prob
    character(len=:), allocatable :: text
    integer :: s
    if (size(prob%speeds) < 2) return
    text = ''
    do s = 1, size(prob%speeds)
      text = text//' '//str(prob%speeds(s), 6)
    end do
    if (prob%objective_speed == 0) then
      call out%comment('operating speeds (rad/s):'//text//'; every constraint at each; the objective summed over '// &
                       'them (a mean square averaged)')
    else
      call out%comment('operating speeds (rad/s):'//text//'; every constraint at each; the objective at speed '// &
                       str(prob%objective_speed)//' only')
    end if
  end subroutine write_speeds

  function evaluator_text(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    if (name == 'shooting') then
      text = 'the exact periodic steady state (shooting, DLSODE)'
    else if (name == 'transient') then
      text = 'the transient model (DLSODE) run to its periodic state from the previous design''s'
    else
      text = 'Tennant''s harmonic series (T26-T28)'
    end if
  end function evaluator_text

  !> One row per accepted design: k, analyses and CPU so far, mass, worst
  !> violation, move limit, the design values, the analysis constraints.
  subroutine write_history(out, opt, prob)
    type(table_t), intent(inout) :: out
    type(design_sequence_t), intent(in) :: opt
    type(design_problem_t), intent(in) :: prob
    character(len=32), allocatable :: names(:)
    real(dp), allocatable :: row(:)
    integer :: r, i, n, nc, np
    n = size(prob%var)
    nc = prob%n_analysis_constraints()
    np = merge(3, 0, prob%has_residuals())
    allocate(names(6 + n + nc + np), row(6 + n + nc + np))
    names(1:6) = [character(len=32) :: 'k', 'analyses', 'cpu_s', 'mass', 'max_violation', 'move_limit']
    names(7:6 + n) = prob%var%name
    do i = 1, nc
      names(6 + n + i) = 'g'//str(i)
    end do
    if (prob%is_path()) names(7 + n + nc:) = [character(len=32) :: 'objective', 'path_error', 'rigid_path_error']
    if (prob%is_shaking()) names(7 + n + nc:) = [character(len=32) :: 'objective', 'peak_shaking', &
                                                                 'rms_shaking']
    if (prob%is_bearing()) names(7 + n + nc:) = [character(len=32) :: 'objective', 'peak_bearing', 'rms_bearing']
    call out%comment('columns: k = design iteration; analyses and cpu_s (analysis CPU) so far; mass of the links; '// &
                     'max_violation = largest g; move_limit = largest change of x in the next approximate problem; '// &
                     'the design values; g<i> = analysis constraints (<= 0 feasible); path objectives: '// &
                     'objective = F / F0, path_error = sum of squared distances of the coupler point from the '// &
                     'targets with the elastic deformation, rigid_path_error = the same for the rigid-body point; '// &
                     'shaking: peak and rms shaking force over the revolution; bearing: peak and rms bearing '// &
                     'force of the named joints')
    call out%columns(names)
    do r = 1, opt%n_steps
      associate (st => opt%steps(r))
        row(1:6) = [real(st%k, dp), real(st%analyses, dp), st%cpu, st%mass, st%max_violation, st%move_limit]
        do i = 1, n
          row(6 + i) = prob%var(i)%value(st%x(i))
        end do
        row(7 + n:6 + n + nc) = st%g
        if (prob%is_path()) row(7 + n + nc:) = [st%objective, st%path_error, st%rigid_path_error]
        if (prob%is_shaking()) row(7 + n + nc:) = [st%objective, st%peak_shaking, st%rms_shaking]
        if (prob%is_bearing()) row(7 + n + nc:) = [st%objective, st%peak_bearing, st%rms_bearing]
        call out%row(row)
        ! after the row: the column names stay the last '#' line before the first row
        if (len(st%events) > 0) call out%comment('k = '//str(st%k)//': '//st%events)
      end associate
    end do
  end subroutine write_history

  subroutine write_results(out, opt, prob, cpu)
    type(table_t), intent(inout) :: out
    type(design_sequence_t), intent(in) :: opt
    type(design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: cpu
    type(design_eval_t) :: ev
    integer :: i, s
    call out%summary('status', trim(merge('converged    ', 'not converged', opt%converged))//' ('//opt%message//')')
    call out%summary('design iterations NI', str(opt%iterations))
    call out%summary('rejected proposals (move limit halved)', str(opt%rejections))
    if (allocated(opt%x)) then
      call prob%evaluate(opt%x, ev)
      do i = 1, size(prob%var)
        call out%summary('final '//trim(prob%var(i)%name), str(prob%var(i)%value(opt%x(i)), 10))
      end do
      call out%summary('final mass', str(ev%mass, 10)//' ('//str(ev%mass/prob%mass0, 6)//' of the initial)')
      if (ev%ok) then
        do i = 1, size(ev%link_stress)
          call out%summary('final peak |stress| link '//str(i), str(ev%link_stress(i), 8))
        end do
        if (size(prob%speeds) > 1) then
          do s = 1, size(prob%speeds)
            do i = 1, size(ev%link_stress)
              call out%summary('final peak |stress| link '//str(i)//' at '//str(prob%speeds(s), 6)//' rad/s', &
                               str(ev%stress_at(i, s), 8))
            end do
          end do
        end if
        if (prob%i_frequency > 0 .and. size(prob%speeds) == 1) call out%summary('final lowest frozen frequency', &
          str(ev%frequency_at(1), 8)//' rad/s = '//str(ev%frequency_at(1)/prob%speeds(1), 5)//' x crank speed')
        do s = 1, size(prob%speeds)
          if (prob%i_frequency > 0 .and. size(prob%speeds) > 1) call out%summary('final lowest frozen frequency at '// &
            str(prob%speeds(s), 6)//' rad/s', str(ev%frequency_at(s), 8)//' rad/s = '// &
            str(ev%frequency_at(s)/prob%speeds(s), 5)//' x crank speed')
        end do
        if (prob%i_transmission > 0) call out%summary('final least transmission angle', &
          str(acos(min(maxval(ev%sample_transmission), 1.0_dp))/deg, 6)//' deg (at joint '// &
          str(prob%transmission_joint)//')')
        do i = 1, prob%n_deflection_points()
          call out%summary('final peak deflection point '//str(i)//' (link '//str(prob%deflection_link(i))//')', &
                           str(maxval(ev%sample_deflection(:, i, :)), 8))
        end do
        if (prob%is_path()) then
          call out%summary('final path error (elastic)', str(ev%path_error, 8)//' (largest miss '// &
                           str(largest_miss(ev%residual), 5)//')')
          call out%summary('final path error (rigid body)', str(ev%rigid_path_error, 8)//' (largest miss '// &
                           str(largest_miss(ev%rigid_residual), 5)//')')
          if (opt%n_steps > 0) then
            call out%summary('initial path error (elastic)', str(opt%steps(1)%path_error, 8))
            call out%summary('initial path error (rigid body)', str(opt%steps(1)%rigid_path_error, 8))
          end if
        end if
        if (prob%is_shaking()) call force_summary('shaking', ev%peak_shaking, ev%rms_shaking)
        if (prob%is_bearing()) then
          call force_summary('bearing', ev%peak_bearing, ev%rms_bearing)
          ! the minimax residuals: |F_j| at each sample, the joints fastest
          if (prob%is_minimax()) then
            do i = 1, size(prob%bearing_joints)
              call out%summary('final peak bearing force joint '//str(prob%bearing_joints(i)), &
                               str(maxval(ev%residual(i::size(prob%bearing_joints))), 8))
            end do
          end if
        end if
      else
        call out%summary('final design analysis', 'failed: '//ev%reason)
      end if
    end if
    if (allocated(prob%last_failure)) call out%comment('last failed analysis: '//prob%last_failure)
    if (prob%n_past_peak > 0) call out%comment(str(prob%n_past_peak)//' designs past the Ramberg-Osgood peak '// &
      'strain (infeasible), the last: '//prob%last_past_peak)
    call out%cost('mechanism analyses NF (every distinct design, derivatives included)', str(prob%n_analyses))
    if (prob%variational_applies()) then
      call out%cost('analyses for derivatives (sensitivity solves, one per iteration and speed, counted as one '// &
                    'analysis each; forward differences after a failed one)', str(opt%fd_analyses))
      call out%cost('sensitivity solves (of them failed: forward differences instead)', str(prob%n_sensitivity)// &
                    ' ('//str(prob%n_sensitivity_fallbacks)//')')
      call out%cost('cpu_seconds_per_sensitivity_solve', str(prob%cpu_sensitivity/max(1, prob%n_sensitivity), 4))
      call out%cost('sensitivity right-hand sides (perturbed designs included)', str(prob%sensitivity_rhs))
    else
      call out%cost('analyses for derivatives (forward differences)', str(opt%fd_analyses))
    end if
    call out%cost('failed analyses', str(prob%n_failed))
    if (prob%evaluator == 'transient') call out%cost('transient revolutions integrated', str(prob%n_revolutions)// &
      ' ('//str(real(prob%n_revolutions, dp)/max(1, prob%n_analyses), 4)//' per analysis)')
    call out%cost('cpu_seconds_per_analysis', str(prob%cpu_analyses/max(1, prob%n_analyses), 4))
    call out%cost('cpu_seconds_analyses', str(prob%cpu_analyses, 4))
    call out%cost('cpu_seconds_design', str(cpu, 4))
  contains
    !> The final and initial peak and rms of a force objective ('shaking', 'bearing').
    subroutine force_summary(what, peak, rms)
      character(len=*), intent(in) :: what
      real(dp), intent(in) :: peak, rms
      call out%summary('final peak '//what//' force', str(peak, 8))
      call out%summary('final rms '//what//' force', str(rms, 8))
      if (opt%n_steps == 0) return
      associate (st => opt%steps(1))
        call out%summary('initial peak '//what//' force', str(merge(st%peak_shaking, st%peak_bearing, &
                                                                    what == 'shaking'), 8))
        call out%summary('initial rms '//what//' force', str(merge(st%rms_shaking, st%rms_bearing, what == 'shaking'), 8))
      end associate
    end subroutine force_summary
  end subroutine write_results

  !> Largest distance of the coupler point from its target.
  real(dp) pure function largest_miss(res) result(d)
    real(dp), intent(in) :: res(:)
    integer :: k
    d = 0.0_dp
    do k = 1, size(res)/2
      d = max(d, hypot(res(2*k - 1), res(2*k)))
    end do
  end function largest_miss

  !> OUT.design.nml (ready to run: &run steady, the final &mechanism, the
  !> analysis groups), then the steady analyses of the initial and final
  !> designs into OUT.initial.out and OUT.final.out.
  subroutine write_final_design(out, deck, prob, x, err)
    type(table_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    type(design_problem_t), intent(in) :: prob
    real(dp), intent(in) :: x(:)
    type(error_t), intent(inout) :: err
    type(mechanism_t) :: mech, mech0
    character(len=:), allocatable :: stem
    integer :: u
    stem = out%path
    if (len(stem) > 4) then
      if (stem(len(stem) - 3:) == '.out') stem = stem(1:len(stem) - 4)
    end if
    call build_mechanism(prob%mechanism_at(x, .true.), mech, err)
    if (.not. err%failed()) call build_mechanism(prob%base, mech0, err)
    if (err%failed()) return
    call write_deck(stem//'.design.nml', 'final design of '//deck%path, mech)
    call write_deck(stem//'.initial.nml', 'initial design of '//deck%path, mech0)
    call out%comment('final design deck: '//stem//'.design.nml')
    call analyse_side(stem//'.initial.nml', stem//'.initial.out')
    call analyse_side(stem//'.design.nml', stem//'.final.out')
    call out%comment('steady-state analyses: '//stem//'.initial.out (initial design), '//stem//'.final.out (final)')
  contains
    subroutine write_deck(path, title, m)
      character(len=*), intent(in) :: path, title
      type(mechanism_t), intent(in) :: m
      open(newunit=u, file=path, status='replace', action='write')
      write(u, '(a)') '! written by '//program_name//' '//program_version//' (design analysis)'
      write(u, '(a)') '&run analysis = ''steady'', title = '''//title//''' /'
      call write_mechanism_group(m, u)
      call write_steady_groups(u, merge('harmonic', 'shooting', prob%evaluator == 'harmonic'))
      close(u)
    end subroutine write_deck

    subroutine analyse_side(deck_path, out_path)
      character(len=*), intent(in) :: deck_path, out_path
      character(len=:), allocatable :: why
      call analyse_steady_deck(deck_path, out_path, why)
      if (len(why) > 0) call out%comment('could not analyse '//deck_path//': '//why)
    end subroutine analyse_side
  end subroutine write_final_design
end module design_analysis
