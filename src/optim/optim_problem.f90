!> An optimization problem for the Gauss family (doc/optimization.md): the type
!> users extend, with forward-difference defaults for every derivative and
!> counters for the work done.
!>
!> Objective.  Either a sum of squares F = phi^T phi (n_residuals > 0; override
!> `residuals`, optionally `jacobian`) or a general F (n_residuals = 0;
!> override `objective`, optionally `gradient` and `hessian`).  The residual
!> Jacobian is stored the papers' way, J(n, p) = [grad phi_1 ... grad phi_p]
!> (P3), so grad F = 2 J phi (B4) and the Gauss matrix is G = 2 J J^T (B5).
!>
!> Constraints g_i(x) <= 0, i = 1..m, and equalities h_j(x) = 0, numbered
!> i = m+j (j = 1..n_eq), each of one kind (m counts the bounds set_bounds
!> adds; the procedures a type overrides see the user's numbering instead,
!> user_index: its own inequalities 1..m_own, then equality j as m_own + j,
!> whatever bounds were added):
!>   linear     g = b^T x - d                     (set_linear_constraint; equalities:
!>                                                 set_linear_equalities, P5)
!>   quadratic  g = 1/2 x^T A x + b^T x - d       (set_quadratic_constraint, B3;
!>                                                 set_quadratic_equality)
!>   general    g from `general_constraint(i, ...)` (Potter's case, §9.5;
!>                                                 set_general_constraint / set_general_equality)
!> The data of constraint i (inequality or equality) is con_kind(i),
!> con_a(:, :, i), con_b(:, i), con_d(i); equalities are always active and
!> their multipliers have no sign.
!>
!> Counting.  The solver calls the non-overridable, counted entry points
!> (`analyse`, `objective_derivatives`, ...).  One call of `analyse` is one
!> analysis (NF, the papers' "function evaluation": one mechanism analysis).
!> Objective evaluations spent inside forward differences are counted apart
!> (fd_analyses), so NF stays comparable with the papers, which do not say how
!> J was obtained.
module optim_problem
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use name_table, only: name_of
  implicit none
  private
  public :: opt_problem_t, opt_counters_t
  public :: con_linear, con_quadratic, con_general, con_kind_name

  integer, parameter :: con_linear = 1, con_quadratic = 2, con_general = 3
  character(len=*), parameter :: con_kind_table(3) = [character(len=9) :: 'linear', 'quadratic', 'general']

  type :: opt_counters_t
    integer :: analyses = 0              !< NF: objective evaluations asked for by the optimizer
    integer :: gradients = 0             !< objective gradients (for sums of squares: via J, one per Jacobian)
    integer :: jacobians = 0             !< residual Jacobian evaluations (sums of squares)
    integer :: hessians = 0              !< objective Hessian evaluations (hessian = 'exact')
    integer :: fd_analyses = 0           !< objective evaluations spent in finite differences
    integer :: constraint_evals = 0      !< constraint vectors evaluated (each at one point)
    integer :: constraint_gradients = 0  !< gradient sets of the general constraints
    integer :: constraint_hessians = 0   !< Hessians of general constraints (Potter re-approximation)
    integer :: fd_constraint_evals = 0   !< general-constraint evaluations spent in finite differences
    integer :: b11_constraint_evals = 0  !< single general-constraint evaluations in B11 (Potter's actual g)
    integer :: powell_h_evals = 0        !< evaluations of H = Sum m_i^2 in Powell's fallback
    integer :: powell_constraint_evals = 0 !< of b11_constraint_evals: those inside Powell's fallback
  end type opt_counters_t

  type, abstract :: opt_problem_t
    character(len=:), allocatable :: name
    integer :: n = 0             !< design variables
    integer :: n_residuals = 0   !< p > 0: F = phi^T phi ; 0: general objective
    integer :: m = 0             !< inequality constraints g_i <= 0
    integer :: n_eq = 0          !< equalities h_j = 0 (constraints m+1..m+n_eq)
    integer, allocatable :: con_kind(:)         !< (m+n_eq) con_linear | con_quadratic | con_general
    real(dp), allocatable :: con_a(:, :, :)     !< (n, n, m+n_eq) A_i of quadratic constraints (0 otherwise)
    real(dp), allocatable :: con_b(:, :)        !< (n, m+n_eq) b_i
    real(dp), allocatable :: con_d(:)           !< (m+n_eq) d_i
    real(dp), allocatable :: xl(:), xu(:)       !< (n) simple bounds (-huge, huge: none), see set_bounds
    integer :: n_bounds = 0                     !< finite bounds, constraints m-n_bounds+1..m
    integer, allocatable :: bound_var(:)        !< (n_bounds) variable of each bound: -j lower, +j upper
    real(dp) :: fd_rel_step = 1.4901161193847656e-8_dp   !< sqrt(eps): forward-difference step factor
    type(opt_counters_t) :: count
  contains
    ! ---- user side: override what the problem can provide
    procedure :: residuals => residuals_not_provided
    procedure :: jacobian => fd_jacobian
    procedure :: objective => objective_from_residuals
    procedure :: gradient => fd_gradient
    procedure :: hessian => fd_hessian
    procedure :: general_constraint => general_constraint_not_provided
    procedure :: general_constraint_gradient => fd_constraint_gradient
    procedure :: general_constraint_hessian => fd_constraint_hessian
    ! ---- set-up
    procedure, non_overridable :: init_problem
    procedure, non_overridable :: set_linear_constraint
    procedure, non_overridable :: set_linear_inequalities
    procedure, non_overridable :: set_quadratic_constraint
    procedure, non_overridable :: set_general_constraint
    procedure, non_overridable :: user_index
    procedure, non_overridable :: set_linear_equalities
    procedure, non_overridable :: set_quadratic_equality
    procedure, non_overridable :: set_general_equality
    procedure, non_overridable :: set_bounds
    procedure, non_overridable :: project_to_bounds
    procedure, non_overridable :: is_least_squares
    procedure, non_overridable :: n_constraints
    ! ---- solver side: counted
    procedure, non_overridable :: analyse
    procedure, non_overridable :: objective_derivatives
    procedure, non_overridable :: objective_hessian
    procedure, non_overridable :: constraint_values
    procedure, non_overridable :: constraint_value
    procedure, non_overridable :: constraint_gradients
    procedure, non_overridable :: constraint_hessian
    procedure, non_overridable :: reset_counters
  end type opt_problem_t

contains

  pure function con_kind_name(kind) result(s)
    integer, intent(in) :: kind
    character(len=:), allocatable :: s
    s = name_of(con_kind_table, kind, con_linear, 'unset')
  end function con_kind_name

  ! ================================================================ set-up

  !> Size the problem.  All inequality constraints start as linear with zero
  !> data; fill them with the set_* procedures.
  subroutine init_problem(self, name, n, n_residuals, m, n_eq)
    class(opt_problem_t), intent(inout) :: self
    character(len=*), intent(in) :: name
    integer, intent(in) :: n, n_residuals, m
    integer, intent(in), optional :: n_eq
    integer :: i
    self%name = name
    self%n = n
    self%n_residuals = n_residuals
    self%m = m
    self%n_eq = 0
    if (present(n_eq)) self%n_eq = n_eq
    if (allocated(self%con_kind)) deallocate(self%con_kind, self%con_a, self%con_b, self%con_d)
    allocate(self%con_kind(m + self%n_eq), self%con_a(n, n, m + self%n_eq), self%con_b(n, m + self%n_eq), &
             self%con_d(m + self%n_eq))
    self%con_kind = con_linear
    self%con_a = 0.0_dp
    self%con_b = 0.0_dp
    self%con_d = 0.0_dp
    self%xl = [(-huge(1.0_dp), i=1, n)]
    self%xu = [(huge(1.0_dp), i=1, n)]
    self%n_bounds = 0
    self%bound_var = [integer ::]
    call self%reset_counters()
  end subroutine init_problem

  !> g_i = b^T x - d <= 0   (P4)
  subroutine set_linear_constraint(self, i, b, d)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: b(:), d
    self%con_kind(i) = con_linear
    self%con_a(:, :, i) = 0.0_dp
    self%con_b(:, i) = b
    self%con_d(i) = d
  end subroutine set_linear_constraint

  !> Linear inequalities as matrices (P4): B^T x - c <= 0, B is n x k; they
  !> become constraints first..first+k-1.
  subroutine set_linear_inequalities(self, bmat, c, first)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: bmat(:, :), c(:)
    integer, intent(in) :: first
    integer :: j
    do j = 1, size(c)
      call self%set_linear_constraint(first + j - 1, bmat(:, j), c(j))
    end do
  end subroutine set_linear_inequalities

  !> g_i = 1/2 x^T A x + b^T x - d <= 0   (B3)
  subroutine set_quadratic_constraint(self, i, a, b, d)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: a(:, :), b(:), d
    self%con_kind(i) = con_quadratic
    self%con_a(:, :, i) = 0.5_dp*(a + transpose(a))
    self%con_b(:, i) = b
    self%con_d(i) = d
  end subroutine set_quadratic_constraint

  !> g_i is computed by the type's `general_constraint` procedure.
  subroutine set_general_constraint(self, i)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    self%con_kind(i) = con_general
    self%con_a(:, :, i) = 0.0_dp
    self%con_b(:, i) = 0.0_dp
    self%con_d(i) = 0.0_dp
  end subroutine set_general_constraint

  !> h = D^T x - e = 0   (P5); D is n x n_eq (all equalities linear).
  subroutine set_linear_equalities(self, d, e)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: d(:, :), e(:)
    integer :: j
    do j = 1, size(e)
      call self%set_linear_constraint(self%m + j, d(:, j), e(j))
    end do
  end subroutine set_linear_equalities

  !> Simple bounds lower <= x <= upper (|value| >= 1e30: none), once, after
  !> the other constraints are set.  Each finite bound is numbered as a
  !> linear inequality with a unit gradient after the inequalities given to
  !> init_problem (m grows by their number, so equality j stays m + j), for
  !> the output (value, multiplier, working set); the optimizer handles it as
  !> a bound: an active bound holds its variable (bound_var) in the step,
  !> and no trial point leaves the box, so F is never evaluated outside it.
  subroutine set_bounds(self, lower, upper)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: lower(:), upper(:)
    integer, allocatable :: kind(:)
    real(dp), allocatable :: a(:, :, :), b(:, :), d(:)
    integer :: j, k, nb, m0, mt0
    real(dp), parameter :: none = 1.0e30_dp
    m0 = self%m
    mt0 = self%m + self%n_eq
    nb = count(lower > -none) + count(upper < none)
    call move_alloc(self%con_kind, kind)
    call move_alloc(self%con_a, a)
    call move_alloc(self%con_b, b)
    call move_alloc(self%con_d, d)
    allocate(self%con_kind(mt0 + nb), self%con_a(self%n, self%n, mt0 + nb), self%con_b(self%n, mt0 + nb), &
             self%con_d(mt0 + nb))
    self%con_kind(1:m0) = kind(1:m0)
    self%con_a(:, :, 1:m0) = a(:, :, 1:m0)
    self%con_b(:, 1:m0) = b(:, 1:m0)
    self%con_d(1:m0) = d(1:m0)
    self%con_kind(m0 + nb + 1:) = kind(m0 + 1:)
    self%con_a(:, :, m0 + nb + 1:) = a(:, :, m0 + 1:)
    self%con_b(:, m0 + nb + 1:) = b(:, m0 + 1:)
    self%con_d(m0 + nb + 1:) = d(m0 + 1:)
    self%m = m0 + nb
    self%n_bounds = nb
    if (allocated(self%bound_var)) deallocate(self%bound_var)
    allocate(self%bound_var(nb))
    k = m0
    do j = 1, self%n
      self%xl(j) = merge(lower(j), -huge(1.0_dp), lower(j) > -none)
      self%xu(j) = merge(upper(j), huge(1.0_dp), upper(j) < none)
      if (lower(j) > -none) then                    ! lower - x <= 0
        k = k + 1
        self%bound_var(k - m0) = -j
        call self%set_linear_constraint(k, unit(j, -1.0_dp), -lower(j))
      end if
      if (upper(j) < none) then                     ! x - upper <= 0
        k = k + 1
        self%bound_var(k - m0) = j
        call self%set_linear_constraint(k, unit(j, 1.0_dp), upper(j))
      end if
    end do
  contains
    pure function unit(i, v) result(e)
      integer, intent(in) :: i
      real(dp), intent(in) :: v
      real(dp) :: e(self%n)
      e = 0.0_dp
      e(i) = v
    end function unit
  end subroutine set_bounds

  !> x clipped into [xl, xu].
  pure function project_to_bounds(self, x) result(p)
    class(opt_problem_t), intent(in) :: self
    real(dp), intent(in) :: x(:)
    real(dp) :: p(size(x))
    p = min(max(x, self%xl), self%xu)
  end function project_to_bounds

  !> Equality j: h_j = 1/2 x^T A x + b^T x - e = 0 (constraint m + j).
  subroutine set_quadratic_equality(self, j, a, b, e)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: j
    real(dp), intent(in) :: a(:, :), b(:), e
    call self%set_quadratic_constraint(self%m + j, a, b, e)
  end subroutine set_quadratic_equality

  !> Equality j: h_j from `general_constraint(m_own + j, ...)` (user_index:
  !> m_own the inequalities given to init_problem, bounds not counted).
  subroutine set_general_equality(self, j)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: j
    call self%set_general_constraint(self%m + j)
  end subroutine set_general_equality

  logical pure function is_least_squares(self)
    class(opt_problem_t), intent(in) :: self
    is_least_squares = self%n_residuals > 0
  end function is_least_squares

  !> Inequalities plus equalities.
  integer pure function n_constraints(self)
    class(opt_problem_t), intent(in) :: self
    n_constraints = self%m + self%n_eq
  end function n_constraints

  subroutine reset_counters(self)
    class(opt_problem_t), intent(inout) :: self
    self%count = opt_counters_t()
  end subroutine reset_counters

  ! ================================================================ user-side defaults

  subroutine residuals_not_provided(self, x, phi, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    phi = 0.0_dp
    if (.false.) phi(1) = x(1)
    call err%set('problem '//self%name, 'n_residuals > 0 but the type does not override `residuals`')
  end subroutine residuals_not_provided

  !> Forward-difference Jacobian J(n, p), column i = grad phi_i; `phi` = phi(x).
  subroutine fd_jacobian(self, x, phi, jac, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), phi(:)
    real(dp), intent(out) :: jac(:, :)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: xp(:), php(:)
    real(dp) :: h
    integer :: j
    allocate(xp(size(x)), php(size(phi)))
    jac = 0.0_dp
    do j = 1, size(x)
      xp = x
      h = fd_step(self%fd_rel_step, x(j))
      xp(j) = x(j) + h
      h = xp(j) - x(j)
      call self%residuals(xp, php, err)
      self%count%fd_analyses = self%count%fd_analyses + 1
      if (err%failed()) then
        call err%add_context('forward-difference Jacobian, variable '//str(j))
        return
      end if
      jac(j, :) = (php - phi)/h
    end do
  end subroutine fd_jacobian

  !> F = phi^T phi (B1).
  subroutine objective_from_residuals(self, x, f, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: phi(:)
    f = 0.0_dp
    if (self%n_residuals <= 0) then
      call err%set('problem '//self%name, 'the type overrides neither `objective` nor `residuals`')
      return
    end if
    allocate(phi(self%n_residuals))
    call self%residuals(x, phi, err)
    if (err%failed()) return
    f = sum(phi**2)
  end subroutine objective_from_residuals

  !> Forward-difference gradient of a general objective; `f` = F(x).
  subroutine fd_gradient(self, x, f, grad, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    call forward_gradient(self, 0, x, f, grad, err)
  end subroutine fd_gradient

  !> Hessian of F by central second differences of F (step eps^(1/4), error
  !> O(h^2) + O(eps/h^2) ~ 1e-8 relative); 2n^2 objective evaluations.
  subroutine fd_hessian(self, x, hess, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    call central_hessian(self, 0, x, hess, err)
  end subroutine fd_hessian

  !> The number constraint i (inequalities, bounds, equalities) has for the
  !> procedures a type overrides (general_constraint and its derivatives):
  !> the user's own inequalities keep theirs, equality j is m_own + j with
  !> m_own = m - n_bounds, so adding bounds does not renumber the equalities.
  pure integer function user_index(self, i) result(k)
    class(opt_problem_t), intent(in) :: self
    integer, intent(in) :: i
    k = merge(i - self%n_bounds, i, i > self%m)
  end function user_index

  subroutine general_constraint_not_provided(self, i, x, g, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = 0.0_dp
    if (.false.) g = x(1)
    call err%set('problem '//self%name, 'constraint '//str(i)// &
                 ' is general but the type does not override `general_constraint`')
  end subroutine general_constraint_not_provided

  !> Forward-difference gradient of general constraint i; `g` = g_i(x).
  subroutine fd_constraint_gradient(self, i, x, g, grad, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:), g
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    call forward_gradient(self, i, x, g, grad, err)
  end subroutine fd_constraint_gradient

  !> Hessian of general constraint i by central second differences.
  subroutine fd_constraint_hessian(self, i, x, hess, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    call central_hessian(self, i, x, hess, err)
  end subroutine fd_constraint_hessian

  !> Central second differences of F (which = 0) or of general constraint `which`.
  subroutine central_hessian(self, which, x, hess, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: which
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    real(dp), parameter :: rel = 1.220703125e-4_dp   ! eps^(1/4)
    real(dp), allocatable :: h(:), xs(:)
    real(dp) :: f0, fpp, fpm, fmp, fmm, fp, fm
    integer :: i, j, n
    n = size(x)
    allocate(h(n), xs(n))
    hess = 0.0_dp
    do i = 1, n
      h(i) = fd_step(rel, x(i))
    end do
    call scalar_value(self, which, x, f0, err)
    do i = 1, n
      xs = x
      xs(i) = x(i) + h(i)
      call scalar_value(self, which, xs, fp, err)
      xs(i) = x(i) - h(i)
      call scalar_value(self, which, xs, fm, err)
      if (err%failed()) return
      hess(i, i) = (fp - 2.0_dp*f0 + fm)/h(i)**2
      do j = 1, i - 1
        xs = x
        xs(i) = x(i) + h(i)
        xs(j) = x(j) + h(j)
        call scalar_value(self, which, xs, fpp, err)
        xs(j) = x(j) - h(j)
        call scalar_value(self, which, xs, fpm, err)
        xs(i) = x(i) - h(i)
        call scalar_value(self, which, xs, fmm, err)
        xs(j) = x(j) + h(j)
        call scalar_value(self, which, xs, fmp, err)
        if (err%failed()) return
        hess(i, j) = (fpp - fpm - fmp + fmm)/(4.0_dp*h(i)*h(j))
        hess(j, i) = hess(i, j)
      end do
    end do
  end subroutine central_hessian

  !> Forward-difference gradient of F (which = 0) or of general constraint
  !> `which`; v0 = the value at x.  Step h_j = fd_rel_step max(|x_j|, 1),
  !> taken as the representable difference (x_j + h) - x_j.
  subroutine forward_gradient(self, which, x, v0, grad, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: which
    real(dp), intent(in) :: x(:), v0
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: xp(:)
    real(dp) :: h, vp
    integer :: j
    allocate(xp(size(x)))
    grad = 0.0_dp
    do j = 1, size(x)
      xp = x
      h = fd_step(self%fd_rel_step, x(j))
      xp(j) = x(j) + h
      h = xp(j) - x(j)
      call scalar_value(self, which, xp, vp, err)
      if (err%failed()) then
        if (which == 0) call err%add_context('forward-difference gradient, variable '//str(j))
        return
      end if
      grad(j) = (vp - v0)/h
    end do
  end subroutine forward_gradient

  !> F (which = 0) or general constraint `which` at x, counted as a
  !> finite-difference evaluation; does nothing once err is set.
  subroutine scalar_value(self, which, x, v, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: which
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: v
    type(error_t), intent(inout) :: err
    v = 0.0_dp
    if (err%failed()) return
    if (which == 0) then
      call self%objective(x, v, err)
      self%count%fd_analyses = self%count%fd_analyses + 1
    else
      call self%general_constraint(which, x, v, err)
      self%count%fd_constraint_evals = self%count%fd_constraint_evals + 1
    end if
  end subroutine scalar_value

  pure real(dp) function fd_step(rel, xj)
    real(dp), intent(in) :: rel, xj
    fd_step = rel*max(abs(xj), 1.0_dp)
  end function fd_step

  ! ================================================================ solver side (counted)

  !> One analysis: F(x), and phi(x) for a sum of squares.  NF += 1.
  subroutine analyse(self, x, f, phi, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    real(dp), intent(out) :: phi(:)    !< size n_residuals (0 for a general objective)
    type(error_t), intent(inout) :: err
    self%count%analyses = self%count%analyses + 1
    f = 0.0_dp
    if (self%n_residuals > 0) then
      call self%residuals(x, phi, err)
      if (.not. err%failed()) f = sum(phi**2)
    else
      call self%objective(x, f, err)
    end if
    if (err%failed()) call err%add_context('analysis '//str(self%count%analyses))
  end subroutine analyse

  !> grad F at x (f, phi from `analyse` at the same x); for a sum of squares
  !> also J(n, p), and grad F = 2 J phi (B4).
  subroutine objective_derivatives(self, x, f, phi, grad, jac, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f, phi(:)
    real(dp), intent(out) :: grad(:)
    real(dp), intent(out) :: jac(:, :)   !< (n, n_residuals)
    type(error_t), intent(inout) :: err
    self%count%gradients = self%count%gradients + 1
    if (self%n_residuals > 0) then
      self%count%jacobians = self%count%jacobians + 1
      call self%jacobian(x, phi, jac, err)
      grad = 2.0_dp*matmul(jac, phi)
    else
      call self%gradient(x, f, grad, err)
    end if
    if (err%failed()) call err%add_context('objective derivatives')
  end subroutine objective_derivatives

  subroutine objective_hessian(self, x, hess, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    self%count%hessians = self%count%hessians + 1
    call self%hessian(x, hess, err)
    if (err%failed()) call err%add_context('objective Hessian')
  end subroutine objective_hessian

  !> g(1:m) inequality values and g(m+1:m+n_eq) equality residuals at x.
  subroutine constraint_values(self, x, g, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g(:)
    type(error_t), intent(inout) :: err
    integer :: i
    self%count%constraint_evals = self%count%constraint_evals + 1
    g = 0.0_dp
    do i = 1, self%m + self%n_eq
      select case (self%con_kind(i))
      case (con_linear)
        g(i) = dot_product(self%con_b(:, i), x) - self%con_d(i)
      case (con_quadratic)
        g(i) = 0.5_dp*dot_product(x, matmul(self%con_a(:, :, i), x)) + dot_product(self%con_b(:, i), x) &
               - self%con_d(i)
      case (con_general)
        call self%general_constraint(self%user_index(i), x, g(i), err)
        if (err%failed()) then
          call err%add_context('constraint '//str(i))
          return
        end if
      end select
    end do
  end subroutine constraint_values

  !> One constraint (inequality i <= m, or equality i - m) at x.
  subroutine constraint_value(self, i, x, g, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    self%count%constraint_evals = self%count%constraint_evals + 1
    g = 0.0_dp
    select case (self%con_kind(i))
    case (con_linear)
      g = dot_product(self%con_b(:, i), x) - self%con_d(i)
    case (con_quadratic)
      g = 0.5_dp*dot_product(x, matmul(self%con_a(:, :, i), x)) + dot_product(self%con_b(:, i), x) - self%con_d(i)
    case (con_general)
      call self%general_constraint(self%user_index(i), x, g, err)
      if (err%failed()) call err%add_context('constraint '//str(i))
    end select
  end subroutine constraint_value

  !> Gradients (n, m + n_eq) at x, given the values g at x (for differences).
  subroutine constraint_gradients(self, x, g, dg, err)
    class(opt_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), g(:)
    real(dp), intent(out) :: dg(:, :)
    type(error_t), intent(inout) :: err
    integer :: i
    logical :: any_general
    dg = 0.0_dp
    any_general = .false.
    do i = 1, self%m + self%n_eq
      select case (self%con_kind(i))
      case (con_linear)
        dg(:, i) = self%con_b(:, i)
      case (con_quadratic)
        dg(:, i) = matmul(self%con_a(:, :, i), x) + self%con_b(:, i)
      case (con_general)
        any_general = .true.
        call self%general_constraint_gradient(self%user_index(i), x, g(i), dg(:, i), err)
        if (err%failed()) then
          call err%add_context('gradient of constraint '//str(i))
          return
        end if
      end select
    end do
    if (any_general) self%count%constraint_gradients = self%count%constraint_gradients + 1
  end subroutine constraint_gradients

  !> Hessian of constraint i at x: A_i for quadratic, 0 for linear, the
  !> type's (or finite-difference) Hessian for general constraints.
  subroutine constraint_hessian(self, i, x, hess, err)
    class(opt_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    hess = 0.0_dp
    select case (self%con_kind(i))
    case (con_quadratic)
      hess = self%con_a(:, :, i)
    case (con_general)
      self%count%constraint_hessians = self%count%constraint_hessians + 1
      call self%general_constraint_hessian(self%user_index(i), x, hess, err)
      if (err%failed()) call err%add_context('Hessian of constraint '//str(i))
    end select
  end subroutine constraint_hessian
end module optim_problem
