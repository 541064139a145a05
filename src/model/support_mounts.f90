!> Lumped flexible mounts under ground joints (doc/general_mechanism.md,
!> "Support structure"): a ground joint that sits on a mount instead of the
!> rigid ground becomes a point body of mass m_d per global direction d,
!> carried to the rigid ground by a spring k_d and a damper c_d.  Its
!> displacement u (global X, Y, Z) is the elastic translation the joint rule
!> gives the link ends there, so the mechanism's reaction excites the mount
!> and the mount's motion moves the links.  The rigid-body motion stays the
!> nominal one (u is elastic and small, like the links' deformation).
!>
!> Each mount adds to the equations of motion M q'' = F of the links
!>     M += P^T diag(m) P,   F += P^T (m g - k u - c u'),   K_t += P^T diag(k) P
!> (P picks the mount's three unknowns, g the gravity acceleration), to the
!> energies (1/2) m u'^2 and (1/2) k u^2, and carries the force k u + c u'
!> to the rigid ground.
!>
!> The links' mass matrix M0 is factored by the model; the mounts' masses
!> are a rank-3-per-mount update, solved by the Sherman-Morrison-Woodbury
!> identity with Y = M0^-1 P^T (one substitution per mount unknown, again
!> only when M0 changes):
!>     (M0 + P^T D P)^-1 b = x - Y (I + D P Y)^-1 D P x,   x = M0^-1 b,
!> where I + D P Y is regular for every D >= 0 (P Y is positive definite).
module support_mounts
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: lu_factor, lu_solve
  use band_kernels, only: band_cholesky_substitute
  implicit none
  private
  public :: support_mount_t, support_mounts_t

  !> One mount: the ground joint it carries and its constants per global direction.
  type :: support_mount_t
    character(len=16) :: joint_name = ''
    integer :: joint = 0                   !< joint number in the mechanism
    real(dp) :: mass(3) = 0.0_dp           !< lb s^2/in
    real(dp) :: stiffness(3) = 0.0_dp      !< lb/in
    real(dp) :: damping(3) = 0.0_dp        !< lb s/in
    integer :: dofs(3) = 0                 !< global unknowns of its displacement (set by the model)
  end type support_mount_t

  !> Every mount of a model and the Woodbury solve's work.
  type :: support_mounts_t
    type(support_mount_t), allocatable :: mounts(:)
    real(dp), allocatable :: y(:, :)        !< (n, 3 mounts) M0^-1 P^T
    real(dp), allocatable :: small(:, :)    !< LU of I + D P Y
    integer, allocatable :: ipiv(:)
  contains
    procedure :: count => mount_count
    procedure :: add_band
    procedure :: add_dense
    procedure :: add_forces
    procedure :: forces
    procedure :: energies
    procedure :: carried_force
    procedure :: newton_dampers
    procedure :: factor_update
    procedure :: solve_update
  end type support_mounts_t

contains

  integer function mount_count(self)
    class(support_mounts_t), intent(in) :: self
    mount_count = 0
    if (allocated(self%mounts)) mount_count = size(self%mounts)
  end function mount_count

  !> The mounts' mass into M (lower band storage, row 1 the diagonal) and
  !> stiffness into K_t (general band storage, row kd+1 the diagonal).
  subroutine add_band(self, kd, mass, stiff)
    class(support_mounts_t), intent(in) :: self
    integer, intent(in) :: kd
    real(dp), intent(inout) :: mass(:, :), stiff(:, :)
    integer :: k, d
    do k = 1, self%count()
      associate (mt => self%mounts(k))
        do d = 1, 3
          mass(1, mt%dofs(d)) = mass(1, mt%dofs(d)) + mt%mass(d)
          stiff(kd + 1, mt%dofs(d)) = stiff(kd + 1, mt%dofs(d)) + mt%stiffness(d)
        end do
      end associate
    end do
  end subroutine add_band

  !> The mounts' mass and stiffness into dense M and K_t.
  subroutine add_dense(self, mass, stiff)
    class(support_mounts_t), intent(in) :: self
    real(dp), intent(inout) :: mass(:, :), stiff(:, :)
    integer :: k, d, i
    do k = 1, self%count()
      associate (mt => self%mounts(k))
        do d = 1, 3
          i = mt%dofs(d)
          mass(i, i) = mass(i, i) + mt%mass(d)
          stiff(i, i) = stiff(i, i) + mt%stiffness(d)
        end do
      end associate
    end do
  end subroutine add_dense

  !> The forces on the mounts' unknowns, m g - k u - c u', mount by mount.
  function forces(self, q, qd, gravity) result(f)
    class(support_mounts_t), intent(in) :: self
    real(dp), intent(in) :: q(:), qd(:), gravity(3)
    real(dp) :: f(3*self%count())
    integer :: k
    do k = 1, self%count()
      f(3*k - 2:3*k) = self%mounts(k)%mass*gravity - self%carried_force(k, q, qd)
    end do
  end function forces

  !> f := f + P^T (m g - k u - c u') of every mount.
  subroutine add_forces(self, q, qd, gravity, f)
    class(support_mounts_t), intent(in) :: self
    real(dp), intent(in) :: q(:), qd(:), gravity(3)
    real(dp), intent(inout) :: f(:)
    real(dp) :: fm(3*self%count())
    integer :: k
    fm = self%forces(q, qd, gravity)
    do k = 1, self%count()
      f(self%mounts(k)%dofs) = f(self%mounts(k)%dofs) + fm(3*k - 2:3*k)
    end do
  end subroutine add_forces

  !> The force (global, lb) mount k carries to the rigid ground: k u + c u'.
  function carried_force(self, k, q, qd) result(f)
    class(support_mounts_t), intent(in) :: self
    integer, intent(in) :: k
    real(dp), intent(in) :: q(:), qd(:)
    real(dp) :: f(3)
    associate (mt => self%mounts(k))
      f = mt%stiffness*q(mt%dofs) + mt%damping*qd(mt%dofs)
    end associate
  end function carried_force

  !> The mounts' kinetic energy (1/2) m u'^2 and spring energy (1/2) k u^2.
  subroutine energies(self, q, qd, kinetic, spring)
    class(support_mounts_t), intent(in) :: self
    real(dp), intent(in) :: q(:), qd(:)
    real(dp), intent(out) :: kinetic, spring
    integer :: k
    kinetic = 0.0_dp
    spring = 0.0_dp
    do k = 1, self%count()
      associate (mt => self%mounts(k))
        kinetic = kinetic + 0.5_dp*sum(mt%mass*qd(mt%dofs)**2)
        spring = spring + 0.5_dp*sum(mt%stiffness*q(mt%dofs)**2)
      end associate
    end do
  end subroutine energies

  !> The mount dampers for DLSODE's Newton matrix (module second_order_newton,
  !> its pair dampers): blocks c - beta k (the stiffness enters K_t, whose
  !> damping the Newton matrix takes as beta K_t), two per mount, to the
  !> ground.  None allocated when every block is zero.
  subroutine newton_dampers(self, beta, blocks, dofs)
    class(support_mounts_t), intent(in) :: self
    real(dp), intent(in) :: beta
    real(dp), allocatable, intent(inout) :: blocks(:, :, :)
    integer, allocatable, intent(inout) :: dofs(:, :)
    integer :: k
    real(dp) :: c(3)
    if (allocated(blocks)) deallocate(blocks, dofs)
    if (self%count() == 0) return
    if (all([(maxval(abs(self%mounts(k)%damping - beta*self%mounts(k)%stiffness)) <= 0.0_dp, &
              k = 1, self%count())])) return
    allocate(blocks(2, 2, 2*self%count()), dofs(4, 2*self%count()))
    blocks = 0.0_dp
    dofs = 0
    do k = 1, self%count()
      associate (mt => self%mounts(k))
        c = mt%damping - beta*mt%stiffness
        blocks(1, 1, 2*k - 1) = c(1)
        blocks(2, 2, 2*k - 1) = c(2)
        dofs(1:2, 2*k - 1) = mt%dofs(1:2)
        blocks(1, 1, 2*k) = c(3)
        dofs(1, 2*k) = mt%dofs(3)
      end associate
    end do
  end subroutine newton_dampers

  !> Y = M0^-1 P^T and the LU of I + D P Y from the Cholesky factor of the
  !> links' mass matrix M0 (lower band storage, half-bandwidth kd).
  subroutine factor_update(self, chol, kd, err)
    class(support_mounts_t), intent(inout) :: self
    real(dp), intent(in), contiguous :: chol(:, :)
    integer, intent(in) :: kd
    type(error_t), intent(inout) :: err
    integer :: nm, j, k, d, idx(3*self%count())
    real(dp) :: dm(3*self%count())
    nm = 3*self%count()
    do k = 1, self%count()
      idx(3*k - 2:3*k) = self%mounts(k)%dofs
      dm(3*k - 2:3*k) = self%mounts(k)%mass
    end do
    if (.not. allocated(self%y)) allocate(self%y(size(chol, 2), nm), self%small(nm, nm), self%ipiv(nm))
    self%y = 0.0_dp
    do j = 1, nm
      self%y(idx(j), j) = 1.0_dp
      call band_cholesky_substitute(chol, kd, self%y(:, j))
    end do
    do j = 1, nm
      do d = 1, nm
        self%small(d, j) = dm(d)*self%y(idx(d), j)
      end do
      self%small(j, j) = self%small(j, j) + 1.0_dp
    end do
    call lu_factor(self%small, self%ipiv, err)
  end subroutine factor_update

  !> x := (M0 + P^T D P)^-1 (M0 x + P^T fm): from x = M0^-1 b, the solution
  !> with the mounts' forces fm (function forces) and masses (the work of
  !> factor_update must be current).
  subroutine solve_update(self, x, err, fm)
    class(support_mounts_t), intent(in) :: self
    real(dp), intent(inout) :: x(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(in) :: fm(:)
    real(dp) :: z(3*self%count())
    integer :: k
    x = x + matmul(self%y, fm)
    z = [(self%mounts(k)%mass*x(self%mounts(k)%dofs), k = 1, self%count())]
    call lu_solve(self%small, self%ipiv, z, err)
    x = x - matmul(self%y, z)
  end subroutine solve_update
end module support_mounts
