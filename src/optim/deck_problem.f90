!> A linear or quadratic problem posed in the deck by its coefficients (issue
!> 11), without any code: `&optimize problem = 'deck'` and the group
!>
!>     &problem_data
!>       n = 3                                   ! variables (1..20)
!>       f_q(1,1) = 4, f_q(1,2) = 2, ...         ! F = 1/2 x^T Q x + c^T x + f0
!>       f_c = -8, -6, -4,  f_0 = 9
!>       n_ineq = 1                              ! g_i = 1/2 x^T Q_i x + a_i^T x - b_i <= 0
!>       g_a(1,:) = 1, 1, 2,  g_b(1) = 3         !   (g_q(:,:,i) = Q_i, default 0: linear)
!>       n_eq = 0                                ! h_j = 1/2 x^T Q_j x + a_j^T x - b_j = 0
!>       lower = 0, 0, 0                         ! simple bounds (default none: -+1e30)
!>       f_star = 0.111111111, x_star = ...      ! optional known optimum (summary distance)
!>       title = 'HS 35 from its coefficients'
!>     /
!>
!> Bounds are set with set_bounds (unit-gradient constraints after the
!> inequalities; NS trial points are kept in the box).  The
!> default start is x = 0 (give x0 in &optimize).
module deck_problem
  use, intrinsic :: iso_fortran_env, only: int64
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t, quadratic_problem_t
  implicit none
  private
  public :: read_deck_problem

  integer, parameter :: max_n = 20, max_ineq = 50, max_eq = 20
  real(dp), parameter :: none = 1.0e30_dp, unset = -huge(1.0_dp)
  real(dp), parameter :: big = 1.0e15_dp      !< coefficients beyond this overflow squares of x

  integer :: n, n_ineq, n_eq
  real(dp) :: f_q(max_n, max_n), f_c(max_n), f_0
  real(dp) :: g_q(max_n, max_n, max_ineq), g_a(max_ineq, max_n), g_b(max_ineq)
  real(dp) :: h_q(max_n, max_n, max_eq), h_a(max_eq, max_n), h_b(max_eq)
  real(dp) :: lower(max_n), upper(max_n), f_star, x_star(max_n)
  character(len=120) :: title
  namelist /problem_data/ n, f_q, f_c, f_0, n_ineq, g_q, g_a, g_b, n_eq, h_q, h_a, h_b, lower, upper, &
                          f_star, x_star, title

