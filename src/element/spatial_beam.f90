!> Spatial beam element for flexible mechanisms (paper E; doc/spatial.md;
!> built in the spirit of Kear's planar element; every choice the
!> OCR leaves open is in doc/spatial.md).  Floating frame: the element's
!> reference line moves with its link's rigid-body motion (rotation R(t),
!> columns = local axes in global components), elastic displacements are
!> measured in that frame.
!>
!> Local DOFs per node (10):  u v w  (translations)  tx ty tz  (small rotation
!> vector: tx = twist theta, ty = -w_x, tz = v_x)  vxx wxx (curvature DOFs of
!> the quintic Hermite functions)  ux uxx (slope and curvature of u).
!> Element: p = [node 1, node 2] (20).  Global element DOFs q: the two vector
!> triples of each node in global components, q = T p with
!> T = diag(R, R, 1, 1, 1, 1) per node; curvature and u-slope DOFs stay
!> local (as Kear's th and m do).
!>
!> Interpolation: theta linear; v, w quintic Hermite (C2, as Kear's w); u
!> quintic Hermite on (u, ux, uxx) in the consistent formulation (default:
!> no membrane locking, as the planar consistent element), linear in Kear's
!> (ux, uxx unused; the model holds them).  Strains: eps = |r'| - 1 (exact
!> stretch), curvature vector r' x r''/|r'|^3 of the centroid line, twist
!> rate theta_x (St. Venant, warping neglected); each nonlinearity has a
!> switch (element_effects_t of the planar element).  In the x-y plane with
!> w = theta = 0, Kear's formulation is every term of the planar Kear
!> 'exact' element (doc/spatial.md, "Planar limit").
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
  use element_effects, only: element_effects_t
  use spatial_section, only: spatial_section_t, spatial_section_resultants, section_extreme_fibre_strain
  use linalg, only: outer, cross
  implicit none
  private
  public :: spatial_rigid_t, spatial_beam_t, spatial_eval_info_t, spatial_stress_t
  public :: spatial_formulation_kear, spatial_formulation_consistent
  public :: spatial_beam_init, spatial_beam_eval, spatial_beam_matrices, spatial_tangent_is_constant
  public :: spatial_internal_force, spatial_tangent_stiffness
  public :: spatial_strain_energy, spatial_kinetic_energy, spatial_to_local, spatial_to_global
  public :: spatial_stress_recovery, spatial_local_displacement

  integer, parameter :: sb_ndof = 20
  integer, parameter :: nd = sb_ndof, no = 10   !< element DOFs, node 2's offset
  !> interpolation of u: Kear's linear u (locks in large deflection with the
  !> exact stretch; DOFs u_x, u_xx unused, held by the model), or the consistent
  !> element's quintic u with nodal u_x, u_xx (as the planar consistent element)
  integer, parameter :: spatial_formulation_kear = 1, spatial_formulation_consistent = 2
  integer, parameter :: nz = 7               !< station variables z = (u_x v_x w_x v_xx w_xx theta_x u_xx)
  integer, parameter :: n_in = 6            !< inertia stations: S^T S has degree 10, exact
  !> rotation components carried by each node's second triple
  integer, parameter :: iu = 1, iv = 2, iw = 3, itx = 4, ity = 5, itz = 6, ivxx = 7, iwxx = 8, iux = 9, iuxx = 10
  !> the DOFs each displacement component's functions touch (u linear; v, w quintic)
  integer, parameter :: u_set(6) = [1, 11, 9, 10, 19, 20], v_set(6) = [2, 6, 7, 12, 16, 17], &
                        w_set(6) = [3, 5, 8, 13, 15, 18]
  !> the four disjoint DOF sets (u, v, w and the twist) on which M_p and the
  !> linear K are block diagonal: a displacement's functions couple only with
  !> its own (rotary inertia: -w_x on w's, v_x on v's), the twist with itself
  integer, parameter :: triple_first(4) = [1, 4, 11, 14]   !< first DOF of each vector triple
  integer, parameter :: sets(6, 3) = reshape([u_set, v_set, w_set], [6, 3]), t_set(2) = [itx, no + itx]
  !> (u's nodal values first: Kear's linear u touches only them, nact(1) = 2)

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
    integer :: formulation = spatial_formulation_consistent
    logical :: quintic_u = .true.             !< consistent formulation: u quintic with nodal u_x, u_xx DOFs
    real(dp) :: eps_star = huge(1.0_dp)
    real(dp) :: mass0(nd, nd) = 0.0_dp        !< M_p (constant)
    real(dp) :: k_lin(nd, nd) = 0.0_dp        !< linear stiffness
    real(dp) :: rot_load(nd, 3) = 0.0_dp      !< int G_phi^T J dx
    ! state-independent sums over the inertia stations (and the concentrated masses), per DOF set:
    ! s_a = the rows of displacement a (u, v, w) on sets(:, a), weight w_i = rho A dx (or m_con)
    real(dp) :: nab(6, 6, 3, 3) = 0.0_dp      !< N_ab = sum_i w_i s_a s_b^T
    real(dp) :: q0(6, 3) = 0.0_dp, q1(6, 3) = 0.0_dp   !< sum_i w_i s_a, sum_i w_i x_i s_a
    real(dp) :: mblk(6, 6, 3) = 0.0_dp, mt(2, 2) = 0.0_dp   !< M_p on sets(:, a) and on t_set
    real(dp) :: kblk(6, 6, 3) = 0.0_dp, kt(2, 2) = 0.0_dp   !< linear K likewise
    integer :: nact(3) = 6                    !< leading entries of each set the interpolation uses
    real(dp), allocatable :: xg(:), wg(:)
    real(dp), allocatable :: gz(:, :, :)      !< (nd, nz, n_gauss): d z / d p, z = (u_x v_x w_x v_xx w_xx theta_x u_xx)
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
                                    n_gauss, damping_beta, masses, local_rotation, formulation)
    type(spatial_beam_t), intent(out) :: el
    real(dp), intent(in) :: length, shear_modulus
    type(spatial_section_t), intent(in) :: sec
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta, masses(2)
    logical, intent(in), optional :: local_rotation(2)   !< unshared link-end rotations (doc/spatial.md)
    integer, intent(in), optional :: formulation         !< spatial_formulation_* (default: consistent)
    real(dp) :: x(n_in), w(n_in), s(nd, 3), gp(nd, 3), jr(3), z(nd, nz)
    integer :: i, k
    logical :: ok

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
    el = spatial_beam_t(length=length, sec=sec, material=material, shear_modulus=shear_modulus, effects=effects)
    if (present(n_gauss)) el%n_gauss = n_gauss
    if (el%n_gauss < 2 .or. el%n_gauss > max_gauss_points) then
      call err%set('spatial_beam_init', 'n_gauss must be in 2..'//str(max_gauss_points)); return
    end if
    if (present(damping_beta)) el%beta = damping_beta
    if (present(masses)) el%mcon = masses
    if (present(local_rotation)) el%local_rotation = local_rotation
    if (present(formulation)) el%formulation = formulation
    if (el%formulation /= spatial_formulation_kear .and. el%formulation /= spatial_formulation_consistent) then
      call err%set('spatial_beam_init', 'unknown formulation '//str(el%formulation)); return
    end if
    el%quintic_u = el%formulation == spatial_formulation_consistent
    el%nact = [merge(6, 2, el%quintic_u), 6, 6]
    if (.not. (el%beta >= 0.0_dp .and. all(el%mcon >= 0.0_dp))) then
      call err%set('spatial_beam_init', 'damping and concentrated masses must be >= 0'); return
    end if
    el%eps_star = peak_strain(material)

    ! inertia: translational stations, rotation rows, constant mass matrix
    jr = material%rho*[sec%ip, sec%iy, sec%iz]
    if (.not. effects%rotary_inertia) jr(2:3) = 0.0_dp      ! torsional inertia stays: it is the twist's mass
    call gauss_legendre_interval(n_in, 0.0_dp, length, x, w)
    do i = 1, n_in
      call rows_at(x(i)/length, length, el%quintic_u, s, gp, z)
      call add_station(el, x(i), material%rho*sec%area*w(i), s)
      do k = 1, 3
        el%mass0 = el%mass0 + material%rho*sec%area*w(i)*outer(s(:, k), s(:, k)) + w(i)*jr(k)*outer(gp(:, k), gp(:, k))
        el%rot_load(:, k) = el%rot_load(:, k) + w(i)*jr(k)*gp(:, k)
      end do
      el%k_lin = el%k_lin + w(i)*(material%e1*sec%area*outer(z(:, 1), z(:, 1)) &
                                  + material%e1*sec%iz*outer(z(:, 4), z(:, 4)) &
                                  + material%e1*sec%iy*outer(z(:, 5), z(:, 5)) &
                                  + shear_modulus*sec%torsion_j*outer(z(:, 6), z(:, 6)))
    end do
    do i = 1, 2                                    ! concentrated masses at the nodes
      call rows_at(real(i - 1, dp), length, el%quintic_u, s, gp, z)
      call add_station(el, real(i - 1, dp)*length, el%mcon(i), s)
      do k = 1, 3
        el%mass0 = el%mass0 + el%mcon(i)*outer(s(:, k), s(:, k))
      end do
    end do

    call split_blocks(el%mass0, el%nact, el%mblk, el%mt, ok)
    if (ok) call split_blocks(el%k_lin, el%nact, el%kblk, el%kt, ok)
    if (ok) ok = all(abs(el%nab(:, 3:6, :, 1)) <= 0.0_dp) .or. el%nact(1) == 6
    if (ok) ok = rot_load_on_sets(el%rot_load)
    if (.not. ok) then                   ! cannot happen with rows_at: the sets are its structure
      call err%set('spatial_beam_init', 'mass, stiffness or rotary load outside the DOF sets'); return
    end if

    allocate(el%xg(el%n_gauss), el%wg(el%n_gauss), el%gz(nd, nz, el%n_gauss))
    call gauss_legendre_interval(el%n_gauss, 0.0_dp, length, el%xg, el%wg)
    do i = 1, el%n_gauss
      call rows_at(el%xg(i)/length, length, el%quintic_u, s, gp, el%gz(:, :, i))
    end do
  end subroutine spatial_beam_init

  !> Add an inertia station (position x, weight wt, displacement rows s) to
  !> the state-independent sums N_ab, q0, q1.
  pure subroutine add_station(el, x, wt, s)
    type(spatial_beam_t), intent(inout) :: el
    real(dp), intent(in) :: x, wt, s(nd, 3)
    integer :: a, b
    do a = 1, 3
      el%q0(:, a) = el%q0(:, a) + wt*s(sets(:, a), a)
      el%q1(:, a) = el%q1(:, a) + wt*x*s(sets(:, a), a)
      do b = 1, 3
        el%nab(:, :, a, b) = el%nab(:, :, a, b) + wt*outer(s(sets(:, a), a), s(sets(:, b), b))
      end do
    end do
  end subroutine add_station

  !> The blocks of a on sets(:, a) and t_set; ok = .false. if a has an entry
  !> outside them or past the used entries nact (a is then not block diagonal
  !> on the sets).
  pure subroutine split_blocks(a, nact, blk, at, ok)
    real(dp), intent(in) :: a(nd, nd)
    integer, intent(in) :: nact(3)
    real(dp), intent(out) :: blk(6, 6, 3), at(2, 2)
    logical, intent(out) :: ok
    real(dp) :: rest(nd, nd)
    integer :: k
    rest = a
    do k = 1, 3
      blk(:, :, k) = a(sets(:, k), sets(:, k))
      rest(sets(1:nact(k), k), sets(1:nact(k), k)) = 0.0_dp
    end do
    at = a(t_set, t_set)
    rest(t_set, t_set) = 0.0_dp
    ok = all(abs(rest) <= 0.0_dp)
  end subroutine split_blocks

  !> rot_load's columns (twist, -w_x, v_x) live on t_set, w's and v's sets.
  pure logical function rot_load_on_sets(r) result(ok)
    real(dp), intent(in) :: r(nd, 3)
    real(dp) :: rest(nd, 3)
    rest = r
    rest(t_set, 1) = 0.0_dp
    rest(w_set, 2) = 0.0_dp
    rest(v_set, 3) = 0.0_dp
    ok = all(abs(rest) <= 0.0_dp)
  end function rot_load_on_sets

  !> y = A x for A block diagonal on the DOF sets (blocks from split_blocks;
  !> its columns past nact are zero).
  pure function block_apply(blk, at, nact, x) result(y)
    real(dp), intent(in) :: blk(6, 6, 3), at(2, 2), x(nd)
    integer, intent(in) :: nact(3)
    real(dp) :: y(nd), ys(6)
    integer :: k, j
    do k = 1, 3                          ! column loops of fixed length 6 (vectorized; the library
      ys = 0.0_dp                        ! matmul costs more at 6 x 6)
      do j = 1, nact(k)
        ys = ys + blk(:, j, k)*x(sets(j, k))
      end do
      y(sets(:, k)) = ys
    end do
    y(t_set) = at(:, 1)*x(t_set(1)) + at(:, 2)*x(t_set(2))
  end function block_apply

  !> y1 = A x1, y2 = A x2 in one pass over A's blocks (as block_apply twice).
  pure subroutine block_apply_pair(blk, at, nact, x1, x2, y1, y2)
    real(dp), intent(in) :: blk(6, 6, 3), at(2, 2), x1(nd), x2(nd)
    integer, intent(in) :: nact(3)
    real(dp), intent(out) :: y1(nd), y2(nd)
    real(dp) :: ys1(6), ys2(6)
    integer :: k, j
    do k = 1, 3
      ys1 = 0.0_dp
      ys2 = 0.0_dp
      do j = 1, nact(k)
        ys1 = ys1 + blk(:, j, k)*x1(sets(j, k))
        ys2 = ys2 + blk(:, j, k)*x2(sets(j, k))
      end do
      y1(sets(:, k)) = ys1
      y2(sets(:, k)) = ys2
    end do
    y1(t_set) = at(:, 1)*x1(t_set(1)) + at(:, 2)*x1(t_set(2))
    y2(t_set) = at(:, 1)*x2(t_set(1)) + at(:, 2)*x2(t_set(2))
  end subroutine block_apply_pair

  !> Rows at x = e l: s(:, k) gives displacement k (u, v, w), gp(:, k) the
  !> small rotation k (theta, -w_x, v_x), z(:, j) the station variables
  !> (u_x, v_x, w_x, v_xx, w_xx, theta_x, u_xx), all as dot products with p.
  !> u: quintic Hermite on (u, u_x, u_xx) of both nodes (quintic_u), else
  !> linear (Kear's) with the u_x, u_xx DOFs unused.
  pure subroutine rows_at(e, l, quintic_u, s, gp, z)
    real(dp), intent(in) :: e, l
    logical, intent(in) :: quintic_u
    real(dp), intent(out) :: s(nd, 3), gp(nd, 3), z(nd, nz)
    real(dp) :: n(2), nx(2), h(6), hx(6), hxx(6)
    integer, parameter :: uq(6) = [iu, iux, iuxx, no + iu, no + iux, no + iuxx]
    call linear_lagrange(e, l, n, nx)
    call quintic_hermite(e, l, h, hx, hxx)
    s = 0.0_dp
    gp = 0.0_dp
    z = 0.0_dp
    if (quintic_u) then
      s(uq, 1) = h
      z(uq, 1) = hx
      z(uq, 7) = hxx
    else
      s([iu, no + iu], 1) = n
      z([iu, no + iu], 1) = nx
    end if
    s(:, 2) = spread_v(h)
    s(:, 3) = spread_w(h)
    gp([itx, no + itx], 1) = n
    gp(:, 2) = -spread_w(hx)
    gp(:, 3) = spread_v(hx)
    z(:, 2) = spread_v(hx)
    z(:, 3) = spread_w(hx)
    z(:, 4) = spread_v(hxx)
    z(:, 5) = spread_w(hxx)
    z([itx, no + itx], 6) = nx
  end subroutine rows_at

  !> v's quintic functions: value, slope (= tz), curvature DOFs.
  pure function spread_v(h) result(r)
    real(dp), intent(in) :: h(6)
    real(dp) :: r(nd)
    r = 0.0_dp
    r([iv, itz, ivxx, no + iv, no + itz, no + ivxx]) = h
  end function spread_v

  !> w's quintic functions: w_x = -ty.
  pure function spread_w(h) result(r)
    real(dp), intent(in) :: h(6)
    real(dp) :: r(nd)
    r = 0.0_dp
    r([iw, ity, iwxx, no + iw, no + ity, no + iwxx]) = [h(1), -h(2), h(3), h(4), -h(5), h(6)]
  end function spread_w

  ! ------------------------------------------------------------ main routine

  !> Mass matrix and force vector of the element in global DOFs q.  The
  !> mass depends on the rigid state only (a model that reuses it at the
  !> same time passes mass_wanted = .false.: mass is then not touched).
  pure subroutine spatial_beam_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), qd(nd)
    type(spatial_rigid_t), intent(in) :: rb
    real(dp), intent(inout) :: mass(nd, nd)
    real(dp), intent(out) :: force(nd)
    type(spatial_eval_info_t), intent(out) :: info
    real(dp), intent(out), optional :: tangent(nd, nd)
    logical, intent(in), optional :: mass_wanted
    real(dp) :: p(nd), v(nd), pd(nd), wl(3), al(3), a0(3), wp(nd), fp(nd), fint(nd), fdamp(nd)
    real(dp) :: kp(nd, nd)

    p = spatial_to_local(rb%rot, q, el%local_rotation)
    v = spatial_to_local(rb%rot, qd, el%local_rotation)
    wl = matmul(rb%omega, rb%rot)          ! R^T omega
    al = matmul(rb%alpha, rb%rot)
    a0 = matmul(rb%x1_dd, rb%rot)
    wp = skew_apply(wl, p, el%local_rotation)
    pd = v - wp

    fp = translational_inertia(el, p, pd, wp, wl, al, a0)
    ! section rotary and torsional inertia: -int G_phi^T J alpha (columns on t_set, w's, v's sets)
    fp(t_set) = fp(t_set) - el%rot_load(t_set, 1)*al(1)
    fp(w_set) = fp(w_set) - el%rot_load(w_set, 2)*al(2)
    fp(v_set) = fp(v_set) - el%rot_load(v_set, 3)*al(3)
    ! transformation terms of p_dd = T^T q_dd - 2 W v + (W^2 - Wdot) p (one product with M_p)
    if (el%effects%coupling) then
      fp = fp + block_apply(el%mblk, el%mt, el%nact, 2.0_dp*skew_apply(wl, v, el%local_rotation) &
                            + skew_apply(al, p, el%local_rotation) - skew_apply(wl, wp, el%local_rotation))
    else
      fp = fp - block_apply(el%mblk, el%mt, el%nact, skew_apply(wl, wp, el%local_rotation))
    end if

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

  !> Mass and elastic tangent of the element in global DOFs q at the rigid
  !> state rb (those of spatial_beam_eval, without its force: the Newton matrix).
  pure subroutine spatial_beam_matrices(el, q, rb, mass, tangent)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(nd)
    type(spatial_rigid_t), intent(in) :: rb
    real(dp), intent(out) :: mass(nd, nd), tangent(nd, nd)
    real(dp) :: p(nd), fint(nd), fdamp(nd), kp(nd, nd)
    type(spatial_eval_info_t) :: info
    mass = matrix_to_global(rb%rot, el%mass0, el%local_rotation)
    if (linear_strain(el)) then
      tangent = matrix_to_global(rb%rot, el%k_lin, el%local_rotation)
    else
      p = spatial_to_local(rb%rot, q, el%local_rotation)
      call strain_terms(el, p, p, .true., .false., info, fint, fdamp, kp)
      tangent = matrix_to_global(rb%rot, kp, el%local_rotation)
    end if
  end subroutine spatial_beam_matrices

  !> The element's tangent is its linear stiffness (no nonlinear strain effect):
  !> independent of q.
  pure logical function spatial_tangent_is_constant(el)
    type(spatial_beam_t), intent(in) :: el
    spatial_tangent_is_constant = linear_strain(el)
  end function spatial_tangent_is_constant

  !> Loads of the translational inertia, LOCAL DOFs: -sum_i w_i S_i^T acc_i
  !> over the inertia stations (and the concentrated masses), with the
  !> station acceleration (r = S_i p, x_i e_x the station on the reference line)
  !>   acc = a0 + alpha x x_i e_x + omega x (omega x (x_i e_x + r)) - 2 omega x S_i W p
  !>         [+ alpha x r + 2 omega x S_i v: coupling]
  !>       = a0 + x_i c1 + L S_i p + Omega S_i h,   L = Omega^2 [+ skew(alpha)],
  !>         h = -2 W p [coupling: 2 (v - W p) = 2 p_dot]
  !> by the precomputed sums: sum_i w_i s_a (L_ab s_b^T y) = L_ab N_ab y.
  pure function translational_inertia(el, p, pd, wp, wl, al, a0) result(fp)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(nd), pd(nd), wp(nd), wl(3), al(3), a0(3)
    real(dp) :: fp(nd)
    real(dp), parameter :: ex(3) = [1.0_dp, 0.0_dp, 0.0_dp]
    real(dp) :: c1(3), lm(3, 3), om(3, 3), y(6), fa(6), ps(6, 3), hs(6, 3)
    integer :: a, b, k
    c1 = cross(al, ex) + cross(wl, cross(wl, ex))
    om = skew(wl)
    do b = 1, 3                            ! Omega^2 r = omega x (omega x r) = (w w^T - |w|^2 I) r
      lm(:, b) = wl*wl(b)
      lm(b, b) = lm(b, b) - dot_product(wl, wl)
    end do
    if (el%effects%coupling) lm = lm + skew(al)
    do b = 1, 3
      ps(:, b) = p(sets(:, b))
      if (el%effects%coupling) then
        hs(:, b) = 2.0_dp*pd(sets(:, b))
      else
        hs(:, b) = -2.0_dp*wp(sets(:, b))
      end if
    end do
    fp = 0.0_dp
    do a = 1, 3
      fa = -(el%q0(:, a)*a0(a) + el%q1(:, a)*c1(a))
      do b = 1, 3
        ! (a zero coefficient pair adds exact zeros: planar motion, omega along z, has 5 of 9)
        if (abs(lm(a, b)) <= 0.0_dp .and. abs(om(a, b)) <= 0.0_dp) cycle
        y = lm(a, b)*ps(:, b) + om(a, b)*hs(:, b)
        do k = 1, el%nact(b)               ! (N_ab's columns past nact(b) are zero)
          fa = fa - el%nab(:, k, a, b)*y(k)
        end do
      end do
      fp(sets(:, a)) = fa
    end do
  end function translational_inertia

  !> The matrix of w x.
  pure function skew(w) result(m)
    real(dp), intent(in) :: w(3)
    real(dp) :: m(3, 3)
    m(:, 1) = [0.0_dp, w(3), -w(2)]
    m(:, 2) = [-w(3), 0.0_dp, w(1)]
    m(:, 3) = [w(2), -w(1), 0.0_dp]
  end function skew

  !> Internal force dSE/dp in LOCAL DOFs.
  pure subroutine spatial_internal_force(el, p, f)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(nd)
    real(dp), intent(out) :: f(nd)
    real(dp) :: fdamp(nd), kp(nd, nd)
    type(spatial_eval_info_t) :: info
    call strain_terms(el, p, p, .false., .false., info, f, fdamp, kp)
  end subroutine spatial_internal_force

  !> Tangent d^2 SE / dp^2 in LOCAL DOFs.
  pure subroutine spatial_tangent_stiffness(el, p, k)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(nd)
    real(dp), intent(out) :: k(nd, nd)
    real(dp) :: f(nd), fdamp(nd)
    type(spatial_eval_info_t) :: info
    call strain_terms(el, p, p, .true., .false., info, f, fdamp, k)
  end subroutine spatial_tangent_stiffness

  !> Strain energy in LOCAL DOFs.
  pure real(dp) function spatial_strain_energy(el, p) result(se)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(nd)
    real(dp) :: f(nd), fdamp(nd), kp(nd, nd)
    type(spatial_eval_info_t) :: info
    call strain_terms(el, p, p, .false., .false., info, f, fdamp, kp)
    se = info%strain_energy
  end function spatial_strain_energy

  !> Kinetic energy from the absolute velocities of the section points
  !> (8-point rule, exact), independent of the precomputed matrices.
  pure real(dp) function spatial_kinetic_energy(el, q, qd, rb) result(ke)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), qd(nd)
    type(spatial_rigid_t), intent(in) :: rb
    integer, parameter :: nt = 8
    real(dp) :: p(nd), pd(nd), wl(3), x(nt), w(nt), s(nd, 3), gp(nd, 3), z(nd, nz), vel(3), om(3), jr(3)
    integer :: i
    p = spatial_to_local(rb%rot, q, el%local_rotation)
    wl = matmul(rb%omega, rb%rot)
    pd = spatial_to_local(rb%rot, qd, el%local_rotation) - skew_apply(wl, p, el%local_rotation)
    jr = el%material%rho*[el%sec%ip, el%sec%iy, el%sec%iz]
    if (.not. el%effects%rotary_inertia) jr(2:3) = 0.0_dp
    ke = 0.0_dp
    call gauss_legendre_interval(nt, 0.0_dp, el%length, x, w)
    do i = 1, nt
      call rows_at(x(i)/el%length, el%length, el%quintic_u, s, gp, z)
      vel = matmul(rb%x1_d, rb%rot) + matmul(pd, s) + cross(wl, [x(i), 0.0_dp, 0.0_dp] + matmul(p, s))
      om = wl + matmul(pd, gp)
      ke = ke + 0.5_dp*w(i)*(el%material%rho*el%sec%area*dot_product(vel, vel) + sum(jr*om*om))
    end do
    do i = 1, 2
      call rows_at(real(i - 1, dp), el%length, el%quintic_u, s, gp, z)
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
    real(dp), intent(in) :: p(nd), prel(nd)
    logical, intent(in) :: want_k, want_damp
    type(spatial_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(nd), fdamp(nd), kp(nd, nd)
    real(dp) :: z(nz), fz(nz), hz(nz, nz), en, gh(nd, nz), emax, yf, zf, s(3)
    integer :: i
    info%strain_energy = 0.0_dp
    info%max_abs_strain = 0.0_dp
    if (linear_strain(el)) then
      if (want_damp) then
        call block_apply_pair(el%kblk, el%kt, el%nact, p, prel, fint, fdamp)
      else
        fint = block_apply(el%kblk, el%kt, el%nact, p)
      end if
      info%strain_energy = 0.5_dp*dot_product(p, fint)
      if (want_k) kp = el%k_lin          ! kp, fdamp are left undefined when not asked for
      ! material off here: no Ramberg-Osgood peak to watch, max_abs_strain is not computed
      return
    end if
    fint = 0.0_dp
    fdamp = 0.0_dp
    kp = 0.0_dp
    do i = 1, el%n_gauss
      z = matmul(p, el%gz(:, :, i))
      call station_energy(el, z, want_k .or. want_damp, en, fz, hz, s)
      info%strain_energy = info%strain_energy + el%wg(i)*en
      fint = fint + el%wg(i)*matmul(el%gz(:, :, i), fz)
      if (want_k) then
        gh = el%wg(i)*matmul(el%gz(:, :, i), hz)
        kp = kp + matmul(gh, transpose(el%gz(:, :, i)))
        if (want_damp) fdamp = fdamp + matmul(gh, matmul(prel, el%gz(:, :, i)))
      else if (want_damp) then         ! G (H (G^T prel)): without the 20 x 7 product G H
        fdamp = fdamp + el%wg(i)*matmul(el%gz(:, :, i), matmul(hz, matmul(prel, el%gz(:, :, i))))
      end if
      call section_extreme_fibre_strain(el%sec, s, emax, yf, zf)
      info%max_abs_strain = max(info%max_abs_strain, emax)
    end do
    info%n_nonlinear_points = el%n_gauss
    info%beyond_peak = el%effects%material .and. info%max_abs_strain > el%eps_star
  end subroutine strain_terms

  !> No nonlinear strain effect: the element's strain energy is p^T K p / 2.
  pure logical function linear_strain(el)
    type(spatial_beam_t), intent(in) :: el
    linear_strain = .not. (el%effects%stretching .or. el%effects%curvature .or. el%effects%material)
  end function linear_strain

  !> Energy per unit length at a station, its gradient and (if want_h) its
  !> Hessian with respect to z = (u_x, v_x, w_x, v_xx, w_xx, theta_x);
  !> s = (eps, kappa_y, kappa_z) on return.
  pure subroutine station_energy(el, z, want_h, en, fz, hz, s)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: z(nz)
    logical, intent(in) :: want_h
    real(dp), intent(out) :: en, fz(nz), hz(nz, nz), s(3)
    real(dp) :: js(3, nz), hs(nz, nz, 3), g(3), h(3, 3), gj
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
  !> hs(:, :, k) = d^2 s_k / dz^2.  With r' = (a, v_x, w_x), a = 1 + u_x,
  !> r'' = (u_xx, v_xx, w_xx) and r = |r'|: eps = r - 1, kappa = r' x r'' / r^3
  !> (exact stretch and curvature of the centroid line), of which the y, z
  !> components are the bending curvatures
  !>   kappa_z = (a v_xx - v_x u_xx) / r^3,  kappa_y = -(a w_xx - w_x u_xx) / r^3
  !> (u_xx = 0 in Kear's linear u; the planar consistent element's kappa in the x-y plane).
  pure subroutine strain_measures(fx, z, want_h, s, js, hs)
    type(element_effects_t), intent(in) :: fx
    real(dp), intent(in) :: z(nz)
    logical, intent(in) :: want_h
    real(dp), intent(out) :: s(3), js(3, nz), hs(nz, nz, 3)
    real(dp) :: gv(3), r, r2, a, sg, num, rm3, dn(nz), dr(nz), d2r(nz, nz)
    integer :: i, j, k, ix, it
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
    ! r^-3 and its derivatives in z(1:3)
    rm3 = 1.0_dp/(r2*r)
    dr = 0.0_dp
    dr(1:3) = -3.0_dp*gv*rm3/r2
    d2r = 0.0_dp
    if (want_h) then
      do j = 1, 3
        do i = 1, 3
          d2r(i, j) = rm3/r2*(-3.0_dp*merge(1.0_dp, 0.0_dp, i == j) + 15.0_dp*gv(i)*gv(j)/r2)
        end do
      end do
    end if
    do k = 2, 3
      ix = merge(5, 4, k == 2)          ! kappa_y uses w_xx and w_x, kappa_z v_xx and v_x
      it = merge(3, 2, k == 2)
      sg = merge(-1.0_dp, 1.0_dp, k == 2)
      num = a*z(ix) - z(it)*z(7)
      dn = 0.0_dp
      dn(1) = z(ix)
      dn(ix) = a
      dn(it) = -z(7)
      dn(7) = -z(it)
      s(k) = sg*num*rm3
      js(k, :) = sg*(dn*rm3 + num*dr)
      if (want_h) then
        do j = 1, nz
          hs(:, j, k) = sg*(dn*dr(j) + dr*dn(j) + num*d2r(:, j))
        end do
        hs(1, ix, k) = hs(1, ix, k) + sg*rm3
        hs(ix, 1, k) = hs(ix, 1, k) + sg*rm3
        hs(it, 7, k) = hs(it, 7, k) - sg*rm3
        hs(7, it, k) = hs(7, it, k) - sg*rm3
      end if
    end do
  end subroutine strain_measures

  ! ------------------------------------------------------------ recovery

  !> Strains s = (eps, kappa_y, kappa_z) and twist rate at x = e l, LOCAL p.
  pure subroutine spatial_section_state(el, p, e, s, twist)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: p(nd), e
    real(dp), intent(out) :: s(3), twist
    real(dp) :: sr(nd, 3), gp(nd, 3), zr(nd, nz), z(nz), js(3, nz), hs(nz, nz, 3)
    call rows_at(e, el%length, el%quintic_u, sr, gp, zr)
    z = matmul(p, zr)
    call strain_measures(el%effects, z, .false., s, js, hs)
    twist = z(6)
  end subroutine spatial_section_state

  !> Maximum |sigma| over the ends and the Gauss stations (extreme fibres),
  !> and the end resultants N, M_y, M_z, T; global q.
  pure function spatial_stress_recovery(el, q, rot) result(rep)
    type(spatial_beam_t), intent(in) :: el
    real(dp), intent(in) :: q(nd), rot(3, 3)
    type(spatial_stress_t) :: rep
    real(dp) :: p(nd), s(3), tw, e, emax, yf, zf, sig, en, g(3), h(3, 3), ef
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
    real(dp), intent(in) :: p(nd), e
    real(dp) :: d(3)
    real(dp) :: s(nd, 3), gp(nd, 3), z(nd, nz)
    call rows_at(e, el%length, el%quintic_u, s, gp, z)
    d = matmul(p, s)
  end function spatial_local_displacement

  ! ------------------------------------------------------------ frames

  !> p = T^T q: the vector triples of each node into the element frame
  !> (a rotation triple flagged local is already in it).
  pure function spatial_to_local(rot, q, local) result(p)
    real(dp), intent(in) :: rot(3, 3), q(nd)
    logical, intent(in), optional :: local(2)
    real(dp) :: p(nd)
    real(dp) :: rot_t(3, 3)
    rot_t = transpose(rot)              ! (a variable: an expression argument would be a temporary)
    p = rotate_triples(rot_t, q, local)
  end function spatial_to_local

  !> q = T p.
  pure function spatial_to_global(rot, p, local) result(q)
    real(dp), intent(in) :: rot(3, 3), p(nd)
    logical, intent(in), optional :: local(2)
    real(dp) :: q(nd)
    q = rotate_triples(rot, p, local)
  end function spatial_to_global

  !> y = x with each vector triple (but the rotation triples flagged local)
  !> multiplied by m: T^T q with m = rot^T, T p with m = rot.  (Scalar
  !> statements: the 3 x 3 products stay in registers, no array temporaries.)
  pure function rotate_triples(m, x, local) result(y)
    real(dp), intent(in) :: m(3, 3), x(nd)
    logical, intent(in), optional :: local(2)
    real(dp) :: y(nd)
    logical :: loc(2)
    integer :: b, r
    loc = .false.
    if (present(local)) loc = local
    y = x                                ! curvature and u-slope DOFs (and local triples) stay
    do b = 1, 4
      if ((b == 2 .and. loc(1)) .or. (b == 4 .and. loc(2))) cycle
      r = triple_first(b)
      y(r) = m(1, 1)*x(r) + m(1, 2)*x(r + 1) + m(1, 3)*x(r + 2)
      y(r + 1) = m(2, 1)*x(r) + m(2, 2)*x(r + 1) + m(2, 3)*x(r + 2)
      y(r + 2) = m(3, 1)*x(r) + m(3, 2)*x(r + 1) + m(3, 3)*x(r + 2)
    end do
  end function rotate_triples

  !> T A T^T, by the 3 x 3 blocks of the vector triples that rotate.
  pure function matrix_to_global(rot, a, local) result(g)
    real(dp), intent(in) :: rot(3, 3), a(nd, nd)
    logical, intent(in) :: local(2)
    real(dp) :: g(nd, nd), c(nd, 3)
    logical :: rotates(4)
    integer :: b, r, j
    rotates = [.true., .not. local(1), .true., .not. local(2)]
    g = a
    do b = 1, 4                                                        ! T A, rows by blocks
      if (.not. rotates(b)) cycle
      r = triple_first(b)
      do j = 1, nd
        g(r:r + 2, j) = rot(:, 1)*a(r, j) + rot(:, 2)*a(r + 1, j) + rot(:, 3)*a(r + 2, j)
      end do
    end do
    do b = 1, 4                                                        ! (T A) T^T, columns by blocks
      if (.not. rotates(b)) cycle
      r = triple_first(b)
      c = g(:, r:r + 2)
      do j = 1, 3
        g(:, r + j - 1) = c(:, 1)*rot(j, 1) + c(:, 2)*rot(j, 2) + c(:, 3)*rot(j, 3)
      end do
    end do
  end function matrix_to_global

  !> W p: omega x each vector triple of p that rotates with the frame
  !> (T_dot = T W); curvature DOFs and local rotation triples map to zero.
  pure function skew_apply(w, p, local) result(r)
    real(dp), intent(in) :: w(3), p(nd)
    logical, intent(in) :: local(2)
    real(dp) :: r(nd)
    logical :: rotates(4)
    integer :: b, k
    rotates = [.true., .not. local(1), .true., .not. local(2)]
    r = 0.0_dp
    do b = 1, 4                          ! (the cross product written out: inlined)
      if (.not. rotates(b)) cycle
      k = triple_first(b)
      r(k) = w(2)*p(k + 2) - w(3)*p(k + 1)
      r(k + 1) = w(3)*p(k) - w(1)*p(k + 2)
      r(k + 2) = w(1)*p(k + 1) - w(2)*p(k)
    end do
  end function skew_apply
end module spatial_beam
