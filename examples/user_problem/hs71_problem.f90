!> An optimization problem of your own, without editing flexmech (doc/optimization.md §10):
!>
!>     make PROBLEM=examples/user_problem/hs71_problem.f90
!>     build/user/flexmech examples/user_problem/hs71.nml -o hs71.out
!>
!> The file defines a module named `user_problems` with the two public
!> procedures below (keep their interfaces exactly); it may define any number
!> of problem types, each extending opt_problem_t.  Here: Hock & Schittkowski
!> problem 71 (LNEMS 187, 1981), a general objective with a general
!> inequality, a quadratic equality and bounds 1 <= x_i <= 5:
!>
!>     min  x1 x4 (x1 + x2 + x3) + x3
!>     s.t. x1 x2 x3 x4 >= 25,  x1^2 + x2^2 + x3^2 + x4^2 = 40,  1 <= x <= 5,
!>
!> x0 = (1, 5, 5, 1), x* = (1, 4.742999643, 3.821149981, 1.379408293), f* = 17.0140173.
!>
!> Numbering: the general inequalities first (here g1), then the simple
!> bounds that set_bounds adds (g2..g9: x1 >= 1, x1 <= 5, x2 >= 1, ...), then
!> the equalities (h1 is constraint 10 in the output's columns).  The
!> procedures below see the general inequality as i = 1; an equality given
!> by a procedure (set_general_equality) arrives as i = m_own + j, m_own the
!> inequalities given to init_problem (here 1): the bounds set_bounds adds do
!> not renumber it (opt_problem_t%user_index).
!> Check the derivatives once with `check_derivatives = T` in &optimize.
module user_problems
  use, intrinsic :: ieee_arithmetic, only: ieee_is_nan
  use kinds, only: dp
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t
  implicit none
  private
  public :: create_user_problem, user_problem_names

  !> Override what the problem can give: objective (here with its gradient
  !> and Hessian) and general constraints; the rest comes from differences.
  type, extends(opt_problem_t) :: hs71_t
  contains
    procedure :: objective => hs71_f
    procedure :: gradient => hs71_grad
    procedure :: hessian => hs71_hess
    procedure :: general_constraint => hs71_g
  end type hs71_t

contains

  subroutine create_user_problem(name, prob, info, found, err)
    character(len=*), intent(in) :: name
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    type(hs71_t), allocatable :: p
    real(dp) :: eye(4, 4)
    integer :: i
    found = name == 'my_hs71'
    if (.not. found) return
    allocate(p)
    ! 4 variables, general objective (0 residuals), 1 general inequality, 1 equality
    call p%init_problem('my_hs71', 4, 0, 1, n_eq=1)
    call p%set_general_constraint(1)                          ! 25 - x1 x2 x3 x4 <= 0
    eye = 0.0_dp
    do i = 1, 4
      eye(i, i) = 2.0_dp                                      ! 1/2 x^T (2 I) x = |x|^2
    end do
    call p%set_quadratic_equality(1, eye, [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp], 40.0_dp)   ! |x|^2 = 40
    ! simple bounds 1 <= x_i <= 5 (+-1e30: none); held as bounds by the optimizer
    call p%set_bounds([1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], [5.0_dp, 5.0_dp, 5.0_dp, 5.0_dp])
    info%title = 'HS 71: general objective and inequality, quadratic equality, bounds'
    info%source = 'Hock & Schittkowski, LNEMS 187 (1981), problem 71 (user problem example)'
    info%method = 'gnlc_general_ns'
    info%x0 = [1.0_dp, 5.0_dp, 5.0_dp, 1.0_dp]
    info%has_optimum = .true.
    info%x_star = [1.0_dp, 4.742999643_dp, 3.821149981_dp, 1.379408293_dp]
    info%f_star = 17.0140173_dp
    call move_alloc(p, prob)
    if (err%failed()) call err%add_context('user problem '//name)   ! an earlier error keeps its origin
  end subroutine create_user_problem

  function user_problem_names() result(names)
    character(len=:), allocatable :: names
    names = '''my_hs71'''
  end function user_problem_names

  subroutine hs71_f(self, x, f, err)
    class(hs71_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    ! a point where the model is undefined is reported, not evaluated
    if (any(ieee_is_nan(x))) call err%set(self%name, 'the design is not a number')
    f = x(1)*x(4)*(x(1) + x(2) + x(3)) + x(3)
  end subroutine hs71_f

  subroutine hs71_grad(self, x, f, grad, err)
    class(hs71_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    ! f = F(x), given for derivatives that reuse it (here none)
    if (ieee_is_nan(f)) call err%set(self%name, 'gradient asked at a point where F is not a number')
    grad = [x(4)*(2.0_dp*x(1) + x(2) + x(3)), x(1)*x(4), x(1)*x(4) + 1.0_dp, x(1)*(x(1) + x(2) + x(3))]
  end subroutine hs71_grad

  subroutine hs71_hess(self, x, hess, err)
    class(hs71_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: hess(:, :)
    type(error_t), intent(inout) :: err
    hess = reshape([2.0_dp*x(4), x(4), x(4), 2.0_dp*x(1) + x(2) + x(3), &
                    x(4), 0.0_dp, 0.0_dp, x(1), &
                    x(4), 0.0_dp, 0.0_dp, x(1), &
                    2.0_dp*x(1) + x(2) + x(3), x(1), x(1), 0.0_dp], [4, 4])
    if (any(ieee_is_nan(hess))) call err%set(self%name, 'Hessian not a number')
  end subroutine hs71_hess

  !> General constraint i (only constraint 1 is general here).
  subroutine hs71_g(self, i, x, g, err)
    class(hs71_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = 25.0_dp - product(x(1:4))
    if (i /= 1) call err%set(self%name, 'constraint '//char(48 + mod(i, 10))//' is not general')
  end subroutine hs71_g
end module user_problems