contains

  subroutine set_defaults()
    n = 0
    n_ineq = 0
    n_eq = 0
    f_q = 0.0_dp
    f_c = 0.0_dp
    f_0 = 0.0_dp
    g_q = 0.0_dp
    g_a = 0.0_dp
    g_b = 0.0_dp
    h_q = 0.0_dp
    h_a = 0.0_dp
    h_b = 0.0_dp
    lower = -none
    upper = none
    f_star = unset
    x_star = unset
    title = 'a problem posed in the deck by its coefficients'
  end subroutine set_defaults

  subroutine read_problem_data(r)
    type(group_read_t), intent(inout) :: r
    read(r%unit, nml=problem_data, iostat=r%ios, iomsg=r%iomsg)
  end subroutine read_problem_data

  !> Read &problem_data, check every value, and build the problem.
  subroutine read_deck_problem(deck, prob, info, err)
    type(deck_t), intent(inout) :: deck
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    type(error_t), intent(inout) :: err
    type(quadratic_problem_t), allocatable :: qp
    logical :: found
    integer :: i, j
    call set_defaults()
    call deck%read_group('problem_data', read_problem_data, .true., found, err)
    if (err%failed()) return
    call check_integer(deck, 'problem_data', 'n', n, err, at_least=1, at_most=max_n)
    call check_integer(deck, 'problem_data', 'n_ineq', n_ineq, err, at_least=0, at_most=max_ineq)
    call check_integer(deck, 'problem_data', 'n_eq', n_eq, err, at_least=0, at_most=max_eq)
    if (err%failed()) return
    call check_all(deck, err)
    if (err%failed()) return
    allocate(qp)
    call qp%init_problem('deck', n, 0, n_ineq, n_eq=n_eq)
    qp%q = f_q(1:n, 1:n)                ! symmetric (check_all)
    qp%lin = f_c(1:n)
    qp%const = f_0
    do i = 1, n_ineq
      if (any(abs(g_q(1:n, 1:n, i)) > 0.0_dp)) then
        call qp%set_quadratic_constraint(i, g_q(1:n, 1:n, i), g_a(i, 1:n), g_b(i))
      else
        call qp%set_linear_constraint(i, g_a(i, 1:n), g_b(i))
      end if
    end do
    do j = 1, n_eq
      if (any(abs(h_q(1:n, 1:n, j)) > 0.0_dp)) then
        call qp%set_quadratic_equality(j, h_q(1:n, 1:n, j), h_a(j, 1:n), h_b(j))
      else
        call qp%set_linear_constraint(qp%m + j, h_a(j, 1:n), h_b(j))
      end if
    end do
    call qp%set_bounds(lower(1:n), upper(1:n))     ! simple bounds, after the inequalities
    info%name = 'deck'
    info%title = trim(title)
    info%source = 'coefficients in &problem_data of the deck'
    info%method = 'auto'
    info%x0 = [(0.0_dp, i=1, n)]
    info%has_optimum = .not. is_unset(f_star)
    if (info%has_optimum) then
      info%f_star = f_star
      info%x_star = x_star(1:n)
      if (any(is_unset(x_star(1:n)))) info%has_optimum = .false.
    end if
    call move_alloc(qp, prob)
  end subroutine read_deck_problem

  !> Every coefficient in use finite and within +-1e15; lower <= upper.
  subroutine check_all(deck, err)
    type(deck_t), intent(in) :: deck
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'problem_data', why = 'a coefficient beyond 1e15 overflows products with x'
    integer :: i
    call check_reals(deck, g, 'f_q', reshape(f_q(1:n, 1:n), [n*n]), err, at_least=-big, at_most=big, why=why)
    call check_reals(deck, g, 'f_c', f_c(1:n), err, at_least=-big, at_most=big, why=why)
    call check_real(deck, g, 'f_0', f_0, err, at_least=-big, at_most=big, why=why)
    call check_family('g', g_q, g_a, g_b, n_ineq)      ! the inequalities, then the equalities
    call check_family('h', h_q, h_a, h_b, n_eq)
    if (err%failed()) return
    call check_symmetric('f_q', f_q(1:n, 1:n))
    do i = 1, n_ineq
      call check_symmetric('g_q(:,:,'//str(i)//')', g_q(1:n, 1:n, i))
    end do
    do i = 1, n_eq
      call check_symmetric('h_q(:,:,'//str(i)//')', h_q(1:n, 1:n, i))
    end do
    call check_reals(deck, g, 'lower', lower(1:n), err, at_least=-none, at_most=none, why='-1e30 means no bound')
    call check_reals(deck, g, 'upper', upper(1:n), err, at_least=-none, at_most=none, why='1e30 means no bound')
    if (err%failed()) return
    do i = 1, n
      if (lower(i) > upper(i)) then
        call invalid_value(deck, g, 'lower('//str(i)//')', str(lower(i)), 'must not exceed upper('//str(i)//') = ' &
                           //str(upper(i)), err)
        return
      end if
    end do
    if (.not. is_unset(f_star)) call check_real(deck, g, 'f_star', f_star, err, at_least=-big, at_most=big)
    ! x* is only compared with the result, but a NaN there trapped the summary (fuzz seed 12, case 23272)
    do i = 1, n
      if (.not. is_unset(x_star(i))) call check_real(deck, g, 'x_star('//str(i)//')', x_star(i), err, &
                                                     at_least=-big, at_most=big)
    end do
  contains
    !> A quadratic term's matrix must be given whole and symmetric: a matrix
    !> given in one triangle would otherwise be read as half the intended
    !> curvature (x^T Q x counts an off-diagonal entry twice), silently.
    subroutine check_symmetric(name, q)
      character(len=*), intent(in) :: name
      real(dp), intent(in) :: q(:, :)
      integer :: i1, j1
      if (err%failed()) return
      do j1 = 1, n
        do i1 = j1 + 1, n
          if (abs(q(i1, j1) - q(j1, i1)) > 1.0e-12_dp*max(abs(q(i1, j1)), abs(q(j1, i1)))) then
            call invalid_value(deck, g, name, 'entry ('//str(i1)//','//str(j1)//') = '//str(q(i1, j1))// &
              ', entry ('//str(j1)//','//str(i1)//') = '//str(q(j1, i1)), 'the matrix must be symmetric: give ' &
              //'both triangles (F = 1/2 x^T Q x + ..., Q(i,j) = Q(j,i) = the coefficient of x_i x_j)', err)
            return
          end if
        end do
      end do
    end subroutine check_symmetric

    !> The m quadratic constraints c_q(:,:,k), c_a(k,:), c_b(k) of one family.
    subroutine check_family(c, q, a, b, m)
      character(len=1), intent(in) :: c
      real(dp), intent(in) :: q(:, :, :), a(:, :), b(:)
      integer, intent(in) :: m
      integer :: k
      do k = 1, m
        call check_reals(deck, g, c//'_q(:,:,'//str(k)//')', reshape(q(1:n, 1:n, k), [n*n]), err, at_least=-big, &
                         at_most=big, why=why)
        call check_reals(deck, g, c//'_a('//str(k)//',:)', a(k, 1:n), err, at_least=-big, at_most=big, why=why)
      end do
      call check_reals(deck, g, c//'_b', b(1:m), err, at_least=-big, at_most=big, why=why)
    end subroutine check_family
  end subroutine check_all

  elemental logical function is_unset(v)
    real(dp), intent(in) :: v
    is_unset = transfer(v, 0_int64) == transfer(unset, 0_int64)
  end function is_unset

end module deck_problem
