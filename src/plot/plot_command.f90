!> `flexmech plot RUN.out [MORE.out ...] [-d DIR] [--png] [--script-only]
!>                [--whole-run] [--animate] [--magnify F]`
!> `flexmech plot A.out B.out ... --compare [-n NAME] [--columns c1,c2] [-t TITLE]
!>                [--labels 'l1;l2'] [-d DIR]`
!>
!> For each output: writes DIR/<stem>.gp (DIR defaults to the output's own
!> directory) and runs gnuplot on it, which draws DIR/<stem>_<figure>.png and
!> .svg.  --png draws the PNG files only; --script-only writes the scripts and
!> does not run gnuplot.  --whole-run draws every revolution of a transient
!> run (default: the last complete one).  --animate also draws DIR/<stem>_anim.gif, the
!> deformed mechanism over the last revolution (module plot_animation); the
!> deformed mechanism's still and animation multiply the elastic displacements
!> by F (default: automatic).  --compare draws
!> the runs together in DIR/NAME_<figure> (module plot_compare; NAME defaults
!> to the first stem followed by _compare).  Exit status 0 when every figure was drawn, 1 on a
!> usage error, 3 when an output could not be read or gnuplot failed.
module plot_command
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use error_status, only: error_t
  use version, only: program_name
  use run_output, only: run_output_t, read_run_output
  use plot_script, only: write_plot_script
  use plot_animation, only: write_animation, append_shape_figure
  use plot_spatial, only: write_spatial_animation, append_spatial_shape
  use plot_compare, only: write_compare_script
  use kinds, only: dp
  use strings, only: shell_quote, file_stem
  use process_runner, only: run_command
  use command_line, only: quit, command_words, max_word
  implicit none
  private
  public :: dispatch_plot

