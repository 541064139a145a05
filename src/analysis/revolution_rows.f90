!> The output rows of a transient run, revolution by revolution: what the
!> planar and the spatial drivers keep of their rows between output times.
!>
!> revolution_rows_t (planar transient): every row's column peaks per crank
!> revolution (revolution_peaks_t), the rows written from a time on or kept
!> until their revolution is complete (output_rows = 'last_revolution' with
!> stop_when_periodic: the last complete revolution is written at the end),
!> and the stop when a revolution's peaks repeat the previous one's.
!>
!>     rows = revolution_rows_t(n_columns=..., t_rows=..., buffered=..., stop_change=..., turning=..., theta_start=...)
!>     call rows%start()
!>     every output time: call rows%add(out, tt, row, crank_deg)
!>                        call rows%close_revolutions(out, theta)  (rows%periodic: stop)
!>     at the end: call rows%write_last_revolution(out, names); call rows%write_peaks(out, names, 'last', ...)
!>
!> revolution_defect_t (spatial): the largest change of the deflection
!> columns over one revolution, each sample against the one a revolution
!> earlier (a ring of one revolution's samples).  A different test from the
!> planar one's: sample by sample rather than peak by peak, defined only
!> when the output step divides a revolution, and reported, not a stop (the
!> two outputs print different numbers, so one cannot replace the other).
module revolution_rows
  use kinds, only: dp, pi, two_pi
  use strings, only: str
  use table_output, only: table_t
  use revolution_peaks, only: revolution_peaks_t, write_peak_lines
  implicit none
  private
  public :: revolution_rows_t, revolution_defect_t

  type :: revolution_rows_t
    type(revolution_peaks_t) :: pk                    !< the columns' peaks (time and crank angle excluded)
    integer :: n_columns = 0
    real(dp) :: t_rows = -huge(1.0_dp)                !< rows at output times from t_rows on are written
    logical :: buffered = .false.                     !< rows kept until their revolution is complete
    real(dp), allocatable :: open_rows(:, :)          !< the open revolution's rows (n_open of them)
    real(dp), allocatable :: last_rows(:, :)          !< the last complete revolution's rows
    integer :: n_open = 0
    real(dp) :: stop_change = 0.0_dp                  !< stop_when_periodic (0: never judged)
    logical :: turning = .false.                      !< the crank turns: revolutions are counted
    real(dp) :: theta_start = 0.0_dp                  !< crank angle at the start (rad)
    logical :: periodic = .false.                     !< the last closed revolution repeated the previous one
  contains
    procedure :: start => start_rows
    procedure :: add => add_row
    procedure :: close_revolutions
    procedure :: write_last_revolution
    procedure :: write_peaks
    procedure :: write_periodicity
  end type revolution_rows_t

  type :: revolution_defect_t
    integer :: per_rev = 0                            !< samples per revolution (0: no defect)
    integer, private :: first = 0                     !< first sample index of the last revolution
    real(dp), allocatable, private :: ring(:, :)      !< the previous revolution's samples, by index mod per_rev
    real(dp) :: defect = 0.0_dp, scale = 0.0_dp       !< largest change, largest value
  contains
    procedure :: init => init_defect
    procedure :: add => add_sample
    procedure :: write => write_defect
  end type revolution_defect_t

contains

  !> The column peaks and (buffered) the row stores for n_columns columns,
  !> of rows built by the keyword constructor revolution_rows_t(n_columns=...,
  !> t_rows=..., buffered=..., stop_change=..., turning=..., theta_start=...).
  subroutine start_rows(self)
    class(revolution_rows_t), intent(inout) :: self
    call self%pk%init(self%n_columns - 2)
    if (self%buffered) allocate(self%open_rows(self%n_columns, 16), self%last_rows(self%n_columns, 0))
  end subroutine start_rows

  !> The row of output time tt at crank angle crank_deg: its columns' peaks,
  !> kept for its revolution or written.
  subroutine add_row(self, out, tt, row, crank_deg)
    class(revolution_rows_t), intent(inout) :: self
    type(table_t), intent(inout) :: out
    real(dp), intent(in) :: tt, row(:), crank_deg
    call self%pk%add(row(3:), crank_deg)
    if (self%buffered) then
      if (self%n_open == size(self%open_rows, 2)) &
        self%open_rows = reshape(self%open_rows, [size(self%open_rows, 1), 2*self%n_open], pad=[0.0_dp])
      self%n_open = self%n_open + 1
      self%open_rows(:, self%n_open) = row
    end if
    if (tt < self%t_rows) return
    call out%row(row)
  end subroutine add_row

  !> Close every revolution the crank has completed at crank angle theta
  !> (its turns counted from theta_start); with stop_change > 0, periodic
  !> when the peaks of the one just closed agree with the previous one's.
  subroutine close_revolutions(self, out, theta)
    class(revolution_rows_t), intent(inout) :: self
    type(table_t), intent(inout) :: out
    real(dp), intent(in) :: theta
    real(dp) :: turns
    if (.not. self%turning) return
    turns = (theta - self%theta_start)/two_pi
    associate (pk => self%pk)
      do while (turns >= pk%n_complete + 1 - 1.0e-9_dp)
        call pk%close_revolution()
        if (self%buffered) then
          self%last_rows = self%open_rows(:, 1:self%n_open)
          self%n_open = 0
        end if
        if (self%stop_change > 0.0_dp .and. pk%change >= 0.0_dp) call out%comment('revolution '// &
          str(pk%n_complete)//': largest relative change of a column''s peak from revolution '// &
          str(pk%n_complete - 1)//': '//str(pk%change, 4))
        if (self%stop_change > 0.0_dp .and. pk%change >= 0.0_dp .and. pk%change <= self%stop_change) then
          self%periodic = .true.
          call out%comment('periodic at revolution '//str(pk%n_complete)//' (crank angle '// &
                           str(theta*180.0_dp/pi, 6)//' deg): stopped')
          return
        end if
      end do
    end associate
  end subroutine close_revolutions

  !> The kept rows of the last complete revolution, under the column names
  !> again (the names are the last '#' line before the rows).
  subroutine write_last_revolution(self, out, names)
    class(revolution_rows_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    character(len=*), intent(in) :: names(:)
    integer :: k
    if (.not. self%buffered) return
    if (size(self%last_rows, 2) == 0) return
    call out%columns(names)
    do k = 1, size(self%last_rows, 2)
      call out%row(self%last_rows(:, k))
    end do
  end subroutine write_last_revolution

  !> The summary lines of the columns' peaks (revolution_peaks' write_peak_lines):
  !> which = 'last' (the last complete revolution) or 'whole' (the whole run);
  !> columns whose names start with skip_prefix are left out (their peaks are
  !> written elsewhere: the elements' stresses).
  subroutine write_peaks(self, out, names, which, skip_prefix)
    class(revolution_rows_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    character(len=*), intent(in) :: names(:), which, skip_prefix
    integer :: i
    call write_peak_lines(self%pk, out, names(3:), '', which, self%turning, self%theta_start*180.0_dp/pi, &
                          skip=[(index(names(i), skip_prefix) == 1, i = 3, size(names))])
  end subroutine write_peaks

  !> The summary line of stop_when_periodic (none without it).
  subroutine write_periodicity(self, out)
    class(revolution_rows_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    if (.not. self%stop_change > 0.0_dp) return
    associate (pk => self%pk)
      if (self%periodic) then
        call out%summary('periodic', 'at revolution '//str(pk%n_complete)//': peaks within '// &
                         str(pk%change, 4)//' of revolution '//str(pk%n_complete - 1)//'; run stopped')
      else if (pk%change >= 0.0_dp) then
        call out%summary('periodic', 'not reached in '//str(pk%n_complete)//' revolutions: last change of the '// &
                         'peaks '//str(pk%change, 4)//' > '//str(self%stop_change))
      else
        call out%summary('periodic', 'not judged: fewer than two complete revolutions')
      end if
    end associate
  end subroutine write_periodicity

  !> n_values columns sampled per_rev times a revolution over n_samples
  !> output steps; no defect unless per_rev > 0 and two revolutions are run.
  subroutine init_defect(self, n_values, per_rev, n_samples)
    class(revolution_defect_t), intent(inout) :: self
    integer, intent(in) :: n_values, per_rev, n_samples
    self%per_rev = per_rev
    if (n_samples < 2*per_rev) self%per_rev = 0
    self%first = n_samples - self%per_rev
    allocate(self%ring(n_values, 0:max(self%per_rev, 1) - 1))
  end subroutine init_defect

  !> Sample k (output steps from the start): in the last revolution, its
  !> change from sample k - per_rev.
  subroutine add_sample(self, k, values)
    class(revolution_defect_t), intent(inout) :: self
    integer, intent(in) :: k
    real(dp), intent(in) :: values(:)
    if (self%per_rev == 0) return
    if (k >= self%first) then
      self%defect = max(self%defect, maxval(abs(values - self%ring(:, mod(k, self%per_rev)))))
      self%scale = max(self%scale, maxval(abs(values)))
    end if
    self%ring(:, mod(k, self%per_rev)) = values
  end subroutine add_sample

  !> The summary line of the defect (none where it is not defined).
  subroutine write_defect(self, out)
    class(revolution_defect_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    if (self%per_rev > 0 .and. self%scale > 0.0_dp) &
      call out%summary('periodicity defect over the last revolution', str(self%defect/self%scale, 4)// &
                       ' (largest change of a deflection column in one revolution / its largest value)')
  end subroutine write_defect
end module revolution_rows
