!> Static checks of the spatial analysis' external loads (spatial_external_loads,
!> spatial_model%static_state) against closed forms.  The RSSR of
!> inputs/spatial_rssr_100.nml (crank 6 in about Z, rocker 12 in about X
!> through (0, 20, 12), coupler 24 in, spherical B and C, circular aluminium
!> links r = 0.25 in) stands at crank angle 90 deg (B = (0, 6, 0)) and turns
!> at 1e-6 rad/s (the inertia loads ~1e-12 of the loads below), linear.
!> There B and C lie in the plane X = 0 and a load along X is normal to the
!> crank, the coupler and the rocker's plane of motion: the coupler, pinned
!> at both ends, carries it as a simply supported beam without axial force,
!> and the crank (clamped at A) and the rocker (clamped at D against bending
!> out of its plane) are cantilevers.  Asserted, for Kear's and the
!> consistent element (the closed forms are in the elements' interpolation,
!> so to round-off; 1e-8 relative):
!>  - force F along X at B:  u_B = F L1^3/(3 E I), C does not move;
!>  - moment M about Z on the crank's end B:  u_B = -M L1^2/(2 E I);
!>  - moment T about Y (the crank's axis) on its end B, which keeps local
!>    rotations: twist T L1/(G J), B does not move;
!>  - force F along X at the crank's middle node (two elements a link):
!>    u_B = 5 F L1^3/(48 E I);
!>  - gravity g along X:  u_B = q L1^4/(8 E I) + (q L2/2) L1^3/(3 E I),
!>    u_C = q L3^4/(8 E I) + (q L2/2) L3^3/(3 E I), q = rho A g.
module test_spatial_loads_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t
  use element_effects, only: element_effects_t
  use spatial_section, only: spatial_section_init, section_circular
  use spatial_beam, only: spatial_formulation_kear, spatial_formulation_consistent, spatial_to_local
  use spatial_kinematics, only: spatial_fourbar_t, spatial_fourbar_init
  use spatial_external_loads, only: spatial_point_load_t
  use spatial_model
  use assertions
  implicit none
  private
  public :: run_all

  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=0.0002536_dp)
  real(dp), parameter :: radius = 0.25_dp, l1 = 6.0_dp, l2 = 24.0_dp, l3 = 12.0_dp
  real(dp), parameter :: ei = 10.87e6_dp*pi*radius**4/4.0_dp, area = pi*radius**2
  integer, parameter :: formulations(2) = [spatial_formulation_kear, spatial_formulation_consistent]

