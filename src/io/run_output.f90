!> A flexmech output file read back: the title, the analysis, the column names
!> and the numeric rows, and the '# summary:' / '# cost:' footer lines.
!>
!> The column-name line is the last '#' line before the first data row that
!> has as many names as that row has numbers (optimizer notes such as
!> '# k = 1: step-back ...' may lie in between).  Used by `flexmech plot` and
!> by the sweep summary, so both read outputs the same way.
module run_output
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower, starts_with
  implicit none
  private
  public :: run_output_t, read_run_output, split_words, column_index, name_t, append_text
  public :: column_unit

  !> One text of any length, in growing lists (column names, header and
  !> footer lines, a figure script's data lines).
  type :: name_t
    character(len=:), allocatable :: s
  end type name_t

  type :: run_output_t
    character(len=:), allocatable :: path, title, analysis, deck
    type(name_t), allocatable :: names(:)
    real(dp), allocatable :: data(:, :)            !< (row, column)
    type(name_t), allocatable :: footer(:)         !< 'summary: ...' and 'cost: ...' texts
    type(name_t), allocatable :: header(:)         !< every '#' line before the data, without '# '
  contains
    procedure :: n_columns
    procedure :: column_name
    procedure :: column
    procedure :: has_column
  end type run_output_t

contains

  integer pure function n_columns(self)
    class(run_output_t), intent(in) :: self
    n_columns = 0
    if (allocated(self%names)) n_columns = size(self%names)
  end function n_columns

  pure function column_name(self, j) result(s)
    class(run_output_t), intent(in) :: self
    integer, intent(in) :: j
    character(len=:), allocatable :: s
    s = self%names(j)%s
  end function column_name

  !> Column j (1-based); empty when out of range.
  pure function column(self, j) result(v)
    class(run_output_t), intent(in) :: self
    integer, intent(in) :: j
    real(dp), allocatable :: v(:)
    allocate(v(0))
    if (j >= 1 .and. j <= self%n_columns()) v = self%data(:, j)
  end function column

  logical pure function has_column(self, name)
    class(run_output_t), intent(in) :: self
    character(len=*), intent(in) :: name
    has_column = column_index(self, name) > 0
  end function has_column

  !> Index of the column called `name`, 0 if none.
  integer pure function column_index(out, name) result(j)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: name
    do j = 1, out%n_columns()
      if (out%names(j)%s == name) return
    end do
    j = 0
  end function column_index

  !> The unit of the columns whose description in the header names `key`:
  !> in the ';'-separated part that names it, the first parenthesised text
  !> after the key that looks like a unit (at most two words, 12 characters,
  !> up to a ';' inside it): 'psi' from 'sigma_max_e<k> = largest |stress|
  !> ... (psi) (the outer-fibre stress ...)', 'in' from '<joint>_U ... (in;
  !> T''s U~1 is B_U)', 'lb in' from 'M_e<k> = ... (lb in)'; '' when none
  !> says.  The 'columns:' line first, then the other descriptions.
  function column_unit(out, key) result(unit)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: key
    character(len=:), allocatable :: unit
    integer :: pass, pass_in, i, a, b, depth, k, c, e
    type(name_t), allocatable :: words(:)
    character(len=:), allocatable :: line, part
    unit = ''
    do pass = 1, 2
      do i = 1, size(out%header)
        line = out%header(i)%s
        if (pass == 1 .neqv. starts_with(line, 'columns:')) cycle
        if (index(line, key) == 0 .or. index(line, ' = ') == 0) cycle
        a = 1
        depth = 0
        do b = 1, len(line) + 1                  ! parts end at a ';' outside parentheses
          if (b <= len(line)) then
            if (line(b:b) == '(') depth = depth + 1
            if (line(b:b) == ')') depth = max(0, depth - 1)
            if (line(b:b) /= ';' .or. depth > 0) cycle
          end if
          part = line(a:b - 1)
          a = b + 1
          k = index(part, key)
          if (k == 0) cycle
          c = k
          do                                     ! the parenthesised texts after the key
            c = c + index(part(c + 1:), '(')
            if (c == k .or. c >= len(part)) exit
            e = index(part(c + 1:), ')')
            if (e == 0) e = len(part) - c + 1
            do pass_in = 1, 2                  ! the text before its first ';', then after its last
              unit = part(c + 1:c + e - 1)
              if (pass_in == 1 .and. scan(unit, ';:') > 0) unit = unit(1:scan(unit, ';:') - 1)
              if (pass_in == 2) unit = unit(scan(unit, ';:', back=.true.) + 1:)
              unit = trim(adjustl(unit))
              call split_words(unit, words)
              if (len(unit) > 0 .and. len(unit) <= 12 .and. size(words) <= 2 .and. index(unit, '<') == 0) return
            end do
            unit = ''
            k = c
          end do
        end do
      end do
    end do
  end function column_unit

  subroutine read_run_output(path, out, err)
    character(len=*), intent(in) :: path
    type(run_output_t), intent(out) :: out
    type(error_t), intent(inout) :: err
    integer :: u, ios, n_rows, n_fields, i
    character(len=:), allocatable :: line
    type(name_t), allocatable :: words(:)
    real(dp), allocatable :: row(:)
    logical :: in_data
    out%path = path
    out%title = ''
    out%analysis = ''
    out%deck = ''
    allocate(out%names(0), out%footer(0), out%header(0))
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) then
      call err%set('output '''//path//'''', 'cannot open (does it exist?)', 2)
      return
    end if
    n_rows = 0
    n_fields = -1
    in_data = .false.
    allocate(out%data(0, 0))
    do
      call read_text_line(u, line, ios)
      if (ios /= 0) exit
      if (len_trim(line) == 0) cycle
      if (line(1:1) == '#') then
        call note_comment(out, line, in_data)
        cycle
      end if
      call parse_numbers(line, row, ios)
      if (ios /= 0) then
        call err%set('output '''//path//'''', 'line '//str(n_rows + 1)//' of data is not numeric', 2)
        close(u)
        return
      end if
      if (.not. in_data) then
        n_fields = size(row)
        call find_column_line(out, n_fields)
        deallocate(out%data)
        allocate(out%data(64, n_fields))
        in_data = .true.
      end if
      if (size(row) /= n_fields) cycle       ! a ragged row is ignored
      n_rows = n_rows + 1
      if (n_rows > size(out%data, 1)) call grow(out%data)
      out%data(n_rows, :) = row
    end do
    close(u)
    out%data = out%data(1:n_rows, :)
    if (.not. in_data) then
      do i = size(out%header), 1, -1       ! no rows: names from the last header line of words
        call split_words(out%header(i)%s, words)
        if (size(words) > 1 .and. index(out%header(i)%s, '=') == 0 .and. index(out%header(i)%s, ':') == 0) then
          out%names = words
          exit
        end if
      end do
    end if
  end subroutine read_run_output

  subroutine note_comment(out, line, in_data)
    type(run_output_t), intent(inout) :: out
    character(len=*), intent(in) :: line
    logical, intent(in) :: in_data
    character(len=:), allocatable :: text
    integer :: q
    text = trim(adjustl(line(2:)))
    if (starts_with(text, 'summary:') .or. starts_with(text, 'cost:')) then
      call append_text(out%footer, text)
    end if
    if (.not. in_data) call append_text(out%header, text)
    if (starts_with(text, 'title: ') .and. len(out%title) == 0) out%title = trim(text(8:))
    if (starts_with(text, 'deck: ') .and. len(out%deck) == 0) out%deck = trim(text(7:))
    if (starts_with(text, 'sweep: ')) out%analysis = 'sweep'
    if (starts_with(text, 'batch: ')) out%analysis = 'batch'
    if (starts_with(lower(text), 'analysis=''') .and. len(out%analysis) == 0) then
      q = index(text(11:), '''')
      if (q > 1) out%analysis = lower(text(11:9 + q))
    end if
  end subroutine note_comment

  !> The column names: the last header line with n words (no '=' or ':').
  subroutine find_column_line(out, n)
    type(run_output_t), intent(inout) :: out
    integer, intent(in) :: n
    integer :: i
    type(name_t), allocatable :: words(:)
    do i = size(out%header), 1, -1
      if (index(out%header(i)%s, '=') > 0 .or. index(out%header(i)%s, ':') > 0) cycle
      call split_words(out%header(i)%s, words)
      if (size(words) == n) then
        out%names = words
        return
      end if
    end do
    deallocate(out%names)
    allocate(out%names(n))
    do i = 1, n
      out%names(i)%s = 'column'//str(i)
    end do
  end subroutine find_column_line

  !> list := [list, text] (the texts move, nothing is copied).
  subroutine append_text(list, text)
    type(name_t), allocatable, intent(inout) :: list(:)
    character(len=*), intent(in) :: text
    type(name_t), allocatable :: longer(:)
    integer :: i
    allocate(longer(size(list) + 1))
    do i = 1, size(list)
      call move_alloc(list(i)%s, longer(i)%s)
    end do
    longer(size(longer))%s = text
    call move_alloc(longer, list)
  end subroutine append_text

  subroutine grow(a)
    real(dp), allocatable, intent(inout) :: a(:, :)
    real(dp), allocatable :: b(:, :)
    allocate(b(2*size(a, 1), size(a, 2)))
    b(1:size(a, 1), :) = a
    call move_alloc(b, a)
  end subroutine grow

  !> Whitespace-separated words of a line.
  subroutine split_words(line, words)
    character(len=*), intent(in) :: line
    type(name_t), allocatable, intent(out) :: words(:)
    integer :: i, start, n, pass
    do pass = 1, 2
      n = 0
      start = 0
      do i = 1, len(line) + 1
        if (i <= len(line)) then
          if (line(i:i) /= ' ' .and. line(i:i) /= achar(9)) then
            if (start == 0) start = i
            cycle
          end if
        end if
        if (start > 0) then
          n = n + 1
          if (pass == 2) words(n)%s = line(start:i - 1)
        end if
        start = 0
      end do
      if (pass == 1) allocate(words(n))
    end do
  end subroutine split_words

  subroutine parse_numbers(line, row, ios)
    character(len=*), intent(in) :: line
    real(dp), allocatable, intent(out) :: row(:)
    integer, intent(out) :: ios
    allocate(row(word_count(line)))
    read(line, *, iostat=ios) row
  end subroutine parse_numbers

  integer pure function word_count(line) result(n)
    character(len=*), intent(in) :: line
    integer :: i
    logical :: in_word
    n = 0
    in_word = .false.
    do i = 1, len(line)
      if (line(i:i) == ' ' .or. line(i:i) == achar(9)) then
        in_word = .false.
      else if (.not. in_word) then
        in_word = .true.
        n = n + 1
      end if
    end do
  end function word_count

  !> One line of any length.
  subroutine read_text_line(unit, line, ios)
    integer, intent(in) :: unit
    character(len=:), allocatable, intent(out) :: line
    integer, intent(out) :: ios
    character(len=512) :: chunk
    integer :: got
    line = ''
    do
      read(unit, '(a)', advance='no', iostat=ios, size=got) chunk
      line = line//chunk(1:got)
      if (ios /= 0) exit
    end do
    if (is_iostat_eor(ios)) ios = 0
    if (is_iostat_end(ios) .and. len(line) > 0) ios = 0     ! a last line without newline
  end subroutine read_text_line
end module run_output
