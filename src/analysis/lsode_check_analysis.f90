!> The `lsode_check` analysis: runs DLSODE through flexmech's wrapper on the
!> stiff chemical-kinetics problem of LSODE's own documentation (Robertson),
!> or on an undamped oscillator with a closed-form solution, and tabulates the
!> solution with the cost of the run.  It is the smallest real analysis of the
!> program and the check that the ODEPACK build is sound.
module lsode_check_analysis
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  use lsode_solver, only: max_steps_ceiling, max_steps_reason, ode_system_t, lsode_t, lsode_counters_t, &
                          mf_from_method, method_names, mf_adams
  implicit none
  private
  public :: run_lsode_check

  type, extends(ode_system_t) :: kinetics_t
  contains
    procedure :: rhs => kinetics_rhs
    procedure :: jacobian => kinetics_jac
  end type kinetics_t

  type, extends(ode_system_t) :: oscillator_t
    real(dp) :: omega = 1.0_dp
  contains
    procedure :: rhs => oscillator_rhs
    procedure :: jacobian => oscillator_jac
  end type oscillator_t

  ! staging variables of the &lsode_check group (defaults: DLSODE's own example)
  character(len=32) :: problem, method
  real(dp) :: rtol, atol(3), t_first, factor, omega
  integer :: n_outputs, max_steps
  namelist /lsode_check/ problem, method, rtol, atol, t_first, factor, n_outputs, omega, max_steps

contains

  subroutine set_defaults()
    problem = 'kinetics'
    method = 'bdf'
    rtol = 1.0e-4_dp
    atol = [1.0e-6_dp, 1.0e-10_dp, 1.0e-6_dp]
    t_first = 0.4_dp
    factor = 10.0_dp
    n_outputs = 12
    omega = 1.0_dp
    max_steps = 20000
  end subroutine set_defaults

  !> The &lsode_check group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine lsode_check_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=lsode_check, delim='apostrophe')
    else
      read(r%unit, nml=lsode_check, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine lsode_check_group

  subroutine run_lsode_check(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    logical :: found
    integer :: mf, k, neq
    real(dp) :: tout
    real(dp), allocatable :: y(:)
    type(kinetics_t), target :: kinetics
    type(oscillator_t), target :: oscillator
    class(ode_system_t), pointer :: sys
    type(lsode_t) :: ode
    type(lsode_counters_t) :: c
    character(len=*), parameter :: g = 'lsode_check'

    call set_defaults()
    call deck%read_group('lsode_check', lsode_check_group, .false., found, err)
    if (err%failed()) return
    mf = mf_from_method(method)
    if (mf == 0) then
      call invalid_value(deck, g, 'method', ''''//trim(method)//'''', 'must be one of '//method_names, err)
      return
    end if
    call check_choice(deck, g, 'problem', problem, [character(len=16) :: 'kinetics', 'oscillator'], err)
    call check_real(deck, g, 'rtol', rtol, err, at_least=1.0e-14_dp, below=1.0_dp, &
                    why='a relative error tolerance; below 1e-14 DLSODE works at round-off')
    call check_reals(deck, g, 'atol', atol, err, at_least=0.0_dp, at_most=1.0e10_dp)
    if (.not. err%failed()) then    ! (nested: .and. does not short-circuit, and a NaN comparison traps)
      if (any(atol > 0.0_dp .and. atol < 1.0e-30_dp)) call invalid_value(deck, g, 'atol', &
        str(minval(atol, mask=atol > 0.0_dp)), 'must be 0 or >= 1e-30 (below, DLSODE''s error weights overflow)', err)
    end if
    call check_real(deck, g, 't_first', t_first, err, at_least=1.0e-10_dp, at_most=1.0e10_dp, &
                    why='the first output time; DLSODE cannot start a step shorter than round-off of t')
    call check_real(deck, g, 'factor', factor, err, above=1.0_dp, at_most=1.0e3_dp, &
                    why='output times grow by this factor (kinetics)')
    call check_integer(deck, g, 'n_outputs', n_outputs, err, at_least=1, at_most=100000)
    call check_real(deck, g, 'omega', omega, err, above=0.0_dp, at_most=1.0e6_dp, why='rad per unit time')
    call check_integer(deck, g, 'max_steps', max_steps, err, at_least=1, at_most=max_steps_ceiling, &
                       why=max_steps_reason)
    if (err%failed()) return
    if (problem == 'kinetics' .and. log10(t_first) + n_outputs*log10(factor) > 300.0_dp) &
      call invalid_value(deck, g, 'n_outputs', str(n_outputs), 'the last output time t_first*factor**n_outputs '// &
                         'must stay below 1e300', err)
    if (err%failed()) return

    call out%echo_group(lsode_check_group)

    if (problem == 'kinetics') then
      neq = 3
      y = [1.0_dp, 0.0_dp, 0.0_dp]
      sys => kinetics
      call out%comment('problem: Robertson chemical kinetics, the stiff example of DLSODE''s prologue')
      call ode%init(neq, 0.0_dp, mf, rtol, atol, err, ml=2, mu=2, max_steps=max_steps)
    else
      neq = 2
      y = [1.0_dp, 0.0_dp]
      oscillator%omega = omega
      sys => oscillator
      call out%comment('problem: undamped oscillator y'''' = -omega^2 y, y(0) = 1, exact y = cos(omega t)')
      call ode%init(neq, 0.0_dp, mf, rtol, atol(1:1), err, ml=1, mu=1, max_steps=max_steps)
    end if
    if (err%failed()) return
    call out%comment('method: '//trim(method)//' (DLSODE MF='//str(mf)//')')
    if (neq == 3) then
      call out%columns([character(len=16) :: 't', 'y1', 'y2', 'y3', 'y1+y2+y3-1'])
    else
      call out%columns([character(len=16) :: 't', 'y', 'dy/dt', 'y_exact', 'error'])
    end if

    tout = t_first
    do k = 1, n_outputs
      call ode%integrate_to(sys, y, tout, err)
      if (err%failed()) exit
      if (neq == 3) then
        call out%row([tout, y, sum(y) - 1.0_dp])
      else
        call out%row([tout, y, cos(omega*tout), y(1) - cos(omega*tout)])
      end if
      if (problem == 'kinetics') then
        tout = tout*factor
      else
        tout = tout + t_first
      end if
    end do

    c = ode%counters()
    if (.not. err%failed()) then
      call out%summary('final state', str(y(1))//' '//str(y(2)))
      if (problem == 'oscillator') call out%summary('periods integrated', str(omega*(tout - t_first)/two_pi))
    end if
    call out%cost('cpu_seconds', str(c%cpu_seconds, 4))
    call out%cost('steps', str(c%steps))
    call out%cost('rhs_evaluations', str(c%rhs_evals))
    call out%cost('jacobian_evaluations', str(c%jac_evals))
    call out%cost('lu_factorizations', str(c%lu_factorizations))
    call out%cost('last_method_order', str(c%order_last))
    if (mf == mf_adams) call out%comment('note: Adams (MF=10) uses functional iteration: no Jacobians, no LU')
  end subroutine run_lsode_check

  subroutine kinetics_rhs(self, t, y, ydot)
    class(kinetics_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    ydot(1) = -0.04_dp*y(1) + 1.0e4_dp*y(2)*y(3)
    ydot(3) = 3.0e7_dp*y(2)*y(2)
    ydot(2) = -ydot(1) - ydot(3)
    if (.false.) call self%fail(t, '')
  end subroutine kinetics_rhs

  !> Full or banded (ml = mu = 2 covers the whole 3x3) analytic Jacobian.
  subroutine kinetics_jac(self, t, y, ml, mu, pd)
    class(kinetics_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    real(dp) :: j(3, 3)
    if (.false.) call self%fail(t, '')
    j(1, :) = [-0.04_dp, 1.0e4_dp*y(3), 1.0e4_dp*y(2)]
    j(3, :) = [0.0_dp, 6.0e7_dp*y(2), 0.0_dp]
    j(2, :) = -j(1, :) - j(3, :)
    call store_jacobian(j, ml, mu, pd)
  end subroutine kinetics_jac

  subroutine oscillator_rhs(self, t, y, ydot)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    if (.false.) call self%fail(t, '')
    ydot(1) = y(2)
    ydot(2) = -self%omega**2*y(1)
  end subroutine oscillator_rhs

  subroutine oscillator_jac(self, t, y, ml, mu, pd)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    real(dp) :: j(2, 2)
    if (.false.) call self%fail(t + y(1), '')
    j = reshape([0.0_dp, -self%omega**2, 1.0_dp, 0.0_dp], [2, 2])
    call store_jacobian(j, ml, mu, pd)
  end subroutine oscillator_jac

  !> DLSODE's layouts: full pd(i, j) = J(i, j) (DLSODE passes ml = mu = 0 and
  !> n rows); banded pd(i - j + mu + 1, j) = J(i, j) otherwise.
  pure subroutine store_jacobian(j, ml, mu, pd)
    real(dp), intent(in) :: j(:, :)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    integer :: r, c, n
    n = size(j, 1)
    if (ml == 0 .and. mu == 0 .and. size(pd, 1) == n) then
      pd(1:n, 1:n) = j
    else
      do c = 1, n
        do r = max(1, c - mu), min(n, c + ml)
          pd(r - c + mu + 1, c) = j(r, c)
        end do
      end do
    end if
  end subroutine store_jacobian
end module lsode_check_analysis
