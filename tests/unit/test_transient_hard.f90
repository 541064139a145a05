!> Hard cases of the transient analysis (issue 3): each run either stays
!> right (checked against a tighter run) or stops with a diagnosis that
!> names where and why, never with a silent NaN.  Crank speed at the first
!> natural frequency; very stiff links (Adams gives up naming stiffness and
!> BDF, BDF completes); strain past the peak of the Ramberg-Osgood law; a
!> linkage that cannot assemble at some crank angle.  The same cases run as
!> decks: tests/decks/hard_*.nml (exit status 3 and message) and
!> inputs/hard_*.nml (reference outputs).
module test_transient_hard_suite
  use kinds, only: dp, pi, two_pi
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use element_effects, only: element_effects_t
  use planar_element, only: stress_report_t
  use mechanism_model, only: mechanism_model_t
  use lsode_solver, only: lsode_t, mf_adams, mf_bdf_full_user
  use transient_fixtures
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('crank_at_first_natural_frequency_stays_right', test_resonance_linear)
    call run_test('crank_at_first_natural_frequency_with_material_stops_past_peak', test_resonance_material)
    call run_test('stiff_links_adams_reports_stiffness_bdf_completes', test_stiff_links)
    call run_test('strain_past_peak_names_element_time_and_strain', test_past_peak)
    call run_test('linkage_that_cannot_assemble_names_the_crank_angle', test_no_assembly)
  end subroutine run_all

  !> Run the §8.1-style model from the rigid state to t_end with the given
  !> method; peak |stress| of every element sampled every 5 deg of crank.
  subroutine run_fourbar(inp, effects, beta, mf, rtol, atol_q, atol_qd, t_end, peak, err, max_steps)
    type(mechanism_input_t), intent(in) :: inp
    type(element_effects_t), intent(in) :: effects
    real(dp), intent(in) :: beta, rtol, atol_q, atol_qd, t_end
    integer, intent(in) :: mf
    real(dp), intent(out) :: peak(3)
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: max_steps
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(stress_report_t) :: rep(3)
    real(dp), allocatable :: y(:)
    real(dp) :: dt, t
    integer :: k, steps
    logical :: ok
    peak = 0.0_dp
    steps = 200000
    if (present(max_steps)) steps = max_steps
    call make_model(inp, effects, beta, model, ok)       ! with the motion table, as the decks
    if (.not. ok) return
    allocate(y(model%state_size()))
    y = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf, rtol, state_atol(size(y), atol_q, atol_qd), err, max_steps=steps)
    dt = 5.0_dp*pi/180.0_dp/inp%omega
    do k = 1, nint(t_end/dt)
      t = k*dt
      call ode%integrate_to(model, y, t, err)
      if (err%failed()) exit
      call model%set_time(t)
      call model%element_stresses(y(1::2), rep)
      peak = max(peak, rep%max_abs_stress)
    end do
    call assert_true(all(ieee_is_finite(y)), 'state stays finite, also when the run stops')
  end subroutine run_fourbar

  !> Crank at 1460 rad/s, 0.998 of the first natural frequency at the start
  !> position (1462.4 rad/s; the output header warns), linear model, beta =
  !> 1e-5 s, two turns from the rigid state: stresses of millions of psi (the
  !> linear law has no limit), but the solution is right: the peak stresses
  !> at rtol = 1e-6 and 1e-9 agree to 1e-4 (measured 3e-6).
  subroutine test_resonance_linear()
    real(dp) :: loose(3), tight(3)
    type(error_t) :: err
    call run_fourbar(fourbar_input(1, 1460.0_dp, 0.0_dp), element_effects_t(), 1.0e-5_dp, mf_bdf_full_user, &
                     1.0e-6_dp, 1.0e-12_dp, 1.0e-8_dp, 2.0_dp*two_pi/1460.0_dp, loose, err)
    call assert_true(.not. err%failed(), err%text())
    call run_fourbar(fourbar_input(1, 1460.0_dp, 0.0_dp), element_effects_t(), 1.0e-5_dp, mf_bdf_full_user, &
                     1.0e-9_dp, 1.0e-14_dp, 1.0e-10_dp, 2.0_dp*two_pi/1460.0_dp, tight, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_all_close(loose, tight, 1.0e-4_dp, 0.0_dp, 'peak stresses at rtol 1e-6 vs 1e-9')
    call assert_true(minval(tight) > 1.0e6_dp, 'resonant stresses are large: '//rtoa(minval(tight)))
  end subroutine test_resonance_linear

  !> The same crank speed with the material law on: the strain passes the
  !> peak of the Ramberg-Osgood curve (6.573e-3) within a few degrees and the
  !> run stops there, naming the element and the strain.
  subroutine test_resonance_material()
    real(dp) :: peak(3)
    type(error_t) :: err
    call run_fourbar(fourbar_input(1, 1460.0_dp, 0.0_dp), element_effects_t(material=.true.), 1.0e-5_dp, &
                     mf_bdf_full_user, 1.0e-6_dp, 1.0e-12_dp, 1.0e-8_dp, two_pi/1460.0_dp, peak, err)
    call assert_true(err%failed(), 'the run stops')
    call assert_true(index(err%text(), 'past the peak of the Ramberg-Osgood curve') > 0 .and. &
                     index(err%text(), 'in element') > 0 .and. index(err%text(), 'eps* = 0.657') > 0, err%text())
  end subroutine test_resonance_material

  !> Links 1e6 times stiffer (E1 = 1.087e13 psi: first natural frequency
  !> 1.46e6 rad/s, 1e4 times the crank speed of 150 rad/s).  Adams (MF 10)
  !> needs a step below 1/omega_max and gives up (20000 steps in one 5-deg
  !> interval) with DLSODE's ISTATE = -1 and a message that names stiffness
  !> and the BDF methods; BDF (MF 21) with beta = 1e-6 s completes a quarter
  !> turn, and the coupler stress is the quasi-static one (the same at any
  !> stiffness: 6000 psi at 20 deg, measured in inputs/hard_stiff_bdf.nml).
  subroutine test_stiff_links()
    type(mechanism_input_t) :: inp
    real(dp) :: peak(3)
    type(error_t) :: err
    inp = fourbar_input(1, 150.0_dp, 0.0_dp)
    inp%link_e1(1:3) = 1.0e6_dp*inp%link_e1(1:3)
    call run_fourbar(inp, element_effects_t(), 0.0_dp, mf_adams, 1.0e-6_dp, 1.0e-12_dp, 1.0e-12_dp, &
                     0.25_dp*two_pi/150.0_dp, peak, err, max_steps=20000)
    call assert_true(err%failed(), 'Adams stops')
    call assert_equal(err%code, -1, 'DLSODE ISTATE = -1 (excess work)')
    call assert_true(index(err%text(), 'stiff') > 0 .and. index(err%text(), 'BDF') > 0, err%text())
    call err%clear()
    call run_fourbar(inp, element_effects_t(), 1.0e-6_dp, mf_bdf_full_user, 1.0e-6_dp, 1.0e-14_dp, 1.0e-10_dp, &
                     0.25_dp*two_pi/150.0_dp, peak, err)
    call assert_true(.not. err%failed(), 'BDF completes: '//err%text())
    call assert_true(peak(2) > 1.0e3_dp .and. peak(2) < 1.0e5_dp, 'coupler stress is quasi-static: '//rtoa(peak(2)))
  end subroutine test_stiff_links

  !> All effects on, 300 rad/s from the rigid state: the start-up transient
  !> bends the crank past the peak strain of the law within 12 degrees; the
  !> message names the element, where in it, the strain, eps* and the time.
  subroutine test_past_peak()
    real(dp) :: peak(3)
    type(error_t) :: err
    call run_fourbar(fourbar_input(1, 300.0_dp, 0.0_dp), all_effects(), 0.0_dp, mf_bdf_full_user, 1.0e-6_dp, &
                     1.0e-10_dp, 1.0e-6_dp, two_pi/300.0_dp, peak, err)
    call assert_true(err%failed(), 'the run stops')
    call assert_true(index(err%text(), 'in element 1') > 0, 'names the element: '//err%text())
    call assert_true(number_after(err%text(), 'strain ') > 6.5728e-3_dp, 'names a strain past eps*: '//err%text())
    call assert_true(index(err%text(), 'eps* = 0.657281E-02') > 0, 'names the peak strain: '//err%text())
    call assert_true(index(err%text(), '(at t = ') > 0, 'names the time: '//err%text())
    call assert_true(peak(1) < 47631.0_dp*1.001_dp, 'stresses before the stop are below the law''s peak stress')
  end subroutine test_past_peak

  !> Non-Grashof four-bar (crank 6, coupler 4.5, rocker 7, ground 9: s + l =
  !> 13.5 > p + q = 13) driven through a full turn: B and D are farther apart
  !> than coupler + rocker beyond acos((36 + 81 - 11.5^2)/108) = 98.117 deg.
  !> Tabulating the motion stops at the first table angle past it (98.5 deg
  !> at 720 points per turn); direct kinematics stops during the integration
  !> at the crank angle the integrator reached, between 98.12 and 98.2 deg.
  subroutine test_no_assembly()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(mechanism_model_t), target :: model
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp), allocatable :: y(:)
    real(dp) :: theta_fail
    logical :: ok
    integer :: k
    inp = fourbar_input(1, 50.0_dp, 0.0_dp)
    inp%joint_x(4) = 9.0_dp
    inp%link_length(1:3) = [6.0_dp, 4.5_dp, 7.0_dp]
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), err%text())
    call model%init_mechanism(mech, element_effects_t(), 'exact', 1.0e-5_dp, err, table_points=720)
    call assert_true(err%failed(), 'tabulation stops')
    call assert_true(index(err%text(), 'cannot be assembled at crank angle 98.50') > 0, err%text())
    ! direct kinematics: the integrator meets the limit
    call err%clear()
    call make_model(inp, element_effects_t(), 1.0e-5_dp, model, ok, table=.false.)
    allocate(y(model%state_size()))
    y = 0.0_dp
    call ode%init(size(y), 0.0_dp, mf_bdf_full_user, 1.0e-6_dp, state_atol(size(y), 1.0e-10_dp, 1.0e-6_dp), err)
    do k = 1, 72
      call ode%integrate_to(model, y, k*5.0_dp*pi/180.0_dp/50.0_dp, err)
      if (err%failed()) exit
    end do
    call assert_true(err%failed(), 'integration stops')
    ! there the coupler and rocker are aligned: a toggle, or no assembly just past it
    call assert_true(index(err%text(), 'cannot be assembled at crank angle') > 0 .or. &
                     index(err%text(), 'toggle (dead-centre) position at crank angle') > 0, err%text())
    theta_fail = number_after(err%text(), 'at crank angle ')
    call assert_true(theta_fail > 98.11_dp .and. theta_fail < 98.5_dp, 'stops at 98.12 deg: '//rtoa(theta_fail))
    call assert_true(all(ieee_is_finite(y)), 'state finite')
  end subroutine test_no_assembly

  !> The number that follows the first occurrence of `key` in `text` (-1 if none).
  real(dp) function number_after(text, key) result(x)
    character(len=*), intent(in) :: text, key
    integer :: i, ios
    x = -1.0_dp
    i = index(text, key)
    if (i == 0) return
    read(text(i + len(key):), *, iostat=ios) x
    if (ios /= 0) x = -1.0_dp
  end function number_after
end module test_transient_hard_suite

program test_transient_hard
  use test_transient_hard_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_hard')
end program test_transient_hard
