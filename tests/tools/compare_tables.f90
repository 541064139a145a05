!> compare_tables REFERENCE COMPUTED [TOLERANCES]
!>
!> Compares two flexmech tabular outputs column by column.  A value passes when
!> |computed - expected| <= atol + rtol*|expected|, with (rtol, atol) from the
!> tolerance file: lines "column rtol atol" and optionally "default rtol atol"
!> ('!' starts a comment; the column name '*' is the same as 'default').
!> Without a tolerance file the default is rtol = 1e-10, atol = 1e-12.
!> A column listed with rtol < 0 is not compared (e.g. CPU-dependent columns).
!> A name may end or start with '*' to match a prefix or a suffix
!> (e.g. 'sigma_max_*', '*_U'); later lines override earlier ones.
!> The line "path rtol atol" widens the tolerances of every row but the last
!> (an optimizer's iterates, whose path the last bits may steer while the
!> final point is the same): there the larger of the column's and the path's
!> tolerances applies.
!>
!> Prints every failing value (column, row, expected, computed, difference, up
!> to 20 of them) and exits 1 on any failure, 0 otherwise.
program compare_tables
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use kinds, only: dp
  use strings, only: lower
  implicit none

  character(len=:), allocatable :: ref_path, new_path, tol_path
  character(len=64), allocatable :: ref_names(:), new_names(:), tol_names(:)
  real(dp), allocatable :: ref(:, :), new(:, :), tol_r(:), tol_a(:)
  real(dp) :: def_r, def_a, r, a, diff, ri, ai, path_r, path_a
  integer :: n_args, i, j, k, n_fail, n_checked
  logical :: ok

  n_args = command_argument_count()
  if (n_args < 2) then
    write(error_unit, '(a)') 'usage: compare_tables REFERENCE COMPUTED [TOLERANCES]'
    error stop 2
  end if
  ref_path = argument(1)
  new_path = argument(2)
  def_r = 1.0e-10_dp
  def_a = 1.0e-12_dp
  allocate(tol_names(0), tol_r(0), tol_a(0))
  if (n_args >= 3) then
    tol_path = argument(3)
    call read_tolerances(tol_path, tol_names, tol_r, tol_a, def_r, def_a)
  end if

  call read_table(ref_path, ref_names, ref, ok)
  if (.not. ok) error stop 2
  call read_table(new_path, new_names, new, ok)
  if (.not. ok) error stop 2

  n_fail = 0
  if (size(ref_names) /= size(new_names)) then
    write(output_unit, '(a,i0,a,i0)') 'column count differs: reference ', size(ref_names), ', computed ', &
      size(new_names)
    n_fail = n_fail + 1
  else if (any(ref_names /= new_names)) then
    write(output_unit, '(a)') 'column names differ'
    n_fail = n_fail + 1
  end if
  if (size(ref, 1) /= size(new, 1)) then
    write(output_unit, '(a,i0,a,i0)') 'row count differs: reference ', size(ref, 1), ', computed ', size(new, 1)
    n_fail = n_fail + 1
  end if
  if (n_fail > 0) error stop 1

  path_r = -1.0_dp
  path_a = 0.0_dp
  do k = 1, size(tol_names)
    if (lower(trim(tol_names(k))) == 'path') then
      path_r = tol_r(k)
      path_a = tol_a(k)
    end if
  end do
  n_checked = 0
  do j = 1, size(ref_names)
    r = def_r
    a = def_a
    do k = 1, size(tol_names)
      if (matches(lower(trim(tol_names(k))), lower(trim(ref_names(j))))) then
        r = tol_r(k)
        a = tol_a(k)
      end if
    end do
    if (r < 0.0_dp) cycle
    do i = 1, size(ref, 1)
      n_checked = n_checked + 1
      diff = new(i, j) - ref(i, j)
      ri = r
      ai = a
      if (i < size(ref, 1) .and. path_r >= 0.0_dp) then
        ri = max(r, path_r)
        ai = max(a, path_a)
      end if
      if (.not. (abs(diff) <= ai + ri*abs(ref(i, j)))) then
        n_fail = n_fail + 1
        if (n_fail <= 20) write(output_unit, '(a,a,a,i0,a,es23.15,a,es23.15,a,es10.3,a,es9.2,a,es9.2,a)') &
          '  column ', trim(ref_names(j)), ' row ', i, ': expected ', ref(i, j), ' computed ', new(i, j), &
          ' diff ', diff, ' (rtol ', ri, ' atol ', ai, ')'
      end if
    end do
  end do
  if (n_fail > 0) then
    write(output_unit, '(i0,a,i0,a)') n_fail, ' of ', n_checked, ' values outside tolerance'
    error stop 1
  end if
  write(output_unit, '(a,i0,a,i0,a)') 'all ', n_checked, ' values within tolerance (', size(ref, 1), ' rows)'

