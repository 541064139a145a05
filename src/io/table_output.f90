!> Tabular output that gnuplot and numpy.loadtxt read directly: '#' header
!> lines (version, deck, effective input, correlation table ...), one '#' line
!> of column names, fixed-width numeric rows, and a '#' footer with the cost.
!>
!> Everything is written to a temporary file beside the target and renamed
!> into place by `commit`, so a failed run never leaves a half-written file.
!> While the temporary file exists, SIGINT, SIGTERM and SIGHUP remove it
!> before the program dies of the signal (a C-interoperable handler calling
!> only async-signal-safe functions: unlink, signal, raise).
module table_output
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char, c_funptr, c_funloc, c_null_funptr, &
                                         c_intptr_t
  use c_library, only: c_rename, c_getpid, c_unlink, c_signal, c_raise
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: int64, error_unit
  use version, only: program_name
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use fast_format, only: format_es, format_es_exact, es_width
  use deck_reader, only: group_reader, write_group
  use unit_system, only: labelled
  implicit none
  private
  public :: table_t

  integer, parameter :: column_width = 24
  character(len=*), parameter :: value_format = '(es23.15e3)'
  integer, parameter :: default_digits = 16       !< of value_format

  type :: table_t
    character(len=:), allocatable :: path, tmp_path
    integer :: unit = 0
    integer :: echo = 0
    logical :: opened = .false.     ! newunit numbers are negative: track state explicitly
    logical :: echoing = .false.
    integer :: n_columns = 0
    integer :: n_rows = 0
    !> The first row offered with a NaN or Inf (never written: the run stops
    !> with a diagnosis instead of a table gnuplot would plot as gaps).
    integer :: bad_row = 0, bad_column = 0
    !> Significant digits of the rows: 0 = 16 (ES23.15E3, correctly rounded);
    !> 3..12 = the fast formatter (src/io/fast_format.f90), narrower columns.
    integer :: digits = 0
    !> Clock of the last flush: rows reach the temporary file at least once a
    !> second, so `tail -f` (and the fuzzer) see a slow run progress.
    integer(int64) :: flushed_at = 0
  contains
    procedure :: open => table_open
    procedure :: comment
    procedure :: comments
    procedure :: warning
    procedure :: echo_unit
    procedure :: end_echo
    procedure :: echo_group
    procedure :: columns
    procedure :: row
    procedure :: summary
    procedure :: cost
    procedure :: commit
    procedure :: discard
    procedure :: is_open
    procedure :: non_finite_text
    procedure :: set_digits
  end type table_t

  !> POSIX signal numbers (the same on Linux, the BSDs and macOS).
  integer(c_int), parameter :: sighup = 1, sigint = 2, sigterm = 15
  integer(c_int), parameter :: cleanup_signals(3) = [sighup, sigint, sigterm]
  integer(c_intptr_t), parameter :: sig_ign = 1     !< the address C's SIG_IGN stands for
  !> The temporary file a signal handler removes: a NUL-terminated C string
  !> built before the handler is installed (a handler must not allocate).
  integer, parameter :: max_path = 4096
  character(kind=c_char) :: pending_tmp(max_path + 1) = c_null_char
  !> The actions the handler replaced (a background job's ignored SIGINT stays ignored after the run).
  type(c_funptr) :: saved_action(size(cleanup_signals))
  logical :: watching = .false.

contains

  subroutine table_open(self, path, err)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_t), intent(inout) :: err
    integer :: ios
    character(len=512) :: iomsg
    self%path = trim(path)
    self%tmp_path = self%path//'.tmp'//str(int(c_getpid()))
    call watch_signals(self%tmp_path)
    open(newunit=self%unit, file=self%tmp_path, status='replace', action='write', iostat=ios, iomsg=iomsg)
    self%opened = ios == 0
    if (ios /= 0) then
      call unwatch_signals()
      call err%set('output '''//self%path//'''', 'cannot create '''//self%tmp_path//''': '//trim(iomsg))
    end if
    self%n_columns = 0
    self%n_rows = 0
  end subroutine table_open

  logical function is_open(self)
    class(table_t), intent(in) :: self
    is_open = self%opened
  end function is_open

  !> A '#' line; its unit labels (written as in-lbf-s) in the run's system of units.
  subroutine comment(self, text)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    call verbatim_comment(self, labelled(text))
  end subroutine comment

  !> A '#' line as given (an echoed group's values are the deck's own).
  subroutine verbatim_comment(self, text)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    if (.not. self%opened) return
    if (len_trim(text) == 0) then
      write(self%unit, '(a)') '#'
    else
      write(self%unit, '(a)') '# '//trim(text)
    end if
  end subroutine verbatim_comment

  !> A plausibility warning: a '# warning:' line and the same on stderr.  It
  !> never changes the result; it says what to check.
  subroutine warning(self, text)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    call self%comment('warning: '//text)
    write(error_unit, '(a)') program_name//': warning: '//labelled(text)
  end subroutine warning

  !> Lines as comments, one '#' line each.
  subroutine comments(self, lines)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: lines(:)
    integer :: i
    do i = 1, size(lines)
      call self%comment(lines(i))
    end do
  end subroutine comments

  !> A scratch unit to write a namelist group to; end_echo copies it into the
  !> header as '#' lines.
  integer function echo_unit(self)
    class(table_t), intent(inout) :: self
    open(newunit=self%echo, status='scratch', action='readwrite')
    self%echoing = .true.
    echo_unit = self%echo
  end function echo_unit

  subroutine end_echo(self)
    class(table_t), intent(inout) :: self
    character(len=4096) :: line
    integer :: ios
    if (.not. self%echoing) return
    rewind(self%echo)
    do
      read(self%echo, '(a)', iostat=ios) line
      if (ios /= 0) exit
      call verbatim_comment(self, squeeze_quoted(line))
    end do
    close(self%echo)
    self%echoing = .false.
  end subroutine end_echo

  !> A namelist group with its values, written by its owner's group
  !> procedure, as '#' lines.
  subroutine echo_group(self, group_io)
    class(table_t), intent(inout) :: self
    procedure(group_reader) :: group_io
    integer :: u
    u = self%echo_unit()
    call write_group(group_io, u)
    call self%end_echo()
  end subroutine echo_group

  !> The column-name line: '#' then names right-aligned over their columns.
  subroutine columns(self, names)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: names(:)
    character(len=:), allocatable :: line
    character(len=column_width) :: cell
    integer :: w
    integer :: i
    self%n_columns = size(names)
    w = column_width
    if (self%digits > 0) w = es_width(self%digits) + 1
    line = '#'
    do i = 1, size(names)
      if (len_trim(names(i)) >= w) then       ! a long name: separated, no longer aligned
        line = line//' '//trim(names(i))
        cycle
      end if
      cell = names(i)
      cell(1:w) = adjustr(cell(1:w))
      if (i == 1) then
        line = line//cell(2:w)
      else
        line = line//cell(1:w)
      end if
    end do
    if (self%opened) write(self%unit, '(a)') line
  end subroutine columns

  subroutine row(self, values)
    class(table_t), intent(inout) :: self
    real(dp), intent(in) :: values(:)
    integer :: i
    if (.not. self%opened .or. self%bad_row > 0) return
    do i = 1, size(values)
      if (.not. ieee_is_finite(values(i))) then
        self%bad_row = self%n_rows + 1
        self%bad_column = i
        return
      end if
    end do
    if (self%digits > 0) then
      call write_fast(self, values)
    else
      call write_exact(self, values)
    end if
    self%n_rows = self%n_rows + 1
    call flush_now_and_then(self)
  end subroutine row

  !> Flush when a second has passed since the last flush (a clock read per
  !> row costs nanoseconds; a flush per row would cost a system call).
  subroutine flush_now_and_then(self)
    class(table_t), intent(inout) :: self
    integer(int64) :: now, rate
    call system_clock(now, rate)
    if (self%flushed_at == 0) self%flushed_at = now
    if (now - self%flushed_at < rate) return
    flush(self%unit)
    self%flushed_at = now
  end subroutine flush_now_and_then

  !> A row through the fast formatter: one blank and es_width characters per value.
  subroutine write_fast(self, values)
    class(table_t), intent(inout) :: self
    real(dp), intent(in) :: values(:)
    character(len=(es_width(self%digits) + 1)*size(values)) :: line
    integer :: i, w
    w = es_width(self%digits) + 1
    do i = 1, size(values)
      line((i - 1)*w + 1:(i - 1)*w + 1) = ' '
      call format_es(values(i), self%digits, line((i - 1)*w + 2:i*w))
    end do
    write(self%unit, '(a)') line
  end subroutine write_fast

  !> A row as WRITE with (*(1x,es23.15e3)) writes it, character for
  !> character: the exact formatter, WRITE for the values it leaves.
  subroutine write_exact(self, values)
    class(table_t), intent(inout) :: self
    real(dp), intent(in) :: values(:)
    character(len=(es_width(default_digits) + 1)*size(values)) :: line
    integer :: i, w
    logical :: done
    w = es_width(default_digits) + 1
    do i = 1, size(values)
      line((i - 1)*w + 1:(i - 1)*w + 1) = ' '
      call format_es_exact(values(i), default_digits, line((i - 1)*w + 2:i*w), done)
      if (.not. done) write(line((i - 1)*w + 2:i*w), value_format) values(i)
    end do
    write(self%unit, '(a)') line
  end subroutine write_exact

  !> Rows with d significant digits (3..12, the fast formatter) or 0 (16, the default).
  subroutine set_digits(self, d)
    class(table_t), intent(inout) :: self
    integer, intent(in) :: d
    self%digits = d
  end subroutine set_digits

  !> Empty, or the diagnosis of the first row that held a NaN or Inf.
  function non_finite_text(self) result(text)
    class(table_t), intent(in) :: self
    character(len=:), allocatable :: text
    text = ''
    if (self%bad_row > 0) text = 'data row '//str(self%bad_row)//', column '//str(self%bad_column)// &
      ': the analysis produced a value that is not a finite number (NaN or Inf); rows from there on are not written'
  end function non_finite_text

  subroutine summary(self, key, value)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: key, value
    call self%comment('summary: '//trim(key)//' = '//trim(value))
  end subroutine summary

  subroutine cost(self, key, value)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: key, value
    call self%comment('cost: '//trim(key)//' = '//trim(value))
  end subroutine cost

  !> Close and move the temporary file into place.
  subroutine commit(self, err)
    class(table_t), intent(inout) :: self
    type(error_t), intent(inout) :: err
    if (.not. self%opened) return
    close(self%unit)
    self%opened = .false.
    if (c_rename(self%tmp_path//c_null_char, self%path//c_null_char) /= 0) then
      call err%set('output '''//self%path//'''', 'cannot rename the temporary file '//self%tmp_path)
    end if
    call unwatch_signals()
  end subroutine commit

  !> Close and delete the temporary file: no output is left behind.
  subroutine discard(self)
    class(table_t), intent(inout) :: self
    if (.not. self%opened) return
    close(self%unit, status='delete')
    self%opened = .false.
    call unwatch_signals()
  end subroutine discard

  !> From now on SIGHUP, SIGINT and SIGTERM remove `tmp_path` first.
  subroutine watch_signals(tmp_path)
    character(len=*), intent(in) :: tmp_path
    type(c_funptr) :: previous
    integer :: i, n
    n = min(len(tmp_path), max_path)
    pending_tmp = c_null_char
    do i = 1, n
      pending_tmp(i) = tmp_path(i:i)
    end do
    do i = 1, size(cleanup_signals)
      previous = c_signal(cleanup_signals(i), c_funloc(remove_pending_and_die))
      if (.not. watching) saved_action(i) = previous
      ! an ignored signal stays ignored (nohup, a background job's SIGINT)
      if (transfer(saved_action(i), 0_c_intptr_t) == sig_ign) previous = c_signal(cleanup_signals(i), saved_action(i))
    end do
    watching = .true.
  end subroutine watch_signals

  !> The signal actions from before watch_signals; nothing to remove.
  subroutine unwatch_signals()
    type(c_funptr) :: previous
    integer :: i
    if (.not. watching) return
    do i = 1, size(cleanup_signals)
      previous = c_signal(cleanup_signals(i), saved_action(i))
    end do
    pending_tmp = c_null_char
    watching = .false.
  end subroutine unwatch_signals

  !> The handler: remove the temporary file, restore the default action and
  !> re-raise, so the parent sees the program killed by the signal.
  subroutine remove_pending_and_die(signum) bind(c)
    integer(c_int), value :: signum
    integer(c_int) :: status
    type(c_funptr) :: previous
    if (pending_tmp(1) /= c_null_char) status = c_unlink(pending_tmp)
    previous = c_signal(signum, c_null_funptr)
    status = c_raise(signum)
  end subroutine remove_pending_and_die
  !> Drop the blank padding gfortran writes inside quoted namelist strings
  !> ('bdf                ' -> 'bdf').
  pure function squeeze_quoted(line) result(s)
    character(len=*), intent(in) :: line
    character(len=:), allocatable :: s
    integer :: i
    logical :: quoted
    s = ''
    quoted = .false.
    do i = 1, len_trim(line)
      if (line(i:i) == '''') then
        if (quoted) s = trim(s)
        quoted = .not. quoted
      end if
      s = s//line(i:i)
    end do
  end function squeeze_quoted
end module table_output
