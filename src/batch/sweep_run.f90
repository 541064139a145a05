!> A sweep: the deck's analysis run once per value of the &sweep variable,
!> each point as its own flexmech process on its own point deck, then one
!> summary table, one row per value: the value, the point's exit status and
!> every number of its footer (summary peaks, convergence, cost).
!>
!> Files: the summary is OUT (default DECK.out); point k's deck, output and
!> log are POINTS/<stem>_<k>.nml, .out, .log with POINTS = points_dir or
!> OUT without its extension followed by _points.  A point that fails (bad
!> value: exit 2; analysis stopped: exit 3; crash) is reported in the summary
!> (a comment line with its diagnosis instead of a row) and never stops the others.  With `make MPI=1` the
!> points are shared by the MPI ranks (src/batch/mpi/job_pool.f90); rank 0
!> writes the point decks and the summary, and every point's output is the
!> same file the serial run writes.
module sweep_run
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, shell_quote, file_stem, append_name
  use name_table, only: name_of
  use version, only: program_name, program_version
  use deck_reader, only: deck_t, invalid_value
  use run_settings, only: read_run_settings, check_deck_groups, analysis_groups, group_len, max_groups
  use table_output, only: table_t
  use sweep_settings, only: sweep_settings_t, read_sweep_settings, echo_sweep_settings
  use point_deck, only: write_point_deck, assignment_text
  use point_metrics, only: metric_t, read_point_metrics, metric_name
  use process_runner, only: run_command, flexmech_command
  use job_pool, only: pool_start, pool_stop, pool_is_root, pool_size, pool_run
  implicit none
  private
  public :: run_sweep, status_meaning

  type :: point_result_t
    type(metric_t), allocatable :: metrics(:)
    character(len=:), allocatable :: notes
  end type point_result_t

