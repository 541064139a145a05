!> Tests of the linkage description (module linkage): defaults, derived
!> section properties, validation messages, mobility count, driver profiles,
!> deck reading and echo, header summary and Grashof classification.
module test_linkage_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use linkage
  use linkage_deck, only: read_mechanism, write_mechanism_group
  use linkage_report, only: mechanism_summary, classify_mechanism
  use reference_materials, only: tennant_aluminium_e1
  use assertions
  use mechanism_fixtures, only: fourbar_abcd, slider_crank_input
  use transient_fixtures, only: two_point_beam => beam_input
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('defaults_are_tennant_aluminium_and_section_b_h', test_defaults)
    call run_test('incidence_and_element_numbering', test_incidence)
    call run_test('lengths_from_joint_coordinates', test_lengths_from_coordinates)
    call run_test('invalid_values_are_named_with_their_value', test_invalid_values)
    call run_test('mobility_other_than_one_is_rejected', test_mobility)
    call run_test('constant_profile', test_constant_profile)
    call run_test('spinup_profile_is_smooth_with_fd_derivatives', test_spinup_profile)
    call run_test('deck_is_read_and_echo_reads_back_identically', test_deck_round_trip)
    call run_test('deck_errors_name_variable_and_line', test_deck_errors)
    call run_test('summary_classifies_fourbars_and_slider_cranks', test_summary)
    call run_test('structure_without_driver_accepts_mobility_zero_or_less', test_structure_without_driver)
    call run_test('structure_without_driver_must_not_move_or_turn', test_structure_rules)
  end subroutine run_all

  !> FORMULATION.md §8.1 four-bar: A clamp at (0,0), D ground pin at (10,0).
  function fourbar_input(a, b, c, d) result(inp)
    real(dp), intent(in) :: a, b, c, d
    type(mechanism_input_t) :: inp
    inp = fourbar_abcd(a, b, c, d)
    inp%omega = 150.0_dp
  end function fourbar_input

  subroutine test_defaults()
    type(mechanism_t) :: mech
    type(error_t) :: err
    integer :: i
    call build_mechanism(fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp), mech, err)
    call assert_true(.not. err%failed(), err%text())
    do i = 1, 3
      associate (lk => mech%links(i))
        call assert_close(lk%e1, 10.87e6_dp, 0.0_dp, 'E1 = Tennant A')
        call assert_close(lk%e2, 0.8387e11_dp, 0.0_dp, 'E2 = Tennant B')
        call assert_close(lk%m, 3.0_dp, 0.0_dp, 'exponent m')
        call assert_close(lk%rho, 2.536e-4_dp, 0.0_dp, 'density')
        ! 0.25 x 1.0 section: A = 0.25, I = 0.25/12 = 0.0208333 (FORMULATION.md §8.1)
        call assert_close(lk%area, 0.25_dp, 1.0e-15_dp, 'A = b h')
        call assert_close(lk%inertia, 0.25_dp/12.0_dp, 1.0e-15_dp, 'I = b h^3/12')
        call assert_equal(lk%n_elements, 1, 'one element per link by default')
      end associate
    end do
    call assert_close(mech%driver%omega, 150.0_dp, 0.0_dp, 'omega')
    call assert_equal(mech%branch, branch_open, 'open branch by default')
    call assert_close(mech%length_scale, (5.0_dp + 11.0_dp + 10.5_dp)/3.0_dp, 1.0e-14_dp, 'length scale')
    ! explicit A and I override b, h
    block
      type(mechanism_input_t) :: inp
      inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
      inp%link_section(2) = 'general'
      inp%link_area(2) = 0.3_dp
      inp%link_inertia(2) = 0.05_dp
      inp%link_c(2) = 0.7_dp
      inp%link_b(3) = 0.5_dp
      inp%link_h(3) = 2.0_dp
      call build_mechanism(inp, mech, err)
      call assert_true(.not. err%failed(), err%text())
      call assert_close(mech%links(2)%area, 0.3_dp, 0.0_dp, 'given area')
      call assert_close(mech%links(2)%inertia, 0.05_dp, 0.0_dp, 'given inertia')
      call assert_close(mech%links(2)%fibre, 0.7_dp, 0.0_dp, 'given outer fibre')
      ! the equivalent rectangle carries the same A and I into the elements
      call assert_close(mech%links(2)%b*mech%links(2)%h, 0.3_dp, 1.0e-15_dp, 'equivalent rectangle: A')
      call assert_close(mech%links(2)%b*mech%links(2)%h**3/12.0_dp, 0.05_dp, 1.0e-15_dp, 'equivalent rectangle: I')
      call assert_close(mech%links(3)%inertia, 0.5_dp*8.0_dp/12.0_dp, 1.0e-15_dp, 'I from b, h')
      call assert_close(mech%links(3)%fibre, 1.0_dp, 0.0_dp, 'rectangle: c = h/2')
      ! A given for a rectangle is an error, not silently ignored
      inp%link_section(2) = 'rectangle'
      call build_mechanism(inp, mech, err)
      call assert_true(err%failed() .and. index(err%text(), 'link_area(2)') > 0, 'A with a rectangle: '//err%text())
      call err%clear()
      ! a circle of diameter 2 and a tube of wall 0.5
      inp%link_area(2) = 0.0_dp
      inp%link_inertia(2) = 0.0_dp
      inp%link_c(2) = 0.0_dp
      inp%link_section(2) = 'circle'
      inp%link_h(2) = 2.0_dp
      inp%link_section(3) = 'tube'
      inp%link_wall(3) = 0.5_dp
      call build_mechanism(inp, mech, err)
      call assert_true(.not. err%failed(), err%text())
      call assert_close(mech%links(2)%area, pi, 1.0e-15_dp, 'circle: A = pi d^2/4')
      call assert_close(mech%links(2)%inertia, pi/4.0_dp, 1.0e-15_dp, 'circle: I = pi d^4/64')
      call assert_close(mech%links(3)%area, 0.75_dp*pi, 1.0e-15_dp, 'tube: A = pi (d^2 - di^2)/4')
      call assert_close(mech%links(3)%inertia, 15.0_dp*pi/64.0_dp, 1.0e-15_dp, 'tube: I = pi (d^4 - di^4)/64')
      call assert_close(mech%links(3)%fibre, 1.0_dp, 0.0_dp, 'tube: c = d/2')
    end block
  end subroutine test_defaults

  subroutine test_incidence()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(error_t) :: err
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%link_n_elements(1:3) = [2, 5, 3]
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_equal(mech%n_elements, 10, 'total elements')
    call assert_equal(mech%links(3)%first_element, 8, 'first element of the rocker')
    ! joint C (3) holds coupler end 2 and rocker end 2
    call assert_equal(mech%joints(3)%n_links, 2, 'links at C')
    call assert_equal(mech%joints(3)%link(1), 2, 'coupler at C')
    call assert_equal(mech%joints(3)%link_end(1), 2, 'coupler end 2 at C')
    call assert_equal(mech%joints(3)%link(2), 3, 'rocker at C')
    call assert_equal(mech%joints(4)%link_end(1), 1, 'rocker end 1 at D')
    call assert_true(mech%joints(1)%grounded .and. mech%joints(4)%grounded, 'A and D on the ground')
    call assert_true(.not. (mech%joints(2)%grounded .or. mech%joints(3)%grounded), 'B and C move')
    call assert_equal(mech%joints(1)%kind, joint_clamp, 'A is the clamp')
    call assert_equal(joint_free, 0, 'joint codes shared with correlation_table (free = 0)')
    call assert_equal(joint_slider_fixed, 4, 'joint codes shared with correlation_table (slider_fixed = 4)')
  end subroutine test_incidence

  !> Lengths left at 0 are the distances between the joints' coordinates.
  subroutine test_lengths_from_coordinates()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(error_t) :: err
    inp = fourbar_input(0.0_dp, 0.0_dp, 10.5_dp, 10.0_dp)
    inp%joint_x(2:3) = [3.0_dp, 10.0_dp]
    inp%joint_y(2:3) = [4.0_dp, 10.5_dp]
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_close(mech%links(1)%length, 5.0_dp, 1.0e-14_dp, 'crank from A and B')
    call assert_close(mech%links(2)%length, hypot(7.0_dp, 6.5_dp), 1.0e-14_dp, 'coupler from B and C')
    call assert_close(mech%links(3)%length, 10.5_dp, 0.0_dp, 'a given length wins')
  end subroutine test_lengths_from_coordinates

  !> Each broken rule yields code 2 and a message naming variable and value.
  subroutine test_invalid_values()
    type(mechanism_input_t) :: inp, base
    base = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp = base; inp%n_joints = 1
    call expect(inp, 'n_joints = 1')
    inp = base; inp%joint_type(3) = 'pim'
    call expect(inp, "joint_type(3) = 'pim'")
    inp = base; inp%joint_x(4) = coordinate_unset; inp%joint_y(4) = coordinate_unset
    call expect(inp, 'joint_x(4), joint_y(4) = not given')
    inp = base; inp%joint_y(2) = 1.0_dp
    call expect(inp, 'only one given')
    inp = base; inp%joint_branch(3) = 'up'
    call expect(inp, "joint_branch(3) = 'up'")
    inp = base; inp%joint_name(2) = 'A'
    call expect(inp, "joint_name(2) = 'A'")
    inp = base; inp%link_joint2(2) = 7
    call expect(inp, 'link_joint2(2) = 7')
    inp = base; inp%link_joint2(2) = 2
    call expect(inp, 'link_joint2(2) = 2: a link must join two different joints')
    inp = base; inp%link_b(2) = -0.25_dp
    call expect(inp, 'link_b(2) = -0.25')
    inp = base; inp%link_h(1) = 0.0_dp
    call expect(inp, 'link_h(1) = 0')
    inp = base; inp%link_e1(3) = 0.0_dp
    call expect(inp, 'link_e1(3) = 0')
    inp = base; inp%link_m(1) = 1.0_dp
    call expect(inp, 'link_m(1) = 1.0')
    inp = base; inp%link_rho(2) = -1.0_dp
    call expect(inp, 'link_rho(2) = -1.0')
    ! a subnormal density: E1/rho overflows (the fuzzer's debug-build trap)
    inp = base; inp%link_rho(2) = 1.0e-310_dp
    call expect(inp, 'E1/rho (the squared bar wave speed) must lie in [1e2, 1e18]')
    inp = base; inp%link_e1(1) = 1.0e-3_dp
    call expect(inp, 'E1/rho (the squared bar wave speed) must lie in [1e2, 1e18]')
    ! a length from joint coordinates 1e-12 apart (the fuzzer found 4.9e-324, a debug-build trap)
    inp = base; inp%link_length(1) = 0.0_dp; inp%joint_x(2) = 1.0e-12_dp; inp%joint_y(2) = 0.0_dp
    call expect(inp, 'taken from its joints is')
    ! a general section whose I exceeds c^2 A (the fuzzer's I = 1.8e308 overflowed 12 I/A)
    inp = base; inp%link_section(2) = 'general'; inp%link_area(2) = 0.25_dp; inp%link_c(2) = 0.5_dp
    inp%link_inertia(2) = 1.0_dp
    call expect(inp, 'no section has its radius of gyration beyond its outer fibre')
    inp = base; inp%link_n_elements(2) = 0
    call expect(inp, 'link_n_elements(2) = 0')
    inp = base; inp%link_length(2) = 0.0_dp
    call expect(inp, 'link_length(2) = 0')
    inp = base; inp%driver_link = 4
    call expect(inp, 'driver_link = 4')
    inp = base; inp%driver_link = 2
    call expect(inp, 'the clamp A must hold')
    inp = base; inp%joint_type(1) = 'pin'
    call expect(inp, "joint_type(1) = 'pin': pin A joins 1 link end(s)")
    inp = base; inp%profile = 'ramp'
    call expect(inp, "profile = 'ramp'")
    inp = base; inp%profile = 'spinup'
    call expect(inp, 'spinup_time = 0')
    inp = base; inp%branch = 'x'
    call expect(inp, "branch = 'x'")
    inp = base; inp%toggle_rcond = 2.0_dp
    call expect(inp, 'toggle_rcond = 2.0')
    inp = base; inp%joint_sliding_link(2) = 1
    call expect(inp, 'joint_sliding_link(2) = 1: only a slider_link joint')
    ! a sleeve needs its sliding link to pass through it
    inp = slider_crank_input(2.0_dp, 7.0_dp, 0.0_dp)
    inp%joint_type(3) = 'slider_link'
    inp%joint_sliding_link(3) = 1
    call expect(inp, 'joint_sliding_link(3) = 1: link link1 must have joint J3')
  contains
    subroutine expect(bad_input, text)
      type(mechanism_input_t), intent(in) :: bad_input
      character(len=*), intent(in) :: text
      type(mechanism_t) :: mech
      type(error_t) :: err
      type(input_issue_t) :: issue
      call build_mechanism(bad_input, mech, err, issue)
      call assert_equal(err%code, 2, 'input error code for "'//text//'"')
      call assert_true(index(err%text(), text) > 0, 'message "'//err%text()//'" contains "'//text//'"')
      call assert_true(allocated(issue%variable), 'issue parts returned for "'//text//'"')
    end subroutine expect
  end subroutine test_invalid_values

  !> Five-bar (two cranks' worth of freedom) and a rigid triangle plus crank.
  subroutine test_mobility()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(error_t) :: err
    ! five-bar: A-B-C-D-E with A, E on the ground: F = 2
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%n_joints = 5
    inp%joint_type(4:5) = [character(len=16) :: 'pin', 'ground_pin']
    inp%joint_x(4) = coordinate_unset
    inp%joint_y(4) = coordinate_unset
    inp%joint_x(5) = 12.0_dp
    inp%joint_y(5) = 0.0_dp
    inp%n_links = 4
    inp%link_joint1(1:4) = [1, 2, 3, 4]
    inp%link_joint2(1:4) = [2, 3, 4, 5]
    inp%link_length(1:4) = [5.0_dp, 11.0_dp, 6.0_dp, 4.0_dp]
    call build_mechanism(inp, mech, err)
    call assert_true(index(err%text(), 'has 2 degrees of freedom') > 0, err%text())
    ! crank plus a triangle between B and two ground points: F = 0
    call err%clear()
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%n_joints = 5
    inp%joint_type(5) = 'ground_pin'
    inp%joint_x(5) = 0.0_dp
    inp%joint_y(5) = 8.0_dp
    inp%n_links = 4
    inp%link_joint1(4) = 5
    inp%link_joint2(4) = 3
    inp%link_length(4) = 9.0_dp
    call build_mechanism(inp, mech, err)
    call assert_true(index(err%text(), 'has 0 degrees of freedom') > 0, err%text())
    call assert_equal(err%code, 2, 'mobility is an input error')
  end subroutine test_mobility

  subroutine test_constant_profile()
    type(driver_t) :: drv
    real(dp) :: th, thd, thdd
    drv = driver_t(1, -7.0_dp, 0.5_dp, profile_constant, 0.0_dp)
    call driver_angle(drv, 2.0_dp, th, thd, thdd)
    call assert_close(th, 0.5_dp - 14.0_dp, 1.0e-14_dp, 'theta = theta0 + omega t (clockwise)')
    call assert_close(thd, -7.0_dp, 0.0_dp, 'theta_d = omega')
    call assert_close(thdd, 0.0_dp, 0.0_dp, 'theta_dd = 0')
  end subroutine test_constant_profile

  !> Cycloidal spin-up over T = 0.4 s to omega = 150 rad/s: at rest at t = 0
  !> with zero acceleration, omega and zero acceleration at T, theta(T) =
  !> theta0 + omega T/2; derivatives against central differences (h = 1e-6 s:
  !> truncation h^2 theta'''' / 6 ~ 1e-8 relative, tolerances 1e-7 of the
  !> scales omega and omega/T).
  subroutine test_spinup_profile()
    type(driver_t) :: drv
    real(dp), parameter :: w = 150.0_dp, tt = 0.4_dp, h = 1.0e-6_dp
    real(dp) :: th, thd, thdd, thm, thdm, thddm, thp, thdp, thddp, t
    integer :: k
    drv = driver_t(1, w, 0.3_dp, profile_spinup, tt)
    call driver_angle(drv, 0.0_dp, th, thd, thdd)
    call assert_close(th, 0.3_dp, 0.0_dp, 'theta(0) = theta0')
    call assert_close(thd, 0.0_dp, 0.0_dp, 'at rest at t = 0')
    call assert_close(thdd, 0.0_dp, 0.0_dp, 'no acceleration at t = 0')
    call driver_angle(drv, tt*(1.0_dp - 1.0e-12_dp), th, thd, thdd)
    call assert_close(thd, w, 1.0e-9_dp, 'omega reached at T')
    call assert_close(thdd, 0.0_dp, 1.0e-6_dp, 'acceleration vanishes at T')
    call assert_close(th, 0.3_dp + w*tt/2.0_dp, 1.0e-9_dp, 'theta(T) = theta0 + omega T/2')
    call driver_angle(drv, tt*(1.0_dp + 1.0e-12_dp), thp, thdp, thddp)
    call assert_close(thp, th, 1.0e-9_dp, 'theta continuous at T')
    call assert_close(thdp, thd, 1.0e-9_dp, 'theta_d continuous at T')
    call driver_angle(drv, 2.0_dp*tt, th, thd, thdd)
    call assert_close(th, 0.3_dp + w*1.5_dp*tt, 1.0e-12_dp, 'constant speed after T')
    ! the peak acceleration is 2 omega/T at T/2
    call driver_angle(drv, 0.5_dp*tt, th, thd, thdd)
    call assert_close(thdd, 2.0_dp*w/tt, 1.0e-9_dp, 'peak acceleration 2 omega/T')
    call assert_close(thd, 0.5_dp*w, 1.0e-9_dp, 'half speed at T/2')
    do k = 1, 9
      t = 0.05_dp*k
      call driver_angle(drv, t - h, thm, thdm, thddm)
      call driver_angle(drv, t + h, thp, thdp, thddp)
      call driver_angle(drv, t, th, thd, thdd)
      call assert_close(thd, (thp - thm)/(2.0_dp*h), 1.0e-7_dp*w, 'theta_d vs FD')
      call assert_close(thdd, (thdp - thdm)/(2.0_dp*h), 1.0e-7_dp*w/tt, 'theta_dd vs FD')
    end do
  end subroutine test_spinup_profile

  subroutine write_file(path, lines)
    character(len=*), intent(in) :: path
    character(len=*), intent(in) :: lines(:)
    integer :: u, i
    open(newunit=u, file=path, status='replace', action='write')
    do i = 1, size(lines)
      write(u, '(a)') trim(lines(i))
    end do
    close(u)
  end subroutine write_file

  subroutine delete_file(path)
    character(len=*), intent(in) :: path
    integer :: u
    logical :: exists
    inquire(file=path, exist=exists)
    if (.not. exists) return
    open(newunit=u, file=path, status='old')
    close(u, status='delete')
  end subroutine delete_file

  function temp_name(stem) result(path)
    character(len=*), intent(in) :: stem
    character(len=:), allocatable :: path
    real(dp) :: x
    character(len=12) :: tag
    logical, save :: seeded = .false.
    ! a fresh seed per run, so that concurrent runs do not share file names
    if (.not. seeded) call random_seed()
    seeded = .true.
    call random_number(x)
    write(tag, '(i0)') int(x*1.0e9_dp)
    path = 'tmp_'//stem//'_'//trim(tag)//'.nml'
  end function temp_name

  !> The §8.1 four-bar as a deck (with a leading group to show order-freedom);
  !> then echo it and read the echo back: the same input.
  subroutine test_deck_round_trip()
    type(deck_t) :: deck, deck2
    type(mechanism_t) :: mech, mech2
    type(error_t) :: err
    character(len=:), allocatable :: path, echo_path
    integer :: u
    path = temp_name('fourbar')
    echo_path = temp_name('echo')
    call write_file(path, [character(len=80) :: &
      '&run analysis = ''kinematics'' /', &
      '! Tennant four-bar, FORMULATION.md 8.1', &
      '&mechanism', &
      '  n_joints = 4', &
      '  joint_name = ''A'', ''B'', ''C'', ''D''', &
      '  joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin''', &
      '  joint_x(1) = 0.0,  joint_y(1) = 0.0', &
      '  joint_x(4) = 10.0, joint_y(4) = 0.0', &
      '  n_links = 3', &
      '  link_name = ''crank'', ''coupler'', ''rocker''', &
      '  link_joint1 = 1, 2, 4', &
      '  link_joint2 = 2, 3, 3', &
      '  link_length = 5.0, 11.0, 10.5', &
      '  link_n_elements = 1, 3, 2', &
      '  driver_link = 1, omega = 150.0, theta0_deg = 0.0', &
      '  profile = ''spinup'', spinup_time = 0.1', &
      '  branch = ''open''', &
      '/'])
    call deck%open(path, err)
    call read_mechanism(deck, mech, err)
    call deck%close()
    call delete_file(path)
    call assert_true(.not. err%failed(), err%text())
    if (err%failed()) return
    call assert_equal(mech%n_joints, 4, 'joints read')
    call assert_equal(trim(mech%links(2)%name), 'coupler', 'link name read')
    call assert_close(mech%links(3)%length, 10.5_dp, 0.0_dp, 'length read')
    call assert_equal(mech%links(2)%n_elements, 3, 'elements read')
    call assert_equal(mech%driver%profile, profile_spinup, 'profile read')
    call assert_close(mech%driver%spinup_time, 0.1_dp, 0.0_dp, 'spin-up time read')
    call assert_close(mech%joints(4)%x, 10.0_dp, 0.0_dp, 'ground point read')
    call assert_close(mech%links(1)%e1, tennant_aluminium_e1, 0.0_dp, 'default material kept')
    ! echo, read back
    open(newunit=u, file=echo_path, status='replace', action='write')
    call write_mechanism_group(mech, u)
    close(u)
    call deck2%open(echo_path, err)
    call read_mechanism(deck2, mech2, err)
    call deck2%close()
    call delete_file(echo_path)
    call assert_true(.not. err%failed(), 'echo reads back: '//err%text())
    if (err%failed()) return
    ! the echo writes 17 significant digits: exact round trip
    call assert_all_close(mech2%input%link_length, mech%input%link_length, 0.0_dp, 0.0_dp, 'lengths survive the echo')
    call assert_all_close(mech2%input%joint_x, mech%input%joint_x, 0.0_dp, 0.0_dp, 'coordinates survive the echo')
    call assert_true(all(mech2%input%joint_type == mech%input%joint_type), 'joint types survive the echo')
    call assert_all_close(mech2%input%link_e2, mech%input%link_e2, 0.0_dp, 0.0_dp, 'materials survive the echo')
    call assert_close(mech2%input%omega, mech%input%omega, 0.0_dp, 'omega survives the echo')
    call assert_true(mech2%input%profile == mech%input%profile, 'profile survives the echo')
  end subroutine test_deck_round_trip

  subroutine test_deck_errors()
    type(deck_t) :: deck, deck2
    type(mechanism_t) :: mech
    type(error_t) :: err
    character(len=:), allocatable :: path
    path = temp_name('bad')
    call write_file(path, [character(len=80) :: &
      '&mechanism', &
      '  n_joints = 3, joint_type = ''clamp'', ''pin'', ''slider_fixed''', &
      '  joint_x = 0.0, , 0.0, joint_y = 0.0, , 0.5', &
      '  n_links = 2, link_joint1 = 1, 2, link_joint2 = 2, 3', &
      '  link_length = 2.0, 7.0', &
      '  link_b = 0.25, -1.0', &
      '/'])
    call deck%open(path, err)
    call read_mechanism(deck, mech, err)
    call deck%close()
    call assert_equal(err%code, 2, 'input error')
    call assert_true(index(err%text(), 'link_b(2) = -1.0') > 0, 'names variable and value: '//err%text())
    call assert_true(index(err%text(), 'line 6') > 0, 'names the deck line: '//err%text())
    ! a group that is missing
    call err%clear()
    call write_file(path, [character(len=80) :: '&run analysis = ''kinematics'' /'])
    call deck2%open(path, err)
    call read_mechanism(deck2, mech, err)
    call deck2%close()
    call delete_file(path)
    call assert_equal(err%code, 2, 'missing group is an input error')
    call assert_true(index(err%text(), 'mechanism') > 0 .and. index(err%text(), 'missing') > 0, err%text())
  end subroutine test_deck_errors

  subroutine test_summary()
    type(mechanism_t) :: mech
    type(error_t) :: err
    character(len=200), allocatable :: lines(:)
    allocate(lines(0))
    call build_mechanism(fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp), mech, err)
    lines = mechanism_summary(mech)
    call assert_equal(size(lines), 1 + 4 + 3 + 3, 'summary lines (head, joints, links, driver, branch, class)')
    call assert_true(index(lines(size(lines)), 'crank-rocker') > 0, lines(size(lines)))
    call assert_true(index(lines(size(lines)), 's + l = 16') > 0, 'Grashof sums: '//lines(size(lines)))
    call assert_true(index(lines(2), 'joint A: clamp at (0') > 0, lines(2))
    call assert_true(index(lines(9), 'driver: link crank, omega 150') > 0, lines(9))
    call build_mechanism(fourbar_input(5.0_dp, 6.0_dp, 7.0_dp, 10.0_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'non-Grashof') > 0, classify_mechanism(mech))
    call build_mechanism(fourbar_input(5.0_dp, 10.0_dp, 5.0_dp, 10.0_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'change point') > 0, classify_mechanism(mech))
    call build_mechanism(fourbar_input(10.0_dp, 11.0_dp, 10.5_dp, 5.0_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'double-crank') > 0, classify_mechanism(mech))
    call build_mechanism(fourbar_input(10.0_dp, 5.0_dp, 10.5_dp, 11.0_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'double-rocker') > 0, classify_mechanism(mech))
    call build_mechanism(fourbar_input(10.0_dp, 11.0_dp, 5.0_dp, 10.5_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'rocker-crank') > 0, classify_mechanism(mech))
    call build_mechanism(slider_crank_input(2.0_dp, 7.0_dp, 0.5_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'slider-crank') > 0 .and. &
                     index(classify_mechanism(mech), 'turns fully') > 0, classify_mechanism(mech))
    call build_mechanism(slider_crank_input(2.0_dp, 2.2_dp, 0.5_dp), mech, err)
    call assert_true(index(classify_mechanism(mech), 'cannot turn fully') > 0, classify_mechanism(mech))
  end subroutine test_summary

  !> A beam between two ground points (pinned-pinned or clamped-clamped, the
  !> verification beams): no driver, Gruebler count -1 (statically
  !> indeterminate: immovable ends), accepted; two clamps are built-in ends.
  function beam_input(end_type) result(inp)
    character(len=*), intent(in) :: end_type
    type(mechanism_input_t) :: inp
    inp = two_point_beam(end_type, 4)   ! 20 in long
    inp%joint_name(1:2) = [character(len=16) :: 'A', 'B']
  end function beam_input

  subroutine test_structure_without_driver()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(error_t) :: err
    character(len=200), allocatable :: lines(:)
    allocate(lines(0))
    call build_mechanism(beam_input('ground_pin'), mech, err)
    call assert_true(.not. err%failed(), 'pinned-pinned beam: '//err%text())
    call assert_equal(mech%driver%link, 0, 'no driver')
    call assert_close(mech%links(1)%length, 20.0_dp, 1.0e-14_dp, 'length from the ground points')
    lines = mechanism_summary(mech)
    call assert_true(index(lines(1), 'no driver') > 0, lines(1))
    call assert_true(any(index(lines, 'driver: none') > 0), 'summary names the missing driver')
    call assert_equal(len(classify_mechanism(mech)), 0, 'a structure is not classified as a linkage')
    call build_mechanism(beam_input('clamp'), mech, err)
    call assert_true(.not. err%failed(), 'clamped-clamped beam: '//err%text())
    ! a rigid triangle on two ground pins: Gruebler count 0
    inp = beam_input('ground_pin')
    inp%n_joints = 3
    inp%joint_type(3) = 'pin'
    inp%n_links = 2
    inp%link_joint1(1:2) = [1, 2]
    inp%link_joint2(1:2) = [3, 3]
    inp%link_length(1:2) = [12.0_dp, 16.0_dp]
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'triangle truss: '//err%text())
  end subroutine test_structure_without_driver

  !> Without a driver: omega must be 0, the linkage must not be able to move,
  !> and driver_link must be 0..n_links; with a driver a second clamp is
  !> still refused.
  subroutine test_structure_rules()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(error_t) :: err
    inp = beam_input('ground_pin')
    inp%omega = 10.0_dp
    call build_mechanism(inp, mech, err)
    call assert_true(index(err%text(), 'omega must be 0') > 0, err%text())
    call assert_equal(err%code, 2, 'input error')
    call err%clear()
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%joint_type(1) = 'ground_pin'
    inp%driver_link = 0
    inp%omega = 0.0_dp
    call build_mechanism(inp, mech, err)
    call assert_true(index(err%text(), 'must not move') > 0 .and. index(err%text(), '1 degree(s) of freedom') > 0, &
                     err%text())
    call err%clear()
    inp = beam_input('ground_pin')
    inp%driver_link = -1
    call build_mechanism(inp, mech, err)
    call assert_true(index(err%text(), 'driver_link = -1') > 0 .and. index(err%text(), 'or 0 for a structure') > 0, &
                     err%text())
    call err%clear()
    inp = fourbar_input(5.0_dp, 11.0_dp, 10.5_dp, 10.0_dp)
    inp%joint_type(4) = 'clamp'
    call build_mechanism(inp, mech, err)
    call assert_true(index(err%text(), 'only one clamp') > 0, err%text())
  end subroutine test_structure_rules
end module test_linkage_suite

program test_linkage
  use test_linkage_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_linkage')
end program test_linkage
