!> Four-bar path generation with circular crank-pivot regions (Boston et
!> al., paper B Table 3; doc/optimization.md), as a sum-of-squares problem for the
!> Gauss family.
!>
!> Variables: x1 ground link, x2 crank, x3 coupler, x4 rocker, x5 crank pin B
!> to coupler point, x6 ground-link angle, x7 coupler-point offset angle, x8
!> initial crank angle (radians), (x10, x9) = (X, Y) of the fixed crank pivot.
!> Residuals: phi_{2i-1} = XX_i - XG_i, phi_{2i} = YY_i - YG_i, i = 1..8, so
!> F = Sum (XX_i - XG_i)^2 + (YY_i - YG_i)^2.
!>
!> The eight desired points and the crank increments appear only in B's
!> Fig. 1 [missing].  We make the target the paper's way: the coupler points
!> of a four-bar of the same family at eight crank positions, by default the
!> design of Table 3 at crank increments 0, 45, ..., 315 degrees.  Then F* = 0
!> at that design, which is feasible with g9, g13 and g14 at zero.
module fourbar_path
  use kinds, only: dp, pi
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  implicit none
  private
  public :: fourbar_path_t, coupler_point, fourbar_constraints
  public :: table3_design, paper_start, default_dgamma, n_points, offset_target

  integer, parameter :: n_points = 8
  !> B Table 3, GNLC column (rounded as printed)
  real(dp), parameter :: table3_design(10) = [30.0_dp, 8.345_dp, 25.821_dp, 12.817_dp, 16.026_dp, &
                                              -1.063_dp, 1.259_dp, 1.118_dp, 4.0_dp, 7.0_dp]
  !> A target four-bar just outside the feasible set (x1 = 31 > 30, crank
  !> pivot (7.4, 3.6) outside both circles; x3, x4 lengthened to stay Grashof):
  !> the constrained optimum then has F* > 0 and g9, g13, g14 active with
  !> positive multipliers, like B's Table 3 (F = 1.78, active 9, 13, 14).
  real(dp), parameter :: offset_target(10) = [31.0_dp, 8.345_dp, 26.5_dp, 13.2_dp, 16.026_dp, &
                                              -1.063_dp, 1.259_dp, 1.118_dp, 3.6_dp, 7.4_dp]
  !> B Table 3, starting point (feasible; g5, g6, g7 at zero)
  real(dp), parameter :: paper_start(10) = [15.0_dp, 5.0_dp, 15.0_dp, 5.0_dp, 15.0_dp, &
                                            -0.007_dp, 0.412_dp, 1.379_dp, 6.0_dp, 5.0_dp]
  real(dp), parameter :: default_dgamma(n_points) = [0.0_dp, 0.25_dp*pi, 0.5_dp*pi, 0.75_dp*pi, pi, &
                                                     1.25_dp*pi, 1.5_dp*pi, 1.75_dp*pi]
  !> crank-pivot circles (CX, CY, R), B: 4, 4, 3 and 7, 7, 3
  real(dp), parameter :: circles(3, 2) = reshape([4.0_dp, 4.0_dp, 3.0_dp, 7.0_dp, 7.0_dp, 3.0_dp], [3, 2])

  type, extends(opt_problem_t) :: fourbar_path_t
    real(dp) :: xg(n_points) = 0.0_dp, yg(n_points) = 0.0_dp   !< desired path points
    real(dp) :: dgamma(n_points) = 0.0_dp                       !< crank increments (rad)
    real(dp) :: target_design(10) = 0.0_dp
    integer :: assembly_clamps = 0     !< arccos arguments outside [-1, 1] met (clamped)
  contains
    procedure :: setup => fourbar_setup
    procedure :: residuals => fourbar_residuals
  end type fourbar_path_t

