!> Joint reactions (src/model/joint_reactions.f90) and the section and
!> link-point responses (src/model/transient_response.f90) against closed
!> forms computed here, independently of the element and the assembly:
!>  - the rigid four-bar's pin forces and crank torque from the Newton-Euler
!>    equations of its three links (a 9 x 9 linear system), against the
!>    model's reactions with very stiff links in quasi-static equilibrium;
!>  - a cantilever under a tip load: root force P, root moment P L, bending
!>    moment M(x) = -P (L - x) (= EI w''), chord deflection at mid-span;
!>  - a simply supported beam under a central load: mid-span deflection
!>    relative to the chord P L^3/(48 EI);
!>  - a spinning bar's axial force N(x) = rho A w^2 (L^2 - x^2)/2 (with the
!>    centrifugal softening of the axial stretch, exactly);
!>  - a flexible four-bar in motion: a pin's forces on its two links are
!>    equal and opposite and a pin transmits no moment.
module test_joint_reactions_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use element_effects, only: element_effects_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use mechanism_model, only: mechanism_model_t
  use external_loads, only: point_load_t
  use joint_reactions, only: joint_reactions_t
  use transient_response, only: section_values_t, section_at, element_section_peaks, link_point_t, &
                                link_point_response
  use lsode_solver, only: lsode_t, mf_bdf_full_user
  use transient_fixtures, only: fourbar_input, cantilever_input, beam_input, beam_length, e1, inertia, area, rho, rtoa, &
                                rigid_fourbar_forces, rigid_limit_state, fourbar_unknowns
  use mechanism_fixtures, only: slider_crank_input
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('rigid_fourbar_pin_forces_match_newton_euler_9x9', test_rigid_fourbar)
    call run_test('cantilever_tip_load_root_force_moment_and_chord', test_cantilever)
    call run_test('simply_supported_central_load_chord_deflection_pl3_48ei', test_simply_supported)
    call run_test('spinning_bar_axial_force_rho_a_w2_l2_minus_x2_over_2', test_spinning_bar)
    call run_test('moving_flexible_fourbar_pin_forces_equal_and_opposite', test_action_reaction)
    call run_test('frictionless_slider_guide_pushes_only_normal_to_the_guide', test_slider_guide)
  end subroutine run_all

  subroutine build(inp, effects, formulation, mech, model, ok, beta, point_loads)
    type(mechanism_input_t), intent(in) :: inp
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: formulation
    type(mechanism_t), intent(out) :: mech
    type(mechanism_model_t), intent(out) :: model
    logical, intent(out) :: ok
    real(dp), intent(in), optional :: beta   !< stiffness-proportional damping (default none)
    type(point_load_t), intent(in), optional :: point_loads(:)   !< without gravity (default none)
    type(error_t) :: err
    real(dp) :: b
    type(point_load_t), allocatable :: loads(:)
    b = 0.0_dp
    if (present(beta)) b = beta
    allocate(loads(0))
    if (present(point_loads)) loads = point_loads
    call build_mechanism(inp, mech, err)
    if (.not. err%failed()) call model%init_mechanism(mech, effects, formulation, b, err, gravity=[0.0_dp, 0.0_dp], &
                                                      point_loads=loads)
    ok = .not. err%failed()
    call assert_true(ok, 'model: '//err%text())
  end subroutine build

  !> The linear model of `inp` under a load p_load downward at the end of
  !> `element`, in static equilibrium q, and the joint reactions there.
  logical function loaded_statics(inp, formulation, element, p_load, mech, model, q, jr) result(ok)
    type(mechanism_input_t), intent(in) :: inp
    character(len=*), intent(in) :: formulation
    integer, intent(in) :: element
    real(dp), intent(in) :: p_load
    type(mechanism_t), intent(out) :: mech
    type(mechanism_model_t), intent(out) :: model
    real(dp), allocatable, intent(out) :: q(:)
    type(joint_reactions_t), intent(out) :: jr
    type(error_t) :: err
    real(dp), allocatable :: zero(:)
    call build(inp, element_effects_t(), formulation, mech, model, ok, &
               point_loads=[point_load_t(element=element, x_over_l=1.0_dp, force=[0.0_dp, -p_load])])
    if (.not. ok) return
    allocate(q(model%n), zero(model%n))
    q = 0.0_dp
    zero = 0.0_dp
    call model%static_equilibrium(0.0_dp, q, 1, err)
    call assert_true(.not. err%failed(), 'static solve: '//err%text())
    call jr%init(mech)
    if (.not. err%failed()) call jr%compute(model, 0.0_dp, q, zero, err)
    ok = .not. err%failed()
  end function loaded_statics

  !> The model at rest in its rigid state at t = 0, and BDF (MF 21) on it.
  subroutine start_at_rest(model, rtol, atol_value, ode, y)
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: rtol, atol_value
    type(lsode_t), intent(out) :: ode
    real(dp), allocatable, intent(out) :: y(:)
    real(dp), allocatable :: atol(:)
    type(error_t) :: err
    allocate(y(model%state_size()), atol(model%state_size()))
    y = 0.0_dp
    atol = atol_value
    call ode%init(size(y), 0.0_dp, mf_bdf_full_user, rtol, atol, err)
    call assert_true(.not. err%failed(), 'integrator: '//err%text())
  end subroutine start_at_rest

  !> Integrate on to t and compute the joint reactions there (false if either fails).
  logical function reactions_at(ode, model, y, jr, t) result(ok)
    type(lsode_t), intent(inout) :: ode
    type(mechanism_model_t), intent(inout), target :: model
    real(dp), intent(inout), contiguous :: y(:)
    type(joint_reactions_t), intent(inout) :: jr
    real(dp), intent(in) :: t
    type(error_t) :: err
    call ode%integrate_to(model, y, t, err)
    call assert_true(.not. err%failed(), 'integration: '//err%text())
    if (.not. err%failed()) call jr%compute(model, t, y(1::2), y(2::2), err)
    call assert_true(.not. err%failed(), 'reactions: '//err%text())
    ok = .not. err%failed()
  end function reactions_at

  ! ------------------------------------------------------------------ rigid four-bar

  !> Links 1e6 times stiffer than aluminium (E = 1.087e13 psi), linear
  !> model, 150 rad/s, at crank angles 0, 50, ..., 300 deg: the elastic
  !> state is the quasi-static equilibrium F(q, 0, t) = 0 (the rigid limit
  !> of the steady motion; deflections ~1e-8 in), and the reactions at it
  !> must be the rigid-body ones.  Tolerance 1e-6 of the largest force (the
  !> geometric change of the loads with q is ~1e-8 relative; measured
  !> agreement ~1e-9).
  subroutine test_rigid_fourbar()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(joint_reactions_t) :: jr
    type(error_t) :: err
    real(dp) :: expect(9), got(9), t, scale, omega, shaking(2), masses(3), acc_g(2, 3)
    real(dp), allocatable :: qq(:), zero(:)
    logical :: ok
    integer :: k
    omega = 150.0_dp
    inp = fourbar_input(1, omega, 0.0_dp)
    inp%link_e1(1:3) = 1.0e6_dp*e1
    call build(inp, element_effects_t(), 'exact', mech, model, ok)
    if (.not. ok) return
    call jr%init(mech)
    call assert_equal(size(jr%ends), 6, 'link ends at joints A, B, B, C, C, D')
    allocate(qq(model%n), zero(model%n))
    zero = 0.0_dp
    do k = 0, 6
      call rigid_limit_state(model, omega, k, t, qq, err)
      call assert_true(.not. err%failed(), 'static equilibrium: '//err%text())
      if (err%failed()) return
      call jr%compute(model, t, qq, zero, err, qdd=zero)
      call assert_true(.not. err%failed(), 'reactions: '//err%text())
      got = fourbar_unknowns(jr)
      call rigid_fourbar_forces(model, omega*t, omega, expect, masses, acc_g)
      scale = maxval(abs(expect))
      call assert_all_close(got, expect, 0.0_dp, 1.0e-6_dp*scale, 'reactions vs Newton-Euler at crank angle '// &
                            rtoa(50.0_dp*k)//' deg')
      call assert_all_close(jr%ends(2)%force, -jr%ends(3)%force, 0.0_dp, 1.0e-9_dp*scale, 'pin B: equal and opposite')
      call assert_all_close(jr%ends(4)%force, -jr%ends(5)%force, 0.0_dp, 1.0e-9_dp*scale, 'pin C: equal and opposite')
      ! the ground carries the shaking force: sum of support forces = sum m a_G
      shaking = matmul(acc_g, masses)
      call assert_all_close(jr%support(1:2, 1) + jr%support(1:2, 4), shaking, 0.0_dp, 1.0e-6_dp*scale, &
                            'ground forces = shaking force')
      if (k == 0) write(*, '(4x,a,3es12.4,a,es10.2)') 'crank angle 0: F_A, T_A = ', expect(1:3), &
        '; largest difference ', maxval(abs(got - expect))
    end do
  end subroutine test_rigid_fourbar

  ! ------------------------------------------------------------------ cantilever

  !> Cantilever (L = 20 in, 4 Kear elements, linear), tip load P = -1 lb
  !> (Y): w is cubic, inside the element's quintic space, so the FE answer
  !> is exact: the clamp pushes up with 1 lb and holds the moment P L =
  !> 20 lb in (counter-clockwise); M(x) = -P (L - x);
  !> bending stress M c/I; mid-span w relative to the chord from the
  !> exact w: w(L/2) - w(L)/2 = P L^3/(16 EI) (small deflection: 1e-8 L
  !> here; tolerance 1e-6 relative).
  subroutine test_cantilever()
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(joint_reactions_t) :: jr
    type(section_values_t) :: v
    type(link_point_t) :: p
    real(dp), allocatable :: q(:)
    real(dp) :: pl, ei, x
    integer :: e
    real(dp), parameter :: p_load = 1.0_dp
    if (.not. loaded_statics(cantilever_input(4, 0.0_dp), 'exact', 4, p_load, mech, model, q, jr)) return
    pl = p_load*beam_length
    ei = e1*inertia
    call assert_all_close(jr%ends(1)%force, [0.0_dp, p_load], 0.0_dp, 1.0e-9_dp*p_load, 'root force')
    call assert_rel_close(jr%ends(1)%moment, pl, 1.0e-9_dp, 'root moment P L')
    call assert_all_close(jr%ends(2)%force, [0.0_dp, 0.0_dp], 0.0_dp, 1.0e-9_dp*p_load, 'free end: no force')
    call assert_all_close(jr%support(1:2, 1), [0.0_dp, p_load], 0.0_dp, 1.0e-9_dp*p_load, 'ground force at the clamp')
    do e = 1, 4
      x = (e - 1)*beam_length/4
      v = section_at(model, e, q, 0.0_dp)
      call assert_rel_close(v%moment, -p_load*(beam_length - x), 1.0e-9_dp, 'M(x) = -P (L - x) at x = '//rtoa(x))
      call assert_rel_close(v%bending_stress, v%moment*0.5_dp/inertia, 1.0e-9_dp, 'bending stress M c/I')
      call assert_close(v%axial_force, 0.0_dp, 1.0e-9_dp*p_load, 'no axial force')
    end do
    v = element_section_peaks(model, 1, q)
    call assert_rel_close(v%moment, -pl, 1.0e-9_dp, 'element 1 peak moment: the root')
    p%link = 1
    p%s = 0.5_dp
    call link_point_response(model, mech, q, p)
    call assert_rel_close(p%w, -5.0_dp*p_load*beam_length**3/(48.0_dp*ei), 1.0e-9_dp, 'w(L/2)')
    call assert_rel_close(p%chord, p_load*beam_length**3/(16.0_dp*ei), 1.0e-6_dp, 'mid-span w relative to the chord')
  end subroutine test_cantilever

  !> Beam pinned at both ends (L = 20 in, 2 consistent elements, linear),
  !> load P at mid-span: deflection relative to the chord P L^3/(48 EI)
  !> (exact in the element space); ground forces P/2 each.
  subroutine test_simply_supported()
    type(mechanism_t) :: mech
    type(mechanism_model_t) :: model
    type(joint_reactions_t) :: jr
    type(link_point_t) :: p
    real(dp), allocatable :: q(:)
    real(dp), parameter :: p_load = 10.0_dp
    if (.not. loaded_statics(beam_input('ground_pin', 2), 'consistent', 1, p_load, mech, model, q, jr)) return
    p%link = 1
    p%s = 0.5_dp
    call link_point_response(model, mech, q, p)
    call assert_rel_close(p%chord, -p_load*beam_length**3/(48.0_dp*e1*inertia), 1.0e-9_dp, 'P L^3/(48 EI)')
    call assert_all_close(jr%support(1:2, 1), [0.0_dp, 0.5_dp*p_load], 0.0_dp, 1.0e-9_dp*p_load, 'left support P/2')
    call assert_all_close(jr%support(1:2, 2), [0.0_dp, 0.5_dp*p_load], 0.0_dp, 1.0e-9_dp*p_load, 'right support P/2')
    call assert_close(jr%ends(1)%moment, 0.0_dp, 1.0e-9_dp*p_load*beam_length, 'a pin carries no moment')
  end subroutine test_simply_supported

  !> Bar (L = 20 in, 4 consistent elements) clamped to a shaft turning at
  !> 150 rad/s, in the state F(q, 0, t) = 0: E A u'' + rho A w^2 x = 0,
  !> N = rho A w^2 (L^2 - x^2)/2 (a quadratic, inside the element's quintic
  !> u).  That state holds the nodal translations still in the inertial
  !> frame, so the centrifugal load on the stretch itself (rho A w^2 u of the
  !> steady rotating state, 5/12 (kL)^2 = 9e-5 of N(0) with k^2 = rho w^2/E)
  !> acts only on the interior field: measured 1.1e-6 of N(0) from the
  !> formula; tolerance 1e-5 (a wrong factor or sign fails by 1e-2 or more).
  !> Linear model, and the exact stretch with coupling (the same here: no
  !> bending).
  subroutine test_spinning_bar()
    real(dp) :: n0
    real(dp), parameter :: w = 150.0_dp
    n0 = rho*area*w**2*beam_length**2/2.0_dp
    call spinning_bar(element_effects_t(), 1.0e-5_dp, ' (linear)')
    call spinning_bar(element_effects_t(stretching=.true., coupling=.true.), 1.0e-5_dp, ' (stretching, coupling)')
  contains
    subroutine spinning_bar(effects, tol, what)
      type(element_effects_t), intent(in) :: effects
      real(dp), intent(in) :: tol
      character(len=*), intent(in) :: what
      type(mechanism_t) :: mech
      type(mechanism_model_t) :: model
      type(joint_reactions_t) :: jr
      type(error_t) :: err
      type(section_values_t) :: v
      real(dp), allocatable :: q(:), zero(:)
      real(dp) :: x, n_expect
      logical :: ok
      integer :: i
      call build(cantilever_input(4, w), effects, 'consistent', mech, model, ok)
      if (.not. ok) return
      allocate(q(model%n), zero(model%n))
      q = 0.0_dp
      zero = 0.0_dp
      call model%static_equilibrium(0.0_dp, q, 1, err)
      call assert_true(.not. err%failed(), 'static solve: '//err%text())
      do i = 0, 8
        x = i*beam_length/8
        v = section_at(model, min(4, 1 + i/2), q, merge(1.0_dp, 0.5_dp*mod(i, 2), i == 8))
        n_expect = rho*area*w**2*(beam_length**2 - x**2)/2.0_dp
        call assert_close(v%axial_force, n_expect, tol*n0, 'N at x = '//rtoa(x)//what)
        call assert_close(v%axial_stress, v%axial_force/area, 1.0e-9_dp*n0/area, 'axial stress N/A')
      end do
      call jr%init(mech)
      call jr%compute(model, 0.0_dp, q, zero, err, qdd=zero)
      ! the bar lies along X at t = 0: the clamp pulls it towards the axis
      v = section_at(model, 1, q, 0.0_dp)
      call assert_close(jr%ends(1)%force(1), -v%axial_force, tol*n0, 'the clamp pulls with N(0)')
    end subroutine spinning_bar
  end subroutine test_spinning_bar

  ! ------------------------------------------------------------------ moving four-bar

  !> The §8.1 four-bar, 2 consistent elements per link, all effects but the
  !> material (its strain passes the law's peak at 150 rad/s), undamped, integrated by bdf over 60 deg from the rigid state:
  !> every 10 deg a pin's forces on its two links cancel (the assembled
  !> equations: 1e-8 of the largest force; round-off of the accelerations)
  !> and the moment on a pinned end vanishes (1e-8 of force x coupler length).
  subroutine test_action_reaction()
    type(mechanism_t) :: mech
    type(mechanism_model_t), target :: model
    type(joint_reactions_t) :: jr
    type(lsode_t) :: ode
    real(dp), allocatable :: y(:)
    real(dp) :: t, scale
    logical :: ok
    integer :: k
    real(dp), parameter :: w = 150.0_dp
    call build(fourbar_input(2, w, 0.0_dp), element_effects_t(.true., .true., .false., .true., .true.), 'consistent', &
               mech, model, ok)
    if (.not. ok) return
    call jr%init(mech)
    call start_at_rest(model, 1.0e-6_dp, 1.0e-9_dp, ode, y)
    do k = 1, 6
      t = (10.0_dp*k*pi/180.0_dp)/w
      if (.not. reactions_at(ode, model, y, jr, t)) return
      scale = maxval([(maxval(abs(jr%ends(k)%force)), k = 1, size(jr%ends))])
      call assert_all_close(jr%ends(2)%force, -jr%ends(3)%force, 0.0_dp, 1.0e-8_dp*scale, 'pin B at '//rtoa(10.0_dp*k))
      call assert_all_close(jr%ends(4)%force, -jr%ends(5)%force, 0.0_dp, 1.0e-8_dp*scale, 'pin C at '//rtoa(10.0_dp*k))
      call assert_close(jr%ends(3)%moment, 0.0_dp, 1.0e-8_dp*scale*11.0_dp, 'coupler end at B: no moment')
      call assert_close(jr%ends(6)%moment, 0.0_dp, 1.0e-8_dp*scale*11.0_dp, 'rocker end at D: no moment')
      call assert_true(abs(jr%ends(1)%moment) > 1.0e-3_dp*scale, 'the clamp carries the driving torque')
    end do
  end subroutine test_action_reaction

  !> Slider-crank (crank 5 clamped, coupler 11, block of 3.5e-4 lb s^2/in on
  !> a guide at 30 deg through the crank axis), 2 Kear elements per link,
  !> linear, 150 rad/s, damped, integrated by bdf: every 15 deg the guide's
  !> force on the mechanism has no component along the guide (the block's
  !> translation along it is a free unknown: 1e-9 of the force), while its
  !> normal component is of the order of the crank's inertia loads.
  subroutine test_slider_guide()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t), target :: model
    type(joint_reactions_t) :: jr
    type(lsode_t) :: ode
    real(dp), allocatable :: y(:)
    real(dp) :: t, guide(2), along, normal
    integer :: k
    logical :: ok
    real(dp), parameter :: w = 150.0_dp, guide_deg = 30.0_dp
    inp = slider_crank_input(5.0_dp, 11.0_dp, 0.0_dp)
    inp%joint_guide_deg(3) = guide_deg
    inp%joint_mass(3) = 3.5e-4_dp
    inp%link_n_elements(1:2) = 2
    inp%omega = w
    call build(inp, element_effects_t(), 'exact', mech, model, ok, beta=1.0e-5_dp)
    if (.not. ok) return
    call jr%init(mech)
    guide = [cos(guide_deg*pi/180.0_dp), sin(guide_deg*pi/180.0_dp)]
    call start_at_rest(model, 1.0e-7_dp, 1.0e-10_dp, ode, y)
    do k = 1, 24
      t = (15.0_dp*k*pi/180.0_dp)/w
      if (.not. reactions_at(ode, model, y, jr, t)) return
      along = dot_product(jr%support(1:2, 3), guide)
      normal = abs(guide(1)*jr%support(2, 3) - guide(2)*jr%support(1, 3))
      call assert_close(along, 0.0_dp, 1.0e-9_dp*maxval(abs(jr%ends(1)%force)), 'no force along the guide at '// &
                        rtoa(15.0_dp*k)//' deg')
      if (k == 6) call assert_true(normal > 1.0e-3_dp*maxval(abs(jr%ends(1)%force)), 'the guide carries a normal force')
    end do
  end subroutine test_slider_guide
end module test_joint_reactions_suite

program test_joint_reactions
  use assertions, only: finish_suite
  use test_joint_reactions_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_joint_reactions')
end program test_joint_reactions
