!> Tests of the rows a transient run keeps revolution by revolution (module
!> revolution_rows; the peaks of module revolution_peaks): the planar
!> driver's periodic stop (a revolution whose column peaks repeat the
!> previous one's stops the run; one that differs does not), the last
!> complete revolution's rows kept for output_rows = 'last_revolution', and
!> the spatial driver's periodicity defect (each sample against the one a
!> revolution earlier), all against values worked out by hand.
module test_revolution_rows_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use table_output, only: table_t
  use revolution_rows, only: revolution_rows_t, revolution_defect_t
  use assertions
  use test_text, only: itoa
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: path = 'test_revolution_rows.tmp'
  integer, parameter :: per_rev = 8              !< output rows per crank revolution
  type(table_t) :: out                           !< the suite's output table (removed at the end)

contains

  subroutine run_all()
    type(error_t) :: err
    call out%open(path, err)
    call assert_true(.not. err%failed(), 'open: '//err%text())
    call run_test('repeated_peaks_stop_the_run_changed_ones_do_not', test_periodic_stop)
    call run_test('last_complete_revolution_rows_are_kept', test_last_revolution)
    call run_test('defect_is_the_largest_change_from_a_revolution_earlier', test_defect)
    call run_test('too_short_a_run_has_no_defect', test_short_run)
    call out%discard()
  end subroutine run_all

  !> Row k (crank angle k/per_rev turns) of a column whose amplitude is amp
  !> in revolution rev: amp sin(2 pi k/per_rev + 0.3).
  function sample_row(k, amp) result(row)
    integer, intent(in) :: k
    real(dp), intent(in) :: amp
    real(dp) :: row(3)
    real(dp) :: theta
    theta = two_pi*k/per_rev
    row = [theta, theta*180.0_dp/pi, amp*sin(theta + 0.3_dp)]
  end function sample_row

  !> Feed revolutions of amplitudes amps (one revolution each) into rows,
  !> closing each at its end; periodic_after(r): rows%periodic after closing r.
  subroutine feed(rows, amps, periodic_after)
    type(revolution_rows_t), intent(inout) :: rows
    real(dp), intent(in) :: amps(:)
    logical, intent(out) :: periodic_after(size(amps))
    integer :: r, j, k
    real(dp) :: row(3)
    do r = 1, size(amps)
      do j = 1, per_rev
        k = (r - 1)*per_rev + j
        row = sample_row(k, amps(r))
        call rows%add(out, row(1), row, row(2))
        call rows%close_revolutions(out, row(1))
      end do
      periodic_after(r) = rows%periodic
    end do
  end subroutine feed

  !> Amplitudes 2, 1, 1 (stop_when_periodic = 1e-6): revolution 2's peak
  !> changed by (2 - 1)/2 = 0.5 from revolution 1's, not periodic;
  !> revolution 3's equals revolution 2's, periodic.  Amplitudes 2, 1, 1.001:
  !> change 1e-3 > 1e-6, never periodic.
  subroutine test_periodic_stop()
    type(revolution_rows_t) :: rows
    logical :: periodic(3)
    integer :: k
    rows = revolution_rows_t(n_columns=3, stop_change=1.0e-6_dp, turning=.true., theta_start=0.0_dp)
    call rows%start()
    call feed(rows, [2.0_dp, 1.0_dp, 1.0_dp], periodic)
    call assert_true(.not. periodic(1) .and. .not. periodic(2), 'not periodic after revolutions 1 and 2')
    call assert_true(periodic(3), 'periodic after revolution 3 (its peak repeats revolution 2''s)')
    call assert_equal(rows%pk%n_complete, 3, 'three revolutions closed')
    call assert_close(rows%pk%whole(1), 2.0_dp*maxval(abs(sin(two_pi*[(real(k, dp), k = 1, per_rev)]/ &
                      per_rev + 0.3_dp))), 1.0e-14_dp, 'whole-run peak: revolution 1''s')
    rows = revolution_rows_t(n_columns=3, stop_change=1.0e-6_dp, turning=.true., theta_start=0.0_dp)
    call rows%start()
    call feed(rows, [2.0_dp, 1.0_dp, 1.001_dp], periodic)
    call assert_true(.not. any(periodic), 'a 1e-3 change of the peak is not periodic at 1e-6')
    call assert_rel_close(rows%pk%change, 1.0e-3_dp/1.001_dp, 1.0e-9_dp, 'change = |1.001 - 1|/1.001')
  end subroutine test_periodic_stop

  !> Buffered rows (output_rows = 'last_revolution'): after three
  !> revolutions the rows kept are revolution 3's, per_rev of them, in order.
  subroutine test_last_revolution()
    type(revolution_rows_t) :: rows
    logical :: periodic(3)
    integer :: j
    rows = revolution_rows_t(n_columns=3, t_rows=huge(1.0_dp), buffered=.true., turning=.true., theta_start=0.0_dp)
    call rows%start()
    call feed(rows, [3.0_dp, 2.0_dp, 1.0_dp], periodic)
    call assert_equal(size(rows%last_rows, 2), per_rev, 'one revolution of rows kept')
    do j = 1, per_rev
      call assert_all_close(rows%last_rows(:, j), sample_row(2*per_rev + j, 1.0_dp), 0.0_dp, 0.0_dp, &
                            'kept row '//itoa(j)//' is revolution 3''s')
    end do
    call assert_equal(rows%n_open, 0, 'no row of an open revolution left')
  end subroutine test_last_revolution

  !> Three revolutions of samples v_k = (1 + 0.1 k) sin(2 pi k/per_rev + 0.3),
  !> k = 0..3 per_rev: the defect over the last revolution is max |v_k -
  !> v_(k - per_rev)| = 0.1 per_rev max |sin| over its samples, its scale the
  !> largest |v_k| there.
  subroutine test_defect()
    type(revolution_defect_t) :: d
    integer :: k, n
    real(dp) :: v(0:3*per_rev), expected_defect, expected_scale
    n = 3*per_rev
    do k = 0, n
      v(k) = (1.0_dp + 0.1_dp*k)*sin(two_pi*k/per_rev + 0.3_dp)
    end do
    call d%init(1, per_rev, n)
    do k = 0, n
      call d%add(k, [v(k)])
    end do
    expected_defect = maxval(abs(v(n - per_rev:n) - v(n - 2*per_rev:n - per_rev)))
    expected_scale = maxval(abs(v(n - per_rev:n)))
    call assert_rel_close(d%defect, expected_defect, 1.0e-14_dp, 'defect: largest change from a revolution earlier')
    call assert_rel_close(d%scale, expected_scale, 1.0e-14_dp, 'scale: largest |value| of the last revolution')
    call assert_rel_close(d%defect, 0.1_dp*per_rev*maxval(abs(sin(two_pi*[(real(k, dp), k = 0, per_rev)]/ &
                          per_rev + 0.3_dp))), 1.0e-12_dp, 'defect = 0.1 per_rev max |sin|')
  end subroutine test_defect

  !> Fewer than two revolutions of samples: nothing to compare, no defect.
  subroutine test_short_run()
    type(revolution_defect_t) :: d
    integer :: k
    call d%init(1, per_rev, 2*per_rev - 1)
    do k = 0, 2*per_rev - 1
      call d%add(k, [real(k, dp)])
    end do
    call assert_equal(d%per_rev, 0, 'no defect defined')
    call assert_close(d%defect, 0.0_dp, 0.0_dp, 'no defect computed')
  end subroutine test_short_run

end module test_revolution_rows_suite

program test_revolution_rows
  use test_revolution_rows_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_revolution_rows')
end program test_revolution_rows
