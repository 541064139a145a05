!> Small string helpers used when composing messages and output headers.
module strings
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  implicit none
  private
  public :: str, lower, starts_with, compact, shell_quote, file_stem, append_name

  interface str
    module procedure str_int, str_real, str_logical
  end interface str

contains

  pure function str_int(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    character(len=32) :: buf
    write(buf, '(i0)') i
    s = trim(buf)
  end function str_int

  !> Shortest faithful-enough form: general format with 8 significant digits,
  !> or `digits` if given.
  pure function str_real(x, digits) result(s)
    real(dp), intent(in) :: x
    integer, intent(in), optional :: digits
    character(len=:), allocatable :: s
    character(len=48) :: buf
    character(len=16) :: fmt
    integer :: d
    d = 8
    if (present(digits)) d = digits
    ! a three-digit exponent needs an explicit exponent width, or the 'E' is
    ! dropped (0.1+301), which gnuplot and numpy cannot read
    ! (ieee_is_finite first: an ordered comparison with NaN traps in the debug build)
    if (.not. ieee_is_finite(x)) then
      write(fmt, '(a,i0,a,i0,a)') '(g', d + 8, '.', d, ')'
    else if (abs(x) >= 1.0e99_dp .or. (abs(x) < 1.0e-99_dp .and. abs(x) > 0.0_dp)) then
      write(fmt, '(a,i0,a,i0,a)') '(g', d + 9, '.', d, 'e3)'
    else
      write(fmt, '(a,i0,a,i0,a)') '(g', d + 8, '.', d, ')'
    end if
    write(buf, fmt) x
    s = trim(adjustl(buf))
  end function str_real

  !> Compact number for headers and messages: 6 significant digits, no
  !> trailing zeros (10.5, 1e-10, 2.5e+06).
  pure function compact(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    integer :: e, k
    if (.not. ieee_is_finite(x)) then
      s = str(x)
      return
    end if
    if (abs(x) < tiny(x)) then
      s = '0'
      return
    end if
    if (abs(x) >= 0.1_dp .and. abs(x) < 1.0e6_dp) then
      write(buf, '(g15.6)') x
    else
      write(buf, '(es14.5e3)') x
    end if
    buf = adjustl(buf)
    e = scan(buf, 'E')
    if (e == 0) e = len_trim(buf) + 1
    k = e - 1
    if (index(buf(1:k), '.') > 0) then
      do while (buf(k:k) == '0')
        k = k - 1
      end do
      if (buf(k:k) == '.') k = k - 1
    end if
    s = buf(1:k)
    if (e <= len_trim(buf)) s = s//'e'//exponent_text(buf(e + 1:len_trim(buf)))
  contains
    pure function exponent_text(t) result(x_text)
      character(len=*), intent(in) :: t       ! '+006', '-010'
      character(len=:), allocatable :: x_text
      integer :: i
      x_text = t(1:1)
      i = 2
      do while (i < len(t) .and. t(i:i) == '0')
        i = i + 1
      end do
      x_text = x_text//t(i:)
      if (x_text(1:1) == '+') x_text = x_text(2:)
    end function exponent_text
  end function compact

  pure function str_logical(b) result(s)
    logical, intent(in) :: b
    character(len=:), allocatable :: s
    if (b) then
      s = 'on'
    else
      s = 'off'
    end if
  end function str_logical

  pure function lower(s) result(t)
    character(len=*), intent(in) :: s
    character(len=len(s)) :: t
    integer :: i, c
    t = s
    do i = 1, len(s)
      c = iachar(s(i:i))
      if (c >= iachar('A') .and. c <= iachar('Z')) t(i:i) = achar(c + 32)
    end do
  end function lower

  logical pure function starts_with(s, prefix)
    character(len=*), intent(in) :: s, prefix
    starts_with = .false.
    if (len(s) >= len(prefix)) starts_with = s(1:len(prefix)) == prefix
  end function starts_with
  !> A word for /bin/sh: single-quoted, embedded quotes as '\''.
  pure function shell_quote(word) result(s)
    character(len=*), intent(in) :: word
    character(len=:), allocatable :: s
    integer :: i
    s = ''''
    do i = 1, len(word)
      if (word(i:i) == '''') then
        s = s//'''\'''''
      else
        s = s//word(i:i)
      end if
    end do
    s = s//''''
  end function shell_quote
  !> The file name without its directory and extension (a leading dot is kept:
  !> '.hidden' stays itself).
  pure function file_stem(path) result(stem)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: stem
    integer :: dot
    stem = path(index(path, '/', back=.true.) + 1:)
    dot = index(stem, '.', back=.true.)
    if (dot > 1) stem = stem(1:dot - 1)
  end function file_stem

  !> A name appended to a growing list of names (figures, metrics).
  subroutine append_name(names, name)
    character(len=64), allocatable, intent(inout) :: names(:)
    character(len=*), intent(in) :: name
    character(len=64), allocatable :: longer(:)
    allocate(longer(size(names) + 1))
    longer(1:size(names)) = names
    longer(size(longer)) = name
    call move_alloc(longer, names)
  end subroutine append_name
end module strings
