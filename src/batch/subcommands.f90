!> The command lines that are not a single analysis, recognised before the
!> main program reads its deck:
!>
!>   flexmech plot RUN.out ...          figures of outputs (module plot_command)
!>
!> `dispatch_subcommands` returns when the command line is an ordinary
!> `flexmech DECK.nml [-o OUT]`; otherwise it runs the command and ends the
!> program with its exit status.
module subcommands
  use command_line, only: quit
  use plot_command, only: run_plot_command
  implicit none
  private
  public :: dispatch_subcommands

  integer, parameter :: max_arg = 4096

contains

  subroutine dispatch_subcommands()
    character(len=max_arg), allocatable :: args(:)
    integer :: i, status
    allocate(args(command_argument_count()))
    do i = 1, size(args)
      call get_command_argument(i, args(i))
    end do
    if (size(args) == 0) return
    if (args(1) == 'plot') then
      call run_plot_command(args(2:), status)
      call quit(status)
    end if
  end subroutine dispatch_subcommands
end module subcommands
