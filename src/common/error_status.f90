!> Errors as values: library routines fill an error_t and return; callers add
!> context and return in turn; only the main program stops.
!>
!>     call solve(..., err);  if (err%failed()) then; call err%add_context('assembling M'); return; end if
module error_status
  implicit none
  private
  public :: error_t

  type :: error_t
    integer :: code = 0                         !< 0 = no error
    character(len=:), allocatable :: message
  contains
    procedure :: failed
    procedure :: set
    procedure :: add_context
    procedure :: clear
    procedure :: text
  end type error_t

contains

  logical pure function failed(self)
    class(error_t), intent(in) :: self
    failed = self%code /= 0
  end function failed

  !> Record an error; `where` names the routine or input item.
  pure subroutine set(self, where, message, code)
    class(error_t), intent(inout) :: self
    character(len=*), intent(in) :: where, message
    integer, intent(in), optional :: code
    self%code = 1
    if (present(code)) self%code = code
    if (len_trim(where) > 0) then
      self%message = trim(where)//': '//trim(message)
    else
      self%message = trim(message)
    end if
  end subroutine set

  !> Prefix the message with the caller's context ("context: message").
  pure subroutine add_context(self, context)
    class(error_t), intent(inout) :: self
    character(len=*), intent(in) :: context
    if (.not. allocated(self%message)) self%message = 'unknown error'
    self%message = trim(context)//': '//self%message
  end subroutine add_context

  pure subroutine clear(self)
    class(error_t), intent(inout) :: self
    self%code = 0
    if (allocated(self%message)) deallocate(self%message)
  end subroutine clear

  pure function text(self) result(msg)
    class(error_t), intent(in) :: self
    character(len=:), allocatable :: msg
    if (allocated(self%message)) then
      msg = self%message
    else
      msg = ''
    end if
  end function text
end module error_status
