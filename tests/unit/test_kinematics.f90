!> Tests of the rigid-body kinematics (module kinematics): positions,
!> velocities and accelerations against closed-form four-bar (Norton, Design
!> of Machinery, eqs. 4.10, 4.13, 6.18, 7.12), slider-crank and inverted
!> slider-crank expressions, against central differences, and the toggle and
!> non-assembly diagnoses.
module test_kinematics_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use linkage
  use kinematics
  use assertions
  use test_text, only: itoa
  use transient_fixtures, only: beam_input
  use mechanism_fixtures, only: fourbar_abcd, slider_crank_input, whitworth_input, ground_sleeve_input
  implicit none
  private
  public :: run_all

  real(dp), parameter :: deg = pi/180.0_dp

contains

  subroutine run_all()
    call run_test('fourbar_open_matches_closed_form_over_a_turn', test_fourbar_open)
    call run_test('fourbar_crossed_matches_closed_form_and_mirrors_open', test_fourbar_crossed)
    call run_test('fourbar_elements_split_links_evenly', test_fourbar_elements)
    call run_test('slider_crank_with_offset_matches_closed_form', test_slider_crank)
    call run_test('inverted_slider_crank_ground_sleeve_matches_closed_form', test_inverted_ground_sleeve)
    call run_test('inverted_slider_crank_sleeve_on_crank_matches_closed_form', test_inverted_moving_sleeve)
    call run_test('sliding_link_elements_match_finite_differences', test_sliding_elements_fd)
    call run_test('velocities_and_accelerations_match_finite_differences', test_fourbar_fd)
    call run_test('six_bar_second_loop_matches_closed_form_fourbar', test_six_bar)
    call run_test('rotating_cantilever_spinup_matches_closed_form', test_cantilever_spinup)
    call run_test('triad_linkage_assembles_from_reference_positions', test_triad)
    call run_test('link_point_matches_rigid_body_formulae', test_link_point)
    call run_test('toggle_at_sampled_angle_is_reported', test_toggle_hit)
    call run_test('toggle_passed_between_samples_is_reported', test_toggle_passed)
    call run_test('toggle_caught_however_close_the_sample', test_toggle_any_offset)
    call run_test('non_grashof_crank_stops_where_it_cannot_assemble', test_non_assembly)
    call run_test('first_assembly_impossible_is_reported', test_non_assembly_first)
    call run_test('newton_warm_start_takes_few_iterations', test_warm_start)
    call run_test('structure_without_driver_stays_at_rest', test_structure_at_rest)
    call run_test('truss_without_driver_is_placed_by_its_dyad', test_truss_at_rest)
    call run_test('structure_that_does_not_fit_is_reported', test_structure_misfit)
  end subroutine run_all

  ! ------------------------------------------------------------------ decks

  !> Four-bar A-B-C-D: crank AB = a clamped at A = (0,0), coupler BC = b,
  !> rocker DC = c pinned at D = (d, 0).  The rocker runs from D to C, so its
  !> angle is Norton's theta4.
  function fourbar_input(a, b, c, d, branch) result(inp)
    real(dp), intent(in) :: a, b, c, d
    character(len=*), intent(in) :: branch
    type(mechanism_input_t) :: inp
    inp = fourbar_abcd(a, b, c, d)
    inp%omega = 10.0_dp
    inp%branch = branch
  end function fourbar_input

  subroutine make(inp, kin)
    type(mechanism_input_t), intent(in) :: inp
    type(kinematics_t), intent(out) :: kin
    type(mechanism_t) :: mech
    type(error_t) :: err
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'build_mechanism: '//err%text())
    if (err%failed()) error stop 'test deck invalid'
    call kin%init(mech, err)
    call assert_true(.not. err%failed(), 'kinematics init: '//err%text())
    if (err%failed()) error stop 'kinematics init failed'
  end subroutine make

  !> Norton's closed-form four-bar: theta3, theta4 (eqs. 4.10, 4.13), omega3,
  !> omega4 (6.18), alpha3, alpha4 (7.12).  sgn = -1 open, +1 crossed.
  subroutine norton(a, b, c, d, t2, w2, al2, sgn, t3, t4, w3, w4, al3, al4)
    real(dp), intent(in) :: a, b, c, d, t2, w2, al2, sgn
    real(dp), intent(out) :: t3, t4, w3, w4, al3, al4
    real(dp) :: k1, k2, k3, k4, k5, ca, cb, cc, cd, ce, cf
    k1 = d/a
    k2 = d/c
    k3 = (a**2 - b**2 + c**2 + d**2)/(2.0_dp*a*c)
    k4 = d/b
    k5 = (c**2 - d**2 - a**2 - b**2)/(2.0_dp*a*b)
    ca = cos(t2) - k1 - k2*cos(t2) + k3
    cb = -2.0_dp*sin(t2)
    cc = k1 - (k2 + 1.0_dp)*cos(t2) + k3
    t4 = 2.0_dp*atan2(-cb + sgn*sqrt(cb**2 - 4.0_dp*ca*cc), 2.0_dp*ca)
    cd = cos(t2) - k1 + k4*cos(t2) + k5
    ce = -2.0_dp*sin(t2)
    cf = k1 + (k4 - 1.0_dp)*cos(t2) + k5
    t3 = 2.0_dp*atan2(-ce + sgn*sqrt(ce**2 - 4.0_dp*cd*cf), 2.0_dp*cd)
    w3 = a*w2/b*sin(t4 - t2)/sin(t3 - t4)
    w4 = a*w2/c*sin(t2 - t3)/sin(t4 - t3)
    ca = c*sin(t4)
    cb = b*sin(t3)
    cc = a*al2*sin(t2) + a*w2**2*cos(t2) + b*w3**2*cos(t3) - c*w4**2*cos(t4)
    cd = c*cos(t4)
    ce = b*cos(t3)
    cf = a*al2*cos(t2) - a*w2**2*sin(t2) - b*w3**2*sin(t3) + c*w4**2*sin(t4)
    al3 = (cc*cd - ca*cf)/(ca*ce - cb*cd)
    al4 = (cc*ce - cb*cf)/(ca*ce - cb*cd)
  end subroutine norton

  !> Difference of two angles reduced to (-pi, pi].
  pure real(dp) function angle_diff(x, y)
    real(dp), intent(in) :: x, y
    angle_diff = modulo(x - y + pi, two_pi) - pi
  end function angle_diff

  ! ------------------------------------------------------------------ tests

  !> FORMULATION.md §8.1 four-bar (5, 11, 10.5, 10), crank from 0 deg
  !> counter-clockwise, one full turn in 5 deg steps (warm starts), with a
  !> crank acceleration so that every term of 7.12 is exercised.  Tolerance
  !> 1e-10 on angles (rad) and 1e-10 relative to omega2 and omega2^2: the
  !> solutions are exact to rounding, so only ~1e-14 is expected.
  subroutine test_fourbar_open()
    call check_fourbar('open', -1.0_dp)
  end subroutine test_fourbar_open

  subroutine test_fourbar_crossed()
    type(kinematics_t) :: ko, kc
    type(error_t) :: err
    real(dp) :: b(2), d(2), co(2), cc(2), e(2), refl(2)
    integer :: k
    call check_fourbar('crossed', 1.0_dp)
    ! the crossed C is the mirror image of the open C in the line BD
    call make(fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'open'), ko)
    call make(fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'crossed'), kc)
    do k = 0, 350, 35
      call ko%solve_angle(k*deg, 1.0_dp, 0.0_dp, err)
      call kc%solve_angle(k*deg, 1.0_dp, 0.0_dp, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      b = ko%joint_position(2)
      d = ko%joint_position(4)
      co = ko%joint_position(3)
      cc = kc%joint_position(3)
      e = (d - b)/norm2(d - b)
      refl = b + 2.0_dp*dot_product(co - b, e)*e - (co - b)
      call assert_all_close(cc, refl, 0.0_dp, 1.0e-12_dp, 'crossed C = mirror of open C in BD')
      call assert_true(norm2(cc - co) > 1.0_dp, 'the two branches are distinct')
    end do
  end subroutine test_fourbar_crossed

  subroutine check_fourbar(branch, sgn)
    character(len=*), intent(in) :: branch
    real(dp), intent(in) :: sgn
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m3, m4
    real(dp), parameter :: a = 5.0_dp, b = 11.0_dp, c = 10.5_dp, d = 10.0_dp, w2 = 10.0_dp, al2 = 30.0_dp
    real(dp) :: t2, t3, t4, w3, w4, al3, al4, cpos(2)
    integer :: k
    call make(fourbar_input(a, b, c, d, branch), kin)
    do k = 0, 72
      t2 = k*5.0_dp*deg
      call kin%solve_angle(t2, w2, al2, err)
      call assert_true(.not. err%failed(), 'solve at '//crank_angle_text(t2)//': '//err%text())
      if (err%failed()) return
      call norton(a, b, c, d, t2, w2, al2, sgn, t3, t4, w3, w4, al3, al4)
      m3 = kin%link_motion(2)
      m4 = kin%link_motion(3)
      call assert_close(angle_diff(m3%phi, t3), 0.0_dp, 1.0e-10_dp, branch//' theta3')
      call assert_close(angle_diff(m4%phi, t4), 0.0_dp, 1.0e-10_dp, branch//' theta4')
      call assert_close(m3%phi_d, w3, 1.0e-10_dp*w2, branch//' omega3')
      call assert_close(m4%phi_d, w4, 1.0e-10_dp*w2, branch//' omega4')
      call assert_close(m3%phi_dd, al3, 1.0e-10_dp*w2**2, branch//' alpha3')
      call assert_close(m4%phi_dd, al4, 1.0e-10_dp*w2**2, branch//' alpha4')
      cpos = [d + c*cos(t4), c*sin(t4)]
      call assert_all_close(kin%joint_position(3), cpos, 0.0_dp, 1.0e-10_dp, branch//' C')
      ! the crank follows the driver exactly
      m3 = kin%link_motion(1)
      call assert_close(m3%phi, t2, 1.0e-14_dp, 'crank angle')
      call assert_close(m3%phi_dd, al2, 1.0e-10_dp, 'crank acceleration')
    end do
  end subroutine check_fourbar

  !> Three elements on the coupler: element k starts at B + (k-1)/3 BC, has
  !> the coupler's angle, and length 11/3; rates by the rigid-body formulae.
  subroutine test_fourbar_elements()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: ml, me
    real(dp) :: f, u(2), up(2)
    integer :: k
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'open')
    inp%link_n_elements(1:3) = [1, 3, 2]
    call make(inp, kin)
    call assert_equal(kin%mech%n_elements, 6, 'total elements')
    call assert_equal(kin%mech%links(2)%first_element, 2, 'first element of the coupler')
    call assert_equal(kin%mech%links(3)%first_element, 5, 'first element of the rocker')
    call kin%solve_angle(40.0_dp*deg, 7.0_dp, 2.0_dp, err)
    call assert_true(.not. err%failed(), err%text())
    ml = kin%link_motion(2)
    u = [cos(ml%phi), sin(ml%phi)]
    up = [-u(2), u(1)]
    do k = 1, 3
      f = (k - 1)/3.0_dp
      me = kin%element_motion(2, k)
      call assert_close(me%x1, ml%x1 + f*11.0_dp*u(1), 1.0e-12_dp, 'element X1')
      call assert_close(me%y1, ml%y1 + f*11.0_dp*u(2), 1.0e-12_dp, 'element Y1')
      call assert_close(me%x1_d, ml%x1_d + f*11.0_dp*ml%phi_d*up(1), 1.0e-11_dp, 'element X1 rate')
      call assert_close(me%y1_dd, ml%y1_dd + f*11.0_dp*(ml%phi_dd*up(2) - ml%phi_d**2*u(2)), 1.0e-10_dp, &
                        'element Y1 second rate')
      call assert_close(me%phi, ml%phi, 0.0_dp, 'element angle = link angle')
      call assert_close(me%length, 11.0_dp/3.0_dp, 1.0e-14_dp, 'element length')
      call assert_close(me%length_d, 0.0_dp, 0.0_dp, 'fixed link: no length rate')
      me = kin%element_motion_global(1 + k)
      call assert_close(me%x1, ml%x1 + f*11.0_dp*u(1), 1.0e-12_dp, 'global element numbering')
    end do
    ! end of the last element = joint C
    me = kin%element_motion(2, 3)
    call assert_all_close([me%x1 + me%length*cos(me%phi), me%y1 + me%length*sin(me%phi)], &
                          kin%joint_position(3), 0.0_dp, 1.0e-12_dp, 'last element ends at C')
  end subroutine test_fourbar_elements

  !> Slider-crank: crank r = 2 about A = (0,0), rod L = 7, slider C on the
  !> line y = e = 0.5 along +X.  Closed form with s = r sin(t) - e,
  !> D = sqrt(L^2 - s^2): x = r cos t + D, rod angle atan2(-s, D).
  subroutine test_slider_crank()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m
    real(dp), parameter :: r = 2.0_dp, rl = 7.0_dp, e = 0.5_dp, w = 12.0_dp, al = -40.0_dp
    real(dp) :: t, s, sd, sdd, dd, x, xd, xdd, ph, phd, phdd, sl(3)
    integer :: k
    inp = slider_crank_input(r, rl, e)
    inp%joint_name(1:3) = [character(len=16) :: 'A', 'B', 'C']
    call make(inp, kin)
    do k = 0, 36
      t = k*10.0_dp*deg
      call kin%solve_angle(t, w, al, err)
      call assert_true(.not. err%failed(), err%text())
      s = r*sin(t) - e
      sd = r*cos(t)*w
      sdd = -r*sin(t)*w**2 + r*cos(t)*al
      dd = sqrt(rl**2 - s**2)
      x = r*cos(t) + dd
      xd = -r*sin(t)*w - s*sd/dd
      xdd = -r*cos(t)*w**2 - r*sin(t)*al - (sd**2 + s*sdd)/dd - s**2*sd**2/dd**3
      ph = atan2(-s, dd)
      phd = -sd/dd
      phdd = -sdd/dd - s*sd**2/dd**3
      sl = kin%slide(3)
      call assert_close(sl(1), x, 1.0e-10_dp, 'slider position')
      call assert_close(sl(2), xd, 1.0e-10_dp*w, 'slider velocity')
      call assert_close(sl(3), xdd, 1.0e-10_dp*w**2, 'slider acceleration')
      call assert_all_close(kin%joint_acceleration(3), [xdd, 0.0_dp], 0.0_dp, 1.0e-10_dp*w**2, &
                            'slider block acceleration is along the guide')
      m = kin%link_motion(2)
      call assert_close(angle_diff(m%phi, ph), 0.0_dp, 1.0e-10_dp, 'rod angle')
      call assert_close(m%phi_d, phd, 1.0e-10_dp*w, 'rod angular velocity')
      call assert_close(m%phi_dd, phdd, 1.0e-10_dp*w**2, 'rod angular acceleration')
    end do
  end subroutine test_slider_crank

  !> Closed form for a link from point B through a fixed point C: w = C - B,
  !> l = |w|, phi = atan2(w), phi_d = (w x w_d)/l^2, l_d = w.w_d/l,
  !> phi_dd = (w x w_dd)/l^2 - 2 phi_d l_d/l, l_dd = (w_d.w_d + w.w_dd)/l - l_d^2/l.
  subroutine line_through(w, wd, wdd, l, ld, ldd, ph, phd, phdd)
    real(dp), intent(in) :: w(2), wd(2), wdd(2)
    real(dp), intent(out) :: l, ld, ldd, ph, phd, phdd
    l = norm2(w)
    ph = atan2(w(2), w(1))
    phd = (w(1)*wd(2) - w(2)*wd(1))/l**2
    ld = dot_product(w, wd)/l
    phdd = (w(1)*wdd(2) - w(2)*wdd(1))/l**2 - 2.0_dp*phd*ld/l
    ldd = (dot_product(wd, wd) + dot_product(w, wdd))/l - ld**2/l
  end subroutine line_through

  !> Link 2 of an inverted slider-crank (crank r about the origin, angle t,
  !> rates w, al) runs along sign*(B - pivot): its active length, angle and
  !> their rates every 10 deg against line_through (1e-10, scaled by w and
  !> w^2); with n_el elements the element length is the active length / n_el.
  subroutine check_sleeve_link(kin, r, w, al, pivot, sign, name, n_el)
    type(kinematics_t), intent(inout) :: kin
    real(dp), intent(in) :: r, w, al, pivot(2), sign
    character(len=*), intent(in) :: name
    integer, intent(in), optional :: n_el
    type(error_t) :: err
    type(motion_t) :: m
    real(dp) :: t, bp(2), bd(2), bdd(2), l, ld, ldd, ph, phd, phdd
    integer :: k
    do k = 0, 36
      t = k*10.0_dp*deg
      call kin%solve_angle(t, w, al, err)
      call assert_true(.not. err%failed(), err%text())
      bp = r*[cos(t), sin(t)]
      bd = r*w*[-sin(t), cos(t)]
      bdd = r*al*[-sin(t), cos(t)] - r*w**2*[cos(t), sin(t)]
      call line_through(sign*(bp - pivot), sign*bd, sign*bdd, l, ld, ldd, ph, phd, phdd)
      m = kin%link_motion(2)
      call assert_close(m%length, l, 1.0e-10_dp, name//' active length')
      call assert_close(m%length_d, ld, 1.0e-10_dp*w, name//' active length rate')
      call assert_close(m%length_dd, ldd, 1.0e-10_dp*w**2, name//' active length second rate')
      call assert_close(angle_diff(m%phi, ph), 0.0_dp, 1.0e-10_dp, name//' angle')
      call assert_close(m%phi_d, phd, 1.0e-10_dp*w, name//' angular velocity')
      call assert_close(m%phi_dd, phdd, 1.0e-10_dp*w**2, name//' angular acceleration')
      if (.not. present(n_el)) cycle
      m = kin%element_motion(2, n_el)
      call assert_close(m%length, l/n_el, 1.0e-10_dp, 'element length = active length / n')
      call assert_close(m%length_dd, ldd/n_el, 1.0e-10_dp*w**2, 'element length second rate')
    end do
  end subroutine check_sleeve_link

  !> Inverted slider-crank (oscillating cylinder): crank AB = 3 about A = (0,0);
  !> link 2 is pinned at B and slides through a sleeve pivoting on the ground
  !> at C = (8, 0).  Its active length is |BC|.
  function inverted_ground_input() result(inp)
    type(mechanism_input_t) :: inp
    inp = ground_sleeve_input(3.0_dp, 14.0_dp, 8.0_dp)
    inp%joint_name(1:3) = [character(len=16) :: 'A', 'B', 'C']
    inp%link_name(1:2) = [character(len=16) :: 'crank', 'rod']
    inp%link_n_elements(2) = 4
  end function inverted_ground_input

  subroutine test_inverted_ground_sleeve()
    type(kinematics_t) :: kin
    call make(inverted_ground_input(), kin)
    call check_sleeve_link(kin, 3.0_dp, 9.0_dp, 25.0_dp, [8.0_dp, 0.0_dp], -1.0_dp, 'rod', 4)
  end subroutine test_inverted_ground_sleeve

  !> Crank AB = 3 about A = (0,0) carries a pivoting sleeve at B; the lever
  !> from the ground pivot D = (0, -6) slides through it (Whitworth-type
  !> quick-return).  The lever's active length is |DB|.
  subroutine test_inverted_moving_sleeve()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    inp = whitworth_input(3.0_dp, 6.0_dp)
    inp%joint_name(1:3) = [character(len=16) :: 'A', 'B', 'D']
    inp%link_name(1:2) = [character(len=16) :: 'crank', 'lever']
    call make(inp, kin)
    call check_sleeve_link(kin, 3.0_dp, 5.0_dp, 0.0_dp, [0.0_dp, -6.0_dp], 1.0_dp, 'lever')
  end subroutine test_inverted_moving_sleeve

  !> Time-driven (spin-up) inverted slider-crank: element end-1 positions of
  !> the sliding rod and element lengths against central differences of the
  !> positions.  h = 1e-5 s; truncation (h^2/6)|x'''| ~ 1e-9 and rounding
  !> eps L/h ~ 1e-10, so 1e-6 relative to the velocity scale r*omega and
  !> 1e-5 to the acceleration scale r*omega^2 are safe yet far below any
  !> missing term (those are O(1)).
  subroutine test_sliding_elements_fd()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: mm, m0, mp
    real(dp), parameter :: h = 1.0e-5_dp
    real(dp) :: t, vs, as
    integer :: k, e
    inp = inverted_ground_input()
    inp%omega = 20.0_dp
    inp%profile = 'spinup'
    inp%spinup_time = 0.5_dp
    inp%theta0_deg = 30.0_dp
    call make(inp, kin)
    vs = 3.0_dp*20.0_dp
    as = 3.0_dp*20.0_dp**2
    do k = 1, 6
      t = 0.11_dp*k
      do e = 1, 4
        call kin%solve(t - h, err)
        mm = kin%element_motion(2, e)
        call kin%solve(t + h, err)
        mp = kin%element_motion(2, e)
        call kin%solve(t, err)
        call assert_true(.not. err%failed(), err%text())
        m0 = kin%element_motion(2, e)
        call assert_close(m0%x1_d, (mp%x1 - mm%x1)/(2*h), 1.0e-6_dp*vs, 'element X1 rate vs FD')
        call assert_close(m0%y1_d, (mp%y1 - mm%y1)/(2*h), 1.0e-6_dp*vs, 'element Y1 rate vs FD')
        call assert_close(m0%x1_dd, (mp%x1_d - mm%x1_d)/(2*h), 1.0e-5_dp*as, 'element X1 second rate vs FD')
        call assert_close(m0%y1_dd, (mp%y1_d - mm%y1_d)/(2*h), 1.0e-5_dp*as, 'element Y1 second rate vs FD')
        call assert_close(m0%length_d, (mp%length - mm%length)/(2*h), 1.0e-6_dp*vs, 'element length rate vs FD')
        call assert_close(m0%length_dd, (mp%length_d - mm%length_d)/(2*h), 1.0e-5_dp*as, &
                          'element length second rate vs FD')
        call assert_close(m0%phi_d, (mp%phi - mm%phi)/(2*h), 1.0e-6_dp*20.0_dp, 'angle rate vs FD')
        call assert_close(m0%phi_dd, (mp%phi_d - mm%phi_d)/(2*h), 1.0e-5_dp*400.0_dp, 'angle second rate vs FD')
      end do
    end do
  end subroutine test_sliding_elements_fd

  !> Four-bar driven in time through the spin-up: every coordinate's rate and
  !> second rate against central differences (same tolerance reasoning as
  !> above, scales a*omega and a*omega^2 with omega = 50).
  subroutine test_fourbar_fd()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    real(dp), parameter :: h = 1.0e-6_dp, w = 50.0_dp
    real(dp), allocatable :: qm(:), qp(:), qdm(:), qdp(:)
    real(dp) :: t
    integer :: k
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'open')
    inp%omega = w
    inp%profile = 'spinup'
    inp%spinup_time = 0.2_dp
    call make(inp, kin)
    do k = 1, 8
      t = 0.03_dp*k
      call kin%solve(t - h, err)
      qm = kin%q
      qdm = kin%qd
      call kin%solve(t + h, err)
      qp = kin%q
      qdp = kin%qd
      call kin%solve(t, err)
      call assert_true(.not. err%failed(), err%text())
      call assert_all_close(kin%qd, (qp - qm)/(2*h), 0.0_dp, 1.0e-6_dp*5.0_dp*w, 'velocities vs FD of positions')
      call assert_all_close(kin%qdd, (qdp - qdm)/(2*h), 0.0_dp, 1.0e-5_dp*5.0_dp*w**2, &
                            'accelerations vs FD of velocities')
    end do
  end subroutine test_fourbar_fd

  !> Watt six-bar built from pins only: the four-bar ABCD, a rigid triangle
  !> D-C-E on the rocker (links DE, CE), and a second four-bar D-E-F-G with
  !> G = (14, 9) on the ground.  The output GF must follow Norton's four-bar
  !> with input DE (angle theta4 + const) and ground DG (rotated frame).
  subroutine test_six_bar()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: mde, mgf, mdc, mef
    real(dp), parameter :: gx = 14.0_dp, gy = 9.0_dp, w = 3.0_dp, al = 2.0_dp
    real(dp) :: t, dg, gam, t3, t4, w3, w4, al3, al4, tri
    integer :: k
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'open')
    inp%n_joints = 7
    inp%joint_name(5:7) = [character(len=16) :: 'E', 'F', 'G']
    inp%joint_type(5:7) = [character(len=16) :: 'pin', 'pin', 'ground_pin']
    inp%joint_x(7) = gx
    inp%joint_y(7) = gy
    inp%joint_branch(5) = 'crossed'   ! E to the left of D->C
    inp%n_links = 7
    inp%link_name(4:7) = [character(len=16) :: 'DE', 'CE', 'EF', 'GF']
    inp%link_joint1(4:7) = [4, 3, 5, 7]
    inp%link_joint2(4:7) = [5, 5, 6, 6]
    inp%link_length(4:7) = [6.0_dp, 8.0_dp, 9.0_dp, 7.5_dp]
    call make(inp, kin)
    dg = hypot(gx - 10.0_dp, gy)
    gam = atan2(gy, gx - 10.0_dp)
    do k = 0, 36
      t = k*10.0_dp*deg
      call kin%solve_angle(t, w, al, err)
      call assert_true(.not. err%failed(), err%text())
      if (err%failed()) return
      mde = kin%link_motion(4)
      mgf = kin%link_motion(7)
      mdc = kin%link_motion(3)
      mef = kin%link_motion(6)
      ! the triangle D-C-E stays rigid
      tri = angle_diff(mde%phi, mdc%phi)
      if (k == 0) then
        call assert_true(tri > 0.0_dp, 'crossed: E to the left of D->C')
      end if
      call assert_close(mde%phi_d, mdc%phi_d, 1.0e-10_dp*w, 'triangle DCE rigid (rate)')
      ! second loop in the frame of its ground line DG; input DE
      call norton(6.0_dp, 9.0_dp, 7.5_dp, dg, mde%phi - gam, mde%phi_d, mde%phi_dd, -1.0_dp, &
                  t3, t4, w3, w4, al3, al4)
      call assert_close(angle_diff(mgf%phi, t4 + gam), 0.0_dp, 1.0e-10_dp, 'six-bar output angle')
      call assert_close(mgf%phi_d, w4, 1.0e-10_dp*w, 'six-bar output angular velocity')
      call assert_close(mgf%phi_dd, al4, 1.0e-9_dp*w**2, 'six-bar output angular acceleration')
      call assert_close(angle_diff(mef%phi, t3 + gam), 0.0_dp, 1.0e-10_dp, 'six-bar EF angle')
    end do
  end subroutine test_six_bar

  !> A class-III Assur group (triad), which cannot be placed dyad by dyad: a
  !> rigid equilateral triangle P-Q-R (side 4) hung from the crank tip B by
  !> BP = 3.5 and from the ground by G1-Q = 3 and G2-R = 3; crank AB = 0.5
  !> (it turns fully; the smallest reciprocal condition is 0.024).  The
  !> deck's reference positions (exact at 0 deg) start Newton.  Checked: every
  !> link keeps its length, the triangle stays rigid, and the velocities match
  !> central differences (h = 1e-6 rad of crank angle, same reasoning as above).
  subroutine test_triad()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(kinematics_t) :: kin
    type(error_t) :: err
    real(dp), allocatable :: qm(:), qp(:)
    real(dp), parameter :: s3 = sqrt(3.0_dp), h = 1.0e-6_dp
    real(dp) :: t, pq(2), pr(2)
    integer :: k, i
    inp%n_joints = 7
    inp%joint_name(1:7) = [character(len=16) :: 'A', 'B', 'P', 'Q', 'R', 'G1', 'G2']
    inp%joint_type(1:7) = [character(len=16) :: 'clamp', 'pin', 'pin', 'pin', 'pin', 'ground_pin', 'ground_pin']
    inp%joint_x(1:7) = [0.0_dp, 0.5_dp, 4.0_dp, 6.0_dp, 8.0_dp, 6.0_dp, 8.0_dp]
    inp%joint_y(1:7) = [0.0_dp, 0.0_dp, 0.0_dp, 2.0_dp*s3, 0.0_dp, 2.0_dp*s3 + 3.0_dp, -3.0_dp]
    inp%n_links = 7
    inp%link_name(1:7) = [character(len=16) :: 'crank', 'BP', 'G1Q', 'G2R', 'PQ', 'QR', 'RP']
    inp%link_joint1(1:7) = [1, 2, 6, 7, 3, 4, 5]
    inp%link_joint2(1:7) = [2, 3, 4, 5, 4, 5, 3]
    inp%link_length(1:7) = 0.0_dp   ! all from the coordinates
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), err%text())
    call kin%init(mech, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_true(.not. kin%plan_complete, 'a triad is not placed dyad by dyad')
    do k = 0, 36
      t = k*10.0_dp*deg
      call kin%solve_angle(t - h, 1.0_dp, 0.0_dp, err)
      qm = kin%q
      call kin%solve_angle(t + h, 1.0_dp, 0.0_dp, err)
      qp = kin%q
      call kin%solve_angle(t, 1.0_dp, 0.0_dp, err)
      call assert_true(.not. err%failed(), err%text())
      if (err%failed()) return
      do i = 1, 7
        associate (lk => kin%mech%links(i))
          call assert_close(norm2(kin%joint_position(lk%joint(2)) - kin%joint_position(lk%joint(1))), lk%length, &
                            1.0e-12_dp, 'triad link length')
        end associate
      end do
      pq = kin%joint_position(4) - kin%joint_position(3)
      pr = kin%joint_position(5) - kin%joint_position(3)
      call assert_close(pq(1)*pr(2) - pq(2)*pr(1), -8.0_dp*s3, 1.0e-10_dp, 'triangle keeps its orientation')
      call assert_all_close(kin%qd, (qp - qm)/(2*h), 0.0_dp, 1.0e-6_dp, 'triad velocities vs FD')
    end do
    ! without reference positions the triad cannot be started
    inp%joint_x(3:5) = coordinate_unset
    inp%joint_y(3:5) = coordinate_unset
    inp%link_length(1:7) = [0.5_dp, 3.5_dp, 3.0_dp, 3.0_dp, 4.0_dp, 4.0_dp, 4.0_dp]
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), err%text())
    call kin%init(mech, err)
    call assert_equal(err%code, 2, 'missing start positions are an input error')
    call assert_true(index(err%text(), 'joints P Q R') > 0, 'names the joints: '//err%text())
  end subroutine test_triad

  !> One link clamped to the shaft with a free end, spun up from rest
  !> (cycloidal profile): element k starts at (k-1) L/n u(theta) with the
  !> rigid rotation's velocity and acceleration.
  subroutine test_cantilever_spinup()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m
    real(dp) :: t, th, thd, thdd, x
    integer :: k, e
    inp%n_joints = 2
    inp%joint_type(1:2) = [character(len=16) :: 'clamp', 'free']
    inp%joint_x(1) = 1.0_dp
    inp%joint_y(1) = -2.0_dp
    inp%n_links = 1
    inp%link_joint1(1) = 1
    inp%link_joint2(1) = 2
    inp%link_length(1) = 12.0_dp
    inp%link_n_elements(1) = 4
    inp%omega = 6.0_dp
    inp%profile = 'spinup'
    inp%spinup_time = 1.5_dp
    call make(inp, kin)
    do k = 0, 20
      t = 0.1_dp*k
      call kin%solve(t, err)
      call assert_true(.not. err%failed(), err%text())
      call driver_angle(kin%mech%driver, t, th, thd, thdd)
      do e = 1, 4
        m = kin%element_motion(1, e)
        x = 3.0_dp*(e - 1)
        call assert_close(m%x1, 1.0_dp + x*cos(th), 1.0e-12_dp, 'cantilever element X1')
        call assert_close(m%y1_d, x*thd*cos(th), 1.0e-11_dp, 'cantilever element Y1 rate')
        call assert_close(m%x1_dd, -x*(thdd*sin(th) + thd**2*cos(th)), 1.0e-10_dp, 'cantilever element X1 accel')
        call assert_close(m%phi_dd, thdd, 1.0e-12_dp, 'cantilever angular acceleration')
      end do
    end do
  end subroutine test_cantilever_spinup

  !> A coupler point off the reference line: position by geometry, velocity
  !> and acceleration by r_B + omega x rho and the rigid-body acceleration.
  subroutine test_link_point()
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m
    real(dp) :: r(2), v(2), a(2), rho(2), u(2)
    call make(fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'open'), kin)
    call kin%solve_angle(123.0_dp*deg, 4.0_dp, -3.0_dp, err)
    call assert_true(.not. err%failed(), err%text())
    call kin%point(2, 4.0_dp, 2.5_dp, r, v, a)
    m = kin%link_motion(2)
    u = [cos(m%phi), sin(m%phi)]
    rho = 4.0_dp*u + 2.5_dp*[-u(2), u(1)]
    call assert_all_close(r, kin%joint_position(2) + rho, 0.0_dp, 1.0e-12_dp, 'point position')
    call assert_all_close(v, kin%joint_velocity(2) + m%phi_d*[-rho(2), rho(1)], 0.0_dp, 1.0e-11_dp, &
                          'point velocity')
    call assert_all_close(a, kin%joint_acceleration(2) + m%phi_dd*[-rho(2), rho(1)] - m%phi_d**2*rho, &
                          0.0_dp, 1.0e-10_dp, 'point acceleration')
    ! the point at the far end on the line is joint C
    call kin%point(2, 11.0_dp, 0.0_dp, r)
    call assert_all_close(r, kin%joint_position(3), 0.0_dp, 1.0e-12_dp, 'link end = joint C')
  end subroutine test_link_point

  !> Parallelogram (5, 10, 5, 10): at crank angle 0 all four links are
  !> collinear, the Jacobian is singular.
  subroutine test_toggle_hit()
    type(kinematics_t) :: kin
    type(error_t) :: err
    call make(fourbar_input(5.0_dp, 10.0_dp, 5.0_dp, 10.0_dp, 'open'), kin)
    call kin%solve_angle(0.0_dp, 1.0_dp, 0.0_dp, err)
    call assert_true(err%failed(), 'toggle at 0 deg must be an error')
    call assert_true(index(err%text(), 'toggle') > 0, 'message says toggle: '//err%text())
    call assert_true(index(err%text(), 'crank angle 0') > 0, 'message names the crank angle: '//err%text())
  end subroutine test_toggle_hit

  !> Parallelogram stepped from 30 deg in 7 deg steps: 177 -> 184 passes the
  !> collinear toggle at 180 deg without sampling it.
  subroutine test_toggle_passed()
    type(kinematics_t) :: kin
    type(error_t) :: err
    integer :: k
    real(dp) :: last
    call make(fourbar_input(5.0_dp, 10.0_dp, 5.0_dp, 10.0_dp, 'open'), kin)
    last = -1.0_dp
    do k = 0, 40
      call kin%solve_angle((30.0_dp + 7.0_dp*k)*deg, 1.0_dp, 0.0_dp, err)
      if (err%failed()) exit
      last = 30.0_dp + 7.0_dp*k
      ! on the open branch the parallelogram stays a parallelogram: C = B + (10, 0)
      call assert_all_close(kin%joint_position(3), kin%joint_position(2) + [10.0_dp, 0.0_dp], 0.0_dp, &
                            1.0e-10_dp, 'parallelogram')
    end do
    call assert_true(err%failed(), 'passing the toggle must be an error')
    call assert_close(last, 177.0_dp, 0.0_dp, 'last good crank angle')
    call assert_true(index(err%text(), 'toggle') > 0, 'message says toggle: '//err%text())
    call assert_true(index(err%text(), 'crank angle 177') > 0 .and. index(err%text(), 'crank angle 184') > 0, &
                     'message names both crank angles: '//err%text())
    ! the previous solution is kept
    call assert_close(kin%theta, 177.0_dp*deg, 1.0e-14_dp, 'state kept at the last good angle')
  end subroutine test_toggle_passed

  !> Parallelogram in 1 deg steps whose grid misses 180 deg by 0 .. 1e-4 rad:
  !> whether Newton lands on the toggle (singular Jacobian), near it (Newton
  !> only converges linearly there), or past it (branch sign flipped), the
  !> run must stop at 180 or 181 deg and never continue on the other branch.
  subroutine test_toggle_any_offset()
    type(kinematics_t) :: kin
    type(error_t) :: err
    real(dp), parameter :: offsets(9) = [0.0_dp, 1.0e-15_dp, -1.0e-13_dp, 1.0e-11_dp, -1.0e-9_dp, 1.0e-8_dp, &
                                         -1.0e-7_dp, 1.0e-6_dp, 1.0e-4_dp]
    integer :: k, m
    do m = 1, size(offsets)
      call make(fourbar_input(5.0_dp, 10.0_dp, 5.0_dp, 10.0_dp, 'open'), kin)
      call err%clear()
      do k = 150, 200
        call kin%solve_angle(k*deg + offsets(m), 1.0_dp, 0.0_dp, err)
        if (err%failed()) exit
      end do
      call assert_true(k == 180 .or. k == 181, 'stopped at 180 or 181 deg, not '//trim(itoa(k)))
      call assert_true(index(err%text(), 'toggle') > 0, 'toggle reported: '//err%text())
    end do
  end subroutine test_toggle_any_offset

  !> Non-Grashof (5, 6, 7, 10): |BD| reaches b + c = 13 at
  !> theta = acos(-0.44) = 116.10 deg; stepping 1 deg the first angle that
  !> cannot assemble is 117 deg.
  subroutine test_non_assembly()
    type(kinematics_t) :: kin
    type(error_t) :: err
    integer :: k, last
    call make(fourbar_input(5.0_dp, 6.0_dp, 7.0_dp, 10.0_dp, 'open'), kin)
    last = -1
    do k = 0, 360
      call kin%solve_angle(k*deg, 1.0_dp, 0.0_dp, err)
      if (err%failed()) exit
      last = k
    end do
    call assert_equal(last, 116, 'last crank angle that assembles')
    call assert_true(index(err%text(), 'cannot be assembled') > 0, 'message: '//err%text())
    call assert_true(index(err%text(), 'crank angle 117') > 0, 'message names the crank angle: '//err%text())
    call assert_true(index(err%text(), 'joint C') > 0, 'message names the joint: '//err%text())
  end subroutine test_non_assembly

  subroutine test_non_assembly_first()
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(mechanism_input_t) :: inp
    call make(fourbar_input(5.0_dp, 6.0_dp, 7.0_dp, 10.0_dp, 'open'), kin)
    call kin%solve_angle(180.0_dp*deg, 1.0_dp, 0.0_dp, err)
    call assert_true(err%failed(), 'no assembly at 180 deg')
    call assert_true(index(err%text(), 'crank angle 180') > 0, 'message names the crank angle: '//err%text())
    ! a slider-crank whose rod is too short for the guide
    call err%clear()
    inp = slider_crank_input(2.0_dp, 4.0_dp, 5.0_dp)
    call make(inp, kin)
    call kin%solve(0.0_dp, err)
    call assert_true(index(err%text(), 'J3 cannot be placed') > 0, 'slider message: '//err%text())
    call assert_true(index(err%text(), 't = 0') > 0, 'time named: '//err%text())
  end subroutine test_non_assembly_first

  !> With the predictor q + (dq/dtheta) dtheta, 1 deg steps need at most 3
  !> Newton iterations (quadratic convergence from an O(dtheta^2) guess).
  subroutine test_warm_start()
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m
    integer :: k, worst
    call make(fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp, 'open'), kin)
    worst = 0
    do k = 0, 720
      call kin%solve_angle(k*deg, 1.0_dp, 0.0_dp, err)
      if (k > 0) worst = max(worst, kin%iterations)
    end do
    call assert_true(.not. err%failed(), err%text())
    call assert_true(worst <= 3, 'at most 3 iterations per 1 deg step, got '//trim(adjustl(itoa(worst))))
    call assert_equal(kin%n_reassemblies, 0, 'no fall-back assembly needed')
    ! two turns: the crank angle is unwrapped and so are the other angles
    m = kin%link_motion(1)
    call assert_close(m%phi, 720.0_dp*deg, 1.0e-12_dp, 'crank angle unwrapped')
  end subroutine test_warm_start

  !> An inclined beam between two ground pins, no driver (driver_link = 0):
  !> the elements split it evenly at every time, with zero rates.
  subroutine test_structure_at_rest()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m
    integer :: k, e
    inp = beam_input('ground_pin', 4)
    inp%joint_x(1:2) = [1.0_dp, 1.0_dp + 8.0_dp*sqrt(3.0_dp)]
    inp%joint_y(1:2) = [2.0_dp, 10.0_dp]
    call make(inp, kin)
    do k = 0, 3
      call kin%solve(0.5_dp*k, err)
      call assert_true(.not. err%failed(), err%text())
      do e = 1, 4
        m = kin%element_motion(1, e)
        call assert_close(m%x1, 1.0_dp + 2.0_dp*(e - 1)*sqrt(3.0_dp), 1.0e-12_dp, 'element start X')
        call assert_close(m%y1, 2.0_dp + 2.0_dp*(e - 1), 1.0e-12_dp, 'element start Y')
        call assert_close(m%phi, 30.0_dp*deg, 1.0e-14_dp, 'beam inclined at 30 deg')
        call assert_close(m%length, 4.0_dp, 1.0e-12_dp, 'element length')
        call assert_true(maxval(abs([m%x1_d, m%y1_d, m%phi_d, m%x1_dd, m%y1_dd, m%phi_dd])) < tiny(1.0_dp), 'at rest')
      end do
    end do
  end subroutine test_structure_at_rest

  !> Two links from ground pins A = (0,0), B = (20,0) meeting at pin C with
  !> lengths 12 and 16: C = (7.2, 9.6) on the open side, cross(C-A, C-B) > 0
  !> (a right triangle).
  subroutine test_truss_at_rest()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    type(motion_t) :: m
    inp%n_joints = 3
    inp%joint_type(1:3) = [character(len=16) :: 'ground_pin', 'ground_pin', 'pin']
    inp%joint_x(1:2) = [0.0_dp, 20.0_dp]
    inp%joint_y(1:2) = [0.0_dp, 0.0_dp]
    inp%n_links = 2
    inp%link_joint1(1:2) = [1, 2]
    inp%link_joint2(1:2) = [3, 3]
    inp%link_length(1:2) = [12.0_dp, 16.0_dp]
    inp%driver_link = 0
    call make(inp, kin)
    call kin%solve(0.0_dp, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_all_close(kin%joint_position(3), [7.2_dp, 9.6_dp], 0.0_dp, 1.0e-12_dp, 'joint C')
    m = kin%link_motion(2)
    call assert_close(m%phi, atan2(9.6_dp, 7.2_dp - 20.0_dp), 1.0e-13_dp, 'link 2 angle')
    call assert_true(maxval(abs(kin%qd)) + maxval(abs(kin%qdd)) < tiny(1.0_dp), 'at rest')
  end subroutine test_truss_at_rest

  !> A link whose length does not match its ground points is named.
  subroutine test_structure_misfit()
    type(mechanism_input_t) :: inp
    type(kinematics_t) :: kin
    type(error_t) :: err
    inp%n_joints = 2
    inp%joint_name(1:2) = [character(len=16) :: 'A', 'B']
    inp%joint_type(1:2) = [character(len=16) :: 'clamp', 'clamp']
    inp%joint_x(1:2) = [0.0_dp, 20.0_dp]
    inp%joint_y(1:2) = [0.0_dp, 0.0_dp]
    inp%n_links = 1
    inp%link_name(1) = 'beam'
    inp%link_joint1(1) = 1
    inp%link_joint2(1) = 2
    inp%link_length(1) = 20.5_dp
    inp%driver_link = 0
    call make(inp, kin)
    call kin%solve(0.0_dp, err)
    call assert_true(index(err%text(), 'does not fit together: link beam is 20.5') > 0 .and. &
                     index(err%text(), 'A and B are 20.0') > 0, err%text())
  end subroutine test_structure_misfit
end module test_kinematics_suite

program test_kinematics
  use test_kinematics_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_kinematics')
end program test_kinematics
