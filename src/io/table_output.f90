!> Tabular output that gnuplot and numpy.loadtxt read directly: '#' header
!> lines (version, deck, effective input, correlation table ...), one '#' line
!> of column names, fixed-width numeric rows, and a '#' footer with the cost.
!>
!> Everything is written to a temporary file beside the target and renamed
!> into place by `commit`, so a failed run never leaves a half-written file.
module table_output
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  implicit none
  private
  public :: table_t, column_width

  integer, parameter :: column_width = 24
  character(len=*), parameter :: row_format = '(*(1x,es23.15e3))'

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
  contains
    procedure :: open => table_open
    procedure :: comment
    procedure :: echo_unit
    procedure :: end_echo
    procedure :: columns
    procedure :: row
    procedure :: summary
    procedure :: cost
    procedure :: commit
    procedure :: discard
    procedure :: is_open
    procedure :: non_finite_text
  end type table_t

  interface
    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename
    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid
  end interface

contains

  subroutine table_open(self, path, err)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: path
    type(error_t), intent(inout) :: err
    integer :: ios
    character(len=512) :: iomsg
    self%path = trim(path)
    self%tmp_path = self%path//'.tmp'//str(int(c_getpid()))
    open(newunit=self%unit, file=self%tmp_path, status='replace', action='write', iostat=ios, iomsg=iomsg)
    self%opened = ios == 0
    if (ios /= 0) call err%set('output '''//self%path//'''', 'cannot create: '//trim(iomsg))
    self%n_columns = 0
    self%n_rows = 0
  end subroutine table_open

  logical function is_open(self)
    class(table_t), intent(in) :: self
    is_open = self%opened
  end function is_open

  subroutine comment(self, text)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    if (.not. self%opened) return
    if (len_trim(text) == 0) then
      write(self%unit, '(a)') '#'
    else
      write(self%unit, '(a)') '# '//trim(text)
    end if
  end subroutine comment

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
      call self%comment(squeeze_quoted(line))
    end do
    close(self%echo)
    self%echoing = .false.
  end subroutine end_echo

  !> The column-name line: '#' then names right-aligned over their columns.
  subroutine columns(self, names)
    class(table_t), intent(inout) :: self
    character(len=*), intent(in) :: names(:)
    character(len=:), allocatable :: line
    character(len=column_width) :: cell
    integer :: i
    self%n_columns = size(names)
    line = '#'
    do i = 1, size(names)
      cell = names(i)
      cell = adjustr(cell)
      if (i == 1) then
        line = line//cell(2:)
      else
        line = line//cell
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
    write(self%unit, row_format) values
    self%n_rows = self%n_rows + 1
  end subroutine row

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
  end subroutine commit

  !> Close and delete the temporary file: no output is left behind.
  subroutine discard(self)
    class(table_t), intent(inout) :: self
    if (.not. self%opened) return
    close(self%unit, status='delete')
    self%opened = .false.
  end subroutine discard
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
