!> Tests of the one deck idiom: every group's echo in the output header is a
!> deck that reads back to the same values (echo, read, echo gives the same
!> text: the staging covers every variable), for the groups of a transient
!> deck (&mechanism, &transient, &effects, &loads), &optimize, &problem_data,
!> &sweep, &spatial_loads and &design; and the checks across the groups of a transient deck, named
!> with group, variable and code 2.
module test_deck_groups_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use deck_runner, only: start_suite, suite_stem, open_deck_text, close_deck_text, line_length
  use linkage, only: mechanism_t
  use external_loads, only: loads_input_t
  use transient_settings, only: transient_settings_t
  use clearance_run, only: clearance_monitor_t
  use transient_deck, only: read_transient_deck, echo_transient_deck
  use optimize_settings, only: optimize_settings_t, read_optimize_settings, echo_optimize_settings
  use deck_problem, only: problem_data_t
  use problem_data_settings, only: read_problem_data, echo_problem_data
  use sweep_settings, only: sweep_settings_t, read_sweep_settings, echo_sweep_settings
  use spatial_external_loads, only: spatial_loads_input_t
  use spatial_loads_settings, only: read_spatial_loads, echo_spatial_loads
  use linkage_deck, only: read_mechanism
  use design_settings, only: design_settings_t, read_design_settings, echo_design_settings
  use assertions
  implicit none
  private
  public :: run_all

  !> A cantilever with gravity and a ramped tip force, no turning crank.
  character(len=*), parameter :: beam = &
    "&run analysis = 'transient' /|" // &
    "&mechanism n_joints = 2, joint_name = 'root', 'tip', joint_type = 'clamp', 'free', joint_x(1) = 0.0, " // &
    "joint_y(1) = 0.0, " // &
    "n_links = 1, link_name = 'beam', link_joint1 = 1, link_joint2 = 2, link_length = 10.0, link_b = 1.0, " // &
    "link_h = 0.1, link_n_elements = 2, driver_link = 1, omega = 0.0 /|"
  character(len=*), parameter :: loads = &
    "&loads gravity_g = 386.09, n_loads = 1, load_joint(1) = 'tip', load_fy(1) = -2.5, load_n_points(1) = 2, " // &
    "load_time(1:2,1) = 0.0, 0.5, load_factor(1:2,1) = 0.0, 1.0 /"

