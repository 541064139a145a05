!> Cost of the spatial analysis (doc/spatial.md, "Cost"):
!>  1. one right-hand side (element evaluations, banded mass assembly and
!>     Cholesky) against the number of elements per link: linear in the
!>     number of elements (banded);
!>  2. the issue-13 target case: Tennant's four-bar in the spatial code, four
!>     elements per link, 150 rad/s, light damping (beta = 1e-5 s), one crank
!>     turn from the rigid-body state, DLSODE bdf / bdf_band at rtol = 1e-6:
!>     CPU per turn, steps, RHS and Jacobian evaluations (Adams is left out:
!>     at four elements per link the curvature DOFs make the system stiff and
!>     Adams needs minutes per turn, as in the planar code, doc/benchmarks.md).
!> Figures, not pass/fail.
program bench_spatial
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t
  use kear_element, only: element_effects_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_bdf_full_user, mf_bdf_band_user
  use spatial_section, only: spatial_section_init, section_rectangular
  use spatial_kinematics, only: spatial_fourbar_t, spatial_fourbar_init
  use spatial_model, only: spatial_model_t, spatial_link_t, spatial_joint_revolute
  implicit none
  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=2.536e-4_dp)
  integer, parameter :: meshes(6) = [1, 2, 4, 8, 16, 32]
  integer :: i, j, k, ncall, mf(2)
  real(dp) :: c0, c1
  real(dp), allocatable :: q(:), qd(:), qdd(:), y(:)
  type(spatial_model_t), target :: sm
  type(lsode_t) :: ode
  type(lsode_counters_t) :: cnt
  type(error_t) :: err
  type(element_effects_t) :: fx
  character(len=8) :: names(2)

  write(*, '(a)') 'spatial four-bar (Tennant geometry, revolute joints), one right-hand side:'
  write(*, '(a)') '  effects    n/link  unknowns  half-band   us/RHS   us/RHS/element'
  do k = 1, 2
    if (k == 1) then
      fx = element_effects_t(.false., .false., .false., .false., .true.)
    else
      fx = element_effects_t(.true., .true., .true., .true., .true.)
    end if
    do i = 1, size(meshes)
      call build(meshes(i), fx, 1.0e-5_dp, sm)
      allocate(q(sm%n), qd(sm%n), qdd(sm%n))
      q = 1.0e-6_dp                             ! small elastic state: no strain near the material peak
      qd = 1.0e-4_dp
      ncall = max(20, 4000/meshes(i))
      call cpu_time(c0)
      do j = 1, ncall
        sm%t_states = -1.0_dp                   ! force the kinematics too, as in a run
        call sm%accelerations(1.0e-3_dp, q, qd, qdd)
      end do
      call cpu_time(c1)
      if (sm%err%failed()) write(*, '(a)') '  (model stopped: '//sm%err%text()//')'
      write(*, '(2x,a8,i8,i10,i11,f10.1,f14.2)') merge('linear  ', 'all on  ', k == 1), meshes(i), sm%n, sm%kd, &
        1.0e6_dp*(c1 - c0)/ncall, 1.0e6_dp*(c1 - c0)/ncall/(3*meshes(i))
      flush(output_unit)
      deallocate(q, qd, qdd)
    end do
  end do

  write(*, '(/,a)') 'issue-13 target: 4 elements per link, 150 rad/s, beta = 1e-5 s, one turn, rtol = 1e-6:'
  write(*, '(a)') '  effects    method     CPU ms/turn    steps      RHS    Jac'
  mf = [mf_bdf_full_user, mf_bdf_band_user]
  names = [character(len=8) :: 'bdf', 'bdf_band']
  do k = 1, 2
    if (k == 1) then
      fx = element_effects_t(.false., .false., .false., .false., .false.)
    else
      fx = element_effects_t(.true., .true., .false., .true., .true.)
    end if
    do i = 1, 2
      call build(4, fx, 1.0e-5_dp, sm)
      allocate(y(2*sm%n))
      y = 0.0_dp
      call ode%init(size(y), 0.0_dp, mf(i), 1.0e-6_dp, [1.0e-10_dp], err, ml=2*sm%kd + 1, mu=2*sm%kd + 1, &
                    max_steps=2000000)
      call cpu_time(c0)
      call ode%integrate_to(sm, y, two_pi/150.0_dp, err)
      call cpu_time(c1)
      cnt = ode%counters()
      if (err%failed()) then
        write(*, '(2x,a10,1x,a8,a)') merge('linear    ', 'geometric ', k == 1), names(i), ' stopped: '//err%text()
        call err%clear()
      else
        write(*, '(2x,a10,1x,a8,f12.1,3i9)') merge('linear    ', 'geometric ', k == 1), names(i), 1.0e3_dp*(c1 - c0), &
          cnt%steps, cnt%rhs_evals, cnt%jac_evals
      end if
      flush(output_unit)
      deallocate(y)
    end do
  end do
  write(*, '(a)') '  (geometric = stretching, curvature, rotary inertia, coupling; with the material law on the'
  write(*, '(a)') '   crank passes the Ramberg-Osgood peak at 12.5 degrees, as in the planar code)'

contains

  subroutine build(n, fx, beta, model)
    integer, intent(in) :: n
    type(element_effects_t), intent(in) :: fx
    real(dp), intent(in) :: beta
    type(spatial_model_t), intent(out) :: model
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(error_t) :: e
    integer :: j
    call spatial_fourbar_init(kin, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [5.0_dp, 0.0_dp, 0.0_dp], &
                              [10.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], 10.5_dp, 11.0_dp, 1, e)
    do j = 1, 3
      links(j)%n_elements = n
      links(j)%material = alu
      links(j)%shear_modulus = alu%e1/2.66_dp
      call spatial_section_init(links(j)%sec, section_rectangular, [1.0_dp, 0.25_dp], alu, e)
    end do
    call model%init(kin, 150.0_dp, 0.0_dp, spatial_joint_revolute, spatial_joint_revolute, links, fx, beta, e)
    if (e%failed()) error stop 'bench_spatial: model'
  end subroutine build
end program bench_spatial
