!> Joint clearance in whole transient runs (module clearance_run through
!> run_transient): Tennant's four-bar at 150 rad/s (the damped deck,
!> inputs/fourbar_150_damped.nml) with clearance at the coupler-rocker pin C.
!>  - all clearances zero: the rows of the pinned run, bit for bit;
!>  - c -> 0 with a stiff contact: the pinned run's peak stresses (0.5 %);
!>  - c = 0.005 in: the joint force and the rocker stress grow;
!>  - very stiff contact (1e14 lb/in^1.5, linearised 1e4 times the links'
!>    axial stiffness): BDF completes; an Adams run is told it is stiff;
!>  - zero restitution (Lankarani-Nikravesh) and e = 0.01 (calibrated) complete.
module test_clearance_run_suite
  use kinds, only: dp
  use error_status, only: error_t
  use transient_analysis, only: run_transient
  use deck_runner, only: scratch_path, run_deck, has_line, summary_value, count_rows, line_length
  use assertions
  use test_text, only: rtoa
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: mechanism_group = &
    "&mechanism|n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|joint_type = 'clamp', 'pin', 'pin', 'ground_pin'|"// &
    "joint_x(1) = 0.0, joint_y(1) = 0.0|joint_x(4) = 10.0, joint_y(4) = 0.0|n_links = 3|"// &
    "link_name = 'crank', 'coupler', 'rocker'|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|"// &
    "link_length = 5.0, 11.0, 10.5|driver_link = 1|omega = 150.0|/|"

