!> Runs a list of independent jobs (shell commands, one flexmech process
!> each) one after the other.  This is the serial build's pool; `make MPI=1`
!> compiles src/batch/mpi/job_pool.f90 instead, with the same interface, whose
!> ranks share the jobs.  The serial build needs no MPI.
module job_pool
  use progress, only: progress_t
  use kinds, only: dp
  use process_runner, only: run_command
  implicit none
  private
  public :: pool_start, pool_stop, pool_is_root, pool_size, pool_run, pool_launched

contains

  subroutine pool_start()
  end subroutine pool_start

  subroutine pool_stop()
  end subroutine pool_stop

  !> Started as one of several MPI processes?  Never in the serial build.
  logical function pool_launched()
    pool_launched = .false.
  end function pool_launched

  logical function pool_is_root()
    pool_is_root = .true.
  end function pool_is_root

  integer function pool_size()
    pool_size = 1
  end function pool_size

  !> statuses(i): exit status of commands(i) (-1: could not be started).
  !> Reports 'label done  k/n' on stderr while it runs, when stderr is a terminal.
  subroutine pool_run(commands, statuses, label)
    character(len=*), intent(in) :: commands(:)
    integer, intent(out) :: statuses(:)
    character(len=*), intent(in) :: label
    type(progress_t) :: bar
    character(len=:), allocatable :: why
    integer :: i
    call bar%start(label//' done', 0.0_dp, real(size(commands), dp), counts=.true.)
    do i = 1, size(commands)
      call run_command(trim(commands(i)), statuses(i), why)
      call bar%update(real(i, dp))
    end do
    call bar%finish()
  end subroutine pool_run
end module job_pool
