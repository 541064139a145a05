!> Namelist input decks: open a deck, read a group order-free, and turn every
!> way a read can fail into a message that names the deck, the group, the
!> offending line and its number.  All input errors carry code 2 (the main
!> program exits with status 2 and writes no output file).
!>
!> Preferred use, from the module that owns a group: one group procedure
!> holds the group's namelist read and write; the deck reads through it, an
!> output echoes through it (table_t%echo_group) and a written deck too
!> (write_group).
!>
!>     namelist /transient/ rtol, atol, ...     ! staging variables of that module
!>     ...set defaults...
!>     call deck%read_group('transient', transient_group, required=.false., found=found, err=err)
!>
!>     subroutine transient_group(r)   ! a module procedure
!>       type(group_read_t), intent(inout) :: r
!>       if (r%writing) then
!>         write(r%unit, nml=transient, delim='apostrophe')
!>       else
!>         read(r%unit, nml=transient, iostat=r%ios, iomsg=r%iomsg)
!>       end if
!>     end subroutine
!>
!> Given the reader, a failed read is replayed on growing prefixes of the
!> group to find the line that breaks it (gfortran reports a wrong-type value
!> as an end of file, with no position).  Before the read, every quoted
!> value is measured against its variable through the same reader (a text
!> longer than its variable would be cut silently).  The scanner that finds
!> groups and lines reads whole lines of any length with tabs as blanks, as
!> the namelist reader does; the groups are read from a copy of the deck
!> whose lines all end with a newline.
module deck_reader
  use, intrinsic :: iso_fortran_env, only: iostat_end
  use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_underflow, ieee_get_halting_mode, &
                                           ieee_set_halting_mode, ieee_set_flag, ieee_support_halting
  use error_status, only: error_t
  use strings, only: str, lower
  use spelling, only: nearest_name
  implicit none
  private
  public :: deck_t, group_reader, group_read_t, write_group, invalid_value, input_error_in, input_error_code, terminator_column
  public :: scan_line, shown_line, group_variables, unknown_target

  integer, parameter :: input_error_code = 2
  integer, parameter :: shown_chars = 200    !< a deck line quoted in a message is cut after this

  !> What a group procedure needs for its one namelist read or write: the
  !> unit, the direction (writing: the group with its values, for an echo or
  !> a written deck), and where a read puts its status and message.
  type :: group_read_t
    integer :: unit = 0
    logical :: writing = .false.
    integer :: ios = 0
    character(len=512) :: iomsg = ''
  end type group_read_t

  abstract interface
    subroutine group_reader(r)
      import :: group_read_t
      type(group_read_t), intent(inout) :: r
    end subroutine group_reader
  end interface

  !> One line of the deck, whatever its length (the namelist reader has no limit either).
  type :: deck_line_t
    character(len=:), allocatable :: text
    logical :: ends_in_lone_cr = .false.   !< cut by a carriage return without a line feed
  end type deck_line_t

  type :: deck_t
    character(len=:), allocatable :: path
    integer :: unit = 0
    logical :: opened = .false.      ! newunit numbers are negative
    type(deck_line_t), allocatable :: lines(:)   !< the deck's text, for locating groups and for messages
  contains
    procedure :: open => deck_open
    procedure :: close => deck_close
    procedure :: rewind => deck_rewind
    procedure :: has_group
    procedure :: read_group
    procedure :: group_line_range
  end type deck_t

