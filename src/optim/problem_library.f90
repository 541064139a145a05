!> Built-in optimization problems, selected by name (deck: &optimize problem=).
!>
!> Each comes with a default start and, where the literature gives one, its
!> known optimum.  Sources: Rosen & Suzuki (CACM 8, 1965) as printed in P
!> (Table I; doc/optimization.md); Moré, Garbow & Hillstrom, ACM TOMS 7 (1981) 17-41
!> (MGH); Hock & Schittkowski, Test Examples for Nonlinear Programming Codes,
!> LNEMS 187 (1981) (HS); B's four-bar (§10.3, module fourbar_path); and three
!> small constructed problems for the bad cases of doc/optimization.md, built
!> by Rosen & Suzuki's recipe (choose x* and lambda*, then the data) so their
!> optima are known exactly.
module problem_library
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower
  use optim_problem, only: opt_problem_t
  use fourbar_path, only: fourbar_path_t, paper_start, table3_design, offset_target
  implicit none
  private
  public :: problem_info_t, create_problem, problem_names
  public :: quadratic_problem_t, test_lsq_t

  character(len=*), parameter :: problem_names = "'rosen_suzuki', 'fourbar_path', 'fourbar_path_13', " // &
    "'fourbar_path_offset', 'fourbar_path_13_offset', " // &
    "'rosenbrock', 'helical_valley', 'powell_singular', 'bard', 'hs15', 'hs21', 'hs28', 'hs35', 'hs65', " // &
    "'general_convex', 'three_circles', 'potter_cycling'"

  type :: problem_info_t
    character(len=:), allocatable :: name
    character(len=:), allocatable :: title
    character(len=:), allocatable :: source
    character(len=:), allocatable :: method      !< the method the problem is meant for
    real(dp), allocatable :: x0(:)               !< default start
    logical :: has_optimum = .false.
    real(dp), allocatable :: x_star(:)
    real(dp) :: f_star = 0.0_dp
    real(dp), allocatable :: lambda_star(:)      !< multipliers at x* (where known)
  end type problem_info_t

  !> F = 1/2 x^T Q x + q^T x + c, analytic gradient and Hessian.
  type, extends(opt_problem_t) :: quadratic_problem_t
    real(dp), allocatable :: q(:, :), lin(:)
    real(dp) :: const = 0.0_dp
  contains
    procedure :: objective => quad_objective
    procedure :: gradient => quad_gradient
    procedure :: hessian => quad_hessian
  end type quadratic_problem_t

  integer, parameter :: p_rosenbrock = 1, p_helical = 2, p_powell = 3, p_bard = 4, p_hs15 = 5, p_hs28 = 6, &
                        p_hs65 = 7, p_general_convex = 8, p_three_circles = 9, p_potter = 10

  !> Sum-of-squares test problems with analytic Jacobians.
  type, extends(opt_problem_t) :: test_lsq_t
    integer :: which = 0
    real(dp) :: target(2) = 0.0_dp     !< p of the distance problems |x - p|^2
  contains
    procedure :: residuals => lsq_residuals
    procedure :: jacobian => lsq_jacobian
    procedure :: general_constraint => lsq_general_constraint
    procedure :: general_constraint_gradient => lsq_general_constraint_gradient
  end type test_lsq_t

  real(dp), parameter :: two_pi_ = 6.283185307179586_dp
  real(dp), parameter :: bard_y(15) = [0.14_dp, 0.18_dp, 0.22_dp, 0.25_dp, 0.29_dp, 0.32_dp, 0.35_dp, 0.39_dp, &
                                       0.37_dp, 0.58_dp, 0.73_dp, 0.96_dp, 1.34_dp, 2.10_dp, 4.39_dp]

