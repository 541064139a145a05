!> The &problem_data group of an optimize deck (`&optimize problem = 'deck'`):
!> the coefficients of a linear or quadratic problem (doc/decks.md).  The
!> coefficients, problem_data_t with its documented defaults, and the problem
!> built from them belong to the optimizer's layer (deck_problem); this
!> module reads, checks and echoes the group.
module problem_data_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer
  use table_output, only: table_t
  use deck_problem, only: problem_data_t, is_unset, max_n, max_ineq, max_eq, no_bound, unset
  implicit none
  private
  public :: read_problem_data, echo_problem_data

  real(dp), parameter :: big = 1.0e15_dp      !< coefficients beyond this overflow squares of x

  ! staging variables of &problem_data
  integer :: n, n_ineq, n_eq
  real(dp) :: f_q(max_n, max_n), f_c(max_n), f_0
  real(dp) :: g_q(max_n, max_n, max_ineq), g_a(max_ineq, max_n), g_c(max_n, max_ineq), g_b(max_ineq)
  real(dp) :: h_q(max_n, max_n, max_eq), h_a(max_eq, max_n), h_c(max_n, max_eq), h_b(max_eq)
  real(dp) :: lower(max_n), upper(max_n), f_star, x_star(max_n)
  character(len=120) :: title
  namelist /problem_data/ n, f_q, f_c, f_0, n_ineq, g_q, g_c, g_a, g_b, n_eq, h_q, h_c, h_a, h_b, lower, upper, &
                          f_star, x_star, title