contains

  function argument(i) result(s)
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    integer :: length
    call get_command_argument(i, length=length)
    allocate(character(len=length) :: s)
    call get_command_argument(i, s)
  end function argument

  !> Column names come from the last '#' line before the first data row.
  subroutine read_table(path, names, values, ok)
    character(len=*), intent(in) :: path
    character(len=64), allocatable, intent(out) :: names(:)
    real(dp), allocatable, intent(out) :: values(:, :)
    logical, intent(out) :: ok
    character(len=8192) :: line, last_comment
    integer :: u, ios, n_rows, n_cols, i
    ok = .false.
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) then
      write(error_unit, '(a)') 'compare_tables: cannot open '//path
      return
    end if
    n_rows = 0
    last_comment = ''
    n_cols = -1
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (len_trim(line) == 0) cycle
      if (adjustl(line) == '#' .or. line(1:1) == '#') then
        if (n_rows == 0) last_comment = line(2:)
        cycle
      end if
      if (n_rows == 0) n_cols = count_words(last_comment)
      n_rows = n_rows + 1
    end do
    if (n_cols <= 0) then
      write(error_unit, '(a)') 'compare_tables: no column-name line or no rows in '//path
      close(u)
      return
    end if
    allocate(names(n_cols), values(n_rows, n_cols))
    call split_words(last_comment, names)
    rewind(u)
    i = 0
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (len_trim(line) == 0 .or. line(1:1) == '#') cycle
      i = i + 1
      read(line, *, iostat=ios) values(i, :)
      if (ios /= 0) then
        write(error_unit, '(a,i0,a)') 'compare_tables: bad data row ', i, ' in '//path
        close(u)
        return
      end if
    end do
    close(u)
    ok = .true.
  end subroutine read_table

  integer function count_words(s)
    character(len=*), intent(in) :: s
    integer :: i
    logical :: in_word
    count_words = 0
    in_word = .false.
    do i = 1, len_trim(s)
      if (s(i:i) /= ' ') then
        if (.not. in_word) count_words = count_words + 1
        in_word = .true.
      else
        in_word = .false.
      end if
    end do
  end function count_words

  logical function matches(pattern, name)
    character(len=*), intent(in) :: pattern, name
    integer :: lp, ln
    lp = len(pattern)
    ln = len(name)
    if (lp > 1 .and. pattern(lp:lp) == '*') then
      matches = ln >= lp - 1
      if (matches) matches = name(1:lp - 1) == pattern(1:lp - 1)
    else if (lp > 1 .and. pattern(1:1) == '*') then
      matches = ln >= lp - 1
      if (matches) matches = name(ln - lp + 2:) == pattern(2:)
    else
      matches = pattern == name
    end if
  end function matches

  !> Whitespace-separated words (list-directed input would stop at a '/').
  subroutine split_words(s, words)
    character(len=*), intent(in) :: s
    character(len=*), intent(out) :: words(:)
    integer :: i, k, start
    k = 0
    start = 0
    do i = 1, len_trim(s) + 1
      if (i <= len_trim(s)) then
        if (s(i:i) /= ' ') then
          if (start == 0) start = i
          cycle
        end if
      end if
      if (start > 0) then
        k = k + 1
        if (k <= size(words)) words(k) = s(start:i - 1)
        start = 0
      end if
    end do
  end subroutine split_words

  subroutine read_tolerances(path, names, rtols, atols, def_r, def_a)
    character(len=*), intent(in) :: path
    character(len=64), allocatable, intent(inout) :: names(:)
    real(dp), allocatable, intent(inout) :: rtols(:), atols(:)
    real(dp), intent(inout) :: def_r, def_a
    character(len=512) :: line
    character(len=64) :: name
    real(dp) :: r, a
    integer :: u, ios, c
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) then
      write(error_unit, '(a)') 'compare_tables: cannot open tolerance file '//path
      error stop 2
    end if
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      c = index(line, '!')
      if (c > 0) line(c:) = ''
      if (len_trim(line) == 0) cycle
      read(line, *, iostat=ios) name, r, a
      if (ios /= 0) then
        write(error_unit, '(a)') 'compare_tables: bad tolerance line: '//trim(line)
        error stop 2
      end if
      if (name == 'default' .or. name == '*') then
        def_r = r
        def_a = a
      else
        names = [names, name]
        rtols = [rtols, r]
        atols = [atols, a]
      end if
    end do
    close(u)
  end subroutine read_tolerances
end program compare_tables
