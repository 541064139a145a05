!> Collects the messages ODEPACK emits through XERRWD, so that flexmech reports
!> them in its own diagnostics instead of letting them go to stdout.
module lsode_messages
  implicit none
  private
  public :: record_lsode_message, take_lsode_messages, clear_lsode_messages

  integer, parameter :: max_keep = 8      ! keep the most recent messages only
  character(len=:), allocatable :: log_text
  integer :: n_kept = 0

contains

  subroutine record_lsode_message(line)
    character(len=*), intent(in) :: line
    if (.not. allocated(log_text) .or. n_kept >= max_keep) then
      log_text = ''
      n_kept = 0
    end if
    if (n_kept > 0) log_text = log_text//' | '
    log_text = log_text//trim(adjustl(line))
    n_kept = n_kept + 1
  end subroutine record_lsode_message

  !> Return the messages since the last call and forget them.
  function take_lsode_messages() result(text)
    character(len=:), allocatable :: text
    if (allocated(log_text)) then
      text = log_text
    else
      text = ''
    end if
    call clear_lsode_messages()
  end function take_lsode_messages

  subroutine clear_lsode_messages()
    log_text = ''
    n_kept = 0
  end subroutine clear_lsode_messages
end module lsode_messages
