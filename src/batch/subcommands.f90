!> The command lines that run several decks, recognised before the main
!> program reads its deck (`flexmech plot` is recognised before them, by
!> module plot_command):
!>
!>   flexmech SWEEP.nml [-o OUT]        a deck with a &sweep group (module sweep_run)
!>   flexmech A.nml B.nml ...           several decks, one table of exit statuses (deck_batch)
!>
!> `dispatch_subcommands` returns when the command line is an ordinary
!> `flexmech DECK.nml [-o OUT]`; otherwise it runs the command and ends the
!> program with its exit status.
module subcommands
  use, intrinsic :: iso_fortran_env, only: error_unit
  use version, only: program_name
  use command_line, only: quit, command_words, max_word
  use command_line, only: default_output
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use sweep_run, only: run_sweep
  use deck_batch, only: run_deck_batch, run_single_deck
  use job_pool, only: pool_launched
  implicit none
  private
  public :: dispatch_subcommands

contains

  subroutine dispatch_subcommands()
    character(len=max_word), allocatable :: args(:), decks(:)
    character(len=:), allocatable :: out_path
    integer :: i, status
    call command_words(args)
    if (size(args) == 0) return
    do i = 1, size(args)     ! another option: the ordinary command line reports it
      if (args(i)(1:1) == '-' .and. args(i) /= '-o' .and. is_deck_argument(args, i)) return
    end do
    decks = pack(args, [(is_deck_argument(args, i) .and. args(i)(1:1) /= '-', i = 1, size(args))])
    if (size(decks) > 1) then
      if (any(args == '-o')) then
        write(error_unit, '(a)') program_name//': -o names one output; with several decks each writes DECK.out'
        call quit(1)
      end if
      call run_deck_batch(decks, status)
      call quit(status)
    end if
    if (size(decks) /= 1) return
    out_path = default_output(trim(decks(1)))
    do i = 1, size(args) - 1
      if (args(i) == '-o') out_path = trim(args(i + 1))
    end do
    if (has_sweep(trim(decks(1)))) then
      call run_sweep(trim(decks(1)), out_path, status)
      call quit(status)
    end if
    if (pool_launched()) then      ! mpirun -n N with one plain deck: run it once
      call run_single_deck(trim(decks(1)), out_path, status)
      call quit(status)
    end if
  end subroutine dispatch_subcommands

  !> A word that is not the file name after -o (and, for decks, not an option).
  logical pure function is_deck_argument(args, i)
    character(len=*), intent(in) :: args(:)
    integer, intent(in) :: i
    is_deck_argument = .true.
    if (i > 1) is_deck_argument = args(i - 1) /= '-o'
  end function is_deck_argument

  logical function has_sweep(path)
    character(len=*), intent(in) :: path
    type(deck_t) :: deck
    type(error_t) :: err
    has_sweep = .false.
    call deck%open(path, err)
    if (err%failed()) return     ! the ordinary run reports the missing deck
    has_sweep = deck%has_group('sweep')
    call deck%close()
  end function has_sweep
end module subcommands
