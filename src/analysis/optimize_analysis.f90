!> The `optimize` analysis: one built-in problem, one method of the Gauss
!> family, one start; an iteration table (k, NF, F, x, multipliers, active
!> set) and a summary with the optimum, the known optimum where the library
!> has one, and the cost (analyses NF, gradients, iterations NI).
!>
!>     &run analysis = 'optimize' /
!>     &optimize problem = 'rosen_suzuki', method = 'gnlc_ns', x0 = 0, 0, 0, 0 /
!>
!> Exit: converged -> 0; bad input (including a GNLC start that violates a
!> constraint) -> code 2; iteration limit, singular G, step-back cycling ->
!> an error with the diagnosis (the table and the best feasible point stay in
!> the output).
module optimize_analysis
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower
  use deck_reader, only: deck_t, invalid_value, input_error_code
  use table_output, only: table_t
  use optim_problem, only: opt_problem_t, con_kind_name
  use problem_library, only: problem_info_t, create_problem, problem_names
  use gauss_optimizer, only: gauss_optimizer_t, method_from_name, method_names, hessian_from_name, &
                             hessian_name, hessian_gauss, hessian_exact, hessian_auto, &
                             status_converged, status_max_iter, set_text
  implicit none
  private
  public :: run_optimize

  integer, parameter :: max_vars = 50
  real(dp), parameter :: unset = -huge(1.0_dp)

  ! staging variables of the &optimize group
  character(len=32) :: problem, method, hessian, potter_fix, step_back
  real(dp) :: x0(max_vars), xtol, ftol, feas_tol, mult_tol, rcond_min, regularization
  integer :: max_iter, newton_max_iter
  namelist /optimize/ problem, method, x0, hessian, max_iter, xtol, ftol, feas_tol, mult_tol, rcond_min, &
                      regularization, newton_max_iter, potter_fix, step_back

