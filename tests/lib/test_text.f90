!> Numbers as text for the tests' assertion messages (one home for what
!> nearly every suite wrote for itself).
module test_text
  use kinds, only: dp
  implicit none
  private
  public :: itoa, rtoa

contains

  !> An integer without blanks.
  pure function itoa(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=16) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function itoa

  !> A real in the edit descriptor `fmt` (default es11.4), without blanks.
  pure function rtoa(x, fmt) result(s)
    real(dp), intent(in) :: x
    character(len=*), intent(in), optional :: fmt
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if (present(fmt)) then
      write(buf, fmt) x
    else
      write(buf, '(es11.4)') x
    end if
    s = trim(adjustl(buf))
  end function rtoa
end module test_text
