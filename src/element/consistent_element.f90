!> The consistent planar beam element: Kear's kinematics (K5), exact stretch
!> and curvature, Ramberg-Osgood material through the depth, exact rotary
!> inertia -- with the axial displacement interpolated by the same quintic
!> Hermite functions as the transverse one.  Kear's linear u makes
!> 1 + u_x constant on an element, so with exact stretching an element cannot
!> bend without stretching (membrane locking, doc/element.md section 15); with
!> quintic u and w both components of the tangent r_x = (1 + u_x, w_x) are
!> quartics and inextensible bending is approximated to the same order as the
!> curvature.  Any planar curve, a full circle included, is representable.
!>
!> Element DOFs  q = [U1 W1 th1 m1 a1 b1  U2 W2 th2 m2 a2 b2]:  U, W global X/Y
!> elastic translations of the nodes, th = w_x, m = w_xx, a = u_x, b = u_xx
!> (local, relative to the link's rigid-body axes).  p = T(phi) q rotates the
!> two translation pairs into the element frame.
!>
!>   M_e qddot = F_e  with  M_e = rho int( A B^T B + I theta_q theta_q^T ),
!>   F_e = -dSE/dq - rho int[ A B^T (c_dd + B_dd q + 2 B_d q_d)
!>                            + I theta_q (theta_dd - theta_q . q_dd) ] - beta K_t pdot
!>
!> the same Lagrange equations as kear_element (doc/element.md sections 3-8),
!> with S (2 x 12) in place of Kear's 2 x 8 interpolation.  All procedures
!> are pure.
module consistent_element
  use kinds, only: dp
  use linalg, only: outer
  use error_status, only: error_t
  use quadrature, only: gauss_legendre_interval
  use shape_functions, only: quintic_hermite
  use material_law, only: ramberg_osgood_t, section_resultants_t, section_response
  use beam_properties, only: element_effects_t, init_beam_properties
  use planar_beam_kernels, only: to_local, to_global, rotate_to_global, jb_times, frame_vectors, in_frame, &
                                 translational_force, frame_acceleration, add_linear_rotary, point_kinetic_energy, &
                                 subtract_elastic_forces, to_global_results, &
                                 add_constant_integrals, rotating_frame_integrals, add_station_terms, exact_angle_terms, &
                                 add_rank_one
  use planar_element, only: planar_element_t, rigid_state_t, kear_eval_info_t, is_linear_strain, &
                            consistent_internal_force => planar_internal_force, &
                            consistent_tangent_stiffness => planar_tangent_stiffness, &
                            consistent_strain_energy => planar_strain_energy, &
                            consistent_stress_recovery => planar_stress_recovery, station_x_over_l
  implicit none
  private
  public :: consistent_ndof, consistent_element_t
  public :: consistent_element_init, consistent_element_eval, consistent_internal_force
  public :: consistent_tangent_stiffness, consistent_strain_energy, consistent_kinetic_energy
  public :: consistent_stress_recovery, consistent_section_strains, consistent_local_displacement
  public :: consistent_local_dofs, consistent_shape, consistent_point_load

  integer, parameter :: consistent_ndof = 12
  integer, parameter :: nd = consistent_ndof
  integer, parameter :: node2 = 7        !< local DOF of node 2's u (then w)
  integer, parameter :: n_exact = 6      !< Gauss points exact for the constant integrals (degree <= 11)

  !> One element.  Arrays in the local DOF order p = [u1 w1 th1 m1 a1 b1 u2 w2 th2 m2 a2 b2].
  type, extends(planar_element_t) :: consistent_element_t
    real(dp) :: mass_trans(nd, nd) = 0.0_dp   !< int S^T S
    real(dp) :: coupling(nd, nd) = 0.0_dp     !< int S^T (J S - S J_b)
    real(dp) :: centrifugal(nd, nd) = 0.0_dp  !< int S^T (S J_b^2 - S - 2 J S J_b)
    real(dp) :: load0(nd, 2) = 0.0_dp         !< int S^T dx
    real(dp) :: load1(nd, 2) = 0.0_dp         !< int x S^T dx
    real(dp) :: k_linear(nd, nd) = 0.0_dp     !< E1 A int gu gu^T + E1 I int gww gww^T
    real(dp) :: rot_linear(nd, nd) = 0.0_dp   !< int gw gw^T
    real(dp) :: rot_load(nd) = 0.0_dp         !< int gw dx
    real(dp), allocatable :: g(:, :, :)       !< (nd, 4, n): d(u_x, w_x, w_xx, u_xx)/dp at the stations xg
  contains
    procedure :: strain_terms => consistent_strain_terms
    procedure :: linear_force => consistent_linear_force
    procedure :: section_strains => consistent_section_strains
    procedure :: station_strains => consistent_station_strains
  end type consistent_element_t

  !> Strain state at a station: value and derivatives in (a, b, c, d) =
  !> (1 + u_x, w_x, w_xx, u_xx).
  type :: strain_point_t
    real(dp) :: eps = 0.0_dp, kap = 0.0_dp
    real(dp) :: de(4) = 0.0_dp, dk(4) = 0.0_dp
    real(dp) :: he(4, 4) = 0.0_dp, hk(4, 4) = 0.0_dp
  end type strain_point_t

contains

  pure subroutine consistent_element_init(el, length, width, depth, material, effects, err, &
                                          n_gauss, damping_beta, objective_damping, fibre_distance)
    type(consistent_element_t), intent(out) :: el
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta
    logical, intent(in), optional :: objective_damping
    real(dp), intent(in), optional :: fibre_distance   !< c of a section given by A, I, c (default t/2)
    real(dp) :: x(n_exact), w(n_exact), su(nd), sw(nd), gs(nd, 4), g2(nd, nd)
    integer :: i

    call init_beam_properties(el%beam_properties_t, 'consistent_element_init', length, width, depth, material, &
                              effects, err, n_gauss, damping_beta, objective_damping, fibre_distance)
    if (err%failed()) return
    el%node2 = node2

    ! constant integrals: S^T S has degree 10, exact with 6 points
    g2 = 0.0_dp
    call gauss_legendre_interval(n_exact, 0.0_dp, length, x, w)
    do i = 1, n_exact
      call consistent_shape(x(i)/length, length, su, sw, gs)
      call add_constant_integrals(w(i), x(i), su, sw, gs(:, 1), gs(:, 2), gs(:, 3), material%e1*el%area, &
                                  material%e1*el%inertia, el%mass_trans, g2, el%load0, el%load1, el%k_linear, &
                                  el%rot_linear, el%rot_load)
    end do
    call rotating_frame_integrals(el%mass_trans, g2, node2, el%coupling, el%centrifugal)

    allocate(el%xg(el%n_gauss), el%wg(el%n_gauss), el%g(nd, 4, el%n_gauss))
    call gauss_legendre_interval(el%n_gauss, 0.0_dp, length, el%xg, el%wg)
    do i = 1, el%n_gauss
      call consistent_shape(el%xg(i)/length, length, su, sw, el%g(:, :, i))
    end do
    allocate(el%gs(nd, 4, 0:el%n_gauss + 1))
    do i = 0, el%n_gauss + 1
      call consistent_shape(station_x_over_l(el%beam_properties_t, el%xg, i), length, su, sw, el%gs(:, :, i))
    end do
  end subroutine consistent_element_init

  !> Interpolation at x = e l: u = su.p, w = sw.p and the gradients
  !> g(:, 1:4) of (u_x, w_x, w_xx, u_xx) with respect to p.
  pure subroutine consistent_shape(e, l, su, sw, g)
    real(dp), intent(in) :: e, l
    real(dp), intent(out) :: su(nd), sw(nd), g(nd, 4)
    real(dp) :: h(6), hx(6), hxx(6)
    call quintic_hermite(e, l, h, hx, hxx)
    su = spread_u(h)
    sw = spread_w(h)
    g(:, 1) = spread_u(hx)
    g(:, 2) = spread_w(hx)
    g(:, 3) = spread_w(hxx)
    g(:, 4) = spread_u(hxx)
  end subroutine consistent_shape

  ! ---------------------------------------------------------- main routine

  !> Mass matrix, force vector and optionally the tangent stiffness d^2SE/dq^2.
  pure subroutine consistent_element_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), qd(nd)
    type(rigid_state_t), intent(in) :: rb
    real(dp), intent(out) :: mass(nd, nd), force(nd)
    type(kear_eval_info_t), intent(out) :: info
    real(dp), intent(out), optional :: tangent(nd, nd)
    logical, intent(in), optional :: mass_wanted     !< .false.: mass not computed (M depends on t only)
    real(dp) :: c, s, p(nd), v(nd), jp(nd), jv(nd), j2p(nd), pdd_nm(nd), prel(nd)
    real(dp) :: fp(nd), kp(nd, nd), fint(nd), fdamp(nd), acc0(2), rhoa, rhoi
    logical :: want_k, want_m

    c = cos(rb%phi)
    s = sin(rb%phi)
    call frame_vectors(c, s, q, qd, node2, p, v, jp, jv, j2p)
    rhoa = el%material%rho*el%area
    rhoi = el%material%rho*el%inertia

    ! translational inertia (exact, constant matrices)
    acc0 = in_frame(c, s, rb%x1_dd, rb%y1_dd)
    want_m = .true.
    if (present(mass_wanted)) want_m = mass_wanted
    if (want_m) mass = rhoa*el%mass_trans
    fp = translational_force(el%load0, el%load1, el%coupling, matmul(el%centrifugal, p), p, v, acc0, rb%phi_d, &
                             rb%phi_dd, rhoa, el%effects%coupling)

    ! strain energy, internal force, damping
    want_k = present(tangent)
    prel = v
    if (el%objective_damping) prel = v - rb%phi_d*jp
    if (is_linear_strain(el)) then
      fint = matmul(el%k_linear, p)
      info%strain_energy = 0.5_dp*dot_product(p, fint)
      if (el%beta > 0.0_dp) fdamp = matmul(el%k_linear, prel)
      call subtract_elastic_forces(fp, fint, fdamp, el%beta)
      if (want_k) kp = el%k_linear
      call linear_strain_peak(el, p, info)
    else
      call nonlinear_strain_terms(el, p, prel, want_k, el%beta > 0.0_dp, info, fint, fdamp, kp)
      call subtract_elastic_forces(fp, fint, fdamp, el%beta)
    end if

    ! rotary inertia
    if (el%effects%rotary_inertia) then
      pdd_nm = frame_acceleration(j2p, jp, jv, rb%phi_d, rb%phi_dd, el%effects%coupling)
      if (.not. el%effects%curvature) then
        call add_linear_rotary(el%rot_linear, el%rot_load, rhoi, rb%phi_dd, pdd_nm, want_m, mass, fp)
      else
        if (.not. want_m) mass = 0.0_dp          ! (a caller's choice: this M depends on q)
        call rotary_nonlinear(el, p, v, jp, pdd_nm, rb%phi_d, rb%phi_dd, rhoi, mass, fp, info)
      end if
    end if

    call to_global_results(c, s, node2, fp, force, want_m, mass, kp, tangent)
  end subroutine consistent_element_eval

  !> planar_element_t's strain_terms: nonlinear_strain_terms (fixed sizes).
  pure subroutine consistent_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:), prel(:)
    logical, intent(in) :: want_k, want_damp
    type(kear_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(:), fdamp(:), kp(size(p), size(p))
    call nonlinear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
  end subroutine consistent_strain_terms

  !> planar_element_t's linear_force: K p and K.
  pure subroutine consistent_linear_force(el, p, want_k, fint, kp)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:)
    logical, intent(in) :: want_k
    real(dp), intent(out) :: fint(:), kp(size(p), size(p))
    real(dp) :: pl(nd)
    pl = p                                   ! fixed size: matmul's sums as before
    fint = matmul(el%k_linear, pl)
    if (want_k) kp = el%k_linear
  end subroutine consistent_linear_force

  !> Kinetic energy from the positions (K5) and the section angle (K8)
  !> directly, independent of the precomputed matrices (a check of them).
  pure real(dp) function consistent_kinetic_energy(el, q, qd, rb) result(ke)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), qd(nd)
    type(rigid_state_t), intent(in) :: rb
    integer, parameter :: nt = 8
    real(dp) :: c, s, p(nd), pd(nd), x(nt), w(nt), su(nd), sw(nd), g(nd, 4)
    real(dp) :: vloc(2), a, b, ad, bd, thd
    integer :: i
    c = cos(rb%phi)
    s = sin(rb%phi)
    p = to_local(c, s, q, node2)
    pd = to_local(c, s, qd, node2) - rb%phi_d*jb_times(p, node2)
    vloc = in_frame(c, s, rb%x1_d, rb%y1_d)
    ke = 0.0_dp
    call gauss_legendre_interval(nt, 0.0_dp, el%length, x, w)
    do i = 1, nt
      call consistent_shape(x(i)/el%length, el%length, su, sw, g)
      ke = ke + point_kinetic_energy(el%material%rho*el%area, w(i), x(i), vloc, su, sw, p, pd, rb%phi_d)
    end do
    if (el%effects%rotary_inertia) then
      do i = 1, el%n_gauss
        a = 1.0_dp + dot_product(el%g(:, 1, i), p)
        b = dot_product(el%g(:, 2, i), p)
        ad = dot_product(el%g(:, 1, i), pd)
        bd = dot_product(el%g(:, 2, i), pd)
        if (el%effects%curvature) then
          thd = rb%phi_d + (bd*a - b*ad)/(a*a + b*b)
        else
          thd = rb%phi_d + bd
        end if
        ke = ke + 0.5_dp*el%material%rho*el%inertia*el%wg(i)*thd**2
      end do
    end if
  end function consistent_kinetic_energy

  ! ------------------------------------------------------ loads and output

  !> Generalized force of a point force f (global X, Y) and a moment mz
  !> (counter-clockwise) at x = e l, and optionally its Jacobian dQ/dq (the
  !> moment's work mz theta depends on q through the section angle).
  pure subroutine consistent_point_load(el, q, phi, e, f, mz, gen, dgen)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), phi, e, f(2), mz
    real(dp), intent(out) :: gen(nd)
    real(dp), intent(out), optional :: dgen(nd, nd)
    real(dp) :: c, s, p(nd), su(nd), sw(nd), g(nd, 4), fl(2), a, b, r2, r4, hp(nd, nd)
    c = cos(phi)
    s = sin(phi)
    p = to_local(c, s, q, node2)
    call consistent_shape(e, el%length, su, sw, g)
    fl = [c*f(1) + s*f(2), -s*f(1) + c*f(2)]
    hp = 0.0_dp
    if (el%effects%curvature) then
      a = 1.0_dp + dot_product(g(:, 1), p)
      b = dot_product(g(:, 2), p)
      r2 = a*a + b*b
      r4 = r2*r2
      gen = fl(1)*su + fl(2)*sw + mz*(-b*g(:, 1) + a*g(:, 2))/r2
      hp = mz*(2.0_dp*a*b/r4*(outer(g(:, 1), g(:, 1)) - outer(g(:, 2), g(:, 2))) &
               + (b*b - a*a)/r4*(outer(g(:, 1), g(:, 2)) + outer(g(:, 2), g(:, 1))))
    else
      gen = fl(1)*su + fl(2)*sw + mz*g(:, 2)             ! theta = phi + w_x
    end if
    gen = to_global(c, s, gen, node2)
    if (present(dgen)) then
      dgen = hp
      call rotate_to_global(c, s, dgen, node2)
    end if
  end subroutine consistent_point_load

  !> Axial strain and curvature at x = e l from LOCAL nodal values p.
  pure subroutine consistent_section_strains(el, p, e, eps_n, kap)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:), e
    real(dp), intent(out) :: eps_n, kap
    real(dp) :: pl(nd), su(nd), sw(nd), g(nd, 4)
    type(strain_point_t) :: sp
    pl = p
    call consistent_shape(e, el%length, su, sw, g)
    call strain_state(el, strain_variables(pl, g), .false., sp)
    eps_n = sp%eps
    kap = sp%kap
  end subroutine consistent_section_strains

  !> Axial strain and curvature at stress station i from LOCAL nodal values p
  !> (the tabulated gradients gs).
  pure subroutine consistent_station_strains(el, p, i, eps_n, kap)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:)
    integer, intent(in) :: i
    real(dp), intent(out) :: eps_n, kap
    real(dp) :: pl(nd)
    type(strain_point_t) :: sp
    pl = p
    call strain_state(el, strain_variables(pl, el%gs(:, :, i)), .false., sp)
    eps_n = sp%eps
    kap = sp%kap
  end subroutine consistent_station_strains

  pure function consistent_local_dofs(phi, q) result(p)
    real(dp), intent(in) :: phi, q(nd)
    real(dp) :: p(nd)
    p = to_local(cos(phi), sin(phi), q, node2)
  end function consistent_local_dofs

  !> Local elastic displacements (u, w) at x = e l.
  pure function consistent_local_displacement(el, q, phi, e) result(uw)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), phi, e
    real(dp) :: uw(2)
    real(dp) :: p(nd), su(nd), sw(nd), g(nd, 4)
    p = to_local(cos(phi), sin(phi), q, node2)
    call consistent_shape(e, el%length, su, sw, g)
    uw = [dot_product(su, p), dot_product(sw, p)]
  end function consistent_local_displacement

  ! ------------------------------------------------------------ internals

  pure subroutine linear_strain_peak(el, p, info)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(nd)
    type(kear_eval_info_t), intent(inout) :: info
    real(dp) :: e
    integer :: i
    info%max_abs_strain = 0.0_dp
    do i = 1, el%n_gauss
      e = abs(dot_product(el%g(:, 1, i), p)) + 0.5_dp*el%depth*abs(dot_product(el%g(:, 3, i), p))
      call info%note_strain(e, el%xg(i)/el%length)
    end do
    info%beyond_peak = .false.
  end subroutine linear_strain_peak

  !> Strain energy, internal force, tangent K_pp (want_k) and K_pp prel
  !> (want_damp).  Per station f = G (N de + M dk), K = G H G^T with
  !> G = [gu gw gww guu] (12 x 4).
  pure subroutine nonlinear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(nd), prel(nd)
    logical, intent(in) :: want_k, want_damp
    type(kear_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(nd), fdamp(nd), kp(nd, nd)
    real(dp) :: e, ht
    type(strain_point_t) :: sp
    type(section_resultants_t) :: res
    integer :: i
    fint = 0.0_dp
    fdamp = 0.0_dp
    kp = 0.0_dp
    info%strain_energy = 0.0_dp
    info%max_abs_strain = 0.0_dp
    ht = 0.5_dp*el%depth
    do i = 1, el%n_gauss
      associate (g => el%g(:, :, i))
        call strain_state(el, strain_variables(p, g), .true., sp)
        res = section_response(el%material, el%area, el%depth, sp%eps, sp%kap, el%effects%material)
        info%strain_energy = info%strain_energy + el%wg(i)*res%energy
        call add_station_terms(el%wg(i), g, res%axial_force, res%moment, res%tangent, sp%de, sp%de, sp%dk, sp%he, &
                               sp%hk, prel, want_k, want_damp, fint, fdamp, kp)
      end associate
      e = abs(sp%eps) + ht*abs(sp%kap)
      call info%note_strain(e, el%xg(i)/el%length)
    end do
    info%n_nonlinear_points = info%n_nonlinear_points + el%n_gauss
    info%beyond_peak = el%effects%material .and. info%max_abs_strain > el%eps_star
  end subroutine nonlinear_strain_terms

  !> z = (u_x, w_x, w_xx, u_xx) = p^T g at a station: fixed-size loops in
  !> matmul's order (matmul on a section of the tabulated gradients takes a
  !> heap temporary on every call).
  pure function strain_variables(p, g) result(z)
    real(dp), intent(in) :: p(nd), g(nd, 4)
    real(dp) :: z(4)
    integer :: j, k
    do k = 1, 4
      z(k) = 0.0_dp
      do j = 1, nd
        z(k) = z(k) + p(j)*g(j, k)
      end do
    end do
  end function strain_variables

  !> eps_n and kappa from z = (u_x, w_x, w_xx, u_xx) with derivatives in
  !> (a, b, c, d) = (1 + u_x, w_x, w_xx, u_xx):
  !>   eps_n = sqrt(a^2 + b^2) - 1          (stretching on; off: u_x)
  !>   kappa = (c a - b d)/(a^2 + b^2)^1.5  (curvature on; off: w_xx)
  pure subroutine strain_state(el, z, derivs, sp)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: z(4)
    logical, intent(in) :: derivs
    type(strain_point_t), intent(out) :: sp
    real(dp) :: a, b, c, d, r2, r, r3, f, fa, fb, faa, fab, fbb, n, r5, r7
    a = 1.0_dp + z(1)
    b = z(2)
    c = z(3)
    d = z(4)
    r2 = a*a + b*b
    r = sqrt(r2)
    r3 = r2*r
    if (el%effects%stretching) then
      sp%eps = (z(1)*(2.0_dp + z(1)) + b*b)/(r + 1.0_dp)      ! r - 1 without cancellation
      if (derivs) then
        sp%de = [a/r, b/r, 0.0_dp, 0.0_dp]
        sp%he(1, 1) = b*b/r3
        sp%he(1, 2) = -a*b/r3
        sp%he(2, 1) = -a*b/r3
        sp%he(2, 2) = a*a/r3
      end if
    else
      sp%eps = z(1)
      if (derivs) sp%de = [1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
    end if
    if (.not. el%effects%curvature) then
      sp%kap = c
      if (derivs) sp%dk = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]
      return
    end if
    n = c*a - b*d
    f = 1.0_dp/r3
    sp%kap = n*f
    if (.not. derivs) return
    r5 = r3*r2
    r7 = r5*r2
    fa = -3.0_dp*a/r5
    fb = -3.0_dp*b/r5
    faa = -3.0_dp/r5 + 15.0_dp*a*a/r7
    fab = 15.0_dp*a*b/r7
    fbb = -3.0_dp/r5 + 15.0_dp*b*b/r7
    sp%dk = [c*f + n*fa, -d*f + n*fb, a*f, -b*f]
    sp%hk(1, 1) = 2.0_dp*c*fa + n*faa
    sp%hk(1, 2) = c*fb - d*fa + n*fab
    sp%hk(2, 2) = -2.0_dp*d*fb + n*fbb
    sp%hk(1, 3) = f + a*fa
    sp%hk(1, 4) = -b*fa
    sp%hk(2, 3) = a*fb
    sp%hk(2, 4) = -f - b*fb
    sp%hk(2, 1) = sp%hk(1, 2)
    sp%hk(3, 1) = sp%hk(1, 3)
    sp%hk(4, 1) = sp%hk(1, 4)
    sp%hk(3, 2) = sp%hk(2, 3)
    sp%hk(4, 2) = sp%hk(2, 4)
  end subroutine strain_state

  !> Rotary inertia with the exact section angle theta = phi + atan2(w_x, 1 + u_x)
  !> (curvature on): adds rho I int theta_q theta_q^T to mp and
  !> -rho I int theta_q (theta_dd - theta_q.q_dd) to fp.
  pure subroutine rotary_nonlinear(el, p, v, jp, pdd_nm, phi_d, phi_dd, rhoi, mp, fp, info)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(nd), v(nd), jp(nd), pdd_nm(nd), phi_d, phi_dd, rhoi
    real(dp), intent(inout) :: mp(nd, nd), fp(nd)
    type(kear_eval_info_t), intent(inout) :: info
    real(dp) :: a, b, xa, xb, tq(nd), acc, quad, pd(nd)
    integer :: i
    pd = v - phi_d*jp
    do i = 1, el%n_gauss
      associate (gu => el%g(:, 1, i), gw => el%g(:, 2, i))
        a = 1.0_dp + dot_product(gu, p)
        b = dot_product(gw, p)
        call exact_angle_terms(a, b, gu, gw, v, jp, pd, phi_d, el%effects%coupling, xa, xb, quad)
        tq = xa*gu + xb*gw
      end associate
      acc = phi_dd + dot_product(tq, pdd_nm) + quad
      call add_rank_one(nd, mp, rhoi*el%wg(i), tq)
      fp = fp - rhoi*el%wg(i)*acc*tq
    end do
    info%n_nonlinear_points = info%n_nonlinear_points + el%n_gauss
  end subroutine rotary_nonlinear

  !> The six Hermite functions at the u DOFs (1, 5, 6, 7, 11, 12) ...
  pure function spread_u(h) result(s)
    real(dp), intent(in) :: h(6)
    real(dp) :: s(nd)
    s = [h(1), 0.0_dp, 0.0_dp, 0.0_dp, h(2), h(3), h(4), 0.0_dp, 0.0_dp, 0.0_dp, h(5), h(6)]
  end function spread_u

  !> ... and at the w DOFs (2, 3, 4, 8, 9, 10).
  pure function spread_w(h) result(s)
    real(dp), intent(in) :: h(6)
    real(dp) :: s(nd)
    s = [0.0_dp, h(1), h(2), h(3), 0.0_dp, 0.0_dp, 0.0_dp, h(4), h(5), h(6), 0.0_dp, 0.0_dp]
  end function spread_w
end module consistent_element
