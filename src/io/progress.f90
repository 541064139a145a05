!> A one-line progress report on stderr for long runs, drawn only when stderr
!> is a terminal, so batch logs and tests stay clean:
!>
!>     transient  42%  revolution 3, crank angle 900 deg, 81234 steps  ETA 3 s
!>     sweep points done  7/20  35%  ETA 1 min
!>
!> The ETA is the elapsed wall time scaled by the fraction still to do; it is
!> shown once a run has taken a second, and redrawn at most ten times a second.
module progress
  use, intrinsic :: iso_c_binding, only: c_int
  use c_library, only: c_isatty
  use, intrinsic :: iso_fortran_env, only: error_unit, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  implicit none
  private
  public :: progress_t

  !> Its state is set by start and kept by update and finish alone.
  type :: progress_t
    private
    logical :: active = .false.
    logical :: counts = .false.          !< show 'k/n' (t0 = 0, t1 = n)
    real(dp) :: t0 = 0.0_dp, t1 = 1.0_dp
    integer :: last_percent = -1
    integer(int64) :: clock0 = 0, last_clock = 0, rate = 1
    character(len=:), allocatable :: label
  contains
    procedure :: start
    procedure :: update
    procedure :: finish
    procedure :: shown
  end type progress_t

contains

  !> Whether the bar is drawn (a terminal on stderr): callers skip building
  !> detail text nobody sees.
  pure logical function shown(self)
    class(progress_t), intent(in) :: self
    shown = self%active
  end function shown

  subroutine start(self, label, t0, t1, counts)
    class(progress_t), intent(inout) :: self
    character(len=*), intent(in) :: label
    real(dp), intent(in) :: t0, t1
    logical, intent(in), optional :: counts
    self%label = label
    self%t0 = t0
    self%t1 = t1
    self%last_percent = -1
    self%counts = .false.
    if (present(counts)) self%counts = counts
    self%active = .false.
    if (.not. (ieee_is_finite(t0) .and. ieee_is_finite(t1))) return
    self%active = c_isatty(2_c_int) == 1 .and. t1 > t0
    call system_clock(self%clock0, self%rate)
    self%last_clock = self%clock0
  end subroutine start

  !> Progress at t (t0..t1); detail: optional text (revolution, steps ...).
  subroutine update(self, t, detail)
    class(progress_t), intent(inout) :: self
    real(dp), intent(in) :: t
    character(len=*), intent(in), optional :: detail
    integer :: percent
    integer(int64) :: now
    real(dp) :: frac, elapsed
    character(len=:), allocatable :: line
    character(len=32) :: buf
    if (.not. self%active) return
    ! a NaN or Inf time (a failing integration) draws nothing rather than trapping in int()
    if (.not. ieee_is_finite(t)) return
    frac = (t - self%t0)/(self%t1 - self%t0)
    if (.not. ieee_is_finite(frac)) return
    frac = max(0.0_dp, min(1.0_dp, frac))
    percent = int(100.0_dp*frac)
    call system_clock(now)
    if (percent == self%last_percent .and. real(now - self%last_clock, dp) < 0.1_dp*real(self%rate, dp)) return
    self%last_percent = percent
    self%last_clock = now
    elapsed = real(now - self%clock0, dp)/real(self%rate, dp)
    line = self%label
    if (self%counts) then
      write(buf, '(i0,a,i0)') nint(t - self%t0), '/', nint(self%t1 - self%t0)
      line = line//'  '//trim(buf)
    end if
    write(buf, '(i3,a)') percent, '%'
    line = line//' '//trim(buf)
    if (present(detail)) line = line//'  '//detail
    if (elapsed >= 1.0_dp .and. frac > 0.0_dp .and. frac < 1.0_dp) &
      line = line//'  ETA '//eta_text(elapsed*(1.0_dp - frac)/frac)
    write(error_unit, '(a,a,a)', advance='no') achar(13), line, achar(27)//'[K'
    flush(error_unit)
  end subroutine update

  subroutine finish(self)
    class(progress_t), intent(inout) :: self
    if (.not. self%active) return
    write(error_unit, '(a)') ''
    self%active = .false.
  end subroutine finish

  !> '42 s', '3 min', '2.5 h'.
  pure function eta_text(seconds) result(s)
    real(dp), intent(in) :: seconds
    character(len=:), allocatable :: s
    character(len=16) :: buf
    if (seconds < 90.0_dp) then
      write(buf, '(i0,a)') nint(seconds), ' s'
    else if (seconds < 5400.0_dp) then
      write(buf, '(i0,a)') nint(seconds/60.0_dp), ' min'
    else
      write(buf, '(f0.1,a)') seconds/3600.0_dp, ' h'
    end if
    s = trim(buf)
  end function eta_text
end module progress
