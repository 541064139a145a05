!> A one-line progress report on stderr for long runs ("label  42%"), drawn
!> only when stderr is a terminal, so batch logs and tests stay clean.
module progress
  use, intrinsic :: iso_c_binding, only: c_int
  use, intrinsic :: iso_fortran_env, only: error_unit
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  implicit none
  private
  public :: progress_t

  type :: progress_t
    logical :: active = .false.
    real(dp) :: t0 = 0.0_dp, t1 = 1.0_dp
    integer :: last_percent = -1
    character(len=:), allocatable :: label
  contains
    procedure :: start
    procedure :: update
    procedure :: finish
  end type progress_t

  interface
    integer(c_int) function c_isatty(fd) bind(c, name='isatty')
      import :: c_int
      integer(c_int), value :: fd
    end function c_isatty
  end interface

contains

  subroutine start(self, label, t0, t1)
    class(progress_t), intent(inout) :: self
    character(len=*), intent(in) :: label
    real(dp), intent(in) :: t0, t1
    self%label = label
    self%t0 = t0
    self%t1 = t1
    self%last_percent = -1
    self%active = .false.
    if (.not. (ieee_is_finite(t0) .and. ieee_is_finite(t1))) return
    self%active = c_isatty(2_c_int) == 1 .and. t1 > t0
  end subroutine start

  subroutine update(self, t)
    class(progress_t), intent(inout) :: self
    real(dp), intent(in) :: t
    integer :: percent
    real(dp) :: fraction
    if (.not. self%active) return
    ! a NaN or Inf time (a failing integration) draws nothing rather than trapping in int()
    if (.not. ieee_is_finite(t)) return
    fraction = (t - self%t0)/(self%t1 - self%t0)
    if (.not. ieee_is_finite(fraction)) return
    percent = int(100.0_dp*max(0.0_dp, min(1.0_dp, fraction)))
    percent = max(0, min(100, percent))
    if (percent == self%last_percent) return
    self%last_percent = percent
    write(error_unit, '(a,a,1x,i3,a)', advance='no') achar(13), self%label, percent, '%'
    flush(error_unit)
  end subroutine update

  subroutine finish(self)
    class(progress_t), intent(inout) :: self
    if (.not. self%active) return
    write(error_unit, '(a)') ''
    self%active = .false.
  end subroutine finish
end module progress
