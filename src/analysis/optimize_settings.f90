!> The &optimize group: the problem, the method of the Gauss family, its
!> options and the start (doc/decks.md, doc/optimization.md §10).
module optimize_settings
  use, intrinsic :: iso_fortran_env, only: int64
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  implicit none
  private
  public :: optimize_settings_t, read_optimize_settings, check_optimize_settings, echo_optimize_settings

  integer, parameter :: max_vars = 50
  character(len=20), parameter :: method_list(7) = [character(len=20) :: 'auto', 'gauss', 'gauss_constrained', &
                                                    'gnlc', 'gnlc_ns', 'gnlc_general', 'gnlc_general_ns']
  !> x0 entries the deck leaves out hold this marker (echoed as such: a deck
  !> written from the echo gives the same start)
  real(dp), parameter :: unset = -huge(1.0_dp)

  !> The group's values; the default initialisation is the documented
  !> defaults (doc/decks.md).  Names are lower case after the read.
  type :: optimize_settings_t
    character(len=32) :: problem = 'rosen_suzuki'
    character(len=32) :: method = 'auto'
    real(dp) :: x0(max_vars) = unset             !< the start; none given: the problem's
    character(len=32) :: hessian = 'auto'
    integer :: max_iter = 50
    real(dp) :: xtol = 1.0e-8_dp
    real(dp) :: ftol = 1.0e-12_dp
    real(dp) :: feas_tol = 1.0e-8_dp
    real(dp) :: mult_tol = 1.0e-8_dp
    real(dp) :: rcond_min = 1.0e-13_dp
    real(dp) :: regularization = 0.0_dp         !< 0: automatic
    integer :: newton_max_iter = 30
    character(len=32) :: potter_fix = 'repeat'
    character(len=32) :: step_back = 'farthest'
    character(len=32) :: singular_g = 'regularize'
    character(len=32) :: globalization = 'filter'
    real(dp) :: stat_tol = 1.0e-4_dp
    logical :: check_derivatives = .false.
  end type optimize_settings_t

  ! staging variables of &optimize
  character(len=32) :: problem, method, hessian, potter_fix, step_back, singular_g, globalization
  real(dp) :: x0(max_vars), xtol, ftol, feas_tol, mult_tol, rcond_min, regularization, stat_tol
  integer :: max_iter, newton_max_iter
  logical :: check_derivatives
  namelist /optimize/ problem, method, x0, hessian, max_iter, xtol, ftol, feas_tol, mult_tol, rcond_min, &
                      regularization, newton_max_iter, potter_fix, step_back, singular_g, globalization, stat_tol, &
                      check_derivatives

