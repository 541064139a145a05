!> The command line of flexmech: `flexmech DECK.nml [-o OUT]`, and a clean
!> exit with a given status (no "STOP n" noise on stderr).
module command_line
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use, intrinsic :: iso_c_binding, only: c_int
  use c_library, only: c_exit
  use version, only: program_name, program_version
  use strings, only: shell_quote, file_stem
  implicit none
  private
  public :: parse_arguments, quit, default_output, output_path_problem, command_words, max_word

  integer, parameter :: max_word = 4096   !< longest command-line word the subcommands read

contains

  !> The command-line words, each in a max_word-long text.
  subroutine command_words(words)
    character(len=max_word), allocatable, intent(out) :: words(:)
    integer :: i
    allocate(words(command_argument_count()))
    do i = 1, size(words)
      call get_command_argument(i, words(i))
    end do
  end subroutine command_words

  subroutine quit(status)
    integer, intent(in) :: status
    flush(output_unit)
    flush(error_unit)
    call c_exit(int(status, c_int))
  end subroutine quit

  subroutine parse_arguments(deck_path, out_path)
    character(len=:), allocatable, intent(out) :: deck_path, out_path
    integer :: i, n, length
    character(len=:), allocatable :: arg
    n = command_argument_count()
    i = 0
    do while (i < n)
      i = i + 1
      call get_command_argument(i, length=length)
      allocate(character(len=length) :: arg)
      call get_command_argument(i, arg)
      select case (arg)
      case ('-h', '--help')
        call usage(output_unit)
        call quit(0)
      case ('--version')
        write(output_unit, '(a)') program_name//' '//program_version
        call quit(0)
      case ('-o')
        if (i == n) then
          write(error_unit, '(a)') program_name//': -o needs a file name'
          call quit(1)
        end if
        if (allocated(out_path)) then
          write(error_unit, '(a)') program_name//': -o given twice'
          call quit(1)
        end if
        i = i + 1
        call get_command_argument(i, length=length)
        allocate(character(len=length) :: out_path)
        call get_command_argument(i, out_path)
      case default
        if (len(arg) > 1 .and. arg(1:1) == '-') then
          write(error_unit, '(a)') program_name//': unknown option '''//arg//''''
          call usage(error_unit)
          call quit(1)
        end if
        if (allocated(deck_path)) then
          write(error_unit, '(a)') program_name//': unexpected argument '''//arg//''''
          call usage(error_unit)
          call quit(1)
        end if
        deck_path = arg
      end select
      deallocate(arg)
    end do
    if (.not. allocated(deck_path)) then
      call usage(error_unit)
      call quit(1)
    end if
    if (.not. allocated(out_path)) out_path = default_output(deck_path)
  end subroutine parse_arguments

  !> Why OUT cannot be the output file of a run of DECK ('' if it can).  The
  !> output is written to OUT.tmpPID and renamed onto OUT at the end, and a
  !> rename replaces whatever node OUT is: refuse, before any work is done,
  !> an empty name, a directory, a symbolic link, a FIFO or device node (any
  !> existing node that is not a regular file) and the deck itself.  Fortran
  !> cannot tell these apart (inquire says only "exists"), so the POSIX
  !> shell's `test` classifies the path; if no shell can be started the
  !> check is skipped and the rename still reports its own failure.
  function output_path_problem(out, deck) result(problem)
    character(len=*), intent(in) :: out, deck
    character(len=:), allocatable :: problem
    character(len=:), allocatable :: o, d
    integer :: exitstat, cmdstat
    character(len=256) :: cmdmsg
    problem = ''
    if (len_trim(out) == 0) then
      problem = 'the output file name is empty'
      return
    end if
    o = shell_quote(out)
    d = shell_quote(deck)
    exitstat = 0
    cmdstat = 0
    call execute_command_line('test -L '//o//' && exit 10; test -d '//o//' && exit 11; ' // &
                              'test -e '//o//' && ! test -f '//o//' && exit 12; ' // &
                              'test -e '//o//' && test '//o//' -ef '//d//' && exit 13; exit 0', &
                              wait=.true., exitstat=exitstat, cmdstat=cmdstat, cmdmsg=cmdmsg)
    if (cmdstat /= 0) return
    select case (exitstat)
    case (10)
      problem = 'is a symbolic link (the output would replace the link, not write through it)'
    case (11)
      problem = 'is a directory (give a file name)'
    case (12)
      problem = 'exists and is not a regular file (a FIFO, socket or device node would be replaced)'
    case (13)
      problem = 'is the deck itself (the output would overwrite the input)'
    end select
  end function output_path_problem

  !> DECK.nml -> DECK.out in the current directory.
  pure function default_output(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    name = file_stem(path)//'.out'
  end function default_output

  subroutine usage(unit)
    integer, intent(in) :: unit
    write(unit, '(a)') 'usage: '//program_name//' DECK.nml [-o OUTPUT]'
    write(unit, '(a)') '  Runs the analysis named in the deck''s &run group (see doc/decks.md).'
    write(unit, '(a)') '  Default OUTPUT: DECK.out in the current directory.'
    write(unit, '(a)') '  A deck with a &sweep group runs a sweep (doc/sweeps.md); several decks run as a batch.'
    write(unit, '(a)') '       '//program_name//' plot RUN.out [-d DIR] [--png] [--animate]   figures (doc/plotting.md)'
  end subroutine usage
end module command_line
