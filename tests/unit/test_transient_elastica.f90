!> Static large deflection of a cantilever against the exact elastica
!> (issue 10, verification 1): tip force P L^2/EI = 1, 2, 5, 10 normal to the
!> undeformed beam, and a tip moment M = 2 pi EI/L that rolls the beam into a
!> full circle.  The model is the transient model's (mechanism_model with
!> init_fixed, point loads through the correlation table), solved by its
!> static Newton solve with load stepping.
!>
!> Reference, computed here independently of the element: the elastica
!> EI theta'' = Fx sin(theta) - Fy cos(theta), theta(0) = 0, EI theta'(L) = M,
!> x' = cos(theta), y' = sin(theta), shot on theta'(0) with a classical
!> Runge-Kutta rule of 4000 steps (error ~1e-13) and secant iteration.  For
!> P L^2/EI = 1 it gives the tip deflections 0.30172 L (transverse) and
!> 0.05643 L (axial), the values of Mattiasson's elliptic-integral tables
!> (Int. J. Numer. Meth. Eng. 17, 1981), checked below to 1e-4.
module test_transient_elastica_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t
  use element_effects, only: element_effects_t
  use planar_element, only: rigid_state_t
  use correlation_table, only: link_end_t, joint_clamp, joint_free
  use mechanism_model, only: mechanism_model_t, element_spec_t
  use external_loads, only: point_load_t, load_factor_at
  use beam_element, only: beam_local_displacement
  use assertions
  implicit none
  private
  public :: run_all

  ! slender unit cantilever: L = 1, EI = 1, EA = 1.2e5 (depth 0.01 L): the
  ! axial strain P/EA <= 1e-4 changes the tip position by < 1e-4 L
  real(dp), parameter :: length = 1.0_dp, width = 0.1_dp, depth = 0.01_dp, modulus = 1.2e8_dp
  real(dp), parameter :: ei = modulus*width*depth**3/12.0_dp