contains

  !> Read &optimize (required); the names in lower case ('gnlc.ns' is 'gnlc_ns').
  !> The values are checked by check_optimize_settings once the problem,
  !> and with it the length of x0, is known.
  subroutine read_optimize_settings(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(optimize_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    type(optimize_settings_t) :: defaults
    logical :: found
    call stage_from(defaults)
    call deck%read_group('optimize', optimize_group, .true., found, err)
    if (err%failed()) return
    s = optimize_settings_t(problem=lower(problem), method=lower(method), x0=x0, hessian=lower(hessian), &
      max_iter=max_iter, xtol=xtol, ftol=ftol, feas_tol=feas_tol, mult_tol=mult_tol, rcond_min=rcond_min, &
      regularization=regularization, newton_max_iter=newton_max_iter, potter_fix=lower(potter_fix), &
      step_back=lower(step_back), singular_g=lower(singular_g), globalization=lower(globalization), &
      stat_tol=stat_tol, check_derivatives=check_derivatives)
    if (s%method == 'gnlc.ns') s%method = 'gnlc_ns'
  end subroutine read_optimize_settings

  !> Check the method, its options and x0 for a problem of n variables (all
  !> of x0(1:n) given, or none: n_given = 0).
  subroutine check_optimize_settings(deck, s, n, n_given, err)
    type(deck_t), intent(in) :: deck
    type(optimize_settings_t), intent(in) :: s
    integer, intent(in) :: n
    integer, intent(out) :: n_given
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'optimize'
    n_given = 0
    call check_choice(deck, g, 'method', s%method, method_list, err)
    call check_choice(deck, g, 'hessian', s%hessian, [character(len=8) :: 'auto', 'gauss', 'exact', 'bfgs'], err)
    call check_choice(deck, g, 'potter_fix', s%potter_fix, [character(len=8) :: 'repeat', 'none'], err)
    call check_choice(deck, g, 'step_back', s%step_back, [character(len=8) :: 'farthest', 'b13'], err)
    call check_choice(deck, g, 'singular_g', s%singular_g, [character(len=12) :: 'regularize', 'stop'], err)
    call check_choice(deck, g, 'globalization', s%globalization, [character(len=8) :: 'filter', 'none'], err)
    if (err%failed()) return
    ! x0: unset entries hold the marker; the given ones must be finite
    n_given = count(.not. is_unset(s%x0))
    if (n_given /= 0 .and. (n_given /= n .or. any(is_unset(s%x0(1:n))))) then
      call invalid_value(deck, g, 'x0', str(n_given)//' values', 'problem '//trim(s%problem)// &
                         ' has '//str(n)//' variables: give all of x0(1:'//str(n)//') or none', err)
      return
    end if
    if (n_given > 0) call check_reals(deck, g, 'x0', s%x0(1:n), err, at_least=-1.0e15_dp, at_most=1.0e15_dp, &
      why='a design variable beyond 1e15 leaves residuals whose squares overflow')
    call check_integer(deck, g, 'max_iter', s%max_iter, err, at_least=0, at_most=100000)
    call check_integer(deck, g, 'newton_max_iter', s%newton_max_iter, err, at_least=1, at_most=1000)
    call check_real(deck, g, 'xtol', s%xtol, err, above=0.0_dp, below=1.0_dp, why='a relative step tolerance')
    call check_real(deck, g, 'ftol', s%ftol, err, above=0.0_dp, below=1.0_dp, why='a relative objective tolerance')
    call check_real(deck, g, 'feas_tol', s%feas_tol, err, above=0.0_dp, below=1.0_dp, &
                    why='an absolute constraint tolerance; 1 or more would call violated constraints satisfied')
    call check_real(deck, g, 'mult_tol', s%mult_tol, err, at_least=0.0_dp, below=1.0_dp, &
                    why='a multiplier threshold relative to |grad F|')
    call check_real(deck, g, 'rcond_min', s%rcond_min, err, above=0.0_dp, below=1.0_dp, &
                    why='a reciprocal condition number')
    call check_real(deck, g, 'regularization', s%regularization, err, at_least=0.0_dp, at_most=1.0_dp, &
                    why='mu = regularization max G_ii; above 1 mu I would swamp G and the step become a gradient step')
    call check_real(deck, g, 'stat_tol', s%stat_tol, err, above=0.0_dp, below=1.0_dp, &
                    why='a relative tolerance on |grad F + C lambda|')
  end subroutine check_optimize_settings

  !> Echo the effective input: x0 is the start used (the problem's when the
  !> deck gives none), its entries beyond the problem's n the unset marker.
  subroutine echo_optimize_settings(s, start, out)
    type(optimize_settings_t), intent(in) :: s
    real(dp), intent(in) :: start(:)
    type(table_t), intent(inout) :: out
    call stage_from(s)
    x0 = unset
    x0(1:size(start)) = start
    call out%echo_group(optimize_group)
  end subroutine echo_optimize_settings

  !> The namelist variables from a settings value (the defaults before a read).
  subroutine stage_from(s)
    type(optimize_settings_t), intent(in) :: s
    problem = s%problem
    method = s%method
    x0 = s%x0
    hessian = s%hessian
    max_iter = s%max_iter
    xtol = s%xtol
    ftol = s%ftol
    feas_tol = s%feas_tol
    mult_tol = s%mult_tol
    rcond_min = s%rcond_min
    regularization = s%regularization
    newton_max_iter = s%newton_max_iter
    potter_fix = s%potter_fix
    step_back = s%step_back
    singular_g = s%singular_g
    globalization = s%globalization
    stat_tol = s%stat_tol
    check_derivatives = s%check_derivatives
  end subroutine stage_from

  !> x0 entries the deck left at the marker (bit comparison: no floating-point
  !> comparison with a NaN the deck may hold).
  elemental logical function is_unset(v)
    real(dp), intent(in) :: v
    is_unset = transfer(v, 0_int64) == transfer(unset, 0_int64)
  end function is_unset

  !> The &optimize group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine optimize_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=optimize, delim='apostrophe')
    else
      read(r%unit, nml=optimize, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine optimize_group
end module optimize_settings
