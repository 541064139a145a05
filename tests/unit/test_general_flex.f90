!> Tests of the flexible general mechanism (module general_flex_model, the
!> &general_links group, the general_transient analysis): the RSSR written
!> as a general mechanism against the spatial four-bar model (frequencies,
!> energies of the rigid motion, static states), the energy balance of the
!> driven undamped RSSR, of a planar two-link arm with two driven joints and
!> of a spatial three-axis manipulator driven by three tables, the joint
!> rules' unknowns, refused joints and bad &general_links input; the
!> four-bar on lumped mounts (module support_mounts): its equations of
!> motion against a dense solve, its energy balance, and the force its
!> mounts carry against the shaking force of the rigid four-bar.
module test_general_flex_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use material_law, only: ramberg_osgood_t
  use element_effects, only: element_effects_t
  use lsode_solver, only: lsode_t, mf_adams, mf_bdf_band_user
  use linalg, only: solve_linear
  use spatial_section, only: spatial_section_init, section_circular, section_rectangular
  use spatial_kinematics, only: spatial_fourbar_t, spatial_fourbar_init
  use spatial_model, only: spatial_model_t, spatial_link_t, spatial_joint_spherical
  use general_mechanism, only: general_mechanism_t
  use general_kinematics, only: general_kinematics_t
  use general_deck, only: read_general_mechanism
  use general_flex_model, only: general_flex_model_t
  use support_mounts, only: support_mount_t
  use general_transient_analysis, only: run_general_transient
  use assertions
  use deck_runner, only: open_deck_text, close_deck_text, scratch_path, run_deck, line_length
  implicit none
  private
  public :: run_all

  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=0.0002536_dp)
  real(dp), parameter :: g_alu = 10.87e6_dp/(2.0_dp*1.33_dp)
  !> the RSSR of inputs/spatial_rssr_100.nml as a &general_mechanism body
  character(len=*), parameter :: rssr_body = "space = 'spatial'|n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|"// &
    "joint_kind = 'revolute', 'spherical', 'spherical', 'revolute'|joint_ground = T, F, F, T|"// &
    "joint_x = 0.0, 6.0, 0.0, 0.0|joint_y = 0.0, 0.0, 11.0, 20.0|joint_z = 0.0, 0.0, 20.0, 12.0|"// &
    "joint_axis(:, 1) = 0.0, 0.0, 1.0|joint_axis(:, 4) = 1.0, 0.0, 0.0|n_links = 3|"// &
    "link_name = 'crank', 'coupler', 'rocker'|link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|"// &
    "link_length = 6.0, 24.0, 12.0|n_drivers = 1|driver_joint = 1|driver_rate = 100.0"
  !> a planar two-link arm: upper arm 10 in from the grounded shoulder S, forearm 8 in to the free tip T
  character(len=*), parameter :: arm_body = "n_joints = 3|joint_name = 'S', 'E', 'T'|"// &
    "joint_kind = 'revolute', 'revolute', 'free'|joint_ground = T, F, F|joint_x = 0.0, 10.0, 18.0|n_links = 2|"// &
    "link_name = 'upper', 'fore'|link_joint1 = 1, 2|link_joint2 = 2, 3|n_drivers = 2|driver_joint = 1, 2|"// &
    "driver_profile = 2*'spinup'|driver_rate = 20.0, -30.0|driver_spinup_time = 2*0.05"
  !> the planar four-bar of inputs/general_fourbar_150.nml, its crank at 20 rad/s
  character(len=*), parameter :: fourbar_body = "n_joints = 4|joint_name = 'A', 'B', 'C', 'D'|"// &
    "joint_kind = 4*'revolute'|joint_ground = T, F, F, T|joint_x = 0.0, 5.0, 8.5, 10.0|"// &
    "joint_y = 0.0, 0.0, 10.0, 0.0|n_links = 3|link_name = 'crank', 'coupler', 'rocker'|"// &
    "link_joint1 = 1, 2, 4|link_joint2 = 2, 3, 3|link_length = 5.0, 11.0, 10.5|n_drivers = 1|driver_joint = 1|"// &
    "driver_rate = 20.0"

  !> the spatial three-axis manipulator of inputs/general_manipulator_3axis.nml
  !> (waist, shoulder and elbow out and back by A sin^4(pi t / 1 s), tables every 0.05 s),
  !> its time axis shifted by -0.3 s: t = 0 is the deck's 0.3 s, the joints turning and accelerating
  character(len=*), parameter :: tt = "-0.3, -0.25, -0.2, -0.15, -0.1, -0.05, 0.0, 0.05, 0.1, 0.15, 0.2, 0.25, "// &
    "0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7"
  character(len=*), parameter :: manipulator_body = "space = 'spatial'|n_joints = 4|"// &
    "joint_name = 'W', 'S', 'E', 'T'|joint_kind = 'revolute', 'revolute', 'revolute', 'free'|"// &
    "joint_ground = T, F, F, F|joint_x = 0.0, 0.0, 20.0, 36.0|joint_z = 0.0, 8.0, 8.0, 8.0|"// &
    "joint_axis(:, 1) = 0.0, 0.0, 1.0|joint_axis(:, 2) = 0.0, 1.0, 0.0|joint_axis(:, 3) = 0.0, 1.0, 0.0|"// &
    "n_links = 3|link_name = 'column', 'upper', 'fore'|link_joint1 = 1, 2, 3|link_joint2 = 2, 3, 4|"// &
    "n_drivers = 3|driver_joint = 1, 2, 3|driver_profile = 3*'table'|driver_n_table = 3*21|"// &
    "driver_table_t(:, 1) = "//tt//"|driver_table_t(:, 2) = "//tt//"|driver_table_t(:, 3) = "//tt//"|"// &
    "driver_table_value(:, 1) = 0.0, 0.035932, 0.547118, 2.54881, 7.16186, 15, 25.7029, 37.8159, 49.0881, "// &
    "57.0993, 60, 57.0993, 49.0881, 37.8159, 25.7029, 15, 7.16186, 2.54881, 0.547118, 0.035932, 0.0|"// &
    "driver_table_value(:, 2) = 0.0, -0.017966, -0.273559, -1.27441, -3.58093, -7.5, -12.8514, -18.908, "// &
    "-24.5441, -28.5497, -30, -28.5497, -24.5441, -18.908, -12.8514, -7.5, -3.58093, -1.27441, -0.273559, "// &
    "-0.017966, 0.0|"// &
    "driver_table_value(:, 3) = 0.0, 0.026949, 0.410338, 1.91161, 5.3714, 11.25, 19.2772, 28.3619, 36.8161, "// &
    "42.8245, 45, 42.8245, 36.8161, 28.3619, 19.2772, 11.25, 5.3714, 1.91161, 0.410338, 0.026949, 0.0"

