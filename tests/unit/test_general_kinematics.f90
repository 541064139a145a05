!> Tests of the general mechanism's rigid-body kinematics (modules
!> general_mechanism, general_deck, general_kinematics, motion_profile):
!> the planar four-bar and slider-crank against module kinematics, the
!> RSSR against module spatial_kinematics, a five-bar with two drivers and a
!> spatial slider-crank against closed forms and central differences, a
!> two-link arm driven by tables against its forward kinematics, the spline,
!> and the mobility, assembly and toggle diagnoses.
module test_general_kinematics_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use kinematics, only: kinematics_t
  use spatial_kinematics, only: spatial_fourbar_t, spatial_pose_t, spatial_fourbar_init, spatial_fourbar_solve
  use motion_profile, only: motion_profile_t, make_spline, motion_value
  use general_mechanism, only: general_mechanism_t
  use general_kinematics, only: general_kinematics_t
  use general_deck, only: read_general_mechanism
  use kinematics_analysis, only: run_kinematics
  use assertions
  use test_text, only: itoa
  use deck_runner, only: open_deck_text, close_deck_text, scratch_path, run_deck, line_length
  use mechanism_fixtures, only: fourbar_abcd, slider_crank_input
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('fourbar_matches_planar_kinematics_over_a_turn', test_fourbar)
    call run_test('slider_crank_matches_planar_kinematics_over_a_turn', test_slider_crank)
    call run_test('rssr_matches_spatial_kinematics_over_a_turn', test_rssr)
    call run_test('five_bar_two_drivers_closes_and_matches_differences', test_five_bar)
    call run_test('two_link_arm_tables_match_forward_kinematics', test_two_link_arm)
    call run_test('spatial_slider_crank_matches_closed_form', test_spatial_slider_crank)
    call run_test('block_on_prismatic_and_welded_crank_match_planar_kinematics', test_block_and_weld)
    call run_test('spatial_point_on_line_and_weld_match_closed_form_and_differences', test_spatial_point_on_line)
    call run_test('spline_is_c2_exact_for_lines_and_close_to_sine', test_spline)
    call run_test('under_driven_names_the_free_link', test_under_driven)
    call run_test('over_driven_names_the_driver', test_over_driven)
    call run_test('redundant_planar_loop_in_space_is_refused', test_redundant)
    call run_test('non_assembly_is_reported_with_time_and_joint', test_non_assembly)
    call run_test('toggle_is_reported_with_time_and_joints', test_toggle)
    call run_test('toggle_passed_between_samples_is_reported', test_toggle_passed)
    call run_test('kinematics_analysis_writes_the_table', test_analysis_table)
  end subroutine run_all

  ! ------------------------------------------------------------ helpers

  function num(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: b
    write(b, '(es24.16e3)') x
    s = trim(adjustl(b))
  end function num

  function vec(x) result(s)
    real(dp), intent(in) :: x(:)
    character(len=:), allocatable :: s
    integer :: i
    s = num(x(1))
    do i = 2, size(x)
      s = s//', '//num(x(i))
    end do
  end function vec

  !> Read a &general_mechanism deck body ('|' between lines) and set up its kinematics.
  subroutine make(body, gk, err)
    character(len=*), intent(in) :: body
    type(general_kinematics_t), intent(out) :: gk
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(general_mechanism_t) :: mech
    character(len=:), allocatable :: stem
    stem = scratch_path('general_kin')
    call open_deck_text(stem, "&run|  analysis = 'kinematics'|/|&general_mechanism|"//body//"|/", deck, err)
    if (.not. err%failed()) call read_general_mechanism(deck, mech, gk, err)
    call close_deck_text(stem, deck)
  end subroutine make

  subroutine make_ok(body, gk)
    character(len=*), intent(in) :: body
    type(general_kinematics_t), intent(out) :: gk
    type(error_t) :: err
    call make(body, gk, err)
    call assert_true(.not. err%failed(), 'set-up: '//err%text())
    if (err%failed()) error stop 'test mechanism refused'
  end subroutine make_ok

  !> The four-bar of inputs/fourbar_150_linear.nml: crank 5 at A = (0, 0),
  !> coupler 11, rocker 10.5 from D = (10, 0); the crank drawn along X.
  function fourbar_body(drivers) result(s)
    character(len=*), intent(in) :: drivers
    character(len=:), allocatable :: s
    s = "n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|joint_kind = 4*'revolute'|joint_ground = T, F, F, T|"// &
        "joint_x = 0.0, 5.0, 8.5, 10.0|joint_y = 0.0, 0.0, 10.0, 0.0|n_links = 3|"// &
        "link_name = 'crank', 'coupler', 'rocker'|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|"// &
        "link_length = 5.0, 11.0, 10.5|"//drivers
  end function fourbar_body

  ! ------------------------------------------------------------ (a) four-bar

  subroutine test_fourbar()
    type(general_kinematics_t) :: gk
    type(kinematics_t) :: kin
    type(mechanism_t) :: mech
    type(mechanism_input_t) :: inp
    type(error_t) :: err
    real(dp) :: t, x(3), v(3), a(3), w
    integer :: k, j
    w = 150.0_dp
    call make_ok(fourbar_body('n_drivers = 1|driver_joint = 1|driver_rate = 150.0'), gk)
    call assert_equal(gk%mobility, 1, 'four-bar mobility')
    call assert_equal(gk%kutzbach, 1, 'four-bar Kutzbach count')
    inp = fourbar_abcd(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%omega = w
    call build_mechanism(inp, mech, err)
    call kin%init(mech, err)
    call assert_true(.not. err%failed(), err%text())
    do k = 0, 72
      t = two_pi/w*k/72.0_dp
      call gk%solve(t, err)
      call kin%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      ! joint j = B (coupler end 1) and C (coupler end 2)
      do j = 2, 3
        call gk%point(2, gk%mech%joints(j)%point(:, merge(2, 1, j == 2)), x, v, a)
        call assert_all_close(x(1:2), kin%joint_position(j), 0.0_dp, 1.0e-10_dp*10.0_dp, 'four-bar position')
        call assert_all_close(v(1:2), kin%joint_velocity(j), 0.0_dp, 1.0e-10_dp*10.0_dp*w, 'four-bar velocity')
        call assert_all_close(a(1:2), kin%joint_acceleration(j), 0.0_dp, 1.0e-10_dp*10.0_dp*w*w, &
                              'four-bar acceleration')
      end do
    end do
    call assert_true(gk%total_iterations < 6*gk%n_solutions, 'Newton from the predictor takes few iterations')
  end subroutine test_fourbar

  ! ------------------------------------------------------------ (b) slider-crank

  subroutine test_slider_crank()
    type(general_kinematics_t) :: gk
    type(kinematics_t) :: kin
    type(mechanism_t) :: mech
    type(mechanism_input_t) :: inp
    type(error_t) :: err
    real(dp) :: t, x(3), v(3), a(3), w, s, sd, sdd
    integer :: k
    w = 100.0_dp
    ! crank 2 at A, rod 6 to the slider C on a guide along X through (0, 0.5)
    call make_ok("n_joints = 3|joint_name = 'A', 'B', 'C'|joint_kind = 'revolute', 'revolute', 'slider'|"// &
      "joint_ground = T, F, T|joint_x = 0.0, 2.0, 7.9|joint_y = 0.0, 0.0, 0.5|joint_axis(:, 3) = 1.0, 0.0, 0.0|"// &
      "n_links = 2|link_name = 'crank', 'rod'|link_joint1 = 1, 2|link_joint2 = 2, 3|link_length = 2.0, 6.0|"// &
      "n_drivers = 1|driver_joint = 1|driver_rate = 100.0", gk)
    inp = slider_crank_input(2.0_dp, 6.0_dp, 0.5_dp)
    inp%omega = w
    call build_mechanism(inp, mech, err)
    call kin%init(mech, err)
    call assert_true(.not. err%failed(), err%text())
    do k = 0, 72
      t = two_pi/w*k/72.0_dp
      call gk%solve(t, err)
      call kin%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(2, gk%mech%joints(3)%point(:, 2), x, v, a)
      call assert_all_close(x(1:2), kin%joint_position(3), 0.0_dp, 1.0e-10_dp*6.0_dp, 'slider position')
      call assert_all_close(v(1:2), kin%joint_velocity(3), 0.0_dp, 1.0e-10_dp*6.0_dp*w, 'slider velocity')
      call assert_all_close(a(1:2), kin%joint_acceleration(3), 0.0_dp, 1.0e-10_dp*6.0_dp*w*w, 'slider acceleration')
      ! the slide: the block's distance along X from the guide's point, drawn at x = 7.9
      call gk%joint_value(3, 0.0_dp, s, sd, sdd)
      call assert_close(s, dot_product(kin%joint_position(3), [1.0_dp, 0.0_dp]) - 7.9_dp, 1.0e-9_dp, 'slide value')
      call assert_close(sd, dot_product(kin%joint_velocity(3), [1.0_dp, 0.0_dp]), 1.0e-9_dp*w, 'slide rate')
      call assert_close(sdd, dot_product(kin%joint_acceleration(3), [1.0_dp, 0.0_dp]), 1.0e-9_dp*w*w, 'slide acceleration')
    end do
  end subroutine test_slider_crank

  ! ------------------------------------------------------------ (c) RSSR

  subroutine test_rssr()
    type(general_kinematics_t) :: gk
    type(spatial_fourbar_t) :: sf
    type(spatial_pose_t) :: pose
    type(error_t) :: err
    real(dp) :: t, x(3), v(3), a(3), w
    integer :: k
    w = 100.0_dp
    ! inputs/spatial_rssr_100.nml: crank about Z (pin at (6, 0, 0)), rocker 12
    ! about X from (0, 20, 12), coupler 24, branch 1, spherical B and C
    call spatial_fourbar_init(sf, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [6.0_dp, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 20.0_dp, 12.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 12.0_dp, 24.0_dp, 1, err)
    call spatial_fourbar_solve(sf, 0.0_dp, w, 0.0_dp, pose, err)
    call assert_true(.not. err%failed(), err%text())
    ! the drawing: C near (not at) its place on branch 1, in the rocker's plane
    call make_ok("space = 'spatial'|n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|"// &
      "joint_kind = 'revolute', 'spherical', 'spherical', 'revolute'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, 6.0, 0.0, 0.0|joint_y = 0.0, 0.0, "//num(pose%c(2) - 0.2_dp)// &
      ", 20.0|joint_z = 0.0, 0.0, "//num(pose%c(3) + 0.1_dp)//", 12.0|"// &
      "joint_axis(:, 1) = 0.0, 0.0, 1.0|joint_axis(:, 4) = 1.0, 0.0, 0.0|n_links = 3|"// &
      "link_name = 'crank', 'coupler', 'rocker'|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|"// &
      "link_length = 6.0, 24.0, 12.0|n_drivers = 1|driver_joint = 1|driver_rate = 100.0", gk)
    call assert_equal(gk%kutzbach, 1, 'RSSR Kutzbach count with the coupler''s idle spin')
    call assert_equal(gk%mobility, 1, 'RSSR mobility')
    do k = 0, 72
      t = two_pi/w*k/72.0_dp
      call gk%solve(t, err)
      call spatial_fourbar_solve(sf, w*t, w, 0.0_dp, pose, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(2, gk%mech%joints(3)%point(:, 1), x, v, a)
      call assert_all_close(x, pose%c, 0.0_dp, 1.0e-10_dp*24.0_dp, 'RSSR C position')
      call assert_all_close(v, pose%c_d, 0.0_dp, 1.0e-10_dp*24.0_dp*w, 'RSSR C velocity')
      call assert_all_close(a, pose%c_dd, 0.0_dp, 1.0e-10_dp*24.0_dp*w*w, 'RSSR C acceleration')
      call gk%body_motion(3, v, a)
      call assert_all_close(v, pose%omega(:, 3), 0.0_dp, 1.0e-10_dp*w, 'RSSR rocker angular velocity')
      call assert_all_close(a, pose%alpha(:, 3), 0.0_dp, 1.0e-10_dp*w*w, 'RSSR rocker angular acceleration')
    end do
  end subroutine test_rssr

  ! ------------------------------------------------------------ (d) five-bar

  !> Cranks 2 at A = (0, 0) and 2.5 at E = (4, 0), couplers 4 and 4.5 to C;
  !> the cranks turn at 10 and -7 rad/s.
  subroutine test_five_bar()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    real(dp) :: t, h, xc(3), vc(3), ac(3), xb(3), vb(3), ab(3), xd(3), vd(3), ad(3)
    real(dp) :: xp(3), vp(3), ap(3), xm(3), vm(3), am(3)
    integer :: k
    call make_ok("n_joints = 5|joint_name = 'A', 'B', 'C', 'D', 'E'|joint_kind = 5*'revolute'|"// &
      "joint_ground = T, F, F, F, T|joint_x = 0.0, 2.0, 3.0, 6.5, 4.0|joint_y = 0.0, 0.0, 3.5, 0.0, 0.0|"// &
      "n_links = 4|link_name = 'crank1', 'coupler1', 'coupler2', 'crank2'|link_joint1 = 1, 2, 4, 5|"// &
      "link_joint2 = 2, 3, 3, 4|link_length = 2.0, 4.0, 4.5, 2.5|"// &
      "n_drivers = 2|driver_joint = 1, 5|driver_rate = 10.0, -7.0", gk)
    call assert_equal(gk%mobility, 2, 'five-bar mobility')
    h = 1.0e-5_dp
    do k = 0, 40
      t = 0.02_dp*k
      call gk%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(2, gk%mech%joints(3)%point(:, 1), xc, vc, ac)
      call gk%point(2, gk%mech%joints(2)%point(:, 2), xb, vb, ab)
      call gk%point(3, gk%mech%joints(4)%point(:, 1), xd, vd, ad)
      call assert_close(norm2(xc - xb), 4.0_dp, 1.0e-12_dp, 'five-bar |BC|')
      call assert_close(norm2(xc - xd), 4.5_dp, 1.0e-12_dp, 'five-bar |DC|')
      call gk%point(3, gk%mech%joints(3)%point(:, 2), xp, vp, ap)
      call assert_all_close(xp, xc, 0.0_dp, 1.0e-12_dp, 'five-bar loop closes at C')
      ! central differences in time, solved fresh on each side
      call gk%solve(t + h, err)
      call gk%point(2, gk%mech%joints(3)%point(:, 1), xp, vp, ap)
      call gk%solve(t - h, err)
      call gk%point(2, gk%mech%joints(3)%point(:, 1), xm, vm, am)
      call gk%solve(t, err)
      call assert_all_close(vc, (xp - xm)/(2.0_dp*h), 0.0_dp, 1.0e-5_dp*maxval(abs(vc)) + 1.0e-6_dp, &
                            'five-bar velocity by differences')
      call assert_all_close(ac, (vp - vm)/(2.0_dp*h), 0.0_dp, 1.0e-5_dp*maxval(abs(ac)) + 1.0e-5_dp, &
                            'five-bar acceleration by differences')
    end do
  end subroutine test_five_bar

  ! ------------------------------------------------------------ (e) two-link arm

  subroutine test_two_link_arm()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    character(len=:), allocatable :: tt, v1, v2
    real(dp) :: t, x(3), v(3), a(3), q1, q1d, q1dd, q2, q2d, q2dd, c1, s1, c12, s12, w12, e12
    real(dp) :: xe(2), ve(2), ae(2)
    integer :: k
    ! shoulder and elbow angle histories (deg) at 21 points over 2 s
    tt = vec([(0.1_dp*k, k = 0, 20)])
    v1 = vec([(30.0_dp*sin(1.5_dp*0.1_dp*k), k = 0, 20)])
    v2 = vec([(45.0_dp*(1.0_dp - cos(2.0_dp*0.1_dp*k)), k = 0, 20)])
    call make_ok("n_joints = 3|joint_name = 'S', 'E', 'T'|joint_kind = 'revolute', 'revolute', 'free'|"// &
      "joint_ground = T, F, F|joint_x = 0.0, 1.0, 1.8|n_links = 2|link_name = 'upper', 'fore'|"// &
      "link_joint1 = 1, 2|link_joint2 = 2, 3|n_drivers = 2|driver_joint = 1, 2|driver_profile = 2*'table'|"// &
      "driver_n_table = 21, 21|driver_table_t(1:21, 1) = "//tt//"|driver_table_value(1:21, 1) = "//v1//"|"// &
      "driver_table_t(1:21, 2) = "//tt//"|driver_table_value(1:21, 2) = "//v2, gk)
    do k = 0, 50
      t = 0.04_dp*k
      call gk%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call motion_value(gk%mech%drivers(1)%motion, t, q1, q1d, q1dd)
      call motion_value(gk%mech%drivers(2)%motion, t, q2, q2d, q2dd)
      c1 = cos(q1)
      s1 = sin(q1)
      c12 = cos(q1 + q2)
      s12 = sin(q1 + q2)
      w12 = q1d + q2d
      e12 = q1dd + q2dd
      xe = [c1 + 0.8_dp*c12, s1 + 0.8_dp*s12]
      ve = [-s1*q1d - 0.8_dp*s12*w12, c1*q1d + 0.8_dp*c12*w12]
      ae = [-c1*q1d**2 - s1*q1dd - 0.8_dp*(c12*w12**2 + s12*e12), -s1*q1d**2 + c1*q1dd - 0.8_dp*(s12*w12**2 - c12*e12)]
      call gk%point(2, gk%mech%joints(3)%point(:, 1), x, v, a)
      call assert_all_close(x(1:2), xe, 0.0_dp, 1.0e-12_dp, 'arm tip position')
      call assert_all_close(v(1:2), ve, 0.0_dp, 1.0e-11_dp, 'arm tip velocity')
      call assert_all_close(a(1:2), ae, 0.0_dp, 1.0e-10_dp, 'arm tip acceleration')
      ! the table follows the sampled history closely (natural spline, h = 0.1 s)
      if (t > 0.3_dp .and. t < 1.7_dp) call assert_close(q1, 30.0_dp*pi/180.0_dp*sin(1.5_dp*t), 2.0e-4_dp, &
                                                          'shoulder table near its history')
    end do
  end subroutine test_two_link_arm

  ! ------------------------------------------------------------ (f) spatial slider-crank

  !> Crank 1 about Z at the origin; rod 4 from the crank pin B (spherical) to
  !> the block C (universal); the block slides along u = (1, 0, 0.5)/|.| through
  !> P0 = (0, 0.5, 2), out of the crank's plane.  Closed form: C = P0 + s u with
  !> |C - B| = l: s = -u.d + sqrt((u.d)^2 - |d|^2 + l^2), d = P0 - B; rates from
  !> (C - B).(u s' - B') = 0 and its derivative.
  subroutine test_spatial_slider_crank()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    real(dp) :: u(3), p0(3), w, t, th, b(3), bd(3), bdd(3), d(3), s, sd, sdd, c(3), cb(3), s0
    real(dp) :: x(3), v(3), a(3), axis2(3), axis1(3), jv, jvd, jvdd
    integer :: k
    w = 50.0_dp
    u = [1.0_dp, 0.0_dp, 0.5_dp]/norm2([1.0_dp, 0.0_dp, 0.5_dp])
    p0 = [0.0_dp, 0.5_dp, 2.0_dp]
    d = p0 - [1.0_dp, 0.0_dp, 0.0_dp]
    s0 = -dot_product(u, d) + sqrt(dot_product(u, d)**2 - dot_product(d, d) + 16.0_dp)
    c = p0 + s0*u
    axis2 = cross3(u, [0.0_dp, 0.0_dp, 1.0_dp])
    axis2 = axis2/norm2(axis2)
    axis1 = cross3(c - [1.0_dp, 0.0_dp, 0.0_dp], axis2)
    axis1 = axis1/norm2(axis1)
    call make_ok("space = 'spatial'|n_joints = 4|joint_name = 'A', 'B', 'C', 'P'|"// &
      "joint_kind = 'revolute', 'spherical', 'universal', 'prismatic'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, 1.0, "//num(c(1))//", "//num(p0(1))//"|joint_y = 0.0, 0.0, "//num(c(2))//", "//num(p0(2))// &
      "|joint_z = 0.0, 0.0, "//num(c(3))//", "//num(p0(3))//"|joint_axis(:, 1) = 0.0, 0.0, 1.0|"// &
      "joint_axis(:, 3) = "//vec(axis1)//"|joint_axis2(:, 3) = "//vec(axis2)//"|joint_axis(:, 4) = "//vec(u)//"|"// &
      "n_links = 3|link_name = 'crank', 'rod', 'block'|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|"// &
      "n_drivers = 1|driver_joint = 1|driver_rate = 50.0", gk)
    call assert_equal(gk%kutzbach, 1, 'spatial slider-crank Kutzbach count')
    call assert_equal(gk%mobility, 1, 'spatial slider-crank mobility')
    do k = 0, 72
      t = two_pi/w*k/72.0_dp
      th = w*t
      b = [cos(th), sin(th), 0.0_dp]
      bd = w*[-sin(th), cos(th), 0.0_dp]
      bdd = -w*w*b
      d = p0 - b
      s = -dot_product(u, d) + sqrt(dot_product(u, d)**2 - dot_product(d, d) + 16.0_dp)
      c = p0 + s*u
      cb = c - b
      sd = dot_product(cb, bd)/dot_product(cb, u)
      sdd = (dot_product(cb, bdd) - dot_product(u*sd - bd, u*sd - bd))/dot_product(cb, u)
      call gk%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(3, gk%mech%joints(3)%point(:, 2), x, v, a)
      call assert_all_close(x, c, 0.0_dp, 1.0e-11_dp, 'block position')
      call assert_all_close(v, sd*u, 0.0_dp, 1.0e-11_dp*w, 'block velocity')
      call assert_all_close(a, sdd*u, 0.0_dp, 1.0e-11_dp*w*w, 'block acceleration')
      call gk%joint_value(4, 0.0_dp, jv, jvd, jvdd)
      call assert_close(jv, s - s0, 1.0e-11_dp, 'slide of the prismatic joint from the drawing')
      call assert_close(jvd, sd, 1.0e-11_dp*w, 'slide rate')
      call assert_close(jvdd, sdd, 1.0e-11_dp*w*w, 'slide acceleration')
      call gk%joint_value(1, w*t, jv, jvd, jvdd)
      call assert_close(jv, w*t, 1.0e-11_dp, 'crank rotation')
      call assert_close(jvd, w, 1.0e-11_dp*w, 'crank rate')
    end do
  end subroutine test_spatial_slider_crank

  pure function cross3(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross3

  ! ------------------------------------------------------------ more joint kinds

  !> The slider-crank of test (b) with the block as a body on a prismatic
  !> joint, and the crank made of two halves welded at M: the same motion as
  !> module kinematics' slider-crank.
  subroutine test_block_and_weld()
    type(general_kinematics_t) :: gk
    type(kinematics_t) :: kin
    type(mechanism_t) :: mech
    type(mechanism_input_t) :: inp
    type(error_t) :: err
    real(dp) :: t, x(3), v(3), a(3), w
    integer :: k
    w = 100.0_dp
    call make_ok("n_joints = 5|joint_name = 'A', 'M', 'B', 'C', 'P'|"// &
      "joint_kind = 'revolute', 'weld', 'revolute', 'revolute', 'prismatic'|joint_ground = T, F, F, F, T|"// &
      "joint_x = 0.0, 1.0, 2.0, 7.9, 7.9|joint_y = 0.0, 0.0, 0.0, 0.5, 0.5|joint_axis(:, 5) = 1.0, 0.0, 0.0|"// &
      "n_links = 4|link_name = 'crank1', 'crank2', 'rod', 'block'|link_joint1 = 1, 2, 3, 5|"// &
      "link_joint2 = 2, 3, 4, 4|link_length = 1.0, 1.0, 6.0, 0.0|n_drivers = 1|driver_joint = 1|driver_rate = 100.0", gk)
    call assert_equal(gk%mobility, 1, 'block-and-weld slider-crank mobility')
    inp = slider_crank_input(2.0_dp, 6.0_dp, 0.5_dp)
    inp%omega = w
    call build_mechanism(inp, mech, err)
    call kin%init(mech, err)
    do k = 0, 72
      t = two_pi/w*k/72.0_dp
      call gk%solve(t, err)
      call kin%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(4, [0.0_dp, 0.0_dp, 0.0_dp], x, v, a)
      call assert_all_close(x(1:2), kin%joint_position(3), 0.0_dp, 1.0e-10_dp*6.0_dp, 'block position')
      call assert_all_close(v(1:2), kin%joint_velocity(3), 0.0_dp, 1.0e-10_dp*6.0_dp*w, 'block velocity')
      call assert_all_close(a(1:2), kin%joint_acceleration(3), 0.0_dp, 1.0e-10_dp*6.0_dp*w*w, 'block acceleration')
      call gk%body_motion(4, v, a)
      call assert_close(v(3), 0.0_dp, 1.0e-10_dp*w, 'the block does not turn')
      call gk%point(2, [1.0_dp, 0.0_dp, 0.0_dp], x, v, a)
      call assert_all_close(x(1:2), kin%joint_position(2), 0.0_dp, 1.0e-10_dp*6.0_dp, 'welded crank''s pin')
    end do
  end subroutine test_block_and_weld

  !> The spatial slider-crank of test (f) with the rod's end on a spatial
  !> slider joint (a point on the guide line, rotation free: the rod spins
  !> idly between it and the spherical joint) and the crank of two halves
  !> welded at M.  Driven by the crank: the closed form; driven by the slide
  !> (the crank passive): loop closure and central differences.
  subroutine test_spatial_point_on_line()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    real(dp) :: u(3), p0(3), w, t, th, b(3), d(3), s, c(3), x(3), v(3), a(3), s0, h
    real(dp) :: xb(3), vb(3), ab(3), xp(3), vp(3), ap(3), xm(3), vm(3), am(3)
    character(len=:), allocatable :: body
    integer :: k
    w = 50.0_dp
    u = [1.0_dp, 0.0_dp, 0.5_dp]/norm2([1.0_dp, 0.0_dp, 0.5_dp])
    p0 = [0.0_dp, 0.5_dp, 2.0_dp]
    d = p0 - [1.0_dp, 0.0_dp, 0.0_dp]
    s0 = -dot_product(u, d) + sqrt(dot_product(u, d)**2 - dot_product(d, d) + 16.0_dp)
    c = p0 + s0*u
    body = "space = 'spatial'|n_joints = 4|joint_name = 'A', 'M', 'B', 'C'|"// &
      "joint_kind = 'revolute', 'weld', 'spherical', 'slider'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, 0.5, 1.0, "//num(c(1))//"|joint_y = 0.0, 0.0, 0.0, "//num(c(2))// &
      "|joint_z = 0.0, 0.0, 0.0, "//num(c(3))//"|joint_axis(:, 4) = "//vec(u)//"|"// &
      "n_links = 3|link_name = 'crank1', 'crank2', 'rod'|link_joint1 = 1, 2, 3|link_joint2 = 2, 3, 4|n_drivers = 1|"
    call make_ok(body//"driver_joint = 1|driver_rate = 50.0", gk)
    call assert_equal(gk%kutzbach, 1, 'point-on-line slider-crank: Kutzbach count with the idle spin')
    call assert_equal(gk%mobility, 1, 'point-on-line slider-crank mobility')
    do k = 0, 36
      t = two_pi/w*k/36.0_dp
      th = w*t
      b = [cos(th), sin(th), 0.0_dp]
      d = p0 - b
      s = -dot_product(u, d) + sqrt(dot_product(u, d)**2 - dot_product(d, d) + 16.0_dp)
      call gk%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(3, gk%mech%joints(4)%point(:, 2), x, v, a)
      call assert_all_close(x, p0 + s*u, 0.0_dp, 1.0e-11_dp, 'rod end on the guide')
    end do
    ! driven by the slide at -0.5 per s for 1 s, drawn with the crank at 90 deg
    ! (the slide's range is [1.93, 3.29], from 2.65 here): the crank follows
    d = p0 - [0.0_dp, 1.0_dp, 0.0_dp]
    s0 = -dot_product(u, d) + sqrt(dot_product(u, d)**2 - dot_product(d, d) + 16.0_dp)
    c = p0 + s0*u
    call make_ok("space = 'spatial'|n_joints = 4|joint_name = 'A', 'M', 'B', 'C'|"// &
      "joint_kind = 'revolute', 'weld', 'spherical', 'slider'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, 0.0, 0.0, "//num(c(1))//"|joint_y = 0.0, 0.5, 1.0, "//num(c(2))// &
      "|joint_z = 0.0, 0.0, 0.0, "//num(c(3))//"|joint_axis(:, 4) = "//vec(u)//"|"// &
      "n_links = 3|link_joint1 = 1, 2, 3|link_joint2 = 2, 3, 4|n_drivers = 1|driver_joint = 4|driver_rate = -0.5", gk)
    h = 1.0e-5_dp
    do k = 0, 10
      t = 0.1_dp*k
      call gk%solve(t, err)
      call assert_true(.not. err%failed(), 'solve: '//err%text())
      if (err%failed()) return
      call gk%point(3, gk%mech%joints(4)%point(:, 2), x, v, a)
      call gk%point(3, gk%mech%joints(3)%point(:, 2), xb, vb, ab)
      call assert_all_close(x, c - 0.5_dp*t*u, 0.0_dp, 1.0e-11_dp, 'the slide follows its driver')
      call assert_close(norm2(x - xb), 4.0_dp, 1.0e-11_dp, 'rod length')
      call assert_close(norm2(xb(1:2)), 1.0_dp, 1.0e-11_dp, 'crank pin on its circle')
      call assert_close(xb(3), 0.0_dp, 1.0e-11_dp, 'crank pin in its plane')
      ! central differences: truncation (h^2/6 of the third derivative) and
      ! Newton's 1e-12 over 2h stay below 1e-6 of the rates here
      call gk%solve(t + h, err)
      call gk%point(3, gk%mech%joints(3)%point(:, 2), xp, vp, ap)
      call gk%solve(t - h, err)
      call gk%point(3, gk%mech%joints(3)%point(:, 2), xm, vm, am)
      call gk%solve(t, err)
      call assert_all_close(vb, (xp - xm)/(2.0_dp*h), 0.0_dp, 1.0e-6_dp*maxval(abs(vb)) + 1.0e-9_dp, &
                            'crank pin velocity by differences')
      call assert_all_close(ab, (vp - vm)/(2.0_dp*h), 0.0_dp, 1.0e-6_dp*maxval(abs(ab)) + 1.0e-8_dp, &
                            'crank pin acceleration by differences')
    end do
  end subroutine test_spatial_point_on_line

  ! ------------------------------------------------------------ spline

  subroutine test_spline()
    type(motion_profile_t) :: p
    real(dp) :: tk(41), v, vd, vdd, vl, vdl, vddl, t
    integer :: k
    tk = [(0.05_dp*k + 0.01_dp*mod(k, 3), k = 0, 40)]
    call make_spline(tk, 2.0_dp - 3.0_dp*tk, p)
    do k = 0, 30
      t = tk(1) + (tk(41) - tk(1))*k/30.0_dp
      call motion_value(p, t, v, vd, vdd)
      call assert_close(v, 2.0_dp - 3.0_dp*t, 1.0e-13_dp, 'spline of a line: value')
      call assert_close(vd, -3.0_dp, 1.0e-12_dp, 'spline of a line: slope')
      call assert_close(vdd, 0.0_dp, 1.0e-10_dp, 'spline of a line: curvature')
    end do
    call make_spline(tk, sin(tk), p)
    do k = 1, 40
      call motion_value(p, tk(k), v, vd, vdd)
      call assert_close(v, sin(tk(k)), 1.0e-15_dp, 'spline through its knots')
    end do
    do k = 5, 35    ! C2 at the knots: the two sides agree
      call motion_value(p, tk(k) - 1.0e-9_dp, vl, vdl, vddl)
      call motion_value(p, tk(k) + 1.0e-9_dp, v, vd, vdd)
      call assert_close(vd, vdl, 1.0e-7_dp, 'spline slope continuous')
      call assert_close(vdd, vddl, 1.0e-7_dp, 'spline curvature continuous')
      t = 0.5_dp*(tk(k) + tk(k + 1))
      call motion_value(p, t, v, vd, vdd)
      call assert_close(v, sin(t), 2.0e-6_dp, 'spline interior value (h^4 error)')
      call assert_close(vd, cos(t), 1.0e-4_dp, 'spline interior slope')
    end do
  end subroutine test_spline

  ! ------------------------------------------------------------ (g) errors

  subroutine test_under_driven()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    call make(fourbar_body('n_drivers = 0'), gk, err)
    call assert_error(err, 2, 'under-driven', 'four-bar without a driver', '1 freedoms and 0 drivers')
    call err%clear()
    ! a five-bar with one driver: a crank or coupler of the loop is named
    call make("n_joints = 5|joint_name = 'A', 'B', 'C', 'D', 'E'|joint_kind = 5*'revolute'|"// &
      "joint_ground = T, F, F, F, T|joint_x = 0.0, 2.0, 3.0, 6.5, 4.0|joint_y = 0.0, 0.0, 3.5, 0.0, 0.0|"// &
      "n_links = 4|link_name = 'crank1', 'coupler1', 'coupler2', 'crank2'|link_joint1 = 1, 2, 4, 5|"// &
      "link_joint2 = 2, 3, 3, 4|n_drivers = 1|driver_joint = 1|driver_rate = 1.0", gk, err)
    call assert_error(err, 2, 'under-driven', 'five-bar with one driver', 'can still move')
    call assert_true(index(err%text(), 'general_mechanism') > 0, 'names the group: '//err%text())
  end subroutine test_under_driven

  subroutine test_over_driven()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    call make(fourbar_body('n_drivers = 2|driver_joint = 1, 4|driver_rate = 1.0, 2.0'), gk, err)
    call assert_error(err, 2, 'over-driven', 'four-bar with two drivers', 'driver 2 (joint ''D'')')
    call err%clear()
    ! in space, where the Euler parameters' rows come after the drivers' in the set
    call make("space = 'spatial'|n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|"// &
      "joint_kind = 'revolute', 'spherical', 'spherical', 'revolute'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, 6.0, 0.0, 0.0|joint_y = 0.0, 0.0, 11.0, 20.0|joint_z = 0.0, 0.0, 20.0, 12.0|"// &
      "joint_axis(:, 4) = 1.0, 0.0, 0.0|n_links = 3|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|"// &
      "link_length = 6.0, 24.0, 12.0|n_drivers = 2|driver_joint = 1, 4|driver_rate = 1.0, 1.0", gk, err)
    call assert_error(err, 2, 'over-driven', 'RSSR with two drivers', 'driver 2 (joint ''D'')')
  end subroutine test_over_driven

  !> A planar four-bar drawn in space with revolute joints: the loop's
  !> constraints repeat (Kutzbach count -2, one freedom by the rank).
  subroutine test_redundant()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    call make("space = 'spatial'|"//fourbar_body('n_drivers = 1|driver_joint = 1|driver_rate = 1.0'), gk, err)
    call assert_error(err, 2, 'redundant constraints', 'planar four-bar in space', 'Kutzbach count gives -2')
  end subroutine test_redundant

  !> A crank of 8 with coupler 7, rocker 6, ground 10 cannot turn round:
  !> |BD| passes coupler + rocker = 13 at 91.8 deg.
  subroutine test_non_assembly()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    integer :: k
    call make_ok("n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|joint_kind = 4*'revolute'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, 8.0, 12.25, 10.0|joint_y = 0.0, 0.0, 5.5, 0.0|n_links = 3|link_joint1 = 1, 2, 4|"// &
      "link_joint2 = 2, 3, 3|link_length = 8.0, 7.0, 6.0|n_drivers = 1|driver_joint = 1|driver_rate = 1.0", gk)
    do k = 0, 360
      call gk%solve(k*pi/180.0_dp, err)
      if (err%failed()) exit
    end do
    call assert_error(err, 3, 'does not assemble at t = ', 'non-Grashof crank', 'joint ''')
    call assert_true(k == 92, 'assembles up to 91.8 deg: stopped at step '//itoa(k))
  end subroutine test_non_assembly

  !> A slider-crank (crank 2, rod 6) driven by its slider at 1 per s from
  !> x = 7: it reaches the outer dead centre x = 8 at t = 1 s.
  subroutine test_toggle()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    integer :: k
    call make_ok("n_joints = 3|joint_name = 'A', 'B', 'C'|joint_kind = 'revolute', 'revolute', 'slider'|"// &
      "joint_ground = T, F, T|joint_x = 0.0, 1.2142857, 7.0|joint_y = 0.0, 1.5890, 0.0|"// &
      "joint_axis(:, 3) = 1.0, 0.0, 0.0|n_links = 2|link_joint1 = 1, 2|link_joint2 = 2, 3|link_length = 2.0, 6.0|"// &
      "n_drivers = 1|driver_joint = 3|driver_rate = 1.0", gk)
    do k = 0, 10
      call gk%solve(0.1_dp*k, err)
      if (err%failed()) exit
    end do
    call assert_equal(k, 10, 'runs up to the dead centre')
    call assert_error(err, 3, 'toggle', 'slider-driven crank at its dead centre', 't = 1')
    call assert_true(index(err%text(), '''B''') > 0, 'names the joints: '//err%text())
    ! a drawing at the dead centre is refused before any solution
    call err%clear()
    call make("n_joints = 3|joint_name = 'A', 'B', 'C'|joint_kind = 'revolute', 'revolute', 'slider'|"// &
      "joint_ground = T, F, T|joint_x = 0.0, 2.0, 8.0|joint_axis(:, 3) = 1.0, 0.0, 0.0|n_links = 2|"// &
      "link_joint1 = 1, 2|link_joint2 = 2, 3|n_drivers = 1|driver_joint = 3|driver_rate = -1.0", gk, err)
    call assert_error(err, 2, 'dead centre', 'a drawing at the dead centre')
  end subroutine test_toggle

  !> A parallelogram four-bar (crank 3, coupler 10, rocker 3, ground 10) is
  !> singular where all its links line up (crank angle 180 deg): sampled from
  !> 5 deg in steps of 7.7 deg, the sign change of the Jacobian's determinant
  !> between 174.4 and 182.1 deg is reported as a toggle passed.
  subroutine test_toggle_passed()
    type(general_kinematics_t) :: gk
    type(error_t) :: err
    real(dp) :: c5, s5
    integer :: k
    c5 = 3.0_dp*cos(5.0_dp*pi/180.0_dp)
    s5 = 3.0_dp*sin(5.0_dp*pi/180.0_dp)
    call make_ok("n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|joint_kind = 4*'revolute'|joint_ground = T, F, F, T|"// &
      "joint_x = 0.0, "//num(c5)//", "//num(10.0_dp + c5)//", 10.0|joint_y = 0.0, "//num(s5)//", "//num(s5)//", 0.0|"// &
      "n_links = 3|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|n_drivers = 1|driver_joint = 1|driver_rate = 1.0", gk)
    do k = 0, 40
      call gk%solve(k*7.7_dp*pi/180.0_dp, err)
      if (err%failed()) exit
    end do
    call assert_equal(k, 23, 'stops at the first sample past 180 deg')
    call assert_error(err, 3, 'passed a toggle', 'parallelogram through its flat position', 'between t = 2.9565878 and 3.0909781 s')
  end subroutine test_toggle_passed

  !> The analysis: header, columns and one row per output time.
  subroutine test_analysis_table()
    character(len=line_length), allocatable :: lines(:)
    type(error_t) :: err
    integer :: k, rows
    call run_deck(run_kinematics, scratch_path('general_table'), "&general_mechanism|"// &
      fourbar_body('n_drivers = 1|driver_joint = 1|driver_rate = 150.0')//"|/|&kinematics|t_end = 0.01|n_steps = 4|/", &
      err, lines)
    call assert_true(.not. err%failed(), err%text())
    rows = 0
    do k = 1, size(lines)
      if (lines(k)(1:1) /= '#') rows = rows + 1
    end do
    call assert_equal(rows, 5, 'one row per output time')
    call assert_true(any(index(lines, 'A_deg') > 0) .and. any(index(lines, 'rocker_alpha') > 0), 'column names')
    call assert_true(any(index(lines, 'cost: newton_iterations') > 0), 'cost footer')
  end subroutine test_analysis_table
end module test_general_kinematics_suite

program test_general_kinematics
  use test_general_kinematics_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_general_kinematics')
end program test_general_kinematics
