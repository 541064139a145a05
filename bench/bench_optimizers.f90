!> The Gauss family beside modern optimizers: the same problems and starts
!> through GNLC / GNLC.NS (ours) and NLopt's SLSQP (gradient-based SQP) and
!> COBYLA (derivative-free), through NLopt's Fortran (F77) interface.  The
!> modern counterpart of the papers' comparison with GRG (FORMULATION.md §10).
!>
!> Printed per run: NF (objective evaluations = analyses), NG (gradient
!> evaluations), NFD (objective evaluations spent in finite differences),
!> NI (iterations; NLopt does not report them), the final F, the distance to
!> the known optimum and the largest constraint violation.  A benchmark:
!> figures, not pass/fail.
module nlopt_glue
  use kinds, only: dp, i8
  use nlopt_api
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  implicit none
  private
  public :: nlopt_run, alg_slsqp, alg_cobyla



  ! NLopt's callbacks carry only an address: the problem being solved is
  ! module state for the duration of one nlopt_run (a legacy callback forces it)
  class(opt_problem_t), pointer :: current => null()
  integer, target, save :: ids(0:200) = 0
  type(error_t), save :: callback_err

contains

  !> Minimise prob from x (in: start, out: NLopt's result) with algorithm
  !> `alg`; ires is NLopt's return code (> 0 success).
  subroutine nlopt_run(prob, alg, x, f, ires, err)
    class(opt_problem_t), intent(inout), target :: prob
    integer, intent(in) :: alg
    real(dp), intent(inout) :: x(:)
    real(dp), intent(out) :: f
    integer, intent(out) :: ires
    type(error_t), intent(inout) :: err
    integer(i8) :: opt
    integer :: i, r
    current => prob
    call callback_err%clear()
    do i = 0, size(ids) - 1
      ids(i) = i
    end do
    call nlo_create(opt, alg, prob%n)
    call nlo_set_min_objective(r, opt, objective_cb, ids(0))
    do i = 1, prob%m
      call nlo_add_inequality_constraint(r, opt, constraint_cb, ids(i), 1.0e-10_dp)
    end do
    do i = prob%m + 1, prob%m + prob%n_eq
      call nlo_add_equality_constraint(r, opt, constraint_cb, ids(i), 1.0e-10_dp)
    end do
    call nlo_set_xtol_rel(r, opt, 1.0e-8_dp)
    call nlo_set_ftol_rel(r, opt, 1.0e-14_dp)
    call nlo_set_maxeval(r, opt, 20000)
    call nlo_optimize(ires, opt, x, f)
    call nlo_destroy(opt)
    if (callback_err%failed()) err = callback_err
    current => null()
  end subroutine nlopt_run

  subroutine objective_cb(val, n, x, grad, need_gradient, f_data)
    real(dp), intent(out) :: val
    integer, intent(in) :: n
    real(dp), intent(in) :: x(n)
    real(dp), intent(inout) :: grad(n)
    integer, intent(in) :: need_gradient
    integer, intent(in) :: f_data
    real(dp), allocatable :: phi(:), jac(:, :)
    allocate(phi(current%n_residuals), jac(n, current%n_residuals))
    call current%analyse(x, val, phi, callback_err)
    if (need_gradient /= 0) call current%objective_derivatives(x, val, phi, grad, jac, callback_err)
    if (f_data /= 0) call callback_err%set('objective_cb', 'unexpected callback data')
  end subroutine objective_cb

  subroutine constraint_cb(val, n, x, grad, need_gradient, f_data)
    real(dp), intent(out) :: val
    integer, intent(in) :: n
    real(dp), intent(in) :: x(n)
    real(dp), intent(inout) :: grad(n)
    integer, intent(in) :: need_gradient
    integer, intent(in) :: f_data
    real(dp), allocatable :: g(:), dg(:, :)
    integer :: mt
    mt = current%n_constraints()
    allocate(g(mt), dg(n, mt))
    call current%constraint_values(x, g, callback_err)
    val = g(f_data)
    if (need_gradient /= 0) then
      call current%constraint_gradients(x, g, dg, callback_err)
      grad = dg(:, f_data)
    end if
  end subroutine constraint_cb
end module nlopt_glue

program bench_optimizers
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t, create_problem
  use gauss_optimizer, only: gauss_optimizer_t, gauss_options_t, method_from_name, status_converged, glob_none, &
                             hessian_bfgs
  use hs_collection, only: hs_problem_t, hs_numbers, hs_holdout, hs_holdout2, create_hs
  use nlopt_glue, only: nlopt_run, alg_slsqp, alg_cobyla
  implicit none

  real(dp), parameter :: r5 = 2.2360679774997897_dp
  integer, parameter :: ns = 4              !< collection: ours (defaults), ours (hessian = 'bfgs'), SLSQP, COBYLA
  real(dp), allocatable :: ref_x(:)
  character(len=16) :: arg

  write(output_unit, '(a)') '# Gauss family (ours) beside NLopt SLSQP and COBYLA: same problems, same starts.'
  write(output_unit, '(a)') '# NF = objective evaluations (analyses), NG = gradient evaluations, NFD = objective'
  write(output_unit, '(a)') '# evaluations inside forward differences, NI = iterations (NLopt does not report them),'
  write(output_unit, '(a)') '# dx = |x - x*|_inf against the known optimum (or against GNLC''s result: "ref"),'
  write(output_unit, '(a)') '# viol = largest constraint violation.  NLopt: xtol_rel 1e-8, ftol_rel 1e-14, tol 1e-10.'
  write(output_unit, '(a)') '#'
  write(output_unit, '(a)') '# problem                  start          solver            NF    NG   NFD    NI' // &
                            '                 F        dx      viol  status'

  ! `bench_optimizers hs`: only the Hock-Schittkowski part (seconds, not minutes)
  call get_command_argument(1, arg)
  if (arg /= 'hs') call paper_problems()
  call collection_profile()
  call collection_noise()

contains

  !> The papers' problems and the library's HS problems, one row per solver.
  subroutine paper_problems()
    call compare('rosen_suzuki', '[0,0,0,0]', [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], ['gnlc_ns', 'gnlc   '])
    call compare('rosen_suzuki', '[1,1,1,1]', [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], ['gnlc_ns', 'gnlc   '])
    call compare('rosen_suzuki', '[2,2,2,2]', [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp], ['gnlc_ns'])
    call compare('rosen_suzuki', '[0,0,r5,0]', [0.0_dp, 0.0_dp, r5, 0.0_dp], ['gnlc_ns', 'gnlc   '])
    call compare('fourbar_path', 'Table 3', [real(dp) ::], ['gnlc   ', 'gnlc_ns'])
    call compare('fourbar_path_13', 'Table 3', [real(dp) ::], ['gnlc'])
    call compare('fourbar_path_offset', 'Table 3', [real(dp) ::], ['gnlc'])
    call compare('fourbar_path_13_offset', 'Table 3', [real(dp) ::], ['gnlc'])
    call compare('hs35', 'HS', [real(dp) ::], ['gauss_constrained'])
    call compare('hs15', 'HS (infeas.)', [real(dp) ::], ['gnlc_ns'])
    call compare('hs65', 'HS (infeas.)', [real(dp) ::], ['gnlc_ns'])
    call compare('general_convex', '[0,0]', [real(dp) ::], ['gnlc_general'])
    call compare('three_circles', '[1,5]', [real(dp) ::], ['gnlc_ns'])
  end subroutine paper_problems

  !> Round-off sensitivity of the collection: each problem from its standard
  !> start times (1 + 1e-14 u), u uniform in [-1, 1], 20 seeds, default
  !> settings; prints the problems not solved in all 20 (the test's criterion).
  !> The second hold-out is left out (minutes of finite differences).
  subroutine collection_noise()
    type(hs_problem_t) :: p
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    real(dp), allocatable :: x0(:), xs(:), u(:)
    real(dp) :: fs, v
    logical :: found
    integer :: k, seed, nseed, ok, i
    integer, allocatable :: put(:)
    call random_seed(size=nseed)
    allocate(put(nseed))
    write(output_unit, '(a)') '#'
    write(output_unit, '(a)') '# collection under relative 1e-14 noise on x0 (20 seeds, defaults); problems not'// &
                              ' solved in every run:'
    do k = 1, size(hs_numbers)
      if (any(hs_numbers(k) == hs_holdout2)) cycle
      ok = 0
      do seed = 1, 20
        do i = 1, nseed
          put(i) = seed*7919 + 104729*i
        end do
        call random_seed(put=put)
        call create_hs(hs_numbers(k), p, x0, xs, fs, found)
        allocate(u(size(x0)))
        call random_number(u)
        x0 = x0*(1.0_dp + 1.0e-14_dp*(2.0_dp*u - 1.0_dp))
        deallocate(u)
        opt%opts%method = method_from_name('auto')
        call opt%solve(p, x0, err)
        v = huge(1.0_dp)
        if (allocated(opt%x)) v = violation(p, opt%x)
        if (opt%status == status_converged .and. abs(opt%f - fs) <= 1.0e-6_dp*(1.0_dp + abs(fs)) .and. &
            v <= 1.0e-6_dp) ok = ok + 1
      end do
      if (ok < 20) write(output_unit, '(a,i3,a,i3,a)') '#   HS', hs_numbers(k), ': solved in', ok, ' of 20'
    end do
  end subroutine collection_noise

  !> The Hock-Schittkowski collection (hs_collection and the HS problems of
  !> problem_library) from the standard starts: ours with default settings,
  !> SLSQP and COBYLA.  A run counts as solved when |f - f*| <= 1e-6 (1 + |f*|)
  !> and the violation <= 1e-6 (the test's criterion).  Writes the NF table
  !> (build/bench/hs_nf.dat) and the Dolan-More performance profile of NF
  !> (build/bench/hs_profile.dat): rho_s(tau) = share of problems that solver
  !> s solves within tau times the fewest evaluations of any solver.  The
  !> count is every objective evaluation: NF plus those spent on finite-
  !> difference gradients and Hessians (the collection's derivatives are
  !> central differences, for every solver alike).
  subroutine collection_profile()
    character(len=16), parameter :: lib_names(6) = [character(len=16) :: 'hs15', 'hs21', 'hs28', 'hs35', &
                                                    'rosen_suzuki', 'hs65']
    integer, parameter :: np = size(hs_numbers) + 6
    character(len=*), parameter :: set_mark(0:2) = [character(len=3) :: '', ' h', ' h2']
    integer :: nf(np, ns), k, u, i, j, n_tau, length, status, ios, set(np)
    real(dp), allocatable :: ratios(:)
    character(len=512) :: dir
    character(len=16) :: names(np)
    real(dp) :: r(np, ns), tau, best, ratio
    logical :: solved(np, ns)
    write(output_unit, '(a)') '#'
    write(output_unit, '(a)') '# Hock-Schittkowski collection, standard starts; ours with default settings (auto) and ' &
                              //'with hessian = ''bfgs''.'
    write(output_unit, '(a)') '# problem      NF_gauss   NF_bfgs  NF_slsqp NF_cobyla   (all objective evaluations, NF + ' &
                              //'finite differences; -1: not solved to |f - f*| <= 1e-6 (1 + |f*|), violation <= 1e-6; ' &
                              //'h: hold-out, h2: second hold-out)'
    do k = 1, size(hs_numbers)
      names(k) = 'hs'//str(hs_numbers(k))
    end do
    names(size(hs_numbers) + 1:) = lib_names
    do k = 1, np
      call run_solvers(k, names(k), nf(k, :), solved(k, :))
      set(k) = 0
      if (k <= size(hs_numbers)) then
        if (any(hs_numbers(min(k, size(hs_numbers))) == hs_holdout)) set(k) = 1
        if (any(hs_numbers(min(k, size(hs_numbers))) == hs_holdout2)) set(k) = 2
      end if
      write(output_unit, '(a14,4i10,a)') names(k), merge(nf(k, :), -1, solved(k, :)), trim(set_mark(set(k)))
    end do
    write(output_unit, '(a,4i4,a,i4)') '# solved (gauss, bfgs, slsqp, cobyla): ', count(solved, dim=1), ' of ', np
    write(output_unit, '(a,4i4,a,i4)') '#   tuning set:                         ', &
      (count(solved(:, j) .and. set == 0), j=1, ns), ' of ', count(set == 0)
    write(output_unit, '(a,4i4,a,i4)') '#   hold-out:                           ', &
      (count(solved(:, j) .and. set == 1), j=1, ns), ' of ', count(set == 1)
    write(output_unit, '(a,4i4,a,i4)') '#   second hold-out:                    ', &
      (count(solved(:, j) .and. set == 2), j=1, ns), ' of ', count(set == 2)
    write(output_unit, '(a,4f10.1)') '# median evaluations over the problems each solves: ', &
      (median(real(pack(nf(:, j), solved(:, j)), dp)), j=1, ns)
    write(output_unit, '(a,4f10.1)') '# median evaluations over the problems all four solve: ', &
      (median(real(pack(nf(:, j), all(solved, dim=2)), dp)), j=1, ns)
    ! data files for the figure: $BENCH_DIR (default build/bench, run_bench.sh's)
    call get_environment_variable('BENCH_DIR', dir, length, status)
    if (status /= 0 .or. length == 0) dir = 'build/bench'
    open(newunit=u, file=trim(dir)//'/hs_nf.dat', status='replace', action='write', iostat=ios)
    if (ios /= 0) then
      write(output_unit, '(a)') '# cannot write '//trim(dir)//'/hs_nf.dat: no data files (set BENCH_DIR)'
      return
    end if
    write(u, '(a)') '# problem NF_gauss NF_bfgs NF_slsqp NF_cobyla (-1: not solved)'
    do k = 1, np
      write(u, '(a14,4i10)') names(k), merge(nf(k, :), -1, solved(k, :))
    end do
    close(u)
    ! performance ratios r_ps = NF_ps / min_s NF_ps (unsolved: infinite)
    r = huge(1.0_dp)
    do k = 1, np
      if (.not. any(solved(k, :))) cycle
      best = minval(real(nf(k, :), dp), mask=solved(k, :))
      do j = 1, ns
        if (solved(k, j)) r(k, j) = real(nf(k, j), dp)/best
      end do
    end do
    open(newunit=u, file=trim(dir)//'/hs_profile.dat', status='replace', action='write')
    write(u, '(a)') '# tau rho_gauss rho_bfgs rho_slsqp rho_cobyla (Dolan-More profile of NF over '//str(np)//' problems)'
    n_tau = 400
    do i = 0, n_tau
      tau = 2.0_dp**(12.0_dp*real(i, dp)/real(n_tau, dp))
      write(u, '(es14.6,4f10.5)') tau, (real(count(r(:, j) <= tau), dp)/real(np, dp), j=1, ns)
    end do
    close(u)
    ! ratio of our NF to the best NLopt method's, on the problems both solve
    do i = 1, 2
      write(output_unit, '(a)') '# NF_'//trim(merge('gauss', 'bfgs ', i == 1))//' / min(NF_slsqp, NF_cobyla) on ' &
                                //'problems solved by it and one NLopt method:'
      ratios = [real(dp) ::]
      do k = 1, np
        if (.not. solved(k, i) .or. .not. any(solved(k, 3:4))) cycle
        ratio = real(nf(k, i), dp)/minval(real(nf(k, 3:4), dp), mask=solved(k, 3:4))
        ratios = [ratios, ratio]
        write(output_unit, '(a,a14,f8.3)') '#   ', names(k), ratio
      end do
      write(output_unit, '(a,f8.3,a,i4,a)') '# median of that ratio ('//trim(merge('defaults      ', &
        'hessian = bfgs', i == 1))//'): ', median(ratios), ' (', size(ratios), ' problems)'
    end do
  end subroutine collection_profile

    !> Problem k of the collection through ours (defaults; hessian = 'bfgs'),
    !> SLSQP and COBYLA.
    subroutine run_solvers(k, name, nf, solved)
      integer, intent(in) :: k
      character(len=*), intent(in) :: name
      integer, intent(out) :: nf(ns)
      logical, intent(out) :: solved(ns)
      class(opt_problem_t), allocatable, target :: prob
      type(hs_problem_t), allocatable, target :: hp
      type(problem_info_t) :: info
      type(gauss_optimizer_t) :: opt
      type(error_t) :: err
      real(dp), allocatable :: x0(:), xs(:), x(:)
      real(dp) :: fs, f, v
      integer :: alg, ires, j
      logical :: found
      do j = 1, ns
        call err%clear()
        if (k <= size(hs_numbers)) then
          allocate(hp)
          call create_hs(hs_numbers(k), hp, x0, xs, fs, found)
          call move_alloc(hp, prob)
        else
          call create_problem(trim(name), prob, info, err)
          x0 = info%x0
          fs = info%f_star
          if (name == 'hs21') x0 = [-1.0_dp, -1.0_dp]
        end if
        x = x0
        if (j <= 2) then
          opt%opts = gauss_options_t()
          if (j == 2) opt%opts%hessian = hessian_bfgs
          call opt%solve(prob, x0, err)
          solved(j) = opt%status == status_converged
          if (allocated(opt%x)) x = opt%x
          f = opt%f
        else
          alg = merge(alg_slsqp, alg_cobyla, j == 3)
          call nlopt_run(prob, alg, x, f, ires, err)
          solved(j) = ires > 0
        end if
        nf(j) = prob%count%analyses + prob%count%fd_analyses
        v = violation(prob, x)
        solved(j) = solved(j) .and. abs(f - fs) <= 1.0e-6_dp*(1.0_dp + abs(fs)) .and. v <= 1.0e-6_dp
        deallocate(prob)
      end do
    end subroutine run_solvers

  !> Median of v (0 for an empty v).
  real(dp) function median(v) result(med)
    real(dp), intent(in) :: v(:)
    real(dp) :: w(size(v)), t
    integer :: i, j
    med = 0.0_dp
    if (size(v) == 0) return
    w = v
    do i = 2, size(w)
      t = w(i)
      j = i - 1
      do while (j >= 1)
        if (w(j) <= t) exit
        w(j + 1) = w(j)
        j = j - 1
      end do
      w(j + 1) = t
    end do
    med = 0.5_dp*(w((size(w) + 1)/2) + w(size(w)/2 + 1))
  end function median

  real(dp) function violation(prob, x) result(v)
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(in) :: x(:)
    real(dp), allocatable :: g(:)
    type(error_t) :: err
    allocate(g(prob%n_constraints()))
    v = 0.0_dp
    if (size(g) == 0) return
    call prob%constraint_values(x, g, err)
    v = max(0.0_dp, maxval([0.0_dp, g(1:prob%m)]), maxval([0.0_dp, abs(g(prob%m + 1:))]))
  end function violation

  !> One problem, one start: our methods, then SLSQP and COBYLA.
  subroutine compare(name, start_label, x0_in, methods)
    character(len=*), intent(in) :: name, start_label
    real(dp), intent(in) :: x0_in(:)
    character(len=*), intent(in) :: methods(:)
    class(opt_problem_t), allocatable, target :: prob
    type(problem_info_t) :: info
    type(error_t) :: err
    real(dp), allocatable :: x0(:), x(:)
    real(dp) :: f
    integer :: k, ires
    logical :: have_ref
    call create_problem(name, prob, info, err)
    if (size(x0_in) > 0) then
      x0 = x0_in
    else
      x0 = info%x0
    end if
    have_ref = info%has_optimum
    if (have_ref) ref_x = info%x_star
    do k = 1, size(methods)
      block
        type(gauss_optimizer_t) :: opt
        call create_problem(name, prob, info, err)
        opt%opts%method = method_from_name(trim(methods(k)))
        opt%opts%globalization = glob_none         ! the papers' methods as printed (their table)
        call err%clear()
        call opt%solve(prob, x0, err)
        if (.not. have_ref .and. opt%status == status_converged) then
          ref_x = opt%x              ! no closed-form optimum: compare with GNLC's
          have_ref = .true.
        end if
        call report(name, start_label, trim(methods(k)), prob, opt%iterations, opt%f, opt%x, have_ref, &
                    merge('converged', 'failed   ', opt%status == status_converged))
      end block
    end do
    call create_problem(name, prob, info, err)
    x = x0
    call nlopt_run(prob, alg_slsqp, x, f, ires, err)
    call report(name, start_label, 'nlopt_slsqp', prob, -1, f, x, have_ref, 'ires='//str(ires))
    call create_problem(name, prob, info, err)
    x = x0
    call nlopt_run(prob, alg_cobyla, x, f, ires, err)
    call report(name, start_label, 'nlopt_cobyla', prob, -1, f, x, have_ref, 'ires='//str(ires))
  end subroutine compare

  subroutine report(name, start_label, solver, prob, ni, f, x, have_ref, status)
    character(len=*), intent(in) :: name, start_label, solver, status
    class(opt_problem_t), intent(inout) :: prob
    integer, intent(in) :: ni
    real(dp), intent(in) :: f, x(:)
    logical, intent(in) :: have_ref
    real(dp), allocatable :: g(:)
    type(error_t) :: err
    real(dp) :: viol, dx
    character(len=8) :: ni_text
    allocate(g(prob%n_constraints()))
    viol = 0.0_dp
    if (size(g) > 0) then
      call prob%constraint_values(x, g, err)
      viol = max(0.0_dp, maxval([0.0_dp, g(1:prob%m)]), maxval([0.0_dp, abs(g(prob%m + 1:))]))
    end if
    dx = -1.0_dp
    if (have_ref) dx = maxval(abs(x - ref_x))
    ni_text = '     -'
    if (ni >= 0) write(ni_text, '(i6)') ni
    write(output_unit, '(a24,1x,a14,1x,a17,3i6,a6,es18.9,2es10.2,2x,a)') name, start_label, solver, &
      prob%count%analyses, prob%count%gradients, prob%count%fd_analyses, ni_text, f, dx, viol, status
  end subroutine report
end program bench_optimizers
