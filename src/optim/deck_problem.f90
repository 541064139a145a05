!> A linear or quadratic problem posed in the deck by its coefficients (issue
!> 11), without any code: `&optimize problem = 'deck'` and the group
!>
!>     &problem_data
!>       n = 3                                   ! variables (1..20)
!>       f_q(1,1) = 4, f_q(1,2) = 2, ...         ! F = 1/2 x^T Q x + c^T x + f0
!>       f_c = -8, -6, -4,  f_0 = 9
!>       n_ineq = 1                              ! g_i = 1/2 x^T Q_i x + a_i^T x - b_i <= 0
!>       g_c(:,1) = 1, 1, 2,  g_b(1) = 3         !   (g_q(:,:,i) = Q_i, default 0: linear;
!>                                               !   g_c(:,i) = a_i, or g_a(i,:) = a_i, not both)
!>       n_eq = 0                                ! h_j = 1/2 x^T Q_j x + a_j^T x - b_j = 0 (h_q, h_c, h_b)
!>       lower = 0, 0, 0                         ! simple bounds (default none: -+1e30)
!>       f_star = 0.111111111, x_star = ...      ! optional known optimum (summary distance)
!>       title = 'HS 35 from its coefficients'
!>     /
!>
!> Bounds are set with set_bounds (unit-gradient constraints after the
!> inequalities; NS trial points are kept in the box).  The
!> default start is x = 0 (give x0 in &optimize).  This module holds the
!> coefficients (problem_data_t, with the documented defaults) and builds the
!> problem from them; the analysis layer reads, checks and echoes the group
!> (problem_data_settings).
module deck_problem
  use, intrinsic :: iso_fortran_env, only: int64
  use kinds, only: dp
  use problem_library, only: quadratic_problem_t, problem_info_t
  use optim_problem, only: opt_problem_t
  implicit none
  private
  public :: problem_data_t, build_deck_problem, is_unset
  public :: max_n, max_ineq, max_eq, no_bound, unset

  integer, parameter :: max_n = 20, max_ineq = 50, max_eq = 20
  real(dp), parameter :: no_bound = 1.0e30_dp      !< a bound of this size is none
  real(dp), parameter :: unset = -huge(1.0_dp)     !< f_star, x_star not given

  !> The coefficients of &problem_data; the default initialisation is the
  !> documented defaults (doc/decks.md).
  type :: problem_data_t
    integer :: n = 0
    real(dp) :: f_q(max_n, max_n) = 0.0_dp
    real(dp) :: f_c(max_n) = 0.0_dp
    real(dp) :: f_0 = 0.0_dp
    integer :: n_ineq = 0
    real(dp) :: g_q(max_n, max_n, max_ineq) = 0.0_dp
    real(dp) :: g_a(max_ineq, max_n) = 0.0_dp
    real(dp) :: g_b(max_ineq) = 0.0_dp
    integer :: n_eq = 0
    real(dp) :: h_q(max_n, max_n, max_eq) = 0.0_dp
    real(dp) :: h_a(max_eq, max_n) = 0.0_dp
    real(dp) :: h_b(max_eq) = 0.0_dp
    real(dp) :: lower(max_n) = -no_bound
    real(dp) :: upper(max_n) = no_bound
    real(dp) :: f_star = unset
    real(dp) :: x_star(max_n) = unset
    character(len=120) :: title = 'a problem posed in the deck by its coefficients'
  end type problem_data_t

contains

  !> The problem of checked coefficients (symmetric matrices, lower <= upper).
  subroutine build_deck_problem(d, prob, info)
    type(problem_data_t), intent(in) :: d
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    type(quadratic_problem_t), allocatable :: qp
    integer :: i, j, n
    n = d%n
    allocate(qp)
    call qp%init_problem('deck', n, 0, d%n_ineq, n_eq=d%n_eq)
    qp%q = d%f_q(1:n, 1:n)
    qp%lin = d%f_c(1:n)
    qp%const = d%f_0
    do i = 1, d%n_ineq
      if (any(abs(d%g_q(1:n, 1:n, i)) > 0.0_dp)) then
        call qp%set_quadratic_constraint(i, d%g_q(1:n, 1:n, i), d%g_a(i, 1:n), d%g_b(i))
      else
        call qp%set_linear_constraint(i, d%g_a(i, 1:n), d%g_b(i))
      end if
    end do
    do j = 1, d%n_eq
      if (any(abs(d%h_q(1:n, 1:n, j)) > 0.0_dp)) then
        call qp%set_quadratic_equality(j, d%h_q(1:n, 1:n, j), d%h_a(j, 1:n), d%h_b(j))
      else
        call qp%set_linear_constraint(qp%m + j, d%h_a(j, 1:n), d%h_b(j))
      end if
    end do
    call qp%set_bounds(d%lower(1:n), d%upper(1:n))     ! simple bounds, after the inequalities
    info%name = 'deck'
    info%title = trim(d%title)
    info%source = 'coefficients in &problem_data of the deck'
    info%method = 'auto'
    info%x0 = [(0.0_dp, i=1, n)]
    info%has_optimum = .not. is_unset(d%f_star)
    if (info%has_optimum) then
      info%f_star = d%f_star
      info%x_star = d%x_star(1:n)
      if (any(is_unset(d%x_star(1:n)))) info%has_optimum = .false.
    end if
    call move_alloc(qp, prob)
  end subroutine build_deck_problem

  !> A value left at the unset marker (bit comparison: no floating-point
  !> comparison with a NaN the deck may hold).
  elemental logical function is_unset(v)
    real(dp), intent(in) :: v
    is_unset = transfer(v, 0_int64) == transfer(unset, 0_int64)
  end function is_unset
end module deck_problem