contains

  subroutine run_all()
    call start_suite('test_deck_groups')
    call run_test('transient_deck_echo_reads_back', test_transient_echo)
    call run_test('optimize_and_problem_data_echo_reads_back', test_optimize_echo)
    call run_test('problem_data_linear_terms_in_either_order_not_both', test_linear_order)
    call run_test('sweep_echo_reads_back_as_values', test_sweep_echo)
    call run_test('spatial_loads_echo_reads_back', test_spatial_loads_echo)
    call run_test('design_echo_reads_back', test_design_echo)
    call run_test('checks_across_groups_are_input_errors', test_across_groups)
  end subroutine run_all

  subroutine test_transient_echo()
    character(len=:), allocatable :: echo1, echo2
    type(transient_settings_t) :: s
    type(loads_input_t) :: l
    type(error_t) :: err
    call transient_echo(beam//"&transient t_end = 0.01, output_step_t = 0.001, rtol = 1e-5, point_link(2) = 'beam', "// &
                        "point_at(2) = 0.25, output_rows = 'none' /|&effects stretching = T /|"//loads, echo1, s, l, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_true(index(echo1, '&LOADS') > 0 .and. index(echo1, '&EFFECTS') > 0, '&loads and &effects echoed')
    call transient_echo("&run analysis = 'transient' /|"//echo1, echo2, s, l, err)
    call assert_true(.not. err%failed(), 'the echo reads back: '//err%text())
    call assert_equal(echo2, echo1, 'echo of the echo')
    call assert_close(l%load_fy(1), -2.5_dp, 0.0_dp, 'load_fy(1)')
    call assert_close(l%load_time(2, 1), 0.5_dp, 0.0_dp, 'load_time(2,1)')
    call assert_close(s%point_at(2), 0.25_dp, 0.0_dp, 'point_at(2)')
    call assert_true(s%effects%stretching .and. .not. s%effects%material, 'effects')
    ! without &loads and &effects: their defaults, whatever the deck before gave (stage_from
    ! covers every variable), and the header has no &loads group
    call transient_echo(beam//"&transient t_end = 0.01, output_step_t = 0.001 /", echo1, s, l, err)
    call assert_true(.not. err%failed() .and. index(echo1, '&LOADS') == 0, 'no loads: no &loads echo')
    call assert_close(l%gravity_g + abs(l%load_fy(1)) + l%load_time(2, 1) + l%load_factor(2, 1), 0.0_dp, 0.0_dp, &
                      'no loads')
    call assert_close(l%load_position(1), 1.0_dp, 0.0_dp, 'load_position default')
    call assert_close(s%point_at(2), 0.5_dp, 0.0_dp, 'point_at default')
    call assert_true(len_trim(s%point_link(2)) == 0 .and. .not. s%effects%stretching, 'point_link, stretching defaults')
    call assert_close(s%rtol, 1.0e-6_dp, 0.0_dp, 'rtol default')
    call assert_equal(trim(s%output_rows), 'all', 'output_rows default')
  end subroutine test_transient_echo

  subroutine test_optimize_echo()
    character(len=*), parameter :: data = "&problem_data n = 2, f_q(1,1) = 2, f_q(2,2) = 4, f_c = -2, -4, "// &
      "n_ineq = 1, g_a(1,:) = 1, 1, g_b(1) = 1, lower = 0, 0, f_star = -1.5, title = 'a small QP' /"
    character(len=:), allocatable :: echo1, echo2
    type(optimize_settings_t) :: s
    type(problem_data_t), allocatable :: d        ! (160 kB: not on the stack)
    type(error_t) :: err
    allocate(d)
    call optimize_echo("&optimize problem = 'DECK', method = 'GNLC.NS', x0 = 0.25, 0.5, max_iter = 7, "// &
                       "check_derivatives = T /|"//data, echo1, s, d, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_equal(trim(s%method), 'gnlc_ns', 'method named as GNLC.NS')
    call optimize_echo(echo1, echo2, s, d, err)
    call assert_true(.not. err%failed(), 'the echo reads back: '//err%text())
    call assert_equal(echo2, echo1, 'echo of the echo')
    call assert_equal(trim(s%problem), 'deck', 'problem')
    call assert_equal(s%max_iter, 7, 'max_iter')
    call assert_true(s%check_derivatives, 'check_derivatives')
    call assert_close(s%x0(2), 0.5_dp, 0.0_dp, 'x0(2)')
    call assert_true(s%x0(3) < -1.0e300_dp, 'x0(3) left unset')
    call assert_equal(d%n, 2, 'n')
    call assert_close(d%f_q(2, 2), 4.0_dp, 0.0_dp, 'f_q(2,2)')
    call assert_close(d%g_a(1, 2), 1.0_dp, 0.0_dp, 'g_a(1,2)')
    call assert_close(d%f_star, -1.5_dp, 0.0_dp, 'f_star')
    call assert_true(d%x_star(1) < -1.0e300_dp, 'x_star left unset')
    call assert_close(d%upper(1), 1.0e30_dp, 0.0_dp, 'upper: none')
    call assert_equal(trim(d%title), 'a small QP', 'title')
    ! a deck without the settings above: the documented defaults again
    call optimize_echo("&optimize problem = 'deck' /|&problem_data n = 1 /", echo1, s, d, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_equal(trim(s%method), 'auto', 'method default')
    call assert_equal(s%max_iter, 50, 'max_iter default')
    call assert_true(.not. s%check_derivatives .and. s%x0(1) < -1.0e300_dp, 'check_derivatives, x0 defaults')
    call assert_close(d%f_q(2, 2) + d%g_a(1, 2) + abs(d%f_c(2)), 0.0_dp, 0.0_dp, 'coefficients default')
    call assert_equal(d%n_ineq, 0, 'n_ineq default')
    call assert_true(d%f_star < -1.0e300_dp .and. d%lower(1) <= -1.0e30_dp, 'f_star, lower defaults')
  end subroutine test_optimize_echo

  !> The linear terms of the constraints in the order of g_q (g_c(j,k):
  !> variable j, constraint k) give the same problem as the older g_a(k,j);
  !> a deck with both for one family is refused (exit 2).
  subroutine test_linear_order()
    character(len=*), parameter :: head = "&optimize problem = 'deck' /|&problem_data n = 3, n_ineq = 2, n_eq = 1, "
    character(len=:), allocatable :: echo
    type(optimize_settings_t) :: s
    type(problem_data_t), allocatable :: d, d_old
    type(error_t) :: err
    allocate(d, d_old)
    call optimize_echo(head//"g_a(1,:) = 1, 2, 3, g_a(2,3) = -4, h_a(1,2) = 5 /", echo, s, d_old, err)
    call assert_true(.not. err%failed(), 'g_a, h_a: '//err%text())
    call optimize_echo(head//"g_c(:,1) = 1, 2, 3, g_c(3,2) = -4, h_c(2,1) = 5 /", echo, s, d, err)
    call assert_true(.not. err%failed(), 'g_c, h_c: '//err%text())
    call assert_all_close(reshape(d%g_a, [size(d%g_a)]), reshape(d_old%g_a, [size(d_old%g_a)]), 0.0_dp, 0.0_dp, &
                          'g_c is g_a transposed')
    call assert_all_close(reshape(d%h_a, [size(d%h_a)]), reshape(d_old%h_a, [size(d_old%h_a)]), 0.0_dp, 0.0_dp, &
                          'h_c is h_a transposed')
    call assert_close(d%g_a(1, 3) + d%g_a(2, 3) + d%h_a(1, 2), 3.0_dp - 4.0_dp + 5.0_dp, 0.0_dp, 'the entries given')
    call optimize_echo(head//"g_a(1,1) = 1, g_c(2,2) = 1 /", echo, s, d, err)
    call assert_true(err%failed() .and. index(err%text(), 'g_c') > 0 .and. index(err%text(), 'not both') > 0, &
                     'g_a and g_c together refused: '//err%text())
    call err%clear()
    call optimize_echo(head//"h_c(1,1) = 1, h_a(1,2) = 1 /", echo, s, d, err)
    call assert_true(err%failed() .and. index(err%text(), 'h_c') > 0, 'h_a and h_c together refused: '//err%text())
    call err%clear()
  end subroutine test_linear_order

  subroutine test_sweep_echo()
    character(len=:), allocatable :: echo1, echo2
    type(sweep_settings_t) :: s
    type(error_t) :: err
    call sweep_echo("&sweep group = 'transient', variable = 'rtol', first = 1e-3, last = 1e-6, n_points = 4, "// &
                    "spacing = 'log' /", echo1, s, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_equal(size(s%values), 4, 'four points')
    call sweep_echo(echo1, echo2, s, err)
    call assert_true(.not. err%failed(), 'the echo reads back: '//err%text())
    call assert_equal(echo2, echo1, 'echo of the echo')
    call assert_equal(size(s%values), 4, 'four values')
    call assert_all_close(s%values, [1.0e-3_dp, 1.0e-4_dp, 1.0e-5_dp, 1.0e-6_dp], 1.0e-14_dp, 0.0_dp, 'the log range')
    call assert_equal(trim(s%spacing), 'log', 'spacing')
    call sweep_echo("&sweep group = 'mechanism', variable = 'omega', values = 50, 60 /", echo1, s, err)
    call assert_true(.not. err%failed(), 'a list after a range: '//err%text())
    call assert_equal(size(s%values), 2, 'two values')
    call assert_equal(trim(s%spacing), 'linear', 'spacing default')
  end subroutine test_sweep_echo

  subroutine test_across_groups()
    call bad("&transient output_step_t = 0.001 /", 'group &transient: t_end')
    call bad("&transient t_end = 0.01, output_step_t = 0.001, stop_when_periodic = 1e-3 /", &
             'group &transient: stop_when_periodic')
    call bad("&transient t_end = 0.01, output_step_t = 0.001, point_link(3) = 'crank' /", &
             "group &transient: point_link(3) = 'crank'")
    call bad("&transient t_end = 0.01, output_step_t = 0.001 /|&loads n_loads = 1 /", 'group &loads: load_joint(1)')
  contains
    subroutine bad(groups, fragment)
      character(len=*), intent(in) :: groups, fragment
      character(len=:), allocatable :: echo
      type(transient_settings_t) :: s
      type(loads_input_t) :: l
      type(error_t) :: err
      call transient_echo(beam//groups, echo, s, l, err)
      call assert_true(err%failed() .and. err%code == 2, fragment//' rejected')
      call assert_true(index(err%text(), fragment) > 0, 'message names '//fragment//': '//err%text())
    end subroutine bad
  end subroutine test_across_groups

  !> Read the groups of a transient deck and echo them as a deck text.
  subroutine transient_echo(text, echo, s, l, err)
    character(len=*), intent(in) :: text
    character(len=:), allocatable, intent(out) :: echo
    type(transient_settings_t), intent(out) :: s
    type(loads_input_t), intent(out) :: l
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(mechanism_t) :: mech
    type(clearance_monitor_t) :: clearance
    type(table_t) :: out
    call open_text(text, deck, echo, err)
    if (.not. err%failed()) call read_transient_deck(deck, mech, s, l, clearance, err)
    call close_text_open_echo(deck, out, err)
    if (err%failed()) return
    call echo_transient_deck(out, mech, l, clearance)
    call close_echo(out, echo, err)
  end subroutine transient_echo

  !> Read &optimize and &problem_data and echo them as a deck text.
  subroutine optimize_echo(text, echo, s, d, err)
    character(len=*), intent(in) :: text
    character(len=:), allocatable, intent(out) :: echo
    type(optimize_settings_t), intent(out) :: s
    type(problem_data_t), intent(out) :: d
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(table_t) :: out
    call open_text(text, deck, echo, err)
    if (.not. err%failed()) call read_optimize_settings(deck, s, err)
    if (.not. err%failed()) call read_problem_data(deck, d, err)
    call close_text_open_echo(deck, out, err)
    if (err%failed()) return
    call echo_optimize_settings(s, s%x0(1:d%n), out)
    call echo_problem_data(d, out)
    call close_echo(out, echo, err)
  end subroutine optimize_echo

  !> &spatial_loads: its echo reads back to the same values and echo; a deck
  !> without the group gets the documented defaults, whatever the deck before gave.
  subroutine test_spatial_loads_echo()
    character(len=:), allocatable :: echo1, echo2
    type(spatial_loads_input_t) :: l
    type(error_t) :: err
    logical :: found
    call spatial_loads_echo("&spatial_loads gravity_g = 386.09, gravity_direction = 0, -1, 0, initial_static = T, "// &
                            "n_loads = 2, load_joint(1) = 'B', load_force(:,1) = 1, 2, 3, load_link(2) = 'coupler', "// &
                            "load_position(2) = 0.5, load_moment(:,2) = 0, 0, -4 /", echo1, l, found, err)
    call assert_true(.not. err%failed() .and. found, 'read: '//err%text())
    call spatial_loads_echo(echo1, echo2, l, found, err)
    call assert_true(.not. err%failed(), 'the echo reads back: '//err%text())
    call assert_equal(echo2, echo1, 'echo of the echo')
    call assert_true(l%initial_static .and. l%n_loads == 2, 'initial_static, n_loads')
    call assert_all_close(l%gravity_direction, [0.0_dp, -1.0_dp, 0.0_dp], 0.0_dp, 0.0_dp, 'gravity_direction')
    call assert_all_close(l%load_force(:, 1), [1.0_dp, 2.0_dp, 3.0_dp], 0.0_dp, 0.0_dp, 'load_force(:,1)')
    call assert_close(l%load_moment(3, 2), -4.0_dp, 0.0_dp, 'load_moment(3,2)')
    call assert_equal(trim(l%load_link(2)), 'coupler', 'load_link(2)')
    call spatial_loads_echo("&spatial_loads n_loads = 0 /", echo1, l, found, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_true(.not. l%initial_static .and. .not. l%gravity_g > 0.0_dp, 'initial_static, gravity_g defaults')
    call assert_all_close(l%gravity_direction, [0.0_dp, 0.0_dp, -1.0_dp], 0.0_dp, 0.0_dp, 'gravity_direction default')
    call assert_close(l%load_position(2) + sum(abs(l%load_force)) + sum(abs(l%load_moment)), 1.0_dp, 0.0_dp, &
                      'position 1, no forces or moments')
    call assert_true(len_trim(l%load_joint(1)) + len_trim(l%load_link(2)) == 0, 'load_joint, load_link defaults')
  end subroutine test_spatial_loads_echo

  !> &design: its echo reads back to the same values and echo (the
  !> derivatives' default resolved), checked against Tennant's four-bar;
  !> a group that names only the variables and bounds gets the defaults.
  subroutine test_design_echo()
    character(len=*), parameter :: fourbar = "&mechanism n_joints = 4, joint_type = 'clamp', 'pin', 'pin', "// &
      "'ground_pin', joint_x(1) = 0.0, joint_y(1) = 0.0, joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3, "// &
      "link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3, link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, "// &
      "link_h = 3*1.0, driver_link = 1, omega = 150.0 /|"
    character(len=:), allocatable :: echo1, echo2
    type(design_settings_t) :: d
    type(error_t) :: err
    call design_echo(fourbar//"&design variables = 'link_h(1)', 'link_h(2)', lower = 2*0.2, upper = 2*4.0, "// &
                     "stress_allowable = 20000.0, peak_stress = 'ks', ks_rho = 50, speeds = 100, 150, "// &
                     "objective_speed = 2, deflection_link = 2, 3, deflection_at = 0.5, 0.25, deflection_limit = "// &
                     "0.05, 0.1, deflection_from = 'chord', 'rigid', transmission_joint = 3, transmission_min_deg = 30 /", &
                     echo1, d, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call design_echo(fourbar//echo1, echo2, d, err)
    call assert_true(.not. err%failed(), 'the echo reads back: '//err%text())
    call assert_equal(echo2, echo1, 'echo of the echo')
    call assert_equal(trim(d%derivatives), 'variational', 'derivatives resolved for the shooting evaluator')
    call assert_equal(d%n_speeds, 2, 'two speeds')
    call assert_all_close(d%deflection_at(1:2), [0.5_dp, 0.25_dp], 0.0_dp, 0.0_dp, 'deflection_at')
    call assert_equal(trim(d%deflection_from(2)), 'rigid', 'deflection_from(2)')
    call assert_equal(d%transmission_joint, 3, 'transmission_joint')
    call assert_close(d%ks_rho, 50.0_dp, 0.0_dp, 'ks_rho')
    call design_echo(fourbar//"&design variables = 'link_h(1)', lower = 0.2, upper = 4.0, frequency_factor = 5 /", &
                     echo1, d, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_true(d%objective == 'mass' .and. d%evaluator == 'shooting' .and. d%peak_stress == 'max' .and. &
                     d%samples == 72 .and. d%max_iterations == 30 .and. d%n_speeds == 0 .and. &
                     d%transmission_joint == 0 .and. all(d%deflection_link == 0), 'defaults')
    call assert_close(d%ks_rho + d%move_limit + d%stop_when_periodic, 200.3_dp + 1.0e-6_dp, 1.0e-12_dp, &
                      'ks_rho, move_limit, stop_when_periodic defaults')
  end subroutine test_design_echo

  !> Read &mechanism and &design and echo &design as a deck text.
  subroutine design_echo(text, echo, d, err)
    character(len=*), intent(in) :: text
    character(len=:), allocatable, intent(out) :: echo
    type(design_settings_t), intent(out) :: d
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(table_t) :: out
    type(mechanism_t) :: mech
    call open_text(text, deck, echo, err)
    if (.not. err%failed()) call read_mechanism(deck, mech, err)
    if (.not. err%failed()) call read_design_settings(deck, mech, d, err)
    call close_text_open_echo(deck, out, err)
    if (err%failed()) return
    call echo_design_settings(d, out)
    call close_echo(out, echo, err)
  end subroutine design_echo

  !> Read &spatial_loads and echo it as a deck text.
  subroutine spatial_loads_echo(text, echo, l, found, err)
    character(len=*), intent(in) :: text
    character(len=:), allocatable, intent(out) :: echo
    type(spatial_loads_input_t), intent(out) :: l
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(table_t) :: out
    found = .false.
    call open_text(text, deck, echo, err)
    if (.not. err%failed()) call read_spatial_loads(deck, l, found, err)
    call close_text_open_echo(deck, out, err)
    if (err%failed()) return
    call echo_spatial_loads(l, out)
    call close_echo(out, echo, err)
  end subroutine spatial_loads_echo

  !> Read &sweep and echo it as a deck text.
  subroutine sweep_echo(text, echo, s, err)
    character(len=*), intent(in) :: text
    character(len=:), allocatable, intent(out) :: echo
    type(sweep_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(table_t) :: out
    call open_text(text, deck, echo, err)
    if (.not. err%failed()) call read_sweep_settings(deck, s, err)
    call close_text_open_echo(deck, out, err)
    if (err%failed()) return
    call echo_sweep_settings(s, out)
    call close_echo(out, echo, err)
  end subroutine sweep_echo

  !> The deck text as a deck open for a reader (no error so far, no echo yet).
  subroutine open_text(text, deck, echo, err)
    character(len=*), intent(in) :: text
    type(deck_t), intent(inout) :: deck
    character(len=:), allocatable, intent(out) :: echo
    type(error_t), intent(inout) :: err
    echo = ''
    call err%clear()
    call open_deck_text(suite_stem(), text, deck, err)
  end subroutine open_text

  !> Close the deck; unless its read failed, an output for the echo.
  subroutine close_text_open_echo(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    call close_deck_text(suite_stem(), deck)
    if (.not. err%failed()) call out%open(suite_stem()//'.out', err)
  end subroutine close_text_open_echo

  !> The output's '#' lines without their '# ', joined by '|' (a deck text).
  subroutine close_echo(out, echo, err)
    type(table_t), intent(inout) :: out
    character(len=:), allocatable, intent(out) :: echo
    type(error_t), intent(inout) :: err
    character(len=line_length) :: line
    integer :: u, ios
    call out%commit(err)
    echo = ''
    open(newunit=u, file=suite_stem()//'.out', status='old', action='read')
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) exit
      if (line(1:2) /= '# ') cycle
      if (len(echo) > 0) echo = echo//'|'
      echo = echo//trim(line(3:))
    end do
    close(u, status='delete')
  end subroutine close_echo
end module test_deck_groups_suite

program test_deck_groups
  use assertions, only: finish_suite
  use test_deck_groups_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_deck_groups')
end program test_deck_groups