contains

  !> Allocate and set up the named problem; info gets the default start and
  !> the known optimum.  Unknown names are an input error (code 2).
  subroutine create_problem(name, prob, info, err)
    character(len=*), intent(in) :: name
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    type(error_t), intent(inout) :: err
    info%name = lower(trim(adjustl(name)))
    select case (info%name)
    case ('rosen_suzuki', 'hs21', 'hs35')
      call create_quadratic(info, prob)
    case ('fourbar_path', 'fourbar_path_13', 'fourbar_path_offset', 'fourbar_path_13_offset')
      call create_fourbar(info, prob)
    case ('rosenbrock', 'helical_valley', 'powell_singular', 'bard', 'hs15', 'hs28', 'hs65', 'general_convex', &
          'three_circles', 'potter_cycling')
      call create_lsq(info, prob)
    case default
      call err%set('problem_library', 'unknown problem '''//trim(name)//'''; expected one of '//problem_names, &
                   code=2)
    end select
  end subroutine create_problem

  !> Quadratic objectives with linear or quadratic constraints (Rosen-Suzuki, HS 21, HS 35).
  subroutine create_quadratic(info, prob)
    type(problem_info_t), intent(inout) :: info
    class(opt_problem_t), allocatable, intent(inout) :: prob
    type(quadratic_problem_t), allocatable :: qp
    real(dp) :: a(4, 4)
    integer :: i
    allocate(qp)
    select case (info%name)
    case ('rosen_suzuki')
      call qp%init_problem('rosen_suzuki', 4, 0, 3)
      qp%q = diag([2.0_dp, 2.0_dp, 4.0_dp, 2.0_dp])
      qp%lin = [-5.0_dp, -5.0_dp, -21.0_dp, 7.0_dp]
      a = diag([2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp])
      call qp%set_quadratic_constraint(1, a, [1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp], 8.0_dp)
      a = diag([2.0_dp, 4.0_dp, 2.0_dp, 4.0_dp])
      call qp%set_quadratic_constraint(2, a, [-1.0_dp, 0.0_dp, 0.0_dp, -1.0_dp], 10.0_dp)
      a = diag([4.0_dp, 2.0_dp, 2.0_dp, 0.0_dp])
      call qp%set_quadratic_constraint(3, a, [2.0_dp, -1.0_dp, 0.0_dp, -1.0_dp], 5.0_dp)
      call set_info(info, 'Rosen-Suzuki: quadratic F, 3 quadratic constraints (P, Table I)', &
                    'Rosen & Suzuki, CACM 8 (1965) 113; HS 43', 'gnlc', [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], &
                    [0.0_dp, 1.0_dp, 2.0_dp, -1.0_dp], -44.0_dp, [1.0_dp, 0.0_dp, 2.0_dp])
    case ('hs21')
      call qp%init_problem('hs21', 2, 0, 5)
      qp%q = diag([0.02_dp, 2.0_dp])
      qp%lin = [0.0_dp, 0.0_dp]
      qp%const = -100.0_dp
      call qp%set_linear_constraint(1, [-10.0_dp, 1.0_dp], -10.0_dp)              ! 10 x1 - x2 >= 10
      call qp%set_linear_constraint(2, [-1.0_dp, 0.0_dp], -2.0_dp)                ! x1 >= 2
      call qp%set_linear_constraint(3, [1.0_dp, 0.0_dp], 50.0_dp)                 ! x1 <= 50
      call qp%set_linear_constraint(4, [0.0_dp, -1.0_dp], 50.0_dp)                ! x2 >= -50
      call qp%set_linear_constraint(5, [0.0_dp, 1.0_dp], 50.0_dp)                 ! x2 <= 50
      ! HS's start (-1, -1) is infeasible; a feasible one for the step-back methods
      call set_info(info, 'quadratic F, linear constraints (bounds)', 'HS 21', 'gauss_constrained', &
                    [10.0_dp, 10.0_dp], [2.0_dp, 0.0_dp], -99.96_dp, [0.0_dp, 0.04_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    case ('hs35')
      call qp%init_problem('hs35', 3, 0, 4)
      qp%q = reshape([4.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 4.0_dp, 0.0_dp, 2.0_dp, 0.0_dp, 2.0_dp], [3, 3])
      qp%lin = [-8.0_dp, -6.0_dp, -4.0_dp]
      qp%const = 9.0_dp
      call qp%set_linear_constraint(1, [1.0_dp, 1.0_dp, 2.0_dp], 3.0_dp)
      do i = 1, 3
        call qp%set_linear_constraint(1 + i, unit_vector(3, i, -1.0_dp), 0.0_dp)
      end do
      call set_info(info, 'Beale: quadratic F, one linear constraint and x >= 0', 'HS 35', 'gauss_constrained', &
                    [0.5_dp, 0.5_dp, 0.5_dp], [4.0_dp/3.0_dp, 7.0_dp/9.0_dp, 4.0_dp/9.0_dp], 1.0_dp/9.0_dp, &
                    [2.0_dp/9.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    end select
    call move_alloc(qp, prob)
  end subroutine create_quadratic

  !> B's four-bar path generation, with the paper's target or one outside the feasible set.
  subroutine create_fourbar(info, prob)
    type(problem_info_t), intent(inout) :: info
    class(opt_problem_t), allocatable, intent(inout) :: prob
    type(fourbar_path_t), allocatable :: fp
    integer :: i
    allocate(fp)
    select case (info%name)
    case ('fourbar_path', 'fourbar_path_13')
      if (info%name == 'fourbar_path') then
        call fp%setup(2)
        call set_info(info, 'four-bar path generation, 10 variables, 14 constraints (B, Table 3)', &
                      'Boston et al. (B); target path from the Table 3 design', 'gnlc', paper_start, &
                      table3_design, 0.0_dp, [(0.0_dp, i=1, 14)])
      else
        call fp%setup(1)
        call set_info(info, 'four-bar path generation, 13 constraints: one crank-pivot circle (paper A)', &
                      'paper A (ASCE 1984); target path from the Table 3 design', 'gnlc', paper_start, &
                      table3_design, 0.0_dp, [(0.0_dp, i=1, 13)])
      end if
    case ('fourbar_path_offset', 'fourbar_path_13_offset')
      ! target just outside the feasible set: F* > 0, no closed-form optimum
      if (info%name == 'fourbar_path_offset') then
        call fp%setup(2, target=offset_target)
        fp%name = 'fourbar_path_offset'
        call set_info(info, 'four-bar path generation, 14 constraints, unreachable target path', &
                      'Boston et al. (B); target path from a four-bar outside the feasible set', 'gnlc', paper_start)
      else
        call fp%setup(1, target=offset_target)
        fp%name = 'fourbar_path_13_offset'
        call set_info(info, 'four-bar path generation, 13 constraints, unreachable target path', &
                      'paper A; target path from a four-bar outside the feasible set', 'gnlc', paper_start)
      end if
    end select
    call move_alloc(fp, prob)
  end subroutine create_fourbar

  !> The sums of squares with analytic Jacobians (test_lsq_t): More, Garbow
  !> & Hillstrom's unconstrained problems, Hock-Schittkowski problems written
  !> as least squares with constraints, and the constructed problems with
  !> exactly known optima (Rosen & Suzuki's recipe).
  subroutine create_lsq(info, prob)
    type(problem_info_t), intent(inout) :: info
    class(opt_problem_t), allocatable, intent(inout) :: prob
    type(test_lsq_t), allocatable :: lp
    real(dp) :: e(2, 2), s3
    integer :: i
    allocate(lp)
    select case (info%name)
    ! ---- More, Garbow & Hillstrom, unconstrained
    case ('rosenbrock')
      lp%which = p_rosenbrock
      call lp%init_problem('rosenbrock', 2, 2, 0)
      call set_info(info, 'Rosenbrock as least squares, unconstrained', 'MGH problem 1', 'gauss', &
                    [-1.2_dp, 1.0_dp], [1.0_dp, 1.0_dp], 0.0_dp)
    case ('helical_valley')
      lp%which = p_helical
      call lp%init_problem('helical_valley', 3, 3, 0)
      call set_info(info, 'helical valley, unconstrained', 'MGH problem 7', 'gauss', &
                    [-1.0_dp, 0.0_dp, 0.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 0.0_dp)
    case ('powell_singular')
      lp%which = p_powell
      call lp%init_problem('powell_singular', 4, 4, 0)
      call set_info(info, 'Powell singular function: J J^T singular at x* (rank 2)', 'MGH problem 13', 'gauss', &
                    [3.0_dp, -1.0_dp, 0.0_dp, 1.0_dp], [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], 0.0_dp)
    case ('bard')
      lp%which = p_bard
      call lp%init_problem('bard', 3, 15, 0)
      call set_info(info, 'Bard data fit, 15 residuals, non-zero residual at x*', 'MGH problem 8', 'gauss', &
                    [1.0_dp, 1.0_dp, 1.0_dp], [0.08241056_dp, 1.133036_dp, 2.343695_dp], 8.21487e-3_dp)
    ! ---- Hock-Schittkowski as least squares with constraints
    case ('hs15')
      lp%which = p_hs15
      call lp%init_problem('hs15', 2, 2, 3)
      call lp%set_quadratic_constraint(1, reshape([0.0_dp, -1.0_dp, -1.0_dp, 0.0_dp], [2, 2]), &
                                       [0.0_dp, 0.0_dp], -1.0_dp)                 ! 1 - x1 x2 <= 0
      call lp%set_quadratic_constraint(2, reshape([0.0_dp, 0.0_dp, 0.0_dp, -2.0_dp], [2, 2]), &
                                       [-1.0_dp, 0.0_dp], 0.0_dp)                 ! -x1 - x2^2 <= 0
      call lp%set_linear_constraint(3, [1.0_dp, 0.0_dp], 0.5_dp)                   ! x1 <= 1/2
      call set_info(info, 'Rosenbrock with non-convex quadratic constraints; infeasible start', 'HS 15', &
                    'gnlc_ns', [-2.0_dp, 1.0_dp], [0.5_dp, 2.0_dp], 306.5_dp, [700.0_dp, 0.0_dp, 1751.0_dp])
    case ('hs28')
      lp%which = p_hs28
      call lp%init_problem('hs28', 3, 2, 0, n_eq=1)
      call lp%set_linear_equalities(reshape([1.0_dp, 2.0_dp, 3.0_dp], [3, 1]), [1.0_dp])
      call set_info(info, 'two residuals, three variables: J J^T singular everywhere; one linear equality', &
                    'HS 28', 'gauss_constrained', [-4.0_dp, 1.0_dp, 1.0_dp], [0.5_dp, -0.5_dp, 0.5_dp], 0.0_dp, &
                    [0.0_dp])
    case ('hs65')
      lp%which = p_hs65
      call lp%init_problem('hs65', 3, 3, 7)
      call lp%set_quadratic_constraint(1, diag([2.0_dp, 2.0_dp, 2.0_dp]), [0.0_dp, 0.0_dp, 0.0_dp], 48.0_dp)
      do i = 1, 3
        call lp%set_linear_constraint(2*i, unit_vector(3, i, -1.0_dp), merge(5.0_dp, 4.5_dp, i == 3))
        call lp%set_linear_constraint(2*i + 1, unit_vector(3, i, 1.0_dp), merge(5.0_dp, 4.5_dp, i == 3))
      end do
      ! HS prints x* = (3.650461821, 3.65046168, 4.6204170507), good to ~5e-7 only
      ! (x1 = x2 by symmetry); stored here: the KKT point to 11 digits
      call set_info(info, 'sum of squares in a ball and a box; infeasible start', 'HS 65', 'gnlc_ns', &
                    [-5.0_dp, 5.0_dp, 0.0_dp], [3.65046172521_dp, 3.65046172521_dp, 4.62041755532_dp], &
                    0.9535288567_dp, [0.0821532773_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp])
    ! ---- constructed, exactly known optima
    case ('general_convex')
      lp%which = p_general_convex
      lp%target = [2.0_dp, 2.5_dp]
      call lp%init_problem('general_convex', 2, 2, 2)
      call lp%set_general_constraint(1)
      call lp%set_general_constraint(2)
      call set_info(info, 'distance to (2, 2.5) with convex exp and quartic constraints (constructed)', &
                    'constructed by the Rosen-Suzuki recipe: x* = (1, 1), lambda* = (1, 1/2)', 'gnlc_general', &
                    [0.0_dp, 0.0_dp], [1.0_dp, 1.0_dp], 3.25_dp, [1.0_dp, 0.5_dp])
    case ('three_circles')
      lp%which = p_three_circles
      lp%target = [1.0_dp, 5.0_dp]
      call lp%init_problem('three_circles', 2, 2, 3)
      e = diag([2.0_dp, 2.0_dp])
      call lp%set_quadratic_constraint(1, e, [0.0_dp, 0.0_dp], 4.0_dp)            ! |x - (0,0)|^2 <= 4
      call lp%set_quadratic_constraint(2, e, [-4.0_dp, 0.0_dp], 0.0_dp)           ! |x - (2,0)|^2 <= 4
      call lp%set_quadratic_constraint(3, e, [-2.0_dp, 0.0_dp], 3.0_dp)           ! |x - (1,0)|^2 <= 4
      s3 = sqrt(3.0_dp)
      call set_info(info, 'nearest point of three discs to (1, 5); B11 has no solution from the start', &
                    'constructed: x* = (1, sqrt 3), lambda1 = lambda2 = (5 - sqrt 3)/(2 sqrt 3)', 'gnlc_ns', &
                    [1.0_dp, 5.0_dp], [1.0_dp, s3], (5.0_dp - s3)**2, &
                    [(5.0_dp - s3)/(2.0_dp*s3), (5.0_dp - s3)/(2.0_dp*s3), 0.0_dp])
    case ('potter_cycling')
      lp%which = p_potter
      lp%target = [0.1_dp, -0.5_dp]
      call lp%init_problem('potter_cycling', 2, 2, 2)
      call lp%set_quadratic_constraint(1, diag([-2.0_dp, -2.0_dp]), [0.0_dp, 0.0_dp], -1.0_dp)  ! |x| >= 1
      call lp%set_linear_constraint(2, [0.0_dp, -1.0_dp], 0.5_dp)                                ! x2 >= -1/2
      s3 = sqrt(3.0_dp)
      call set_info(info, 'nearest point to (0.1, -0.5) outside the unit disc with x2 >= -1/2 (non-convex)', &
                    'constructed to trigger the step-back cycling of Potter (P, 9.5 item 3)', 'gnlc', &
                    [0.0_dp, 1.0_dp], [0.5_dp*s3, -0.5_dp], (0.5_dp*s3 - 0.1_dp)**2, &
                    [1.0_dp - 0.2_dp/s3, 1.0_dp - 0.2_dp/s3])
    end select
    call move_alloc(lp, prob)
  end subroutine create_lsq

  subroutine set_info(info, title, source, method, x0, x_star, f_star, lambda_star)
    type(problem_info_t), intent(inout) :: info
    character(len=*), intent(in) :: title, source, method
    real(dp), intent(in) :: x0(:)
    real(dp), intent(in), optional :: x_star(:), f_star, lambda_star(:)
    info%title = title
    info%source = source
    info%method = method
    info%x0 = x0
    info%has_optimum = present(x_star) .and. present(f_star)
    if (present(x_star)) info%x_star = x_star
    if (present(f_star)) info%f_star = f_star
    if (present(lambda_star)) info%lambda_star = lambda_star
  end subroutine set_info

  pure function diag(v) result(a)
    real(dp), intent(in) :: v(:)
    real(dp) :: a(size(v), size(v))
    integer :: i
    a = 0.0_dp
    do i = 1, size(v)
      a(i, i) = v(i)
    end do
  end function diag

  pure function unit_vector(n, i, v) result(e)
    integer, intent(in) :: n, i
    real(dp), intent(in) :: v
    real(dp) :: e(n)
    e = 0.0_dp
    e(i) = v
  end function unit_vector

  ! ================================================================ quadratic objective

  subroutine quad_objective(self, x, f, err)
    class(quadratic_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    f = 0.5_dp*dot_product(x, matmul(self%q, x)) + dot_product(self%lin, x) + self%const
    if (.false.) call err%clear()
  end subroutine quad_objective

  subroutine quad_gradient(self, x, f, grad, err)
    class(quadratic_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    grad = matmul(self%q, x) + self%lin
    if (.false.) grad(1) = f
    if (.false.) call err%clear()
  end subroutine quad_gradient

  subroutine quad_hessian(self, x, hess, err)
    class(quadratic_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    hess = self%q
    if (.false.) hess(1, 1) = x(1)
    if (.false.) call err%clear()
  end subroutine quad_hessian

  ! ================================================================ sums of squares

  subroutine lsq_residuals(self, x, phi, err)
    class(test_lsq_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    integer :: i
    real(dp) :: u, v, w
    select case (self%which)
    case (p_rosenbrock, p_hs15)
      phi = [10.0_dp*(x(2) - x(1)**2), 1.0_dp - x(1)]
    case (p_helical)
      phi = [10.0_dp*(x(3) - 10.0_dp*helical_theta(x(1), x(2))), 10.0_dp*(norm2(x(1:2)) - 1.0_dp), x(3)]
    case (p_powell)
      phi = [x(1) + 10.0_dp*x(2), sqrt(5.0_dp)*(x(3) - x(4)), (x(2) - 2.0_dp*x(3))**2, &
             sqrt(10.0_dp)*(x(1) - x(4))**2]
    case (p_bard)
      do i = 1, 15
        u = real(i, dp)
        v = real(16 - i, dp)
        w = min(u, v)
        phi(i) = bard_y(i) - (x(1) + u/(v*x(2) + w*x(3)))
      end do
    case (p_hs28)
      phi = [x(1) + x(2), x(2) + x(3)]
    case (p_hs65)
      phi = [x(1) - x(2), (x(1) + x(2) - 10.0_dp)/3.0_dp, x(3) - 5.0_dp]
    case (p_general_convex, p_three_circles, p_potter)
      phi = x(1:2) - self%target
    case default
      phi = 0.0_dp
      call err%set('test_lsq', 'problem not set up')
    end select
  end subroutine lsq_residuals

  !> J(n, p): column i = grad phi_i (P3).
  subroutine lsq_jacobian(self, x, phi, jac, err)
    class(test_lsq_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), phi(:)
    real(dp), intent(out) :: jac(:, :)
    type(error_t), intent(inout) :: err
    integer :: i
    real(dp) :: u, v, w, den, r2
    jac = 0.0_dp
    if (.false.) jac(1, 1) = phi(1)
    select case (self%which)
    case (p_rosenbrock, p_hs15)
      jac(:, 1) = [-20.0_dp*x(1), 10.0_dp]
      jac(:, 2) = [-1.0_dp, 0.0_dp]
    case (p_helical)
      r2 = x(1)**2 + x(2)**2
      jac(:, 1) = [100.0_dp*x(2)/(two_pi_*r2), -100.0_dp*x(1)/(two_pi_*r2), 10.0_dp]
      jac(:, 2) = [10.0_dp*x(1)/sqrt(r2), 10.0_dp*x(2)/sqrt(r2), 0.0_dp]
      jac(:, 3) = [0.0_dp, 0.0_dp, 1.0_dp]
    case (p_powell)
      jac(:, 1) = [1.0_dp, 10.0_dp, 0.0_dp, 0.0_dp]
      jac(:, 2) = [0.0_dp, 0.0_dp, sqrt(5.0_dp), -sqrt(5.0_dp)]
      jac(:, 3) = [0.0_dp, 2.0_dp*(x(2) - 2.0_dp*x(3)), -4.0_dp*(x(2) - 2.0_dp*x(3)), 0.0_dp]
      jac(:, 4) = [2.0_dp*sqrt(10.0_dp)*(x(1) - x(4)), 0.0_dp, 0.0_dp, -2.0_dp*sqrt(10.0_dp)*(x(1) - x(4))]
    case (p_bard)
      do i = 1, 15
        u = real(i, dp)
        v = real(16 - i, dp)
        w = min(u, v)
        den = (v*x(2) + w*x(3))**2
        jac(:, i) = [-1.0_dp, u*v/den, u*w/den]
      end do
    case (p_hs28)
      jac(:, 1) = [1.0_dp, 1.0_dp, 0.0_dp]
      jac(:, 2) = [0.0_dp, 1.0_dp, 1.0_dp]
    case (p_hs65)
      jac(:, 1) = [1.0_dp, -1.0_dp, 0.0_dp]
      jac(:, 2) = [1.0_dp, 1.0_dp, 0.0_dp]/3.0_dp
      jac(:, 3) = [0.0_dp, 0.0_dp, 1.0_dp]
    case (p_general_convex, p_three_circles, p_potter)
      jac(:, 1) = [1.0_dp, 0.0_dp]
      jac(:, 2) = [0.0_dp, 1.0_dp]
    case default
      call err%set('test_lsq', 'problem not set up')
    end select
  end subroutine lsq_jacobian

  !> MGH's theta: (1/2 pi) arctan(x2/x1), plus 1/2 for x1 < 0.
  pure real(dp) function helical_theta(x1, x2)
    real(dp), intent(in) :: x1, x2
    if (x1 > 0.0_dp) then
      helical_theta = atan(x2/x1)/two_pi_
    else if (x1 < 0.0_dp) then
      helical_theta = atan(x2/x1)/two_pi_ + 0.5_dp
    else
      helical_theta = sign(0.25_dp, x2)
    end if
  end function helical_theta

  !> general_convex: g1 = exp(x1 - 1) + x2^2 - 2, g2 = (x1 + x2)^4/16 - 1.
  subroutine lsq_general_constraint(self, i, x, g, err)
    class(test_lsq_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = 0.0_dp
    if (.not. has_general_constraint(self, i, err)) return
    select case (i)
    case (1)
      g = exp(min(x(1) - 1.0_dp, 700.0_dp)) + x(2)**2 - 2.0_dp
    case (2)
      g = (x(1) + x(2))**4/16.0_dp - 1.0_dp
    end select
  end subroutine lsq_general_constraint

  subroutine lsq_general_constraint_gradient(self, i, x, g, grad, err)
    class(test_lsq_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:), g
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    grad = 0.0_dp
    if (.false.) grad(1) = g
    if (.not. has_general_constraint(self, i, err)) return
    select case (i)
    case (1)
      grad = [exp(min(x(1) - 1.0_dp, 700.0_dp)), 2.0_dp*x(2)]
    case (2)
      grad = (x(1) + x(2))**3/4.0_dp
    end select
  end subroutine lsq_general_constraint_gradient

  !> Only general_convex has general constraints: .false. with err set for
  !> constraint i of any other problem.
  logical function has_general_constraint(self, i, err) result(has)
    class(test_lsq_t), intent(in) :: self
    integer, intent(in) :: i
    type(error_t), intent(inout) :: err
    has = self%which == p_general_convex
    if (.not. has) call err%set('test_lsq', 'problem '//self%name//' has no general constraint '//str(i))
  end function has_general_constraint
end module problem_library