contains

  subroutine run_all()
    call run_test('tip_force_at_b_is_a_cantilever', test_tip_force)
    call run_test('tip_moment_on_the_crank_end', test_tip_moment)
    call run_test('torque_on_the_crank_end_in_its_local_axes', test_tip_torque)
    call run_test('force_at_an_interior_node', test_interior_force)
    call run_test('gravity_normal_to_the_links', test_gravity)
  end subroutine run_all

  !> The RSSR at crank angle 90 deg, n elements a link, linear, nearly at rest.
  subroutine model_at_90(n, formulation, sm)
    integer, intent(in) :: n, formulation
    type(spatial_model_t), intent(out) :: sm
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(error_t) :: err
    integer :: k
    call spatial_fourbar_init(kin, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [l1, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 20.0_dp, 12.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], l3, l2, 1, err)
    do k = 1, 3
      links(k)%n_elements = n
      links(k)%material = alu
      links(k)%shear_modulus = 10.87e6_dp/(2.0_dp*1.33_dp)
      call spatial_section_init(links(k)%sec, section_circular, [radius], alu, err)
    end do
    call sm%init(kin, 1.0e-6_dp, pi/2.0_dp, spatial_joint_spherical, spatial_joint_spherical, links, &
                 element_effects_t(.false., .false., .false., .false., .false.), 0.0_dp, err, formulation=formulation)
    call assert_true(.not. err%failed(), 'rssr model: '//err%text())
  end subroutine model_at_90

  !> Static displacements of B and C (global) under gravity and one point load.
  subroutine static_bc(n, formulation, gravity, load, ub, uc)
    integer, intent(in) :: n, formulation
    real(dp), intent(in) :: gravity(3)
    type(spatial_point_load_t), intent(in) :: load(:)
    real(dp), intent(out) :: ub(3), uc(3)
    type(spatial_model_t) :: sm
    type(error_t) :: err
    real(dp), allocatable :: q(:)
    call model_at_90(n, formulation, sm)
    call sm%set_loads(gravity, load)
    allocate(q(sm%n))
    q = 0.0_dp
    call sm%static_state(0.0_dp, q, err)
    call assert_true(.not. err%failed(), 'static state: '//err%text())
    ub = q(sm%b_dofs)
    uc = q(sm%c_dofs)
  end subroutine static_bc

  subroutine test_tip_force()
    real(dp), parameter :: f = 10.0_dp
    real(dp) :: ub(3), uc(3), expect
    integer :: i
    expect = f*l1**3/(3.0_dp*ei)
    do i = 1, 2
      call static_bc(1, formulations(i), [0.0_dp, 0.0_dp, 0.0_dp], [spatial_point_load_t(element=1, node=2, &
                     force=[f, 0.0_dp, 0.0_dp])], ub, uc)
      call assert_rel_close(ub(1), expect, 1.0e-8_dp, 'u_B = F L^3/(3 E I)')
      call assert_true(maxval(abs(ub(2:3))) <= 1.0e-8_dp*expect, 'B moves along the force only')
      call assert_true(maxval(abs(uc)) <= 1.0e-8_dp*expect, 'C does not move')
    end do
  end subroutine test_tip_force

  subroutine test_tip_moment()
    real(dp), parameter :: m = 25.0_dp
    real(dp) :: ub(3), uc(3), expect
    integer :: i
    expect = -m*l1**2/(2.0_dp*ei)
    do i = 1, 2
      call static_bc(1, formulations(i), [0.0_dp, 0.0_dp, 0.0_dp], [spatial_point_load_t(element=1, node=2, &
                     moment=[0.0_dp, 0.0_dp, m])], ub, uc)
      call assert_rel_close(ub(1), expect, 1.0e-8_dp, 'u_B = -M L^2/(2 E I)')
      call assert_true(maxval(abs(ub(2:3))) <= 1.0e-8_dp*abs(expect), 'B moves along X only')
    end do
  end subroutine test_tip_moment

  !> The twist of the crank's end 2 (local tx) under a torque given in global components.
  subroutine test_tip_torque()
    real(dp), parameter :: m = 25.0_dp, g_alu = 10.87e6_dp/(2.0_dp*1.33_dp)
    type(spatial_model_t) :: sm
    type(error_t) :: err
    real(dp), allocatable :: q(:)
    real(dp) :: p(20), expect
    integer :: i
    expect = m*l1/(g_alu*pi*radius**4/2.0_dp)
    do i = 1, 2
      call model_at_90(1, formulations(i), sm)
      call sm%set_loads([0.0_dp, 0.0_dp, 0.0_dp], [spatial_point_load_t(element=1, node=2, &
                        moment=[0.0_dp, m, 0.0_dp])])
      if (allocated(q)) deallocate(q)
      allocate(q(sm%n))
      q = 0.0_dp
      call sm%static_state(0.0_dp, q, err)
      call assert_true(.not. err%failed(), 'static state: '//err%text())
      p = spatial_to_local(sm%rb(1)%rot, sm%table%gather(1, q), sm%el(1)%local_rotation)
      call assert_rel_close(p(14), expect, 1.0e-8_dp, 'crank twist = T L/(G J)')
      call assert_true(maxval(abs(q(sm%b_dofs))) <= 1.0e-8_dp*expect*l1, 'B does not move under the torque')
    end do
  end subroutine test_tip_torque

  !> Two elements a link: the crank's node 1 (its middle) is end 2 of element 1.
  subroutine test_interior_force()
    real(dp), parameter :: f = 10.0_dp
    real(dp) :: ub(3), uc(3), expect
    integer :: i
    expect = 5.0_dp*f*l1**3/(48.0_dp*ei)
    do i = 1, 2
      call static_bc(2, formulations(i), [0.0_dp, 0.0_dp, 0.0_dp], [spatial_point_load_t(element=1, node=2, &
                     force=[f, 0.0_dp, 0.0_dp])], ub, uc)
      call assert_rel_close(ub(1), expect, 1.0e-8_dp, 'u_B = 5 F L^3/(48 E I) for F at the middle')
    end do
  end subroutine test_interior_force

  subroutine test_gravity()
    real(dp), parameter :: g = 386.09_dp
    real(dp) :: ub(3), uc(3), q, pin
    type(spatial_point_load_t) :: none(0)
    integer :: i
    q = alu%rho*area*g
    pin = q*l2/2.0_dp
    do i = 1, 2
      call static_bc(1, formulations(i), [g, 0.0_dp, 0.0_dp], none, ub, uc)
      call assert_rel_close(ub(1), q*l1**4/(8.0_dp*ei) + pin*l1**3/(3.0_dp*ei), 1.0e-8_dp, 'u_B under gravity')
      call assert_rel_close(uc(1), q*l3**4/(8.0_dp*ei) + pin*l3**3/(3.0_dp*ei), 1.0e-8_dp, 'u_C under gravity')
      call assert_true(maxval(abs([ub(2:3), uc(2:3)])) <= 1.0e-8_dp*uc(1), 'B and C move along gravity only')
    end do
  end subroutine test_gravity
end module test_spatial_loads_suite

program test_spatial_loads
  use assertions, only: finish_suite
  use test_spatial_loads_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_spatial_loads')
end program test_spatial_loads
