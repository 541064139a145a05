!> Small ODE systems with known solutions or documented output, shared by
!> the DLSODE suites (test_lsode_solver, test_lsode_events, test_lsode_newton) and the
!> contact-law suite: each is an ode_system_t the wrapper integrates.
module ode_problems
  use kinds, only: dp
  use contact_law, only: contact_law_t, normal_force
  use lsode_solver, only: ode_system_t
  implicit none
  private
  public :: decay_t, newton_decay_t, kinetics_t, oscillator_t, failing_t, impact_t

  !> y' = -y: y = y(0) exp(-t).
  type, extends(ode_system_t) :: decay_t
  contains
    procedure :: rhs => decay_rhs
  end type decay_t

  !> Robertson's chemical kinetics, the stiff example of DLSODE's prologue.
  type, extends(ode_system_t) :: kinetics_t
  contains
    procedure :: rhs => kinetics_rhs
    procedure :: jacobian => kinetics_jac
  end type kinetics_t

  !> Undamped oscillator y'' = -w^2 y, closed form y = cos(w t).
  type, extends(ode_system_t) :: oscillator_t
    real(dp) :: omega = 3.0_dp
  contains
    procedure :: rhs => oscillator_rhs
  end type oscillator_t

  !> A model that fails once t passes 0.5.
  type, extends(ode_system_t) :: failing_t
  contains
    procedure :: rhs => failing_rhs
  end type failing_t

  !> A mass m hitting the contact at speed v0: state (delta, delta_dot).
  type, extends(ode_system_t) :: impact_t
    type(contact_law_t) :: law
    real(dp) :: mass = 1.0_dp, v0 = 1.0_dp
  contains
    procedure :: rhs => impact_rhs
  end type impact_t

  !> y' = -k y (k = 1 ... n) with its own Newton matrix P = I + hl0 diag(k);
  !> the right-hand side fails (model error) for t > t_fail.
  type, extends(ode_system_t) :: newton_decay_t
    real(dp) :: t_fail = huge(1.0_dp)
    real(dp) :: hl0 = 0.0_dp
    integer :: n_factor = 0
  contains
    procedure :: rhs => newton_decay_rhs
    procedure :: has_newton_matrix => newton_decay_has_newton
    procedure :: newton_factor => newton_decay_factor
    procedure :: newton_solve => newton_decay_solve
  end type newton_decay_t

contains

  subroutine decay_rhs(self, t, y, ydot)
    class(decay_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    ydot = -y
    if (.false.) ydot(1) = t + merge(1.0_dp, 0.0_dp, self%err%failed())
  end subroutine decay_rhs

  subroutine kinetics_rhs(self, t, y, ydot)
    class(kinetics_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    ydot(1) = -0.04_dp*y(1) + 1.0e4_dp*y(2)*y(3)
    ydot(3) = 3.0e7_dp*y(2)*y(2)
    ydot(2) = -ydot(1) - ydot(3)
    if (.false.) call self%fail(t, '')
  end subroutine kinetics_rhs

  subroutine kinetics_jac(self, t, y, ml, mu, pd)
    class(kinetics_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    if (.false.) call self%fail(t + ml + mu, '')
    pd(1, 1) = -0.04_dp
    pd(1, 2) = 1.0e4_dp*y(3)
    pd(1, 3) = 1.0e4_dp*y(2)
    pd(2, 1) = 0.04_dp
    pd(2, 3) = -pd(1, 3)
    pd(3, 2) = 6.0e7_dp*y(2)
    pd(2, 2) = -pd(1, 2) - pd(3, 2)
  end subroutine kinetics_jac

  subroutine oscillator_rhs(self, t, y, ydot)
    class(oscillator_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    if (.false.) call self%fail(t, '')
    ydot(1) = y(2)
    ydot(2) = -self%omega**2*y(1)
  end subroutine oscillator_rhs

  subroutine failing_rhs(self, t, y, ydot)
    class(failing_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    ydot = -y
    if (t > 0.5_dp) call self%fail(t, 'mass matrix is not positive definite')
  end subroutine failing_rhs

  subroutine impact_rhs(self, t, y, ydot)
    class(impact_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    real(dp) :: f, d1, d2
    call normal_force(self%law, y(1), y(2), self%v0, f, d1, d2)
    ydot(1) = y(2)
    ydot(2) = -f/self%mass
    if (.false.) ydot(1) = t   ! t unused: the contact is autonomous
  end subroutine impact_rhs

  subroutine newton_decay_rhs(self, t, y, ydot)
    class(newton_decay_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    integer :: k
    if (t > self%t_fail) call self%fail(t, 'decay model stops past t_fail')
    do k = 1, size(y)
      ydot(k) = -k*y(k)
    end do
  end subroutine newton_decay_rhs

  logical function newton_decay_has_newton(self)
    class(newton_decay_t), intent(in) :: self
    newton_decay_has_newton = .true.
    if (.false.) newton_decay_has_newton = self%err%failed()   ! argument intentionally unused
  end function newton_decay_has_newton

  subroutine newton_decay_factor(self, t, y, hl0, ok)
    class(newton_decay_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:), hl0
    logical, intent(out) :: ok
    ok = .not. self%err%failed() .and. t >= 0.0_dp .and. size(y) > 0
    self%hl0 = hl0
    self%n_factor = self%n_factor + 1
  end subroutine newton_decay_factor

  subroutine newton_decay_solve(self, x)
    class(newton_decay_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    integer :: k
    do k = 1, size(x)
      x(k) = x(k)/(1.0_dp + self%hl0*k)
    end do
  end subroutine newton_decay_solve
end module ode_problems
