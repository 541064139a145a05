!> The deck of one sweep point: the sweep deck's own lines without its &sweep
!> group, with `variable = value` added at the end of the varied group (a
!> later assignment in a namelist group overrides an earlier one), or the
!> group added when the deck does not have it.  Each point deck is written
!> beside its output, so every point can be rerun on its own.
module point_deck
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t, terminator_column
  use strings, only: str
  implicit none
  private
  public :: write_point_deck, value_text, assignment_text

contains

  subroutine write_point_deck(deck, group, variable, value, path, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group, variable, path
    real(dp), intent(in) :: value
    type(error_t), intent(inout) :: err
    integer :: u, ios, i, s_first, s_last, g_first, g_last, col
    character(len=:), allocatable :: line, assign
    call deck%group_line_range('sweep', s_first, s_last)
    call deck%group_line_range(group, g_first, g_last)
    assign = assignment_text(variable, value)
    open(newunit=u, file=path, status='replace', action='write', iostat=ios)
    if (ios /= 0) then
      call err%set('sweep', 'cannot write the point deck '''//path//'''', 1)
      return
    end if
    write(u, '(a)') '! sweep point: '//assign//' in &'//group//' (written by flexmech from '//deck%path//')'
    do i = 1, size(deck%lines)
      if (s_first > 0 .and. i >= s_first .and. i <= s_last) cycle
      line = trim(deck%lines(i)%text)
      if (i == g_last) then
        col = terminator_column(line, i == g_first)
        write(u, '(a)') line(1:col - 1)
        write(u, '(a)') '  '//assign
        write(u, '(a)') line(col:)
      else
        write(u, '(a)') line
      end if
    end do
    if (g_first == 0) then
      write(u, '(a)') '&'//group
      write(u, '(a)') '  '//assign
      write(u, '(a)') '/'
    end if
    close(u)
  end subroutine write_point_deck

  !> 'name = v' or 'name(a:b) = n*v'.
  pure function assignment_text(variable, value) result(s)
    character(len=*), intent(in) :: variable
    real(dp), intent(in) :: value
    character(len=:), allocatable :: s
    integer :: p, c, a, b, ios
    s = trim(variable)//' = '//value_text(value)
    p = index(variable, '(')
    c = index(variable, ':')
    if (p == 0 .or. c == 0) return
    read(variable(p + 1:c - 1), *, iostat=ios) a
    if (ios /= 0) return
    read(variable(c + 1:len_trim(variable) - 1), *, iostat=ios) b
    if (ios /= 0 .or. b < a) return
    s = trim(variable)//' = '//str(b - a + 1)//'*'//value_text(value)
  end function assignment_text

  !> An integral value as an integer (readable by integer and real variables),
  !> any other with the fewest significant digits (15 to 17) that read back as
  !> the same double.
  pure function value_text(value) result(s)
    real(dp), intent(in) :: value
    character(len=:), allocatable :: s
    character(len=32) :: buf
    real(dp) :: back
    integer :: digits, ios
    if (abs(value) < 1.0e9_dp .and. abs(aint(value) - value) <= 0.0_dp) then
      s = str(nint(value))
      return
    end if
    do digits = merge(17, 15, abs(value) > 1.0e307_dp), 17
      ! (near huge() a shorter text rounds up past it: reading it back overflows)
      write(buf, '(es32.'//str(digits - 1)//'e3)') value
      read(buf, *, iostat=ios) back
      if (ios == 0 .and. abs(back - value) <= 0.0_dp) exit
    end do
    s = trim(adjustl(buf))
  end function value_text
end module point_deck
