!> Namelist input decks: open a deck, read a group order-free, and turn every
!> way a read can fail into a message that names the deck, the group, the
!> offending line and its number.  All input errors carry code 2 (the main
!> program exits with status 2 and writes no output file).
!>
!> Preferred use, from the module that owns a group:
!>
!>     namelist /transient/ rtol, atol, ...     ! staging variables of that module
!>     ...set defaults...
!>     call deck%read_group('transient', read_transient_group, required=.false., found=found, err=err)
!>
!>     subroutine read_transient_group(unit, ios, iomsg)   ! a module procedure
!>       integer, intent(in) :: unit; integer, intent(out) :: ios; character(len=*), intent(inout) :: iomsg
!>       read(unit, nml=transient, iostat=ios, iomsg=iomsg)
!>     end subroutine
!>
!> Given the reader, a failed read is replayed on growing prefixes of the
!> group to find the line that breaks it (gfortran reports a wrong-type value
!> as an end of file, with no position).  `check_read` is the simpler form
!> for callers that do the read themselves; it names the line only for
!> unknown variables.
module deck_reader
  use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_underflow, ieee_get_halting_mode, &
                                           ieee_set_halting_mode, ieee_set_flag, ieee_support_halting
  use error_status, only: error_t
  use strings, only: str, lower
  implicit none
  private
  public :: deck_t, group_reader, invalid_value, input_error_code

  integer, parameter :: input_error_code = 2
  integer, parameter :: max_line = 1024

  abstract interface
    subroutine group_reader(unit, ios, iomsg)
      integer, intent(in) :: unit
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: iomsg
    end subroutine group_reader
  end interface

  type :: deck_t
    character(len=:), allocatable :: path
    integer :: unit = 0
    logical :: opened = .false.      ! newunit numbers are negative
    character(len=max_line), allocatable :: lines(:)   !< the deck's text, for messages
  contains
    procedure :: open => deck_open
    procedure :: close => deck_close
    procedure :: rewind => deck_rewind
    procedure :: has_group
    procedure :: read_group
    procedure :: check_read
    procedure :: group_line_range
  end type deck_t

