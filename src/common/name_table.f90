!> Names of small integer codes (methods, kinds, statuses, return states)
!> kept in one table per family instead of a pair of select-case functions.
!>
!> A table is a character array whose entry k names code first + k - 1; a
!> blank entry is a gap (a code without a name).  `name_of` maps a code to
!> its name, `code_of` a name (case and surrounding blanks ignored) to its
!> code; both return the caller's `otherwise` outside the table.
module name_table
  use strings, only: lower
  implicit none
  private
  public :: name_of, code_of

contains

  !> The name of `code` (trailing blanks trimmed); `otherwise` for a code
  !> outside the table or on a gap.
  pure function name_of(names, code, first, otherwise) result(name)
    character(len=*), intent(in) :: names(:)
    integer, intent(in) :: code, first
    character(len=*), intent(in) :: otherwise
    character(len=:), allocatable :: name
    integer :: k
    k = code - first + 1
    name = otherwise
    if (k < 1 .or. k > size(names)) return
    if (len_trim(names(k)) > 0) name = trim(names(k))
  end function name_of

  !> The code named `name` (case and surrounding blanks ignored); `otherwise`
  !> for a name not in the table (a blank name never matches a gap).
  integer pure function code_of(names, name, first, otherwise) result(code)
    character(len=*), intent(in) :: names(:)
    character(len=*), intent(in) :: name
    integer, intent(in) :: first, otherwise
    character(len=len(name)) :: key
    integer :: k
    key = lower(adjustl(name))
    code = otherwise
    if (len_trim(key) == 0) return
    do k = 1, size(names)
      if (names(k) == key) then
        code = first + k - 1
        return
      end if
    end do
  end function code_of
end module name_table
