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
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use version, only: program_name, program_version
  use deck_reader, only: deck_t, invalid_value
  use deck_checks, only: check_real, check_integer, check_choice
  use table_output, only: table_t
  use linkage, only: mechanism_t, read_mechanism, build_mechanism, echo_mechanism, profile_constant
  use steady_settings, only: steady_settings_t, read_steady_settings, echo_steady_settings, write_steady_groups
  use steady_analysis, only: run_steady
  use design_problem, only: design_problem_t, design_variable_t, design_eval_t, parse_variable
  use design_sequence, only: design_sequence_t
  implicit none
  private
  public :: run_design

  integer, parameter :: max_vars = 20
  real(dp), parameter :: unset = -huge(1.0_dp)

  ! staging variables of the &design group
  character(len=32) :: variables(max_vars), objective
  character(len=16) :: evaluator
  real(dp) :: lower(max_vars), upper(max_vars), scale(max_vars), stress_allowable, frequency_factor
  real(dp) :: xtol, feas_tol, move_limit
  integer :: max_iterations, samples
  namelist /design/ variables, lower, upper, scale, objective, evaluator, stress_allowable, &
                    frequency_factor, max_iterations, samples, xtol, feas_tol, move_limit

contains

  subroutine set_defaults()
    variables = ''
    lower = unset
    upper = unset
    scale = 0.0_dp
    objective = 'mass'
    evaluator = 'shooting'
    stress_allowable = 0.0_dp
    frequency_factor = 0.0_dp
    max_iterations = 30
    samples = 72
    xtol = 1.0e-3_dp
    feas_tol = 1.0e-3_dp
    move_limit = 0.3_dp
  end subroutine set_defaults

  subroutine read_design_group(unit, ios, iomsg)
    integer, intent(in) :: unit
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    read(unit, nml=design, iostat=ios, iomsg=iomsg)
  end subroutine read_design_group

  subroutine run_design(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(mechanism_t) :: mech
    type(steady_settings_t) :: s
    type(design_problem_t) :: prob
    type(design_sequence_t) :: opt
    type(error_t) :: run_err
    real(dp), allocatable :: x0(:)
    real(dp) :: cpu0, cpu1

    call read_mechanism(deck, mech, err)
    if (err%failed()) return
    call read_steady_settings(deck, mech%n_links, s, err)
    if (err%failed()) return
    call read_design(deck, mech, prob, x0, err)
    if (err%failed()) return
    prob%element = s%element
    prob%sections = s%sections
    prob%harmonic = s%harmonic
    prob%shooting = s%shooting
    call echo_all(out, mech)

    call prob%setup('design of '//trim(deck%path), x0)
    ! finite-difference steps above the analysis' noise (doc/design.md)
    prob%fd_rel_step = merge(1.0e-4_dp, 1.0e-5_dp, evaluator == 'shooting')
    call write_design_header(out, prob)

    opt%max_iterations = max_iterations
    opt%xtol = xtol
    opt%feas_tol = feas_tol
    opt%move_limit = move_limit
    call cpu_time(cpu0)
    call opt%solve(prob, x0, run_err)
    call cpu_time(cpu1)

    call write_history(out, opt, prob)
    call write_results(out, opt, prob, cpu1 - cpu0)
    if (.not. run_err%failed() .and. .not. opt%converged) &
      call run_err%set('design', 'not converged: '//opt%message, 3)
    if (allocated(opt%x)) call write_final_design(out, deck, prob, opt%x, err)
    if (run_err%failed()) err = run_err
  end subroutine run_design

  !> Read &design and make the problem's variables; x0 = initial values/scale.
  subroutine read_design(deck, mech, prob, x0, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(design_problem_t), intent(inout) :: prob
    real(dp), allocatable, intent(out) :: x0(:)
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'design'
    logical :: found, ok
    integer :: n, i, limit
    real(dp) :: value
    call set_defaults()
    call deck%read_group(g, read_design_group, .true., found, err)
    if (err%failed()) return
    n = count(len_trim(variables) > 0)
    if (n == 0 .or. any(len_trim(variables(1:n)) == 0)) then
      call invalid_value(deck, g, 'variables', str(n)//' given', 'name one or more design variables, '// &
                         'one after another (e.g. ''link_h(1)'', ''link_b(2)'', ''joint_x(4)'')', err)
      return
    end if
    call check_choice(deck, g, 'objective', objective, [character(len=32) :: 'mass'], err)
    call check_choice(deck, g, 'evaluator', evaluator, [character(len=16) :: 'shooting', 'harmonic'], err)
    call check_real(deck, g, 'stress_allowable', stress_allowable, err, at_least=0.0_dp, at_most=1.0e12_dp, &
                    why='0 = no stress constraint')
    call check_real(deck, g, 'frequency_factor', frequency_factor, err, at_least=0.0_dp, at_most=1.0e3_dp, &
                    why='lowest natural frequency >= factor x crank speed; 0 = no frequency constraint')
    call check_integer(deck, g, 'max_iterations', max_iterations, err, at_least=1, at_most=1000)
    call check_integer(deck, g, 'samples', samples, err, at_least=8, at_most=3600, &
                       why='crank angles per revolution where stresses and frequencies are taken')
    call check_real(deck, g, 'xtol', xtol, err, at_least=1.0e-8_dp, below=1.0_dp, &
                    why='design step test, relative change of sizes; below 1e-8 it is analysis noise')
    call check_real(deck, g, 'feas_tol', feas_tol, err, at_least=1.0e-8_dp, below=1.0_dp, &
                    why='allowed ln(stress/allowable) etc.: a relative violation')
    call check_real(deck, g, 'move_limit', move_limit, err, above=0.0_dp, at_most=2.0_dp, &
                    why='initial largest change of ln(size) per design iteration')
    if (err%failed()) return
    if (.not. (stress_allowable > 0.0_dp .or. frequency_factor > 0.0_dp)) then
      call invalid_value(deck, g, 'stress_allowable', '0', 'a minimum-mass design needs a stress or a '// &
                         'frequency constraint (else the minimum is the lower bounds)', err)
      return
    end if
    if (frequency_factor > 0.0_dp .and. .not. abs(mech%driver%omega) > 0.0_dp) then
      call invalid_value(deck, g, 'frequency_factor', str(frequency_factor), 'needs a turning crank (omega > 0)', err)
      return
    end if
    if (.not. mech%driver%omega > 0.0_dp .or. mech%driver%profile /= profile_constant) then
      call invalid_value(deck, 'mechanism', 'omega', str(mech%driver%omega), 'a design at the steady state '// &
                         'needs a crank turning at constant speed > 0', err)
      return
    end if
    allocate(prob%var(n), x0(n))
    do i = 1, n
      call parse_variable(variables(i), prob%var(i), ok)
      if (.not. ok) then
        call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(variables(i))//'''', 'must be '// &
                           'link_b(i), link_h(i), link_length(i), joint_x(j) or joint_y(j)', err)
        return
      end if
      limit = merge(mech%n_joints, mech%n_links, prob%var(i)%kind >= 4)
      if (prob%var(i)%index < 1 .or. prob%var(i)%index > limit) then
        call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(variables(i))//'''', 'the index must '// &
                           'lie in 1..'//str(limit), err)
        return
      end if
      value = initial_value(mech, prob%var(i))
      call check_real(deck, g, 'lower('//str(i)//')', lower(i), err, at_least=-1.0e8_dp, at_most=1.0e8_dp, &
                      why='every design variable needs bounds')
      call check_real(deck, g, 'upper('//str(i)//')', upper(i), err, at_least=-1.0e8_dp, at_most=1.0e8_dp, &
                      why='every design variable needs bounds')
      call check_real(deck, g, 'scale('//str(i)//')', scale(i), err, at_least=0.0_dp, at_most=1.0e8_dp, &
                      why='0 = the initial value''s magnitude')
      if (err%failed()) return
      if (.not. (lower(i) < upper(i))) then
        call invalid_value(deck, g, 'upper('//str(i)//')', str(upper(i)), 'must exceed lower('//str(i)//') = '// &
                           str(lower(i)), err)
        return
      end if
      prob%var(i)%lower = lower(i)
      prob%var(i)%upper = upper(i)
      prob%var(i)%scale = scale(i)
      if (.not. scale(i) > 0.0_dp) prob%var(i)%scale = max(abs(value), 1.0e-3_dp*(upper(i) - lower(i)))
      if (prob%var(i)%logarithmic .and. .not. lower(i) > 0.0_dp) then
        call invalid_value(deck, g, 'lower('//str(i)//')', str(lower(i)), 'a size or length must stay > 0', err)
        return
      end if
      if (.not. (value >= lower(i) .and. value <= upper(i))) then
        call invalid_value(deck, g, 'variables('//str(i)//')', ''''//trim(variables(i))//''' = '//str(value), &
                           'the initial design must lie within its bounds ['//str(lower(i))//', '//str(upper(i))//']', err)
        return
      end if
      x0(i) = prob%var(i)%to_x(value)
    end do
    prob%base = mech%input
    prob%evaluator = evaluator
    prob%samples = samples
    prob%stress_allowable = stress_allowable
    prob%frequency_factor = frequency_factor
  end subroutine read_design

  !> The deck value a variable starts from (a link length from the joints
  !> when the deck gives none).
  real(dp) function initial_value(mech, v) result(value)
    type(mechanism_t), intent(in) :: mech
    type(design_variable_t), intent(in) :: v
    select case (v%kind)
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

  subroutine echo_all(out, mech)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    integer :: u
    u = out%echo_unit()
    call echo_mechanism(mech, u)
    call out%end_echo()
    call echo_steady_settings(out)
    u = out%echo_unit()
    write(u, nml=design, delim='apostrophe')
    call out%end_echo()
  end subroutine echo_all

  subroutine write_design_header(out, prob)
    type(table_t), intent(inout) :: out
    type(design_problem_t), intent(in) :: prob
    integer :: i
    call out%comment('design: minimum mass of the links (F = mass / initial mass '//str(prob%mass0, 8)//')')
    do i = 1, size(prob%var)
      call out%comment('variable x'//str(i)//' = '//trim(merge('ln(', '   ', prob%var(i)%logarithmic))// &
                       trim(prob%var(i)%name)//' / '//str(prob%var(i)%scale, 6)//trim(merge(')', ' ', prob%var(i)%logarithmic))// &
                       ', bounds ['//str(prob%var(i)%lower, 6)//', '//str(prob%var(i)%upper, 6)//']')
    end do
    if (prob%n_stress > 0) call out%comment('constraints g1-g'//str(prob%n_stress)//': peak |stress| of each link '// &
      'over the steady revolution: ln(stress / '//str(prob%stress_allowable, 6)//') <= 0')
    if (prob%i_frequency > 0) call out%comment('constraint g'//str(prob%i_frequency)//': ln('// &
      str(prob%frequency_factor, 4)//' x crank speed / lowest frozen natural frequency over the revolution) <= 0')
    call out%comment('bounds as linear constraints after them; each analysis: '//trim(evaluator_text(prob%evaluator))// &
      ' with stresses and frequencies at '//str(prob%samples)// &
      ' crank angles; forward-difference derivatives, relative step '//str(prob%fd_rel_step, 3))
  end subroutine write_design_header

  function evaluator_text(name) result(text)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: text
    if (name == 'shooting') then
      text = 'the exact periodic steady state (shooting, DLSODE)'
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
    integer :: r, i, n, nc
    n = size(prob%var)
    nc = prob%n_analysis_constraints()
    allocate(names(6 + n + nc), row(6 + n + nc))
    names(1:6) = [character(len=32) :: 'k', 'analyses', 'cpu_s', 'mass', 'max_violation', 'move_limit']
    names(7:6 + n) = prob%var%name
    do i = 1, nc
      names(6 + n + i) = 'g'//str(i)
    end do
    call out%comment('columns: k = design iteration; analyses and cpu_s (analysis CPU) so far; mass of the links; '// &
                     'max_violation = largest g; move_limit = largest change of x in the next approximate problem; '// &
                     'the design values; g<i> = analysis constraints (<= 0 feasible)')
    call out%columns(names)
    do r = 1, opt%n_steps
      associate (st => opt%steps(r))
        row(1:6) = [real(st%k, dp), real(st%analyses, dp), st%cpu, st%mass, st%max_violation, st%move_limit]
        do i = 1, n
          row(6 + i) = prob%var(i)%value(st%x(i))
        end do
        row(7 + n:) = st%g
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
    integer :: i
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
        if (prob%i_frequency > 0) call out%summary('final lowest frozen frequency', str(ev%lowest_frequency, 8)// &
          ' rad/s = '//str(ev%lowest_frequency/prob%base%omega, 5)//' x crank speed')
      else
        call out%summary('final design analysis', 'failed: '//ev%reason)
      end if
    end if
    if (allocated(prob%last_failure)) call out%comment('last failed analysis: '//prob%last_failure)
    call out%cost('mechanism analyses NF (every distinct design, derivatives included)', str(prob%n_analyses))
    call out%cost('analyses for derivatives (forward differences)', str(opt%iterations*size(prob%var)))
    call out%cost('failed analyses', str(prob%n_failed))
    call out%cost('cpu_seconds_per_analysis', str(prob%cpu_analyses/max(1, prob%n_analyses), 4))
    call out%cost('cpu_seconds_analyses', str(prob%cpu_analyses, 4))
    call out%cost('cpu_seconds_design', str(cpu, 4))
  end subroutine write_results

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
      call echo_mechanism(m, u)
      call write_steady_groups(u, merge('shooting', 'harmonic', prob%evaluator == 'shooting'))
      close(u)
    end subroutine write_deck

    subroutine analyse_side(deck_path, out_path)
      character(len=*), intent(in) :: deck_path, out_path
      type(deck_t) :: side_deck
      type(table_t) :: side_out
      type(error_t) :: side_err
      call side_deck%open(deck_path, side_err)
      if (.not. side_err%failed()) call side_out%open(out_path, side_err)
      if (side_err%failed()) then
        call out%comment('could not analyse '//deck_path//': '//side_err%text())
        return
      end if
      call side_out%comment(program_name//' '//program_version)
      call side_out%comment('deck: '//deck_path)
      call run_steady(side_deck, side_out, side_err)
      call side_deck%close()
      if (side_err%failed()) call side_out%comment('stopped: '//side_err%text())
      call side_out%commit(side_err)
    end subroutine analyse_side
  end subroutine write_final_design
end module design_analysis
