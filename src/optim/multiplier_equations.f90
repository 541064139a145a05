!> The Lagrange-multiplier equations of the Gauss family (P4-P25, B3-B13;
!> doc/optimization.md) and the step they define.
!>
!> For an active set S (l constraints) the KKT conditions at the new point,
!> with F quadratic through G, give the step s = x_{k+1} - x_k as a function
!> of the multipliers (B10 written relative to x_k):
!>
!>     ( G + Sum_j lambda_j A_j ) s = -( grad F(x_k) + Sum_j lambda_j c_j ),
!>
!> c_j = grad g_j(x_k), A_j = Hess g_j.  With A_j x_k + b_j = c_j this is
!> exactly B10; the relative form avoids the cancellation of G x_k - grad F.
!> Substituting s(lambda) into the active constraints gives l equations in l
!> unknowns (B11):
!>
!>     m_i(lambda) = g_i(x_k) + c_i^T s + 1/2 s^T A_i s = 0        (quadratic model)
!>     m_i(lambda) = g_i(x_k + s(lambda))                           (Potter §9.5 item 2)
!>
!> solved by Newton-Raphson; if Newton fails, H(lambda) = Sum m_i^2 is
!> minimised by Powell's method and the minimiser is used whether or not
!> H = 0 (Boston et al., text after B11).  For linear constraints (A_j = 0)
!> the equations are linear and their solution is the closed form of
!> Paradis & Willmert (P16, P17): `linear_multipliers`.
module multiplier_equations
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use linalg, only: lu_factor, lu_solve, solve_linear, cholesky_factor, symmetric_eigenvalues
  use optim_problem, only: opt_problem_t
  use powell_minimizer, only: powell_function_t, powell_options_t, powell_result_t, powell_minimize
  implicit none
  private
  public :: multiplier_system_t, multiplier_result_t, multiplier_system
  public :: gauss_step, linear_multipliers

  !> Value of H where s(lambda) does not exist (M singular): large but finite.
  real(dp), parameter :: h_undefined = 1.0e30_dp

  type, extends(powell_function_t) :: multiplier_system_t
    integer :: n = 0
    integer :: l = 0
    real(dp), allocatable :: gmat(:, :)     !< G (n, n)
    real(dp), allocatable :: gradf(:)       !< grad F(x_k)
    real(dp), allocatable :: xk(:)
    integer, allocatable :: idx(:)          !< (l) constraint numbers in the problem
    real(dp), allocatable :: gval(:)        !< (l) g_j(x_k)
    real(dp), allocatable :: c(:, :)        !< (n, l) grad g_j(x_k)
    real(dp), allocatable :: a(:, :, :)     !< (n, n, l) A_j
    logical, allocatable :: actual(:)       !< (l) use g_j(x_k + s) in B11 (Potter)
    logical, allocatable :: nonneg(:)       !< (l) inequality: Powell's compromise keeps lambda_j >= 0
    logical, allocatable :: fixed(:)        !< (n) variables held at a simple bound: s_j = s_fix(j)
    real(dp), allocatable :: s_fix(:)       !< (n) their prescribed step (bound - x_k)
    real(dp) :: fix_scale = 1.0_dp          !< diagonal put in the rows of fixed variables (G's scale)
    class(opt_problem_t), pointer :: prob => null()   !< needed only where actual(j)
    real(dp) :: rcond_min = 1.0e-14_dp      !< M with a smaller reciprocal condition is singular
    ! state of the last `evaluate_step`
    real(dp), allocatable :: mlu(:, :)
    integer, allocatable :: ipiv(:)
    real(dp), allocatable :: s(:)
    real(dp) :: m_rcond = 0.0_dp
    type(error_t) :: eval_err               !< first failure of an actual constraint inside Powell
    integer :: evaluations = 0              !< evaluations of m(lambda)
    logical :: in_powell = .false.          !< counting: evaluations now are Powell's
  contains
    procedure :: evaluate_step
    procedure :: residual
    procedure :: newton_matrix
    procedure :: value => h_value
    procedure :: solve
    procedure :: model_positive_definite
    procedure :: project
    procedure :: fix_rows
    procedure :: kkt_newton
    procedure :: bound_multipliers
  end type multiplier_system_t

  type :: multiplier_result_t
    logical :: solved = .false.               !< max |m_i| <= tolerance at the returned lambda
    character(len=:), allocatable :: how      !< 'newton', 'powell', 'powell+newton'
    character(len=:), allocatable :: newton_failure  !< why Newton failed (empty if it did not)
    integer :: newton_iterations = 0
    integer :: powell_evaluations = 0
    real(dp) :: residual = 0.0_dp             !< max |m_i(lambda)|
    logical :: no_step = .false.              !< no multiplier tried gave a usable step (M singular, or the step
                                              !< 1e10 times |x|): the error of `solve`
  end type multiplier_result_t

  !> The work of one `solve`: the residual m(lambda) of the last iterate and
  !> the best point Newton in lambda saw (least H = Sum m_i^2: Powell's start).
  type :: lambda_search_t
    real(dp), allocatable :: r(:)
    real(dp), allocatable :: lam_best(:)
    real(dp) :: h_best = huge(1.0_dp)
    real(dp) :: tol = 0.0_dp                !< max |m_i| accepted as a solution
    integer :: max_newton = 0
  end type lambda_search_t

contains

  !> The system of one iteration and active set.  `prob` is only used for
  !> constraints with actual(j) = .true.; every constraint may take either
  !> sign (default) and no variable is held (default).
  function multiplier_system(gmat, gradf, xk, idx, gval, c, a, actual, prob, nonneg, fixed, s_fix) result(sys)
    real(dp), intent(in) :: gmat(:, :), gradf(:), xk(:), gval(:), c(:, :), a(:, :, :)
    integer, intent(in) :: idx(:)
    logical, intent(in) :: actual(:)
    class(opt_problem_t), intent(in), pointer :: prob
    logical, intent(in), optional :: nonneg(:)   !< (l) inequality: lambda_j >= 0 in Powell's compromise
    logical, intent(in), optional :: fixed(:)    !< (n) variables held at a bound
    real(dp), intent(in), optional :: s_fix(:)   !< (n) their step
    type(multiplier_system_t) :: sys
    logical :: sign_kept(size(idx)), held(size(xk))
    real(dp) :: held_step(size(xk))
    integer :: j, n
    n = size(xk)
    sign_kept = .false.
    if (present(nonneg)) sign_kept = nonneg
    held = .false.
    held_step = 0.0_dp
    if (present(fixed)) held = fixed
    if (present(s_fix)) held_step = s_fix
    sys = multiplier_system_t(n=n, l=size(idx), gmat=gmat, gradf=gradf, xk=xk, idx=idx, gval=gval, c=c, a=a, &
                              actual=actual, nonneg=sign_kept, fixed=held, s_fix=held_step, &
                              fix_scale=max(maxval([(abs(gmat(j, j)), j=1, n)]), 1.0e-300_dp), prob=prob)
    allocate(sys%mlu(n, n), sys%ipiv(n), sys%s(n))
    sys%s = 0.0_dp
  end function multiplier_system

  !> s(lambda) from B10; ok = .false. if G + Sum lambda_j A_j is singular.
  subroutine evaluate_step(self, lambda, ok)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(in) :: lambda(:)
    logical, intent(out) :: ok
    type(error_t) :: lerr
    integer :: j
    self%mlu = self%gmat
    self%s = -self%gradf
    do j = 1, self%l
      self%mlu = self%mlu + lambda(j)*self%a(:, :, j)
      self%s = self%s - lambda(j)*self%c(:, j)
    end do
    call self%fix_rows(self%mlu, self%s)
    call lu_factor(self%mlu, self%ipiv, lerr, self%m_rcond)
    ok = .not. lerr%failed() .and. self%m_rcond >= self%rcond_min
    if (.not. ok) then
      self%s = 0.0_dp
      return
    end if
    call lu_solve(self%mlu, self%ipiv, self%s, lerr)
    ok = .not. lerr%failed() .and. all(ieee_is_finite(self%s))
    ! a step 1e10 times the size of the point is no model step: M is nearly
    ! singular for this lambda (and the constraints evaluated there would
    ! overflow: fuzz seed 8, general_convex from x0 = (1e9, 0))
    if (ok) ok = maxval(abs(self%s)) <= 1.0e10_dp*(1.0_dp + maxval(abs(self%xk)))
    if (.not. ok) self%s = 0.0_dp
  end subroutine evaluate_step

  !> m(lambda) (B11) at the step of the last `evaluate_step`.
  subroutine residual(self, r, err)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(out) :: r(:)
    type(error_t), intent(inout) :: err
    integer :: j
    self%evaluations = self%evaluations + 1
    do j = 1, self%l
      if (self%actual(j)) then
        call self%prob%constraint_value(self%idx(j), self%xk + self%s, r(j), err)   ! Potter §9.5 item 2
        self%prob%count%b11_constraint_evals = self%prob%count%b11_constraint_evals + 1
        if (self%in_powell) self%prob%count%powell_constraint_evals = self%prob%count%powell_constraint_evals + 1
        if (err%failed()) return
      else
        r(j) = self%gval(j) + dot_product(self%c(:, j), self%s) &
               + 0.5_dp*dot_product(self%s, matmul(self%a(:, :, j), self%s))
      end if
    end do
  end subroutine residual

  !> The residual m at the step in self%s, as a Newton iterate uses it:
  !> values not finite or past 1e100 (the iterates diverge) set `reason`
  !> ('constraint values overflow at '//where); `reason` is kept otherwise.
  subroutine checked_residual(self, r, where, reason, err)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(out) :: r(:)
    character(len=*), intent(in) :: where
    character(len=:), allocatable, intent(inout) :: reason
    type(error_t), intent(inout) :: err
    call self%residual(r, err)
    if (err%failed()) return
    if (.not. all(ieee_is_finite(r)) .or. maxval(abs(r)) > 1.0e100_dp) &
      reason = 'constraint values overflow at '//where
  end subroutine checked_residual

  !> dm_i/dlambda_j = -w_i^T M^{-1} w_j, w_j = c_j + A_j s (the model gradient
  !> at x_k + s; for Potter's actual constraints an approximation).
  !> ok = .false. when M is too nearly singular for the products to stay
  !> finite (an overflow would trap in the debug build: fuzz seed 8).
  subroutine newton_matrix(self, jm, ok)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(out) :: jm(:, :)
    logical, intent(out) :: ok
    real(dp), allocatable :: w(:, :), z(:, :)
    type(error_t) :: lerr
    integer :: j
    allocate(w(self%n, self%l), z(self%n, self%l))
    do j = 1, self%l
      w(:, j) = self%c(:, j) + matmul(self%a(:, :, j), self%s)
      where (self%fixed) w(:, j) = 0.0_dp
    end do
    z = w
    call lu_solve(self%mlu, self%ipiv, z, lerr)
    ok = .not. lerr%failed() .and. all(ieee_is_finite(z)) .and. all(ieee_is_finite(w))
    if (ok) ok = maxval(abs(z)) <= 1.0e300_dp/(real(max(1, self%n), dp)*max(maxval(abs(w)), 1.0_dp))
    if (.not. ok) then
      jm = 0.0_dp
      return
    end if
    jm = -matmul(transpose(w), z)
  end subroutine newton_matrix

  !> Variables held at a simple bound: their rows and columns of mat become
  !> fix_scale times the identity and, with rhs, their prescribed step goes
  !> to the right-hand side after its contribution has been moved out of
  !> the free rows.  A solve then gives s_j = s_fix(j) on the fixed variables
  !> and B10 restricted to the free ones (bounds as bounds, not as rows of
  !> the multiplier system).
  pure subroutine fix_rows(self, mat, rhs)
    class(multiplier_system_t), intent(in) :: self
    real(dp), intent(inout) :: mat(:, :)
    real(dp), intent(inout), optional :: rhs(:)
    integer :: j
    if (.not. any(self%fixed)) return
    if (present(rhs)) then
      do j = 1, self%n
        if (self%fixed(j)) rhs = rhs - mat(:, j)*self%s_fix(j)
      end do
    end if
    do j = 1, self%n
      if (.not. self%fixed(j)) cycle
      mat(j, :) = 0.0_dp
      mat(:, j) = 0.0_dp
      mat(j, j) = self%fix_scale
      if (present(rhs)) rhs(j) = self%fix_scale*self%s_fix(j)
    end do
  end subroutine fix_rows

  !> r = M s + grad F + Sum lambda_j c_j at the current step (M = G + Sum
  !> lambda_j A_j): zero on the free variables; on a fixed one the force its
  !> bound carries, so the bound's multiplier is r_j (lower) or -r_j (upper).
  function bound_multipliers(self, lambda) result(r)
    class(multiplier_system_t), intent(in) :: self
    real(dp), intent(in) :: lambda(:)
    real(dp) :: r(self%n)
    real(dp), allocatable :: mm(:, :)
    integer :: j
    allocate(mm(self%n, self%n))
    mm = self%gmat
    r = self%gradf
    do j = 1, self%l
      mm = mm + lambda(j)*self%a(:, :, j)
      r = r + lambda(j)*self%c(:, j)
    end do
    r = r + matmul(mm, self%s)
  end function bound_multipliers

  !> B10 and B11 solved together by Newton's method in (s_free, lambda):
  !> residuals r = M(lambda) s + grad F + Sum lambda_j c_j (free rows) and
  !> m(lambda, s), Jacobian [M_FF W_F; W_F^T 0] with W_j = c_j + A_j s.  Its
  !> roots are those of B10/B11 wherever M is nonsingular, but the Jacobian
  !> needs M nonsingular only on the tangent space of the active
  !> constraints (the second-order conditions), not on all of R^n.  At the
  !> optimum of HS 18 and 31 (homogeneous quadratic objective, constraint
  !> x1 x2 >= c) M(lambda*) is singular and s(lambda) of B10 is -x_k for
  !> every other lambda, so B11 in lambda alone has no root.  Newton starts
  !> at s = 0 (x_k); a root is accepted only if the Jacobian has the inertia
  !> (n_free, l, 0) of a minimiser of the Lagrangian model on the active
  !> constraints (not a saddle or a maximum).  On return self%s is the step.
  subroutine kkt_newton(self, lam, tol, max_it, ok, reason, iterations, err)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(inout) :: lam(:)
    real(dp), intent(in) :: tol
    integer, intent(in) :: max_it
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: reason
    integer, intent(out) :: iterations
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: mm(:, :), kk(:, :), w(:, :), r1(:), r2(:), d(:), s(:)
    integer, allocatable :: free(:)
    integer :: nf, l, nk, it, j
    real(dp) :: scale
    logical :: singular
    l = self%l
    free = pack([(j, j=1, self%n)], .not. self%fixed)
    nf = size(free)
    nk = nf + l
    allocate(mm(self%n, self%n), kk(nk, nk), w(self%n, l), r1(self%n), r2(l), d(nk))
    s = merge(self%s_fix, 0.0_dp, self%fixed)
    ok = .false.
    reason = ''
    iterations = 0
    do it = 0, max_it
      iterations = it
      self%s = s
      call checked_residual(self, r2, 'iterate '//str(it), reason, err)
      if (err%failed() .or. len(reason) > 0) return
      call constraint_normals(self, s, it > 0, r2, w, err)
      if (err%failed()) return
      if (it == 0) call first_order_multipliers(self, w, free, lam)
      mm = self%gmat
      r1 = self%gradf + matmul(self%gmat, s) + matmul(w, lam)
      scale = maxval(abs(self%gradf)) + maxval(abs(matmul(self%gmat, s))) + sum(abs(lam)*maxval(abs(w), dim=1))
      do j = 1, l
        mm = mm + lam(j)*self%a(:, :, j)
      end do
      if (.not. all(ieee_is_finite(r1))) then
        reason = 'stationarity residual overflows at iterate '//str(it)
        return
      end if
      kk = 0.0_dp
      kk(1:nf, 1:nf) = mm(free, free)
      kk(1:nf, nf + 1:nk) = w(free, :)
      kk(nf + 1:nk, 1:nf) = transpose(w(free, :))
      if (maxval(abs(r2)) <= tol .and. maxval(abs(r1(free)), mask=nf > 0) <= 1.0e-9_dp*max(scale, tiny(1.0_dp))) then
        ok = minimiser_inertia(kk, nf, l)
        if (.not. ok) reason = 'root is no minimiser of the Lagrangian model (inertia of [M W; W^T 0])'
        return
      end if
      if (it == max_it) then
        ! stationarity at the accuracy of the constraint gradients: with
        ! forward differences (error ~sqrt(eps) relative, and different at
        ! every iterate) r1 stagnates at a noise floor above 1e-9 scale while
        ! B11 holds (HS 71 as a user problem: r1 between 5e-8 and 4e-7 for
        ! 10 iterations, 1e-9 scale = 3.4e-8; whether one iterate dipped
        ! below it was round-off, and the run was lost at -O3 -march=native)
        if (maxval(abs(r2)) <= tol .and. maxval(abs(r1(free)), mask=nf > 0) <= &
            sqrt(epsilon(1.0_dp))*max(scale, tiny(1.0_dp))) then
          ok = minimiser_inertia(kk, nf, l)
          if (.not. ok) reason = 'root is no minimiser of the Lagrangian model (inertia of [M W; W^T 0])'
          return
        end if
        reason = 'no convergence in '//str(max_it)//' iterations (max |g| = '//str(maxval(abs(r2)), 3)//')'
        return
      end if
      d(1:nf) = -r1(free)
      d(nf + 1:nk) = -r2
      call equilibrated_solve(kk, d, singular)
      if (singular) then
        reason = 'singular KKT matrix at iterate '//str(it)
        return
      end if
      s(free) = s(free) + d(1:nf)
      lam = lam + d(nf + 1:nk)
      if (maxval(abs(lam)) > 1.0e12_dp .or. .not. all(ieee_is_finite(s))) then
        reason = 'iterates diverge'
        return
      end if
    end do
  end subroutine kkt_newton

  !> The active constraints' gradients at x_k + s (kkt_newton's W): the
  !> model's c + A s, or for Potter's actual constraints past the first
  !> iterate their own gradient (the stationarity of the quadratic F model
  !> under the actual constraint; with the model gradient the multipliers
  !> pass a pole where c + A s vanishes, as for exp(x) at s = -1 in HS 34,
  !> and Newton converges only linearly); r2 takes their values there.
  subroutine constraint_normals(self, s, actual_gradients, r2, w, err)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(in) :: s(:)
    logical, intent(in) :: actual_gradients
    real(dp), intent(inout) :: r2(:)
    real(dp), intent(inout) :: w(:, :)
    type(error_t), intent(inout) :: err
    integer :: j
    do j = 1, self%l
      if (self%actual(j) .and. actual_gradients) then
        call self%prob%general_constraint_gradient(self%prob%user_index(self%idx(j)), self%xk + s, r2(j), w(:, j), &
          err)
        self%prob%count%constraint_gradients = self%prob%count%constraint_gradients + 1
        if (err%failed()) return
      else
        w(:, j) = self%c(:, j) + matmul(self%a(:, :, j), s)
      end if
    end do
  end subroutine constraint_normals

  !> kkt_newton's start: least-squares multipliers of grad F + W lambda = 0
  !> on the free variables at x_k (the warm start may be a Powell
  !> compromise, huge and meaningless).  lam is kept if W_F is rank-deficient.
  subroutine first_order_multipliers(self, w, free, lam)
    class(multiplier_system_t), intent(in) :: self
    real(dp), intent(in) :: w(:, :)
    integer, intent(in) :: free(:)
    real(dp), intent(inout) :: lam(:)
    real(dp), allocatable :: ww(:, :), rhs(:)
    integer, allocatable :: p(:)
    real(dp) :: rcw
    type(error_t) :: werr
    integer :: l
    if (size(free) == 0) return
    l = self%l
    allocate(ww(l, l), rhs(l), p(l))
    ww = matmul(transpose(w(free, :)), w(free, :))
    rhs = -matmul(transpose(w(free, :)), self%gradf(free))
    call lu_factor(ww, p, werr, rcw)
    if (werr%failed() .or. rcw < 1.0e-12_dp) return
    call lu_solve(ww, p, rhs, werr)
    if (werr%failed()) return
    lam = rhs
  end subroutine first_order_multipliers

  !> Has the KKT matrix [M_FF W_F; W_F^T 0] the inertia (nf, l, 0) of a
  !> minimiser of the Lagrangian model on the active constraints?
  logical function minimiser_inertia(kk, nf, l) result(good)
    real(dp), intent(in) :: kk(:, :)
    integer, intent(in) :: nf, l
    real(dp), allocatable :: ev(:)
    real(dp) :: big
    type(error_t) :: lerr
    allocate(ev(size(kk, 1)))
    call symmetric_eigenvalues(kk, ev, lerr)
    good = .not. lerr%failed()
    if (.not. good) return
    big = 1.0e-12_dp*maxval(abs(ev))
    good = count(ev > big) == nf .and. count(ev < -big) == l
  end function minimiser_inertia

  !> kk d = rhs solved in place (kk overwritten) after symmetric
  !> equilibration: the multipliers and the step live on different scales,
  !> and rcond should judge singularity, not units.  singular: rcond < 1e-14.
  subroutine equilibrated_solve(kk, d, singular)
    real(dp), intent(inout) :: kk(:, :)
    real(dp), intent(inout), contiguous :: d(:)
    logical, intent(out) :: singular
    real(dp) :: dsc(size(d)), rc
    integer :: piv(size(d)), j
    type(error_t) :: lerr
    do j = 1, size(d)
      dsc(j) = 1.0_dp/sqrt(max(maxval(abs(kk(j, :))), tiny(1.0_dp)))
    end do
    do j = 1, size(d)
      kk(:, j) = dsc*kk(:, j)*dsc(j)
    end do
    d = dsc*d
    call lu_factor(kk, piv, lerr, rc)
    singular = lerr%failed() .or. rc < 1.0e-14_dp
    if (singular) return
    call lu_solve(kk, piv, d, lerr)
    d = dsc*d
  end subroutine equilibrated_solve

  !> Is G + Sum lambda_j A_j positive definite (Cholesky succeeds)?
  logical function model_positive_definite(self, lambda) result(pd)
    class(multiplier_system_t), intent(in) :: self
    real(dp), intent(in) :: lambda(:)
    real(dp), allocatable :: mm(:, :)
    type(error_t) :: lerr
    integer :: j
    allocate(mm(self%n, self%n))
    mm = self%gmat
    do j = 1, self%l
      mm = mm + lambda(j)*self%a(:, :, j)
    end do
    call self%fix_rows(mm)
    call cholesky_factor(mm, lerr)
    pd = .not. lerr%failed()
  end function model_positive_definite

  !> H(lambda) = Sum m_i(lambda)^2, the function Powell minimises, at the
  !> projection of lambda on the sign restrictions (see `project`).
  function h_value(self, x) result(h)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: h
    real(dp), allocatable :: r(:)
    logical :: ok
    h = h_undefined*1.0e100_dp
    if (maxval(abs(x)) > 1.0e50_dp) return
    h = h_undefined*(1.0_dp + sum(x**2))
    call self%evaluate_step(self%project(x), ok)
    if (.not. ok) return
    allocate(r(self%l))
    call self%residual(r, self%eval_err)
    if (self%eval_err%failed()) return
    if (.not. all(ieee_is_finite(r))) return
    if (maxval(abs(r)) > 1.0e100_dp) return
    h = sum(r**2)
  end function h_value

  !> lambda with the sign-restricted (inequality) components clipped at 0.
  !> Powell's compromise for an inconsistent B11 is not a KKT point, and its
  !> multipliers carry no sign information; unrestricted, H can have local
  !> minima at negative multipliers (or beyond poles of M) that depend on the
  !> last bits, and the drop rule would then act on them.  Clipped, the
  !> compromise of an inequality is the step that best reduces its violation
  !> with lambda >= 0, i.e. with the Lagrangian model still minimised.
  pure function project(self, lambda) result(p)
    class(multiplier_system_t), intent(in) :: self
    real(dp), intent(in) :: lambda(:)
    real(dp) :: p(size(lambda))
    p = lambda
    where (self%nonneg) p = max(lambda, 0.0_dp)
  end function project

  !> Solve B11 for lambda (in: starting guess, out: solution or Powell's
  !> minimiser of H).  Newton first; on failure Powell, then a Newton polish
  !> from Powell's point.  On return the step of the returned lambda is in
  !> self%s.  err is set only if no lambda gives a step at all or an actual
  !> constraint cannot be evaluated.
  subroutine solve(self, lambda, tol, max_newton, res, err)
    class(multiplier_system_t), intent(inout) :: self
    real(dp), intent(inout) :: lambda(:)
    real(dp), intent(in) :: tol            !< max |m_i| accepted as a solution
    integer, intent(in) :: max_newton
    type(multiplier_result_t), intent(out) :: res
    type(error_t), intent(inout) :: err
    type(lambda_search_t) :: work
    logical :: ok, kkt_done
    character(len=:), allocatable :: why

    allocate(work%r(self%l))
    work%lam_best = lambda
    work%tol = tol
    work%max_newton = max_newton
    res%newton_failure = ''
    call newton_starts(self, work, lambda, ok, why, res, err)
    if (err%failed()) return
    kkt_done = .false.
    if (.not. ok) then
      call tangent_space_newton(self, work, lambda, why, kkt_done, res, err)
      if (err%failed()) return
    end if
    if (.not. (ok .or. kkt_done)) then
      res%newton_failure = why
      call powell_compromise(self, work, lambda, res, err)
      if (err%failed()) return
    end if
    ok = .true.
    if (.not. kkt_done) call self%evaluate_step(lambda, ok)
    if (.not. ok) then
      res%no_step = .true.
      call err%set('multiplier equations', 'G + Sum lambda_j A_j is singular at every multiplier tried (rcond = ' &
                   //str(self%m_rcond, 3)//'); the active set cannot define a step')
      return
    end if
    call self%residual(work%r, err)
    if (err%failed()) return
    res%residual = maxval(abs(work%r))
    res%solved = res%residual <= tol
  end subroutine solve

  !> Newton in lambda (B11) from the given lambda and, if that fails, from
  !> lambda = 0 (the unconstrained step); ok: lambda is the root.  why: the
  !> failures.
  subroutine newton_starts(self, work, lambda, ok, why, res, err)
    class(multiplier_system_t), intent(inout) :: self
    type(lambda_search_t), intent(inout) :: work
    real(dp), intent(inout) :: lambda(:)
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: why
    type(multiplier_result_t), intent(inout) :: res
    type(error_t), intent(inout) :: err
    real(dp) :: start(size(lambda))
    character(len=:), allocatable :: why2
    start = lambda
    call newton_from(self, work, start, lambda, 'newton', ok, why, res, err)
    if (err%failed()) return
    if (.not. ok .and. maxval(abs(lambda)) > 0.0_dp) then
      start = 0.0_dp
      call newton_from(self, work, start, lambda, 'newton', ok, why2, res, err)
      if (err%failed()) return
      if (.not. ok) why = why//'; from lambda = 0: '//why2
    end if
  end subroutine newton_starts

  !> Newton in lambda (lambda_newton) from start, its iterations counted in
  !> res; on convergence lambda takes the root and res%how = how.
  subroutine newton_from(self, work, start, lambda, how, ok, why, res, err)
    class(multiplier_system_t), intent(inout) :: self
    type(lambda_search_t), intent(inout) :: work
    real(dp), intent(in) :: start(:)
    real(dp), intent(inout) :: lambda(:)
    character(len=*), intent(in) :: how
    logical, intent(out) :: ok
    character(len=:), allocatable, intent(out) :: why
    type(multiplier_result_t), intent(inout) :: res
    type(error_t), intent(inout) :: err
    real(dp) :: lam_newton(size(start))
    integer :: its
    lam_newton = start
    call lambda_newton(self, work, lam_newton, ok, why, its, err)
    if (err%failed()) return
    res%newton_iterations = res%newton_iterations + its
    if (ok) then
      lambda = lam_newton
      res%how = how
    end if
  end subroutine newton_from

  !> B10 and B11 together (kkt_newton) after Newton in lambda failed: where
  !> the elimination of s is degenerate (M or the Newton matrix singular),
  !> the (s, lambda) system needs M nonsingular only on the tangent space.
  !> Not where Newton diverged or stalled: there B11 has no root near and
  !> Powell's compromise is the papers' remedy (with it HS 15 reaches x*;
  !> the (s, lambda) root, a vertex with a negative multiplier, led to its
  !> other local minimum).  done: lambda and self%s are that root.
  subroutine tangent_space_newton(self, work, lambda, why, done, res, err)
    class(multiplier_system_t), intent(inout) :: self
    type(lambda_search_t), intent(in) :: work
    real(dp), intent(inout) :: lambda(:)
    character(len=:), allocatable, intent(inout) :: why
    logical, intent(out) :: done
    type(multiplier_result_t), intent(inout) :: res
    type(error_t), intent(inout) :: err
    real(dp) :: lam_newton(size(lambda))
    character(len=:), allocatable :: why2
    integer :: its
    lam_newton = lambda
    call self%kkt_newton(lam_newton, work%tol, work%max_newton, done, why2, its, err)
    if (err%failed()) return
    res%newton_iterations = res%newton_iterations + its
    ! a negative multiplier of a violated inequality would make the drop
    ! rule abandon its restoration on the strength of a root that Newton in
    ! lambda (with its positive-definiteness safeguard) did not reach:
    ! such a root is left to Powell's compromise (HS 15: the root is the
    ! vertex (-1, -1) with lambda_2 = -201; dropping g2 there led to HS 15's
    ! other local minimum)
    if (done) done = .not. any(self%nonneg .and. self%gval > 100.0_dp*work%tol .and. lam_newton < 0.0_dp)
    if (done) then
      lambda = lam_newton
      res%how = 'kkt'
      res%newton_failure = why
    else
      if (len(why2) == 0) why2 = 'negative multiplier of a violated inequality'
      why = why//'; (s, lambda) Newton: '//why2
    end if
  end subroutine tangent_space_newton

  !> Powell on H from the best point Newton saw (Boston et al. after B11),
  !> then a Newton polish from Powell's point (Newton converges
  !> quadratically once Powell is near a root).
  subroutine powell_compromise(self, work, lambda, res, err)
    class(multiplier_system_t), intent(inout) :: self
    type(lambda_search_t), intent(inout) :: work
    real(dp), intent(inout) :: lambda(:)
    type(multiplier_result_t), intent(inout) :: res
    type(error_t), intent(inout) :: err
    type(powell_options_t) :: popts
    type(powell_result_t) :: pres
    real(dp) :: start(size(lambda))
    character(len=:), allocatable :: why
    logical :: ok
    popts%ftol = 1.0e-15_dp
    popts%f_target = (0.01_dp*work%tol)**2
    popts%initial_step = 0.1_dp*max(1.0_dp, maxval(abs(work%lam_best)))
    popts%max_iter = 100*max(1, self%l)
    lambda = self%project(work%lam_best)
    self%in_powell = .true.
    call powell_minimize(self, lambda, popts, pres)
    self%in_powell = .false.
    lambda = self%project(lambda)
    res%powell_evaluations = pres%evaluations
    if (associated(self%prob)) self%prob%count%powell_h_evals = self%prob%count%powell_h_evals + pres%evaluations
    if (self%eval_err%failed()) then
      err = self%eval_err
      call err%add_context('multiplier equations (Powell)')
      return
    end if
    res%how = 'powell'
    start = lambda
    call newton_from(self, work, start, lambda, 'powell+newton', ok, why, res, err)
  end subroutine powell_compromise

  !> B11 by Newton-Raphson in lambda, with work%tol and work%max_newton;
  !> the best point seen (least H = Sum m_i^2) goes into work.
  subroutine lambda_newton(self, work, lam, converged, reason, iterations, nerr)
    class(multiplier_system_t), intent(inout) :: self
    type(lambda_search_t), intent(inout) :: work
    real(dp), intent(inout) :: lam(:)
    logical, intent(out) :: converged
    character(len=:), allocatable, intent(out) :: reason
    integer, intent(out) :: iterations
    type(error_t), intent(inout) :: nerr
    real(dp), allocatable :: jm(:, :), d(:)
    integer, allocatable :: piv(:)
    real(dp) :: rc, h
    type(error_t) :: lerr
    logical :: okstep, ok_matrix
    integer :: it, halvings
    allocate(jm(self%l, self%l), d(self%l), piv(self%l))
    converged = .false.
    reason = ''
    iterations = 0
    do it = 0, work%max_newton
      iterations = it
      call self%evaluate_step(lam, okstep)
      if (.not. okstep) then
        reason = 'G + Sum lambda_j A_j singular at Newton iterate '//str(it)
        return
      end if
      call checked_residual(self, work%r, 'Newton iterate '//str(it), reason, nerr)
      if (nerr%failed() .or. len(reason) > 0) return
      h = sum(work%r**2)
      if (h < work%h_best) then
        work%h_best = h
        work%lam_best = lam
      end if
      if (maxval(abs(work%r)) <= work%tol) then
        converged = .true.
        return
      end if
      if (it == work%max_newton) then
        reason = 'no convergence in '//str(work%max_newton)//' Newton iterations (max |g| = ' &
                 //str(maxval(abs(work%r)), 3)//')'
        return
      end if
      call self%newton_matrix(jm, ok_matrix)
      if (.not. ok_matrix) then
        reason = 'the Newton matrix for the multipliers overflows (G + Sum lambda A nearly singular)'
        return
      end if
      call lu_factor(jm, piv, lerr, rc)
      if (lerr%failed() .or. rc < 1.0e-14_dp) then
        reason = 'singular Newton matrix for the multipliers (active constraints dependent, ' &
                 //'or more active constraints than the step can satisfy)'
        return
      end if
      d = -work%r
      call lu_solve(jm, piv, d, lerr)
      ! our safeguard (the papers are silent): while G + Sum lambda A is
      ! positive definite, halve steps that would leave that region, so B10
      ! stays the minimiser of the quadratic Lagrangian model and Newton
      ! does not jump to a root that maximises it
      if (self%model_positive_definite(lam)) then
        do halvings = 1, 30
          if (self%model_positive_definite(lam + d)) exit
          d = 0.5_dp*d
        end do
      end if
      lam = lam + d
      if (maxval(abs(lam)) > 1.0e12_dp) then
        reason = 'Newton iterates for the multipliers diverge (|lambda| > 1e12)'
        return
      end if
    end do
  end subroutine lambda_newton

  !> Unconstrained Gauss step (B12, P2): s = -G^{-1} grad F = -(J J^T)^{-1} J phi
  !> for G = 2 J J^T, grad F = 2 J phi.
  subroutine gauss_step(gmat, gradf, s, err, rcond)
    real(dp), intent(in) :: gmat(:, :), gradf(:)
    real(dp), intent(out), contiguous :: s(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: rcond
    s = -gradf
    call solve_linear(gmat, s, err, rcond)
  end subroutine gauss_step

  !> Multipliers and step for linear active constraints (A_j = 0), closed
  !> form.  With r_S = g_S(x_k) (zero when x_k lies on the active
  !> constraints, the case P16/P17 assume):
  !>     lambda = [C^T G^{-1} C]^{-1} ( r_S - C^T G^{-1} grad F )     (P16)
  !>     s      = -G^{-1} ( grad F + C lambda )                        (P14, = P17)
  subroutine linear_multipliers(gmat, gradf, c, gs, lambda, s, err)
    real(dp), intent(in) :: gmat(:, :), gradf(:), c(:, :), gs(:)
    real(dp), intent(out), contiguous :: lambda(:), s(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: lu(:, :), z(:, :), y(:), k(:, :)
    integer, allocatable :: ipiv(:), kpiv(:)
    real(dp) :: rc
    integer :: n, l
    n = size(gradf)
    l = size(gs)
    allocate(lu(n, n), ipiv(n), z(n, l), y(n), k(l, l), kpiv(l))
    lu = gmat
    call lu_factor(lu, ipiv, err)
    if (err%failed()) return
    z = c
    y = gradf
    call lu_solve(lu, ipiv, z, err)
    call lu_solve(lu, ipiv, y, err)
    k = matmul(transpose(c), z)
    lambda = gs - matmul(transpose(c), y)
    call lu_factor(k, kpiv, err, rc)
    if (.not. err%failed() .and. rc < 1.0e-14_dp) &
      call err%set('lu_factor', 'reciprocal condition '//str(rc, 3))
    if (err%failed()) then
      call err%add_context('linear_multipliers: the active constraint gradients are linearly dependent')
      return
    end if
    call lu_solve(k, kpiv, lambda, err)
    s = -(y + matmul(z, lambda))
  end subroutine linear_multipliers
end module multiplier_equations
