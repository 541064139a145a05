!> Cost of the spatial analysis (doc/spatial.md, "Cost"):
!>  1. one right-hand side (element evaluations, the mass solve of
!>     spatial_mass) against the number of elements per link: linear in the
!>     number of elements (banded);
!>  2. the target case: Tennant's four-bar in the spatial code, four
!>     elements per link, 150 rad/s, light damping (beta = 1e-5 s), one crank
!>     turn from the rigid-body state, DLSODE bdf through the model's banded
!>     Newton matrix and (before) through DLSODE's dense one: CPU per turn,
!>     steps, RHS and Jacobian evaluations, coupler peak stress (Adams is
!>     left out: the curvature DOFs make four elements per link stiff);
!>  3. the banded route against the mesh (1 to 16 elements per link).
!> `bench_spatial turns` skips part 1, `bench_spatial rhs` runs part 1 at 4 elements per
!> link only (new time and reused mass); `bench_spatial probe N [geometric|linear [RTOL]]`
!> runs one turn (tolerances B) at N elements per link, e.g. under perf.  Figures, not pass/fail.
program bench_spatial
  use, intrinsic :: iso_fortran_env, only: output_unit
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use material_law, only: ramberg_osgood_t
  use element_effects, only: element_effects_t
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_bdf_full_user
  use spatial_section, only: spatial_section_init, section_rectangular
  use spatial_kinematics, only: spatial_fourbar_t, spatial_fourbar_init
  use spatial_model, only: spatial_model_t, spatial_link_t, spatial_joint_revolute
  use spatial_beam, only: spatial_stress_t, spatial_formulation_kear
  implicit none
  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=2.536e-4_dp)
  integer, parameter :: meshes(6) = [1, 2, 4, 8, 16, 32]
  integer :: i, j, k
  real(dp) :: c1
  type(spatial_model_t), target :: sm
  type(lsode_t) :: ode
  type(lsode_counters_t) :: cnt
  type(error_t) :: err
  type(element_effects_t) :: fx

  character(len=16) :: arg, arg2
  real(dp) :: rtol_b = 1.0e-4_dp

  call get_command_argument(1, arg)
  if (trim(arg) == 'probe') then           ! one turn, tolerances B, e.g. under perf: probe N [geometric]
    call get_command_argument(2, arg)
    read(arg, *) i
    call get_command_argument(3, arg)
    fx = element_effects_t(.false., .false., .false., .false., .false.)
    if (trim(arg) == 'geometric') fx = element_effects_t(.true., .true., .false., .true., .true.)
    call get_command_argument(4, arg2)       ! rtol of tolerances B (default 1e-4)
    if (len_trim(arg2) > 0) read(arg2, *) rtol_b
    call turn(i, fx, 2, .true., merge('geometric ', 'linear    ', trim(arg) == 'geometric'), 'bdf      ')
    stop
  end if
  if (trim(arg) == 'rhs') then             ! the right-hand side at 4 elements per link only
    call rhs_cost(3)
    stop
  end if
  if (trim(arg) /= 'turns') call rhs_cost(size(meshes))

  write(*, '(/,a)') 'target case: 4 elements per link, 150 rad/s, beta = 1e-5 s, one turn from the rigid state'
  write(*, '(a)') '  bdf = DLSODE MF 21 through the model''s banded N x N Newton matrix; bdf dense = the same with'
  write(*, '(a)') '  structured = .false. (DLSODE''s dense 2N x 2N P from the dense M^-1 K_t: the route before)'
  write(*, '(a)') '  tolerances A: rtol 1e-6, atol 1e-10; B: rtol 1e-4, atol 1e-7 in, 1e-4 in/s (the planar bench)'
  write(*, '(a)') '  effects    method     tol  CPU ms/turn    steps      RHS    Jac   peak |stress| coupler'
  do k = 1, 2
    if (k == 1) then
      fx = element_effects_t(.false., .false., .false., .false., .false.)
    else
      fx = element_effects_t(.true., .true., .false., .true., .true.)
    end if
    do j = 1, 2
      do i = 1, 2
        if (i == 2 .and. j == 2 .and. k == 2) cycle      ! dense is slow: linear and tolerance A suffice
        call turn(4, fx, j, i == 1, merge('linear    ', 'geometric ', k == 1), &
                  merge('bdf      ', 'bdf dense', i == 1))
      end do
    end do
  end do
  write(*, '(a)') '  (geometric = stretching, curvature, rotary inertia, coupling; with the material law on the'
  write(*, '(a)') '   crank passes the Ramberg-Osgood peak at 12.5 degrees, as in the planar code)'

  write(*, '(/,a)') 'banded Newton matrix against the mesh: linear, tolerances B, one turn at 150 rad/s'
  write(*, '(a)') '  effects    method     tol  CPU ms/turn    steps      RHS    Jac   peak |stress| coupler'
  do i = 1, 5
    write(*, '(a,i0,a)') '  n/link = ', meshes(i), ':'
    call turn(meshes(i), element_effects_t(.false., .false., .false., .false., .false.), 2, .true., &
              'linear    ', 'bdf      ')
  end do

