!> `flexmech A.nml B.nml ...`: several decks, each run as its own flexmech
!> process writing DECK.out in the current directory (a deck with a &sweep
!> group runs its sweep), then one table of exit statuses on stdout.  With
!> `make MPI=1` under mpirun the decks are shared by the ranks.
module deck_batch
  use, intrinsic :: iso_fortran_env, only: output_unit
  use version, only: program_name
  use command_line, only: default_output
  use strings, only: shell_quote, str
  use process_runner, only: flexmech_command
  use job_pool, only: pool_start, pool_stop, pool_is_root, pool_run
  use sweep_run, only: status_meaning
  implicit none
  private
  public :: run_deck_batch, run_single_deck

contains

  !> exit_status: 0 when every deck succeeded, else 3.
  subroutine run_deck_batch(decks, exit_status)
    character(len=*), intent(in) :: decks(:)
    integer, intent(out) :: exit_status
    character(len=2048) :: commands(size(decks))
    integer :: statuses(size(decks)), k
    character(len=:), allocatable :: run
    character(len=22) :: meaning
    call pool_start()
    run = flexmech_command()
    do k = 1, size(decks)
      commands(k) = run//' '//shell_quote(trim(decks(k)))//' -o '// &
                    shell_quote(default_output(trim(decks(k))))
    end do
    call pool_run(commands, statuses, 'batch decks')
    exit_status = 0
    if (pool_is_root()) then
      write(output_unit, '(a)') program_name//': batch of '//str(size(decks))//' decks:'
      write(output_unit, '(a)') '   exit  meaning                deck -> output'
      do k = 1, size(decks)
        meaning = status_meaning(statuses(k))
        write(output_unit, '(i7,2x,a22,1x,a)') statuses(k), meaning, &
          trim(decks(k))//' -> '//default_output(trim(decks(k)))
      end do
      write(output_unit, '(a)') program_name//': '//str(count(statuses == 0))//' succeeded, '// &
        str(count(statuses /= 0))//' failed'
      if (any(statuses /= 0)) exit_status = 3
    end if
    call pool_stop()
  end subroutine run_deck_batch

  !> One deck under mpirun with several ranks: run once (by one worker), with
  !> the deck's own exit status on rank 0 and 0 on the others.
  subroutine run_single_deck(deck, out_path, exit_status)
    character(len=*), intent(in) :: deck, out_path
    integer, intent(out) :: exit_status
    character(len=2048) :: commands(1)
    integer :: statuses(1)
    call pool_start()
    commands(1) = flexmech_command()//' '//shell_quote(deck)//' -o '//shell_quote(out_path)
    call pool_run(commands, statuses, 'deck')
    exit_status = 0
    if (pool_is_root()) exit_status = max(0, statuses(1))
    call pool_stop()
  end subroutine run_single_deck
end module deck_batch
