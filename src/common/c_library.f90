!> The C library functions flexmech calls (POSIX), each bound once here:
!> a clean process exit, the terminal test, rename and unlink of files, the
!> process id, signals, the executable's path (readlink) and a short sleep.
module c_library
  use, intrinsic :: iso_c_binding, only: c_int, c_char, c_funptr, c_size_t, c_long
  implicit none
  private
  public :: c_exit, c_isatty, c_rename, c_getpid, c_unlink, c_signal, c_raise, c_readlink, c_usleep

  interface
    subroutine c_exit(status) bind(c, name='exit')
      import :: c_int
      integer(c_int), value :: status
    end subroutine c_exit

    integer(c_int) function c_isatty(fd) bind(c, name='isatty')
      import :: c_int
      integer(c_int), value :: fd
    end function c_isatty

    integer(c_int) function c_rename(old, new) bind(c, name='rename')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: old(*), new(*)
    end function c_rename

    integer(c_int) function c_getpid() bind(c, name='getpid')
      import :: c_int
    end function c_getpid

    integer(c_int) function c_unlink(path) bind(c, name='unlink')
      import :: c_int, c_char
      character(kind=c_char), intent(in) :: path(*)
    end function c_unlink

    type(c_funptr) function c_signal(signum, handler) bind(c, name='signal')
      import :: c_int, c_funptr
      integer(c_int), value :: signum
      type(c_funptr), value :: handler
    end function c_signal

    integer(c_int) function c_raise(signum) bind(c, name='raise')
      import :: c_int
      integer(c_int), value :: signum
    end function c_raise

    function c_readlink(path, buf, bufsize) bind(c, name='readlink') result(n)
      import :: c_char, c_size_t, c_long
      character(kind=c_char), intent(in) :: path(*)
      character(kind=c_char), intent(out) :: buf(*)
      integer(c_size_t), value :: bufsize
      integer(c_long) :: n
    end function c_readlink

    integer(c_int) function c_usleep(usec) bind(c, name='usleep')
      import :: c_int
      integer(c_int), value :: usec
    end function c_usleep
  end interface
end module c_library
