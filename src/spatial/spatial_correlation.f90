!> The variable correlation table of the spatial analysis (the papers' idea,
!> src/assembly/correlation_table.f90, for 20-DOF elements): every element
!> DOF equals a coefficient times one global unknown, or is held at zero.
!> The spatial model fills it node by node from its joint rules
!> (doc/spatial.md, "Joints"); this module owns the bookkeeping, the
!> half-bandwidth and the header listing.
module spatial_correlation
  use kinds, only: dp
  use strings, only: str
  implicit none
  private
  public :: spatial_table_t, sdofs

  integer, parameter :: sdofs = 20
  character(len=4), parameter :: node_dof_names(8) = ['UX  ', 'UY  ', 'UZ  ', 'RX  ', 'RY  ', 'RZ  ', 'vxx ', 'wxx ']

  type :: spatial_table_t
    integer :: n_elements = 0
    integer :: n_global = 0
    integer :: half_bandwidth = 0
    integer, allocatable :: map(:, :)              !< (20, n_elements), 0 = held at zero
    real(dp), allocatable :: coef(:, :)
    character(len=24), allocatable :: label(:)
  contains
    procedure :: init
    procedure :: new_unknown
    procedure :: finish
    procedure :: gather
    procedure :: gather_pair
    procedure :: scatter_add
    procedure :: describe
  end type spatial_table_t

contains

  subroutine init(self, n_elements)
    class(spatial_table_t), intent(inout) :: self
    integer, intent(in) :: n_elements
    self%n_elements = n_elements
    self%n_global = 0
    if (allocated(self%map)) deallocate(self%map, self%coef, self%label)
    allocate(self%map(sdofs, n_elements), self%coef(sdofs, n_elements), self%label(0))
    self%map = 0
    self%coef = 0.0_dp
  end subroutine init

  !> A fresh global unknown with a label such as 'crank N2 RZ'.
  integer function new_unknown(self, text) result(g)
    class(spatial_table_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    self%n_global = self%n_global + 1
    self%label = [character(len=24) :: self%label, text]
    g = self%n_global
  end function new_unknown

  !> Half-bandwidth of the assembled matrices.
  subroutine finish(self)
    class(spatial_table_t), intent(inout) :: self
    integer :: e, lo, hi
    self%half_bandwidth = 0
    do e = 1, self%n_elements
      if (all(self%map(:, e) == 0)) cycle
      lo = minval(self%map(:, e), mask=self%map(:, e) > 0)
      hi = maxval(self%map(:, e))
      self%half_bandwidth = max(self%half_bandwidth, hi - lo)
    end do
  end subroutine finish

  pure function gather(self, e, q) result(qe)
    class(spatial_table_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:)
    real(dp) :: qe(sdofs)
    integer :: i
    do i = 1, sdofs
      if (self%map(i, e) > 0) then
        qe(i) = self%coef(i, e)*q(self%map(i, e))
      else
        qe(i) = 0.0_dp
      end if
    end do
  end function gather

  !> gather of two global vectors (displacements and rates) in one pass.
  pure subroutine gather_pair(self, e, q, qd, qe, qde)
    class(spatial_table_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:), qd(:)
    real(dp), intent(out) :: qe(sdofs), qde(sdofs)
    integer :: i, g
    do i = 1, sdofs
      g = self%map(i, e)
      if (g > 0) then
        qe(i) = self%coef(i, e)*q(g)
        qde(i) = self%coef(i, e)*qd(g)
      else
        qe(i) = 0.0_dp
        qde(i) = 0.0_dp
      end if
    end do
  end subroutine gather_pair

  pure subroutine scatter_add(self, e, fe, f)
    class(spatial_table_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: fe(sdofs)
    real(dp), intent(inout) :: f(:)
    integer :: i
    do i = 1, sdofs
      if (self%map(i, e) > 0) f(self%map(i, e)) = f(self%map(i, e)) + self%coef(i, e)*fe(i)
    end do
  end subroutine scatter_add

  !> Header lines: element DOFs -> global unknowns, and the unknowns' names.
  subroutine describe(self, lines)
    class(spatial_table_t), intent(in) :: self
    character(len=160), allocatable, intent(out) :: lines(:)
    integer :: e, i, n, k
    character(len=160) :: l
    n = 3 + self%n_elements + (self%n_global + 3)/4
    allocate(lines(n))
    lines(1) = 'variable correlation table: '//str(self%n_elements)//' elements, '//str(self%n_global)// &
               ' global unknowns, half-bandwidth '//str(self%half_bandwidth)
    l = '  element :'
    do k = 1, 2
      do i = 1, 8
        l = trim(l)//' '//adjustr(node_dof_names(i)(1:3))//str(k)
      end do
    end do
    lines(2) = trim(l)//'   (global unknown; 0 = held at zero; RX..RZ global or, at a spherical end, local)'
    do e = 1, self%n_elements
      write(l, '(2x,i7,a,20i5)') e, ' :', self%map(:, e)
      lines(2 + e) = l
    end do
    lines(3 + self%n_elements) = '  global unknowns:'
    do i = 1, (self%n_global + 3)/4
      l = ''
      do e = 4*(i - 1) + 1, min(4*i, self%n_global)
        write(l(len_trim(l) + 1:), '(2x,i4,": ",a22)') e, self%label(e)
      end do
      lines(3 + self%n_elements + i) = l
    end do
  end subroutine describe
end module spatial_correlation
