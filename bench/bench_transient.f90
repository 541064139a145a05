!> Work-precision study of the transient analysis (issue 3): the §8.1
!> four-bar at 150 rad/s with stiffness-proportional damping beta = 1e-5 s,
!> started from the rigid state and run for five crank revolutions; the
!> figure of merit is the peak |stress| in the coupler during the fifth turn
!> (past the start-up: the per-turn peak changes by 3e-5 from the fifth to
!> the fourteenth), against CPU seconds per crank revolution.
!>
!>   1. cost of one right-hand side (assembly + banded Cholesky), of one
!>      banded Newton matrix (M and K_t assembled, S factored) and of one
!>      dense BDF Jacobian (dense M^-1 K_t) against the number of elements;
!>   2. CPU per crank turn against elements per link 1 ... 32 (bdf, rtol
!>      1e-4): DLSODE's Newton matrix through the model's banded elimination
!>      (now) and DLSODE's dense 2N x 2N P (before, `structured = .false.`);
!>   3. the terms the analytic Jacobian leaves out (inertial stiffness,
!>      gyroscopic, damping rotation): bdf against bdf_fd (the exact Jacobian
!>      by differences), corrector iterations per step;
!>   4. elements per link 1, 2, 4, 8, 16 x rtol 1e-3 ... 1e-10 x method
!>      adams (MF 10) / bdf (MF 21); error against the finest, tightest run;
!>      each run stops when it exceeds a CPU budget;
!>   5. the effect of the absolute tolerance on the rates.
!>
!>   6. (`bench_transient output`) the cost of writing and of the optional
!>      columns: the damped four-bar deck through the whole analysis, output
!>      every 0.5 deg, rows all / last revolution / none, 16 or 8 digits.
!>
!>   7. (`bench_transient settings`) the cheapest setting that keeps the peak
!>      within 1 % of the converged value, at 2 and 8 elements per link, with
!>      the rate tolerance of the study and a looser one.
!>
!> `bench_transient scaling` runs 2, 7 and 3 only, `bench_transient cost` 1 only,
!> `bench_transient output` 6 only, `bench_transient settings` 7 only.
!>
!> Tables go to standard output (make bench keeps them in
!> build/bench/bench_transient.txt); data files for doc/figures/*.gp go to
!> build/bench/transient_*.dat.  A benchmark: figures, not pass/fail.
module bench_transient_cases
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use element_effects, only: element_effects_t
  use planar_element, only: stress_report_t
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_adams, mf_bdf_full_user
  implicit none
  private
  public :: case_result_t, run_case, rhs_cost, jacobian_cost, newton_matrix_cost, fourbar

  real(dp), parameter :: crank_speed = 150.0_dp, beta = 1.0e-5_dp
  integer, parameter :: revolutions = 5

  type :: case_result_t
    logical :: finished = .false.
    character(len=80) :: why = ''
    real(dp) :: peak = 0.0_dp              !< peak |stress| in the coupler, fifth turn (psi)
    real(dp) :: cpu_per_rev = 0.0_dp       !< CPU seconds per crank revolution (whole run / turns done)
    real(dp) :: steps_per_rev = 0.0_dp, rhs_per_rev = 0.0_dp, jac_per_rev = 0.0_dp
    real(dp) :: turns = 0.0_dp
    integer :: n_state = 0                 !< 2N, for the difference columns of bdf_fd
  end type case_result_t

contains

  !> The §8.1 four-bar with n elements per link.  The rocker runs from D to
  !> C as in the decks (FORMULATION.md §8.1), or from C to D with `chain`
  !> (links end to end A-B-C-D: the same mechanism, other unknown numbering).
  function fourbar(n, chain) result(inp)
    integer, intent(in) :: n
    logical, intent(in), optional :: chain
    type(mechanism_input_t) :: inp
    inp%n_joints = 4
    inp%joint_name(1:4) = [character(len=16) :: 'A', 'B', 'C', 'D']
    inp%joint_type(1:4) = [character(len=16) :: 'clamp', 'pin', 'pin', 'ground_pin']
    inp%joint_x(1) = 0.0_dp
    inp%joint_y(1) = 0.0_dp
    inp%joint_x(4) = 10.0_dp
    inp%joint_y(4) = 0.0_dp
    inp%n_links = 3
    inp%link_joint1(1:3) = [1, 2, 4]
    inp%link_joint2(1:3) = [2, 3, 3]
    inp%link_length(1:3) = [5.0_dp, 11.0_dp, 10.5_dp]
    inp%link_n_elements(1:3) = n
    inp%omega = crank_speed
    if (present(chain)) then
      if (chain) then
        inp%link_joint1(3) = 3
        inp%link_joint2(3) = 4
      end if
    end if
  end function fourbar

  subroutine make(n, effects, model, err, chain)
    integer, intent(in) :: n
    type(element_effects_t), intent(in) :: effects
    type(mechanism_model_t), intent(inout) :: model
    type(error_t), intent(inout) :: err
    logical, intent(in), optional :: chain
    type(mechanism_t) :: mech
    call build_mechanism(fourbar(n, chain), mech, err)
    if (err%failed()) return
    call model%init_mechanism(mech, effects, 'exact', beta, err, table_points=720)
  end subroutine make

  !> One run: n elements per link, method mf, relative tolerance rtol;
  !> absolute tolerances atol_q = 1e-3 rtol (in) on displacements and
  !> atol_qd = rate_scale * rtol (in/s) on rates.  Stops when the CPU time
  !> spent in DLSODE (right-hand sides and Jacobians included; the sampling
  !> below is not) exceeds `budget` seconds.  Output every degree in the
  !> first four turns, every quarter degree in the fifth; the peak |stress|
  !> over the coupler's elements in the fifth turn is the largest sample,
  !> refined by a parabola through it and its neighbours (the peak is a smooth
  !> maximum about 2 degrees wide: quarter-degree samples leave < 1e-4).
  !> `dense`: DLSODE's dense P from the model's dense Jacobian (the route
  !> before the banded Newton matrix).
  function run_case(n, mf, rtol, effects, budget, rate_scale, dense) result(res)
    integer, intent(in) :: n, mf
    real(dp), intent(in) :: rtol, budget, rate_scale
    type(element_effects_t), intent(in) :: effects
    logical, intent(in), optional :: dense
    type(case_result_t) :: res
    logical :: structured
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    type(lsode_counters_t) :: c
    type(stress_report_t), allocatable :: rep(:)
    real(dp), allocatable :: y(:), atol(:)
    real(dp) :: deg, t, s, s_prev, s_prev2, best
    integer :: k, n_out, ml, first, last, per_degree, k5
    call make(n, effects, model, err)
    if (err%failed()) then
      res%why = err%text()
      return
    end if
    allocate(y(model%state_size()), atol(model%state_size()), rep(size(model%el)))
    y = 0.0_dp
    atol(1::2) = 1.0e-3_dp*rtol
    atol(2::2) = rate_scale*rtol
    ml = min(2*model%kd + 1, size(y) - 1)
    structured = .true.
    if (present(dense)) structured = .not. dense
    res%n_state = size(y)
    call ode%init(size(y), 0.0_dp, mf, rtol, atol, err, ml=ml, mu=ml, max_steps=200000, structured=structured)
    first = model%table%first_element(2)
    last = model%table%first_element(3) - 1
    deg = pi/180.0_dp/crank_speed
    per_degree = 4
    n_out = 360*(revolutions - 1) + 360*per_degree
    best = 0.0_dp
    s_prev = 0.0_dp
    s_prev2 = 0.0_dp
    do k = 1, n_out
      k5 = k - 360*(revolutions - 1)                  ! > 0 in the fifth turn
      if (k5 <= 0) then
        t = k*deg
      else
        t = (360*(revolutions - 1) + real(k5, dp)/per_degree)*deg
      end if
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) then
        res%why = err%text()
        exit
      end if
      c = ode%counters()
      if (c%cpu_seconds > budget) then
        res%why = 'over the CPU budget'
        exit
      end if
      if (k5 >= 0) then
        call model%set_time(t)
        call model%element_stresses(y(1::2), rep)
        s = maxval(rep(first:last)%max_abs_stress)
        if (k5 >= 2 .and. s_prev >= s_prev2 .and. s_prev >= s) best = max(best, parabola_max(s_prev2, s_prev, s))
        best = max(best, s)
        s_prev2 = s_prev
        s_prev = s
      end if
    end do
    c = ode%counters()
    res%turns = ode%t*crank_speed/two_pi
    if (res%turns > 0.0_dp) then
      res%cpu_per_rev = c%cpu_seconds/res%turns
      res%steps_per_rev = c%steps/res%turns
      res%rhs_per_rev = c%rhs_evals/res%turns
      res%jac_per_rev = c%jac_evals/res%turns
    end if
    res%finished = .not. err%failed() .and. k > n_out
    res%peak = best
  end function run_case

  pure real(dp) function parabola_max(a, b, c) result(m)
    real(dp), intent(in) :: a, b, c
    real(dp) :: d
    d = a - 2.0_dp*b + c
    if (d < 0.0_dp) then
      m = b - 0.125_dp*(c - a)**2/d
    else
      m = b
    end if
  end function parabola_max

  !> CPU microseconds per right-hand side at a deformed state (n elements
  !> per link, 3n elements), averaged over enough calls to take ~0.2 s.
  real(dp) function rhs_cost(n, effects, chain, n_unknowns, half_bandwidth) result(us)
    integer, intent(in) :: n
    type(element_effects_t), intent(in) :: effects
    logical, intent(in) :: chain
    integer, intent(out) :: n_unknowns, half_bandwidth
    type(mechanism_model_t), target :: model
    type(error_t) :: err
    real(dp), allocatable :: y(:), f(:)
    real(dp) :: cpu0, cpu1, t
    integer :: k, calls
    call make(n, effects, model, err, chain)
    n_unknowns = model%n
    half_bandwidth = model%kd
    allocate(y(model%state_size()), f(model%state_size()))
    ! a smooth deformed state: small elastic rates and displacements
    call random_number(y)
    y = 1.0e-7_dp*(y - 0.5_dp)
    calls = 0
    call cpu_time(cpu0)
    do
      do k = 1, 100
        t = 1.0e-5_dp*(calls + k)          ! a new time each call: the rigid motion is interpolated too
        call model%rhs(t, y, f)
      end do
      calls = calls + 100
      call cpu_time(cpu1)
      if (cpu1 - cpu0 > 0.2_dp) exit
    end do
    us = 1.0e6_dp*(cpu1 - cpu0)/calls
    if (model%err%failed()) us = -1.0_dp       ! the model stopped: not a cost
  end function rhs_cost

  !> CPU microseconds per banded Newton matrix (model%newton_factor: M and
  !> K_t assembled in band storage, S = M + c K_t factored).
  real(dp) function newton_matrix_cost(n) result(us)
    integer, intent(in) :: n
    type(mechanism_model_t), target :: model
    type(error_t) :: err
    real(dp), allocatable :: y(:)
    real(dp) :: cpu0, cpu1
    integer :: calls
    logical :: ok
    call make(n, element_effects_t(), model, err)
    allocate(y(model%state_size()))
    y = 0.0_dp
    calls = 0
    call cpu_time(cpu0)
    do
      call model%newton_factor(1.0e-3_dp, y, 3.0e-5_dp, ok)
      calls = calls + 1
      call cpu_time(cpu1)
      if (cpu1 - cpu0 > 0.2_dp) exit
    end do
    us = 1.0e6_dp*(cpu1 - cpu0)/calls
  end function newton_matrix_cost

  !> CPU microseconds per dense BDF Jacobian (model%jacobian, full storage;
  !> DLSODE's dense route then also factors the 2N x 2N P).
  real(dp) function jacobian_cost(n) result(us)
    integer, intent(in) :: n
    type(mechanism_model_t), target :: model
    type(error_t) :: err
    real(dp), allocatable :: y(:), pd(:, :)
    real(dp) :: cpu0, cpu1
    integer :: calls
    call make(n, element_effects_t(), model, err)
    allocate(y(model%state_size()), pd(model%state_size(), model%state_size()))
    y = 0.0_dp
    calls = 0
    call cpu_time(cpu0)
    do
      pd = 0.0_dp
      call model%jacobian(1.0e-3_dp, y, 0, 0, pd)
      calls = calls + 1
      call cpu_time(cpu1)
      if (cpu1 - cpu0 > 0.2_dp) exit
    end do
    us = 1.0e6_dp*(cpu1 - cpu0)/calls
  end function jacobian_cost
end module bench_transient_cases

program bench_transient
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use transient_analysis, only: run_transient
  use element_effects, only: element_effects_t
  use lsode_solver, only: mf_adams, mf_bdf_full_user, mf_bdf_full_fd
  use bench_transient_cases
  implicit none
  integer, parameter :: ns(5) = [1, 2, 4, 8, 16], ns_cost(6) = [1, 2, 4, 8, 16, 32]
  real(dp), parameter :: rate_atols(4) = [1.0e-3_dp, 1.0e0_dp, 1.0e3_dp, 1.0e6_dp]
  integer, parameter :: mfs(3) = [mf_adams, mf_bdf_full_user, mf_bdf_full_fd]
  character(len=8), parameter :: method_names(3) = [character(len=8) :: 'adams', 'bdf', 'bdf_fd']
  real(dp), parameter :: budget = 60.0_dp          ! CPU seconds per run
  real(dp), parameter :: rate_scale = 1.0_dp       ! atol on rates = rate_scale * rtol (in/s)
  real(dp), parameter :: scaled_rate_scale = 1.0e4_dp   ! the looser rate floor of the 1 % setting
  type(element_effects_t) :: linear
  type(case_result_t) :: ref, r
  real(dp) :: rtol, us, err_rel
  integer :: i, j, k, u
  character(len=32) :: arg
  character(len=*), parameter :: data_dir = 'build/bench/'
  logical :: skip

  linear = element_effects_t()
  ! `bench_transient probe N METHOD RTOL [all|dense] [RATE_SCALE]`: one run, for profiling
  if (command_argument_count() >= 4) then
    call get_command_argument(2, arg)
    read(arg, *) i
    call get_command_argument(3, arg)
    k = findloc(method_names, trim(arg), dim=1)
    call get_command_argument(4, arg)
    read(arg, *) rtol
    us = rate_scale
    skip = .false.
    do j = 5, command_argument_count()
      call get_command_argument(j, arg)
      if (trim(arg) == 'all') then
        linear = element_effects_t(.true., .true., .true., .true., .true.)
      else if (trim(arg) == 'dense') then
        skip = .true.
      else
        read(arg, *) us
      end if
    end do
    r = run_case(i, mfs(k), rtol, linear, 3600.0_dp, us, dense=skip)
    print '(a,l2,1x,a,f0.4,a,f0.3,a,f0.0,a,f0.0,a,f0.0)', 'finished', r%finished, trim(r%why)//' peak ', r%peak, &
      ' CPU ms/turn ', 1.0e3_dp*r%cpu_per_rev, ' steps/turn ', r%steps_per_rev, ' RHS/turn ', r%rhs_per_rev, &
      ' Jac/turn ', r%jac_per_rev
    stop
  end if
  call execute_command_line('mkdir -p '//data_dir)
  arg = ''
  if (command_argument_count() == 1) call get_command_argument(1, arg)

  ! ---- 1. cost per right-hand side and per Jacobian against the number of elements
  if (trim(arg) == 'output') then
    call output_costs(data_dir)
    stop
  end if
  if (trim(arg) == 'settings') then
    call cheapest_settings()
    stop
  end if
  if (trim(arg) /= 'scaling') call cost_tables(data_dir)
  if (trim(arg) == 'cost') stop      ! `bench_transient cost`: the cost tables only

  ! ---- 2. and 3. cost per turn against the mesh; the terms left out of the Jacobian
  call scaling_table(data_dir)
  call cheapest_settings()
  if (trim(arg) == 'settings') stop
  call left_out_terms()
  if (trim(arg) == 'scaling') stop

  ! ---- 2. work-precision
  print '(a)', '## Work-precision: peak coupler stress in the fifth turn, 150 rad/s, beta = 1e-5 s, linear model'
  print '(a)', ''
  ! reference: the finest mesh at a tight tolerance (16 elements per link, bdf, rtol 1e-9)
  ref = run_case(16, mf_bdf_full_user, 1.0e-9_dp, linear, 7200.0_dp, rate_scale)
  if (.not. ref%finished) then
    print '(a)', 'reference run (16 elements per link, bdf, rtol 1e-9) did not finish: '//trim(ref%why)
    ref = run_case(8, mf_bdf_full_user, 1.0e-10_dp, linear, 7200.0_dp, rate_scale)
    print '(a)', 'reference taken from 8 elements per link, rtol 1e-10, instead'
  end if
  print '(a,f0.4,a,f0.3,a)', 'reference: peak coupler stress ', ref%peak, ' psi (', ref%cpu_per_rev, &
    ' CPU s per turn; 16 elements per link, bdf, rtol 1e-9)'
  print '(a)', ''
  print '(a)', '| method | n per link | rtol | peak (psi) | rel. error | CPU ms/turn | steps/turn | RHS/turn | Jac/turn |'
  print '(a)', '|---|---|---|---|---|---|---|---|---|'
  open(newunit=u, file=data_dir//'transient_work_precision.dat', status='replace')
  write(u, '(a)') '# method n_per_link rtol peak rel_error cpu_ms_per_turn steps_per_turn rhs_per_turn jac_per_turn finished'
  do k = 1, 2
    write(u, '(a)') ''
    write(u, '(a)') ''
    write(u, '(a)') '# method '//trim(method_names(k))
    do i = 1, size(ns)
      skip = .false.
      do j = 3, 10
        rtol = 10.0_dp**(-j)
        if (skip) then
          print '(a,a,a,i0,a,es7.0,a)', '| ', trim(method_names(k)), ' | ', ns(i), ' | ', rtol, &
            ' | - | - | (skipped: a looser tolerance was over budget) | | | |'
          cycle
        end if
        r = run_case(ns(i), mfs(k), rtol, linear, budget, rate_scale)
        if (.not. r%finished) then
          print '(a,a,a,i0,a,es7.0,a,a,a,f0.2,a)', '| ', trim(method_names(k)), ' | ', ns(i), ' | ', rtol, &
            ' | - | - | stopped: ', trim(r%why), ' after ', r%turns, ' turns | | | |'
          skip = .true.
          cycle
        end if
        err_rel = abs(r%peak - ref%peak)/ref%peak
        print '(a,a,a,i0,a,es7.0,a,f0.3,a,es9.2,a,f0.2,a,f0.0,a,f0.0,a,f0.0,a)', '| ', trim(method_names(k)), ' | ', &
          ns(i), ' | ', rtol, ' | ', r%peak, ' | ', err_rel, ' | ', 1.0e3_dp*r%cpu_per_rev, ' | ', r%steps_per_rev, &
          ' | ', r%rhs_per_rev, ' | ', r%jac_per_rev, ' |'
        write(u, '(a10,i4,es10.2,f14.4,es12.4,4es13.5,l3)') trim(method_names(k)), ns(i), rtol, r%peak, err_rel, &
          1.0e3_dp*r%cpu_per_rev, r%steps_per_rev, r%rhs_per_rev, r%jac_per_rev, r%finished
      end do
    end do
  end do
  close(u)
  print '(a)', ''

  ! ---- 3. the rate tolerance
  print '(a)', '## Absolute tolerance on the rates (bdf, 1 element per link, rtol 1e-6; atol on displacements 1e-9 in)'
  print '(a)', ''
  print '(a)', '| atol on rates (in/s) | peak (psi) | CPU ms/turn | steps/turn |'
  print '(a)', '|---|---|---|---|'
  do i = 1, size(rate_atols)
    us = rate_atols(i)
    r = run_case(1, mf_bdf_full_user, 1.0e-6_dp, linear, budget, us)
    print '(a,es8.1,a,f0.3,a,f0.2,a,f0.0,a)', '| ', us*1.0e-6_dp, ' | ', r%peak, ' | ', 1.0e3_dp*r%cpu_per_rev, ' | ', &
      r%steps_per_rev, ' |'
  end do
contains

  !> CPU per crank turn, bdf, rtol 1e-4, linear model, elements per link 1 ... 32:
  !> the banded Newton matrix (now) and DLSODE's dense P (before; over the
  !> budget the figure is from the turns done).
  subroutine scaling_table(dir)
    character(len=*), intent(in) :: dir
    type(case_result_t) :: now, before, scaled
    integer :: ii, uu
    real(dp) :: prev, prev_scaled
    print '(a)', '## CPU per crank turn against the mesh (bdf, rtol 1e-4, 150 rad/s, beta = 1e-5 s, linear)'
    print '(a)', ''
    print '(a)', '| n per link | unknowns 2N | banded S: ms/turn | ratio to n/2 | steps/turn | RHS/turn | Jac/turn | '// &
                 'peak (psi) | dense P (before): ms/turn | turns done | atol_rate 1e4 rtol: ms/turn | ratio | '// &
                 'steps/turn | peak (psi) |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|---|---|'
    open(newunit=uu, file=dir//'transient_scaling.dat', status='replace')
    write(uu, '(a)') '# n_per_link state_size banded_ms_per_turn dense_ms_per_turn banded_scaled_atol_ms_per_turn'
    prev = 0.0_dp
    prev_scaled = 0.0_dp
    do ii = 1, size(ns_cost)
      now = run_case(ns_cost(ii), mf_bdf_full_user, 1.0e-4_dp, element_effects_t(), budget, rate_scale)
      before = run_case(ns_cost(ii), mf_bdf_full_user, 1.0e-4_dp, element_effects_t(), budget, rate_scale, dense=.true.)
      scaled = run_case(ns_cost(ii), mf_bdf_full_user, 1.0e-4_dp, element_effects_t(), budget, scaled_rate_scale)
      print '(a,i0,a,i0,a,f0.2,a,f0.2,a,f0.0,a,f0.0,a,f0.0,a,f0.2,a,f0.1,a,f0.2,a,f0.2,a,f0.2,a,f0.0,a,f0.2,a)', '| ', &
        ns_cost(ii), ' | ', now%n_state, ' | ', 1.0e3_dp*now%cpu_per_rev, ' | ', &
        merge(now%cpu_per_rev/max(prev, tiny(1.0_dp)), 0.0_dp, prev > 0.0_dp), ' | ', now%steps_per_rev, ' | ', &
        now%rhs_per_rev, ' | ', now%jac_per_rev, ' | ', now%peak, ' | ', 1.0e3_dp*before%cpu_per_rev, ' | ', &
        before%turns, ' | ', 1.0e3_dp*scaled%cpu_per_rev, ' | ', &
        merge(scaled%cpu_per_rev/max(prev_scaled, tiny(1.0_dp)), 0.0_dp, prev_scaled > 0.0_dp), ' | ', &
        scaled%steps_per_rev, ' | ', scaled%peak, ' |'
      write(uu, '(i4,i6,3es14.5)') ns_cost(ii), now%n_state, 1.0e3_dp*now%cpu_per_rev, 1.0e3_dp*before%cpu_per_rev, &
        1.0e3_dp*scaled%cpu_per_rev
      prev = now%cpu_per_rev
      prev_scaled = scaled%cpu_per_rev
    end do
    close(uu)
    print '(a)', ''
  end subroutine scaling_table

  !> The issue's 1 % targets: the peak coupler stress within 1 % of the
  !> mesh-converged 17,965 psi at the least CPU.  Two and eight elements per
  !> link, bdf, rtol 1e-4 ... 1e-3, the absolute tolerance on the rates
  !> 1 rtol in/s (the work-precision study's) or 1e4 rtol in/s (the rates
  !> then enter the error test relatively: their absolute floor no longer
  !> makes DLSODE follow the velocities of lightly damped high modes).  Each
  !> run three times on the shared machine: best and worst CPU per turn.
  subroutine cheapest_settings()
    real(dp), parameter :: converged = 17965.0_dp, rtols(4) = [1.0e-4_dp, 3.0e-4_dp, 5.0e-4_dp, 1.0e-3_dp]
    real(dp), parameter :: scales(2) = [1.0_dp, scaled_rate_scale]
    integer, parameter :: meshes(2) = [2, 8]
    type(case_result_t) :: rr
    real(dp) :: lo, hi
    integer :: im, ir, is, rep
    print '(a)', '## The 1 % setting: peak coupler stress within 1 % of 17,965 psi (bdf, linear, 150 rad/s)'
    print '(a)', ''
    print '(a)', '| n per link | rtol | atol_rate (in/s) | peak (psi) | error | CPU ms/turn best | worst (3 runs) | '// &
                 'steps/turn | RHS/turn | Jac/turn |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|'
    do im = 1, size(meshes)
      do is = 1, size(scales)
        do ir = 1, size(rtols)
          lo = huge(1.0_dp)
          hi = 0.0_dp
          do rep = 1, 3
            rr = run_case(meshes(im), mf_bdf_full_user, rtols(ir), element_effects_t(), budget, scales(is))
            lo = min(lo, rr%cpu_per_rev)
            hi = max(hi, rr%cpu_per_rev)
          end do
          print '(a,i0,a,es7.0,a,es7.0,a,f0.1,a,sp,f0.2,ss,a,f0.2,a,f0.2,a,f0.0,a,f0.0,a,f0.0,a)', '| ', meshes(im), &
            ' | ', rtols(ir), ' | ', scales(is)*rtols(ir), ' | ', rr%peak, ' | ', 1.0e2_dp*(rr%peak/converged - 1.0_dp), &
            ' % | ', 1.0e3_dp*lo, ' | ', 1.0e3_dp*hi, ' | ', rr%steps_per_rev, ' | ', rr%rhs_per_rev, ' | ', &
            rr%jac_per_rev, ' |'
        end do
      end do
    end do
    print '(a)', ''
  end subroutine cheapest_settings

  !> bdf (analytic Jacobian without inertial stiffness, gyroscopic and
  !> damping-rotation terms) against bdf_fd (the exact Jacobian by forward
  !> differences): corrector iterations per step = (RHS - 2N per Jacobian for
  !> the differences) / steps.  Equal counts mean the left-out terms do not
  !> slow the chord iteration.
  subroutine left_out_terms()
    type(case_result_t) :: a, f
    type(element_effects_t) :: fx(2)
    character(len=24) :: fx_name(2) = [character(len=24) :: 'linear', 'geometric + inertia']
    integer :: ii, jj, nn
    real(dp) :: rtol
    fx(1) = element_effects_t()
    fx(2) = element_effects_t(stretching=.true., curvature=.true., rotary_inertia=.true., coupling=.true.)
    print '(a)', '## Terms left out of the analytic Jacobian: bdf (approximate J) against bdf_fd (exact J by differences)'
    print '(a)', ''
    print '(a)', '| effects | n per link | rtol | bdf steps/turn | bdf iterations/step | bdf_fd steps/turn | '// &
                 'bdf_fd iterations/step | peak bdf | peak bdf_fd |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|'
    do jj = 1, 2
      do ii = 1, 2
        nn = ii
        rtol = 1.0e-4_dp
        a = run_case(nn, mf_bdf_full_user, rtol, fx(jj), budget, rate_scale)
        f = run_case(nn, mf_bdf_full_fd, rtol, fx(jj), budget, rate_scale)
        print '(a,a,a,i0,a,es7.0,a,f0.0,a,f0.3,a,f0.0,a,f0.3,a,f0.3,a,f0.3,a)', '| ', trim(fx_name(jj)), ' | ', nn, &
          ' | ', rtol, ' | ', a%steps_per_rev, ' | ', a%rhs_per_rev/max(a%steps_per_rev, 1.0_dp), ' | ', &
          f%steps_per_rev, ' | ', (f%rhs_per_rev - f%n_state*f%jac_per_rev)/max(f%steps_per_rev, 1.0_dp), ' | ', &
          a%peak, ' | ', f%peak, ' |'
      end do
    end do
    print '(a)', ''
  end subroutine left_out_terms

  !> RHS and Jacobian cost against elements: the rocker numbered from D (the
  !> decks) and from C (a chain A-B-C-D), linear and all effects on.
  subroutine cost_tables(dir)
    character(len=*), intent(in) :: dir
    type(element_effects_t) :: full
    real(dp) :: lin_dc, lin_cd, full_cd, jac, newton
    integer :: kd_dc, kd_cd, nu, ii, jj, uu
    full = element_effects_t(.true., .true., .true., .true., .true.)
    print '(a)', '## Cost per right-hand side and per BDF Jacobian (four-bar, 3n elements)'
    print '(a)', ''
    print '(a)', 'RHS = element evaluations, assembly of M (band) and F, banded Cholesky of M, solve.  kd = half-bandwidth of M.'
    print '(a)', 'Rocker D->C: as in the decks; C->D: links numbered end to end (A-B-C-D), same mechanism.'
    print '(a)', ''
    print '(a)', '| n per link | elements | unknowns | kd (D->C) | RHS linear D->C (us) | kd (C->D) | RHS linear C->D (us) | '// &
                 'per element | RHS all effects C->D (us) | per element | dense Jacobian (us) | banded Newton matrix (us) |'
    print '(a)', '|---|---|---|---|---|---|---|---|---|---|---|---|'
    open(newunit=uu, file=dir//'transient_rhs_cost.dat', status='replace')
    write(uu, '(a)') '# n_per_link elements unknowns kd_dc rhs_linear_dc_us kd_cd rhs_linear_cd_us rhs_all_cd_us jacobian_us '// &
                     'newton_matrix_us'
    do ii = 1, size(ns_cost)
      jj = ns_cost(ii)
      lin_dc = rhs_cost(jj, element_effects_t(), .false., nu, kd_dc)
      lin_cd = rhs_cost(jj, element_effects_t(), .true., nu, kd_cd)
      full_cd = rhs_cost(jj, full, .true., nu, kd_cd)
      jac = -1.0_dp
      if (jj <= 16) jac = jacobian_cost(jj)
      newton = newton_matrix_cost(jj)
      print '(a,i0,a,i0,a,i0,a,i0,a,f0.2,a,i0,a,f0.2,a,f0.3,a,f0.2,a,f0.3,a,f0.1,a,f0.2,a)', '| ', jj, ' | ', 3*jj, ' | ', &
        nu, ' | ', kd_dc, ' | ', lin_dc, ' | ', kd_cd, ' | ', lin_cd, ' | ', lin_cd/(3*jj), ' | ', full_cd, ' | ', &
        full_cd/(3*jj), ' | ', jac, ' | ', newton, ' |'
      write(uu, '(i4,i6,i6,i5,es14.5,i5,4es14.5)') jj, 3*jj, nu, kd_dc, lin_dc, kd_cd, lin_cd, full_cd, jac, newton
    end do
    close(uu)
    print '(a)', ''
  end subroutine cost_tables
  !> Whole-analysis CPU (best of three; the deck read and the header are
  !> included) of the damped four-bar, five turns, output every 0.5 deg
  !> (3,601 output times): how much of a cheap run the rows and the optional
  !> columns cost.
  subroutine output_costs(dir)
    character(len=*), intent(in) :: dir
    character(len=*), parameter :: mech = &
      "&run|  analysis = 'transient'|/|&mechanism|  n_joints = 4|  joint_name = 'A', 'B', 'C', 'D'|"// &
      "  joint_type = 'clamp', 'pin', 'pin', 'ground_pin'|  joint_x(1) = 0.0, joint_y(1) = 0.0|"// &
      "  joint_x(4) = 10.0, joint_y(4) = 0.0|  n_links = 3|  link_name = 'crank', 'coupler', 'rocker'|"// &
      "  link_joint1 = 1, 2, 4|  link_joint2 = 2, 3, 3|  link_length = 5.0, 11.0, 10.5|  link_n_elements = 3*1|"// &
      "  driver_link = 1|  omega = 150.0|/|&transient|  method = 'bdf', rtol = 1.0e-7, atol = 1.0e-11, "// &
      "revolutions = 5, output_step_deg = 0.5, damping_beta = 1.0e-5|"
    character(len=96), parameter :: variants(10) = [character(len=96) :: &
      "output_rows = 'all'", "output_rows = 'all', output_digits = 8", &
      "output_rows = 'last_revolution'", "output_rows = 'last_revolution', output_digits = 8", &
      "output_rows = 'none'", "output_rows = 'none', stress_columns = 'all'", &
      "output_rows = 'none', link_points = T", "output_rows = 'none', reactions = T", &
      "output_rows = 'all', stress_columns = 'all', link_points = T, reactions = T", &
      "output_rows = 'all', stress_columns = 'all', link_points = T, reactions = T, output_digits = 8"]
    integer :: v, k
    real(dp) :: best, cpu
    print '(a)', '## Output cost: damped four-bar, 5 turns, output every 0.5 deg (3,601 output times)'
    print '(a)', ''
    print '(a)', '| &transient | CPU s (best of 3) |'
    print '(a)', '|---|---|'
    do v = 1, size(variants)
      best = huge(1.0_dp)
      do k = 1, 3
        cpu = deck_cpu(dir, mech//'  '//trim(variants(v))//'|/|')
        best = min(best, cpu)
      end do
      print '(a,a,a,f0.4,a)', '| ', trim(variants(v)), ' | ', best, ' |'
    end do
    print '(a)', ''
  end subroutine output_costs

  !> CPU seconds of one transient analysis of the deck text ('|' separates lines).
  real(dp) function deck_cpu(dir, text) result(cpu)
    character(len=*), intent(in) :: dir, text
    type(deck_t) :: deck
    type(table_t) :: out
    type(error_t) :: err
    real(dp) :: c0, c1
    integer :: u, i0, i
    open(newunit=u, file=dir//'bench_output.nml', status='replace', action='write')
    i0 = 1
    do i = 1, len(text)
      if (text(i:i) == '|') then
        write(u, '(a)') text(i0:i - 1)
        i0 = i + 1
      end if
    end do
    close(u)
    call cpu_time(c0)
    call deck%open(dir//'bench_output.nml', err)
    call out%open(dir//'bench_output.out', err)
    if (.not. err%failed()) call run_transient(deck, out, err)
    call deck%close()
    call out%commit(err)
    call cpu_time(c1)
    cpu = c1 - c0
    if (err%failed()) print '(a)', 'run failed: '//err%text()
  end function deck_cpu
end program bench_transient
