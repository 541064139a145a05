!> Feasibility restoration for the Gauss family (issue 11): from a point
!> where GNLC.NS cannot move (HS 23 at the origin: grad F = 0 and the
!> violated constraints x1^2 + x2^2 >= 1, 9 x1^2 + x2^2 >= 9 have zero
!> gradients, so B10 gives s = 0 for every multiplier), minimise the
!> constraint violation
!>
!>     V(x) = Sum_i max(g_i(x), 0)^2 + Sum_j h_j(x)^2
!>
!> by the Gauss method itself (B12 applied to the residuals r = violations,
!> J = their gradients): s = -J (J^T J + mu I)^{-1} r, the minimum-norm
!> Levenberg step, which for fewer violated constraints than variables is
!> the shortest step that zeroes the linearised violations.  A step that
!> does not reduce V is halved (only constraint functions are evaluated:
!> no analysis, nothing counts in NF).  Trial points stay in the box: a
!> variable on a bound that the step pushes outward is held there and the
!> step recomputed without it.
!> Ends when max violation <= feas_tol (ok) or after max_iter steps.
module feasibility_restoration
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: lu_factor, lu_solve
  use optim_problem, only: opt_problem_t
  implicit none
  private
  public :: restore_feasibility

contains

  !> x: start, on return the restored point (the least violated one found
  !> when ok = .false.); g: constraints there; steps: Gauss steps taken.
  subroutine restore_feasibility(prob, x, g, feas_tol, max_iter, ok, steps, err)
    class(opt_problem_t), intent(inout) :: prob
    real(dp), intent(inout) :: x(:)
    real(dp), intent(out) :: g(:)
    real(dp), intent(in) :: feas_tol
    integer, intent(in) :: max_iter
    logical, intent(out) :: ok
    integer, intent(out) :: steps
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: dg(:, :), r(:), a(:, :), y(:), s(:), x_t(:), g_t(:)
    integer, allocatable :: idx(:), ipiv(:)
    logical, allocatable :: held(:), out(:)
    real(dp) :: v, v_t, mu
    integer :: i, l, m, mt, halvings, passes
    m = prob%m
    mt = prob%m + prob%n_eq
    allocate(dg(prob%n, mt), s(prob%n), g_t(mt), held(prob%n), out(prob%n))
    ok = .false.
    call prob%constraint_values(x, g, err)
    if (err%failed()) return
    do steps = 0, max_iter
      r = violations(g, m)
      if (maxval(abs(r)) <= feas_tol) then
        ok = .true.
        return
      end if
      if (steps == max_iter) return
      call prob%constraint_gradients(x, g, dg, err)
      if (err%failed()) return
      idx = pack([(i, i=1, mt)], abs(r) > feas_tol)
      l = size(idx)
      ! a variable on a bound that the step would push out of the box is held
      ! there (its row of J zeroed) and the step recomputed: projecting the
      ! free step instead shrinks it to nothing where the violated
      ! constraints pull against the box (HS 97 from x0 = 0: two variables
      ! reach their upper bounds, and the projected steps stall)
      held = .false.
      do passes = 1, prob%n + 1
        do i = 1, l
          where (held) dg(:, idx(i)) = 0.0_dp
        end do
        ! (J^T J + mu I) y = r, s = -J y; mu: 1e-8 of the scale (a zero gradient
        ! of a violated constraint leaves a zero row, not a singular system)
        a = matmul(transpose(dg(:, idx)), dg(:, idx))
        mu = 1.0e-8_dp*maxval([(a(i, i), i=1, l)])
        if (.not. mu > 0.0_dp) return            ! every violated gradient zero: a stationary point of V
        do i = 1, l
          a(i, i) = a(i, i) + mu
        end do
        y = r(idx)
        if (allocated(ipiv)) deallocate(ipiv)
        allocate(ipiv(l))
        call lu_factor(a, ipiv, err)
        if (err%failed()) return
        call lu_solve(a, ipiv, y, err)
        if (err%failed()) return
        s = -matmul(dg(:, idx), y)
        if (.not. allocated(prob%xl)) exit
        out = .not. held .and. ((x <= prob%xl .and. s < 0.0_dp) .or. (x >= prob%xu .and. s > 0.0_dp))
        if (.not. any(out)) exit
        held = held .or. out
      end do
      v = sum(r**2)
      v_t = huge(1.0_dp)
      do halvings = 0, 30
        x_t = x + s
        if (prob%n_bounds > 0) x_t = prob%project_to_bounds(x_t)
        call prob%constraint_values(x_t, g_t, err)
        if (err%failed()) return
        if (all(ieee_is_finite(g_t))) then
          v_t = sum(violations(g_t, m)**2)
          if (v_t < v) exit
        end if
        s = 0.5_dp*s
      end do
      if (.not. (all(ieee_is_finite(g_t)) .and. v_t < v)) return     ! no descent: a local minimum of V
      x = x_t
      g = g_t
    end do
  end subroutine restore_feasibility

  !> Violations: max(g_i, 0) for the m inequalities, h_j for the equalities.
  pure function violations(g, m) result(r)
    real(dp), intent(in) :: g(:)
    integer, intent(in) :: m
    real(dp) :: r(size(g))
    r(1:m) = max(g(1:m), 0.0_dp)
    r(m + 1:) = g(m + 1:)
  end function violations
end module feasibility_restoration
