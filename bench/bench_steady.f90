!> Steady-state benchmark (doc/steady_state.md §7-8): Tennant's four-bar,
!> one element per link.
!>
!>   A. CPU of one steady state by the harmonic series, linear 8-DOF to full
!>      nonlinear 14-DOF (the 1985 code needed hours; target: full nonlinear
!>      in at most 1 ms).
!>   B. Harmonic series N = 2 ... 32 against the exact periodic solution:
!>      error against CPU time, at 100 and 150 rad/s.
!>   C. The legacy answer against the exact one as the crank speed rises.
!>   D. How the exact periodic solution depends on damping, on the
!>      integrator and on its tolerance (the step size).
!>
!> Prints tables; never passes or fails.
program bench_steady
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use harmonic_solver, only: harmonic_settings_t, harmonic_report_t, harmonic_solve
  use periodic_shooting, only: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit
  implicit none

  integer, parameter :: n_out = 72

  call part_a()
  call part_b(100.0_dp)
  call part_b(150.0_dp)
  call part_c()
  call part_d()

contains

  subroutine four_bar(w, opt, model)
    real(dp), intent(in) :: w
    type(tennant_options_t), intent(in) :: opt
    type(steady_model_t), intent(out) :: model
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(link_sections_t) :: secs(3)
    type(error_t) :: err
    inp%n_joints = 4
    inp%joint_type(1:4) = [character(len=16) :: 'clamp', 'pin', 'pin', 'ground_pin']
    inp%joint_x(1) = 0.0_dp
    inp%joint_y(1) = 0.0_dp
    inp%joint_x(4) = 10.0_dp
    inp%joint_y(4) = 0.0_dp
    inp%n_links = 3
    inp%link_joint1(1:3) = [1, 2, 4]
    inp%link_joint2(1:3) = [2, 3, 3]
    inp%link_length(1:3) = [5.0_dp, 11.0_dp, 10.5_dp]
    inp%omega = w
    call build_mechanism(inp, mech, err)
    call model%init_mechanism(mech, opt, secs, err)
    if (err%failed()) error stop 'bench_steady: model'
  end subroutine four_bar

  function grid(w, n) result(t)
    real(dp), intent(in) :: w
    integer, intent(in) :: n
    real(dp) :: t(n)
    integer :: j
    do j = 1, n
      t(j) = (j - 1)*(two_pi/n)/w
    end do
  end function grid

  !> n_out + 1 times over one revolution, both ends included.
  function revolution(w) result(t)
    real(dp), intent(in) :: w
    real(dp) :: t(n_out + 1)
    integer :: j
    do j = 0, n_out
      t(j + 1) = j*(two_pi/n_out)/w
    end do
  end function revolution

  !> Smallest CPU time of `reps` solves, each on a freshly built model (cold
  !> kinematics cache; construction not timed).
  subroutine time_harmonic(w, opt, nh, n_times, reps, cpu, rep)
    real(dp), intent(in) :: w
    type(tennant_options_t), intent(in) :: opt
    integer, intent(in) :: nh, n_times, reps
    real(dp), intent(out) :: cpu
    type(harmonic_report_t), intent(out) :: rep
    type(steady_model_t) :: model
    type(harmonic_settings_t) :: s
    type(error_t) :: err
    real(dp), allocatable :: q(:, :)
    real(dp) :: c0, c1
    integer :: r
    s%n_harmonics = nh
    cpu = huge(1.0_dp)
    do r = 1, reps
      call four_bar(w, opt, model)
      allocate(q(model%n, n_times))
      call cpu_time(c0)
      call harmonic_solve(model, s, grid(w, n_times), q, rep, err)
      call cpu_time(c1)
      cpu = min(cpu, c1 - c0)
      deallocate(q)
    end do
  end subroutine time_harmonic

  subroutine part_a()
    real(dp) :: cpu
    type(harmonic_report_t) :: rep
    integer :: k
    type(tennant_options_t) :: opts(4)
    character(len=48) :: names(4)
    opts(1) = tennant_options_t()
    opts(2) = tennant_options_t(d_k=1.0_dp, d_b=1.0_dp, d_g=1.0_dp)
    opts(3) = tennant_options_t(shear=.true.)
    opts(4) = tennant_options_t(d_k=1.0_dp, d_b=1.0_dp, d_g=1.0_dp, shear=.true.)
    names = [character(len=48) :: '8-DOF slender, linear', '8-DOF slender, full nonlinear', &
             '14-DOF shear angle, linear', '14-DOF shear angle, full nonlinear']
    write(*, '(a)') '== A. CPU of one steady state, four-bar at 150 rad/s (Figs. 5-8), N = 8'
    write(*, '(a)') '   (best of 100 and 20 runs, fresh model each time; 16 = the 2N collocation times, 73 = every 5 deg)'
    write(*, '(a48,2a16,a12,a14)') 'model', 'CPU 16 times', 'CPU 73 times', 'outer it.', 'factorizations'
    do k = 1, 4
      call time_harmonic(150.0_dp, opts(k), 8, 16, 100, cpu, rep)
      write(*, '(a48,es16.3)', advance='no') names(k), cpu
      call time_harmonic(150.0_dp, opts(k), 8, 73, 20, cpu, rep)
      write(*, '(es16.3,i12,i14)') cpu, rep%outer_iterations, rep%factorizations
    end do
    write(*, *)
  end subroutine part_a

  !> The exact periodic solution (BDF, rtol 1e-10) at 72 + 1 times and its CPU.
  subroutine exact_solution(w, beta, q, cpu, rep, rtol, adams)
    real(dp), intent(in) :: w, beta
    real(dp), allocatable, intent(out) :: q(:, :)
    real(dp), intent(out) :: cpu
    type(shooting_report_t), intent(out) :: rep
    real(dp), intent(in), optional :: rtol
    logical, intent(in), optional :: adams
    type(steady_model_t), target :: model
    type(shooting_settings_t) :: s
    type(error_t) :: err
    real(dp), allocatable :: qd(:, :), y0(:)
    real(dp) :: c0, c1
    call four_bar(w, tennant_options_t(damping_beta=beta), model)
    s%rtol = 1.0e-10_dp
    if (present(rtol)) s%rtol = rtol
    s%atol = 1.0e-4_dp*s%rtol
    s%newton_tol = max(1.0e-7_dp, 100.0_dp*s%rtol)
    s%bdf = .true.
    if (present(adams)) s%bdf = .not. adams
    s%singular_rcond = 0.0_dp
    allocate(q(model%n, n_out + 1), qd(model%n, n_out + 1), y0(2*model%n))
    y0 = 0.0_dp
    call cpu_time(c0)
    call shooting_solve(model, s, y0, rep, err)
    if (.not. err%failed()) call periodic_orbit(model, s, y0, revolution(w), &
                                                q, qd, rep, err)
    call cpu_time(c1)
    cpu = c1 - c0
    if (err%failed()) then
      q = huge(1.0_dp)
      write(*, '(a)') '   (exact solution failed: '//err%text()//')'
    end if
  end subroutine exact_solution

  subroutine part_b(w)
    real(dp), intent(in) :: w
    real(dp), allocatable :: qe(:, :), qh(:, :)
    real(dp) :: cpu_e, cpu_h, c0, c1, err_rel
    type(shooting_report_t) :: srep
    type(harmonic_report_t) :: hrep
    type(harmonic_settings_t) :: s
    type(steady_model_t) :: model
    type(error_t) :: err
    integer :: k, r
    integer, parameter :: ns(12) = [2, 3, 4, 6, 8, 10, 12, 14, 16, 20, 24, 32]
    call exact_solution(w, 1.0e-5_dp, qe, cpu_e, srep)
    write(*, '(a,f6.1,a)') '== B. Harmonic series against the exact periodic solution, linear four-bar at ', w, ' rad/s'
    write(*, '(a,es10.3,a,f7.4,a)') '   exact: BDF rtol 1e-10, beta = 1e-5 s; CPU ', cpu_e, ' s; largest |multiplier| ', &
      srep%max_multiplier, '; error = max|Q_h - Q_exact| / max|Q_exact| over 73 times'
    write(*, '(a6,a12,a14,a16,a10)') 'N', 'error', 'CPU (s)', 'rcond ratio', 'flagged'
    do k = 1, size(ns)
      s%n_harmonics = ns(k)
      cpu_h = huge(1.0_dp)
      do r = 1, 5
        call four_bar(w, tennant_options_t(), model)
        if (.not. allocated(qh)) allocate(qh(model%n, n_out + 1))
        call cpu_time(c0)
        call harmonic_solve(model, s, revolution(w), qh, hrep, err)
        call cpu_time(c1)
        cpu_h = min(cpu_h, c1 - c0)
      end do
      err_rel = maxval(abs(qh - qe))/maxval(abs(qe))
      write(*, '(i6,es12.3,es14.3,es16.3,l10)') ns(k), err_rel, cpu_h, hrep%worst_ratio, hrep%near_resonance
    end do
    write(*, *)
  end subroutine part_b

  subroutine part_c()
    real(dp), allocatable :: qe(:, :), q0(:, :), qh(:, :), qb(:, :)
    real(dp) :: w, cpu_e, cpu_0, cpu_h, cpu_b, c0, c1, w1_min
    type(shooting_report_t) :: srep, srep0
    type(harmonic_report_t) :: hrep, brep
    type(harmonic_settings_t) :: s
    type(steady_model_t) :: model
    type(error_t) :: err
    integer :: k, n_best
    w1_min = 1417.0_dp
    write(*, '(a)') '== C. Legacy harmonic series against the exact periodic solution as the crank speed rises'
    write(*, '(a)') '   linear four-bar; exact with beta = 1e-5 s (BDF) and undamped (Adams, rtol 1e-10);'
    write(*, '(a)') '   harmonic with N = 8 and with the largest N keeping N w below 0.9 of the lowest natural'
    write(*, '(a)') '   frequency (1417 rad/s); errors relative to max|Q_exact| (damped)'
    write(*, '(a7,a12,a10,a10,a12,a12,a6,a12,a12,a12,a12)') 'w', 'max|Q_ex|', 'undamped', '|mu|max', 'err N=8', &
      'flag N=8', 'N*', 'err N*', 'CPU exact', 'CPU N=8', 'CPU N*'
    do k = 1, 8
      w = 25.0_dp*k
      call exact_solution(w, 1.0e-5_dp, qe, cpu_e, srep)
      call exact_solution(w, 0.0_dp, q0, cpu_0, srep0, adams=.true.)
      call four_bar(w, tennant_options_t(), model)
      allocate(qh(model%n, n_out + 1), qb(model%n, n_out + 1))
      s%n_harmonics = 8
      call cpu_time(c0)
      call harmonic_solve(model, s, revolution(w), qh, hrep, err)
      call cpu_time(c1)
      cpu_h = c1 - c0
      n_best = min(32, int(0.9_dp*w1_min/w))
      s%n_harmonics = n_best
      call four_bar(w, tennant_options_t(), model)
      call cpu_time(c0)
      call harmonic_solve(model, s, revolution(w), qb, brep, err)
      call cpu_time(c1)
      cpu_b = c1 - c0
      write(*, '(f7.1,es12.3,f10.3,f10.4,es12.3,l12,i6,es12.3,es12.3,es12.3,es12.3)') w, maxval(abs(qe)), &
        maxval(abs(q0 - qe))/maxval(abs(qe)), srep%max_multiplier, maxval(abs(qh - qe))/maxval(abs(qe)), &
        hrep%near_resonance, n_best, maxval(abs(qb - qe))/maxval(abs(qe)), cpu_e, cpu_h, cpu_b
      deallocate(qh, qb)
    end do
    write(*, '(a)') '   (undamped = max|Q_undamped - Q_damped| / max|Q_damped|)'
    write(*, *)
  end subroutine part_c

  subroutine part_d()
    real(dp), allocatable :: qref(:, :), q(:, :)
    real(dp) :: cpu, betas(4) = [0.0_dp, 1.0e-6_dp, 1.0e-5_dp, 1.0e-4_dp], tols(4) = [1.0e-6_dp, 1.0e-8_dp, &
                1.0e-10_dp, 1.0e-12_dp]
    type(shooting_report_t) :: rep
    integer :: i, j, k
    logical :: adams
    write(*, '(a)') '== D. The exact periodic solution at 150 rad/s: damping, integrator and tolerance'
    write(*, '(a)') '   difference = max|Q - Q_ref| / max|Q_ref|, Q_ref = same beta and integrator at rtol 1e-12'
    write(*, '(a10,a8,a10,a12,a12,a10,a12,a10,a12)') 'beta', 'method', 'rtol', 'max|Q|', 'difference', '|mu|max', &
      'rcond(J)', 'steps', 'CPU (s)'
    do i = 1, 4
      do j = 1, 2
        adams = j == 1
        if (.not. adams .and. i == 1) cycle
        call exact_solution(150.0_dp, betas(i), qref, cpu, rep, rtol=1.0e-12_dp, adams=adams)
        call print_line(betas(i), adams, 1.0e-12_dp, qref, qref, rep, cpu)
        do k = 3, 1, -1
          call exact_solution(150.0_dp, betas(i), q, cpu, rep, rtol=tols(k), adams=adams)
          call print_line(betas(i), adams, tols(k), q, qref, rep, cpu)
        end do
      end do
    end do
    write(*, '(a)') '   (BDF is not run undamped: its numerical damping of the high modes would be the damping)'
  end subroutine part_d
  subroutine print_line(beta, adams, rt, qq, qref, rep, cpu)
    real(dp), intent(in) :: beta, rt, qq(:, :), qref(:, :), cpu
    logical, intent(in) :: adams
    type(shooting_report_t), intent(in) :: rep
    write(*, '(es10.1,a8,es10.1,es12.4,es12.3,f10.4,es12.3,i10,es12.3)') beta, merge('adams', 'bdf  ', adams), rt, &
      maxval(abs(qq)), maxval(abs(qq - qref))/maxval(abs(qref)), rep%max_multiplier, rep%rcond_newton, rep%steps, cpu
  end subroutine print_line
end program bench_steady