contains

  !> Read &problem_data (required) and check every value.
  subroutine read_problem_data(deck, d, err)
    type(deck_t), intent(inout) :: deck
    type(problem_data_t), intent(out) :: d
    type(error_t), intent(inout) :: err
    logical :: found
    call stage_from(d)        ! (intent(out): the defaults)
    g_a = unset               ! given or not: one order per family (one_order)
    g_c = unset
    h_a = unset
    h_c = unset
    call deck%read_group('problem_data', problem_data_group, .true., found, err)
    if (err%failed()) return
    call one_order(deck, 'g', g_a, g_c, err)
    call one_order(deck, 'h', h_a, h_c, err)
    if (err%failed()) return
    d = problem_data_t(n=n, f_q=f_q, f_c=f_c, f_0=f_0, n_ineq=n_ineq, g_q=g_q, g_a=g_a, g_b=g_b, n_eq=n_eq, &
                       h_q=h_q, h_a=h_a, h_b=h_b, lower=lower, upper=upper, f_star=f_star, x_star=x_star, title=title)
    call check_integer(deck, 'problem_data', 'n', d%n, err, at_least=1, at_most=max_n)
    call check_integer(deck, 'problem_data', 'n_ineq', d%n_ineq, err, at_least=0, at_most=max_ineq)
    call check_integer(deck, 'problem_data', 'n_eq', d%n_eq, err, at_least=0, at_most=max_eq)
    if (err%failed()) return
    call check_all(deck, d, err)
  end subroutine read_problem_data

  !> Every coefficient in use finite and within +-1e15; lower <= upper.
  subroutine check_all(deck, d, err)
    type(deck_t), intent(in) :: deck
    type(problem_data_t), intent(in) :: d
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'problem_data', why = 'a coefficient beyond 1e15 overflows products with x'
    integer :: i, m
    m = d%n
    call check_reals(deck, g, 'f_q', reshape(d%f_q(1:m, 1:m), [m*m]), err, at_least=-big, at_most=big, why=why)
    call check_reals(deck, g, 'f_c', d%f_c(1:m), err, at_least=-big, at_most=big, why=why)
    call check_real(deck, g, 'f_0', d%f_0, err, at_least=-big, at_most=big, why=why)
    call check_family('g', d%g_q, d%g_a, d%g_b, d%n_ineq)      ! the inequalities, then the equalities
    call check_family('h', d%h_q, d%h_a, d%h_b, d%n_eq)
    if (err%failed()) return
    call check_symmetric('f_q', d%f_q(1:m, 1:m))
    do i = 1, d%n_ineq
      call check_symmetric('g_q(:,:,'//str(i)//')', d%g_q(1:m, 1:m, i))
    end do
    do i = 1, d%n_eq
      call check_symmetric('h_q(:,:,'//str(i)//')', d%h_q(1:m, 1:m, i))
    end do
    call check_reals(deck, g, 'lower', d%lower(1:m), err, at_least=-no_bound, at_most=no_bound, &
                     why='-1e30 means no bound')
    call check_reals(deck, g, 'upper', d%upper(1:m), err, at_least=-no_bound, at_most=no_bound, &
                     why='1e30 means no bound')
    if (err%failed()) return
    do i = 1, m
      if (d%lower(i) > d%upper(i)) then
        call invalid_value(deck, g, 'lower('//str(i)//')', str(d%lower(i)), 'must not exceed upper('//str(i)//') = ' &
                           //str(d%upper(i)), err)
        return
      end if
    end do
    if (.not. is_unset(d%f_star)) call check_real(deck, g, 'f_star', d%f_star, err, at_least=-big, at_most=big)
    ! x* is only compared with the result, but a NaN there trapped the summary (fuzz seed 12, case 23272)
    do i = 1, m
      if (.not. is_unset(d%x_star(i))) call check_real(deck, g, 'x_star('//str(i)//')', d%x_star(i), err, &
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
      do j1 = 1, m
        do i1 = j1 + 1, m
          if (abs(q(i1, j1) - q(j1, i1)) > 1.0e-12_dp*max(abs(q(i1, j1)), abs(q(j1, i1)))) then
            call invalid_value(deck, g, name, 'entry ('//str(i1)//','//str(j1)//') = '//str(q(i1, j1))// &
              ', entry ('//str(j1)//','//str(i1)//') = '//str(q(j1, i1)), 'the matrix must be symmetric: give ' &
              //'both triangles (F = 1/2 x^T Q x + ..., Q(i,j) = Q(j,i) = the coefficient of x_i x_j)', err)
            return
          end if
        end do
      end do
    end subroutine check_symmetric

    !> The k quadratic constraints c_q(:,:,k), c_a(k,:), c_b(k) of one family.
    subroutine check_family(c, q, a, b, k_max)
      character(len=1), intent(in) :: c
      real(dp), intent(in) :: q(:, :, :), a(:, :), b(:)
      integer, intent(in) :: k_max
      integer :: k
      do k = 1, k_max
        call check_reals(deck, g, c//'_q(:,:,'//str(k)//')', reshape(q(1:m, 1:m, k), [m*m]), err, at_least=-big, &
                         at_most=big, why=why)
        call check_reals(deck, g, c//'_a('//str(k)//',:)', a(k, 1:m), err, at_least=-big, at_most=big, why=why)
      end do
      call check_reals(deck, g, c//'_b', b(1:k_max), err, at_least=-big, at_most=big, why=why)
    end subroutine check_family
  end subroutine check_all

  !> The linear terms of one constraint family in the order of the deck's
  !> other data, c_c(j, k) (the constraint index last, as in c_q(i, j, k)),
  !> or in the older order c_a(k, j); both in one deck is ambiguous (exit 2).
  !> On return c_a holds them (entries not given are 0).
  subroutine one_order(deck, c, a, cc, err)
    type(deck_t), intent(in) :: deck
    character(len=1), intent(in) :: c
    real(dp), intent(inout) :: a(:, :), cc(:, :)
    type(error_t), intent(inout) :: err
    logical :: a_given, c_given
    if (err%failed()) return
    a_given = .not. all(is_unset(a))
    c_given = .not. all(is_unset(cc))
    if (a_given .and. c_given) then
      call invalid_value(deck, 'problem_data', c//'_a', 'given with '//c//'_c', 'give the linear terms in one ' &
        //'order: '//c//'_c(j,k) (variable j, constraint k: the order of '//c//'_q(i,j,k)) or '//c//'_a(k,j), not both', err)
      return
    end if
    if (c_given) a = transpose(cc)
    where (is_unset(a)) a = 0.0_dp
  end subroutine one_order

  !> Echo the coefficients into the output header.
  subroutine echo_problem_data(d, out)
    type(problem_data_t), intent(in) :: d
    type(table_t), intent(inout) :: out
    call stage_from(d)
    call out%echo_group(problem_data_group)
  end subroutine echo_problem_data

  !> The namelist variables from coefficients (the defaults before a read).
  subroutine stage_from(d)
    type(problem_data_t), intent(in) :: d
    n = d%n
    f_q = d%f_q
    f_c = d%f_c
    f_0 = d%f_0
    n_ineq = d%n_ineq
    g_q = d%g_q
    g_a = d%g_a
    g_c = unset
    g_b = d%g_b
    n_eq = d%n_eq
    h_q = d%h_q
    h_a = d%h_a
    h_c = unset
    h_b = d%h_b
    lower = d%lower
    upper = d%upper
    f_star = d%f_star
    x_star = d%x_star
    title = d%title
  end subroutine stage_from

  !> The &problem_data group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine problem_data_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=problem_data, delim='apostrophe')
    else
      read(r%unit, nml=problem_data, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine problem_data_group
end module problem_data_settings
