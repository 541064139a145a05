!> A mechanism model M(q, t) q'' = F(q, q', t) as DLSODE's first-order system:
!> the steps every second-order model (the planar and the spatial one) takes
!> the same way, written once.
!>
!> - The state is interleaved, y(2i-1) = q_i and y(2i) = q'_i, so that the
!>   Jacobian of the first-order system has the band structure of M and K_t
!>   (for DLSODE's banded BDF options); `rhs` splits it into q and q' and
!>   asks the model for q'' (`accelerations`).
!> - `jacobian` (MF = 21, 24 without the model's Newton matrix): the
!>   approximate J = [[0, I], [-M^-1 K_t, -beta M^-1 K_t]] (inertial stiffness
!>   and gyroscopic terms left out: the chord iteration needs an approximation
!>   only) from the model's dense M and K_t (module companion_jacobian).
!> - DLSODE's Newton matrix P = I - hl0 J without forming J (module
!>   second_order_newton): `newton_factor` has the model fill M and K_t in
!>   band storage (`assemble_band`, through `newton_fill`) and factors S;
!>   `newton_solve` solves with it.
!> - Where a run stopped: `name_stop_angle` names the crank angle of the
!>   time the model failed (ode_system_t%stop_time) in the run's error.
!>
!> A model extends this type and implements what differs: its rigid motion
!> (`set_time`), its elements' mass, force and tangent (`accelerations`,
!> `assemble_dense`, `assemble_band`), its stiffness-proportional damping
!> (`damping_beta`) and its crank angle (`crank_angle`).
module second_order_model
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use linalg, only: lu_factor, lu_solve
  use lsode_solver, only: ode_system_t
  use second_order_newton, only: second_order_newton_t
  use companion_jacobian, only: fill_companion_jacobian
  implicit none
  private
  public :: second_order_model_t

  type, abstract, extends(ode_system_t) :: second_order_model_t
    integer :: n = 0                              !< global unknowns
    integer :: kd = 0                             !< half-bandwidth of M and K_t
    real(dp), allocatable :: mass_band(:, :)      !< (kd+1, n) M, lower band storage (its factor once factored)
    real(dp), allocatable :: force(:)             !< F(q, q', t) of the last right-hand side
    type(second_order_newton_t) :: newton         !< DLSODE's Newton matrix, banded
    ! cost and diagnostics
    integer :: n_rhs = 0                          !< right-hand sides evaluated
    integer :: n_mass_factorizations = 0
    integer :: n_nonlinear_points = 0             !< nonlinear integrand evaluations (cost proxy)
    integer :: n_kinematics = 0                   !< rigid-body kinematics solutions
    logical :: stop_beyond_peak = .true.          !< stop when a strain passes the Ramberg-Osgood peak
    real(dp) :: t_states = -huge(1.0_dp)          !< time of the rigid states the model holds
    ! q, q', q'' of the right-hand side (automatic arrays of run-time size are heap-allocated)
    real(dp), allocatable :: work_q(:), work_qd(:), work_qdd(:)
  contains
    procedure :: rhs => model_rhs
    procedure :: jacobian => model_jacobian
    procedure :: has_newton_matrix => model_has_newton_matrix
    procedure :: newton_factor => model_newton_factor
    procedure :: newton_solve => model_newton_solve
    procedure :: state_size
    procedure :: size_state
    procedure :: name_stop_angle
    procedure :: newton_fill
    procedure(set_time_interface), deferred :: set_time
    procedure(accelerations_interface), deferred :: accelerations
    procedure(assemble_interface), deferred :: assemble_dense
    procedure(assemble_interface), deferred :: assemble_band
    procedure(beta_interface), deferred :: damping_beta
    procedure(angle_interface), deferred :: crank_angle
  end type second_order_model_t

  abstract interface
    !> Rigid states of every element at time t (self%fail when the kinematics fail).
    subroutine set_time_interface(self, t)
      import :: second_order_model_t, dp
      class(second_order_model_t), intent(inout) :: self
      real(dp), intent(in) :: t
    end subroutine set_time_interface
    !> q'' from M(q, t) q'' = F(q, q', t); self%fail when it cannot.
    subroutine accelerations_interface(self, t, q, qd, qdd)
      import :: second_order_model_t, dp
      class(second_order_model_t), intent(inout) :: self
      real(dp), intent(in) :: t, q(:), qd(:)
      real(dp), intent(out), contiguous :: qdd(:)
    end subroutine accelerations_interface
    !> M and the elastic tangent K_t at q and the current rigid states: dense
    !> (n x n), or banded (M lower band storage m(1+i-j, j), kd+1 rows; K_t
    !> general band storage k(kd+1+i-j, j), 2kd+1 rows).
    subroutine assemble_interface(self, q, mass, stiff)
      import :: second_order_model_t, dp
      class(second_order_model_t), intent(inout) :: self
      real(dp), intent(in) :: q(:)
      real(dp), intent(out), contiguous :: mass(:, :), stiff(:, :)
    end subroutine assemble_interface
    !> The stiffness-proportional damping coefficient beta (C = beta K_t).
    real(dp) function beta_interface(self)
      import :: second_order_model_t, dp
      class(second_order_model_t), intent(in) :: self
    end function beta_interface
    !> The crank angle (rad) at time t.
    real(dp) function angle_interface(self, t)
      import :: second_order_model_t, dp
      class(second_order_model_t), intent(in) :: self
      real(dp), intent(in) :: t
    end function angle_interface
  end interface

contains

  integer function state_size(self)
    class(second_order_model_t), intent(in) :: self
    state_size = 2*self%n
  end function state_size

  !> n unknowns, half-bandwidth kd: the mass band, the force and the work
  !> vectors of the right-hand side (again when the unknowns change).
  subroutine size_state(self, n, kd)
    class(second_order_model_t), intent(inout) :: self
    integer, intent(in) :: n, kd
    self%n = n
    self%kd = kd
    if (allocated(self%mass_band)) deallocate(self%mass_band, self%force, self%work_q, self%work_qd, self%work_qdd)
    allocate(self%mass_band(kd + 1, n), self%force(n), self%work_q(n), self%work_qd(n), self%work_qdd(n))
  end subroutine size_state

  !> The crank angle where a run stopped (at the model's failure, else at the
  !> solver's time t_solver) as context of its error: '<what> stopped at
  !> crank angle ... deg'.
  subroutine name_stop_angle(self, what, t_solver, err)
    class(second_order_model_t), intent(in) :: self
    character(len=*), intent(in) :: what
    real(dp), intent(in) :: t_solver
    type(error_t), intent(inout) :: err
    call err%add_context(what//' stopped at crank angle '// &
                         str(self%crank_angle(self%stop_time(t_solver))*180.0_dp/pi, 7)//' deg')
  end subroutine name_stop_angle

  subroutine model_rhs(self, t, y, ydot)
    class(second_order_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    self%n_rhs = self%n_rhs + 1
    self%work_q = y(1::2)      ! contiguous copies: the state is interleaved
    self%work_qd = y(2::2)
    call self%accelerations(t, self%work_q, self%work_qd, self%work_qdd)
    ydot(1::2) = self%work_qd
    ydot(2::2) = self%work_qdd
  end subroutine model_rhs

  !> Approximate Jacobian for DLSODE's BDF options (MF = 21, 24):
  !>   d(q_d)/dq_d = I,  d(q_dd)/dq = -M^-1 K_t,  d(q_dd)/dq_d = -beta M^-1 K_t.
  subroutine model_jacobian(self, t, y, ml, mu, pd)
    class(second_order_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    real(dp) :: mass(self%n, self%n), stiff(self%n, self%n), q(self%n)
    integer :: ipiv(self%n)
    type(error_t) :: err
    call self%set_time(t)
    q = y(1::2)
    call self%assemble_dense(q, mass, stiff)
    call lu_factor(mass, ipiv, err)
    if (err%failed()) then
      call self%fail(t, 'mass matrix in the Jacobian: '//err%text())
      return
    end if
    call lu_solve(mass, ipiv, stiff, err)      ! stiff := M^-1 K_t
    call fill_companion_jacobian(stiff, self%damping_beta(), ml, mu, pd)
  end subroutine model_jacobian

  logical function model_has_newton_matrix(self)
    class(second_order_model_t), intent(in) :: self
    model_has_newton_matrix = self%n > 0
  end function model_has_newton_matrix

  !> DLSODE's Newton matrix P = I - hl0 J for the Jacobian of model_jacobian,
  !> without forming J: the banded S = M + (hl0 beta + hl0^2) K_t of
  !> second_order_newton, O(N kd^2); ok = .false. when S is singular.  A model
  !> with terms of its own (pair dampers, a K_t known symmetric) overrides
  !> this with newton_fill, its terms and newton%factor.
  subroutine model_newton_factor(self, t, y, hl0, ok)
    class(second_order_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:), hl0
    logical, intent(out) :: ok
    call self%newton_fill(t, y, ok)
    if (ok) call self%newton%factor(hl0, self%damping_beta(), ok)
  end subroutine model_newton_factor

  !> M and K_t of the Newton matrix at (t, y) into self%newton (band
  !> storage); ok = .false. when the rigid motion failed.
  subroutine newton_fill(self, t, y, ok)
    class(second_order_model_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    logical, intent(out) :: ok
    ok = .false.
    call self%set_time(t)
    if (self%err%failed()) return
    call self%newton%size_for(self%n, self%kd)
    call self%assemble_band(y(1::2), self%newton%mass, self%newton%stiff)
    ok = .true.
  end subroutine newton_fill

  !> x := P^-1 x with the P of the last model_newton_factor.
  subroutine model_newton_solve(self, x)
    class(second_order_model_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    type(error_t) :: err
    call self%newton%solve(x, err)
    if (err%failed()) call self%fail(0.0_dp, err%text())
  end subroutine model_newton_solve
end module second_order_model
