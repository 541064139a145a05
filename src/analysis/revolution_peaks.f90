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
!> crank angle per revolution and over the run (the transient and spatial
!> drivers) and writes them as summary lines.
!>
!> The summary lines of both (write_peak_lines) lead with the last complete
!> revolution, 'last revolution peak |X| = value at A deg of revolution N'
!> with A in [0, 360), and then the whole run, 'whole run peak |X|, start-up
!> included = ...': the first turns from the rigid-body start carry a
!> start-up transient the steady running does not.
module revolution_peaks
  use kinds, only: dp
  use strings, only: str
  use table_output, only: table_t
  implicit none
  private
  public :: revolution_peaks_t, element_peaks_t, write_peak_lines

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
    type(revolution_peaks_t) :: pk                    !< largest |stress| of each element, its crank angle
    character(len=48), allocatable :: label(:)        !< 'crank (element 1)': the link's deck name
    logical :: turning = .false.                      !< the crank turns: revolutions are closed
    real(dp) :: start_deg = 0.0_dp                    !< crank angle at the start (deg)
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

  !> n_elements elements named by labels; turning: the crank turns from
  !> crank angle start_deg (revolutions are closed as note passes them).
  subroutine init_element_peaks(self, labels, turning, start_deg)
    class(element_peaks_t), intent(inout) :: self
    character(len=*), intent(in) :: labels(:)
    logical, intent(in) :: turning
    real(dp), intent(in) :: start_deg
    call self%pk%init(size(labels))
    allocate(self%label(size(labels)))
    self%label = labels
    self%turning = turning
    self%start_deg = start_deg
  end subroutine init_element_peaks

  !> The elements' largest |stress| at crank angle deg (pass a contiguous
  !> array: a component of an array of stress reports made the debug build
  !> print 'array temporary was created'); a revolution the crank completes
  !> there is closed (the row at its end belongs to it).
  subroutine note_element_peaks(self, stress, deg)
    class(element_peaks_t), intent(inout) :: self
    real(dp), intent(in) :: stress(:), deg
    call self%pk%add(stress, deg)
    if (.not. self%turning) return
    do while ((deg - self%start_deg)/360.0_dp >= self%pk%n_complete + 1 - 1.0e-9_dp)
      call self%pk%close_revolution()
    end do
  end subroutine note_element_peaks

  !> The summary lines of the elements' peak |stress| (write_peak_lines).
  subroutine write_element_peaks(self, out, which)
    class(element_peaks_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    character(len=*), intent(in) :: which
    character(len=64) :: labels(size(self%label))
    integer :: i
    do i = 1, size(labels)
      labels(i) = 'stress| '//trim(self%label(i))
    end do
    call write_peak_lines(self%pk, out, labels, ' psi', which, self%turning, self%start_deg)
  end subroutine write_element_peaks

  !> Summary lines of the peaks in pk of the quantities named by labels
  !> (the text after 'peak |': 'B_U|' or 'stress| crank (element 1)'; a
  !> label without '|' is closed by one): which = 'last', the last complete
  !> revolution's, angles in [0, 360) (none before a revolution is complete,
  !> or when the crank does not turn); which = 'whole', the whole run's,
  !> labelled as including the start-up when revolutions were completed.
  !> skip: quantities left out (written elsewhere).
  subroutine write_peak_lines(pk, out, labels, unit, which, turning, start_deg, skip)
    type(revolution_peaks_t), intent(in) :: pk
    type(table_t), intent(inout) :: out
    character(len=*), intent(in) :: labels(:), unit, which
    logical, intent(in) :: turning
    real(dp), intent(in) :: start_deg
    logical, intent(in), optional :: skip(:)
    character(len=:), allocatable :: name
    integer :: i, rev
    do i = 1, size(labels)
      if (present(skip)) then
        if (skip(i)) cycle
      end if
      name = trim(labels(i))
      if (index(name, '|') == 0) name = name//'|'
      if (.not. turning) then
        if (which == 'whole') call out%summary('whole run peak |'//name, str(pk%whole(i), 8)//unit)
      else if (which == 'last') then
        if (pk%n_complete > 0) call out%summary('last revolution peak |'//name, str(pk%last(i), 8)//unit// &
          ' at '//str(modulo(pk%last_deg(i), 360.0_dp), 6)//' deg of revolution '//str(pk%n_complete))
      else
        rev = max(1, ceiling((pk%whole_deg(i) - start_deg)/360.0_dp - 1.0e-9_dp))
        if (pk%n_complete > 0) then
          call out%summary('whole run peak |'//name//', start-up included', str(pk%whole(i), 8)//unit//' at '// &
                           str(modulo(pk%whole_deg(i), 360.0_dp), 6)//' deg of revolution '//str(rev))
        else
          call out%summary('whole run peak |'//name, str(pk%whole(i), 8)//unit//' at '// &
                           str(modulo(pk%whole_deg(i), 360.0_dp), 6)//' deg of revolution '//str(rev)// &
                           ' (no revolution complete)')
        end if
      end if
    end do
  end subroutine write_peak_lines

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