contains

  subroutine run_all()
    call run_test('zero_clearance_rows_are_the_pinned_rows_bit_for_bit', test_zero_is_pinned)
    call run_test('clearance_to_zero_gives_pinned_peak_stresses_within_half_percent', test_small_clearance)
    call run_test('three_clearance_joints_to_zero_give_pinned_peaks_within_1_percent', test_three_joints)
    call run_test('clearance_0p005_raises_joint_force_and_rocker_stress', test_clearance_growth)
    call run_test('very_stiff_contact_bdf_completes_adams_is_told', test_stiff_contact)
    call run_test('zero_restitution_and_calibrated_0p01_complete', test_low_restitution)
  end subroutine run_all

  function deck(revolutions, method, rtol, clearance_group) result(text)
    character(len=*), intent(in) :: revolutions, method, rtol, clearance_group
    character(len=:), allocatable :: text
    text = "&run|analysis = 'transient'|/|"//mechanism_group//"&transient|method = '"//method//"'|rtol = "//rtol// &
           "|atol = 1.0e-11|revolutions = "//revolutions//"|output_step_deg = 2.0|damping_beta = 1.0e-5|/|"// &
           clearance_group
  end function deck

  function clearance(c, k, e, law) result(text)
    character(len=*), intent(in) :: c, k, e
    character(len=*), intent(in), optional :: law
    character(len=:), allocatable :: text
    text = "&clearance|joint_clearance(3) = "//c//"|joint_stiffness(3) = "//k//"|joint_restitution(3) = "//e//"|"
    if (present(law)) text = text//"law = '"//law//"'|"
    text = text//"/"
  end function clearance

  subroutine peaks(lines, p)
    character(len=*), intent(in) :: lines(:)
    real(dp), intent(out) :: p(3)
    p(1) = summary_value(lines, '# summary: whole run peak |stress| crank (element 1), start-up included =')
    p(2) = summary_value(lines, '# summary: whole run peak |stress| coupler (element 2), start-up included =')
    p(3) = summary_value(lines, '# summary: whole run peak |stress| rocker (element 3), start-up included =')
  end subroutine peaks

  !> One revolution (bdf, rtol 1e-7) pinned and with the &clearance group
  !> `group`: the clearance run's output and both runs' peak stresses.
  subroutine pinned_and_clear(stem, group, b, p0, p1)
    character(len=*), intent(in) :: stem, group
    character(len=line_length), allocatable, intent(out) :: b(:)
    real(dp), intent(out) :: p0(3), p1(3)
    character(len=line_length), allocatable :: a(:)
    type(error_t) :: err
    call run_deck(run_transient, scratch_path(stem//'_a'), deck('1', 'bdf', '1.0e-7', ''), err, a)
    call assert_true(.not. err%failed(), 'pinned run: '//err%text())
    call run_deck(run_transient, scratch_path(stem//'_b'), deck('1', 'bdf', '1.0e-7', group), err, b)
    call assert_true(.not. err%failed(), 'clearance run: '//err%text())
    call peaks(a, p0)
    call peaks(b, p1)
  end subroutine pinned_and_clear

  !> &clearance given with every clearance zero: the model is today's (same
  !> unknowns, same arithmetic), so the rows are identical as text.
  subroutine test_zero_is_pinned()
    character(len=line_length), allocatable :: a(:), b(:)
    type(error_t) :: err
    integer :: i, j, n
    call run_deck(run_transient, scratch_path('cl_zero_a'), deck('0.1', 'bdf', '1.0e-7', ''), err, a)
    call assert_true(.not. err%failed(), err%text())
    call run_deck(run_transient, scratch_path('cl_zero_b'), deck('0.1', 'bdf', '1.0e-7', &
                  clearance('0.0', '3.0e7', '0.9')), err, b)
    call assert_true(.not. err%failed(), err%text())
    call assert_equal(count_rows(a), count_rows(b), 'same rows')
    call assert_true(count_rows(a) > 10, 'rows written')
    n = 0
    j = 0
    do i = 1, size(a)
      if (a(i)(1:1) == '#') cycle
      do
        j = j + 1
        if (b(j)(1:1) /= '#') exit
      end do
      if (a(i) /= b(j)) n = n + 1
    end do
    call assert_equal(n, 0, 'rows differing')
    call assert_true(.not. has_line(b, 'clearance_impacts'), 'no clearance footer when off')
  end subroutine test_zero_is_pinned

  !> c = 1e-5 in with K = 1e10 lb/in^1.5 (penetration ~ (950/1e10)^(2/3) =
  !> 2e-6 in at the peak force): one revolution from the rigid state, peak
  !> stresses of all three links within 0.5 % of the pinned run (measured
  !> 0.16 %; with K = 1e9 the rocker is 0.45 % off: the contact's compliance,
  !> not only c, must vanish).
  subroutine test_small_clearance()
    character(len=line_length), allocatable :: b(:)
    real(dp) :: p0(3), p1(3)
    call pinned_and_clear('cl_small', clearance('1.0e-5', '1.0e10', '0.9'), b, p0, p1)
    call assert_all_close(p1, p0, 5.0e-3_dp, 0.0_dp, 'peak stresses, c = 1e-5 in vs pinned')
    call assert_true(summary_value(b, '# cost: clearance_separations =') < huge(1.0_dp), 'counts in the footer')
  end subroutine test_small_clearance

  !> Clearance 1e-5 in at B, C and the ground pin D (K = 1e10): three splits,
  !> each shifting the unknowns of the ones before; a force on a wrong pair
  !> would move the peaks by far more than the 1 % allowed (measured 0.47 %:
  !> three compliant joints in series add up).
  subroutine test_three_joints()
    character(len=line_length), allocatable :: b(:)
    real(dp) :: p0(3), p1(3)
    call pinned_and_clear('cl_three', &
      '&clearance|joint_clearance = 0, 1e-5, 1e-5, 1e-5|joint_stiffness = 0, 1e10, 1e10, 1e10|/', b, p0, p1)
    call assert_true(has_line(b, 'with clearance: 16 global unknowns'), 'three journals: 10 + 6 unknowns')
    call assert_all_close(p1, p0, 1.0e-2_dp, 0.0_dp, 'peak stresses, three joints at c = 1e-5 in vs pinned')
  end subroutine test_three_joints

  !> c = 0.005 in, K = 4e7 (Lankarani-Nikravesh's sphere formula for a 1/4 in
  !> steel pin in aluminium): over the first revolution the peak joint force
  !> exceeds the nearly pinned one (953 lb at c = 1e-5) by more than 20 %
  !> (measured 1.31x) and the rocker's peak stress the pinned 25.5 ksi by more
  !> than 5 % (measured 13 %): the impacts load the links.
  subroutine test_clearance_growth()
    character(len=line_length), allocatable :: b(:)
    type(error_t) :: err
    real(dp) :: p(3), f
    call run_deck(run_transient, scratch_path('cl_grow'), deck('1', 'bdf', '1.0e-7', &
                  clearance('0.005', '4.0e7', '0.9')), err, b)
    call assert_true(.not. err%failed(), err%text())
    call peaks(b, p)
    f = summary_value(b, '# cost: clearance_peak_contact_force =')
    call assert_true(f > 1.2_dp*953.0_dp .and. f < 1.0e4_dp, 'peak contact force grows: '//trim(adjustl(rtoa(f))))
    call assert_true(p(3) > 1.05_dp*25531.6_dp, 'rocker stress grows: '//trim(adjustl(rtoa(p(3)))))
    call assert_true(summary_value(b, '# cost: clearance_impacts =') >= 5.0_dp, 'impacts counted')
  end subroutine test_clearance_growth

  !> K = 1e14 lb/in^1.5: at ~1000 lb the Hertz slope 1.5 K^(2/3) F^(1/3) is
  !> 3e10 lb/in, 1e5 times a link's axial stiffness EA/L = 2.5e5 lb/in.  BDF
  !> completes a quarter revolution (c = 1e-5) with the pinned peak stresses
  !> (0.5 %); Adams completes too here (the links' own axial modes already
  !> keep its steps small, measured 2.4 times BDF's steps) and its summary
  !> names the stiffness, the step bound 1/omega_c and BDF.
  subroutine test_stiff_contact()
    character(len=line_length), allocatable :: a(:), b(:), c(:)
    type(error_t) :: err
    real(dp) :: p0(3), p1(3)
    call run_deck(run_transient, scratch_path('cl_stiff_a'), deck('0.1', 'bdf', '1.0e-5', ''), err, a)
    call run_deck(run_transient, scratch_path('cl_stiff_b'), deck('0.1', 'bdf', '1.0e-5', &
                  clearance('1.0e-5', '1.0e14', '0.5')), err, b)
    call assert_true(.not. err%failed(), 'BDF: '//err%text())
    call peaks(a, p0)
    call peaks(b, p1)
    call assert_all_close(p1, p0, 5.0e-3_dp, 0.0_dp, 'BDF, stiff contact: pinned peaks')
    call assert_true(.not. has_line(b, 'Adams (functional iteration) is stable only'), 'no Adams warning with BDF')
    call run_deck(run_transient, scratch_path('cl_stiff_c'), deck('0.05', 'adams', '1.0e-5', &
                  clearance('1.0e-5', '1.0e14', '0.5')), err, c)
    call assert_true(.not. err%failed(), 'Adams: '//err%text())
    call assert_true(has_line(c, 'Adams (functional iteration) is stable only'), 'Adams told of the stiffness')
    call assert_true(has_line(c, 'method = ''bdf'''), 'and of BDF')
  end subroutine test_stiff_contact

  !> e = 0 with Lankarani-Nikravesh (chi = 3/4: still a rebound of 0.66 v, the
  !> law's limit, doc/clearance.md) and e = 0.01 with the calibrated law
  !> (chi ~ 100, nearly plastic): both complete a revolution at c = 0.005 in
  !> with impacts counted and finite forces; the nearly plastic joint
  !> separates less often.
  subroutine test_low_restitution()
    character(len=line_length), allocatable :: a(:), b(:)
    type(error_t) :: err
    real(dp) :: na, nb
    call run_deck(run_transient, scratch_path('cl_e0'), deck('1', 'bdf', '1.0e-7', &
                  clearance('0.005', '4.0e7', '0.0')), err, a)
    call assert_true(.not. err%failed(), 'LN e = 0: '//err%text())
    call run_deck(run_transient, scratch_path('cl_e001'), deck('1', 'bdf', '1.0e-7', &
                  clearance('0.005', '4.0e7', '0.01', 'calibrated')), err, b)
    call assert_true(.not. err%failed(), 'calibrated e = 0.01: '//err%text())
    na = summary_value(a, '# cost: clearance_separations =')
    nb = summary_value(b, '# cost: clearance_separations =')
    call assert_true(na > 0.0_dp .and. na < 1.0e5_dp, 'LN e = 0 separations counted')
    call assert_true(nb >= 0.0_dp .and. nb < na, 'nearly plastic: fewer separations')
    call assert_true(summary_value(b, '# cost: clearance_peak_contact_force =') < 1.0e5_dp, 'finite force')
  end subroutine test_low_restitution
end module test_clearance_run_suite

program test_clearance_run
  use test_clearance_run_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_clearance_run')
end program test_clearance_run
