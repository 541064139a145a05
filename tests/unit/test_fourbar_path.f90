!> Tests of the four-bar path-generation problem (module fourbar_path):
!> coupler-point geometry, B's constraints at Table 3's start and optimum, and
!> GNLC on the reconstructed problem.
module test_fourbar_path_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use fourbar_path
  use gauss_optimizer
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('coupler_point_closes_the_loop', test_loop_closure)
    call run_test('table3_optimum_satisfies_constraints_active_9_13_14', test_table3_constraints)
    call run_test('paper_start_is_feasible_change_point_linkage', test_start)
    call run_test('constraint_data_match_constraint_functions', test_constraint_data)
    call run_test('target_from_table3_design_gives_zero_residuals', test_target)
    call run_test('gnlc_recovers_target_design_from_paper_start', test_gnlc_exact)
    call run_test('gnlc_offset_target_active_9_13_14_like_table3', test_gnlc_offset)
  end subroutine run_all

  !> The coupler point is B + x5 e(psi) with the coupler BC at angle
  !> psi - x7; C must lie at distance x4 (rocker) from the rocker pivot
  !> D = A + x1 e(x6), at every crank angle (an independent check of the
  !> reconstructed eps, eta and 2 x3 d).
  subroutine test_loop_closure()
    real(dp) :: x(10), gamma, xx, yy, arg, bx, by, cx, cy, dx, dy, psi
    integer :: i
    x = table3_design
    do i = 0, 35
      gamma = x(8) + real(i, dp)*pi/18.0_dp
      call coupler_point(x, gamma, xx, yy, arg)
      bx = x(10) + x(2)*cos(gamma)
      by = x(9) + x(2)*sin(gamma)
      psi = atan2(yy - by, xx - bx)
      call assert_close(hypot(xx - bx, yy - by), x(5), 1.0e-12_dp, 'coupler point at distance x5 from B')
      cx = bx + x(3)*cos(psi - x(7))
      cy = by + x(3)*sin(psi - x(7))
      dx = x(10) + x(1)*cos(x(6))
      dy = x(9) + x(1)*sin(x(6))
      call assert_close(hypot(cx - dx, cy - dy), x(4), 1.0e-11_dp, 'rocker length |CD| = x4')
      ! B's path synthesis (doc/optimization.md): the acos argument stays in [0.868, 0.996]
      call assert_true(arg >= 0.86_dp .and. arg <= 0.997_dp, 'assembles with margin at the Table 3 design')
    end do
  end subroutine test_loop_closure

  !> B Table 3: optimum x = (30, 8.345, ...), G_ACT = 9, 13, 14.
  subroutine test_table3_constraints()
    real(dp) :: g(14)
    logical :: active(14)
    integer :: k
    g = fourbar_constraints(table3_design)
    call assert_true(all(g <= 1.0e-12_dp), 'all 14 constraints hold')
    active = abs(g) <= 1.0e-9_dp
    call assert_true(all(active .eqv. [(i_in([9, 13, 14], k), k=1, 14)]), 'active set is exactly {9, 13, 14}')
    ! §10.3: the nearest inactive constraint is the Grashof margin g6 = -0.293
    call assert_close(g(6), -0.293_dp, 1.0e-12_dp, 'g6 = -0.293')
    call assert_close(maxval(g, mask=.not. active), g(6), 0.0_dp, 'g6 is the nearest inactive constraint')
    call assert_close(g(11), -17.183_dp, 1.0e-12_dp, 'reconstructed g11 far from active')
    call assert_close(g(12), -13.974_dp, 1.0e-12_dp, 'reconstructed g12 far from active')
  end subroutine test_table3_constraints

  pure logical function i_in(set, k)
    integer, intent(in) :: set(:), k
    i_in = any(set == k)
  end function i_in

  subroutine test_start()
    real(dp) :: g(14), xx, yy, arg
    integer :: k
    g = fourbar_constraints(paper_start)
    call assert_true(all(g <= 0.0_dp), 'Table 3 start is feasible')
    call assert_true(all(abs(g([5, 6, 7])) <= 1.0e-12_dp), 'g5, g6, g7 active (change-point linkage)')
    call assert_close(g(13), -4.0_dp, 1.0e-12_dp, 'g13 = -4')
    call assert_close(g(14), -4.0_dp, 1.0e-12_dp, 'g14 = -4')
    ! x1 + x2 = x3 + x4: the acos argument reaches 1 where crank and ground align
    call coupler_point(paper_start, paper_start(6), xx, yy, arg)
    call assert_close(arg, 1.0_dp, 1.0e-12_dp, 'acos argument = 1 at gamma = x6')
    do k = 1, n_points
      call coupler_point(paper_start, paper_start(8) + default_dgamma(k), xx, yy, arg)
      call assert_true(abs(arg) < 1.0_dp, 'no sampled crank position at the change point')
    end do
  end subroutine test_start

  subroutine test_constraint_data()
    type(fourbar_path_t) :: p
    type(error_t) :: err
    real(dp) :: g(14), x(10)
    call p%setup(2)
    x = [17.0_dp, 4.0_dp, 12.0_dp, 9.0_dp, 7.0_dp, 0.3_dp, -0.2_dp, 2.0_dp, 5.5_dp, 4.5_dp]
    call p%constraint_values(x, g, err)
    call assert_all_close(g, fourbar_constraints(x), 0.0_dp, 1.0e-12_dp, 'linear/quadratic data = functions')
    call assert_equal(p%m, 14, '14 constraints')
    call p%setup(1)
    call assert_equal(p%m, 13, '13-constraint variant')
    call assert_true(.not. err%failed(), 'no error')
  end subroutine test_constraint_data

  subroutine test_target()
    type(fourbar_path_t) :: p
    type(error_t) :: err
    real(dp) :: phi(16), f
    call p%setup(2)
    call p%analyse(table3_design, f, phi, err)
    call assert_close(f, 0.0_dp, 1.0e-24_dp, 'F(target design) = 0')
    call p%analyse(paper_start, f, phi, err)
    call assert_true(f > 100.0_dp, 'F(start) large (paper: 220.29 for its own target)')
    call assert_equal(p%assembly_clamps, 0, 'no clamped acos arguments')
  end subroutine test_target

  !> Known optimum: the target design, F* = 0, on g9, g13, g14.
  subroutine test_gnlc_exact()
    type(fourbar_path_t) :: p
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    call p%setup(2)
    opt%opts%method = method_gnlc
    call opt%solve(p, paper_start, err)
    call assert_true(opt%status == status_converged, 'converged: '//err%text())
    ! F* = 0: Gauss-Newton converges quadratically; x to 1e-8 of a design
    ! with entries up to 30 (forward-difference J limits nothing at F = 0)
    call assert_all_close(opt%x, table3_design, 0.0_dp, 1.0e-8_dp, 'x = Table 3 design')
    call assert_true(opt%f < 1.0e-16_dp, 'F = 0')
    call assert_true(opt%iterations <= 11, 'NI <= 11 (paper, GNLC)')
    call assert_equal(p%count%analyses, opt%iterations + 1, 'NF = NI + 1')
    call assert_true(all(abs(opt%g([9, 13, 14])) <= 1.0e-8_dp), 'g9, g13, g14 at zero')
    call assert_true(all(opt%log(1:opt%n_log)%max_violation <= opt%opts%feas_tol), 'every iterate feasible')
  end subroutine test_gnlc_exact

  !> Unreachable target: optimum with F* > 0 and positive multipliers on
  !> exactly {9, 13, 14} (as in Table 3); checked by the KKT conditions.
  subroutine test_gnlc_offset()
    type(fourbar_path_t) :: p
    type(gauss_optimizer_t) :: opt
    type(error_t) :: err
    logical :: active(14)
    integer :: k
    call p%setup(2, target=offset_target)
    opt%opts%method = method_gnlc
    opt%opts%globalization = glob_none   ! B's GNLC as printed: NF = NI + 1 counts every trial point accepted
    call opt%solve(p, paper_start, err)
    call assert_true(opt%status == status_converged, 'converged: '//err%text())
    active = abs(opt%g) <= 1.0e-8_dp
    call assert_true(all(active .eqv. [(i_in([9, 13, 14], k), k=1, 14)]), 'active set {9, 13, 14}')
    call assert_true(all(opt%lambda([9, 13, 14]) > 1.0e-3_dp), 'positive multipliers on 9, 13, 14')
    call assert_true(opt%f > 0.1_dp .and. opt%f < 0.2_dp, 'F* > 0 (0.1627)')
    ! forward-difference J: gradient error ~ sqrt(eps) |phi| |J| ~ 1e-7 x F-scale
    call assert_true(opt%kkt_residual < 1.0e-5_dp, 'KKT residual < 1e-5')
    call assert_equal(p%count%analyses, opt%iterations + 1, 'NF = NI + 1')
  end subroutine test_gnlc_offset
end module test_fourbar_path_suite

program test_fourbar_path
  use test_fourbar_path_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_fourbar_path')
end program test_fourbar_path
