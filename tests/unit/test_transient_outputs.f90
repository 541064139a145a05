!> The transient analysis' optional outputs from a deck: stop_when_periodic,
!> the peaks of the last revolution and of the whole run, and the stress
!> columns' consistency with the outer-fibre stress.  The §8.1 four-bar at
!> 150 rad/s, damped (beta = 1e-5 s), one element per link, bdf.
module test_transient_outputs_suite
  use kinds, only: dp
  use error_status, only: error_t
  use transient_analysis, only: run_transient
  use deck_runner, only: scratch_path, run_deck, has_line, count_rows, line_length, summary_value
  use assertions
  use test_text, only: itoa
  implicit none
  private
  public :: run_all

  character(len=:), allocatable :: scratch

  character(len=*), parameter :: mechanism = &
    "&run|  analysis = 'transient'|/|&mechanism|  n_joints = 4|  joint_name = 'A', 'B', 'C', 'D'|"// &
    "  joint_type = 'clamp', 'pin', 'pin', 'ground_pin'|  joint_x(1) = 0.0, joint_y(1) = 0.0|"// &
    "  joint_x(4) = 10.0, joint_y(4) = 0.0|  n_links = 3|  link_name = 'crank', 'coupler', 'rocker'|"// &
    "  link_joint1 = 1, 2, 4|  link_joint2 = 2, 3, 3|  link_length = 5.0, 11.0, 10.5|  link_n_elements = 3*1|"// &
    "  driver_link = 1|  omega = 150.0|/|"
  character(len=*), parameter :: transient = &
    "&transient|  method = 'bdf', rtol = 1.0e-6, atol = 1.0e-10, output_step_deg = 2.0, damping_beta = 1.0e-5|"

