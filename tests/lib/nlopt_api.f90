!> NLopt's F77 API (Debian's libnlopt, nlopt.f) behind one explicit interface, for
!> the benchmarks that compare the Gauss optimizers with NLopt (bench_optimizers,
!> bench_design). Only the benchmarks link libnlopt; nothing here calls it.
module nlopt_api
  use kinds, only: dp, i8
  implicit none
  private
  public :: nlopt_callback, alg_cobyla, alg_slsqp
  public :: nlo_create, nlo_destroy, nlo_set_min_objective, nlo_add_inequality_constraint
  public :: nlo_add_equality_constraint, nlo_set_lower_bounds, nlo_set_upper_bounds, nlo_set_xtol_abs1
  public :: nlo_set_xtol_rel, nlo_set_ftol_rel, nlo_set_maxeval, nlo_optimize

  integer, parameter :: alg_cobyla = 25   ! NLOPT_LN_COBYLA (nlopt.f)
  integer, parameter :: alg_slsqp = 40    ! NLOPT_LD_SLSQP

  abstract interface
    subroutine nlopt_callback(val, n, x, grad, need_gradient, f_data)
      import :: dp
      real(dp), intent(out) :: val
      integer, intent(in) :: n
      real(dp), intent(in) :: x(n)
      real(dp), intent(inout) :: grad(n)
      integer, intent(in) :: need_gradient
      integer, intent(in) :: f_data
    end subroutine nlopt_callback
  end interface

  !> the shapes NLopt's setters share: one real, one array of n reals, a
  !> constraint callback with its tolerance
  abstract interface
    subroutine nlopt_set_real(ires, opt, tol)
      import :: i8, dp
      integer, intent(out) :: ires
      integer(i8), intent(in) :: opt
      real(dp), intent(in) :: tol
    end subroutine nlopt_set_real
    subroutine nlopt_set_reals(ires, opt, values)
      import :: i8, dp
      integer, intent(out) :: ires
      integer(i8), intent(in) :: opt
      real(dp), intent(in) :: values(*)
    end subroutine nlopt_set_reals
    subroutine nlopt_add_constraint(ires, opt, fc, fc_data, tol)
      import :: i8, dp, nlopt_callback
      integer, intent(out) :: ires
      integer(i8), intent(in) :: opt
      procedure(nlopt_callback) :: fc
      integer, intent(in) :: fc_data
      real(dp), intent(in) :: tol
    end subroutine nlopt_add_constraint
  end interface

  ! NLopt's F77 API (libnlopt, nlopt.f): explicit interfaces
  procedure(nlopt_add_constraint) :: nlo_add_inequality_constraint
  procedure(nlopt_add_constraint) :: nlo_add_equality_constraint
  procedure(nlopt_set_real) :: nlo_set_xtol_rel
  procedure(nlopt_set_real) :: nlo_set_ftol_rel
  procedure(nlopt_set_real) :: nlo_set_xtol_abs1
  procedure(nlopt_set_reals) :: nlo_set_lower_bounds
  procedure(nlopt_set_reals) :: nlo_set_upper_bounds

  interface
    subroutine nlo_create(opt, alg, n)
      import :: i8
      integer(i8), intent(out) :: opt
      integer, intent(in) :: alg, n
    end subroutine nlo_create
    subroutine nlo_destroy(opt)
      import :: i8
      integer(i8), intent(in) :: opt
    end subroutine nlo_destroy
    subroutine nlo_set_min_objective(ires, opt, f, f_data)
      import :: i8, nlopt_callback
      integer, intent(out) :: ires
      integer(i8), intent(in) :: opt
      procedure(nlopt_callback) :: f
      integer, intent(in) :: f_data
    end subroutine nlo_set_min_objective
    subroutine nlo_set_maxeval(ires, opt, n)
      import :: i8
      integer, intent(out) :: ires
      integer(i8), intent(in) :: opt
      integer, intent(in) :: n
    end subroutine nlo_set_maxeval
    subroutine nlo_optimize(ires, opt, x, f)
      import :: i8, dp
      integer, intent(out) :: ires
      integer(i8), intent(in) :: opt
      real(dp), intent(inout) :: x(*)
      real(dp), intent(out) :: f
    end subroutine nlo_optimize
  end interface
end module nlopt_api
