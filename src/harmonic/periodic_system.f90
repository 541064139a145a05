!> A mechanism driven at constant crank speed, as the steady-state solvers
!> see it (T25):
!>
!>     M(t) Q_dd + C(t) Q_d + K_e(t) Q + f_n(Q, t) = F(t),   period T = 2 pi / omega
!>
!> with f_n = K_n(Q, t) Q the nonlinear part of the internal force.  The
!> harmonic-series method (module harmonic_solver) and the periodic shooting
!> reference (module periodic_shooting) work on any extension of this type;
!> module steady_model is the flexible linkage, the tests also use small
!> systems with known answers.
module periodic_system
  use kinds, only: dp
  use error_status, only: error_t
  implicit none
  private
  public :: periodic_system_t, nonlinear_info_t

  !> By-products of a nonlinear evaluation (material law checks, cost).
  type :: nonlinear_info_t
    real(dp) :: max_abs_strain = 0.0_dp
    integer :: element = 0                !< where the largest strain is
    logical :: beyond_peak = .false.      !< a strain passed the peak of the Ramberg-Osgood law
    integer :: n_points = 0               !< nonlinear integrand evaluations
  end type nonlinear_info_t

  type, abstract :: periodic_system_t
    integer :: n = 0                      !< global unknowns
    real(dp) :: omega = 0.0_dp            !< crank speed (rad/s)
    ! cost counters
    integer :: n_linear_evaluations = 0   !< assemblies of M, C, K_e, F
    integer :: n_nonlinear_evaluations = 0
    integer :: n_nonlinear_points = 0
  contains
    procedure(set_time_interface), deferred :: set_time
    procedure(linear_interface), deferred :: linear_terms
    procedure(nonlinear_interface), deferred :: nonlinear_terms
    procedure(flag_interface), deferred :: is_nonlinear
    procedure :: period
  end type periodic_system_t

  abstract interface
    !> Move the system to time t (rigid-body kinematics).
    subroutine set_time_interface(self, t, err)
      import :: periodic_system_t, dp, error_t
      class(periodic_system_t), intent(inout) :: self
      real(dp), intent(in) :: t
      type(error_t), intent(inout) :: err
    end subroutine set_time_interface

    !> M, C, K_e, F at the current time (dense n x n).  Without velocity terms
    !> C is not formed (returned zero) and damping is left out entirely.
    subroutine linear_interface(self, mass, damp, stiff, force, velocity_terms)
      import :: periodic_system_t, dp
      class(periodic_system_t), intent(inout) :: self
      real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
      logical, intent(in) :: velocity_terms
    end subroutine linear_interface

    !> f_n(Q) at the current time, optionally the secant K_n (K_n Q = f_n)
    !> and the tangent d f_n / dQ.
    subroutine nonlinear_interface(self, q, fn, info, secant, tangent)
      import :: periodic_system_t, dp, nonlinear_info_t
      class(periodic_system_t), intent(inout) :: self
      real(dp), intent(in) :: q(:)
      real(dp), intent(out) :: fn(:)
      type(nonlinear_info_t), intent(out) :: info
      real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    end subroutine nonlinear_interface

    logical function flag_interface(self)
      import :: periodic_system_t
      class(periodic_system_t), intent(in) :: self
    end function flag_interface
  end interface

contains

  real(dp) function period(self)
    class(periodic_system_t), intent(in) :: self
    period = 8.0_dp*atan(1.0_dp)/self%omega
  end function period
end module periodic_system
