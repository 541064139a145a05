!> The &lsode_check group of the `lsode_check` analysis: which test problem,
!> DLSODE's method and tolerances, the output times (doc/decks.md).
module lsode_check_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  use lsode_solver, only: max_steps_ceiling, max_steps_reason, mf_from_method, method_names
  implicit none
  private
  public :: lsode_check_settings_t, read_lsode_check_settings, echo_lsode_check_settings

  !> The group's values; the default initialisation is the documented
  !> defaults (doc/decks.md): DLSODE's own example.
  type :: lsode_check_settings_t
    character(len=32) :: problem = 'kinetics'   !< 'kinetics' (Robertson) or 'oscillator'
    character(len=32) :: method = 'bdf'
    integer :: mf = 0                           !< DLSODE's MF of `method` (after the read)
    real(dp) :: rtol = 1.0e-4_dp
    real(dp) :: atol(3) = [1.0e-6_dp, 1.0e-10_dp, 1.0e-6_dp]
    real(dp) :: t_first = 0.4_dp
    real(dp) :: factor = 10.0_dp
    integer :: n_outputs = 12
    real(dp) :: omega = 1.0_dp
    integer :: max_steps = 20000
  end type lsode_check_settings_t

  ! staging variables of &lsode_check
  character(len=32) :: problem, method
  real(dp) :: rtol, atol(3), t_first, factor, omega
  integer :: n_outputs, max_steps
  namelist /lsode_check/ problem, method, rtol, atol, t_first, factor, n_outputs, omega, max_steps

contains

  !> Read &lsode_check (optional) and check every value.
  subroutine read_lsode_check_settings(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(lsode_check_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    logical :: found
    call stage_from(s)        ! (intent(out): the defaults)
    call deck%read_group('lsode_check', lsode_check_group, .false., found, err)
    if (err%failed()) return
    s = lsode_check_settings_t(problem=problem, method=method, mf=mf_from_method(method), rtol=rtol, atol=atol, &
                               t_first=t_first, factor=factor, n_outputs=n_outputs, omega=omega, max_steps=max_steps)
    call validate(deck, s, err)
  end subroutine read_lsode_check_settings

  subroutine validate(deck, s, err)
    type(deck_t), intent(in) :: deck
    type(lsode_check_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'lsode_check'
    if (s%mf == 0) then
      call invalid_value(deck, g, 'method', ''''//trim(s%method)//'''', 'must be one of '//method_names, err)
      return
    end if
    call check_choice(deck, g, 'problem', s%problem, [character(len=16) :: 'kinetics', 'oscillator'], err)
    call check_real(deck, g, 'rtol', s%rtol, err, at_least=1.0e-14_dp, below=1.0_dp, &
                    why='a relative error tolerance; below 1e-14 DLSODE works at round-off')
    call check_reals(deck, g, 'atol', s%atol, err, at_least=0.0_dp, at_most=1.0e10_dp)
    if (.not. err%failed()) then    ! (nested: .and. does not short-circuit, and a NaN comparison traps)
      if (any(s%atol > 0.0_dp .and. s%atol < 1.0e-30_dp)) call invalid_value(deck, g, 'atol', &
        str(minval(s%atol, mask=s%atol > 0.0_dp)), 'must be 0 or >= 1e-30 (below, DLSODE''s error weights overflow)', &
        err)
    end if
    call check_real(deck, g, 't_first', s%t_first, err, at_least=1.0e-10_dp, at_most=1.0e10_dp, &
                    why='the first output time; DLSODE cannot start a step shorter than round-off of t')
    call check_real(deck, g, 'factor', s%factor, err, above=1.0_dp, at_most=1.0e3_dp, &
                    why='output times grow by this factor (kinetics)')
    call check_integer(deck, g, 'n_outputs', s%n_outputs, err, at_least=1, at_most=100000)
    call check_real(deck, g, 'omega', s%omega, err, above=0.0_dp, at_most=1.0e6_dp, why='rad per unit time')
    call check_integer(deck, g, 'max_steps', s%max_steps, err, at_least=1, at_most=max_steps_ceiling, &
                       why=max_steps_reason)
    if (err%failed()) return
    if (s%problem == 'kinetics' .and. log10(s%t_first) + s%n_outputs*log10(s%factor) > 300.0_dp) &
      call invalid_value(deck, g, 'n_outputs', str(s%n_outputs), 'the last output time t_first*factor**n_outputs '// &
                         'must stay below 1e300', err)
  end subroutine validate

  !> Echo the group into the output header.
  subroutine echo_lsode_check_settings(s, out)
    type(lsode_check_settings_t), intent(in) :: s
    type(table_t), intent(inout) :: out
    call stage_from(s)
    call out%echo_group(lsode_check_group)
  end subroutine echo_lsode_check_settings

  !> The namelist variables from a settings value (the defaults before a read).
  subroutine stage_from(s)
    type(lsode_check_settings_t), intent(in) :: s
    problem = s%problem
    method = s%method
    rtol = s%rtol
    atol = s%atol
    t_first = s%t_first
    factor = s%factor
    n_outputs = s%n_outputs
    omega = s%omega
    max_steps = s%max_steps
  end subroutine stage_from

  !> The &lsode_check group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine lsode_check_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=lsode_check, delim='apostrophe')
    else
      read(r%unit, nml=lsode_check, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine lsode_check_group
end module lsode_check_settings
