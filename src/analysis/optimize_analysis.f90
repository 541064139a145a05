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
  use optim_problem, only: opt_problem_t, opt_counters_t, con_kind_name
  use problem_library, only: problem_info_t, create_problem, problem_names
  use user_problems, only: create_user_problem, user_problem_names
  use deck_problem, only: problem_data_t, build_deck_problem
  use problem_data_settings, only: read_problem_data, echo_problem_data
  use optimize_settings, only: optimize_settings_t, read_optimize_settings, check_optimize_settings, &
                               echo_optimize_settings
  use hs_collection, only: hs_problem_t, hs_numbers, create_hs
  use gauss_optimizer, only: gauss_optimizer_t, method_from_name, hessian_from_name, &
                             hessian_name, hessian_gauss, hessian_exact, hessian_auto, &
                             status_converged, status_max_iter, set_text, globalization_from_name
  implicit none
  private
  public :: run_optimize, check_problem_derivatives

contains

  subroutine run_optimize(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    class(opt_problem_t), allocatable, target :: prob
    type(problem_info_t) :: info
    type(gauss_optimizer_t) :: opt
    type(optimize_settings_t) :: s
    type(problem_data_t), allocatable :: data       ! problem = 'deck': its coefficients
    type(error_t) :: run_err
    integer :: n, n_given
    real(dp), allocatable :: start(:)
    real(dp) :: cpu0, cpu1
    character(len=160), allocatable :: check_lines(:)
    integer :: i

    call read_optimize_settings(deck, s, err)
    if (err%failed()) return
    call select_problem(deck, s%problem, prob, info, data, err)
    if (err%failed()) return
    n = prob%n
    call check_optimize_settings(deck, s, n, n_given, err)
    if (err%failed()) return
    if (n_given == 0) then
      start = info%x0
    else
      start = s%x0(1:n)
    end if
    call echo_optimize_settings(s, start, out)
    if (allocated(data)) call echo_problem_data(data, out)

    call out%comment('problem: '//trim(s%problem)//': '//info%title)
    call out%comment('source: '//info%source)
    call out%comment('variables: '//str(n)//'; objective: '//objective_text(prob)//'; constraints: ' &
                     //constraint_text(prob))
    if (s%check_derivatives) then
      call check_problem_derivatives(prob, start, check_lines, err)
      do i = 1, size(check_lines)
        call out%comment(trim(check_lines(i)))
      end do
      if (err%failed()) then
        call err%add_context('deck '''//deck%path//''', group &optimize, check_derivatives')
        return
      end if
    end if
    call set_options(s, opt)
    call out%comment('method: '//trim(s%method)//', G = '//g_text(opt%opts%hessian, prob)// &
                     ', convergence: feasible, multipliers >= 0, |s| <= xtol (1 + |x|), |dL_pred| <= ftol (1 + |F|), ' &
                     //'|grad L| <= stat_tol max(1, |grad F|); step acceptance: '//trim(s%globalization))

    call cpu_time(cpu0)
    call opt%solve(prob, start, run_err)
    call cpu_time(cpu1)
    if (run_err%failed() .and. run_err%code == input_error_code) then
      err = run_err
      call err%add_context('deck '''//deck%path//''', group &optimize, x0')
      return
    end if

    call write_table(out, opt, prob)
    call write_summary(out, opt, prob, info)
    call write_cost(out, opt, prob, cpu1 - cpu0)
    if (allocated(opt%final_events)) then
      if (len(opt%final_events) > 0) call out%comment('final test: '//opt%final_events)
    end if
    if (run_err%failed()) err = run_err
  end subroutine run_optimize

  !> The problem named in the deck: one posed by coefficients in the deck; the
  !> user's problems (make PROBLEM=...); the Hock-Schittkowski collection; then
  !> the library.  An unknown name is an input error listing the choices.
  subroutine select_problem(deck, problem, prob, info, data, err)
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(in) :: problem
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    type(problem_data_t), allocatable, intent(out) :: data
    type(error_t), intent(inout) :: err
    logical :: found
    character(len=:), allocatable :: names
    found = .false.
    if (problem == 'deck') then
      allocate(data)
      call read_problem_data(deck, data, err)
      if (err%failed()) return
      call build_deck_problem(data, prob, info)
      found = .true.
    end if
    if (.not. found) call create_user_problem(trim(problem), prob, info, found, err)
    if (.not. found .and. .not. err%failed()) call create_collection_problem(trim(problem), prob, info, found)
    if (.not. err%failed() .and. .not. found) call create_problem(problem, prob, info, err)
    if (err%failed()) then
      call err%clear()
      names = problem_names
      if (len(user_problem_names()) > 0) names = user_problem_names()//', '//names
      names = '''deck'' (coefficients in &problem_data), '//names// &
              ', ''hsN'' for the Hock-Schittkowski collection (N = '//collection_text()//')'
      call invalid_value(deck, 'optimize', 'problem', ''''//trim(problem)//'''', 'must be one of '//names// &
                         ' (or a problem of your own: make PROBLEM=file.f90, doc/optimization.md)', err)
    end if
  end subroutine select_problem

  subroutine set_options(s, opt)
    type(optimize_settings_t), intent(in) :: s
    type(gauss_optimizer_t), intent(inout) :: opt
    opt%opts%method = method_from_name(s%method)
    opt%opts%hessian = hessian_from_name(s%hessian)
    opt%opts%max_iter = s%max_iter
    opt%opts%xtol = s%xtol
    opt%opts%ftol = s%ftol
    opt%opts%feas_tol = s%feas_tol
    opt%opts%mult_tol = s%mult_tol
    opt%opts%rcond_min = s%rcond_min
    opt%opts%regularization = s%regularization
    opt%opts%auto_regularize = s%singular_g == 'regularize'
    opt%opts%newton_max_iter = s%newton_max_iter
    opt%opts%potter_repeat = s%potter_fix == 'repeat'
    opt%opts%step_back_refine = s%step_back == 'farthest'
    opt%opts%globalization = globalization_from_name(s%globalization)
    opt%opts%stat_tol = s%stat_tol
  end subroutine set_options

  !> Status, the optimum found (or the best feasible iterate) and the known optimum.
  subroutine write_summary(out, opt, prob, info)
    type(table_t), intent(inout) :: out
    type(gauss_optimizer_t), intent(in) :: opt
    class(opt_problem_t), intent(in) :: prob
    type(problem_info_t), intent(in) :: info
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
        call out%summary('active constraints (|g| <= feas_tol)', set_text(abs(opt%g) <= opt%opts%feas_tol))
        call out%summary('working set', set_text(opt%active))
        call out%summary('multipliers', vector_text(opt%lambda))
        call out%summary('max violation', str(max(0.0_dp, maxval([0.0_dp, opt%g(1:prob%m)]), &
                                                  maxval([0.0_dp, abs(opt%g(prob%m + 1:))])), 4))
      end if
      if (opt%status == status_converged) call out%summary('KKT residual |grad F + C lambda|_inf', &
                                                           str(opt%kkt_residual, 4))
      call out%summary('first-order test: |grad L|_inf / max(1, |grad F|_inf) (<= stat_tol)', &
                       str(opt%stationarity, 4)//' (<= '//str(opt%opts%stat_tol, 3)//')')
      call out%summary('first-order test: smallest lambda_i |c_i| / |grad F| (>= -mult_tol)', &
                       str(opt%min_multiplier, 4)//' (>= '//str(-opt%opts%mult_tol, 3)//')')
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
  end subroutine write_summary

  !> check_derivatives = T: the problem's derivatives at x0 against central
  !> differences of its values (gradient and residual Jacobian against F and
  !> phi, constraint gradients against g, Hessians against the gradients),
  !> step h = eps^(1/3) max(1, |x_j|); one comment line per function with
  !> the relative error max |d - d_fd| / max(1, max |d_fd|).  Above 1e-5
  !> (first derivatives; central differences are good to about 1e-10) or
  !> 1e-3 (Hessians: a difference Hessian, the default where the problem
  !> gives none, is good to about sqrt(eps) |F| / h^2, 1.4e-4 on HS 63 with
  !> |F| = 976; a wrong one is off by O(1)) the run stops with exit 2
  !> naming every wrong derivative and its error.  The
  !> check's evaluations are reported on its own line and left out of the
  !> run's counts.
  subroutine check_problem_derivatives(prob, x, lines, err)
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:)
    character(len=160), allocatable, intent(out) :: lines(:)   !< the table, one line per function
    type(error_t), intent(inout) :: err
    type(opt_counters_t) :: saved
    real(dp), allocatable :: phi(:), grad(:), jac(:, :), g(:), dg(:, :), hess(:, :), xp(:), xm(:), fd(:, :), &
                             gp(:), gm(:), phip(:), phim(:), dgp(:, :), dgm(:, :), jacp(:, :)
    real(dp) :: f, fp, fm, h, rel, worst
    character(len=:), allocatable :: worst_name
    integer :: j, i, n, mt, evals
    n = prob%n
    mt = prob%n_constraints()
    saved = prob%count
    allocate(lines(0))
    allocate(phi(prob%n_residuals), grad(n), jac(n, prob%n_residuals), g(mt), dg(n, mt), hess(n, n), xp(n), &
             xm(n), phip(prob%n_residuals), phim(prob%n_residuals), gp(mt), gm(mt), fd(n, max(1, prob%n_residuals)), &
             dgp(n, mt), dgm(n, mt), jacp(n, prob%n_residuals))
    worst = 0.0_dp
    worst_name = ''
    call prob%analyse(x, f, phi, err)
    call prob%objective_derivatives(x, f, phi, grad, jac, err)
    if (mt > 0) call prob%constraint_values(x, g, err)
    if (mt > 0) call prob%constraint_gradients(x, g, dg, err)
    if (err%failed()) return
    call add('derivative check at x0 (central differences, relative error max |d - d_fd| / max(1, |d_fd|)):')
    ! gradient, residual Jacobian and constraint gradients against the values
    block
      real(dp) :: gfd(n), cfd(n, mt), jfd(n, prob%n_residuals)
      do j = 1, n
        call points(j)
        call prob%analyse(xp, fp, phip, err)
        call prob%analyse(xm, fm, phim, err)
        gfd(j) = (fp - fm)/(2.0_dp*h)
        if (prob%n_residuals > 0) jfd(j, :) = (phip - phim)/(2.0_dp*h)
        if (mt > 0) then
          call prob%constraint_values(xp, gp, err)
          call prob%constraint_values(xm, gm, err)
          cfd(j, :) = (gp - gm)/(2.0_dp*h)
        end if
        if (err%failed()) return
      end do
      call judge('objective gradient', grad, gfd, 1.0e-5_dp)
      if (prob%n_residuals > 0) call judge('residual Jacobian', reshape(jac, [n*prob%n_residuals]), &
                                           reshape(jfd, [n*prob%n_residuals]), 1.0e-5_dp)
      do i = 1, mt
        call judge('gradient of constraint '//str(i), dg(:, i), cfd(:, i), 1.0e-5_dp)
      end do
    end block
    ! Hessians against differences of the (checked) gradients
    if (.not. prob%is_least_squares()) then
      call prob%objective_hessian(x, hess, err)
      if (err%failed()) return
      block
        real(dp) :: hfd(n, n), gr_p(n), gr_m(n)
        do j = 1, n
          call points(j)
          call prob%analyse(xp, fp, phip, err)
          call prob%objective_derivatives(xp, fp, phip, gr_p, jacp, err)
          call prob%analyse(xm, fm, phim, err)
          call prob%objective_derivatives(xm, fm, phim, gr_m, jacp, err)
          if (err%failed()) return
          hfd(:, j) = (gr_p - gr_m)/(2.0_dp*h)
        end do
        call judge('objective Hessian', reshape(hess, [n*n]), reshape(hfd, [n*n]), 1.0e-3_dp)
      end block
    end if
    do i = 1, mt
      call prob%constraint_hessian(i, x, hess, err)
      if (err%failed()) return
      block
        real(dp) :: hfd(n, n)
        do j = 1, n
          call points(j)
          call prob%constraint_values(xp, gp, err)
          call prob%constraint_gradients(xp, gp, dgp, err)
          call prob%constraint_values(xm, gm, err)
          call prob%constraint_gradients(xm, gm, dgm, err)
          if (err%failed()) return
          hfd(:, j) = (dgp(:, i) - dgm(:, i))/(2.0_dp*h)
        end do
        call judge('Hessian of constraint '//str(i), reshape(hess, [n*n]), reshape(hfd, [n*n]), 1.0e-3_dp)
      end block
    end do
    evals = prob%count%analyses - saved%analyses
    call add('derivative check: '//str(evals)//' analyses, '//str(prob%count%gradients - saved%gradients)// &
                     ' gradient evaluations (not in the run''s counts)')
    prob%count = saved
    if (len(worst_name) > 0) call err%set('check_derivatives', 'derivatives at x0 that disagree with central ' &
      //'differences of the values (relative error): '//worst_name, code=input_error_code)
  contains
    subroutine add(text)
      character(len=*), intent(in) :: text
      lines = [character(len=160) :: lines, text]
    end subroutine add

    subroutine points(jj)
      integer, intent(in) :: jj
      h = 6.0554544523933395e-6_dp*max(1.0_dp, abs(x(jj)))
      xp = x
      xm = x
      xp(jj) = x(jj) + h
      xm(jj) = x(jj) - h
    end subroutine points

    subroutine judge(name, d, dfd, tol)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: d(:), dfd(:), tol
      rel = 0.0_dp
      if (size(d) > 0) rel = maxval(abs(d - dfd))/max(1.0_dp, maxval(abs(dfd)))
      call add('  '//name//': '//str(rel, 3)//merge(' WRONG', '      ', rel > tol))
      if (rel > tol) then
        worst = max(worst, rel)
        if (len(worst_name) > 0) worst_name = worst_name//', '
        worst_name = worst_name//name//' '//str(rel, 3)
      end if
    end subroutine judge
  end subroutine check_problem_derivatives

  !> The cost footer: iterations, analyses and every kind of evaluation.
  subroutine write_cost(out, opt, prob, cpu_seconds)
    type(table_t), intent(inout) :: out
    type(gauss_optimizer_t), intent(in) :: opt
    class(opt_problem_t), intent(in) :: prob
    real(dp), intent(in) :: cpu_seconds
    call out%cost('iterations NI', str(opt%iterations))
    call out%cost('analyses NF (objective evaluations)', str(prob%count%analyses))
    call out%cost('gradient evaluations', str(prob%count%gradients))
    call out%cost('residual Jacobian evaluations', str(prob%count%jacobians))
    call out%cost('objective evaluations in finite differences', str(prob%count%fd_analyses))
    call out%cost('objective Hessian evaluations', str(prob%count%hessians))
    call out%cost('constraint evaluations', str(prob%count%constraint_evals))
    call out%cost('general-constraint evaluations in B11 / of them in Powell''s fallback', &
                  str(prob%count%b11_constraint_evals)//' / '//str(prob%count%powell_constraint_evals))
    call out%cost('H evaluations in Powell''s fallback', str(prob%count%powell_h_evals))
    call out%cost('general-constraint gradients / Hessians', str(prob%count%constraint_gradients)//' / '// &
                  str(prob%count%constraint_hessians))
    call out%cost('constraint evaluations in finite differences', str(prob%count%fd_constraint_evals))
    call out%cost('multiplier solves / Powell fallbacks', str(opt%newton_solves)//' / '//str(opt%powell_fallbacks))
    call out%cost('drops / additions / releases', str(opt%drops)//' / '//str(opt%additions)//' / '//str(opt%releases))
    call out%cost('step-backs / Potter repeats', str(opt%step_backs)//' / '//str(opt%potter_repeats))
    call out%cost('regularizations of G', str(opt%regularizations))
    call out%cost('filter: rejected trial points (each one analysis) / first-order refusals', &
                  str(opt%backtracks)//' / '//str(opt%kkt_refusals))
    call out%cost('all objective evaluations (NF + finite differences)', &
                  str(prob%count%analyses + prob%count%fd_analyses))
    call out%cost('optimizer_cpu_seconds', str(cpu_seconds, 4))
  end subroutine write_cost

  !> 'hsN' for a problem of the Hock-Schittkowski collection (not those the
  !> library poses itself): standard start and published optimum.
  subroutine create_collection_problem(name, prob, info, found)
    character(len=*), intent(in) :: name
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    logical, intent(out) :: found
    type(hs_problem_t), allocatable :: hp
    integer :: number, ios
    found = .false.
    if (len(name) < 3 .or. name(1:min(2, len(name))) /= 'hs') return
    read(name(3:), *, iostat=ios) number
    if (ios /= 0 .or. verify(name(3:), '0123456789') /= 0) return
    allocate(hp)
    call create_hs(number, hp, info%x0, info%x_star, info%f_star, found)
    if (.not. found) return
    info%name = name
    info%title = 'Hock-Schittkowski problem '//str(number)//' (collection, central differences)'
    info%source = 'Hock & Schittkowski, LNEMS 187 (1981), problem '//str(number)
    info%method = 'auto'
    info%has_optimum = .true.
    call move_alloc(hp, prob)
  end subroutine create_collection_problem

  function collection_text() result(s)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, size(hs_numbers)
      if (i > 1) s = s//' '
      s = s//str(hs_numbers(i))
    end do
  end function collection_text

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
    else if (hessian_name(h) == 'bfgs') then
      s = 'objective Hessian at x_0, then damped BFGS updates'
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
    do i = prob%m + 1, prob%m + prob%n_eq
      if (len(s) > 0) s = s//', '
      s = s//'h'//str(i)//' '//con_kind_name(prob%con_kind(i))//' equality'
    end do
  end function constraint_text
end module optimize_analysis