contains

  !> Runs the sweep of deck_path; exit_status 0 when every point succeeded,
  !> 2 for a bad &sweep group, 3 when a point failed (summary still written).
  subroutine run_sweep(deck_path, out_path, exit_status)
    character(len=*), intent(in) :: deck_path, out_path
    integer, intent(out) :: exit_status
    type(deck_t) :: deck
    type(sweep_settings_t) :: s
    type(error_t) :: err
    character(len=32) :: analysis
    character(len=256) :: title
    character(len=:), allocatable :: dir, stem, why
    character(len=2048), allocatable :: commands(:)
    integer, allocatable :: statuses(:)
    integer :: k, st
    call pool_start()
    call deck%open(deck_path, err)
    if (.not. err%failed()) call read_run_settings(deck, analysis, title, err)
    if (.not. err%failed()) call check_deck_groups(deck, analysis, .true., err)
    if (.not. err%failed()) call read_sweep_settings(deck, s, err)
    if (.not. err%failed()) call check_swept_group(deck, analysis, s%group, err)
    if (err%failed()) then
      if (pool_is_root()) write(error_unit, '(a)') program_name//': input error: '//err%text()
      call pool_stop()
      exit_status = 2
      return
    end if
    call point_names(out_path, s%points_dir, dir, stem)
    allocate(commands(size(s%values)), statuses(size(s%values)))
    do k = 1, size(s%values)
      commands(k) = point_command(flexmech_command(), point_file(dir, stem, k, size(s%values)))
    end do
    if (pool_is_root()) then
      call run_command('mkdir -p '//shell_quote(dir), st, why)
      do k = 1, size(s%values)
        call write_point_deck(deck, trim(s%group), trim(s%variable), s%values(k), &
                              point_file(dir, stem, k, size(s%values))//'.nml', err)
        if (err%failed()) write(error_unit, '(a)') program_name//': '//err%text()
        call err%clear()
      end do
    end if
    call pool_run(commands, statuses, 'sweep points')
    exit_status = 0
    if (pool_is_root()) then
      call write_summary(deck, s, title, out_path, dir, stem, statuses, err)
      if (err%failed()) then
        write(error_unit, '(a)') program_name//': error: '//err%text()
        exit_status = 1
      else
        write(output_unit, '(a)') program_name//': sweep of '//trim(s%variable)//' over '// &
          str(size(s%values))//' values: '//str(count(statuses == 0))//' succeeded, '// &
          str(count(statuses /= 0))//' failed; summary '//out_path//', points in '//dir
        if (any(statuses /= 0)) exit_status = 3
      end if
    end if
    call deck%close()
    call pool_stop()
  end subroutine run_sweep

  !> The swept group must be one the analysis reads (else every point would
  !> be refused for a group it does not read).
  subroutine check_swept_group(deck, analysis, group, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: analysis, group
    type(error_t), intent(inout) :: err
    character(len=group_len) :: reads(max_groups)
    integer :: i
    logical :: read_by
    reads = analysis_groups(trim(analysis))
    read_by = .false.
    do i = 1, size(reads)
      read_by = read_by .or. reads(i) == group
    end do
    if (.not. read_by) call invalid_value(deck, 'sweep', 'group', ''''//trim(group)//'''', &
                                          'the '''//trim(analysis)//''' analysis does not read it', err)
  end subroutine check_swept_group

  !> The shell command of one point (POINT.nml -> POINT.out, messages to POINT.log).
  pure function point_command(flexmech, point) result(c)
    character(len=*), intent(in) :: flexmech, point
    character(len=:), allocatable :: c
    c = flexmech//' '//shell_quote(point//'.nml')//' -o '//shell_quote(point//'.out')// &
        ' > '//shell_quote(point//'.log')//' 2>&1'
  end function point_command

  subroutine point_names(out_path, points_dir, dir, stem)
    character(len=*), intent(in) :: out_path, points_dir
    character(len=:), allocatable, intent(out) :: dir, stem
    integer :: slash
    slash = index(out_path, '/', back=.true.)
    stem = file_stem(out_path)
    if (len_trim(points_dir) > 0) then
      dir = trim(points_dir)
    else
      dir = out_path(1:slash)//stem//'_points'
    end if
  end subroutine point_names

  pure function point_file(dir, stem, k, n) result(p)
    character(len=*), intent(in) :: dir, stem
    integer, intent(in) :: k, n
    character(len=:), allocatable :: p
    character(len=16) :: buf
    write(buf, '(i0.'//str(max(3, len(str(n))))//')') k
    p = dir//'/'//stem//'_'//trim(buf)
  end function point_file

  integer pure function name_index(names, name) result(i)
    character(len=*), intent(in) :: names(:), name
    do i = 1, size(names)
      if (names(i) == name) return
    end do
    i = 0
  end function name_index

  !> The first line of a point's log (its diagnosis), at most 300 characters.
  function first_line(path) result(s)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: s
    character(len=300) :: buf
    integer :: u, ios
    s = 'no log'
    open(newunit=u, file=path, status='old', action='read', iostat=ios)
    if (ios /= 0) return
    read(u, '(a)', iostat=ios) buf
    if (ios == 0) s = trim(buf)
    close(u)
  end function first_line

  !> Names separated by spaces (metric names may be longer than a column).
  pure function column_line(names) result(s)
    character(len=*), intent(in) :: names(:)
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, size(names)
      s = s//' '//trim(names(i))
    end do
  end function column_line

  !> A run's exit status in words: -1 for a run that could not be started,
  !> 0..3 flexmech's exit codes, anything else a crash.
  pure function status_meaning(status) result(s)
    integer, intent(in) :: status
    character(len=:), allocatable :: s
    character(len=*), parameter :: meanings(5) = [character(len=21) :: 'could not be started', 'ok', &
      'usage or output error', 'input error', 'analysis stopped']
    s = name_of(meanings, status, -1, 'crashed')
  end function status_meaning

  !> The summary table: a row per point that succeeded, with the numbers its
  !> footer shares with every other such point (a table holds finite numbers
  !> only); a failed point has no row and a comment line with its diagnosis,
  !> among the notes before the column names.
  subroutine write_summary(deck, s, title, out_path, dir, stem, statuses, err)
    type(deck_t), intent(in) :: deck
    type(sweep_settings_t), intent(in) :: s
    character(len=*), intent(in) :: title, out_path, dir, stem
    integer, intent(in) :: statuses(:)
    type(error_t), intent(inout) :: err
    type(point_result_t) :: r(size(statuses))
    type(table_t) :: out
    character(len=64), allocatable :: names(:), all_names(:)
    real(dp), allocatable :: row(:)
    real(dp) :: cpu_sum
    integer :: k, j, n
    call collect_points(dir, stem, statuses, r, names)
    call out%open(out_path, err)
    if (err%failed()) return
    call out%comment(program_name//' '//program_version)
    call out%comment('deck: '//deck%path)
    if (len_trim(title) > 0) call out%comment('title: '//trim(title))
    call out%comment('sweep: '//trim(s%variable)//' of &'//trim(s%group)//' over '//str(size(s%values))// &
                     ' values; point decks, outputs and logs in '//dir//'/'//stem//'_<k>.{nml,out,log}')
    call echo_sweep_settings(s, out)
    call out%comment('columns: the swept value; the exit status of the point (0); every number of the '// &
                     'summary and cost footer common to all points that succeeded. A failed point has no row: '// &
                     'its exit status (2 input error, 3 analysis stopped) and diagnosis are in its point line above')
    n = size(names)
    allocate(all_names(n + 2), row(n + 2))
    all_names(1) = metric_name(s%variable(1:scan(s%variable//'(', '(') - 1))
    all_names(2) = 'exit_status'
    all_names(3:) = names
    ! the points' notes first: the column names stay the last '#' line before the rows
    do k = 1, size(statuses)
      if (statuses(k) /= 0) then
        call out%comment('point '//str(k)//': '//assignment_text(trim(s%variable), s%values(k))//': exit '// &
                         str(statuses(k))//' ('//status_meaning(statuses(k))//'), no row'//r(k)%notes)
      else if (len(r(k)%notes) > 0) then           ! text summaries: status = converged ...
        call out%comment('point '//str(k)//': '//assignment_text(trim(s%variable), s%values(k))//r(k)%notes)
      end if
    end do
    call out%comment(column_line(all_names))
    cpu_sum = 0.0_dp
    do k = 1, size(statuses)
      do j = 1, size(r(k)%metrics)
        if (r(k)%metrics(j)%name == 'cost_total_cpu_seconds') cpu_sum = cpu_sum + r(k)%metrics(j)%value
      end do
      if (statuses(k) /= 0) cycle
      row(1) = s%values(k)
      row(2) = 0.0_dp
      do j = 1, size(r(k)%metrics)
        if (name_index(names, r(k)%metrics(j)%name) > 0) &
          row(2 + name_index(names, r(k)%metrics(j)%name)) = r(k)%metrics(j)%value
      end do
      call out%row(row)
    end do
    call out%summary('points', str(size(statuses)))
    call out%summary('points succeeded', str(count(statuses == 0)))
    call out%summary('points failed', str(count(statuses /= 0)))
    call out%cost('points_total_cpu_seconds', str(cpu_sum, 4))
    call out%cost('processes', str(pool_size()))
    call out%commit(err)
  end subroutine write_summary

  !> Footer numbers of every point that succeeded, and the names that all of
  !> them have with finite values (in the first point's order).
  subroutine collect_points(dir, stem, statuses, r, names)
    character(len=*), intent(in) :: dir, stem
    integer, intent(in) :: statuses(:)
    type(point_result_t), intent(out) :: r(:)
    character(len=64), allocatable, intent(out) :: names(:)
    type(error_t) :: perr
    character(len=64), allocatable :: first(:)
    integer :: k, j, n_ok
    allocate(first(0))
    n_ok = 0
    do k = 1, size(statuses)
      r(k)%notes = ''
      allocate(r(k)%metrics(0))
      if (statuses(k) /= 0) then
        r(k)%notes = '; '//first_line(point_file(dir, stem, k, size(statuses))//'.log')
        cycle
      end if
      call read_point_metrics(point_file(dir, stem, k, size(statuses))//'.out', r(k)%metrics, r(k)%notes, perr)
      call perr%clear()
      n_ok = n_ok + 1
      if (n_ok > 1) cycle
      do j = 1, size(r(k)%metrics)
        if (name_index(first, r(k)%metrics(j)%name) == 0) call append_name(first, r(k)%metrics(j)%name)
      end do
    end do
    allocate(names(0))
    do j = 1, size(first)
      if (all([(has_finite(r(k)%metrics, first(j)) .or. statuses(k) /= 0, k = 1, size(statuses))])) &
        call append_name(names, first(j))
    end do
  end subroutine collect_points

  logical function has_finite(metrics, name)
    type(metric_t), intent(in) :: metrics(:)
    character(len=*), intent(in) :: name
    integer :: j
    has_finite = .false.
    do j = 1, size(metrics)
      if (metrics(j)%name == name) has_finite = ieee_is_finite(metrics(j)%value)
    end do
  end function has_finite
end module sweep_run
