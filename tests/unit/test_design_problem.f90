!> Tests of the design problem's pieces (module design_problem): the coupler
!> point of the path objectives against the closed-form four-bar of module
!> fourbar_path (B's equations, an independent implementation); the KS
!> aggregate of the peak stress constraints (ks_peak); the peak read between
!> the samples (sample_peaks).
module test_design_problem_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use tennant_element, only: tennant_options_t
  use steady_model, only: steady_model_t, link_sections_t
  use fourbar_path, only: table3_design, coupler_point
  use design_problem, only: coupler_point_of, design_problem_t, design_eval_t, ks_peak, sample_peaks
  use design_sequence, only: design_sequence_t
  use design_fixtures, only: load_design_text
  use deck_runner, only: scratch_path
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('rigid_coupler_point_matches_closed_form_fourbar', test_rigid_point)
    call run_test('path_design_recovers_a_flexible_design_from_its_path', test_path_recovery)
    call run_test('ks_aggregate_bounds_the_peak_and_is_smooth_where_the_peak_switches', test_ks_peak)
    call run_test('parabola_reads_the_peak_between_samples_continuously', test_sample_peaks)
  end subroutine run_all

  !> sample_peaks 'parabola' on a sharp periodic peak exp(kappa (cos(theta -
  !> theta_p) - 1)), kappa = 60 (about 15 deg wide at half height, as the
  !> crank's stress peak of design example 1), peak value 1, at N = 72
  !> samples.  With theta_p midway between two samples the largest sample
  !> is 5.6 % low; read in ln (exactly a parabola for a Gaussian), the peak
  !> is within 1e-3 (measured 8e-5: the cosine's quartic term), and halving
  !> the spacing divides that error by 10 or more (d^4: 16; the largest
  !> sample's d^2: 4).  Never below the largest sample.  The peak between the
  !> last and the first sample (periodic wrap) is read as well.  Moving theta_p
  !> across two spacings in 400 steps (the largest sample switches twice),
  !> the read peak moves by at most 1e-3 a step (continuous: a jump where the
  !> largest sample switches would be the largest sample's 5 % error or its
  !> parabola's difference).  'none' returns the samples.
  subroutine test_sample_peaks()
    real(dp), parameter :: kappa = 60.0_dp
    real(dp) :: e72, e144, before, now, jump, d
    integer :: i
    d = 2*pi/72
    call assert_true(1.0_dp - maxval(bump(72, 0.5_dp*d)) > 0.05_dp, 'the largest sample misses the peak by 5 %')
    e72 = abs(1.0_dp - maxval(sample_peaks(bump(72, 0.5_dp*d), 'parabola')))
    e144 = abs(1.0_dp - maxval(sample_peaks(bump(144, 0.25_dp*d), 'parabola')))
    call assert_true(e72 < 1.0e-3_dp, 'the parabola in ln reads the peak to 1e-3: '//str(e72))
    call assert_true(e144 < 0.1_dp*e72, 'its error falls faster than d^3: '//str(e72)//' at 72, '//str(e144)//' at 144')
    call assert_true(all(sample_peaks(bump(72, 0.3_dp*d), 'parabola') >= bump(72, 0.3_dp*d)), &
                     'never below the sample')
    call assert_close(maxval(sample_peaks(bump(72, -0.4_dp*d), 'parabola')), 1.0_dp, 1.0e-3_dp, &
                      'the peak between the last and the first sample')
    call assert_all_close(sample_peaks(bump(72, 0.3_dp*d), 'none'), bump(72, 0.3_dp*d), 0.0_dp, 0.0_dp, &
                          '''none'' keeps the samples')
    jump = 0.0_dp
    before = maxval(sample_peaks(bump(72, -d), 'parabola'))
    do i = 1, 400
      now = maxval(sample_peaks(bump(72, -d + 2*d*i/400), 'parabola'))
      jump = max(jump, abs(now - before))
      before = now
    end do
    call assert_true(jump < 1.0e-3_dp, 'continuous where the largest sample switches: largest step '//str(jump))
  contains
    function bump(n, theta_p) result(v)
      integer, intent(in) :: n
      real(dp), intent(in) :: theta_p
      real(dp) :: v(n)
      integer :: k
      do k = 1, n
        v(k) = exp(kappa*(cos(2*pi*(k - 1)/n - theta_p) - 1.0_dp))
      end do
    end function bump
  end subroutine test_sample_peaks

  !> The KS aggregate of ln(stress) (design_problem's ks_peak): never below
  !> the largest value, never more than ln(N)/rho above it, exactly that far
  !> above for N equal values (the bound is sharp), and within (N - 1)
  !> exp(-10) / rho of the largest when the others are 10/rho below it.  Where
  !> the largest of two samples switches (v = (a + t, a - t) at t = 0) the
  !> max has one-sided slopes +1 and -1; the KS function's two one-sided
  !> differences agree to O(h) (slope 0 at the switch): a gradient method sees
  !> a smooth constraint.
  subroutine test_ks_peak()
    real(dp), parameter :: rho = 200.0_dp, h = 1.0e-6_dp
    real(dp) :: v(72), ks, right, left
    integer :: k
    do k = 1, size(v)
      v(k) = 0.3_dp*sin(2.0_dp*pi*k/size(v)) + 0.05_dp*cos(6.0_dp*pi*k/size(v))
    end do
    ks = ks_peak(v, rho)
    call assert_true(ks >= maxval(v), 'KS is not below the largest sample')
    call assert_true(ks <= maxval(v) + log(real(size(v), dp))/rho, 'KS is at most ln(N)/rho above it')
    v = 0.7_dp
    call assert_close(ks_peak(v, rho), 0.7_dp + log(real(size(v), dp))/rho, 1.0e-12_dp, 'equal samples: the bound')
    v = 0.7_dp - 10.0_dp/rho
    v(5) = 0.7_dp
    call assert_true(ks_peak(v, rho) - 0.7_dp <= (size(v) - 1)*exp(-10.0_dp)/rho*(1.0_dp + 1.0e-9_dp), &
                     'a lone peak is overestimated by (N - 1) exp(-10) / rho at most')
    right = (ks_peak([0.5_dp + h, 0.5_dp - h], rho) - ks_peak([0.5_dp, 0.5_dp], rho))/h
    left = (ks_peak([0.5_dp, 0.5_dp], rho) - ks_peak([0.5_dp - h, 0.5_dp + h], rho))/h
    call assert_true(abs(right - left) < 10.0_dp*rho*h, 'one-sided slopes at the switch agree to O(h): '// &
                     'right and left differences')
    call assert_true(abs(right) < 10.0_dp*rho*h, 'slope 0 at the switch of two equal peaks')
  end subroutine test_ks_peak

  !> B's Table 3 four-bar as a flexmech mechanism (crank pivot A = (x10, x9),
  !> rocker pivot D = A + x1 e(x6), crank angle x8 at t = 0): the rigid-body
  !> coupler point at 16 crank angles equals B's closed form to 1e-9 in
  !> (the kinematics' Newton solution converges to round-off of the 30 in
  !> linkage; 1e-9 leaves three orders for it).  With zero deformation the
  !> elastic point is the rigid one.
  subroutine test_rigid_point()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(steady_model_t) :: model
    type(error_t) :: err
    type(tennant_options_t) :: opt
    type(link_sections_t) :: sections(3)
    real(dp) :: x(10), rigid(2), flexible(2), xx, yy, arg, gamma
    real(dp), allocatable :: q(:)
    integer :: i
    x = table3_design
    inp%n_joints = 4
    inp%joint_name(1:4) = [character(len=16) :: 'A', 'B', 'C', 'D']
    inp%joint_type(1:4) = [character(len=16) :: 'clamp', 'pin', 'pin', 'ground_pin']
    inp%joint_x(1) = x(10)
    inp%joint_y(1) = x(9)
    inp%joint_x(4) = x(10) + x(1)*cos(x(6))
    inp%joint_y(4) = x(9) + x(1)*sin(x(6))
    inp%n_links = 3
    inp%link_joint1(1:3) = [1, 2, 4]
    inp%link_joint2(1:3) = [2, 3, 3]
    inp%link_length(1:3) = x(2:4)
    inp%omega = 10.0_dp
    inp%theta0_deg = x(8)*180.0_dp/pi
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'Table 3 four-bar builds: '//err%text())
    call model%init_mechanism(mech, opt, sections, err)
    call assert_true(.not. err%failed(), 'model: '//err%text())
    if (err%failed()) return
    allocate(q(model%n))
    q = 0.0_dp
    do i = 0, 15
      gamma = x(8) + real(i, dp)*pi/8.0_dp
      call model%set_time(real(i, dp)*(pi/8.0_dp)/inp%omega, err)
      call coupler_point_of(model, mech%links(2)%first_element, q, x(5), x(7), rigid, flexible)
      call coupler_point(x, gamma, xx, yy, arg)
      call assert_close(rigid(1), xx, 1.0e-9_dp, 'rigid coupler point X at crank step '//char(48 + mod(i, 10)))
      call assert_close(rigid(2), yy, 1.0e-9_dp, 'rigid coupler point Y')
      call assert_true(maxval(abs(flexible - rigid)) <= 1.0e-14_dp*x(1), 'no deformation: the elastic point is the rigid one')
    end do
  end subroutine test_rigid_point

  !> The path objective with the elastic deformation, a case with a known
  !> answer: the targets are the ELASTIC coupler points of B's Table 3
  !> four-bar at 60 rad/s (harmonic evaluator, three variables: coupler
  !> length, coupler-point angle, crank angle at the first target).  From a
  !> start 1.5 % / 1 deg / 1 deg off, the design loop must return to that
  !> design: F falls below 1e-8 of its start (the start's F is about 1 in^2,
  !> a miss of 1e-4 in) and the variables within 1e-4 relative.  The rigid
  !> path error of the answer is not zero (the targets are not a rigid path).
  subroutine test_path_recovery()
    character(len=*), parameter :: deck_text = '&run analysis = ''design'' /|&mechanism n_joints = 4, '// &
      'joint_type = ''clamp'', ''pin'', ''pin'', ''ground_pin'', joint_x(1) = 7.0, joint_y(1) = 4.0, '// &
      'joint_x(4) = 21.5875845825, joint_y(4) = -22.2145451238, n_links = 3, link_joint1 = 1, 2, 4, '// &
      'link_joint2 = 2, 3, 3, link_length = 8.345, 25.821, 12.817, link_b = 3*0.25, link_h = 3*1.0, '// &
      'driver_link = 1, omega = 60.0, theta0_deg = 64.05668149562604 /|&steady damping_beta = 1.0e-5 /|'// &
      '&tennant d_k = 0, d_b = 0, d_g = 0 /|&design variables = ''link_length(2)'', ''path_angle_deg'', '// &
      '''theta0_deg'', lower = 22.0, 62.0, 54.0, upper = 29.0, 82.0, 74.0, objective = ''path'', '// &
      'evaluator = ''harmonic'', samples = 12, path_link = 2, path_r = 16.026, path_angle_deg = 72.13538640697064, '// &
      'path_x = 8*0.0, path_y = 8*0.0, path_dgamma_deg = 0, 45, 90, 135, 180, 225, 270, 315 /'
    type(design_problem_t), target :: prob
    type(design_sequence_t) :: seq
    type(design_eval_t) :: ev
    type(error_t) :: err
    real(dp), allocatable :: x_star(:), x0(:)
    call load_design_text(scratch_path('test_design_problem'), deck_text, prob, x_star, err)
    call assert_true(.not. err%failed(), 'deck loads: '//err%text())
    if (err%failed()) return
    ! the elastic coupler points of the design x_star become the targets
    call prob%setup('recovery', x_star)
    call prob%evaluate(x_star, ev)
    call assert_true(ev%ok, 'the design analyses: '//ev%reason)
    prob%path_x = prob%path_x + ev%residual(1::2)
    prob%path_y = prob%path_y + ev%residual(2::2)
    x0 = x_star + [log(1.015_dp), 1.0_dp/72.13538640697064_dp, 1.0_dp/64.05668149562604_dp]
    call prob%setup('recovery', x0)
    seq%xtol = 1.0e-7_dp
    call seq%solve(prob, x0, err)
    call assert_true(.not. err%failed() .and. seq%converged, 'converges: '//err%text())
    call prob%evaluate(seq%x, ev)
    call assert_true(ev%path_error <= 1.0e-8_dp*prob%f0, 'elastic path error back to zero')
    call assert_close(prob%var(1)%value(seq%x(1)), 25.821_dp, 1.0e-4_dp*25.821_dp, 'coupler length')
    call assert_close(prob%var(2)%value(seq%x(2)), 72.13538640697064_dp, 1.0e-4_dp*72.1_dp, 'coupler-point angle')
    call assert_close(prob%var(3)%value(seq%x(3)), 64.05668149562604_dp, 1.0e-4_dp*64.1_dp, 'crank angle')
    call assert_true(ev%rigid_path_error > 1.0e-6_dp, 'the rigid path of the answer misses the elastic targets')
  end subroutine test_path_recovery
end module test_design_problem_suite

program test_design_problem
  use test_design_problem_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_design_problem')
end program test_design_problem