contains

  subroutine deck_open(self, path, err)
    class(deck_t), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_t), intent(inout) :: err
    logical :: exists
    integer :: ios, n
    character(len=512) :: iomsg
    character(len=max_line) :: line
    self%path = trim(path)
    inquire(file=self%path, exist=exists)
    if (.not. exists) then
      call err%set('deck '''//self%path//'''', 'file not found', input_error_code)
      return
    end if
    open(newunit=self%unit, file=self%path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call err%set('deck '''//self%path//'''', 'cannot open: '//trim(iomsg), input_error_code)
      return
    end if
    n = 0
    do
      read(self%unit, '(a)', iostat=ios) line
      if (ios /= 0) exit
      n = n + 1
    end do
    self%opened = .true.
    allocate(self%lines(n))
    rewind(self%unit)
    do n = 1, size(self%lines)
      read(self%unit, '(a)') self%lines(n)
    end do
    rewind(self%unit)
  end subroutine deck_open

  subroutine deck_close(self)
    class(deck_t), intent(inout) :: self
    if (self%opened) close(self%unit)
    self%opened = .false.
  end subroutine deck_close

  subroutine deck_rewind(self)
    class(deck_t), intent(inout) :: self
    rewind(self%unit)
  end subroutine deck_rewind

  logical function has_group(self, group)
    class(deck_t), intent(in) :: self
    character(len=*), intent(in) :: group
    integer :: first, last
    call self%group_line_range(group, first, last)
    has_group = first > 0
  end function has_group

  !> Lines [first, last] of the group: from its '&name' to the line holding its
  !> terminating '/'.  first = 0 if absent; last = 0 if never terminated.
  subroutine group_line_range(self, group, first, last)
    class(deck_t), intent(in) :: self
    character(len=*), intent(in) :: group
    integer, intent(out) :: first, last
    integer :: i, k
    character(len=:), allocatable :: key
    character(len=max_line) :: l
    first = 0
    last = 0
    key = '&'//lower(trim(group))
    do i = 1, size(self%lines)
      l = adjustl(lower(self%lines(i)))
      if (l(1:1) == '!') cycle
      k = len(key)
      if (l(1:k) == key) then
        if (len_trim(l) == k .or. scan(l(k + 1:k + 1), ' ,/') == 1) then
          first = i
          exit
        end if
      end if
    end do
    if (first == 0) return
    do i = first, size(self%lines)
      if (has_terminator(self%lines(i), i == first, len(key))) then
        last = i
        return
      end if
    end do
  end subroutine group_line_range

  !> Does this line contain a '/' that ends a namelist group (outside quotes
  !> and comments)?  On the group's first line, skip the '&name' token.
  logical pure function has_terminator(line, is_first, key_len)
    character(len=*), intent(in) :: line
    logical, intent(in) :: is_first
    integer, intent(in) :: key_len
    integer :: i, start
    character(len=1) :: quote
    has_terminator = .false.
    quote = ' '
    start = 1
    if (is_first) start = index(line, '&') + key_len
    do i = start, len_trim(line)
      if (quote /= ' ') then
        if (line(i:i) == quote) quote = ' '
      else if (line(i:i) == '''' .or. line(i:i) == '"') then
        quote = line(i:i)
      else if (line(i:i) == '!') then
        return
      else if (line(i:i) == '/') then
        has_terminator = .true.
        return
      end if
    end do
  end function has_terminator

  !> Read one group through the owner's reader procedure and validate the read.
  subroutine read_group(self, group, reader, required, found, err)
    class(deck_t), intent(inout) :: self
    character(len=*), intent(in) :: group
    procedure(group_reader) :: reader
    logical, intent(in) :: required
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    integer :: ios, first, last, bad
    character(len=512) :: iomsg
    found = .false.
    call self%group_line_range(group, first, last)
    if (first == 0) then
      if (required) call err%set(context(self, group), 'required group is missing from the deck', input_error_code)
      return
    end if
    if (last == 0) then
      call err%set(context(self, group), 'group starting on line '//str(first)// &
                   ' is not closed with ''/''', input_error_code)
      return
    end if
    call self%rewind()
    iomsg = ''
    call read_quietly(reader, self%unit, ios, iomsg)
    if (ios == 0) then
      found = .true.
      return
    end if
    bad = first_bad_line(self, group, reader, first, last)
    if (bad > 0) then
      call err%set(context(self, group), 'cannot read line '//str(bad)//': "'//trim(adjustl(self%lines(bad)))// &
                   '": '//explain(iomsg, ios), input_error_code)
    else
      call err%set(context(self, group), explain(iomsg, ios), input_error_code)
    end if
  end subroutine read_group

  !> Call a group reader with overflow halting off: the C library's strtod
  !> raises the overflow flag on a value such as 1e309 (read as Infinity and
  !> rejected afterwards by the finiteness checks), which would otherwise
  !> trap in a build with -ffpe-trap=overflow.
  subroutine read_quietly(reader, unit, ios, iomsg)
    procedure(group_reader) :: reader
    integer, intent(in) :: unit
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    logical :: halt_overflow, halt_underflow
    if (.not. (ieee_support_halting(ieee_overflow) .and. ieee_support_halting(ieee_underflow))) then
      call reader(unit, ios, iomsg)
      return
    end if
    call ieee_get_halting_mode(ieee_overflow, halt_overflow)
    call ieee_get_halting_mode(ieee_underflow, halt_underflow)
    call ieee_set_halting_mode(ieee_overflow, .false.)
    call ieee_set_halting_mode(ieee_underflow, .false.)
    call reader(unit, ios, iomsg)
    call ieee_set_flag(ieee_overflow, .false.)
    call ieee_set_flag(ieee_underflow, .false.)
    call ieee_set_halting_mode(ieee_overflow, halt_overflow)
    call ieee_set_halting_mode(ieee_underflow, halt_underflow)
  end subroutine read_quietly

  !> Replay the group on growing prefixes of its lines; the first prefix that
  !> fails to read names the offending line.
  integer function first_bad_line(self, group, reader, first, last) result(bad)
    class(deck_t), intent(in) :: self
    character(len=*), intent(in) :: group
    procedure(group_reader) :: reader
    integer, intent(in) :: first, last
    integer :: k, u, ios, i
    character(len=512) :: iomsg
    bad = 0
    do k = first, last
      open(newunit=u, status='scratch', action='readwrite')
      do i = first, k
        write(u, '(a)') trim(self%lines(i))
      end do
      if (k < last) write(u, '(a)') '/'
      if (k == first .and. .not. has_terminator(self%lines(first), .true., len_trim(group) + 1)) then
        ! the '&group' line alone: nothing to test yet
        close(u)
        cycle
      end if
      rewind(u)
      iomsg = ''
      call read_quietly(reader, u, ios, iomsg)
      close(u)
      if (ios /= 0) then
        bad = k
        return
      end if
    end do
  end function first_bad_line

  !> For callers that perform `read(deck%unit, nml=...)` themselves.
  subroutine check_read(self, group, ios, iomsg, required, found, err)
    class(deck_t), intent(inout) :: self
    character(len=*), intent(in) :: group, iomsg
    integer, intent(in) :: ios
    logical, intent(in) :: required
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    integer :: first, last, i
    character(len=:), allocatable :: name
    found = ios == 0
    if (found) return
    call self%group_line_range(group, first, last)
    if (first == 0) then
      if (required) call err%set(context(self, group), 'required group is missing from the deck', input_error_code)
      return
    end if
    if (last == 0) then
      call err%set(context(self, group), 'group starting on line '//str(first)//' is not closed with ''/''', &
                   input_error_code)
      return
    end if
    ! an unknown variable: find the line that names it
    i = index(iomsg, 'object name ')
    if (i > 0) then
      name = lower(trim(iomsg(i + 12:)))
      do i = first, last
        if (index(lower(self%lines(i)), name) > 0) then
          call err%set(context(self, group), 'line '//str(i)//': "'//trim(adjustl(self%lines(i)))//'": ' &
                       //explain(iomsg, ios), input_error_code)
          return
        end if
      end do
    end if
    call err%set(context(self, group), 'lines '//str(first)//'-'//str(last)//': '//explain(iomsg, ios), &
                 input_error_code)
  end subroutine check_read

  !> A value that was read but breaks a rule.
  subroutine invalid_value(deck, group, variable, value_text, rule, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group, variable, value_text, rule
    type(error_t), intent(inout) :: err
    integer :: first, last, i
    character(len=:), allocatable :: at, var
    at = ''
    call deck%group_line_range(group, first, last)
    if (first > 0 .and. last > 0) then
      var = lower(trim(variable))
      i = index(var, '(')
      if (i > 1) var = var(1:i - 1)
      do i = first, last
        if (names_variable(lower(deck%lines(i)), var)) then
          at = ' (line '//str(i)//')'
          exit
        end if
      end do
    end if
    call err%set(context(deck, group), trim(variable)//' = '//trim(value_text)//at//': '//trim(rule), &
                 input_error_code)
  end subroutine invalid_value

  logical pure function names_variable(line, var)
    character(len=*), intent(in) :: line, var
    integer :: i, j
    names_variable = .false.
    i = index(line, var)
    do while (i > 0)
      j = i + len(var)
      if (i == 1 .or. scan(line(max(i - 1, 1):max(i - 1, 1)), ' ,&') == 1) then
        if (j > len(line)) return
        if (scan(line(j:j), ' =(') == 1) then
          names_variable = .true.
          return
        end if
      end if
      if (j > len(line)) return
      i = index(line(j:), var)
      if (i > 0) i = i + j - 1
    end do
  end function names_variable

  pure function context(deck, group) result(s)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group
    character(len=:), allocatable :: s
    s = 'deck '''//deck%path//''', group &'//trim(group)
  end function context

  pure function explain(iomsg, ios) result(s)
    character(len=*), intent(in) :: iomsg
    integer, intent(in) :: ios
    character(len=:), allocatable :: s
    if (index(iomsg, 'Cannot match namelist object name') > 0) then
      s = 'unknown variable '''//trim(iomsg(index(iomsg, 'name ') + 5:))//''''
    else if (ios < 0) then
      s = 'a value has the wrong type or form (e.g. text for a number, a real for an integer)'
    else if (len_trim(iomsg) > 0) then
      s = trim(iomsg)
    else
      s = 'read error (iostat '//str(ios)//')'
    end if
  end function explain
end module deck_reader