contains

  subroutine deck_open(self, path, err)
    class(deck_t), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_t), intent(inout) :: err
    logical :: exists, at_end
    integer :: ios, n
    character(len=512) :: iomsg
    character(len=:), allocatable :: line
    self%path = trim(path)
    inquire(file=self%path, exist=exists)
    if (.not. exists) then
      call err%set('deck '''//self%path//'''', 'file not found', input_error_code)
      return
    end if
    inquire(file=self%path//'/.', exist=exists)
    if (exists) then
      call err%set('deck '''//self%path//'''', 'is a directory', input_error_code)
      return
    end if
    open(newunit=self%unit, file=self%path, status='old', action='read', iostat=ios, iomsg=iomsg)
    if (ios /= 0) then
      call err%set('deck '''//self%path//'''', 'cannot open: '//trim(iomsg), input_error_code)
      return
    end if
    n = 0
    at_end = .false.
    do
      call read_line(self%unit, line, ios, iomsg, at_end)
      if (ios /= 0) exit
      n = n + 1
    end do
    if (.not. is_iostat_end(ios)) then      ! a device that fails
      close(self%unit)
      call err%set('deck '''//self%path//'''', 'cannot read: '//trim(iomsg), input_error_code)
      return
    end if
    self%opened = .true.
    allocate(self%lines(n))
    rewind(self%unit)
    at_end = .false.
    do n = 1, size(self%lines)
      call read_line(self%unit, self%lines(n)%text, ios, iomsg, at_end)
    end do
    rewind(self%unit)
    call read_from_copy(self)
    call mark_lone_returns(self)   ! (after the copy: gfortran opens a file on one unit at a time)
  end subroutine deck_open

  !> gfortran's formatted reads end a record at a carriage return that no
  !> line feed follows, and its namelist reader then joins a name cut there
  !> ('link_n<CR>ame' reads as link_name) where the scanner sees two words:
  !> mark those lines, so that a group containing one is refused (read_group).
  subroutine mark_lone_returns(self)
    class(deck_t), intent(inout) :: self
    character(len=:), allocatable :: bytes
    integer :: u, ios, n, k, line
    inquire(file=self%path, size=n)
    if (n <= 0) return
    allocate(character(len=n) :: bytes)
    open(newunit=u, file=self%path, access='stream', form='unformatted', status='old', action='read', iostat=ios)
    if (ios /= 0) return
    read(u, iostat=ios) bytes
    close(u)
    if (ios /= 0) return
    line = 1
    do k = 1, n
      if (bytes(k:k) == achar(10)) then
        line = line + 1
      else if (bytes(k:k) == achar(13)) then
        if (k < n) then
          if (bytes(k + 1:k + 1) == achar(10)) cycle   ! CRLF: the line feed ends the line
        end if
        if (line <= size(self%lines)) self%lines(line)%ends_in_lone_cr = .true.
        line = line + 1
      end if
    end do
  end subroutine mark_lone_returns

  !> The groups are read from a copy of the deck whose lines all end with a
  !> newline: gfortran's namelist reader does not see a group closed on a
  !> last line without one (the scanner, reading whole lines, does).
  subroutine read_from_copy(self)
    class(deck_t), intent(inout) :: self
    integer :: i
    close(self%unit)
    open(newunit=self%unit, status='scratch', action='readwrite')
    do i = 1, size(self%lines)
      write(self%unit, '(a)') self%lines(i)%text
    end do
    rewind(self%unit)
  end subroutine read_from_copy

  !> The next record, whole (non-advancing reads of 512-character pieces).
  subroutine read_line(unit, line, ios, iomsg, at_end)
    integer, intent(in) :: unit
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    logical, intent(inout) :: at_end      !< set once the end of file is met
    character(len=512) :: piece
    integer :: got
    line = ''
    if (at_end) then
      ios = iostat_end
      return
    end if
    do
      got = 0
      read(unit, '(a)', advance='no', size=got, iostat=ios, iomsg=iomsg) piece
      line = line//piece(1:got)
      if (is_iostat_eor(ios)) then
        ios = 0
        return
      end if
      if (ios /= 0) then
        ! a last line without a newline still counts; a read after it would
        ! fail with an error rather than an end of file, so remember the end
        if (is_iostat_end(ios) .and. len(line) > 0) then
          ios = 0
          at_end = .true.
        end if
        return
      end if
    end do
  end subroutine read_line

  !> Line i as the scanner sees it: lower case, tabs and carriage returns as
  !> blanks (the namelist reader treats them as separators too).
  pure function scan_line(deck, i) result(l)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: i
    character(len=:), allocatable :: l
    integer :: k
    l = lower(deck%lines(i)%text)
    do k = 1, len(l)
      if (l(k:k) == achar(9) .or. l(k:k) == achar(13)) l(k:k) = ' '
    end do
  end function scan_line

  !> Line i quoted in a message: without its indentation, cut if very long.
  function shown_line(deck, i) result(l)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: i
    character(len=:), allocatable :: l, scanned
    integer :: a
    scanned = scan_line(deck, i)
    a = verify(scanned, ' ')
    l = ''
    if (a > 0) l = deck%lines(i)%text(a:len_trim(scanned))
    if (len(l) > shown_chars) l = l(1:shown_chars)//' ... ('//str(len(l))//' characters)'
    ! a control character (a stray byte in the file) shown as '?', not sent to the terminal
    do a = 1, len(l)
      if (iachar(l(a:a)) < 32 .or. iachar(l(a:a)) == 127) l(a:a) = '?'
    end do
  end function shown_line

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

  !> Call a group reader with overflow halting off: the C library's strtod
  !> raises the overflow flag on a value such as 1e309 (read as Infinity and
  !> rejected afterwards by the finiteness checks), which would otherwise
  !> trap in a build with -ffpe-trap=overflow.
  subroutine read_quietly(reader, unit, ios, iomsg)
    procedure(group_reader) :: reader
    integer, intent(in) :: unit
    integer, intent(out) :: ios
    character(len=*), intent(inout) :: iomsg
    logical :: quiet, halt_overflow, halt_underflow
    type(group_read_t) :: r
    r%unit = unit
    r%iomsg = iomsg
    quiet = ieee_support_halting(ieee_overflow) .and. ieee_support_halting(ieee_underflow)
    if (quiet) then
      call ieee_get_halting_mode(ieee_overflow, halt_overflow)
      call ieee_get_halting_mode(ieee_underflow, halt_underflow)
      call ieee_set_halting_mode(ieee_overflow, .false.)
      call ieee_set_halting_mode(ieee_underflow, .false.)
    end if
    call reader(r)
    if (quiet) then
      call ieee_set_flag(ieee_overflow, .false.)
      call ieee_set_flag(ieee_underflow, .false.)
      call ieee_set_halting_mode(ieee_overflow, halt_overflow)
      call ieee_set_halting_mode(ieee_underflow, halt_underflow)
    end if
    ios = r%ios
    iomsg = r%iomsg
  end subroutine read_quietly

  !> Write a group with its current values through its owner's group procedure.
  subroutine write_group(group_io, unit)
    procedure(group_reader) :: group_io
    integer, intent(in) :: unit
    type(group_read_t) :: r
    r%unit = unit
    r%writing = .true.
    call group_io(r)
  end subroutine write_group

  !> Lines [first, last] of the group: from its '&name' to the line holding its
  !> terminating '/'.  first = 0 if absent; last = 0 if never terminated.
  subroutine group_line_range(self, group, first, last)
    class(deck_t), intent(in) :: self
    character(len=*), intent(in) :: group
    integer, intent(out) :: first, last
    integer :: i, k
    character(len=:), allocatable :: key, l
    first = 0
    last = 0
    key = '&'//lower(trim(group))
    k = len(key)
    do i = 1, size(self%lines)
      l = trim(adjustl(scan_line(self, i)))
      if (len(l) < k) cycle
      if (l(1:k) == key) then
        if (len(l) == k) then
          first = i
        else if (scan(l(k + 1:k + 1), ' ,/') == 1) then
          first = i
        end if
        if (first > 0) exit
      end if
    end do
    if (first == 0) return
    do i = first, size(self%lines)
      if (has_terminator(scan_line(self, i), i == first)) then
        last = i
        return
      end if
    end do
  end subroutine group_line_range

  !> Does this line contain a '/' that ends a namelist group?
  logical pure function has_terminator(line, is_first)
    character(len=*), intent(in) :: line
    logical, intent(in) :: is_first
    has_terminator = terminator_column(line, is_first) <= len_trim(line)
  end function has_terminator

  !> Column of the '/' ending a group on this line (outside quotes and
  !> comments), len(line) + 1 if there is none; on the group's first line the
  !> '&name' is skipped.
  integer pure function terminator_column(line, is_first) result(col)
    character(len=*), intent(in) :: line
    logical, intent(in) :: is_first
    integer :: start
    character(len=1) :: quote
    quote = ' '
    start = 1
    if (is_first) start = index(line, '&') + 1
    do col = start, len_trim(line)
      if (quote /= ' ') then
        if (line(col:col) == quote) quote = ' '
      else if (line(col:col) == '''' .or. line(col:col) == '"') then
        quote = line(col:col)
      else if (line(col:col) == '!') then
        exit
      else if (line(col:col) == '/') then
        return
      end if
    end do
    col = len(line) + 1
  end function terminator_column

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
    character(len=:), allocatable :: unknown
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
    bad = findloc(self%lines(first:last)%ends_in_lone_cr, .true., dim=1)
    if (bad > 0) then
      call err%set(context(self, group), 'line '//str(first + bad - 1)//': "'//shown_line(self, first + bad - 1)// &
                   '" ends in a carriage return without a line feed: save the deck with LF (or CRLF) line ends', &
                   input_error_code)
      return
    end if
    ! before the real read, which then overwrites what the probes wrote
    call check_string_lengths(self, group, reader, first, last, err)
    if (err%failed()) return
    call self%rewind()
    iomsg = ''
    call read_quietly(reader, self%unit, ios, iomsg)
    if (ios == 0) then
      found = .true.
      return
    end if
    bad = first_bad_line(self, reader, first, last)
    if (bad > 0) then
      ! a name the group does not have, wherever the reader's message points
      ! (after an array it blames the array: 'Bad data for ... link_joint2')
      unknown = unknown_target(scan_line(self, bad), group_variables(reader))
      if (len(unknown) > 0) then
        call err%set(context(self, group), 'cannot read line '//str(bad)//': "'//shown_line(self, bad)// &
                     '": unknown variable '''//unknown//''''//did_you_mean(unknown, group_variables(reader)), &
                     input_error_code)
        return
      end if
      call err%set(context(self, group), 'cannot read line '//str(bad)//': "'//shown_line(self, bad)// &
                   '": '//explain(iomsg, ios, scan_line(self, bad)), input_error_code)
    else
      call err%set(context(self, group), explain(iomsg, ios, ''), input_error_code)
    end if
  end subroutine read_group

  !> A quoted value longer than its character variable is cut silently by the
  !> namelist reader; make it an error.  Every string assigned in the group is
  !> measured, and the variable's length is probed through the owner's reader
  !> with a one-character substring assignment: `name(1)(L:L) = 'x'` for an
  !> array element, `name(L:L) = 'x'` for a scalar; gfortran answers
  !> "Substring out of range" when the variable is shorter than L.  A probe
  !> that succeeds writes one character into the element or scalar the deck
  !> assigns, which the real read then overwrites.
  subroutine check_string_lengths(self, group, reader, first, last, err)
    class(deck_t), intent(in) :: self
    character(len=*), intent(in) :: group
    procedure(group_reader) :: reader
    integer, intent(in) :: first, last
    type(error_t), intent(inout) :: err
    character(len=:), allocatable :: l, target, sub
    integer :: i, k, j, n, longest, fits
    target = ''
    sub = ''
    longest = 0
    do i = first, last
      l = scan_line(self, i)
      k = 1
      if (i == first) k = index(l, '&') + len_trim(group) + 1
      do while (k <= len(l))
        if (l(k:k) == '!' .or. l(k:k) == '/') exit
        if (l(k:k) == '''' .or. l(k:k) == '"') then
          call quoted_value(l, k, j, n)
          if (j > len(l)) then
            ! the reader would run on into the next lines (and groups)
            call err%set(context(self, group), 'line '//str(i)//': "'//shown_line(self, i)//'": the text opened by '// &
                         l(k:k)//' is not closed on its line', input_error_code)
            return
          end if
          if (len(target) > 0 .and. n > longest) then
            longest = n
            fits = longest_fitting(reader, group, target, sub, n)
            if (fits < n) then
              call invalid_value(self, group, target//sub, self%lines(i)%text(k:min(j, k + 40, len(l)))// &
                                 trim(merge('...', '   ', j > k + 40)), 'the text has '//str(n)// &
                                 ' characters, at most '//str(fits)//' fit (it would be cut silently)', err)
              return
            end if
          end if
          k = j + 1
        else if (scan(l(k:k), 'abcdefghijklmnopqrstuvwxyz_') == 1) then
          call assignment_target(l, k, j, target, sub, longest)
          k = j
        else if (scan(l(k:k), '0123456789.+-') == 1) then
          ! a number; before '*' it must be a repeat count: gfortran reads
          ! '2.5*'text'' into a character variable as the undelimited string
          ! "2.5*'text'", cut to the variable's length (fuzz seed 8)
          j = k + scan(l(k:), ' ,/*!=') - 1
          if (j < k) j = len(l) + 1
          ! gfortran reads '3x'open'' into a character variable as undelimited
          ! text, cut to its length (fuzz seed 12, case 10731): a number runs
          ! on into letters only as a logical (.true.) or an exponent
          if (verify(l(k:j - 1), '0123456789.+-ed') > 0 .and. .not. is_logical_or_special(l(k:j - 1))) then
            call err%set(context(self, group), 'line '//str(i)//': "'//shown_line(self, i)//'": a value starts '// &
                         'as a number and runs on into other characters (text values must be quoted)', input_error_code)
            return
          end if
          if (j <= len(l)) then
            if (l(j:j) == '*' .and. verify(l(k:j - 1), '0123456789') > 0) then
              call err%set(context(self, group), 'line '//str(i)//': "'//shown_line(self, i)//'": the repeat '// &
                           'count '''//l(k:j - 1)//''' is not a positive integer', input_error_code)
              return
            end if
          end if
          k = max(j, k + 1)
        else
          k = k + 1
        end if
      end do
    end do
  end subroutine check_string_lengths

  !> A namelist logical written with its dots (.true., .f), or a signed
  !> infinity or NaN (-inf: read, then refused by the finiteness checks with
  !> the variable's name); lower case.
  pure logical function is_logical_or_special(token)
    character(len=*), intent(in) :: token
    is_logical_or_special = .false.
    if (len(token) >= 2) is_logical_or_special = token(1:1) == '.' .and. (token(2:2) == 't' .or. token(2:2) == 'f')
    if (len(token) >= 4) is_logical_or_special = is_logical_or_special .or. (scan(token(1:1), '+-') == 1 .and. &
                                                       (token(2:4) == 'inf' .or. token(2:4) == 'nan'))
  end function is_logical_or_special

  !> The quoted value opening at l(k:k): its closing quote l(j:j) (j > len(l)
  !> if unterminated) and its length n without trailing blanks, a doubled
  !> quote counting once.
  pure subroutine quoted_value(l, k, j, n)
    character(len=*), intent(in) :: l
    integer, intent(in) :: k
    integer, intent(out) :: j, n
    integer :: m
    character(len=1) :: q
    q = l(k:k)
    j = k + 1
    m = 0
    n = 0
    do while (j <= len(l))
      if (l(j:j) == q) then
        if (j == len(l)) exit
        if (l(j + 1:j + 1) /= q) exit
        j = j + 1
      end if
      m = m + 1
      if (l(j:j) /= ' ') n = m
      j = j + 1
    end do
  end subroutine quoted_value

  !> The name starting at l(k:k): if `name [(subscript)] =` follows, it is the
  !> new assignment target (longest string so far reset); j is where scanning
  !> goes on (after the '=', or after the name if it is a value such as T).
  pure subroutine assignment_target(l, k, j, target, sub, longest)
    character(len=*), intent(in) :: l
    integer, intent(in) :: k
    integer, intent(out) :: j
    character(len=:), allocatable, intent(inout) :: target, sub
    integer, intent(inout) :: longest
    integer :: e, p, q
    e = verify(l(k:), 'abcdefghijklmnopqrstuvwxyz0123456789_%')
    if (e == 0) then
      j = len(l) + 1
      return
    end if
    e = k + e - 1                 ! first character after the name
    j = e
    if (len_trim(l(e:)) == 0) return
    p = e + verify(l(e:), ' ') - 1
    q = p - 1
    if (l(p:p) == '(') then
      q = index(l(p:), ')')
      if (q == 0) return
      q = p + q - 1
      if (len_trim(l(q + 1:)) == 0) return
      p = q + verify(l(q + 1:), ' ')
    end if
    if (l(p:p) /= '=') return
    target = l(k:e - 1)
    sub = ''
    if (q >= e) sub = trim(adjustl(l(e:q)))
    longest = 0
    j = p + 1
  end subroutine assignment_target

  !> n if a string of n characters fits the target, else the most that fit.
  integer function longest_fitting(reader, group, target, sub, n) result(fits)
    procedure(group_reader) :: reader
    character(len=*), intent(in) :: group, target, sub
    integer, intent(in) :: n
    integer :: lo, hi, mid
    if (string_fits(reader, group, target, sub, n)) then
      fits = n
      return
    end if
    lo = 0
    hi = n
    do while (hi - lo > 1)
      mid = (lo + hi)/2
      if (string_fits(reader, group, target, sub, mid)) then
        lo = mid
      else
        hi = mid
      end if
    end do
    fits = lo
  end function longest_fitting

  !> Does a string of n characters fit the target?  Probe the element the
  !> deck assigns first (or element 1); "Missing colon" means a scalar.
  logical function string_fits(reader, group, target, sub, n) result(fits)
    procedure(group_reader) :: reader
    character(len=*), intent(in) :: group, target, sub
    integer, intent(in) :: n
    character(len=:), allocatable :: element, range, msg
    integer :: e
    element = '1'
    if (len(sub) > 2) then
      e = scan(sub, ':,)')
      if (e > 2) element = sub(2:e - 1)
    end if
    range = '('//str(n)//':'//str(n)//')'
    fits = .true.
    msg = probe(reader, '&'//group//' '//target//'('//element//')'//range//' = ''x'' /')
    if (index(msg, 'Substring out of range') > 0) fits = .false.
    if (index(msg, 'Missing colon') == 0 .or. len(sub) > 0) return
    msg = probe(reader, '&'//group//' '//target//range//' = ''x'' /')
    if (index(msg, 'Substring out of range') > 0) fits = .false.
  end function string_fits

  !> The reader's message on a one-line group ('' if it reads).
  function probe(reader, text) result(msg)
    procedure(group_reader) :: reader
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: msg
    integer :: u, ios
    character(len=512) :: iomsg
    open(newunit=u, status='scratch', action='readwrite')
    write(u, '(a)') text
    rewind(u)
    iomsg = ''
    call read_quietly(reader, u, ios, iomsg)
    close(u)
    msg = ''
    if (ios /= 0) msg = trim(iomsg)
  end function probe

  !> Replay the group on growing prefixes of its lines; the first prefix that
  !> fails to read names the offending line.
  integer function first_bad_line(self, reader, first, last) result(bad)
    class(deck_t), intent(in) :: self
    procedure(group_reader) :: reader
    integer, intent(in) :: first, last
    integer :: k, u, ios, i
    character(len=512) :: iomsg
    bad = 0
    do k = first, last
      open(newunit=u, status='scratch', action='readwrite')
      do i = first, k
        write(u, '(a)') trim(self%lines(i)%text)
      end do
      if (k < last) write(u, '(a)') '/'
      if (k == first .and. .not. has_terminator(scan_line(self, first), .true.)) then
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

  !> The variables of a group (lower case), from its namelist write: each
  !> line of the form ' NAME=...' names one.
  function group_variables(reader) result(names)
    procedure(group_reader) :: reader
    character(len=64), allocatable :: names(:)
    integer :: u, ios, e
    logical :: at_end
    character(len=512) :: iomsg
    character(len=:), allocatable :: line
    allocate(names(0))
    open(newunit=u, status='scratch', action='readwrite')
    call write_group(reader, u)
    rewind(u)
    at_end = .false.
    do
      call read_line(u, line, ios, iomsg, at_end)
      if (ios /= 0) exit
      line = lower(line)
      if (len(line) < 3) cycle
      if (line(1:1) /= ' ' .or. scan(line(2:2), 'abcdefghijklmnopqrstuvwxyz') /= 1) cycle
      e = verify(line(2:), 'abcdefghijklmnopqrstuvwxyz0123456789_') + 1
      if (e < 3) cycle
      if (line(e:e) == '=') names = [character(len=64) :: names, line(2:e - 1)]
    end do
    close(u)
  end function group_variables

  !> The first name a deck line (as scan_line gives it) assigns to that is not
  !> in `names`; '' if every target is known.  Quoted text, numbers and
  !> comments are skipped; a '/' ends the group.
  pure function unknown_target(l, names) result(unknown)
    character(len=*), intent(in) :: l
    character(len=*), intent(in) :: names(:)
    character(len=:), allocatable :: unknown, target, sub
    integer :: k, j, n, longest
    unknown = ''
    longest = 0
    k = 1
    do while (k <= len(l))
      if (l(k:k) == '!' .or. l(k:k) == '/') return
      if (l(k:k) == '''' .or. l(k:k) == '"') then
        call quoted_value(l, k, j, n)
        k = j + 1
      else if (scan(l(k:k), 'abcdefghijklmnopqrstuvwxyz_') == 1) then
        target = ''
        sub = ''
        call assignment_target(l, k, j, target, sub, longest)
        if (len(target) > 0) then
          if (.not. any(names == target)) then
            unknown = target
            return
          end if
        end if
        k = max(j, k + 1)
      else if (scan(l(k:k), '0123456789.+-&') == 1) then
        j = scan(l(k:), ' ,/*!=')       ! a number, a logical, or the '&group' word
        if (j == 0) return
        k = k + j - 1
        if (l(k:k) == '*' .or. l(k:k) == '=') k = k + 1
      else
        k = k + 1
      end if
    end do
  end function unknown_target

  !> ' (did you mean ''x''?)' when a candidate is a likely misspelling of word.
  function did_you_mean(word, candidates) result(s)
    character(len=*), intent(in) :: word
    character(len=*), intent(in) :: candidates(:)
    character(len=:), allocatable :: s, near
    near = nearest_name(word, candidates)
    s = ''
    if (len(near) > 0) s = ' (did you mean '''//near//'''?)'
  end function did_you_mean

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
        if (names_variable(scan_line(deck, i), var)) then
          at = ' (line '//str(i)//')'
          exit
        end if
      end do
    end if
    call err%set(context(deck, group), trim(variable)//' = '//trim(value_text)//at//': '//trim(rule), &
                 input_error_code)
  end subroutine invalid_value

  !> A lower layer refused what a group's values describe (a model, loads, a
  !> joint): the failure becomes an input error (exit status 2) with the deck
  !> and group ('mechanism', or 'mechanism/&tennant') named as its context.
  subroutine input_error_in(deck, group, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group
    type(error_t), intent(inout) :: err
    err%code = input_error_code
    call err%add_context('deck '''//deck%path//''', group &'//group)
  end subroutine input_error_in

  logical pure function names_variable(line, var)
    character(len=*), intent(in) :: line, var
    integer :: i, j
    names_variable = .false.
    if (len(var) == 0) return
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

  !> The reader's complaint in the deck's terms.  `line` (lower case, '' if
  !> unknown) is the offending line: gfortran takes a value it cannot read as
  !> a number (rtol = 'abc', rtol = fast) for the name of the next variable,
  !> so a name that the line does not assign to is a value of the wrong type.
  pure function explain(iomsg, ios, line) result(s)
    character(len=*), intent(in) :: iomsg, line
    integer, intent(in) :: ios
    character(len=:), allocatable :: s, name, token
    integer :: n
    logical :: known
    if (index(iomsg, 'Cannot match namelist object name') > 0) then
      token = trim(iomsg(index(iomsg, 'name ') + 5:))
      n = verify(lower(token), 'abcdefghijklmnopqrstuvwxyz0123456789_%') - 1
      if (n < 0) n = len(token)
      name = lower(token(1:n))
      known = n > 0 .and. len(line) == 0       ! (Fortran's .and. does not short-circuit)
      if (n > 0 .and. len(line) > 0) known = names_variable(line, name)
      if (known) then
        s = 'unknown variable '''//token(1:n)//''''
      else
        if (index(token, '&') > 1) token = token(1:index(token, '&') - 1)
        s = 'the value '//trim(token)//' has the wrong type or form (e.g. text for a number)'
      end if
    else if (ios < 0) then
      s = 'a value has the wrong type or form (e.g. text for a number, a real for an integer)'
    else if (len_trim(iomsg) > 0) then
      s = trim(iomsg)
    else
      s = 'read error (iostat '//str(ios)//')'
    end if
  end function explain
end module deck_reader
