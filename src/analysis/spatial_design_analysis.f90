!> The `spatial_design` analysis: least mass of a spatial four-bar's links
!> under a stress limit (and optionally a first-frequency bound), each design
!> analysed by the spatial transient model run to its periodic state
!> (module spatial_design_problem), solved by GNLC with general constraints
!> (Potter's variant without step-back: any start; module gauss_optimizer).
!> doc/design.md, "Spatial mechanisms".
!>
!>     &run analysis = 'spatial_design' /
!>     &spatial_mechanism ... /       the initial design (circular or rectangular links)
!>     &transient damping_beta = ... /  &effects ... /   how each design is analysed
!>     &design variables = 'link_radius(1)', ..., lower = ..., upper = ...,
!>             stress_allowable = 20000, evaluator = 'transient' /
!>
!> Output: the design history (one row per GNLC iteration), the final design
!> and the cost; the final design as a ready-to-run spatial deck
!> OUT.design.nml (the deck's &transient and &effects copied).
module spatial_design_analysis
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str, lower
  use version, only: program_name, program_version
  use deck_reader, only: deck_t, invalid_value
  use deck_checks, only: check_real
  use table_output, only: table_t
  use lsode_solver, only: mf_adams
  use transient_settings, only: transient_settings_t, read_transient_settings, echo_transient_settings
  use spatial_kinematics, only: spatial_fourbar_t
  use spatial_model, only: spatial_model_t, spatial_link_t
  use spatial_settings, only: spatial_input_t, read_spatial_mechanism, spatial_mechanism_group, build_spatial, &
                              write_spatial_mechanism
  use spatial_run_steps, only: spatial_formulation_of, choose_settings
  use periodic_transient, only: periodic_transient_settings_t
  use design_problem, only: design_variable_t
  use design_settings, only: design_settings_t, read_design_group, echo_design_settings, unset_value
  use spatial_design_problem, only: spatial_design_problem_t, spatial_eval_t, spatial_var_depth, spatial_var_width, &
                                    spatial_var_radius
  use gauss_optimizer, only: gauss_optimizer_t, method_gnlc_general_ns, status_converged
  implicit none
  private
  public :: run_spatial_design, load_spatial_design

  character(len=*), parameter :: g = 'design'
  character(len=7), parameter :: link_names(3) = ['crank  ', 'coupler', 'rocker ']

contains

  subroutine run_spatial_design(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(spatial_design_problem_t) :: prob
    type(gauss_optimizer_t) :: opt
    type(spatial_input_t) :: inp
    type(design_settings_t) :: ds
    type(error_t) :: run_err
    real(dp), allocatable :: x0(:)
    real(dp) :: cpu0, cpu1
    call load_spatial_design(deck, out, prob, x0, opt, inp, ds, err)
    if (err%failed()) return
    call write_header(out, prob)
    call cpu_time(cpu0)
    call opt%solve(prob, x0, run_err)
    call cpu_time(cpu1)
    call write_history(out, opt, prob)
    call write_results(out, opt, prob, cpu1 - cpu0)
    if (allocated(opt%x)) call write_final_deck(out, deck, prob, inp, opt%x)
    if (.not. run_err%failed() .and. opt%status /= status_converged) &
      call run_err%set('spatial design', 'not converged: '//opt%message, 3)
    if (run_err%failed()) err = run_err
  end subroutine run_spatial_design

  !> Read a spatial design deck: the mechanism, how each design is analysed
  !> (&transient, &effects: damping, tolerances; the solver settings the deck
  !> leaves out chosen for the initial design, with their lines in out), the
  !> &design group; the problem set up at x0 and the optimizer's options.
  !> Public for the benchmark that runs the same problem through NLopt.
  subroutine load_spatial_design(deck, out, prob, x0, opt, inp, ds, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(spatial_design_problem_t), intent(out) :: prob
    real(dp), allocatable, intent(out) :: x0(:)
    type(gauss_optimizer_t), intent(out) :: opt
    type(spatial_input_t), intent(out) :: inp
    type(design_settings_t), intent(out) :: ds
    type(error_t), intent(inout) :: err
    type(transient_settings_t) :: ts
    type(spatial_model_t) :: model
    real(dp), allocatable :: y(:)
    integer :: n, i
    call read_spatial_mechanism(deck, inp, err)
    if (err%failed()) return
    call read_transient_settings(deck, ts, err)
    if (err%failed()) return
    call read_design_group(deck, ds, err)
    if (err%failed()) return
    call check_spatial_design(deck, inp, ts, ds, err)
    if (err%failed()) return
    n = count(len_trim(ds%variables) > 0)
    allocate(prob%var(n), x0(n))
    do i = 1, n
      call read_variable(deck, inp, ds, i, prob%var(i), x0(i), err)
      if (err%failed()) return
    end do
    call out%echo_group(spatial_mechanism_group)
    call echo_transient_settings(out)
    call echo_design_settings(ds, out)
    call build_spatial(deck, inp, prob%kin, prob%links, prob%joint_b, prob%joint_c, err)
    if (err%failed()) return
    prob%omega = inp%omega
    prob%theta0 = inp%theta0_deg*pi/180.0_dp
    prob%beta = ts%damping_beta
    prob%effects = ts%effects
    prob%formulation = spatial_formulation_of(ts)
    ! the solver settings the deck left out, from the initial design's static response over a revolution
    call model%init(prob%kin, prob%omega, prob%theta0, prob%joint_b, prob%joint_c, prob%links, prob%effects, &
                    prob%beta, err, formulation=prob%formulation)
    if (err%failed()) return
    allocate(y(model%state_size()))
    y = 0.0_dp
    call choose_settings(out, ts, model, y, 0.0_dp, 2.0_dp*pi/prob%omega, prob%omega, err)
    if (err%failed()) return
    prob%transient = periodic_transient_settings_t(tolerance=ds%stop_when_periodic, &
      max_revolutions=ds%max_revolutions, rtol=ts%rtol, atol=ts%atol, atol_rate=ts%atol_rate, bdf=ts%mf /= mf_adams, &
      max_steps=ts%max_steps)
    prob%stress_allowable = ds%stress_allowable
    prob%frequency_factor = ds%frequency_factor
    prob%samples = ds%samples
    prob%peak_stress = ds%peak_stress
    prob%peak_interpolation = ds%peak_interpolation
    prob%ks_rho = ds%ks_rho
    prob%fd_rel_step = difference_step(ds%stop_when_periodic)
    call prob%setup('spatial design of '//trim(deck%path), x0, err)
    if (err%failed()) return
    opt%opts%method = method_gnlc_general_ns
    opt%opts%max_iter = ds%max_iterations
    opt%opts%xtol = ds%xtol
    opt%opts%feas_tol = ds%feas_tol
    opt%opts%ftol = ds%xtol**2
    ! Potter's B11 evaluates the actual constraints and their differences at
    ! each Newton iterate (n + 1 analyses each); on analyses with noise near
    ! 1e-4 more than two of them buy nothing (doc/design.md)
    opt%opts%newton_max_iter = 2
  end subroutine load_spatial_design

  !> The forward-difference step in x = ln(size): the analysis is the
  !> periodic state to within about the periodicity tolerance tau (relative),
  !> so a difference of g = ln(ratio) errs by about tau/h + h g''/2, least
  !> near h = sqrt(2 tau) for g'' ~ 1; sqrt(tau) (1e-3 at tau = 1e-6, the
  !> planar transient evaluator's step) keeps both parts near 1e-3.
  real(dp) function difference_step(tau) result(h)
    real(dp), intent(in) :: tau
    h = sqrt(tau)
  end function difference_step

  !> What the spatial design takes of &design and &transient.
  subroutine check_spatial_design(deck, inp, ts, ds, err)
    type(deck_t), intent(inout) :: deck
    type(spatial_input_t), intent(in) :: inp
    type(transient_settings_t), intent(in) :: ts
    type(design_settings_t), intent(in) :: ds
    type(error_t), intent(inout) :: err
    if (ds%objective /= 'mass') then
      call invalid_value(deck, g, 'objective', ''''//trim(ds%objective)//'''', 'the spatial design minimises '// &
                         'the links'' mass: objective = ''mass''', err)
    else if (ds%evaluator /= 'transient') then
      call invalid_value(deck, g, 'evaluator', ''''//trim(ds%evaluator)//'''', 'the spatial design runs the '// &
                         'spatial transient model to its periodic state: evaluator = ''transient''', err)
    else if (.not. (ds%stress_allowable > 0.0_dp .or. ds%frequency_factor > 0.0_dp)) then
      call invalid_value(deck, g, 'stress_allowable', '0', 'a minimum-mass design needs a stress or a '// &
                         'frequency constraint (else the minimum is the lower bounds)', err)
    else if (ds%speeds(1) > 0.5_dp*unset_value .or. ds%path_link /= 0 .or. any(ds%deflection_link /= 0) .or. &
             ds%transmission_joint /= 0) then
      call invalid_value(deck, g, 'speeds', 'given', 'the spatial design has the stress and frequency '// &
                         'constraints at the deck''s omega only (no speeds, path, deflection or transmission '// &
                         'values)', err)
    else if (.not. ts%damping_beta > 0.0_dp) then
      call invalid_value(deck, 'transient', 'damping_beta', str(ts%damping_beta), 'the spatial design needs '// &
                         'damping (> 0) to reach a periodic state', err)
    else if (ts%initial /= 'rigid') then
      call invalid_value(deck, 'transient', 'initial', ''''//trim(ts%initial)//'''', 'the spatial design starts '// &
                         'each design from the previous one''s periodic state (the first from rest): ''rigid''', err)
    else if (ds%stop_when_periodic < 10.0_dp*ts%rtol) then
      call invalid_value(deck, g, 'stop_when_periodic', str(ds%stop_when_periodic), 'must be at least 10 x '// &
                         'the integration''s rtol (&transient rtol = '//str(ts%rtol)//'): below it the change '// &
                         'per revolution is integration noise', err)
    else if (.not. inp%omega > 0.0_dp) then
      call invalid_value(deck, 'spatial_mechanism', 'omega', str(inp%omega), 'a design at the periodic state '// &
                         'needs a turning crank (omega > 0)', err)
    end if
  end subroutine check_spatial_design

  !> Design variable i: 'link_radius(l)' (a circular link), 'link_depth(l)'
  !> or 'link_width(l)' (a rectangular one), its bounds and scale; x0 its
  !> initial value as x = ln(value / scale).
  subroutine read_variable(deck, inp, ds, i, v, x0, err)
    type(deck_t), intent(inout) :: deck
    type(spatial_input_t), intent(in) :: inp
    type(design_settings_t), intent(in) :: ds
    integer, intent(in) :: i
    type(design_variable_t), intent(out) :: v
    real(dp), intent(out) :: x0
    type(error_t), intent(inout) :: err
    character(len=32) :: word
    character(len=:), allocatable :: name
    integer :: open_at, close_at, ios, l
    real(dp) :: value
    word = lower(adjustl(ds%variables(i)))
    name = 'variables('//str(i)//')'
    open_at = index(word, '(')
    close_at = index(word, ')')
    l = 0
    ios = 1
    if (open_at > 1 .and. close_at > open_at + 1) read(word(open_at + 1:close_at - 1), *, iostat=ios) l
    select case (word(1:max(1, open_at - 1)))
    case ('link_radius')
      v%kind = spatial_var_radius
    case ('link_depth')
      v%kind = spatial_var_depth
    case ('link_width')
      v%kind = spatial_var_width
    case default
      ios = 1
    end select
    if (ios /= 0) then
      call invalid_value(deck, g, name, ''''//trim(word)//'''', 'must be link_radius(l), link_depth(l) or '// &
                         'link_width(l), l = 1 (crank), 2 (coupler), 3 (rocker)', err)
      return
    end if
    if (l < 1 .or. l > 3) then
      call invalid_value(deck, g, name, ''''//trim(word)//'''', 'the link index must lie in 1..3', err)
      return
    end if
    if ((v%kind == spatial_var_radius) .neqv. (inp%link_section(l) == 'circular')) then
      call invalid_value(deck, g, name, ''''//trim(word)//'''', 'link '//str(l)//' is '// &
                         trim(inp%link_section(l))//': a circular link has link_radius, a rectangular one '// &
                         'link_depth and link_width', err)
      return
    end if
    select case (v%kind)
    case (spatial_var_radius)
      value = inp%link_radius(l)
    case (spatial_var_depth)
      value = inp%link_depth(l)
    case default
      value = inp%link_width(l)
    end select
    v%name = word
    v%index = l
    v%logarithmic = .true.
    call check_real(deck, g, 'lower('//str(i)//')', ds%lower(i), err, above=0.0_dp, at_most=100.0_dp, &
                    why='every design variable needs bounds; a size stays > 0')
    call check_real(deck, g, 'upper('//str(i)//')', ds%upper(i), err, above=0.0_dp, at_most=100.0_dp, &
                    why='every design variable needs bounds; a size stays > 0')
    call check_real(deck, g, 'scale('//str(i)//')', ds%scale(i), err, at_least=1.0e-8_dp, at_most=1.0e8_dp, &
                    why='0 = the initial value; x = ln(value / scale)', or_zero=.true.)
    if (err%failed()) return
    if (.not. (ds%lower(i) < ds%upper(i))) then
      call invalid_value(deck, g, 'upper('//str(i)//')', str(ds%upper(i)), 'must exceed lower('//str(i)//') = '// &
                         str(ds%lower(i)), err)
      return
    end if
    if (.not. (value >= ds%lower(i) .and. value <= ds%upper(i))) then
      call invalid_value(deck, g, name, ''''//trim(word)//''' = '//str(value), 'the initial design must lie '// &
                         'within its bounds ['//str(ds%lower(i))//', '//str(ds%upper(i))//']', err)
      return
    end if
    v%lower = ds%lower(i)
    v%upper = ds%upper(i)
    v%scale = merge(ds%scale(i), value, ds%scale(i) > 0.0_dp)
    x0 = v%to_x(value)
  end subroutine read_variable

  subroutine write_header(out, prob)
    type(table_t), intent(inout) :: out
    type(spatial_design_problem_t), intent(in) :: prob
    integer :: i
    call out%comment('spatial design: least mass of the links (crank '//str(prob%length(1), 6)//', coupler '// &
                     str(prob%length(2), 6)//', rocker '//str(prob%length(3), 6)//' in) at '//str(prob%omega, 6)// &
                     ' rad/s; initial mass '//str(prob%mass0, 8)//' lb s^2/in; objective F = mass / initial mass')
    do i = 1, size(prob%var)
      call out%comment('variable x'//str(i)//' = ln('//trim(prob%var(i)%name)//' / '//str(prob%var(i)%scale, 6)// &
                       '), bounds ['//str(prob%var(i)%lower, 6)//', '//str(prob%var(i)%upper, 6)//']')
    end do
    if (prob%n_stress > 0) call out%comment('constraints g1-g3: peak |stress| of each link (crank, coupler, '// &
      'rocker) over the periodic revolution: ln(stress / '//str(prob%stress_allowable, 6)//') <= 0')
    if (prob%n_stress > 0 .and. prob%peak_stress == 'ks') call out%comment('the peak taken as the KS aggregate '// &
      'of ln(stress) over the '//str(prob%samples)//' samples, rho = '//str(prob%ks_rho, 6)// &
      ': above the largest sample by at most ln(samples)/rho = '//str(log(real(prob%samples, dp))/prob%ks_rho, 3))
    if (prob%i_frequency > 0) call out%comment('constraint g'//str(prob%i_frequency)//': ln('// &
      str(prob%frequency_factor, 4)//' x crank speed / lowest natural frequency at the start position) <= 0')
    call out%comment('each analysis: the spatial transient model (DLSODE, rtol '//str(prob%transient%rtol, 3)// &
      ', atol '//str(prob%transient%atol, 3)//', rates '//str(prob%transient%atol_rate, 3)// &
      ') run from the previous design''s periodic state until a revolution changes the response by at most '// &
      str(prob%transient%tolerance, 3)//' (relative), stresses at '// &
      str(prob%samples)//' crank angles of the last revolution; forward-difference derivatives, step '// &
      str(prob%fd_rel_step, 3)//' in x; constraint Hessians taken as zero (GNLC general, no step-back)')
  end subroutine write_header

  !> One row per GNLC iterate: k, the analysis that gave it, mass, F, worst
  !> violation, the design values, the analysis constraints.
  subroutine write_history(out, opt, prob)
    type(table_t), intent(inout) :: out
    type(gauss_optimizer_t), intent(in) :: opt
    type(spatial_design_problem_t), intent(inout) :: prob
    character(len=32), allocatable :: names(:)
    real(dp), allocatable :: row(:)
    type(spatial_eval_t) :: ev
    integer :: r, i, n, nc
    n = size(prob%var)
    nc = prob%n_analysis_constraints()
    allocate(names(5 + n + nc), row(5 + n + nc))
    names(1:5) = [character(len=32) :: 'k', 'analysis', 'mass', 'objective', 'max_violation']
    names(6:5 + n) = prob%var%name
    do i = 1, nc
      names(5 + n + i) = 'g'//str(i)
    end do
    call out%comment('columns: k = GNLC iteration; analysis = the number of the analysis that gave x_k (analyses '// &
                     'in order, difference neighbours included); mass of the links (lb s^2/in); objective = mass / '// &
                     'initial mass; max_violation = largest g; the design values (in); g<i> = analysis constraints '// &
                     '(<= 0 feasible)')
    call out%columns(names)
    do r = 1, opt%n_log
      associate (it => opt%log(r))
        call prob%evaluate(it%x, ev)     ! (analysed already: the iterate's record)
        row(1:5) = [real(it%k, dp), real(ev%index, dp), ev%mass, it%f, it%max_violation]
        do i = 1, n
          row(5 + i) = prob%var(i)%value(it%x(i))
        end do
        if (ev%ok) then
          row(6 + n:) = ev%g
        else
          row(6 + n:) = 0.0_dp
        end if
        call out%row(row)
        if (len(it%events) > 0) call out%comment('k = '//str(it%k)//': '//it%events)
      end associate
    end do
  end subroutine write_history

  subroutine write_results(out, opt, prob, cpu)
    type(table_t), intent(inout) :: out
    type(gauss_optimizer_t), intent(in) :: opt
    type(spatial_design_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: cpu
    type(spatial_eval_t) :: ev
    integer :: i
    call out%summary('status', trim(merge('converged    ', 'not converged', opt%status == status_converged))// &
                     ' ('//opt%message//')')
    call out%summary('GNLC iterations NI', str(opt%iterations))
    if (allocated(opt%x)) then
      call prob%evaluate(opt%x, ev)
      do i = 1, size(prob%var)
        call out%summary('final '//trim(prob%var(i)%name), str(prob%var(i)%value(opt%x(i)), 10))
      end do
      call out%summary('final mass', str(ev%mass, 10)//' lb s^2/in ('//str(ev%mass/prob%mass0, 6)//' of the initial)')
      if (ev%ok) then
        do i = 1, 3
          if (prob%n_stress > 0) call out%summary('final peak |stress| '//trim(link_names(i)), &
                                                  str(maxval(ev%sample_stress(:, i)), 8)//' psi (allowable '// &
                                                  str(prob%stress_allowable, 6)//')')
        end do
        if (prob%i_frequency > 0) call out%summary('final lowest natural frequency', str(ev%omega_1, 8)// &
          ' rad/s = '//str(ev%omega_1/prob%omega, 5)//' x crank speed')
        call out%summary('final largest constraint', str(maxval(ev%g), 6))
      else
        call out%summary('final design analysis', 'failed: '//ev%reason)
      end if
    end if
    if (allocated(prob%last_failure)) call out%comment('last failed analysis: '//prob%last_failure)
    call out%cost('spatial analyses NF (every distinct design, derivatives included)', str(prob%n_analyses))
    call out%cost('failed analyses', str(prob%n_failed))
    call out%cost('transient revolutions integrated', str(prob%n_revolutions)//' ('// &
                  str(real(prob%n_revolutions, dp)/max(1, prob%n_analyses), 4)//' per analysis)')
    call out%cost('cpu_seconds_per_analysis', str(prob%cpu_analyses/max(1, prob%n_analyses), 4))
    call out%cost('cpu_seconds_analyses', str(prob%cpu_analyses, 4))
    call out%cost('cpu_seconds_design', str(cpu, 4))
  end subroutine write_results

  !> OUT.design.nml: &run spatial, the final &spatial_mechanism, the deck's
  !> &transient and &effects as written.
  subroutine write_final_deck(out, deck, prob, inp, x)
    type(table_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    type(spatial_design_problem_t), intent(in) :: prob
    type(spatial_input_t), intent(in) :: inp
    real(dp), intent(in) :: x(:)
    type(spatial_input_t) :: best
    character(len=:), allocatable :: stem
    integer :: u, i
    stem = out%path
    if (len(stem) > 4) then
      if (stem(len(stem) - 3:) == '.out') stem = stem(1:len(stem) - 4)
    end if
    best = inp
    do i = 1, size(prob%var)
      associate (v => prob%var(i))
        select case (v%kind)
        case (spatial_var_radius)
          best%link_radius(v%index) = v%value(x(i))
        case (spatial_var_depth)
          best%link_depth(v%index) = v%value(x(i))
        case default
          best%link_width(v%index) = v%value(x(i))
        end select
      end associate
    end do
    open(newunit=u, file=stem//'.design.nml', status='replace', action='write')
    write(u, '(a)') '! written by '//program_name//' '//program_version//' (spatial design analysis)'
    write(u, '(a)') '&run analysis = ''spatial'', title = ''final design of '//deck%path//''' /'
    call write_spatial_mechanism(best, u)
    call copy_group('transient')
    call copy_group('effects')
    close(u)
    call out%comment('final design deck: '//stem//'.design.nml')
  contains
    subroutine copy_group(group)
      character(len=*), intent(in) :: group
      integer :: first, last, k
      call deck%group_line_range(group, first, last)
      if (first == 0 .or. last == 0) return
      do k = first, last
        write(u, '(a)') deck%lines(k)%text
      end do
    end subroutine copy_group
  end subroutine write_final_deck
end module spatial_design_analysis