contains

  subroutine run_all()
    call run_test('rssr_general_equals_spatial_model', test_rssr_equals_spatial)
    call run_test('rssr_joint_rules_unknowns', test_rssr_rules)
    call run_test('driven_rssr_jacobi_energy_balance', test_rssr_balance)
    call run_test('driven_two_link_arm_jacobi_energy_balance', test_arm_balance)
    call run_test('spatial_manipulator_jacobi_energy_balance', test_manipulator_balance)
    call run_test('unsupported_joints_refused', test_refused)
    call run_test('bad_general_links_input_names_the_variable', test_bad_links)
    call run_test('mounted_fourbar_equations_against_dense_solve', test_mounted_equations)
    call run_test('mounted_fourbar_jacobi_energy_balance', test_mounted_balance)
    call run_test('mount_forces_against_rigid_shaking_force', test_mount_shaking)
  end subroutine run_all

  ! ------------------------------------------------------------ helpers

  !> The kinematics of a &general_mechanism body ('|' between lines).
  subroutine make_kinematics(body, gk, err)
    character(len=*), intent(in) :: body
    type(general_kinematics_t), intent(out) :: gk
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(general_mechanism_t) :: mech
    character(len=:), allocatable :: stem
    stem = scratch_path('general_flex')
    call open_deck_text(stem, "&run|  analysis = 'general_transient'|/|&general_mechanism|"//body//"|/", deck, err)
    if (.not. err%failed()) call read_general_mechanism(deck, mech, gk, err)
    call close_deck_text(stem, deck)
  end subroutine make_kinematics

  !> The general model of a mechanism body, every link a circular bar of
  !> radius r (or a rectangular 0.5 x 0.25 in bar) with n elements.
  subroutine make_model(body, n, fx, model, err, radius, mounts)
    character(len=*), intent(in) :: body
    integer, intent(in) :: n
    type(element_effects_t), intent(in) :: fx
    type(general_flex_model_t), intent(out) :: model
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: radius
    type(support_mount_t), intent(in), optional :: mounts(:)
    type(general_kinematics_t) :: gk
    type(spatial_link_t), allocatable :: links(:)
    integer :: k
    call make_kinematics(body, gk, err)
    if (err%failed()) return
    allocate(links(gk%mech%n_links))
    do k = 1, size(links)
      links(k)%n_elements = n
      links(k)%material = alu
      links(k)%shear_modulus = g_alu
      if (present(radius)) then
        call spatial_section_init(links(k)%sec, section_circular, [radius], alu, err)
      else
        call spatial_section_init(links(k)%sec, section_rectangular, [0.5_dp, 0.25_dp], alu, err)
      end if
    end do
    call model%init_general(gk, links, fx, 0.0_dp, err, mounts=mounts)
  end subroutine make_model

  !> Mounts under the four-bar's ground joints A (1) and D (4), the same
  !> mass, stiffness and damping in every direction.
  function fourbar_mounts(m, k, c) result(mounts)
    real(dp), intent(in) :: m, k, c
    type(support_mount_t) :: mounts(2)
    mounts(1) = support_mount_t('A', 1, [m, m, m], [k, k, k], [c, c, c])
    mounts(2) = support_mount_t('D', 4, [m, m, m], [k, k, k], [c, c, c])
  end function fourbar_mounts

  !> The spatial four-bar model of the same RSSR (module spatial_model).
  subroutine make_spatial_rssr(n, fx, sm)
    integer, intent(in) :: n
    type(element_effects_t), intent(in) :: fx
    type(spatial_model_t), intent(out) :: sm
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(error_t) :: err
    integer :: k
    call spatial_fourbar_init(kin, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [6.0_dp, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 20.0_dp, 12.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 12.0_dp, 24.0_dp, 1, err)
    do k = 1, 3
      links(k)%n_elements = n
      links(k)%material = alu
      links(k)%shear_modulus = g_alu
      call spatial_section_init(links(k)%sec, section_circular, [0.25_dp], alu, err)
    end do
    call sm%init(kin, 100.0_dp, 0.0_dp, spatial_joint_spherical, spatial_joint_spherical, links, fx, 0.0_dp, err)
    call assert_true(.not. err%failed(), 'spatial rssr: '//err%text())
  end subroutine make_spatial_rssr

  ! ------------------------------------------------------------ tests

  !> Same links, elements and joints: the natural frequencies at the start,
  !> the kinetic energy of the rigid motion (q = q' = 0) and the static
  !> elastic state under the inertia loads (its strain energy) at three
  !> crank angles agree with the spatial four-bar model to 1e-9 relative
  !> (round-off of two Newton solutions of the kinematics; a wrong joint
  !> rule, frame, rate or acceleration of the rigid motion changes them by
  !> 1e-3 or more).
  subroutine test_rssr_equals_spatial()
    type(general_flex_model_t) :: gm
    type(spatial_model_t) :: sm
    type(error_t) :: err
    type(element_effects_t) :: fx
    real(dp), allocatable :: wg(:), ws(:), qg(:), qs(:), zg(:)
    real(dp) :: keg, kes, seg, ses, t
    integer :: k
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call make_model(rssr_body, 2, fx, gm, err, radius=0.25_dp)
    call assert_true(.not. err%failed(), 'general rssr: '//err%text())
    if (err%failed()) return
    call make_spatial_rssr(2, fx, sm)
    call assert_equal(gm%n, sm%n, 'the same number of unknowns')
    call assert_equal(gm%kd, sm%kd, 'the same half-bandwidth')
    if (gm%n /= sm%n) return
    allocate(wg(gm%n), ws(sm%n), qg(gm%n), qs(sm%n), zg(gm%n))
    call gm%linear_modes(wg, err)
    call sm%linear_modes(ws, err)
    do k = 1, 6
      call assert_rel_close(wg(k), ws(k), 1.0e-9_dp, 'frequency '//str_int(k))
    end do
    zg = 0.0_dp
    do k = 1, 3
      t = 0.004_dp*k
      call gm%energies(t, zg, zg, keg, seg)
      call sm%energies(t, zg, zg, kes, ses)
      call assert_rel_close(keg, kes, 1.0e-9_dp, 'kinetic energy of the rigid motion at t = '//str_int(k))
      qg = 0.0_dp
      qs = 0.0_dp
      call gm%static_state(t, qg, err)
      call sm%static_state(t, qs, err)
      call assert_true(.not. err%failed(), 'static states: '//err%text())
      call gm%energies(t, qg, zg, keg, seg)
      call sm%energies(t, qs, zg, kes, ses)
      call assert_true(ses > 1.0_dp, 'the inertia loads strain the links')
      call assert_rel_close(seg, ses, 1.0e-9_dp, 'static strain energy at t = '//str_int(k))
    end do
  end subroutine test_rssr_equals_spatial

  !> The unknowns of the joint rules: the crank clamped at A (driven), the
  !> coupler's twist held at B and free at C, no moment at the spherical
  !> joints (curvatures held), the rocker's rotation at D about the axis
  !> only; rotations local at the spherical ends.
  subroutine test_rssr_rules()
    type(general_flex_model_t) :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    integer :: ec, er
    call make_model(rssr_body, 1, fx, gm, err, radius=0.25_dp)
    call assert_true(.not. err%failed(), 'general rssr: '//err%text())
    if (err%failed()) return
    ec = gm%glinks(2)%first_element
    er = gm%glinks(3)%first_element
    call assert_true(all(gm%table%unknowns_of([1, 2, 3, 4, 5, 6], 1) == 0), 'crank clamped at A')
    call assert_true(all(gm%table%unknowns_of([7, 8], 1) > 0), 'moment passes at A')
    call assert_equal(gm%table%unknown(4, ec), 0, 'coupler twist held at B')
    call assert_true(gm%table%unknown(14, ec) > 0, 'coupler twist free at C')
    call assert_true(all(gm%table%unknowns_of([7, 8, 17, 18], ec) == 0), 'no moment at B and C')
    call assert_true(gm%el(ec)%local_rotation(1) .and. gm%el(ec)%local_rotation(2), 'coupler rotations local')
    call assert_true(all(gm%table%unknowns_of([5, 6, 7], er) == 0) .and. gm%table%unknown(4, er) > 0, &
                     'rocker at D: rotation about X only, no moment about X')
    call assert_true(all(gm%table%unknowns_of([11, 12, 13], 1) == gm%table%unknowns_of([1, 2, 3], ec)), &
                     'B translations shared')
  end subroutine test_rssr_rules

  !> The RSSR at 100 rad/s, every effect on, undamped, one element per link.
  subroutine test_rssr_balance()
    type(general_flex_model_t), target :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call make_model(rssr_body, 1, fx, gm, err, radius=0.25_dp)
    call assert_true(.not. err%failed(), 'general rssr: '//err%text())
    if (err%failed()) return
    call jacobi_balance(gm, (0.05_dp*pi/180.0_dp)/100.0_dp, 400, 1.0_dp)
  end subroutine test_rssr_balance

  !> The two-link arm (circular bars of radius 0.1 in), shoulder and elbow
  !> spun up to 20 and -30 rad/s in 0.05 s, every effect on, one element a
  !> link, undamped, over the first 5.8 ms (largest strain energy 1.5e-5
  !> lb in, balance residual 4e-13 lb in): the driven revolute between the
  !> links (rotations shared) and the free tip.
  subroutine test_arm_balance()
    type(general_flex_model_t), target :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call make_model(arm_body, 1, fx, gm, err, radius=0.1_dp)
    call assert_true(.not. err%failed(), 'arm: '//err%text())
    if (err%failed()) return
    call assert_true(all(gm%table%unknowns_of([1, 2, 3, 4, 5, 6], 1) == 0), 'upper arm clamped at the driven shoulder')
    call assert_true(all(gm%table%unknowns_of([11, 12, 13, 14, 15, 16], 1) == &
                         gm%table%unknowns_of([1, 2, 3, 4, 5, 6], 2)), 'elbow: translations and rotations shared')
    call jacobi_balance(gm, (0.05_dp*pi/180.0_dp)/30.0_dp, 200, 1.0e-6_dp)
  end subroutine test_arm_balance

  !> The spatial three-axis manipulator of inputs/general_manipulator_3axis.nml
  !> (circular bars of radius 0.5 in), one element a link, linear material,
  !> every other effect on, undamped, from the rigid state at the deck's
  !> 0.3 s (the joints turning at 2.0-4.1 rad/s and accelerating) over 0.01 s:
  !> three table drivers, two driven revolute joints between moving links
  !> whose axes turn with the waist, a free tip.
  subroutine test_manipulator_balance()
    type(general_flex_model_t), target :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    fx = element_effects_t(.true., .true., .false., .true., .true.)
    call make_model(manipulator_body, 1, fx, gm, err, radius=0.5_dp)
    call assert_true(.not. err%failed(), 'manipulator: '//err%text())
    if (err%failed()) return
    call jacobi_balance(gm, 2.0e-5_dp, 500, 1.0e-3_dp)
  end subroutine test_manipulator_balance

  !> Energy balance of a driven undamped run (test_spatial_model's RSSR
  !> balance): with L(q, q', t) = KE - SE, the Jacobi integral h = KE2 - KE0
  !> + SE obeys dh/dt = -dL/dt|_(q,q'), the explicit time dependence being the
  !> rigid motion.  KE2 - KE0 by polarisation, dL/dt by central differences
  !> (1e-8 s, the kinematics re-solved), the integral by Simpson's rule over
  !> n steps of dt.  Adams at rtol = 1e-9: bound 1e-6 of the largest strain
  !> energy (a wrong joint rule, a rate of the rigid motion inconsistent with
  !> its positions, or a wrong inertia term give O(1)); the links must
  !> deform (largest strain energy above se_min).
  subroutine jacobi_balance(gm, dt, n, se_min)
    type(general_flex_model_t), target, intent(inout) :: gm
    real(dp), intent(in) :: dt, se_min
    integer, intent(in) :: n
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:), zero(:), h(:), dldt(:)
    real(dp) :: t, kp, km, k0, se, sdum, se_max, integral, residual
    real(dp), parameter :: delta = 1.0e-8_dp
    integer :: k
    allocate(y(2*gm%n), zero(gm%n), h(0:n), dldt(0:n))
    y = 0.0_dp
    zero = 0.0_dp
    se_max = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_adams, 1.0e-9_dp, [1.0e-13_dp], err, max_steps=500000)
    do k = 0, n
      t = real(k, dp)*dt
      if (k > 0) call ode%integrate_to(gm, y, t, err)
      call assert_true(.not. err%failed(), 'integration: '//err%text())
      if (err%failed()) return
      call gm%energies(t, y(1::2), y(2::2), kp, se)
      call gm%energies(t, y(1::2), -y(2::2), km, sdum)
      call gm%energies(t, y(1::2), zero, k0, sdum)
      h(k) = 0.5_dp*(kp + km) - 2.0_dp*k0 + se
      se_max = max(se_max, se)
      call gm%energies(t + delta, y(1::2), y(2::2), kp, sdum)
      call gm%energies(t - delta, y(1::2), y(2::2), km, se)
      dldt(k) = (kp - sdum - km + se)/(2.0_dp*delta)
      call gm%set_time(t)
    end do
    integral = 0.0_dp
    do k = 0, n - 2, 2
      integral = integral + dt/3.0_dp*(dldt(k) + 4.0_dp*dldt(k + 1) + dldt(k + 2))
    end do
    residual = h(n) - h(0) + integral
    call assert_true(se_max > se_min, 'the links deform (strain energy '//str_real(se_max)//')')
    call assert_close(residual, 0.0_dp, 1.0e-6_dp*se_max, 'h(t1) - h(t0) + int dL/dt dt = 0')
    print '(a,es10.3,a,es10.3)', '    Jacobi balance residual ', residual, ' lb in; max strain energy ', se_max
  end subroutine jacobi_balance

  !> Joints the flexible analysis does not model are input errors naming the joint.
  subroutine test_refused()
    type(general_flex_model_t) :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    call make_model("n_joints = 3|joint_name = 'A', 'B', 'C'|joint_kind = 'revolute', 'revolute', 'slider'|"// &
      "joint_ground = T, F, T|joint_x = 0.0, 2.0, 7.9|joint_y = 0.0, 0.0, 0.5|joint_axis(:, 3) = 1.0, 0.0, 0.0|"// &
      "n_links = 2|link_length = 2.0, 6.0|"// &
      "link_joint1 = 1, 2|link_joint2 = 2, 3|n_drivers = 1|driver_joint = 1|driver_rate = 10.0", 1, fx, gm, err)
    call assert_true(err%failed() .and. err%code == 2, 'slider refused')
    call assert_true(index(err%text(), '''C'' is slider') > 0, 'names the joint: '//err%text())
  end subroutine test_refused

  !> A bad &general_links value: code 2 naming the deck, the group, the
  !> variable with its link index, and the line.
  subroutine test_bad_links()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    call run_deck(run_general_transient, scratch_path('general_links_bad'), &
      "&run|  analysis = 'general_transient'|/|&general_mechanism|"//arm_body//"|/|&general_links|"// &
      "  link_section = 'circular', 'circular'|  link_radius = 0.1, -0.2|/", err, lines)
    call assert_true(err%failed() .and. err%code == 2, 'refused with code 2')
    call assert_true(index(err%text(), 'deck ''') > 0 .and. index(err%text(), 'group &general_links') > 0, &
                     'names deck and group: '//err%text())
    call assert_true(index(err%text(), 'link_radius(2)') > 0, 'names the variable: '//err%text())
  end subroutine test_bad_links

  !> The four-bar on damped mounts: the mounts' translations are the link
  !> ends' at A and D, and q'' (the links' factored mass with the mounts'
  !> Woodbury update) satisfies the dense (M + P^T m P) q'' = F + P^T f_m
  !> to round-off at an arbitrary state (a wrong update or a missing mount
  !> force leaves a residual of the order of the mount force).
  subroutine test_mounted_equations()
    type(general_flex_model_t) :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    real(dp), allocatable :: q(:), qd(:), qdd(:), f(:), mass(:, :), stiff(:, :)
    integer :: i
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call make_model(fourbar_body, 2, fx, gm, err, mounts=fourbar_mounts(0.02_dp, 3.0e4_dp, 5.0_dp))
    call assert_true(.not. err%failed(), 'mounted four-bar: '//err%text())
    if (err%failed()) return
    call assert_true(all(gm%table%unknowns_of([1, 2, 3], 1) == gm%support%mounts(1)%dofs) .and. &
                     all(gm%support%mounts(1)%dofs > 0), 'the crank''s end at A moves with mount A')
    call assert_true(all(gm%table%unknowns_of([1, 2, 3], gm%glinks(3)%first_element) == gm%support%mounts(2)%dofs), &
                     'the rocker''s end at D moves with mount D')
    call assert_true(all(gm%table%unknowns_of([4, 5, 6], 1) == 0), 'the crank''s rotations still held at A')
    allocate(q(gm%n), qd(gm%n), qdd(gm%n), f(gm%n), mass(gm%n, gm%n), stiff(gm%n, gm%n))
    q = [(1.0e-4_dp*sin(1.3_dp*i), i = 1, gm%n)]
    qd = [(2.0e-2_dp*cos(0.7_dp*i), i = 1, gm%n)]
    call gm%accelerations(0.01_dp, q, qd, qdd)
    f = gm%force
    call gm%support%add_forces(q, qd, gm%gravity, f)
    call assert_true(maxval(abs(f - gm%force)) > 1.0_dp, 'the mounts exert forces')
    call gm%assemble_dense(q, mass, stiff)
    call assert_close(maxval(abs(matmul(mass, qdd) - f)), 0.0_dp, 1.0e-9_dp*maxval(abs(f)), 'M q'''' = F')
  end subroutine test_mounted_equations

  !> The four-bar at 20 rad/s on undamped mounts (0.02 lb s^2/in, 3e4 lb/in:
  !> 1225 rad/s) from rest, every effect on, undamped: the Jacobi balance of
  !> jacobi_balance with the mounts' kinetic and spring energy in KE and SE
  !> (leaving either out, or a mount force inconsistent with its energy,
  !> breaks it by the mounts' share, which must be above 5 % of the links'
  !> largest strain energy over the span).
  subroutine test_mounted_balance()
    type(general_flex_model_t), target :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    real(dp) :: km, sm, ke, se, mount_max, links_max
    real(dp), allocatable :: y(:)
    type(lsode_t) :: ode
    integer :: k
    fx = element_effects_t(.true., .true., .true., .true., .true.)
    call make_model(fourbar_body, 1, fx, gm, err, mounts=fourbar_mounts(0.02_dp, 3.0e4_dp, 0.0_dp))
    call assert_true(.not. err%failed(), 'mounted four-bar: '//err%text())
    if (err%failed()) return
    allocate(y(2*gm%n))
    y = 0.0_dp
    mount_max = 0.0_dp
    links_max = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_adams, 1.0e-9_dp, [1.0e-13_dp], err, max_steps=500000)
    do k = 1, 40
      call ode%integrate_to(gm, y, 1.0e-4_dp*k, err)
      if (err%failed()) exit
      call gm%support%energies(y(1::2), y(2::2), km, sm)
      call gm%energies(1.0e-4_dp*k, y(1::2), y(2::2), ke, se)
      mount_max = max(mount_max, km + sm)
      links_max = max(links_max, se - sm)
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    print '(a,es10.3,a,es10.3,a)', '    largest mount energy ', mount_max, ' lb in; links'' strain energy ', &
      links_max, ' lb in'
    call assert_true(mount_max > 0.05_dp*links_max, 'the mounts take a share of the energy')
    call jacobi_balance(gm, 1.0e-5_dp, 400, 0.1_dp*links_max)
  end subroutine test_mounted_balance

  !> The force the support receives: the four-bar at 20 rad/s (its links'
  !> first frequency far above the crank's) on light stiff mounts (1e-4
  !> lb s^2/in, 1e4 lb/in, critically damped), the linear element with its
  !> rotary inertia and Coriolis terms, from the static state at its
  !> quasi-static rate, by BDF on the model's Newton matrix.  The sum of the
  !> forces the mounts carry, k u + c u', equals minus the shaking force of the rigid four-bar,
  !> the rate of its momentum sum m a_G, computed here independently of the
  !> model: the joints of the four-bar by its closed-form position (circle
  !> intersection), the link centres' accelerations by central differences.
  !> Over the first half revolution (rows every 10 degrees) the largest
  !> difference is 1.5 % of the shaking force's peak (the links' elastic
  !> momentum and the mounts' inertia; (omega/omega_1)^2 is about 1 %):
  !> bound 2.5 %; a wrong mass, sign or direction gives O(1).
  subroutine test_mount_shaking()
    type(general_flex_model_t), target :: gm
    type(error_t) :: err
    type(element_effects_t) :: fx
    type(lsode_t) :: ode
    real(dp), allocatable :: y(:), qm(:), qp(:), atol(:)
    real(dp) :: t, carried(3), shaking(2), worst, peak, h
    integer :: k
    real(dp), parameter :: omega = 20.0_dp, c = 2.0_dp*sqrt(1.0e-4_dp*1.0e4_dp)
    fx = element_effects_t(.false., .false., .false., .true., .true.)
    call make_model(fourbar_body, 1, fx, gm, err, mounts=fourbar_mounts(1.0e-4_dp, 1.0e4_dp, c))
    call assert_true(.not. err%failed(), 'mounted four-bar: '//err%text())
    if (err%failed()) return
    allocate(y(2*gm%n), qm(gm%n), qp(gm%n), atol(2*gm%n))
    h = 1.0e-4_dp
    y = 0.0_dp
    qm = 0.0_dp
    qp = 0.0_dp
    call gm%static_state(-h, qm, err)
    call gm%static_state(h, qp, err)
    y(1::2) = 0.5_dp*(qm + qp)
    call gm%static_state(0.0_dp, y(1::2), err)
    y(2::2) = (qp - qm)/(2.0_dp*h)
    call assert_true(.not. err%failed(), 'static start: '//err%text())
    atol(1::2) = 1.0e-10_dp
    atol(2::2) = 1.0e-6_dp
    call ode%init(size(y), 0.0_dp, mf_bdf_band_user, 1.0e-7_dp, atol, err, ml=2*gm%kd + 1, mu=2*gm%kd + 1, &
                  max_steps=500000)
    worst = 0.0_dp
    peak = 0.0_dp
    do k = 0, 18
      t = (k*10.0_dp*pi/180.0_dp)/omega
      if (k > 0) call ode%integrate_to(gm, y, t, err)
      if (err%failed()) exit
      carried = gm%support%carried_force(1, y(1::2), y(2::2)) + gm%support%carried_force(2, y(1::2), y(2::2))
      shaking = rigid_shaking(t, omega, gm%glinks(1)%sec%area*alu%rho)
      worst = max(worst, norm2(carried(1:2) + shaking))
      peak = max(peak, norm2(shaking))
      call assert_close(carried(3), 0.0_dp, 1.0e-9_dp*norm2(shaking), 'no force out of the plane')
    end do
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    print '(a,es10.3,a,es10.3,a)', '    largest |sum of mount forces + shaking force| ', worst, ' lb of a peak ', &
      peak, ' lb'
    call assert_true(peak > 1.0_dp, 'the four-bar shakes')
    call assert_close(worst, 0.0_dp, 0.025_dp*peak, 'mount forces = - shaking force')
  end subroutine test_mount_shaking

  !> The shaking force (lb, X and Y) of the rigid four-bar of fourbar_body at
  !> time t, crank at omega t, links of mass rho A per length: sum m a_G by
  !> central differences (step 1e-5 / omega s) of the closed-form positions.
  function rigid_shaking(t, omega, rho_a) result(f)
    real(dp), intent(in) :: t, omega, rho_a
    real(dp) :: f(2)
    real(dp) :: g(2, -1:1), dt
    integer :: s
    dt = 1.0e-5_dp/omega
    do s = -1, 1
      g(:, s) = first_moment(omega*(t + s*dt))
    end do
    f = rho_a*(g(:, 1) - 2.0_dp*g(:, 0) + g(:, -1))/dt**2
  end function rigid_shaking

  !> sum L_i x_G,i of the rigid four-bar (A at 0, D at (10, 0); crank 5,
  !> coupler 11, rocker 10.5) at crank angle theta, C on the branch above AD.
  function first_moment(theta) result(s)
    real(dp), intent(in) :: theta
    real(dp) :: s(2)
    real(dp), parameter :: d(2) = [10.0_dp, 0.0_dp], lc = 11.0_dp, lr = 10.5_dp
    real(dp) :: b(2), bd(2), e, a, hh, cc(2), u(2)
    b = 5.0_dp*[cos(theta), sin(theta)]
    bd = d - b
    e = norm2(bd)
    u = bd/e
    a = (lc**2 - lr**2 + e**2)/(2.0_dp*e)
    hh = sqrt(lc**2 - a**2)
    cc = b + a*u + hh*[-u(2), u(1)]
    if (cc(2) < 0.0_dp) cc = b + a*u - hh*[-u(2), u(1)]
    s = 5.0_dp*0.5_dp*b + lc*0.5_dp*(b + cc) + lr*0.5_dp*(d + cc)
  end function first_moment

  function str_int(k) result(s)
    integer, intent(in) :: k
    character(len=:), allocatable :: s
    character(len=12) :: b
    write(b, '(i0)') k
    s = trim(b)
  end function str_int

  function str_real(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=16) :: b
    write(b, '(es12.4)') x
    s = trim(adjustl(b))
  end function str_real
end module test_general_flex_suite

program test_general_flex
  use test_general_flex_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_general_flex')
end program test_general_flex
