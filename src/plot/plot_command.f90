!> `flexmech plot RUN.out [MORE.out ...] [-d DIR] [--png] [--script-only]`
!>
!> For each output: writes DIR/<stem>.gp (DIR defaults to the output's own
!> directory) and runs gnuplot on it, which draws DIR/<stem>_<figure>.png and
!> .svg.  --png draws the PNG files only; --script-only writes the scripts and
!> does not run gnuplot.  Exit status 0 when every figure was drawn, 1 on a
!> usage error, 3 when an output could not be read or gnuplot failed.
module plot_command
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use error_status, only: error_t
  use version, only: program_name
  use run_output, only: run_output_t, read_run_output
  use plot_script, only: write_plot_script
  use process_runner, only: shell_quote, run_command
  implicit none
  private
  public :: run_plot_command

contains

  !> args: the command-line words after 'plot'.
  subroutine run_plot_command(args, exit_status)
    character(len=*), intent(in) :: args(:)
    integer, intent(out) :: exit_status
    character(len=:), allocatable :: dir
    logical :: script_only, png_only
    integer :: i, status
    logical :: want(size(args))
    exit_status = 0
    script_only = .false.
    png_only = .false.
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
      case default
        want(i) = .true.
      end select
    end do
    if (.not. any(want)) then
      call usage('no output file given')
      exit_status = 1
      return
    end if
    do i = 1, size(args)
      if (.not. want(i)) cycle
      call plot_one(trim(args(i)), dir, script_only, png_only, status)
      exit_status = max(exit_status, status)
    end do
  end subroutine run_plot_command

  subroutine plot_one(path, dir, script_only, png_only, status)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(in) :: dir
    logical, intent(in) :: script_only, png_only
    integer, intent(out) :: status
    type(run_output_t) :: out
    type(error_t) :: err
    character(len=64), allocatable :: figures(:)
    character(len=:), allocatable :: base, script, why, command
    integer :: i
    status = 0
    base = figure_base(path, dir)
    script = base//'.gp'
    call read_run_output(path, out, err)
    if (.not. err%failed()) then
      call write_plot_script(out, base, script, figures, err)
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
    do i = 1, size(figures)
      write(output_unit, '(a)') program_name//' plot: drew '//base//'_'//trim(figures(i))// &
        trim(merge('.png      ', '.png, .svg', png_only))
    end do
  end subroutine plot_one

  !> DIR/<stem> where stem is the output's file name without its extension.
  pure function figure_base(path, dir) result(base)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(in) :: dir
    character(len=:), allocatable :: base
    integer :: slash, dot
    slash = index(path, '/', back=.true.)
    base = path(slash + 1:)
    dot = index(base, '.', back=.true.)
    if (dot > 1) base = base(1:dot - 1)
    if (allocated(dir)) then
      base = dir//'/'//base
    else if (slash > 0) then
      base = path(1:slash)//base
    end if
  end function figure_base

  subroutine usage(why)
    character(len=*), intent(in) :: why
    write(error_unit, '(a)') program_name//' plot: '//why
    write(error_unit, '(a)') 'usage: '//program_name//' plot RUN.out [MORE.out ...] [-d DIR] [--png] [--script-only]'
  end subroutine usage
end module plot_command
