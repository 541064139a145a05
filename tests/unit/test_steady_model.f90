!> Tests of the assembled steady-state model (module steady_model): the
!> global equations M Q_dd + C Q_d + K Q - F are Lagrange's equations of the
!> summed element energies (finite differences along the motion) for a
!> four-bar, a slider-crank with a block mass, and both inverted
!> slider-cranks (a sleeve on the crank pin and a sleeve on the ground:
!> angle-dependent maps, a varying element length); frozen natural
!> frequencies equal the transient model's; periodic time and cache.
module test_steady_model_suite
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use tennant_element, only: tennant_options_t, tennant_kinetic_energy, tennant_strain_energy
  use steady_model, only: steady_model_t, link_sections_t
  use mechanism_model, only: mechanism_model_t
  use element_effects, only: element_effects_t
  use assertions
  use transient_fixtures, only: fourbar_input
  use mechanism_fixtures, only: slider_crank_input, whitworth_input, ground_sleeve_input
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('four_bar_equations_are_fd_lagrange_equations', test_lagrange_four_bar)
    call run_test('slider_crank_with_block_mass_is_fd_lagrange', test_lagrange_slider_crank)
    call run_test('sleeve_on_crank_pin_is_fd_lagrange', test_lagrange_sleeve_carried)
    call run_test('ground_sleeve_is_fd_lagrange', test_lagrange_sleeve_ground)
    call run_test('frozen_frequencies_equal_transient_model_modes', test_frequencies)
    call run_test('one_period_later_the_state_is_the_same', test_periodic_time)
  end subroutine run_all

  subroutine build(inp, opt, model)
    type(mechanism_input_t), intent(in) :: inp
    type(tennant_options_t), intent(in) :: opt
    type(steady_model_t), intent(out) :: model
    type(mechanism_t) :: mech
    type(link_sections_t) :: secs(inp%n_links)
    type(error_t) :: err
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'mechanism: '//err%text())
    call model%init_mechanism(mech, opt, secs, err)
    call assert_true(.not. err%failed(), 'model: '//err%text())
  end subroutine build

  function four_bar_input(w) result(inp)
    real(dp), intent(in) :: w
    type(mechanism_input_t) :: inp
    inp = fourbar_input(1, w, 0.0_dp)
    inp%joint_mass(2) = 0.002_dp
    inp%link_n_elements(2) = 2
  end function four_bar_input

  !> Sum of the element energies at the model's current time; element rates
  !> q_e_d = C Q_d + C_d Q (C_d nonzero only at a sleeve).
  real(dp) function kinetic(model, q, qd) result(ke)
    type(steady_model_t), intent(in) :: model
    real(dp), intent(in) :: q(:), qd(:)
    integer :: e, ng, nd
    ke = 0.0_dp
    do e = 1, size(model%el)
      nd = model%el(e)%nd
      if (model%table%is_sleeve_element(e)) then
        ng = model%ng(e)
        ke = ke + tennant_kinetic_energy(model%el(e), model%element_q(e, q), &
          matmul(model%cm(1:nd, 1:ng, e), qd(model%table%globals_of(e))) + &
          matmul(model%cmd(1:nd, 1:ng, e), q(model%table%globals_of(e))), model%fs(e))
      else
        ke = ke + tennant_kinetic_energy(model%el(e), model%element_q(e, q), model%element_q(e, qd), model%fs(e))
      end if
    end do
  end function kinetic

  real(dp) function strain(model, q) result(se)
    type(steady_model_t), intent(in) :: model
    real(dp), intent(in) :: q(:)
    integer :: e
    se = 0.0_dp
    do e = 1, size(model%el)
      se = se + tennant_strain_energy(model%el(e), model%element_q(e, q), model%fs(e))
    end do
  end function strain

  !> Along Q(t) = Q0 + Q1 t + Q2 t^2: d/dt dKE/dQ_d - dKE/dQ + dSE/dQ equals
  !> M Q_dd + C Q_d + K Q - F (C and its damping-free terms kept).  Energies
  !> are quadratic in (Q, Q_d): central differences in them are exact; the
  !> time derivative uses a 5-point stencil, h = 2e-6 s (crank 100 rad/s):
  !> tolerance 1e-6 of the largest term.
  subroutine check_lagrange(model, t0, label)
    type(steady_model_t), intent(inout) :: model
    real(dp), intent(in) :: t0
    character(len=*), intent(in) :: label
    real(dp), parameter :: h = 2.0e-6_dp
    real(dp) :: q0(model%n), q1(model%n), q2(model%n), q(model%n), qd(model%n), qdd(model%n)
    real(dp) :: g(model%n, -2:2), gq(model%n), gs(model%n), lag(model%n), mdl(model%n), scale
    real(dp) :: m(model%n, model%n), c(model%n, model%n), k(model%n, model%n), f(model%n)
    type(error_t) :: err
    integer :: j, i
    do i = 1, model%n
      q0(i) = 1.0e-3_dp*sin(1.7_dp*i)
      q1(i) = 0.1_dp*cos(2.3_dp*i)
      q2(i) = 10.0_dp*sin(0.9_dp*i + 0.4_dp)
    end do
    do j = -2, 2
      call model%set_time(t0 + j*h, err)
      call assert_true(.not. err%failed(), 'kinematics')
      q = q0 + q1*(t0 + j*h) + q2*(t0 + j*h)**2
      qd = q1 + 2.0_dp*q2*(t0 + j*h)
      do i = 1, model%n
        g(i, j) = (kinetic(model, q, qd + unit(i)) - kinetic(model, q, qd - unit(i)))/2.0_dp
      end do
    end do
    call model%set_time(t0, err)
    q = q0 + q1*t0 + q2*t0**2
    qd = q1 + 2.0_dp*q2*t0
    qdd = 2.0_dp*q2
    do i = 1, model%n
      gq(i) = (kinetic(model, q + 1.0e-3_dp*unit(i), qd) - kinetic(model, q - 1.0e-3_dp*unit(i), qd))/2.0e-3_dp
      gs(i) = (strain(model, q + 1.0e-3_dp*unit(i)) - strain(model, q - 1.0e-3_dp*unit(i)))/2.0e-3_dp
    end do
    lag = (g(:, -2) - 8.0_dp*g(:, -1) + 8.0_dp*g(:, 1) - g(:, 2))/(12.0_dp*h) - gq + gs
    call model%linear_terms(m, c, k, f, .true.)
    mdl = matmul(m, qdd) + matmul(c, qd) + matmul(k, q) - f
    scale = max(maxval(abs(f)), maxval(abs(matmul(k, q))), maxval(abs(matmul(m, qdd))), maxval(abs(matmul(c, qd))))
    call assert_all_close(mdl, lag, 0.0_dp, 1.0e-6_dp*scale, label)
  contains
    function unit(ii) result(u)
      integer, intent(in) :: ii
      real(dp) :: u(model%n)
      u = 0.0_dp
      u(ii) = 1.0_dp
    end function unit
  end subroutine check_lagrange

  subroutine test_lagrange_four_bar()
    type(steady_model_t) :: model
    call build(four_bar_input(100.0_dp), tennant_options_t(), model)
    call check_lagrange(model, 0.004_dp, 'four-bar, slender')
    call build(four_bar_input(100.0_dp), tennant_options_t(shear=.true.), model)
    call check_lagrange(model, 0.004_dp, 'four-bar, shear angle')
  end subroutine test_lagrange_four_bar

  subroutine test_lagrange_slider_crank()
    type(mechanism_input_t) :: inp
    type(steady_model_t) :: model
    inp = slider_crank_input(2.0_dp, 7.0_dp, 0.5_dp)
    inp%joint_guide_deg(3) = 10.0_dp
    inp%joint_mass(3) = 0.003_dp
    inp%link_n_elements(1:2) = [1, 2]
    inp%omega = 100.0_dp
    call build(inp, tennant_options_t(), model)
    call check_lagrange(model, 0.007_dp, 'slider-crank with block mass')
  end subroutine test_lagrange_slider_crank

  !> Whitworth-type inverted slider-crank: crank AB = 3, the lever from the
  !> ground pin D = (0, -6) slides through a sleeve on the crank pin B.
  subroutine test_lagrange_sleeve_carried()
    type(mechanism_input_t) :: inp
    type(steady_model_t) :: model
    inp = whitworth_input(3.0_dp, 6.0_dp)
    inp%joint_mass(2) = 0.002_dp
    inp%omega = 100.0_dp
    call build(inp, tennant_options_t(), model)
    call assert_true(model%table%is_sleeve_element(2), 'the lever ends in the sleeve')
    call check_lagrange(model, 0.005_dp, 'sleeve on the crank pin')
    call build(inp, tennant_options_t(shear=.true.), model)
    call check_lagrange(model, 0.005_dp, 'sleeve on the crank pin, shear angle')
  end subroutine test_lagrange_sleeve_carried

  !> Oscillating cylinder: crank AB = 3, rod pinned at B sliding through a
  !> sleeve pivoting on the ground at C = (8, 0).
  subroutine test_lagrange_sleeve_ground()
    type(mechanism_input_t) :: inp
    type(steady_model_t) :: model
    inp = ground_sleeve_input(3.0_dp, 14.0_dp, 8.0_dp)
    inp%omega = 100.0_dp
    call build(inp, tennant_options_t(), model)
    call check_lagrange(model, 0.011_dp, 'ground sleeve')
  end subroutine test_lagrange_sleeve_ground

  !> At a crawling crank (1e-3 rad/s) the frozen frequencies are the
  !> structural ones: equal to the transient model's linear modes (Kear's
  !> element, rotary inertia on), 1e-8 relative.
  subroutine test_frequencies()
    type(steady_model_t) :: model
    type(mechanism_model_t) :: tm
    type(mechanism_t) :: mech
    type(error_t) :: err
    real(dp) :: w1(10), w2(10), shapes(10, 10)
    type(mechanism_input_t) :: inp
    inp = four_bar_input(1.0e-3_dp)
    inp%joint_mass(2) = 0.0_dp
    inp%link_n_elements(1:3) = 1
    call build(inp, tennant_options_t(), model)
    call model%frozen_frequencies(w1, err)
    call build_mechanism(inp, mech, err)
    call tm%init_mechanism(mech, element_effects_t(rotary_inertia=.true.), 'exact', 0.0_dp, err)
    call tm%linear_modes(w2, shapes, err)
    call assert_all_close(w1, w2, 1.0e-8_dp, 0.0_dp, 'natural frequencies')
    call assert_close(w1(1), 1460.7_dp, 0.1_dp, 'the four-bar''s 1460.7 rad/s at crank angle 0 (1462.4 without rotary inertia)')
  end subroutine test_frequencies

  !> The crank turns at constant speed: the matrices one period later (and
  !> after visiting other times) are the same, to round-off.
  subroutine test_periodic_time()
    type(steady_model_t) :: model
    type(error_t) :: err
    real(dp), allocatable, dimension(:, :) :: m1, c1, k1, m2, c2, k2
    real(dp), allocatable :: f1(:), f2(:)
    real(dp) :: t_period
    integer :: n
    call build(four_bar_input(150.0_dp), tennant_options_t(), model)
    n = model%n
    allocate(m1(n, n), c1(n, n), k1(n, n), m2(n, n), c2(n, n), k2(n, n), f1(n), f2(n))
    t_period = two_pi/150.0_dp
    call model%set_time(0.3_dp*t_period, err)
    call model%linear_terms(m1, c1, k1, f1, .true.)
    call model%set_time(0.8_dp*t_period, err)
    call model%set_time(1.3_dp*t_period, err)
    call model%linear_terms(m2, c2, k2, f2, .true.)
    call assert_all_close(reshape(m2, [n*n]), reshape(m1, [n*n]), 1.0e-10_dp, 0.0_dp, 'M')
    call assert_all_close(reshape(k2, [n*n]), reshape(k1, [n*n]), 1.0e-10_dp, 1.0e-6_dp, 'K')
    call assert_all_close(f2, f1, 1.0e-9_dp, 1.0e-9_dp*maxval(abs(f1)), 'F')
  end subroutine test_periodic_time
end module test_steady_model_suite

program test_steady_model
  use assertions, only: finish_suite
  use test_steady_model_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_steady_model')
end program test_steady_model