contains

  !> Part 1: CPU of one right-hand side against the mesh.
  subroutine rhs_cost(upto)
    integer, intent(in) :: upto           !< meshes(1:upto), or meshes(3) alone if upto = 3
    integer :: ncall, i0
    real(dp) :: c0
    real(dp), allocatable :: q(:), qd(:), qdd(:)
    write(*, '(a)') 'spatial four-bar (Tennant geometry, revolute joints), one right-hand side:'
    write(*, '(a)') '  effects    n/link  unknowns  half-band   us/RHS   us/RHS/element'
    do k = 1, 2
      if (k == 1) then
        fx = element_effects_t(.false., .false., .false., .false., .true.)
      else
        fx = element_effects_t(.true., .true., .true., .true., .true.)
      end if
      i0 = merge(3, 1, upto == 3)
      do i = i0, upto
        call build(meshes(i), fx, 1.0e-5_dp, sm)
        allocate(q(sm%n), qd(sm%n), qdd(sm%n))
        q = 1.0e-6_dp                             ! small elastic state: no strain near the material peak
        qd = 1.0e-4_dp
        ncall = max(20, 4000/meshes(i))
        if (upto == 3) ncall = 20000
        call cpu_time(c0)
        do j = 1, ncall
          sm%t_states = -1.0_dp                   ! force the kinematics and the mass (a new time)
          sm%t_mass = -1.0_dp
          call sm%accelerations(1.0e-3_dp, q, qd, qdd)
        end do
        call cpu_time(c1)
        if (upto == 3) then                       ! and at an unchanged time (mass factor reused)
          write(*, '(a,f8.2)') '  new time, us per RHS:', 1.0e6_dp*(c1 - c0)/ncall
          call cpu_time(c0)
          do j = 1, ncall
            call sm%accelerations(1.0e-3_dp, q, qd, qdd)
          end do
          call cpu_time(c1)
          write(*, '(a,f8.2)') '  same time, us per RHS:', 1.0e6_dp*(c1 - c0)/ncall
          call cpu_time(c0)
          do j = 1, ncall
            sm%t_states = -1.0_dp
            call sm%set_time(1.0e-3_dp)
          end do
          call cpu_time(c1)
          write(*, '(a,f8.2)') '  kinematics and element frames, us:', 1.0e6_dp*(c1 - c0)/ncall
        end if
        if (sm%err%failed()) write(*, '(a)') '  (model stopped: '//sm%err%text()//')'
        write(*, '(2x,a8,i8,i10,i11,f10.1,f14.2)') merge('linear  ', 'all on  ', k == 1), meshes(i), sm%n, sm%kd, &
          1.0e6_dp*(c1 - c0)/ncall, 1.0e6_dp*(c1 - c0)/ncall/(3*meshes(i))
        flush(output_unit)
        deallocate(q, qd, qdd)
      end do
    end do
  end subroutine rhs_cost

  !> One crank turn from the rigid state at n elements per link; tolerance
  !> set tol (1: A, 2: B); structured: the model's banded Newton matrix.
  subroutine turn(n, fx, tol, structured, label, method)
    integer, intent(in) :: n, tol
    type(element_effects_t), intent(in) :: fx
    logical, intent(in) :: structured
    character(len=*), intent(in) :: label, method
    real(dp), allocatable :: y(:), atol(:)
    real(dp) :: peak, t0, t1
    integer :: step, nsteps
    type(spatial_stress_t), allocatable :: rep(:)
    call build(n, fx, 1.0e-5_dp, sm)
    allocate(y(2*sm%n), atol(2*sm%n), rep(size(sm%el)))
    y = 0.0_dp
    if (tol == 1) then
      atol = 1.0e-10_dp
      call ode%init(size(y), 0.0_dp, mf_bdf_full_user, 1.0e-6_dp, atol, err, max_steps=2000000, structured=structured)
    else
      atol(1::2) = 1.0e-7_dp
      atol(2::2) = 1.0e-4_dp
      call ode%init(size(y), 0.0_dp, mf_bdf_full_user, rtol_b, atol, err, max_steps=2000000, structured=structured)
    end if
    ! 360 output points (the stress peak); CPU of the DLSODE calls only
    nsteps = 360
    peak = 0.0_dp
    t1 = 0.0_dp
    do step = 1, nsteps
      call cpu_time(t0)
      call ode%integrate_to(sm, y, step*two_pi/150.0_dp/nsteps, err)
      call cpu_time(c1)
      t1 = t1 + (c1 - t0)
      if (err%failed()) exit
      call sm%set_time(ode%t)
      call sm%element_stresses(y(1::2), rep)
      peak = max(peak, maxval(rep(sm%links(2)%first_element:sm%links(2)%first_element + n - 1)%max_abs_stress))
    end do
    cnt = ode%counters()
    if (err%failed()) then
      write(*, '(2x,a10,1x,a9,a)') label, method, ' stopped: '//err%text()
      call err%clear()
    else
      write(*, '(2x,a10,1x,a9,2x,a1,f12.1,3i9,f14.2)') label, method, merge('A', 'B', tol == 1), 1.0e3_dp*t1, &
        cnt%steps, cnt%rhs_evals, cnt%jac_evals, peak
    end if
    flush(output_unit)
  end subroutine turn

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
    call model%init(kin, 150.0_dp, 0.0_dp, spatial_joint_revolute, spatial_joint_revolute, links, fx, beta, e, &
                    formulation=spatial_formulation_kear)    ! the mechanism decks' element (doc/spatial.md)
    if (e%failed()) error stop 'bench_spatial: model'
  end subroutine build
end program bench_spatial
