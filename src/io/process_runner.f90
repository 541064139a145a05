!> Child processes: flexmech runs each sweep point and each deck of a batch as
!> its own process (`flexmech POINT.nml -o POINT.out`).  DLSODE keeps its state
!> in COMMON blocks, so one analysis per process is the simple way to run many;
!> a point that crashes or stops cannot disturb the others, and a point's
!> result is the same whether the batch runs serially or on MPI ranks.
module process_runner
  use, intrinsic :: iso_c_binding, only: c_char, c_size_t, c_null_char, c_long
  use c_library, only: c_readlink
  use strings, only: shell_quote
  implicit none
  private
  public :: run_command, flexmech_command, is_child

contains

  !> Runs a shell command and waits.  status: the command's exit status, or
  !> -1 when it could not be started (message in `why`).
  subroutine run_command(command, status, why)
    character(len=*), intent(in) :: command
    integer, intent(out) :: status
    character(len=:), allocatable, intent(out) :: why
    integer :: cmdstat
    character(len=256) :: cmdmsg
    why = ''
    status = -1
    cmdmsg = ''
    call execute_command_line(command, wait=.true., exitstat=status, cmdstat=cmdstat, cmdmsg=cmdmsg)
    if (cmdstat /= 0) then
      status = -1
      why = 'cannot run '''//command//''': '//trim(cmdmsg)
    end if
  end subroutine run_command

  !> The shell command that runs this flexmech executable as a child process
  !> (marked by FLEXMECH_CHILD=1: under mpirun a child inherits the launcher's
  !> environment and must not take itself for an MPI rank).
  function flexmech_command() result(c)
    character(len=:), allocatable :: c
    c = 'FLEXMECH_CHILD=1 '//shell_quote(self_executable())
  end function flexmech_command

  !> Is this process a child run by a sweep or a batch?
  logical function is_child()
    integer :: status
    call get_environment_variable('FLEXMECH_CHILD', status=status)
    is_child = status == 0
  end function is_child

  !> The path of the running flexmech executable (/proc/self/exe; argv[0] elsewhere).
  function self_executable() result(path)
    character(len=:), allocatable :: path
    character(kind=c_char) :: buf(4096)
    integer(c_long) :: n
    integer :: i, length
    n = c_readlink('/proc/self/exe'//c_null_char, buf, int(size(buf), c_size_t))
    if (n > 0 .and. n < size(buf)) then
      allocate(character(len=int(n)) :: path)
      do i = 1, int(n)
        path(i:i) = buf(i)
      end do
      return
    end if
    call get_command_argument(0, length=length)
    allocate(character(len=length) :: path)
    call get_command_argument(0, path)
  end function self_executable
end module process_runner