contains

  subroutine set_defaults()
    problem = 'rosen_suzuki'
    method = 'gnlc'
    x0 = unset
    hessian = 'auto'
    max_iter = 50
    xtol = 1.0e-8_dp
    ftol = 1.0e-12_dp
    feas_tol = 1.0e-8_dp
    mult_tol = 1.0e-8_dp
    rcond_min = 1.0e-13_dp
    regularization = 0.0_dp
    newton_max_iter = 30
    potter_fix = 'repeat'
    step_back = 'farthest'
  end subroutine set_defaults

  subroutine read_optimize(unit, ios, iomsg)
    integer, intent(in) :: unit
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    read(unit, nml=optimize, iostat=ios, iomsg=iomsg)
  end subroutine read_optimize

  subroutine run_optimize(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    class(opt_problem_t), allocatable, target :: prob
    type(problem_info_t) :: info
    type(gauss_optimizer_t) :: opt
    type(error_t) :: run_err
    logical :: found
    integer :: n, n_given, u
    real(dp), allocatable :: start(:)
    real(dp) :: cpu0, cpu1

    call set_defaults()
    call deck%read_group('optimize', read_optimize, .true., found, err)
    if (err%failed()) return
    problem = lower(problem)
    method = lower(method)
    hessian = lower(hessian)
    potter_fix = lower(potter_fix)
    step_back = lower(step_back)
    call create_problem(problem, prob, info, err)
    if (err%failed()) then
      call err%clear()
      call invalid_value(deck, 'optimize', 'problem', ''''//trim(problem)//'''', 'must be one of '//problem_names, err)
      return
    end if
    n = prob%n
    n_given = count(x0 > 0.5_dp*unset)
    if (method_from_name(method) == 0) then
      call invalid_value(deck, 'optimize', 'method', ''''//trim(method)//'''', 'must be one of '//method_names, err)
    else if (hessian_from_name(hessian) < 0) then
      call invalid_value(deck, 'optimize', 'hessian', ''''//trim(hessian)//'''', &
                         'must be ''auto'', ''gauss'' (G = 2JJ^T) or ''exact''', err)
    else if (n_given /= 0 .and. (n_given /= n .or. any(x0(1:n) <= 0.5_dp*unset))) then
      call invalid_value(deck, 'optimize', 'x0', str(n_given)//' values', 'problem '//trim(problem)// &
                         ' has '//str(n)//' variables: give all of x0(1:'//str(n)//') or none', err)
    else if (max_iter < 0) then
      call invalid_value(deck, 'optimize', 'max_iter', str(max_iter), 'must be >= 0', err)
    else if (.not. (xtol > 0.0_dp)) then
      call invalid_value(deck, 'optimize', 'xtol', str(xtol), 'must be > 0', err)
    else if (.not. (ftol > 0.0_dp)) then
      call invalid_value(deck, 'optimize', 'ftol', str(ftol), 'must be > 0', err)
    else if (.not. (feas_tol > 0.0_dp)) then
      call invalid_value(deck, 'optimize', 'feas_tol', str(feas_tol), 'must be > 0', err)
    else if (.not. (mult_tol >= 0.0_dp)) then
      call invalid_value(deck, 'optimize', 'mult_tol', str(mult_tol), 'must be >= 0', err)
    else if (.not. (rcond_min > 0.0_dp .and. rcond_min < 1.0_dp)) then
      call invalid_value(deck, 'optimize', 'rcond_min', str(rcond_min), 'must lie in (0, 1)', err)
    else if (.not. (regularization >= 0.0_dp)) then
      call invalid_value(deck, 'optimize', 'regularization', str(regularization), 'must be >= 0', err)
    else if (newton_max_iter < 1) then
      call invalid_value(deck, 'optimize', 'newton_max_iter', str(newton_max_iter), 'must be >= 1', err)
    else if (potter_fix /= 'repeat' .and. potter_fix /= 'none') then
      call invalid_value(deck, 'optimize', 'potter_fix', ''''//trim(potter_fix)//'''', &
                         'must be ''repeat'' (Potter''s fix (a)) or ''none'' (report the cycling)', err)
    else if (step_back /= 'farthest' .and. step_back /= 'b13') then
      call invalid_value(deck, 'optimize', 'step_back', ''''//trim(step_back)//'''', &
                         'must be ''farthest'' (the boundary, P) or ''b13'' (one linear interpolation)', err)
    end if
    if (err%failed()) return
    if (n_given == 0) then
      start = info%x0
      x0(1:n) = start
    else
      start = x0(1:n)
    end if

    ! echo the effective input (x0 only as far as the problem uses it)
    u = out%echo_unit()
    write(u, '(a)') '&optimize'
    write(u, '(a)') ' problem = '''//trim(problem)//''', method = '''//trim(method)//''', hessian = ''' &
                    //trim(hessian)//''','
    write(u, '(a,*(g0.17,:,", "))') ' x0 = ', start
    write(u, '(a)') ' max_iter = '//str(max_iter)//', newton_max_iter = '//str(newton_max_iter)// &
                    ', potter_fix = '''//trim(potter_fix)//''', step_back = '''//trim(step_back)//''','
    write(u, '(a)') ' xtol = '//str(xtol)//', ftol = '//str(ftol)//', feas_tol = '//str(feas_tol)//','
    write(u, '(a)') ' mult_tol = '//str(mult_tol)//', rcond_min = '//str(rcond_min)//', regularization = ' &
                    //str(regularization)
    write(u, '(a)') '/'
    call out%end_echo()

    call out%comment('problem: '//trim(problem)//': '//info%title)
    call out%comment('source: '//info%source)
    call out%comment('variables: '//str(n)//'; objective: '//objective_text(prob)//'; constraints: ' &
                     //constraint_text(prob))
    opt%opts%method = method_from_name(method)
    opt%opts%hessian = hessian_from_name(hessian)
    opt%opts%max_iter = max_iter
    opt%opts%xtol = xtol
    opt%opts%ftol = ftol
    opt%opts%feas_tol = feas_tol
    opt%opts%mult_tol = mult_tol
    opt%opts%rcond_min = rcond_min
    opt%opts%regularization = regularization
    opt%opts%newton_max_iter = newton_max_iter
    opt%opts%potter_repeat = potter_fix == 'repeat'
    opt%opts%step_back_refine = step_back == 'farthest'
    call out%comment('method: '//trim(method)//', G = '//g_text(opt%opts%hessian, prob)// &
                     ', convergence: feasible, multipliers >= 0, |s| <= xtol (1 + |x|), |dF_pred| <= ftol (1 + |F|)')

    call cpu_time(cpu0)
    call opt%solve(prob, start, run_err)
    call cpu_time(cpu1)
    if (run_err%failed() .and. run_err%code == input_error_code) then
      err = run_err
      call err%add_context('deck '''//deck%path//''', group &optimize, x0')
      return
    end if

    call write_table(out, opt, prob)

    ! ---- summary
    if (opt%status == status_converged) then
      call out%summary('status', 'converged')
    else if (opt%status == status_max_iter) then
      call out%summary('status', 'iteration limit reached')
    else
      call out%summary('status', 'stopped')
    end if
    call out%summary('NI', str(opt%iterations))
    call out%summary('NF', str(prob%count%analyses))
    if (allocated(opt%x)) then
      call out%summary('F', str(opt%f, 15))
      call out%summary('x', vector_text(opt%x))
      if (prob%n_constraints() > 0) then
        call out%summary('g', vector_text(opt%g))
        call out%summary('active constraints (|g| <= feas_tol)', set_text(abs(opt%g) <= feas_tol))
        call out%summary('working set', set_text(opt%active))
        call out%summary('multipliers', vector_text(opt%lambda))
        call out%summary('max violation', str(max(0.0_dp, maxval([0.0_dp, opt%g(1:prob%m)]), &
                                                  maxval([0.0_dp, abs(opt%g(prob%m + 1:))])), 4))
      end if
      if (opt%status == status_converged) call out%summary('KKT residual |grad F + C lambda|_inf', &
                                                           str(opt%kkt_residual, 4))
    end if
    if (opt%status /= status_converged) then
      if (opt%have_best) then
        call out%summary('best feasible iterate k', str(opt%k_best))
        call out%summary('best feasible F', str(opt%f_best, 15))
        call out%summary('best feasible x', vector_text(opt%x_best))
      else
        call out%summary('best feasible iterate', 'none (no iterate satisfied every constraint)')
      end if
    end if
    if (info%has_optimum .and. allocated(opt%x)) then
      call out%summary('known optimum x*', vector_text(info%x_star))
      call out%summary('known optimum F*', str(info%f_star, 15))
      call out%summary('|x - x*|_inf', str(maxval(abs(opt%x - info%x_star)), 4))
      call out%summary('|F - F*|', str(abs(opt%f - info%f_star), 4))
    end if

    ! ---- cost
    call out%cost('iterations NI', str(opt%iterations))
    call out%cost('analyses NF (objective evaluations)', str(prob%count%analyses))
    call out%cost('gradient evaluations', str(prob%count%gradients))
    call out%cost('objective evaluations in finite differences', str(prob%count%fd_analyses))
    call out%cost('objective Hessian evaluations', str(prob%count%hessians))
    call out%cost('constraint evaluations', str(prob%count%constraint_evals))
    call out%cost('general-constraint gradients / Hessians', str(prob%count%constraint_gradients)//' / '// &
                  str(prob%count%constraint_hessians))
    call out%cost('constraint evaluations in finite differences', str(prob%count%fd_constraint_evals))
    call out%cost('multiplier solves / Powell fallbacks', str(opt%newton_solves)//' / '//str(opt%powell_fallbacks))
    call out%cost('drops / additions / releases', str(opt%drops)//' / '//str(opt%additions)//' / '//str(opt%releases))
    call out%cost('step-backs / Potter repeats', str(opt%step_backs)//' / '//str(opt%potter_repeats))
    call out%cost('regularizations of G', str(opt%regularizations))
    call out%cost('optimizer_cpu_seconds', str(cpu1 - cpu0, 4))
    if (allocated(opt%final_events)) then
      if (len(opt%final_events) > 0) call out%comment('final test: '//opt%final_events)
    end if
    if (run_err%failed()) err = run_err
  end subroutine run_optimize

  !> Rows k, NF, F, max violation, step, |S|, x(1:n), lambda(1:m+n_eq),
  !> active(1:m+n_eq) (1 = in the working set); events as '#' lines.
  subroutine write_table(out, opt, prob)
    type(table_t), intent(inout) :: out
    type(gauss_optimizer_t), intent(in) :: opt
    class(opt_problem_t), intent(in) :: prob
    character(len=16), allocatable :: names(:)
    integer :: i, n, mt, r
    n = prob%n
    mt = prob%n_constraints()
    allocate(names(6 + n + 2*mt))
    names(1:6) = [character(len=16) :: 'k', 'NF', 'F', 'max_violation', 'step', 'n_active']
    do i = 1, n
      names(6 + i) = 'x'//str(i)
    end do
    do i = 1, mt
      names(6 + n + i) = 'lambda'//str(i)
      names(6 + n + mt + i) = 'active'//str(i)
    end do
    call out%columns(names)
    do r = 1, opt%n_log
      associate (row => opt%log(r))
        call out%row([real(row%k, dp), real(row%nf, dp), row%f, row%max_violation, row%step, &
                      real(count(row%active), dp), row%x, row%lambda, merge(1.0_dp, 0.0_dp, row%active)])
        if (len(row%events) > 0) call out%comment('k = '//str(row%k)//': '//row%events)
      end associate
    end do
  end subroutine write_table

  function vector_text(v) result(s)
    real(dp), intent(in) :: v(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, size(v)
      if (i > 1) s = s//' '
      s = s//str(v(i), 12)
    end do
  end function vector_text

  function objective_text(prob) result(s)
    class(opt_problem_t), intent(in) :: prob
    character(len=:), allocatable :: s
    if (prob%is_least_squares()) then
      s = 'sum of '//str(prob%n_residuals)//' squared residuals'
    else
      s = 'general'
    end if
  end function objective_text

  function g_text(h, prob) result(s)
    integer, intent(in) :: h
    class(opt_problem_t), intent(in) :: prob
    character(len=:), allocatable :: s
    integer :: hk
    hk = h
    if (hk == hessian_auto) then
      hk = hessian_exact
      if (prob%is_least_squares()) hk = hessian_gauss
    end if
    if (hk == hessian_gauss) then
      s = '2 J J^T (B5)'
    else
      s = 'objective Hessian'
    end if
    s = s//' (hessian = '''//hessian_name(h)//''')'
  end function g_text

  function constraint_text(prob) result(s)
    class(opt_problem_t), intent(in) :: prob
    character(len=:), allocatable :: s
    integer :: i, j
    if (prob%n_constraints() == 0) then
      s = 'none'
      return
    end if
    s = ''
    i = 1
    do while (i <= prob%m)
      j = i
      do while (j < prob%m)
        if (prob%con_kind(j + 1) /= prob%con_kind(i)) exit
        j = j + 1
      end do
      if (len(s) > 0) s = s//', '
      if (j > i) then
        s = s//'g'//str(i)//'-g'//str(j)//' '//con_kind_name(prob%con_kind(i))
      else
        s = s//'g'//str(i)//' '//con_kind_name(prob%con_kind(i))
      end if
      i = j + 1
    end do
    if (prob%n_eq > 0) then
      if (len(s) > 0) s = s//', '
      s = s//str(prob%n_eq)//' linear equalities (numbered '//str(prob%m + 1)//'-'//str(prob%m + prob%n_eq)//')'
    end if
  end function constraint_text
end module optimize_analysis
