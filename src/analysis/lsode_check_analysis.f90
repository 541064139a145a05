!> The `lsode_check` analysis: runs DLSODE through flexmech's wrapper on the
!> stiff chemical-kinetics problem of LSODE's own documentation (Robertson),
!> or on an undamped oscillator with a closed-form solution, and tabulates the
!> solution with the cost of the run.  It is the smallest real analysis of the
!> program and the check that the ODEPACK build is sound.
module lsode_check_analysis
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use lsode_solver, only: ode_system_t, lsode_t, lsode_counters_t, mf_adams
  use lsode_check_settings, only: lsode_check_settings_t, read_lsode_check_settings, echo_lsode_check_settings
  implicit none
  private
  public :: run_lsode_check

  !> Robertson's reactions y1 -> y2 (k1), y2 + y3 -> y1 + y3 (k2), 2 y2 -> y3 + y2 (k3).
  type, extends(ode_system_t) :: kinetics_t
    real(dp) :: k1 = 0.04_dp, k2 = 1.0e4_dp, k3 = 3.0e7_dp
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

contains

  subroutine run_lsode_check(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(lsode_check_settings_t) :: s
    integer :: k, neq
    real(dp) :: tout
    real(dp), allocatable :: y(:)
    type(kinetics_t), target :: kinetics
    type(oscillator_t), target :: oscillator
    class(ode_system_t), pointer :: sys
    type(lsode_t) :: ode
    type(lsode_counters_t) :: c

    call read_lsode_check_settings(deck, s, err)
    if (err%failed()) return
    call echo_lsode_check_settings(s, out)

    if (s%problem == 'kinetics') then
      neq = 3
      y = [1.0_dp, 0.0_dp, 0.0_dp]
      sys => kinetics
      call out%comment('problem: Robertson chemical kinetics, the stiff example of DLSODE''s prologue')
      call ode%init(neq, 0.0_dp, s%mf, s%rtol, s%atol, err, ml=2, mu=2, max_steps=s%max_steps)
    else
      neq = 2
      y = [1.0_dp, 0.0_dp]
      oscillator%omega = s%omega
      sys => oscillator
      call out%comment('problem: undamped oscillator y'''' = -omega^2 y, y(0) = 1, exact y = cos(omega t)')
      call ode%init(neq, 0.0_dp, s%mf, s%rtol, s%atol(1:1), err, ml=1, mu=1, max_steps=s%max_steps)
    end if
    if (err%failed()) return
    call out%comment('method: '//trim(s%method)//' (DLSODE MF='//str(s%mf)//')')
    if (neq == 3) then
      call out%columns([character(len=16) :: 't', 'y1', 'y2', 'y3', 'y1+y2+y3-1'])
    else
      call out%columns([character(len=16) :: 't', 'y', 'dy/dt', 'y_exact', 'error'])
    end if

    tout = s%t_first
    do k = 1, s%n_outputs
      call ode%integrate_to(sys, y, tout, err)
      if (err%failed()) exit
      if (neq == 3) then
        call out%row([tout, y, sum(y) - 1.0_dp])
      else
        call out%row([tout, y, cos(s%omega*tout), y(1) - cos(s%omega*tout)])
      end if
      if (s%problem == 'kinetics') then
        tout = tout*s%factor
      else
        tout = tout + s%t_first
      end if
    end do

    c = ode%counters()
    if (.not. err%failed()) then
      call out%summary('final state', str(y(1))//' '//str(y(2)))
      if (s%problem == 'oscillator') call out%summary('periods integrated', str(s%omega*(tout - s%t_first)/two_pi))
    end if
    call out%cost('cpu_seconds', str(c%cpu_seconds, 4))
    call out%cost('steps', str(c%steps))
    call out%cost('rhs_evaluations', str(c%rhs_evals))
    call out%cost('jacobian_evaluations', str(c%jac_evals))
    call out%cost('lu_factorizations', str(c%lu_factorizations))
    call out%cost('last_method_order', str(c%order_last))
    if (s%mf == mf_adams) call out%comment('note: Adams (MF=10) uses functional iteration: no Jacobians, no LU')
  end subroutine run_lsode_check

  ! Both systems are autonomous: the time the interface gives is named in an
  ! empty associate block (the idiom for an argument a fixed interface
  ! imposes, module lsode_solver).

  subroutine kinetics_rhs(self, t, y, ydot)
    class(kinetics_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    associate (unused_t => t)
    end associate
    ydot(1) = -self%k1*y(1) + self%k2*y(2)*y(3)
    ydot(3) = self%k3*y(2)*y(2)
    ydot(2) = -ydot(1) - ydot(3)
  end subroutine kinetics_rhs

  !> Full or banded (ml = mu = 2 covers the whole 3x3) analytic Jacobian.
  subroutine kinetics_jac(self, t, y, ml, mu, pd)
    class(kinetics_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    real(dp) :: j(3, 3)
    associate (unused_t => t)
    end associate
    j(1, :) = [-self%k1, self%k2*y(3), self%k2*y(2)]
    j(3, :) = [0.0_dp, 2.0_dp*self%k3*y(2), 0.0_dp]
    j(2, :) = -j(1, :) - j(3, :)
    call store_jacobian(j, ml, mu, pd)
  end subroutine kinetics_jac

  subroutine oscillator_rhs(self, t, y, ydot)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    associate (unused_t => t)
    end associate
    ydot(1) = y(2)
    ydot(2) = -self%omega**2*y(1)
  end subroutine oscillator_rhs

  subroutine oscillator_jac(self, t, y, ml, mu, pd)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    real(dp) :: j(2, 2)
    associate (unused_t => t, unused_y => y)
    end associate
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
