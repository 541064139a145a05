!> Tests of a link sliding through a sleeve in the transient model (module
!> sliding_link inside mechanism_model) against the steady model, whose
!> equations of the same mechanisms are checked against finite-difference
!> Lagrange equations (test_steady_model): with the same physics (linear,
!> rotatory inertia, Coriolis/Euler terms, the same damping) the transient
!> model's accelerations M^-1 F(Q, Q_d, t) equal the steady model's
!> M^-1 (F - C Q_d - K Q) at every instant, for the sleeve on the crank pin
!> (Whitworth) and the sleeve on the ground (oscillating cylinder); the
!> sliding length and its rates from the rigid states equal the kinematics';
!> the frozen frequencies equal the linear modes; bad set-ups are refused.
module test_sliding_link_suite
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use kinematics, only: motion_t
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use periodic_system, only: nonlinear_info_t
  use mechanism_model, only: mechanism_model_t
  use element_effects, only: element_effects_t
  use linalg, only: solve_linear
  use assertions
  use mechanism_fixtures, only: whitworth_input, ground_sleeve_input
  implicit none
  private
  public :: run_all

  real(dp), parameter :: beta = 2.0e-5_dp     !< s, stiffness-proportional damping in both models

contains

  subroutine run_all()
    call run_test('whitworth_accelerations_equal_steady_model', test_whitworth)
    call run_test('ground_sleeve_accelerations_equal_steady_model', test_ground_sleeve)
    call run_test('tabulated_motion_gives_the_same_accelerations', test_tabulated)
    call run_test('material_nonlinearity_agrees_with_steady_model', test_material)
    call run_test('sliding_length_rates_equal_kinematics', test_length_rates)
    call run_test('linear_modes_equal_steady_frozen_frequencies', test_modes)
    call run_test('sliding_link_refused_without_coupling_or_with_consistent_element', test_refusals)
  end subroutine run_all

  !> Whitworth: crank AB = 3 clamped at A, the lever from the ground pin
  !> D = (0, -6) slides through a sleeve (mass 0.002) on the crank pin B.
  function whitworth(omega) result(inp)
    real(dp), intent(in) :: omega
    type(mechanism_input_t) :: inp
    inp = whitworth_input(3.0_dp, 6.0_dp)
    inp%joint_mass(2) = 0.002_dp
    inp%omega = omega
  end function whitworth

  !> Oscillating cylinder: crank AB = 3, two elements; the rod pinned at B
  !> slides through a sleeve pivoting on the ground at C = (8, 0).
  function ground_sleeve(omega) result(inp)
    real(dp), intent(in) :: omega
    type(mechanism_input_t) :: inp
    inp = ground_sleeve_input(3.0_dp, 14.0_dp, 8.0_dp)
    inp%joint_mass(2) = 0.001_dp
    inp%link_n_elements(1:2) = [2, 1]
    inp%omega = omega
  end function ground_sleeve

  !> Both models of one mechanism with the same physics.
  subroutine build_both(inp, tm, sm, tabulate, material, damping)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_model_t), intent(out) :: tm
    type(steady_model_t), intent(out) :: sm
    logical, intent(in) :: tabulate
    logical, intent(in), optional :: material   !< Ramberg-Osgood on: &effects material = T, &tennant D_k = 1
    real(dp), intent(in), optional :: damping   !< instead of beta
    type(mechanism_t) :: mech
    type(link_sections_t) :: secs(inp%n_links)
    type(error_t) :: err
    integer :: i
    logical :: ro
    real(dp) :: b
    ro = .false.
    if (present(material)) ro = material
    b = beta
    if (present(damping)) b = damping
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'mechanism: '//err%text())
    call tm%init_mechanism(mech, element_effects_t(material=ro, rotary_inertia=.true., coupling=.true.), 'exact', &
                           b, err, table_points=merge(720, 0, tabulate))
    call assert_true(.not. err%failed(), 'transient model: '//err%text())
    call sm%init_mechanism(mech, tennant_options_t(d_k=merge(1.0_dp, 0.0_dp, ro), rotary_inertia=.true., &
                                                   damping_beta=b), secs, err)
    call assert_true(.not. err%failed(), 'steady model: '//err%text())
    call assert_equal(tm%n, sm%n, 'the same global unknowns')
    do i = 1, min(tm%n, sm%n)
      call assert_true(tm%table%label_of(i) == sm%table%label_of(i), &
                       'unknown '//trim(tm%table%label_of(i))//' numbered alike')
    end do
  end subroutine build_both

  !> Displacements of about 1e-3 in (strains ~ 1e-4) and rates ~ omega of
  !> them, deterministic, every unknown different.
  subroutine state(n, omega, q, qd, size)
    integer, intent(in) :: n
    real(dp), intent(in) :: omega
    real(dp), intent(out) :: q(n), qd(n)
    real(dp), intent(in), optional :: size      !< instead of 1e-3 in
    integer :: i
    real(dp) :: a
    a = 1.0e-3_dp
    if (present(size)) a = size
    do i = 1, n
      q(i) = a*sin(1.7_dp*i + 0.3_dp)
      qd(i) = omega*a*cos(2.3_dp*i - 0.5_dp)
    end do
  end subroutine state

  !> Transient q_dd and the steady model's M^-1 (F - C Q_d - K Q) at times
  !> over a revolution: the same to rtol (of the largest entry).
  subroutine compare_accelerations(tm, sm, omega, rtol, label, size)
    type(mechanism_model_t), intent(inout) :: tm
    type(steady_model_t), intent(inout) :: sm
    real(dp), intent(in) :: omega, rtol
    character(len=*), intent(in) :: label
    real(dp), intent(in), optional :: size
    real(dp), allocatable :: q(:), qd(:), a1(:), a2(:), m(:, :), c(:, :), k(:, :), f(:), fn(:)
    type(nonlinear_info_t) :: info
    type(error_t) :: err
    real(dp) :: t
    integer :: n, it
    n = tm%n
    allocate(q(n), qd(n), a1(n), a2(n), m(n, n), c(n, n), k(n, n), f(n), fn(n))
    call state(n, omega, q, qd, size)
    do it = 0, 6
      t = (0.05_dp + it/7.0_dp)*two_pi/omega
      call tm%accelerations(t, q, qd, a1)
      call assert_true(.not. tm%err%failed(), label//': transient model: '//tm%err%text())
      call sm%set_time(t, err)
      call sm%linear_terms(m, c, k, f, .true.)
      call sm%nonlinear_terms(q, fn, info)
      a2 = f - matmul(c, qd) - matmul(k, q) - fn
      call solve_linear(m, a2, err)
      call assert_true(.not. err%failed(), label//': steady M')
      call assert_all_close(a1, a2, 0.0_dp, rtol*maxval(abs(a2)), label//' at crank step '//achar(48 + it))
    end do
  end subroutine compare_accelerations

  !> The crank's Kear element and the lever's Tennant element with its
  !> moving length and sleeve map against the steady model's Tennant
  !> elements: round-off of the assembly (1e-9 of the largest entry).
  subroutine test_whitworth()
    call check_sleeve_accelerations(whitworth(60.0_dp), 2, 'Whitworth')
  end subroutine test_whitworth

  subroutine test_ground_sleeve()
    call check_sleeve_accelerations(ground_sleeve(80.0_dp), 3, 'ground sleeve')
  end subroutine test_ground_sleeve

  !> Both models of `inp` (crank speed inp%omega), element `sleeve_element`
  !> ending in the sleeve, accelerations equal to 1e-9.
  subroutine check_sleeve_accelerations(inp, sleeve_element, label)
    type(mechanism_input_t), intent(in) :: inp
    integer, intent(in) :: sleeve_element
    character(len=*), intent(in) :: label
    type(mechanism_model_t) :: tm
    type(steady_model_t) :: sm
    call build_both(inp, tm, sm, .false.)
    call assert_true(tm%table%is_sleeve_element(sleeve_element), label//': the link ends in the sleeve')
    call compare_accelerations(tm, sm, inp%omega, 1.0e-9_dp, label)
  end subroutine check_sleeve_accelerations

  !> The decks tabulate the rigid motion (720 crank angles, quintic Hermite,
  !> 1e-12 relative); Delta and its rates then come from the interpolated
  !> states of the lever and the crank: 1e-8.
  subroutine test_tabulated()
    type(mechanism_model_t) :: tm
    type(steady_model_t) :: sm
    call build_both(whitworth(60.0_dp), tm, sm, .true.)
    call compare_accelerations(tm, sm, 60.0_dp, 1.0e-8_dp, 'Whitworth, tabulated')
    call build_both(ground_sleeve(80.0_dp), tm, sm, .true.)
    call compare_accelerations(tm, sm, 80.0_dp, 1.0e-8_dp, 'ground sleeve, tabulated')
  end subroutine test_tabulated

  !> The Ramberg-Osgood material on every element (Kear's crank with
  !> material = T, the sliding lever's and the steady model's Tennant
  !> elements with D_k = 1: the same section law, exact Gauss rules) at
  !> displacements of 2e-3 in (strains to 4e-3, below the peak 6.6e-3):
  !> the same accelerations to 1e-9; they differ from the linear ones by more.
  !> Without damping: Kear's elements damp with the tangent stiffness, the
  !> steady model with K_lin (doc/steady_state.md §2.6), 3e-5 apart here.
  subroutine test_material()
    type(mechanism_model_t) :: tm, tl
    type(steady_model_t) :: sm, sl
    real(dp) :: q(7), qd(7), a_nl(7), a_lin(7)
    call build_both(whitworth(60.0_dp), tm, sm, .false., material=.true., damping=0.0_dp)
    call compare_accelerations(tm, sm, 60.0_dp, 1.0e-9_dp, 'Whitworth, material', size=2.0e-3_dp)
    call build_both(whitworth(60.0_dp), tl, sl, .false., damping=0.0_dp)
    call assert_equal(tm%n, 7, 'seven unknowns')
    call state(7, 60.0_dp, q, qd, 2.0e-3_dp)
    call tm%accelerations(0.01_dp, q, qd, a_nl)
    call tl%accelerations(0.01_dp, q, qd, a_lin)
    call assert_true(maxval(abs(a_nl - a_lin)) > 1.0e-6_dp*maxval(abs(a_lin)), &
                     'the material law changes the accelerations (the comparison sees it)')
    call build_both(ground_sleeve(80.0_dp), tm, sm, .false., material=.true., damping=0.0_dp)
    call compare_accelerations(tm, sm, 80.0_dp, 1.0e-9_dp, 'ground sleeve, material', size=2.0e-3_dp)
  end subroutine test_material

  !> Delta = (P - R1).u and its rates (module sliding_link) against the
  !> kinematics' active length of the sliding link (its own Newton solution
  !> with the length as a coordinate): 1e-9 relative, accelerating crank.
  subroutine test_length_rates()
    type(mechanism_model_t) :: tm
    type(steady_model_t) :: sm
    type(mechanism_input_t) :: inp
    type(motion_t) :: m
    type(error_t) :: err
    integer :: it
    real(dp) :: t
    inp = whitworth(60.0_dp)
    inp%profile = 'spinup'
    inp%spinup_time = 0.2_dp
    call build_both(inp, tm, sm, .false.)
    do it = 1, 5
      t = 0.03_dp*it
      call tm%set_time(t)
      call tm%kin%solve(t, err)
      m = tm%kin%element_motion_global(2)
      call assert_rel_close(tm%slide(1)%fs%length, m%length, 1.0e-9_dp, 'Delta')
      call assert_close(tm%slide(1)%fs%length_d, m%length_d, 1.0e-9_dp*max(1.0_dp, abs(m%length_d)), 'Delta_d')
      call assert_close(tm%slide(1)%fs%length_dd, m%length_dd, 1.0e-9_dp*max(1.0_dp, abs(m%length_dd)), 'Delta_dd')
    end do
    call assert_true(abs(m%length_dd) > 1.0_dp, 'the crank accelerates: Delta_dd is exercised')
  end subroutine test_length_rates

  !> At a crawling crank the steady model's frozen frequencies are the
  !> structural ones; the transient model's linear modes (its Newton
  !> matrix's M and K_t, the sleeve block included) equal them: 1e-8.
  subroutine test_modes()
    type(mechanism_model_t) :: tm
    type(steady_model_t) :: sm
    type(error_t) :: err
    real(dp), allocatable :: w1(:), w2(:), shapes(:, :)
    call build_both(whitworth(1.0e-3_dp), tm, sm, .false.)
    allocate(w1(sm%n), w2(tm%n), shapes(tm%n, tm%n))
    call sm%frozen_frequencies(w1, err)
    call assert_true(.not. err%failed(), 'steady frequencies')
    call tm%linear_modes(w2, shapes, err)
    call assert_true(.not. err%failed(), 'transient modes')
    call assert_all_close(w2, w1, 1.0e-8_dp, 0.0_dp, 'natural frequencies of the Whitworth linkage')
  end subroutine test_modes

  !> A sliding link needs the coupling terms (its element always has them)
  !> and Kear's 8-DOF table (not the consistent element's).
  subroutine test_refusals()
    type(mechanism_model_t) :: tm, tm2
    type(mechanism_t) :: mech
    type(error_t) :: err
    call build_mechanism(whitworth(60.0_dp), mech, err)
    call tm%init_mechanism(mech, element_effects_t(rotary_inertia=.true.), 'exact', 0.0_dp, err)
    call assert_true(err%failed(), 'coupling = F refused')
    call assert_true(index(err%text(), 'coupling = T') > 0, 'the message names the switch: '//err%text())
    call err%clear()
    call tm2%init_mechanism(mech, element_effects_t(coupling=.true.), 'consistent', 0.0_dp, err)
    call assert_true(err%failed(), 'the consistent element refused')
    call assert_true(index(err%text(), 'exact') > 0, 'the message names the formulations: '//err%text())
  end subroutine test_refusals
end module test_sliding_link_suite

program test_sliding_link
  use test_sliding_link_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_sliding_link')
end program test_sliding_link