contains

  subroutine run_all()
    call run_test('elastica_shooting_reproduces_mattiasson_table', test_reference)
    call run_test('consistent_element_tip_force_within_half_percent_of_elastica', test_tip_force)
    call run_test('consistent_element_rolls_into_a_circle_under_2pi_ei_over_l', test_circle)
    call run_test('kear_element_locks_under_large_tip_force', test_kear_locks)
    call run_test('gravity_sag_is_q_l4_over_8_ei', test_gravity)
    call run_test('load_table_is_piecewise_linear_and_held', test_load_table)
  end subroutine run_all

  !> Tip (X, Y) of the exact elastica under tip force f and tip moment m.
  function elastica_tip(f, m) result(tip)
    real(dp), intent(in) :: f(2), m
    real(dp) :: tip(2), k0, k1, g0, g1, k2, s(4), lam, kprev
    integer :: it, step
    integer, parameter :: n_steps = 20
    ! continuation in the load from the straight beam: each step's secant
    ! iteration starts from the previous root (one branch, no jumping)
    kprev = 0.0_dp
    do step = 1, n_steps
      lam = real(step, dp)/n_steps
      k0 = kprev
      k1 = kprev + (m + f(2)*length)/ei/n_steps
      g0 = shoot(k0, s)
      g1 = shoot(k1, s)
      do it = 1, 100
        if (abs(g1) < 1.0e-13_dp .or. abs(g1 - g0) <= tiny(1.0_dp)) exit
        k2 = k1 - g1*(k1 - k0)/(g1 - g0)
        k0 = k1
        g0 = g1
        k1 = k2
        g1 = shoot(k1, s)
      end do
      kprev = k1
    end do
    tip = s(3:4)
  contains
    !> Integrate from s = 0 with theta'(0) = k; return EI theta'(L) - m.
    real(dp) function shoot(k, y)
      real(dp), intent(in) :: k
      real(dp), intent(out) :: y(4)
      real(dp) :: h, k1_(4), k2_(4), k3_(4), k4_(4)
      integer :: i
      integer, parameter :: n = 4000
      h = length/n
      y = [0.0_dp, k, 0.0_dp, 0.0_dp]               ! theta, theta', x, y
      do i = 1, n
        k1_ = rhs(y)
        k2_ = rhs(y + 0.5_dp*h*k1_)
        k3_ = rhs(y + 0.5_dp*h*k2_)
        k4_ = rhs(y + h*k3_)
        y = y + h*(k1_ + 2*k2_ + 2*k3_ + k4_)/6
      end do
      shoot = ei*y(2) - lam*m
    end function shoot
    function rhs(y) result(d)
      real(dp), intent(in) :: y(4)
      real(dp) :: d(4)
      d = [y(2), lam*(f(1)*sin(y(1)) - f(2)*cos(y(1)))/ei, cos(y(1)), sin(y(1))]
    end function rhs
  end function elastica_tip

  !> Cantilever of n elements along X, clamped at X = 0, tip load (f, m);
  !> static equilibrium in n_steps load steps; tip displacement (U, W).
  function model_tip(n, formulation, f, m, n_steps, gravity, effects) result(disp)
    integer, intent(in) :: n, n_steps
    character(len=*), intent(in) :: formulation
    real(dp), intent(in) :: f(2), m
    real(dp), intent(in), optional :: gravity(2)
    type(element_effects_t), intent(in), optional :: effects
    real(dp) :: disp(2)
    type(mechanism_model_t) :: model
    type(element_spec_t) :: specs(n)
    type(rigid_state_t) :: states(n)
    type(link_end_t) :: ends(2, 1)
    type(error_t) :: err
    real(dp), allocatable :: q(:)
    type(element_effects_t) :: fx
    real(dp) :: g(2)
    integer :: e
    do e = 1, n
      specs(e) = element_spec_t(length/n, width, depth, ramberg_osgood_t(modulus, 0.0_dp, 3.0_dp, 1.0_dp))
      states(e) = rigid_state_t(x1=(e - 1)*length/n, y1=0.0_dp, phi=0.0_dp)
    end do
    ends(1, 1) = link_end_t(joint_clamp, 0, 0.0_dp)
    ends(2, 1) = link_end_t(joint_free, 0, 0.0_dp)
    fx = element_effects_t(stretching=.true., curvature=.true.)
    if (present(effects)) fx = effects
    g = 0.0_dp
    if (present(gravity)) g = gravity
    call model%init_fixed(specs, states, [n], ends, fx, formulation, 0.0_dp, err, gravity=g, &
                          point_loads=[point_load_t(element=n, x_over_l=1.0_dp, force=f, moment=m)])
    call assert_true(.not. err%failed(), 'model: '//err%text())
    allocate(q(model%n))
    q = 0.0_dp
    call model%static_equilibrium(0.0_dp, q, n_steps, err)
    call assert_true(.not. err%failed(), formulation//' static solve: '//err%text())
    disp = beam_local_displacement(model%el(n), model%table%gather(n, q), 0.0_dp, 1.0_dp)
  end function model_tip

  !> P L^2/EI = 1: tip deflection 0.30172 L transverse, 0.05643 L axial
  !> (Mattiasson 1981, Table 1, to the 5 digits printed: 1e-4 absolute).
  !> Small load P L^2/EI = 1e-3: the linear P L^3/(3 EI) (1e-6 relative).
  subroutine test_reference()
    real(dp) :: tip(2)
    tip = elastica_tip([0.0_dp, -ei/length**2], 0.0_dp)
    call assert_close(-tip(2), 0.30172_dp*length, 1.0e-4_dp, 'transverse tip deflection, PL^2/EI = 1')
    call assert_close(length - tip(1), 0.05643_dp*length, 1.0e-4_dp, 'axial tip deflection, PL^2/EI = 1')
    tip = elastica_tip([0.0_dp, -1.0e-3_dp*ei/length**2], 0.0_dp)
    call assert_rel_close(-tip(2), 1.0e-3_dp*length/3.0_dp, 1.0e-6_dp, 'linear limit')
  end subroutine test_reference

  !> Consistent element, 4 and 8 elements: |tip error| <= 0.5 % of the
  !> exact tip displacement for P L^2/EI = 1, 2, 5, 10 (issue 10's
  !> requirement at <= 8 elements).
  subroutine test_tip_force()
    real(dp), parameter :: loads(4) = [1.0_dp, 2.0_dp, 5.0_dp, 10.0_dp]
    integer, parameter :: meshes(2) = [4, 8]
    real(dp) :: f(2), exact(2), disp(2), err_rel
    integer :: i, k
    character(len=80) :: label
    do i = 1, size(loads)
      f = [0.0_dp, -loads(i)*ei/length**2]
      exact = elastica_tip(f, 0.0_dp) - [length, 0.0_dp]
      do k = 1, size(meshes)
        disp = model_tip(meshes(k), 'consistent', f, 0.0_dp, nint(4*loads(i)) + 4)
        err_rel = norm2(disp - exact)/norm2(exact)
        write(label, '(a,f5.1,a,i0,a,es10.3)') 'PL^2/EI = ', loads(i), ', ', meshes(k), ' elements: error ', err_rel
        write(*, '(4x,a)') trim(label)
        call assert_true(err_rel <= 5.0e-3_dp, trim(label))
      end do
    end do
  end subroutine test_tip_force

  !> M = 2 pi EI/L: the exact beam is a full circle of radius L/(2 pi), its tip
  !> back at the root: displacement (-L, 0).  8 elements: within 0.5 % of L.
  subroutine test_circle()
    real(dp) :: disp(2), err_rel
    character(len=80) :: label
    disp = model_tip(8, 'consistent', [0.0_dp, 0.0_dp], 2.0_dp*pi*ei/length, 40)
    err_rel = norm2(disp - [-length, 0.0_dp])/length
    write(label, '(a,2f10.6,a,es10.3)') 'circle: tip displacement', disp, ', error ', err_rel
    write(*, '(4x,a)') trim(label)
    call assert_true(err_rel <= 5.0e-3_dp, trim(label))
  end subroutine test_circle

  !> Kear's element (linear u) with exact stretching, same loads: at
  !> P L^2/EI = 10 and 8 elements its tip is more than 5 % off (it
  !> cannot shorten its projection without stretching: membrane locking).
  subroutine test_kear_locks()
    real(dp) :: f(2), exact(2), disp(2), err_rel
    character(len=80) :: label
    f = [0.0_dp, -10.0_dp*ei/length**2]
    exact = elastica_tip(f, 0.0_dp) - [length, 0.0_dp]
    disp = model_tip(8, 'exact', f, 0.0_dp, 44)
    err_rel = norm2(disp - exact)/norm2(exact)
    write(label, '(a,es10.3)') 'Kear element, PL^2/EI = 10, 8 elements: error ', err_rel
    write(*, '(4x,a)') trim(label)
    call assert_true(err_rel > 0.05_dp, trim(label))
  end subroutine test_kear_locks
  !> Own weight, linear model (all effects off), density 1 (q = rho A g),
  !> g = 1e-3 along -Y: tip sag q L^4/(8 EI) = 1.25e-7 L.  The
  !> deflection is a quartic, which the quintic elements hold exactly: 1e-9
  !> relative with 2 elements, both formulations.  Gravity along +X (the
  !> beam's axis) stretches it by rho g L^2/(2E) with no sag.
  subroutine test_gravity()
    real(dp) :: disp(2), q
    integer :: k
    character(len=10), parameter :: forms(2) = [character(len=10) :: 'exact', 'consistent']
    q = 1.0_dp*width*depth*1.0e-3_dp
    do k = 1, 2
      disp = model_tip(2, trim(forms(k)), [0.0_dp, 0.0_dp], 0.0_dp, 1, gravity=[0.0_dp, -1.0e-3_dp], &
                       effects=element_effects_t())
      call assert_rel_close(-disp(2), q*length**4/(8.0_dp*ei), 1.0e-9_dp, trim(forms(k))//': sag')
      disp = model_tip(2, trim(forms(k)), [0.0_dp, 0.0_dp], 0.0_dp, 1, gravity=[1.0e-3_dp, 0.0_dp], &
                       effects=element_effects_t())
      call assert_rel_close(disp(1), 1.0_dp*1.0e-3_dp*length**2/(2.0_dp*modulus), 1.0e-9_dp, &
                            trim(forms(k))//': axial stretch')
      call assert_true(abs(disp(2)) < 1.0e-20_dp, trim(forms(k))//': no sag under axial gravity')
    end do
  end subroutine test_gravity

  !> A load table (0, 0), (2, 1), (3, -0.5): factor 0 before, 0.5 at t = 1,
  !> 0.25 at 2.5, held at -0.5 after 3; no table: 1.
  subroutine test_load_table()
    type(point_load_t) :: load
    call assert_close(load_factor_at(load, 7.0_dp), 1.0_dp, 0.0_dp, 'constant load')
    load%times = [0.0_dp, 2.0_dp, 3.0_dp]
    load%factors = [0.0_dp, 1.0_dp, -0.5_dp]
    call assert_close(load_factor_at(load, -1.0_dp), 0.0_dp, 0.0_dp, 'before the table')
    call assert_close(load_factor_at(load, 1.0_dp), 0.5_dp, 1.0e-15_dp, 't = 1')
    call assert_close(load_factor_at(load, 2.5_dp), 0.25_dp, 1.0e-15_dp, 't = 2.5')
    call assert_close(load_factor_at(load, 9.0_dp), -0.5_dp, 0.0_dp, 'held after the table')
  end subroutine test_load_table
end module test_transient_elastica_suite

program test_transient_elastica
  use test_transient_elastica_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_transient_elastica')
end program test_transient_elastica
