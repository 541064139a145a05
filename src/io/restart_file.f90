!> Restart files of the transient analyses: the time and the state (q, q_dot
!> interleaved), one number a line, in the format the planar transient
!> analysis writes (so the spatial analysis reads and writes the same files;
!> and start_from_restart is the 'restart' initial state both take).
module restart_file
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use table_output, only: table_t
  implicit none
  private
  public :: write_restart_file, start_from_restart

contains

  subroutine write_restart_file(path, t, y, err)
    character(len=*), intent(in) :: path
    real(dp), intent(in) :: t, y(:)
    type(error_t), intent(inout) :: err
    integer :: u, ios
    open(newunit=u, file=trim(path), status='replace', action='write', iostat=ios)
    if (ios /= 0) then
      call err%set('restart file '''//trim(path)//'''', 'cannot be written')
      return
    end if
    write(u, '(a)') '# flexmech transient restart: t, number of states, then the state (q, q_dot interleaved)'
    write(u, '(es25.17e3)') t
    write(u, '(i0)') size(y)
    write(u, '(es25.17e3)') y
    close(u)
  end subroutine write_restart_file

  !> t and y from path; the file must hold exactly size(y) states.
  subroutine read_restart_file(path, t, y, err)
    character(len=*), intent(in) :: path
    real(dp), intent(out) :: t
    real(dp), intent(inout) :: y(:)
    type(error_t), intent(inout) :: err
    integer :: u, ios, n
    character(len=256) :: line
    t = 0.0_dp
    open(newunit=u, file=trim(path), status='old', action='read', iostat=ios)
    if (ios /= 0) then
      call err%set('restart file '''//trim(path)//'''', 'not found or not readable')
      return
    end if
    read(u, '(a)', iostat=ios) line
    if (ios == 0) read(u, *, iostat=ios) t
    if (ios == 0) read(u, *, iostat=ios) n
    if (ios /= 0) then
      call err%set('restart file '''//trim(path)//'''', 'is not a flexmech restart file')
    else if (n /= size(y)) then
      call err%set('restart file '''//trim(path)//'''', 'holds '//str(n)//' states; this model has '//str(size(y)))
    else
      read(u, *, iostat=ios) y
      if (ios /= 0) call err%set('restart file '''//trim(path)//'''', 'is truncated')
    end if
    close(u)
  end subroutine read_restart_file

  !> The initial state initial = 'restart' of a transient deck: t0 and y from
  !> the file named by restart_in.  A missing or mismatched file is an input
  !> error of the deck (code 2); the output header says where the run starts.
  subroutine start_from_restart(deck_path, path, out, t0, y, err)
    character(len=*), intent(in) :: deck_path, path
    type(table_t), intent(inout) :: out
    real(dp), intent(out) :: t0
    real(dp), intent(inout) :: y(:)
    type(error_t), intent(inout) :: err
    call read_restart_file(path, t0, y, err)
    if (err%failed()) then
      err%code = 2
      call err%add_context('deck '''//deck_path//''', group &transient, restart_in')
      return
    end if
    call out%comment('initial state: restart file '//trim(path)//' at t = '//str(t0))
  end subroutine start_from_restart
end module restart_file
