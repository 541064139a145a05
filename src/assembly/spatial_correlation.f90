!> The variable correlation table of the spatial analysis: the one table of
!> src/assembly/correlation_table.f90 (`correlation_base_t`: every element DOF
!> equals a coefficient times one global unknown, or is held at zero; gather,
!> scatter, labels, half-bandwidth) for El-Sawy's 20-DOF elements.  The spatial
!> model fills it node by node from its joint rules (doc/spatial.md,
!> "Joints"); this module adds the spatial DOF names and the header listing.
module spatial_correlation
  use strings, only: str
  use correlation_table, only: correlation_base_t
  implicit none
  private
  public :: spatial_table_t, sdofs

  integer, parameter :: sdofs = 20
  character(len=4), parameter :: node_dof_names(8) = ['UX  ', 'UY  ', 'UZ  ', 'RX  ', 'RY  ', 'RZ  ', 'vxx ', 'wxx ']

  type, extends(correlation_base_t) :: spatial_table_t
  contains
    procedure :: init
    procedure :: describe
  end type spatial_table_t

contains

  !> An empty table of n_elements spatial elements.
  subroutine init(self, n_elements)
    class(spatial_table_t), intent(inout) :: self
    integer, intent(in) :: n_elements
    call self%start_table(n_elements, sdofs)
  end subroutine init

  !> Header lines: element DOFs -> global unknowns, and the unknowns' names.
  subroutine describe(self, lines)
    class(spatial_table_t), intent(in) :: self
    character(len=160), allocatable, intent(out) :: lines(:)
    character(len=160) :: head(2), rows(self%n_elements())
    integer :: e, i, k
    character(len=160) :: l
    head(1) = 'variable correlation table: '//str(self%n_elements())//' elements, '//str(self%n_unknowns())// &
              ' global unknowns, half-bandwidth '//str(self%band())
    l = '  element :'
    do k = 1, 2
      do i = 1, 8
        l = trim(l)//' '//adjustr(node_dof_names(i)(1:3))//str(k)
      end do
    end do
    head(2) = trim(l)//'   (global unknown; 0 = held at zero; RX..RZ global or, at a spherical end, local)'
    do e = 1, self%n_elements()
      write(rows(e), '(2x,i7,a,20i5)') e, ' :', self%unknowns(e)
    end do
    call self%table_lines(head, rows, 22, lines)
  end subroutine describe
end module spatial_correlation
