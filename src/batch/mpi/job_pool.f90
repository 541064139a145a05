!> The job pool of `make MPI=1`: the same interface as src/batch/serial/job_pool.f90,
!> with the jobs shared by the MPI ranks.  Rank 0 is the manager: it hands
!> out job indices one at a time to whichever worker asks (dynamic balance:
!> long and short points mix), collects exit statuses and reports progress;
!> ranks 1..N-1 run the jobs (each job is its own flexmech process, so a
!> failing or crashing point only returns a status).  With one rank, rank 0
!> runs every job itself.  The manager waits with MPI_Test and short sleeps,
!> not in a busy receive, so that it does not take a core from the workers.
module job_pool
  use, intrinsic :: iso_c_binding, only: c_int
  use c_library, only: c_usleep
  use mpi_f08, only: MPI_Init, MPI_Initialized, MPI_Finalize, MPI_Finalized, MPI_Comm_rank, MPI_Comm_size, &
    MPI_Send, MPI_Recv, MPI_Irecv, MPI_Test, MPI_Barrier, MPI_Bcast, MPI_COMM_WORLD, MPI_INTEGER, &
    MPI_ANY_SOURCE, MPI_Status, MPI_Request, MPI_STATUS_IGNORE
  use kinds, only: dp
  use progress, only: progress_t
  use process_runner, only: run_command, is_child
  implicit none
  private
  public :: pool_start, pool_stop, pool_is_root, pool_size, pool_run, pool_launched

  integer, parameter :: tag_request = 1, tag_job = 2
  logical, save :: started_here = .false.

contains

  subroutine pool_start()
    logical :: up
    call MPI_Initialized(up)
    if (up) return
    call MPI_Init()
    started_here = .true.
  end subroutine pool_start

  subroutine pool_stop()
    logical :: down
    if (.not. started_here) return
    call MPI_Finalized(down)
    if (.not. down) call MPI_Finalize()
    started_here = .false.
  end subroutine pool_stop

  !> Started by mpirun as one of several processes (read from the launcher's
  !> environment, before MPI_Init): a single deck then runs once, not once per rank.
  logical function pool_launched()
    character(len=16) :: value
    integer :: n, ios, status, k
    character(len=*), parameter :: names(3) = [character(len=20) :: 'OMPI_COMM_WORLD_SIZE', 'PMI_SIZE', 'PMIX_SIZE']
    pool_launched = .false.
    if (is_child()) return          ! a point or deck run by a rank, not a rank
    do k = 1, size(names)
      call get_environment_variable(trim(names(k)), value, status=status)
      if (status /= 0) cycle
      read(value, *, iostat=ios) n
      if (ios == 0 .and. n > 1) pool_launched = .true.
    end do
  end function pool_launched

  logical function pool_is_root()
    integer :: rank
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    pool_is_root = rank == 0
  end function pool_is_root

  integer function pool_size()
    call MPI_Comm_size(MPI_COMM_WORLD, pool_size)
  end function pool_size

  !> statuses(i): exit status of commands(i) (-1: could not be started), on
  !> every rank.  The barrier first: rank 0 has written the jobs' files.
  subroutine pool_run(commands, statuses, label)
    character(len=*), intent(in) :: commands(:)
    integer, intent(out) :: statuses(:)
    character(len=*), intent(in) :: label
    character(len=:), allocatable :: why
    integer :: i
    statuses = -1
    call MPI_Barrier(MPI_COMM_WORLD)
    if (pool_size() == 1) then
      do i = 1, size(commands)
        call run_command(trim(commands(i)), statuses(i), why)
      end do
    else if (pool_is_root()) then
      call manage(size(commands), statuses, label)
    else
      call work(commands)
    end if
    if (size(statuses) > 0) call MPI_Bcast(statuses, size(statuses), MPI_INTEGER, 0, MPI_COMM_WORLD)
  end subroutine pool_run

  !> Rank 0: answer each request [finished job, its status] with the next job
  !> index, or 0 (stop) when none is left, until every worker has stopped.
  subroutine manage(n, statuses, label)
    integer, intent(in) :: n
    integer, intent(inout) :: statuses(:)
    character(len=*), intent(in) :: label
    integer, asynchronous :: msg(2)
    integer :: next, stopped, done, stop_job(1), job(1)
    integer(c_int) :: slept
    type(MPI_Status) :: st
    type(MPI_Request) :: req
    type(progress_t) :: bar
    logical :: arrived
    next = 1
    stopped = 0
    done = 0
    stop_job = 0
    call bar%start(label//' done', 0.0_dp, real(n, dp), counts=.true.)
    do while (stopped < pool_size() - 1)
      call MPI_Irecv(msg, 2, MPI_INTEGER, MPI_ANY_SOURCE, tag_request, MPI_COMM_WORLD, req)
      do
        call MPI_Test(req, arrived, st)
        if (arrived) exit
        slept = c_usleep(20000_c_int)
      end do
      if (msg(1) > 0) then
        statuses(msg(1)) = msg(2)
        done = done + 1
        call bar%update(real(done, dp))
      end if
      if (next <= n) then
        job = next
        next = next + 1
        call MPI_Send(job, 1, MPI_INTEGER, st%MPI_SOURCE, tag_job, MPI_COMM_WORLD)
      else
        call MPI_Send(stop_job, 1, MPI_INTEGER, st%MPI_SOURCE, tag_job, MPI_COMM_WORLD)
        stopped = stopped + 1
      end if
    end do
    call bar%finish()
  end subroutine manage

  !> Ranks 1..: ask for a job, run it, report its status, until told to stop.
  subroutine work(commands)
    character(len=*), intent(in) :: commands(:)
    integer :: msg(2), job(1), status
    character(len=:), allocatable :: why
    msg = 0
    do
      call MPI_Send(msg, 2, MPI_INTEGER, 0, tag_request, MPI_COMM_WORLD)
      call MPI_Recv(job, 1, MPI_INTEGER, 0, tag_job, MPI_COMM_WORLD, MPI_STATUS_IGNORE)
      if (job(1) == 0) exit
      call run_command(trim(commands(job(1))), status, why)
      msg = [job(1), status]
    end do
  end subroutine work
end module job_pool