contains

  !> Coupler point (XX, YY) at crank angle gamma (B, reconstructed, §10.3):
  !>   eps = atan[x2 sin(gamma - x6) / (x1 - x2 cos(gamma - x6))]
  !>   eta = acos[(x1^2 + x2^2 + x3^2 - x4^2 - 2 x1 x2 cos(gamma - x6)) / (2 x3 d)]
  !>   psi = x6 + x7 + eta - eps
  !>   XX = x10 + x2 cos gamma + x5 cos psi ;  YY = x9 + x2 sin gamma + x5 sin psi
  !> d = |BD| = (x1^2 + x2^2 - 2 x1 x2 cos(gamma - x6))^(1/2).  `arg` returns the
  !> unclamped acos argument: |arg| > 1 means the linkage cannot assemble.
  pure subroutine coupler_point(x, gamma, xx, yy, arg)
    real(dp), intent(in) :: x(10), gamma
    real(dp), intent(out) :: xx, yy, arg
    real(dp) :: th, d, eps, eta, psi
    th = gamma - x(6)
    d = sqrt(max(x(1)**2 + x(2)**2 - 2.0_dp*x(1)*x(2)*cos(th), tiny(1.0_dp)))
    eps = atan2(x(2)*sin(th), x(1) - x(2)*cos(th))
    arg = (x(1)**2 + x(2)**2 + x(3)**2 - x(4)**2 - 2.0_dp*x(1)*x(2)*cos(th))/(2.0_dp*x(3)*d)
    eta = acos(max(-1.0_dp, min(1.0_dp, arg)))
    psi = x(6) + x(7) + eta - eps
    xx = x(10) + x(2)*cos(gamma) + x(5)*cos(psi)
    yy = x(9) + x(2)*sin(gamma) + x(5)*sin(psi)
  end subroutine coupler_point

  !> The 14 constraints g_i <= 0 of B (g2, g7, g11, g12 reconstructed [OCR?]).
  pure function fourbar_constraints(x) result(g)
    real(dp), intent(in) :: x(10)
    real(dp) :: g(14)
    g(1) = 1.0_dp - x(2)
    g(2) = 1.0_dp - x(5)
    g(3) = x(2) - x(1)
    g(4) = x(2) - x(3)
    g(5) = x(2) - x(4)
    g(6) = x(1) + x(2) - x(3) - x(4)       ! g6-g8: Grashof, the crank turns fully
    g(7) = x(2) + x(3) - x(1) - x(4)
    g(8) = x(2) + x(4) - x(1) - x(3)
    g(9) = x(1) - 30.0_dp
    g(10) = x(3) - 30.0_dp
    g(11) = x(4) - 30.0_dp
    g(12) = x(5) - 30.0_dp
    g(13) = (x(10) - circles(1, 1))**2 + (x(9) - circles(2, 1))**2 - circles(3, 1)**2
    g(14) = (x(10) - circles(1, 2))**2 + (x(9) - circles(2, 2))**2 - circles(3, 2)**2
  end function fourbar_constraints

  !> n_circles = 2: B's 14-constraint problem; 1: the 13-constraint variant of
  !> paper A (one circle, centre (4, 4), radius 3).  The target path comes from
  !> `target` (default Table 3's design) at crank increments `dgamma`.
  subroutine fourbar_setup(self, n_circles, target, dgamma)
    class(fourbar_path_t), intent(inout) :: self
    integer, intent(in) :: n_circles
    real(dp), intent(in), optional :: target(10), dgamma(n_points)
    real(dp) :: lin(10, 12), a(10, 10), b(10), arg
    integer :: i, c
    real(dp), parameter :: dconst(12) = [-1.0_dp, -1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, &
                                         30.0_dp, 30.0_dp, 30.0_dp, 30.0_dp]
    if (n_circles == 1) then
      call self%init_problem('fourbar_path_13', 10, 2*n_points, 13)
    else
      call self%init_problem('fourbar_path', 10, 2*n_points, 14)
    end if
    ! g1..g12 = lin(:, i)^T x - dconst(i), the same functions as fourbar_constraints
    lin = 0.0_dp
    lin(2, 1) = -1.0_dp
    lin(5, 2) = -1.0_dp
    lin(1:2, 3) = [-1.0_dp, 1.0_dp]
    lin([2, 3], 4) = [1.0_dp, -1.0_dp]
    lin([2, 4], 5) = [1.0_dp, -1.0_dp]
    lin(1:4, 6) = [1.0_dp, 1.0_dp, -1.0_dp, -1.0_dp]
    lin(1:4, 7) = [-1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp]
    lin(1:4, 8) = [-1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp]
    lin(1, 9) = 1.0_dp
    lin(3, 10) = 1.0_dp
    lin(4, 11) = 1.0_dp
    lin(5, 12) = 1.0_dp
    do i = 1, 12
      call self%set_linear_constraint(i, lin(:, i), dconst(i))
    end do
    ! circle c: (x10 - CX)^2 + (x9 - CY)^2 - R^2 = 1/2 x^T A x + b^T x - d
    do c = 1, n_circles
      a = 0.0_dp
      a(9, 9) = 2.0_dp
      a(10, 10) = 2.0_dp
      b = 0.0_dp
      b(9) = -2.0_dp*circles(2, c)
      b(10) = -2.0_dp*circles(1, c)
      call self%set_quadratic_constraint(12 + c, a, b, circles(3, c)**2 - circles(1, c)**2 - circles(2, c)**2)
    end do
    self%target_design = table3_design
    if (present(target)) self%target_design = target
    self%dgamma = default_dgamma
    if (present(dgamma)) self%dgamma = dgamma
    do i = 1, n_points
      call coupler_point(self%target_design, self%target_design(8) + self%dgamma(i), self%xg(i), self%yg(i), arg)
    end do
    self%assembly_clamps = 0
  end subroutine fourbar_setup

  !> One "analysis": the coupler point at the eight crank positions
  !> gamma_i = x8 + dgamma_i.  Designs that cannot assemble at some crank
  !> angle (|acos argument| > 1, possible only when g3-g8 are violated) get the
  !> clamped angle and are counted in assembly_clamps.
  subroutine fourbar_residuals(self, x, phi, err)
    class(fourbar_path_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    real(dp) :: xx, yy, arg
    integer :: i
    if (x(3) <= 0.0_dp) then
      phi = 0.0_dp
      call err%set('fourbar_path', 'coupler length x3 must be positive (x3 = '//trim(adjustl(real_text(x(3))))//')')
      return
    end if
    do i = 1, n_points
      call coupler_point(x, x(8) + self%dgamma(i), xx, yy, arg)
      if (abs(arg) > 1.0_dp) self%assembly_clamps = self%assembly_clamps + 1
      phi(2*i - 1) = xx - self%xg(i)
      phi(2*i) = yy - self%yg(i)
    end do
  end subroutine fourbar_residuals

  function real_text(v) result(s)
    real(dp), intent(in) :: v
    character(len=32) :: s
    write(s, '(es13.4e3)') v
  end function real_text
end module fourbar_path