contains

  subroutine run_all()
    scratch = scratch_path('test_transient_outputs')
    call run_test('stop_when_periodic_stops_and_its_last_revolution_is_the_periodic_state', test_periodic_stop)
  end subroutine run_all

  !> With stop_when_periodic = 1e-3 the run stops before its 12 revolutions,
  !> with one row per 2 deg up to the end of the revolution it names.  The
  !> summary's last-revolution peak of each stress column is the largest
  !> |value| of that revolution's rows (to the 8 digits printed) and the
  !> whole-run peak is at least it.  Against a run of all 12 revolutions
  !> (the periodic state: the per-revolution peaks then change by < 1e-5),
  !> the last-revolution peaks agree within 2e-3 (the stop tolerance 1e-3
  !> with the remaining decay; measured 7e-5).  Row by row, the outer-fibre
  !> stress lies between max(|axial|, |bending|) and |axial| + |bending| of
  !> the element's peaks (axial +- bending are the outer-fibre stresses).
  subroutine test_periodic_stop()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:), full(:)
    real(dp), allocatable :: rows(:, :), rows_full(:, :)
    character(len=32), allocatable :: names(:)
    integer :: r, e, i, k, c_max, c_b, c_a, stop_rev
    character(len=*), parameter :: link(3) = [character(len=7) :: 'crank', 'coupler', 'rocker']
    real(dp) :: first, peak_rows, peak_summary, whole_summary, peak_full, smax, sa, sb
    call run_deck(run_transient, scratch, mechanism//transient//"  revolutions = 12, stop_when_periodic = 1.0e-3, "// &
                  "stress_columns = 'all', reactions = T, link_points = T|/|", err, lines)
    call assert_true(.not. err%failed(), 'stopping run: '//err%text())
    if (err%failed()) return
    call assert_true(has_line(lines, '# summary: periodic = at revolution'), 'the summary names the revolution')
    stop_rev = revolution_of(lines)
    call assert_true(stop_rev >= 3 .and. stop_rev < 12, 'stopped at revolution '//itoa(stop_rev)//' of 12')
    call assert_equal(count_rows(lines), 180*stop_rev + 1, 'rows up to the end of that revolution')
    call run_deck(run_transient, scratch, mechanism//transient//"  revolutions = 12|/|", err, full)
    call assert_true(.not. err%failed(), 'full run: '//err%text())
    if (err%failed()) return
    call table(full, names, rows_full)
    call table(lines, names, rows)      ! (the same columns: names of the stopped run)
    do e = 1, 3
      c_max = column(names, 'sigma_max_e'//itoa(e))
      c_b = column(names, 'sigma_b_e'//itoa(e))
      c_a = column(names, 'sigma_a_e'//itoa(e))
      first = 360.0_dp*(stop_rev - 1)
      peak_rows = maxval(abs(rows(c_max, :)), mask=rows(2, :) > first + 1.0_dp)
      peak_summary = summary_value(lines, '# summary: last revolution peak |stress| '//trim(link(e))//' (element '// &
                                   itoa(e)//') = ')
      whole_summary = summary_value(lines, '# summary: whole run peak |stress| '//trim(link(e))//' (element '// &
                                    itoa(e)//'), start-up included = ')
      call assert_true(summary_value(lines, '# summary: last revolution peak |'//trim(link(e))//'_w_end| = ') < &
                       huge(1.0_dp), 'a column''s last-revolution peak line, link '//trim(link(e)))
      call assert_true(summary_value(lines, '# summary: whole run peak |'//trim(link(e))//'_w_end|, start-up '// &
                       'included = ') < huge(1.0_dp), 'a column''s whole-run peak line, link '//trim(link(e)))
      call assert_true(.not. has_line(lines, '# summary: last revolution peak |sigma_max_e'), &
                       'the stress columns'' peaks are the elements'' lines, once')
      call assert_rel_close(peak_summary, peak_rows, 1.0e-7_dp, 'last-revolution peak = largest row, element '//itoa(e))
      call assert_true(whole_summary >= peak_summary, 'whole-run peak >= last revolution''s, element '//itoa(e))
      peak_full = maxval(abs(rows_full(c_max, :)), mask=rows_full(2, :) > 360.0_dp*11 + 1.0_dp)
      write(*, '(4x,a,i0,a,es12.5,a,es12.5,a,es9.2)') 'element ', e, ': peak in the stop revolution ', peak_summary, &
        ', revolution 12 ', peak_full, ', relative difference ', abs(peak_summary - peak_full)/peak_full
      call assert_rel_close(peak_summary, peak_full, 2.0e-3_dp, 'stop revolution vs revolution 12, element '//itoa(e))
      do i = 1, size(rows, 2)
        smax = rows(c_max, i)
        sa = abs(rows(c_a, i))
        sb = abs(rows(c_b, i))
        if (smax < max(sa, sb)*(1.0_dp - 1.0e-12_dp) .or. smax > (sa + sb)*(1.0_dp + 1.0e-12_dp) + 1.0e-9_dp) then
          call assert_true(.false., 'max(|axial|, |bending|) <= outer-fibre <= |axial| + |bending| at row '// &
                           itoa(i)//', element '//itoa(e))
          exit
        end if
      end do
    end do
    r = count_rows(full)
    call assert_equal(r, 180*12 + 1, 'the full run: 12 revolutions of rows')
    k = size(names)
    call assert_equal(k, 45, 'columns: 15 + 12 section + 9 link points + 4 pin + 5 ground')
  end subroutine test_periodic_stop

  integer function revolution_of(lines) result(r)
    character(len=*), intent(in) :: lines(:)
    integer :: i, k, ios
    character(len=*), parameter :: key = '# summary: periodic = at revolution '
    r = -1
    do i = 1, size(lines)
      if (index(lines(i), key) /= 1) cycle
      k = len(key) + index(lines(i)(len(key) + 1:), ':')
      read(lines(i)(len(key) + 1:k - 1), *, iostat=ios) r
      if (ios /= 0) r = -1
      return
    end do
  end function revolution_of

  !> Column names (the last '#' line before the first row) and the rows.
  subroutine table(lines, names, rows)
    character(len=*), intent(in) :: lines(:)
    character(len=32), allocatable, intent(out) :: names(:)
    real(dp), allocatable, intent(out) :: rows(:, :)
    integer :: i, first, n, k
    character(len=32) :: word
    first = 0
    do i = 1, size(lines)
      if (lines(i)(1:1) /= '#' .and. len_trim(lines(i)) > 0) then
        first = i
        exit
      end if
    end do
    allocate(names(0))
    associate (h => lines(first - 1))
      k = 2
      do while (k <= len_trim(h))
        if (h(k:k) == ' ') then
          k = k + 1
          cycle
        end if
        i = k
        do while (k <= len_trim(h))
          if (h(k:k) == ' ') exit
          k = k + 1
        end do
        word = h(i:k - 1)
        names = [character(len=32) :: names, word]
      end do
    end associate
    n = count_rows(lines)
    allocate(rows(size(names), n))
    k = 0
    do i = first, size(lines)
      if (lines(i)(1:1) == '#' .or. len_trim(lines(i)) == 0) cycle
      k = k + 1
      read(lines(i), *) rows(:, k)
    end do
  end subroutine table

  integer function column(names, name) result(c)
    character(len=*), intent(in) :: names(:), name
    do c = 1, size(names)
      if (names(c) == name) return
    end do
    c = 0
  end function column
end module test_transient_outputs_suite

program test_transient_outputs
  use test_transient_outputs_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_outputs')
end program test_transient_outputs
