!> DLSODE's Newton matrix for a mechanism model M(q, t) q'' = F(q, q', t) in
!> first-order form (state interleaved, y(2i-1) = q_i, y(2i) = q'_i), with the
!> approximate Jacobian J = [[0, I], [-M^-1 K_t, -beta M^-1 K_t]], without
!> forming J (doc/transient.md, "The Newton matrix of BDF"): eliminating the
!> displacement corrections of P = I - hl0 J leaves the N x N band matrix
!>     S = M + (hl0 beta + hl0^2) K_t,
!> factored by banded Cholesky when K_t is symmetric and S positive definite,
!> by banded LU otherwise; O(N kd^2) per factorization, O(N kd) per solve.
!>
!> The model fills `mass` (lower band storage m(1+i-j, j), kd+1 rows) and
!> `stiff` (general band storage k(kd+1+i-j, j), 2kd+1 rows) at the state of
!> the factorization and calls `factor`; `solve` then serves DLSODE's DSOLSY
!> (module lsode_newton).  Any model with this structure (the planar and the
!> spatial mechanism models) can own one.
!>
!> Dampers between DOF pairs that do not damp in proportion to K_t (the
!> contacts of clearance joints): a model that has them sets `damper`, the
!> blocks D_k - beta K_k of each, and `damper_dofs`; then
!>     S = M + (hl0 beta + hl0^2) K_t + hl0 sum_k (D_k - beta K_k),
!> each block acting on e = q(dofs 1:2) - q(dofs 3:4) (add_pair_band).
module second_order_newton
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: band_lu_factor, band_lu_solve
  use band_kernels, only: band_cholesky_inplace, band_cholesky_substitute, symmetric_band_product, add_pair_band
  implicit none
  private
  public :: second_order_newton_t, symmetric_band, band_combination

  type :: second_order_newton_t
    integer :: n = 0, kd = 0
    real(dp), allocatable :: mass(:, :)     !< (kd+1, n) M, lower band storage (filled by the model)
    real(dp), allocatable :: stiff(:, :)    !< (2kd+1, n) K_t, general band storage (filled by the model)
    real(dp), allocatable :: chol(:, :)     !< (kd+1, n) Cholesky factor of S
    real(dp), allocatable :: lu(:, :)       !< (3kd+1, n) banded LU of S
    integer, allocatable :: ipiv(:)
    real(dp), allocatable :: damper(:, :, :)   !< (2, 2, k) D_k - beta K_k of the pair dampers (filled by the model)
    integer, allocatable :: damper_dofs(:, :)  !< (4, k) their DOFs (0: ground)
    real(dp), allocatable :: r1(:), r2(:), dv(:)   !< work of solve
    real(dp) :: hl0 = 0.0_dp                !< h*el0 of the last factorization
    real(dp) :: beta = 0.0_dp               !< beta of the last factorization
    logical :: cholesky = .true.            !< S was factored by Cholesky (else banded LU)
    integer :: n_factorizations = 0
    integer :: n_lu = 0                     !< of which by banded LU
  contains
    procedure :: size_for
    procedure :: factor
    procedure :: solve
  end type second_order_newton_t

contains

  !> Work arrays for n unknowns and half-bandwidth kd (kept when the sizes agree).
  subroutine size_for(self, n, kd)
    class(second_order_newton_t), intent(inout) :: self
    integer, intent(in) :: n, kd
    if (allocated(self%mass) .and. self%n == n .and. self%kd == kd) return
    if (allocated(self%mass)) deallocate(self%mass, self%stiff, self%chol, self%lu, self%ipiv, self%r1, self%r2, &
                                         self%dv)
    self%n = n
    self%kd = kd
    allocate(self%mass(kd + 1, n), self%stiff(2*kd + 1, n), self%chol(kd + 1, n), self%lu(3*kd + 1, n), &
             self%ipiv(n), self%r1(n), self%r2(n), self%dv(n))
  end subroutine size_for

  !> Factor S = M + (hl0 beta + hl0^2) K_t (+ the dampers) from the filled
  !> mass and stiff; ok = .false. when S is singular (DLSODE then cuts the
  !> step).  symmetric: K_t's symmetry when the model knows it (the check
  !> costs a fifth of a factorization).
  subroutine factor(self, hl0, beta, ok, symmetric)
    class(second_order_newton_t), intent(inout) :: self
    real(dp), intent(in) :: hl0, beta
    logical, intent(out) :: ok
    logical, intent(in), optional :: symmetric
    type(error_t) :: err
    real(dp) :: c
    integer :: kd, n, i, j, info
    kd = self%kd
    n = self%n
    c = hl0*beta + hl0**2
    self%hl0 = hl0
    self%beta = beta
    self%n_factorizations = self%n_factorizations + 1
    if (present(symmetric)) then
      self%cholesky = symmetric
    else
      self%cholesky = symmetric_band(self%stiff, kd)
    end if
    if (self%cholesky) then
      self%chol = self%mass + c*self%stiff(kd + 1:, :)
      call add_dampers(self, hl0, self%chol, 1, .true.)
      call band_cholesky_inplace(self%chol, kd, info)
      self%cholesky = info == 0
    end if
    if (self%cholesky) then
      ok = .true.
      return
    end if
    ! banded LU: S in rows kd+1.. of the general band layout ab(2kd+1+i-j, j)
    self%n_lu = self%n_lu + 1
    self%lu = 0.0_dp
    self%lu(kd + 1:, :) = c*self%stiff
    do j = 1, n
      do i = j, min(n, j + kd)
        self%lu(2*kd + 1 + i - j, j) = self%lu(2*kd + 1 + i - j, j) + self%mass(1 + i - j, j)
        if (i > j) self%lu(2*kd + 1 + j - i, i) = self%lu(2*kd + 1 + j - i, i) + self%mass(1 + i - j, j)
      end do
    end do
    call add_dampers(self, hl0, self%lu, 2*kd + 1, .false.)
    call band_lu_factor(self%lu, kd, kd, self%ipiv, err)
    ok = .not. err%failed()
  end subroutine factor

  !> band += hl0 (D_k - beta K_k) of every pair damper (rows from off:
  !> 1 in the Cholesky's lower band storage, 2kd+1 in the LU's layout).
  subroutine add_dampers(self, hl0, band, off, lower)
    type(second_order_newton_t), intent(in) :: self
    real(dp), intent(in) :: hl0
    real(dp), intent(inout) :: band(:, :)
    integer, intent(in) :: off
    logical, intent(in) :: lower
    integer :: k
    if (.not. allocated(self%damper)) return
    do k = 1, size(self%damper, 3)
      call add_pair_band(self%damper_dofs(:, k), self%damper(:, :, k), hl0, band, off, lower)
    end do
  end subroutine add_dampers

  !> x := P^-1 x.  With x = (r1, r2) (displacement and rate rows, interleaved),
  !> P (dq, dv) = (r1, r2) is dq - hl0 dv = r1, dv + hl0 M^-1 (K_t dq + beta K_t dv) = r2:
  !>     S dv = M r2 - hl0 K_t r1,   dq = r1 + hl0 dv.
  !> With S = M + c K_t, c = hl0 (beta + hl0) and no dampers, hl0 K_t =
  !> (S - M)/(beta + hl0), so
  !>     dv = S^-1 M (r2 + g r1) - g r1,   g = 1/(beta + hl0):
  !> one symmetric band product with M instead of M and the general band K_t
  !> (the same P; r1 is of order hl0 times a rate, so g r1 is a rate and
  !> nothing cancels).  This is taken when S was factored by Cholesky.
  subroutine solve(self, x, err)
    class(second_order_newton_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    type(error_t), intent(inout) :: err
    real(dp) :: g
    associate(r1 => self%r1, r2 => self%r2, dv => self%dv)
    r1 = x(1::2)
    if (self%cholesky .and. .not. allocated(self%damper)) then
      g = 1.0_dp/(self%beta + self%hl0)
      r2 = x(2::2) + g*r1
      call symmetric_band_product(self%mass, self%kd, r2, dv)
      call band_cholesky_substitute(self%chol, self%kd, dv)
      dv = dv - g*r1
    else
      r2 = x(2::2)
      call band_combination(self%mass, self%stiff, self%kd, r2, self%hl0, r1, dv)
      if (self%cholesky) then
        call band_cholesky_substitute(self%chol, self%kd, dv)
      else
        call band_lu_solve(self%lu, self%kd, self%kd, self%ipiv, dv, err)
      end if
      if (err%failed()) call err%add_context('Newton matrix solve')
    end if
    x(2::2) = dv
    x(1::2) = r1 + self%hl0*dv
    end associate
  end subroutine solve

  !> Whether a band matrix in general band storage (half-bandwidth kd) is
  !> symmetric to round-off (1e-10 of its largest entry).
  pure logical function symmetric_band(kb, kd) result(sym)
    real(dp), intent(in) :: kb(:, :)
    integer, intent(in) :: kd
    integer :: i, j, n
    real(dp) :: tol
    n = size(kb, 2)
    tol = 1.0e-10_dp*maxval(abs(kb))
    sym = .true.
    do j = 1, n
      do i = j + 1, min(n, j + kd)
        if (abs(kb(kd + 1 + i - j, j) - kb(kd + 1 + j - i, i)) > tol) then
          sym = .false.
          return
        end if
      end do
    end do
  end function symmetric_band

  !> y = M a - c K b for M symmetric in lower band storage m(1+i-j, j) and K
  !> in general band storage k(kd+1+i-j, j), both of half-bandwidth kd: O(N kd).
  pure subroutine band_combination(m, k, kd, a, c, b, y)
    real(dp), intent(in), contiguous :: m(:, :), k(:, :), a(:), b(:)
    real(dp), intent(in) :: c
    integer, intent(in) :: kd
    real(dp), intent(out), contiguous :: y(:)
    integer :: i, j, n
    real(dp) :: aj, cbj, s
    n = size(a)
    y = 0.0_dp
    do j = 1, n
      aj = a(j)
      cbj = c*b(j)
      s = m(1, j)*aj
      do i = max(1, j - kd), min(n, j + kd)
        y(i) = y(i) - k(kd + 1 + i - j, j)*cbj
      end do
      do i = j + 1, min(n, j + kd)
        y(i) = y(i) + m(1 + i - j, j)*aj
        s = s + m(1 + i - j, j)*a(i)
      end do
      y(j) = y(j) + s
    end do
  end subroutine band_combination
end module second_order_newton