contains

  !> `flexmech plot ...`: when the first command-line word is 'plot', draws
  !> the figures and ends the program with the command's exit status;
  !> returns otherwise.
  subroutine dispatch_plot()
    character(len=max_word), allocatable :: args(:)
    integer :: status
    call command_words(args)
    if (size(args) == 0) return
    if (args(1) /= 'plot') return
    call run_plot_command(args(2:), status)
    call quit(status)
  end subroutine dispatch_plot

  !> args: the command-line words after 'plot'.
  subroutine run_plot_command(args, exit_status)
    character(len=*), intent(in) :: args(:)
    integer, intent(out) :: exit_status
    character(len=:), allocatable :: dir
    character(len=1024) :: name, only, title, run_labels
    logical :: script_only, png_only, animate, compare, whole_run
    integer :: i, status, ios
    logical :: want(size(args))
    real(dp) :: magnify
    character(len=:), allocatable :: why
    exit_status = 0
    script_only = .false.
    png_only = .false.
    animate = .false.
    compare = .false.
    whole_run = .false.
    only = ''
    name = ''
    title = ''
    run_labels = ''
    magnify = 0.0_dp
    want = .false.
    i = 0
    do while (i < size(args))
      i = i + 1
      select case (trim(args(i)))
      case ('-d')
        if (i == size(args)) then
          call usage('-d needs a directory')
          exit_status = 1
          return
        end if
        i = i + 1
        dir = trim(args(i))
      case ('--script-only')
        script_only = .true.
      case ('--png')
        png_only = .true.
      case ('--animate')
        animate = .true.
      case ('--whole-run')
        whole_run = .true.
      case ('--compare')
        compare = .true.
      case ('-n', '--columns', '-t', '--labels')
        if (i == size(args)) then
          call usage(trim(args(i))//' needs a value')
          exit_status = 1
          return
        end if
        select case (trim(args(i)))
        case ('-n')
          name = args(i + 1)
        case ('-t')
          title = args(i + 1)
        case ('--labels')
          run_labels = args(i + 1)
        case default
          only = args(i + 1)
        end select
        i = i + 1
      case ('--magnify')
        ios = 1
        if (i < size(args)) read(args(i + 1), *, iostat=ios) magnify
        if (ios == 0) ios = merge(0, 1, magnify > 0.0_dp .and. magnify < 1.0e12_dp)
        if (ios /= 0) then
          call usage('--magnify needs a factor > 0')
          exit_status = 1
          return
        end if
        i = i + 1
      case default
        want(i) = .true.
      end select
    end do
    if (.not. any(want)) then
      call usage('no output file given')
      exit_status = 1
      return
    end if
    if (allocated(dir)) then          ! -d DIR is created when missing
      call run_command('mkdir -p '//shell_quote(dir), status, why)
    end if
    if (compare) then
      call compare_runs(args, want, dir, trim(name), trim(only), trim(title), trim(run_labels), &
                        script_only, png_only, exit_status)
      return
    end if
    do i = 1, size(args)
      if (.not. want(i)) cycle
      call plot_one(trim(args(i)), dir, script_only, png_only, whole_run, magnify, status)
      exit_status = max(exit_status, status)
      if (animate .and. status == 0) then
        call animate_one(trim(args(i)), dir, script_only, magnify, status)
        exit_status = max(exit_status, status)
      end if
    end do
  end subroutine run_plot_command

  subroutine plot_one(path, dir, script_only, png_only, whole_run, magnify, status)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(in) :: dir
    logical, intent(in) :: script_only, png_only, whole_run
    real(dp), intent(in) :: magnify     !< of the deformed shape's still; <= 0: automatic
    integer, intent(out) :: status
    integer :: u
    type(run_output_t) :: out
    type(error_t) :: err
    character(len=64), allocatable :: figures(:)
    character(len=:), allocatable :: base, script, why, command
    status = 0
    base = figure_base(path, dir)
    script = base//'.gp'
    call read_run_output(path, out, err)
    if (.not. err%failed()) then
      call write_plot_script(out, base, script, figures, err, whole_run)
    end if
    if (.not. err%failed()) then        ! the still of the deformed mechanism
      if (size(figures) > 0 .and. any(out%analysis == [character(len=9) :: 'transient', 'steady', 'spatial'])) then
        open(newunit=u, file=script, position='append', action='write')
        if (out%analysis == 'spatial') then
          call append_spatial_shape(u, out, base, figures, magnify)
        else
          call append_shape_figure(u, out, base, figures, magnify)
        end if
        close(u)
      end if
    end if
    if (err%failed()) then
      write(error_unit, '(a)') program_name//' plot: '//err%text()
      status = 3
      return
    end if
    if (size(figures) == 0) then
      write(output_unit, '(a)') program_name//' plot: '//path//': nothing to draw (no data rows)'
      return
    end if
    write(output_unit, '(a)') program_name//' plot: wrote '//script
    if (script_only) return
    command = 'gnuplot'
    if (png_only) command = command//' -e '//shell_quote('formats="png"')
    call run_command(command//' '//shell_quote(script), status, why)
    if (status /= 0) then
      if (len(why) > 0) write(error_unit, '(a)') program_name//' plot: '//why
      if (status == 127) then
        write(error_unit, '(a)') program_name//' plot: gnuplot not found (`make deps` installs gnuplot-nox)'
      else
        write(error_unit, '(a)') program_name//' plot: gnuplot failed on '//script
      end if
      status = 3
      return
    end if
    call report_drawn(base, figures, png_only)
  end subroutine plot_one

  subroutine compare_runs(args, want, dir, name, only, title, run_labels, script_only, png_only, status)
    character(len=*), intent(in) :: args(:)
    logical, intent(in) :: want(:)
    character(len=:), allocatable, intent(in) :: dir
    character(len=*), intent(in) :: name, only, title, run_labels
    logical, intent(in) :: script_only, png_only
    integer, intent(out) :: status
    type(run_output_t), allocatable :: outs(:)
    character(len=64), allocatable :: labels(:), figures(:)
    type(error_t) :: err
    character(len=:), allocatable :: base, command, why
    integer :: i, k, first
    allocate(outs(count(want)), labels(count(want)))
    first = findloc(want, .true., dim=1)
    base = figure_base(trim(args(first)), dir)
    if (len(name) > 0) then
      base = base(1:index(base, '/', back=.true.))//name
    else
      base = base//'_compare'
    end if
    k = 0
    do i = 1, size(args)
      if (.not. want(i)) cycle
      k = k + 1
      call read_run_output(trim(args(i)), outs(k), err)
      if (err%failed()) exit
      labels(k) = nth_label(run_labels, k, file_stem(trim(args(i))))
    end do
    if (.not. err%failed()) call write_compare_script(outs, labels, base, base//'.gp', only, title, figures, err)
    status = 0
    if (err%failed()) then
      write(error_unit, '(a)') program_name//' plot: '//err%text()
      status = 3
      return
    end if
    write(output_unit, '(a)') program_name//' plot: wrote '//base//'.gp'
    if (script_only .or. size(figures) == 0) return
    command = 'gnuplot'
    if (png_only) command = command//' -e '//shell_quote('formats="png"')
    call run_command(command//' '//shell_quote(base//'.gp'), status, why)
    if (status /= 0) then
      write(error_unit, '(a)') program_name//' plot: gnuplot failed on '//base//'.gp '//why
      status = 3
      return
    end if
    call report_drawn(base, figures, png_only)
  end subroutine compare_runs

  !> One line per figure gnuplot drew.
  subroutine report_drawn(base, figures, png_only)
    character(len=*), intent(in) :: base, figures(:)
    logical, intent(in) :: png_only
    integer :: i
    do i = 1, size(figures)
      write(output_unit, '(a)') program_name//' plot: drew '//base//'_'//trim(figures(i))// &
        trim(merge('.png      ', '.png, .svg', png_only))
    end do
  end subroutine report_drawn

  !> The k-th ';'-separated label, or `default` when there is none.
  pure function nth_label(list, k, default) result(s)
    character(len=*), intent(in) :: list, default
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    integer :: i, a, b
    s = default
    a = 1
    do i = 1, k
      if (a > len(list)) return
      b = index(list(a:)//';', ';') + a - 1
      if (i == k .and. b > a) s = list(a:b - 1)
      a = b + 1
    end do
  end function nth_label

  subroutine animate_one(path, dir, script_only, magnify, status)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(in) :: dir
    logical, intent(in) :: script_only
    real(dp), intent(in) :: magnify
    integer, intent(out) :: status
    type(run_output_t) :: out
    type(error_t) :: err
    character(len=:), allocatable :: base, why
    integer :: n_frames, u, ios
    status = 0
    base = figure_base(path, dir)
    call read_run_output(path, out, err)
    if (.not. err%failed()) then
      if (out%analysis == 'spatial') then
        call write_spatial_animation(out, base, magnify, n_frames, err)
      else
        call write_animation(out, base, magnify, n_frames, err)
      end if
    end if
    if (err%failed()) then
      write(error_unit, '(a)') program_name//' plot: '//err%text()
      status = 3
      return
    end if
    write(output_unit, '(a)') program_name//' plot: wrote '//base//'_anim.gp, '//base//'_anim.dat'
    if (script_only) return
    ! gnuplot's gif terminal reports the frame count on stderr: kept in a log, shown on failure
    call run_command('gnuplot '//shell_quote(base//'_anim.gp')//' 2> '//shell_quote(base//'_anim.log'), status, why)
    if (status /= 0) then
      write(error_unit, '(a)') program_name//' plot: gnuplot failed on '//base//'_anim.gp '//why// &
        ' (its messages: '//base//'_anim.log)'
      status = 3
      return
    end if
    open(newunit=u, file=base//'_anim.log', status='old', iostat=ios)
    if (ios == 0) close(u, status='delete')
    write(output_unit, '(a,i0,a)') program_name//' plot: drew '//base//'_anim.gif (', n_frames, ' frames)'
  end subroutine animate_one

  !> DIR/<stem> where stem is the output's file name without its extension.
  pure function figure_base(path, dir) result(base)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(in) :: dir
    character(len=:), allocatable :: base
    integer :: slash
    slash = index(path, '/', back=.true.)
    base = file_stem(path)
    if (allocated(dir)) then
      base = dir//'/'//base
    else if (slash > 0) then
      base = path(1:slash)//base
    end if
  end function figure_base

  subroutine usage(why)
    character(len=*), intent(in) :: why
    write(error_unit, '(a)') program_name//' plot: '//why
    write(error_unit, '(a)') 'usage: '//program_name//' plot RUN.out [MORE.out ...] [-d DIR] [--png] [--script-only]'// &
      ' [--whole-run] [--animate] [--magnify F]'
    write(error_unit, '(a)') '       '//program_name//' plot A.out B.out ... --compare [-n NAME] [--columns c1,c2]'// &
      ' [-t TITLE] [--labels ''l1;l2''] [-d DIR]'
  end subroutine usage
end module plot_command
