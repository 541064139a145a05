!> Peaks of a run's output quantities (largest |value| and the crank angle
!> where it occurred) over the whole run and per crank revolution, and the
!> test of periodicity: the largest relative change of any quantity's peak
!> from one complete revolution to the next.
!>
!>     call pk%init(n)
!>     every output time: call pk%add(values, crank_deg)
!>     at the end of a revolution: call pk%close_revolution()  (pk%change: the
!>       largest relative change from the previous one, -1 for the first)
!>     pk%whole, pk%whole_deg: whole run; pk%last, pk%last_deg: the last
!>       complete revolution pk%n_complete (0: none yet)
!>
!> element_peaks_t keeps the largest |stress| of every element and its
!> crank angle (the transient and spatial drivers) and writes them as
!> summary lines.
module revolution_peaks
  use kinds, only: dp
  use strings, only: str
  use table_output, only: table_t
  implicit none
  private
  public :: revolution_peaks_t, element_peaks_t

  type :: revolution_peaks_t
    real(dp), allocatable :: whole(:), whole_deg(:)   !< whole run
    real(dp), allocatable :: cur(:), cur_deg(:)       !< the open revolution
    real(dp), allocatable :: last(:), last_deg(:)     !< the last complete revolution
    integer :: n_complete = 0                         !< complete revolutions so far
    real(dp) :: change = -1.0_dp                      !< largest relative change of a peak, last two revolutions
  contains
    procedure :: init
    procedure :: add
    procedure :: close_revolution
  end type revolution_peaks_t

  type :: element_peaks_t
    real(dp), allocatable :: peak(:), deg(:)          !< largest |stress| of each element, its crank angle
  contains
    procedure :: init => init_element_peaks
    procedure :: note => note_element_peaks
    procedure :: write => write_element_peaks
  end type element_peaks_t

contains

  subroutine init(self, n)
    class(revolution_peaks_t), intent(inout) :: self
    integer, intent(in) :: n
    allocate(self%whole(n), self%whole_deg(n), self%cur(n), self%cur_deg(n), self%last(n), self%last_deg(n))
    self%whole = 0.0_dp
    self%whole_deg = 0.0_dp
    self%cur = 0.0_dp
    self%cur_deg = 0.0_dp
    self%last = 0.0_dp
    self%last_deg = 0.0_dp
  end subroutine init

  !> One output time: values (signed) at crank angle deg.
  subroutine add(self, values, deg)
    class(revolution_peaks_t), intent(inout) :: self
    real(dp), intent(in) :: values(:), deg
    call note_peaks(values, deg, self%whole, self%whole_deg)
    call note_peaks(values, deg, self%cur, self%cur_deg)
  end subroutine add

  !> peak = the largest |value| so far, peak_deg the angle where it occurred
  !> (elemental: one call for every quantity).
  elemental subroutine note_peaks(value, deg, peak, peak_deg)
    real(dp), intent(in) :: value, deg
    real(dp), intent(inout) :: peak, peak_deg
    if (abs(value) > peak) then
      peak = abs(value)
      peak_deg = deg
    end if
  end subroutine note_peaks

  subroutine init_element_peaks(self, n_elements)
    class(element_peaks_t), intent(inout) :: self
    integer, intent(in) :: n_elements
    allocate(self%peak(n_elements), self%deg(n_elements))
    self%peak = 0.0_dp
    self%deg = 0.0_dp
  end subroutine init_element_peaks

  !> The elements' largest |stress| at crank angle deg (pass a contiguous
  !> array: a component of an array of stress reports made the debug build
  !> print 'array temporary was created').
  subroutine note_element_peaks(self, stress, deg)
    class(element_peaks_t), intent(inout) :: self
    real(dp), intent(in) :: stress(:), deg
    call note_peaks(stress, deg, self%peak, self%deg)
  end subroutine note_element_peaks

  !> One summary line per element: its peak |stress| and where it occurred.
  subroutine write_element_peaks(self, out)
    class(element_peaks_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    integer :: e
    do e = 1, size(self%peak)
      call out%summary('element '//str(e)//' peak |stress|', str(self%peak(e), 8)//' psi at crank angle '// &
                       str(self%deg(e), 6)//' deg')
    end do
  end subroutine write_element_peaks

  !> The open revolution is complete: compare it with the previous complete
  !> one (change = max over quantities of |p - p_prev| / max(p, p_prev);
  !> quantities zero in both are equal) and open the next.
  subroutine close_revolution(self)
    class(revolution_peaks_t), intent(inout) :: self
    integer :: i
    real(dp) :: big
    if (self%n_complete > 0) then
      self%change = 0.0_dp
      do i = 1, size(self%cur)
        big = max(self%cur(i), self%last(i))
        if (big > 0.0_dp) self%change = max(self%change, abs(self%cur(i) - self%last(i))/big)
      end do
    end if
    self%last = self%cur
    self%last_deg = self%cur_deg
    self%n_complete = self%n_complete + 1
    self%cur = 0.0_dp
    self%cur_deg = 0.0_dp
  end subroutine close_revolution
end module revolution_peaks
