!> Spatial beam element for flexible mechanisms (paper E, FORMULATION.md
!> section 7, built in the spirit of Kear's planar element; every choice the
!> OCR leaves open is in doc/spatial.md).  Floating frame: the element's
!> reference line moves with its link's rigid-body motion (rotation R(t),
!> columns = local axes in global components), elastic displacements are
!> measured in that frame.
!>
!> Local DOFs per node (8):  u v w  (translations)  tx ty tz  (small rotation
!> vector: tx = twist theta, ty = -w_x, tz = v_x)  vxx wxx (curvature DOFs of
!> the quintic Hermite functions).  Element: p = [node 1, node 2] (16).
!> Global element DOFs q: the two vector triples of each node in global
!> components, q = T p with T = diag(R, R, 1, 1) per node; the curvature
!> DOFs stay local (as Kear's th and m do).
!>
!> Interpolation: u, theta linear; v, w quintic Hermite (C2, as Kear's w).
!> Strains: eps = |r'| - 1 (exact stretch), curvature vector r' x r''/|r'|^3
!> of the centroid line (exact for u_xx = 0), twist rate theta_x (St. Venant,
!> warping neglected); each nonlinearity has a switch (element_effects_t of
!> the planar element).  In the x-y plane with w = theta = 0 every term is
!> Kear's 'exact' formulation (doc/spatial.md, "Planar limit").
!>
!> M_e qddot = F_e is the element's part of Lagrange's equations:
!>   M_e = T M_p T^T,  F_e = T [F_p + M_p (2 W v + Wdot p - W^2 p)]
!> where M_p p_dd = F_p are the Lagrange equations in the moving frame,
!> v = T^T q_dot and W = skew(omega_local) on the vector triples (p_dot =
!> v - W p).  The coupling switch drops the Euler (alpha x r_el) and
!> Coriolis (omega x v) terms of the elastic motion exactly as the planar
!> element does.
module spatial_beam
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use quadrature, only: gauss_legendre_interval, max_gauss_points
  use shape_functions, only: quintic_hermite, linear_lagrange
  use material_law, only: ramberg_osgood_t, validate_material, ro_stress, peak_strain
  use kear_element, only: element_effects_t
  use spatial_section, only: spatial_section_t, spatial_section_resultants, section_extreme_fibre_strain
  implicit none
  private
  public :: sb_ndof, spatial_rigid_t, spatial_beam_t, spatial_eval_info_t, spatial_stress_t
  public :: spatial_beam_init, spatial_beam_eval, spatial_internal_force, spatial_tangent_stiffness
  public :: spatial_strain_energy, spatial_kinetic_energy, spatial_to_local, spatial_to_global
  public :: spatial_section_state, spatial_stress_recovery, spatial_local_displacement

  integer, parameter :: sb_ndof = 16
  integer, parameter :: n_in = 6            !< inertia stations: S^T S has degree 10, exact
  !> rotation components carried by each node's second triple
  integer, parameter :: iu = 1, iv = 2, iw = 3, itx = 4, ity = 5, itz = 6, ivxx = 7, iwxx = 8
  !> the DOFs each displacement component's functions touch (u linear; v, w quintic)
  integer, parameter :: u_set(2) = [1, 9], v_set(6) = [2, 6, 7, 10, 14, 15], w_set(6) = [3, 5, 8, 11, 13, 16]

  !> Rigid-body state of the element frame, global components.
  type :: spatial_rigid_t
    real(dp) :: rot(3, 3) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
    real(dp) :: x1(3) = 0.0_dp, x1_d(3) = 0.0_dp, x1_dd(3) = 0.0_dp   !< end 1 of the reference line
    real(dp) :: omega(3) = 0.0_dp, alpha(3) = 0.0_dp                 !< angular velocity, acceleration
  end type spatial_rigid_t

  type :: spatial_beam_t
    real(dp) :: length = 0.0_dp
    type(spatial_section_t) :: sec
    type(ramberg_osgood_t) :: material
    real(dp) :: shear_modulus = 0.0_dp
    type(element_effects_t) :: effects
    real(dp) :: beta = 0.0_dp                 !< stiffness-proportional damping on p_dot
    real(dp) :: mcon(2) = 0.0_dp              !< concentrated masses at the nodes (paper E's m_con1, m_con2)
    logical :: local_rotation(2) = .false.    !< node's rotation triple in local, not global, components
    integer :: n_gauss = 8                    !< stations of the nonlinear strain integrals
    real(dp) :: eps_star = huge(1.0_dp)
    real(dp) :: mass0(16, 16) = 0.0_dp        !< M_p (constant)
    real(dp) :: k_lin(16, 16) = 0.0_dp        !< linear stiffness
    real(dp) :: rot_load(16, 3) = 0.0_dp      !< int G_phi^T J dx
    real(dp) :: xi(n_in + 2) = 0.0_dp, wi(n_in + 2) = 0.0_dp   !< inertia stations (last two: the nodes)
    real(dp) :: si(16, 3, n_in + 2) = 0.0_dp  !< displacement rows (u, v, w) at the inertia stations
    real(dp), allocatable :: xg(:), wg(:)
    real(dp), allocatable :: gz(:, :, :)      !< (16, 6, n_gauss): d z / d p, z = (u_x v_x w_x v_xx w_xx theta_x)
  end type spatial_beam_t

  type :: spatial_eval_info_t
    real(dp) :: strain_energy = 0.0_dp
    real(dp) :: max_abs_strain = 0.0_dp
    logical :: beyond_peak = .false.
    integer :: n_nonlinear_points = 0
  end type spatial_eval_info_t

  !> Section state at one station: strains and resultants.
  type :: spatial_stress_t
    real(dp) :: max_abs_stress = 0.0_dp     !< over the stations and the section
    real(dp) :: x_over_l = 0.0_dp           !< where
    real(dp) :: axial_force(2) = 0.0_dp     !< N at x = 0, l
    real(dp) :: moment_y(2) = 0.0_dp, moment_z(2) = 0.0_dp, torque(2) = 0.0_dp
    logical :: beyond_peak = .false.
  end type spatial_stress_t

contains

  !> Build an element: length, section, material, shear modulus and switches.
  pure subroutine spatial_beam_init(el, length, sec, material, shear_modulus, effects, err, &
                                    n_gauss, damping_beta, masses, local_rotation)
    type(spatial_beam_t), intent(out) :: el
    real(dp), intent(in) :: length, shear_modulus
    type(spatial_section_t), intent(in) :: sec
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta, masses(2)
    logical, intent(in), optional :: local_rotation(2)   !< unshared link-end rotations (doc/spatial.md)
    real(dp) :: x(n_in), w(n_in), s(16, 3), gp(16, 3), jr(3), z(16, 6)
    integer :: i, k

    if (.not. (length > 0.0_dp)) then
      call err%set('spatial_beam_init', 'element length must be positive, got '//str(length)); return
    end if
    if (.not. (shear_modulus > 0.0_dp)) then
      call err%set('spatial_beam_init', 'shear modulus must be positive, got '//str(shear_modulus)); return
    end if
    if (.not. (sec%area > 0.0_dp)) then
      call err%set('spatial_beam_init', 'section not initialised'); return
    end if
    call validate_material(material, err)
    if (err%failed()) then
      call err%add_context('spatial_beam_init'); return
    end if
    el%length = length
    el%sec = sec
    el%material = material
    el%shear_modulus = shear_modulus
    el%effects = effects
    if (present(n_gauss)) el%n_gauss = n_gauss
    if (el%n_gauss < 2 .or. el%n_gauss > max_gauss_points) then
      call err%set('spatial_beam_init', 'n_gauss must be in 2..'//str(max_gauss_points)); return
    end if
    if (present(damping_beta)) el%beta = damping_beta
    if (present(masses)) el%mcon = masses
    if (present(local_rotation)) el%local_rotation = local_rotation
    if (.not. (el%beta >= 0.0_dp .and. all(el%mcon >= 0.0_dp))) then
      call err%set('spatial_beam_init', 'damping and concentrated masses must be >= 0'); return
    end if
    el%eps_star = peak_strain(material)

    ! inertia: translational stations, rotation rows, constant mass matrix
    jr = material%rho*[sec%ip, sec%iy, sec%iz]
    if (.not. effects%rotary_inertia) jr(2:3) = 0.0_dp      ! torsional inertia stays: it is the twist's mass
    call gauss_legendre_interval(n_in, 0.0_dp, length, x, w)
    do i = 1, n_in
      call rows_at(x(i)/length, length, s, gp, z)
      el%xi(i) = x(i)
      el%wi(i) = material%rho*sec%area*w(i)
      el%si(:, :, i) = s
      do k = 1, 3
        el%mass0 = el%mass0 + el%wi(i)*outer(s(:, k), s(:, k)) + w(i)*jr(k)*outer(gp(:, k), gp(:, k))
        el%rot_load(:, k) = el%rot_load(:, k) + w(i)*jr(k)*gp(:, k)
      end do
      el%k_lin = el%k_lin + w(i)*(material%e1*sec%area*outer(z(:, 1), z(:, 1)) &
                                  + material%e1*sec%iz*outer(z(:, 4), z(:, 4)) &
                                  + material%e1*sec%iy*outer(z(:, 5), z(:, 5)) &
                                  + shear_modulus*sec%torsion_j*outer(z(:, 6), z(:, 6)))
    end do
    do i = 1, 2                                    ! concentrated masses at the nodes
      call rows_at(real(i - 1, dp), length, s, gp, z)
      el%xi(n_in + i) = real(i - 1, dp)*length
      el%wi(n_in + i) = el%mcon(i)
      el%si(:, :, n_in + i) = s
      do k = 1, 3
        el%mass0 = el%mass0 + el%mcon(i)*outer(s(:, k), s(:, k))
      end do
    end do

    allocate(el%xg(el%n_gauss), el%wg(el%n_gauss), el%gz(16, 6, el%n_gauss))
    call gauss_legendre_interval(el%n_gauss, 0.0_dp, length, el%xg, el%wg)
    do i = 1, el%n_gauss
      call rows_at(el%xg(i)/length, length, s, gp, el%gz(:, :, i))
    end do
  end subroutine spatial_beam_init

  !> Rows at x = e l: s(:, k) gives displacement k (u, v, w), gp(:, k) the
  !> small rotation k (theta, -w_x, v_x), z(:, j) the station variables
  !> (u_x, v_x, w_x, v_xx, w_xx, theta_x), all as dot products with p.
  pure subroutine rows_at(e, l, s, gp, z)
    real(dp), intent(in) :: e, l
    real(dp), intent(out) :: s(16, 3), gp(16, 3), z(16, 6)
    real(dp) :: n(2), nx(2), h(6), hx(6), hxx(6)
    call linear_lagrange(e, l, n, nx)
    call quintic_hermite(e, l, h, hx, hxx)
    s = 0.0_dp
    gp = 0.0_dp
    z = 0.0_dp
    s([iu, 8 + iu], 1) = n
    s(:, 2) = spread_v(h)
    s(:, 3) = spread_w(h)
    gp([itx, 8 + itx], 1) = n
    gp(:, 2) = -spread_w(hx)
    gp(:, 3) = spread_v(hx)
    z([iu, 8 + iu], 1) = nx
    z(:, 2) = spread_v(hx)
    z(:, 3) = spread_w(hx)
    z(:, 4) = spread_v(hxx)
    z(:, 5) = spread_w(hxx)
    z([itx, 8 + itx], 6) = nx
  end subroutine rows_at

  !> v's quintic functions: value, slope (= tz), curvature DOFs.
  pure function spread_v(h) result(r)
    real(dp), intent(in) :: h(6)
    real(dp) :: r(16)
    r = 0.0_dp
    r([iv, itz, ivxx, 8 + iv, 8 + itz, 8 + ivxx]) = h
  end function spread_v

  !> w's quintic functions: w_x = -ty.
  pure function spread_w(h) result(r)
    real(dp), intent(in) :: h(6)
    real(dp) :: r(16)
    r = 0.0_dp
    r([iw, ity, iwxx, 8 + iw, 8 + ity, 8 + iwxx]) = [h(1), -h(2), h(3), h(4), -h(5), h(6)]
  end function spread_w

  ! ------------------------------------------------------------ main routine

  !> Mass matrix and force vector of the element in global DOFs q.  The
  !> mass depends on the rigid state only (a model that reuses it at the
  !> same time passes mass_wanted = .false.: mass is then not touched).
  pure subroutine spatial_beam_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(16), qd(16)
    type(spatial_rigid_t), intent(in) :: rb
    real(dp), intent(inout) :: mass(16, 16)
    real(dp), intent(out) :: force(16)
    type(spatial_eval_info_t), intent(out) :: info
    real(dp), intent(out), optional :: tangent(16, 16)
    logical, intent(in), optional :: mass_wanted
    real(dp) :: p(16), v(16), pd(16), wl(3), al(3), a0(3), wp(16), fp(16), fint(16), fdamp(16)
    real(dp) :: kp(16, 16), rel(3), acc(3), vel(3), wpi(3), xe(3)
    integer :: i

    p = spatial_to_local(rb%rot, q, el%local_rotation)
    v = spatial_to_local(rb%rot, qd, el%local_rotation)
    wl = matmul(rb%omega, rb%rot)          ! R^T omega
    al = matmul(rb%alpha, rb%rot)
    a0 = matmul(rb%x1_dd, rb%rot)
    wp = skew_apply(wl, p, el%local_rotation)
    pd = v - wp

    ! translational inertia at the stations (and the concentrated masses)
    fp = 0.0_dp
    do i = 1, n_in + 2
      if (.not. (el%wi(i) > 0.0_dp)) cycle
      xe = [el%xi(i), 0.0_dp, 0.0_dp]
      rel = station_rows(el%si(:, :, i), p)
      wpi = station_rows(el%si(:, :, i), wp)
      acc = a0 + cross(al, xe) + cross(wl, cross(wl, xe + rel)) - 2.0_dp*cross(wl, wpi)
      if (el%effects%coupling) then
        vel = station_rows(el%si(:, :, i), v)
        acc = acc + cross(al, rel) + 2.0_dp*cross(wl, vel)
      end if
      call station_scatter(el%si(:, :, i), -el%wi(i)*acc, fp)
    end do
    ! section rotary and torsional inertia: -int G_phi^T J alpha
    fp = fp - matmul(el%rot_load, al)
    ! transformation terms of p_dd = T^T q_dd - 2 W v + (W^2 - Wdot) p
    fp = fp - matmul(el%mass0, skew_apply(wl, wp, el%local_rotation))
    if (el%effects%coupling) fp = fp + matmul(el%mass0, 2.0_dp*skew_apply(wl, v, el%local_rotation) &
                                                        + skew_apply(al, p, el%local_rotation))

    ! strain energy, internal force, damping on the local strain rates
    call strain_terms(el, p, pd, present(tangent), el%beta > 0.0_dp, info, fint, fdamp, kp)
    fp = fp - fint
    if (el%beta > 0.0_dp) fp = fp - el%beta*fdamp

    if (.not. present(mass_wanted)) then
      mass = matrix_to_global(rb%rot, el%mass0, el%local_rotation)
    else if (mass_wanted) then
      mass = matrix_to_global(rb%rot, el%mass0, el%local_rotation)
    end if
    force = spatial_to_global(rb%rot, fp, el%local_rotation)
    if (present(tangent)) tangent = matrix_to_global(rb%rot, kp, el%local_rotation)
  end subroutine spatial_beam_eval

  !> Internal force dSE/dp in LOCAL DOFs.
  pure subroutine spatial_internal_force(el, p, f)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(16)
    real(dp), intent(out) :: f(16)
    real(dp) :: fdamp(16), kp(16, 16)
    type(spatial_eval_info_t) :: info
    call strain_terms(el, p, p, .false., .false., info, f, fdamp, kp)
  end subroutine spatial_internal_force

  !> Tangent d^2 SE / dp^2 in LOCAL DOFs.
  pure subroutine spatial_tangent_stiffness(el, p, k)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(16)
    real(dp), intent(out) :: k(16, 16)
    real(dp) :: f(16), fdamp(16)
    type(spatial_eval_info_t) :: info
    call strain_terms(el, p, p, .true., .false., info, f, fdamp, k)
  end subroutine spatial_tangent_stiffness

  !> Strain energy in LOCAL DOFs.
  pure real(dp) function spatial_strain_energy(el, p) result(se)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(16)
    real(dp) :: f(16), fdamp(16), kp(16, 16)
    type(spatial_eval_info_t) :: info
    call strain_terms(el, p, p, .false., .false., info, f, fdamp, kp)
    se = info%strain_energy
  end function spatial_strain_energy

  !> Kinetic energy from the absolute velocities of the section points
  !> (8-point rule, exact), independent of the precomputed matrices.
  pure real(dp) function spatial_kinetic_energy(el, q, qd, rb) result(ke)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(16), qd(16)
    type(spatial_rigid_t), intent(in) :: rb
    integer, parameter :: nt = 8
    real(dp) :: p(16), pd(16), wl(3), x(nt), w(nt), s(16, 3), gp(16, 3), z(16, 6), vel(3), om(3), jr(3)
    integer :: i
    p = spatial_to_local(rb%rot, q, el%local_rotation)
    wl = matmul(rb%omega, rb%rot)
    pd = spatial_to_local(rb%rot, qd, el%local_rotation) - skew_apply(wl, p, el%local_rotation)
    jr = el%material%rho*[el%sec%ip, el%sec%iy, el%sec%iz]
    if (.not. el%effects%rotary_inertia) jr(2:3) = 0.0_dp
    ke = 0.0_dp
    call gauss_legendre_interval(nt, 0.0_dp, el%length, x, w)
    do i = 1, nt
      call rows_at(x(i)/el%length, el%length, s, gp, z)
      vel = matmul(rb%x1_d, rb%rot) + matmul(pd, s) + cross(wl, [x(i), 0.0_dp, 0.0_dp] + matmul(p, s))
      om = wl + matmul(pd, gp)
      ke = ke + 0.5_dp*w(i)*(el%material%rho*el%sec%area*dot_product(vel, vel) + sum(jr*om*om))
    end do
    do i = 1, 2
      call rows_at(real(i - 1, dp), el%length, s, gp, z)
      vel = matmul(rb%x1_d, rb%rot) + matmul(pd, s) &
            + cross(wl, [real(i - 1, dp)*el%length, 0.0_dp, 0.0_dp] + matmul(p, s))
      ke = ke + 0.5_dp*el%mcon(i)*dot_product(vel, vel)
    end do
  end function spatial_kinetic_energy

  ! ------------------------------------------------------------ strains

  !> Strain energy, internal force, tangent (want_k) and tangent times prel
  !> (want_damp), by Gauss quadrature along the element; LOCAL DOFs.
  pure subroutine strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(16), prel(16)
    logical, intent(in) :: want_k, want_damp
    type(spatial_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(16), fdamp(16), kp(16, 16)
    real(dp) :: z(6), fz(6), hz(6, 6), en, gh(16, 6), emax, yf, zf, s(3)
    integer :: i
    fint = 0.0_dp
    fdamp = 0.0_dp
    kp = 0.0_dp
    info%strain_energy = 0.0_dp
    info%max_abs_strain = 0.0_dp
    if (.not. (el%effects%stretching .or. el%effects%curvature .or. el%effects%material)) then
      fint = matmul(el%k_lin, p)
      info%strain_energy = 0.5_dp*dot_product(p, fint)
      if (want_k) kp = el%k_lin
      if (want_damp) fdamp = matmul(el%k_lin, prel)
      ! material off here: no Ramberg-Osgood peak to watch, max_abs_strain is not computed
      return
    end if
    do i = 1, el%n_gauss
      z = matmul(p, el%gz(:, :, i))
      call station_energy(el, z, want_k .or. want_damp, en, fz, hz, s)
      info%strain_energy = info%strain_energy + el%wg(i)*en
      fint = fint + el%wg(i)*matmul(el%gz(:, :, i), fz)
      if (want_k .or. want_damp) then
        gh = el%wg(i)*matmul(el%gz(:, :, i), hz)
        if (want_k) kp = kp + matmul(gh, transpose(el%gz(:, :, i)))
        if (want_damp) fdamp = fdamp + matmul(gh, matmul(prel, el%gz(:, :, i)))
      end if
      call section_extreme_fibre_strain(el%sec, s, emax, yf, zf)
      info%max_abs_strain = max(info%max_abs_strain, emax)
    end do
    info%n_nonlinear_points = el%n_gauss
    info%beyond_peak = el%effects%material .and. info%max_abs_strain > el%eps_star
  end subroutine strain_terms

  !> Energy per unit length at a station, its gradient and (if want_h) its
  !> Hessian with respect to z = (u_x, v_x, w_x, v_xx, w_xx, theta_x);
  !> s = (eps, kappa_y, kappa_z) on return.
  pure subroutine station_energy(el, z, want_h, en, fz, hz, s)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: z(6)
    logical, intent(in) :: want_h
    real(dp), intent(out) :: en, fz(6), hz(6, 6), s(3)
    real(dp) :: js(3, 6), hs(6, 6, 3), g(3), h(3, 3), gj
    integer :: k
    call strain_measures(el%effects, z, want_h, s, js, hs)
    call spatial_section_resultants(el%sec, el%material, s, el%effects%material, en, g, h)
    gj = el%shear_modulus*el%sec%torsion_j
    en = en + 0.5_dp*gj*z(6)**2
    fz = matmul(g, js)
    fz(6) = fz(6) + gj*z(6)
    hz = 0.0_dp
    if (want_h) then
      hz = matmul(transpose(js), matmul(h, js))
      do k = 1, 3
        hz = hz + g(k)*hs(:, :, k)
      end do
      hz(6, 6) = hz(6, 6) + gj
    end if
  end subroutine station_energy

  !> s = (eps, kappa_y, kappa_z) from z, Jacobian js = ds/dz and Hessians
  !> hs(:, :, k) = d^2 s_k / dz^2.  With r' = (1 + u_x, v_x, w_x) and
  !> r'' = (0, v_xx, w_xx) (u_xx = 0 for linear u): eps = |r'| - 1,
  !> kappa = r' x r'' / |r'|^3, of which the y, z components are the bending
  !> curvatures: kappa_z = a v_xx / r^3, kappa_y = -a w_xx / r^3.
  pure subroutine strain_measures(fx, z, want_h, s, js, hs)
    type(element_effects_t), intent(in) :: fx
    real(dp), intent(in) :: z(6)
    logical, intent(in) :: want_h
    real(dp), intent(out) :: s(3), js(3, 6), hs(6, 6, 3)
    real(dp) :: gv(3), r, r2, r3, r5, r7, a, xk, sg
    integer :: i, j, k, ix
    a = 1.0_dp + z(1)
    gv = [a, z(2), z(3)]
    r2 = dot_product(gv, gv)
    r = sqrt(r2)
    js = 0.0_dp
    hs = 0.0_dp
    if (fx%stretching) then
      s(1) = (z(1)*(2.0_dp + z(1)) + z(2)**2 + z(3)**2)/(r + 1.0_dp)   ! r - 1 without cancellation
      js(1, 1:3) = gv/r
      if (want_h) then
        do j = 1, 3
          do i = 1, 3
            hs(i, j, 1) = (merge(1.0_dp, 0.0_dp, i == j) - gv(i)*gv(j)/r2)/r
          end do
        end do
      end if
    else
      s(1) = z(1)
      js(1, 1) = 1.0_dp
    end if
    if (.not. fx%curvature) then
      s(2) = -z(5)
      s(3) = z(4)
      js(2, 5) = -1.0_dp
      js(3, 4) = 1.0_dp
      return
    end if
    r3 = r2*r
    r5 = r3*r2
    r7 = r5*r2
    do k = 2, 3
      ix = merge(5, 4, k == 2)          ! kappa_y uses w_xx, kappa_z uses v_xx
      sg = merge(-1.0_dp, 1.0_dp, k == 2)
      xk = z(ix)
      s(k) = sg*a*xk/r3
      do i = 1, 3
        js(k, i) = sg*xk*(merge(1.0_dp, 0.0_dp, i == 1)/r3 - 3.0_dp*a*gv(i)/r5)
      end do
      js(k, ix) = sg*a/r3
      if (want_h) then
        do j = 1, 3
          do i = 1, 3
            hs(i, j, k) = sg*xk*(-3.0_dp*(merge(gv(j), 0.0_dp, i == 1) + merge(gv(i), 0.0_dp, j == 1))/r5 &
                                 + a*(-3.0_dp*merge(1.0_dp, 0.0_dp, i == j)/r5 + 15.0_dp*gv(i)*gv(j)/r7))
          end do
          hs(j, ix, k) = sg*(merge(1.0_dp, 0.0_dp, j == 1)/r3 - 3.0_dp*a*gv(j)/r5)
          hs(ix, j, k) = hs(j, ix, k)
        end do
      end if
    end do
  end subroutine strain_measures

  ! ------------------------------------------------------------ recovery

  !> Strains s = (eps, kappa_y, kappa_z) and twist rate at x = e l, LOCAL p.
  pure subroutine spatial_section_state(el, p, e, s, twist)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(16), e
    real(dp), intent(out) :: s(3), twist
    real(dp) :: sr(16, 3), gp(16, 3), zr(16, 6), z(6), js(3, 6), hs(6, 6, 3)
    call rows_at(e, el%length, sr, gp, zr)
    z = matmul(p, zr)
    call strain_measures(el%effects, z, .false., s, js, hs)
    twist = z(6)
  end subroutine spatial_section_state

  !> Maximum |sigma| over the ends and the Gauss stations (extreme fibres),
  !> and the end resultants N, M_y, M_z, T; global q.
  pure function spatial_stress_recovery(el, q, rot) result(rep)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(16), rot(3, 3)
    type(spatial_stress_t) :: rep
    real(dp) :: p(16), s(3), tw, e, emax, yf, zf, sig, en, g(3), h(3, 3), ef
    type(ramberg_osgood_t) :: law
    integer :: i, k
    law = el%material
    if (.not. el%effects%material) law%e2 = 0.0_dp
    p = spatial_to_local(rot, q, el%local_rotation)
    rep%max_abs_stress = -1.0_dp
    do i = 0, el%n_gauss + 1
      if (i == 0 .or. i == el%n_gauss + 1) then
        e = merge(0.0_dp, 1.0_dp, i == 0)
      else
        e = el%xg(i)/el%length
      end if
      call spatial_section_state(el, p, e, s, tw)
      call section_extreme_fibre_strain(el%sec, s, emax, yf, zf)
      ef = s(1) - yf*s(3) + zf*s(2)
      sig = ro_stress(law, ef)
      if (abs(sig) > rep%max_abs_stress) then
        rep%max_abs_stress = abs(sig)
        rep%x_over_l = e
      end if
      rep%beyond_peak = rep%beyond_peak .or. (el%effects%material .and. emax > el%eps_star)
      if (i == 0 .or. i == el%n_gauss + 1) then
        k = merge(1, 2, i == 0)
        call spatial_section_resultants(el%sec, el%material, s, el%effects%material, en, g, h)
        rep%axial_force(k) = g(1)
        rep%moment_y(k) = g(2)
        rep%moment_z(k) = g(3)
        rep%torque(k) = el%shear_modulus*el%sec%torsion_j*tw
      end if
    end do
  end function spatial_stress_recovery

  !> Local elastic displacement (u, v, w) at x = e l from LOCAL p.
  pure function spatial_local_displacement(el, p, e) result(d)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(16), e
    real(dp) :: d(3)
    real(dp) :: s(16, 3), gp(16, 3), z(16, 6)
    call rows_at(e, el%length, s, gp, z)
    d = matmul(p, s)
  end function spatial_local_displacement

  !> (u, v, w) = s^T p at a station, over the DOFs each component touches
  !> (s is zero elsewhere: a third of the dense product's work).
  pure function station_rows(s, p) result(d)
    real(dp), intent(in) :: s(16, 3), p(16)
    real(dp) :: d(3)
    d(1) = dot_product(s(u_set, 1), p(u_set))
    d(2) = dot_product(s(v_set, 2), p(v_set))
    d(3) = dot_product(s(w_set, 3), p(w_set))
  end function station_rows

  !> f := f + s a at a station (the transpose of station_rows).
  pure subroutine station_scatter(s, a, f)
    real(dp), intent(in) :: s(16, 3), a(3)
    real(dp), intent(inout) :: f(16)
    f(u_set) = f(u_set) + s(u_set, 1)*a(1)
    f(v_set) = f(v_set) + s(v_set, 2)*a(2)
    f(w_set) = f(w_set) + s(w_set, 3)*a(3)
  end subroutine station_scatter

  ! ------------------------------------------------------------ frames

  !> p = T^T q: the vector triples of each node into the element frame
  !> (a rotation triple flagged local is already in it).
  pure function spatial_to_local(rot, q, local) result(p)
    real(dp), intent(in) :: rot(3, 3), q(16)
    logical, intent(in), optional :: local(2)
    real(dp) :: p(16)
    logical :: loc(2)
    loc = .false.
    if (present(local)) loc = local
    p = q
    p(1:3) = matmul(q(1:3), rot)
    if (.not. loc(1)) p(4:6) = matmul(q(4:6), rot)
    p(9:11) = matmul(q(9:11), rot)
    if (.not. loc(2)) p(12:14) = matmul(q(12:14), rot)
  end function spatial_to_local

  !> q = T p.
  pure function spatial_to_global(rot, p, local) result(q)
    real(dp), intent(in) :: rot(3, 3), p(16)
    logical, intent(in), optional :: local(2)
    real(dp) :: q(16)
    logical :: loc(2)
    loc = .false.
    if (present(local)) loc = local
    q = p
    q(1:3) = matmul(rot, p(1:3))
    if (.not. loc(1)) q(4:6) = matmul(rot, p(4:6))
    q(9:11) = matmul(rot, p(9:11))
    if (.not. loc(2)) q(12:14) = matmul(rot, p(12:14))
  end function spatial_to_global

  !> T A T^T, by the 3 x 3 blocks of the vector triples that rotate.
  pure function matrix_to_global(rot, a, local) result(g)
    real(dp), intent(in) :: rot(3, 3), a(16, 16)
    logical, intent(in) :: local(2)
    real(dp) :: g(16, 16), t(16, 16), rt(3, 3)
    integer, parameter :: first(4) = [1, 4, 9, 12]
    logical :: rotates(4)
    integer :: b, r
    rotates = [.true., .not. local(1), .true., .not. local(2)]
    rt = transpose(rot)
    t = a
    do b = 1, 4
      r = first(b)
      if (rotates(b)) t(r:r + 2, :) = matmul(rot, a(r:r + 2, :))       ! T A
    end do
    g = t
    do b = 1, 4
      r = first(b)
      if (rotates(b)) g(:, r:r + 2) = matmul(t(:, r:r + 2), rt)        ! (T A) T^T
    end do
  end function matrix_to_global

  !> W p: omega x each vector triple of p that rotates with the frame
  !> (T_dot = T W); curvature DOFs and local rotation triples map to zero.
  pure function skew_apply(w, p, local) result(r)
    real(dp), intent(in) :: w(3), p(16)
    logical, intent(in) :: local(2)
    real(dp) :: r(16)
    r = 0.0_dp
    r(1:3) = cross(w, p(1:3))
    if (.not. local(1)) r(4:6) = cross(w, p(4:6))
    r(9:11) = cross(w, p(9:11))
    if (.not. local(2)) r(12:14) = cross(w, p(12:14))
  end function skew_apply

  pure function cross(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross

  pure function outer(x, y) result(m)
    real(dp), intent(in) :: x(:), y(:)
    real(dp) :: m(size(x), size(y))
    integer :: j
    do j = 1, size(y)
      m(:, j) = x*y(j)
    end do
  end function outer
end module spatial_beam
