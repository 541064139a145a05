!> The steps the two planar beam elements share (Kear's 8-DOF element and
!> the consistent 12-DOF element, doc/element.md): the same Lagrange
!> equations with another interpolation, so the same frame rotation, the
!> same constant integrals of the translational inertia, the same
!> per-station internal force and tangent and the same exact section angle.
!> Written for any DOF layout whose node translations (u, w) stand at
!> (1, 2) and (k2, k2 + 1): k2 = 5 for Kear's element, 7 for the consistent
!> one.  Same arithmetic, in the same order, as each element had.
module planar_beam_kernels
  use kinds, only: dp
  use linalg, only: outer
  implicit none
  private
  public :: to_local, to_global, rotate_to_global, jb_times, frame_vectors, in_frame
  public :: translational_force, frame_acceleration, add_linear_rotary, point_kinetic_energy
  public :: subtract_elastic_forces, to_global_results
  public :: add_constant_integrals, rotating_frame_integrals
  public :: add_station_terms, exact_angle_terms, add_rank_one

contains

  ! ------------------------------------------------------------ frame

  !> p = T(phi) q: rotate the node translations into the element frame (K26).
  pure function to_local(c, s, q, k2) result(p)
    real(dp), intent(in) :: c, s, q(:)
    integer, intent(in) :: k2
    real(dp) :: p(size(q))
    p = q
    p(1) = c*q(1) + s*q(2)
    p(2) = -s*q(1) + c*q(2)
    p(k2) = c*q(k2) + s*q(k2 + 1)
    p(k2 + 1) = -s*q(k2) + c*q(k2 + 1)
  end function to_local

  !> T^T f.
  pure function to_global(c, s, f, k2) result(g)
    real(dp), intent(in) :: c, s, f(:)
    integer, intent(in) :: k2
    real(dp) :: g(size(f))
    g = f
    g(1) = c*f(1) - s*f(2)
    g(2) = s*f(1) + c*f(2)
    g(k2) = c*f(k2) - s*f(k2 + 1)
    g(k2 + 1) = s*f(k2) + c*f(k2 + 1)
  end function to_global

  !> a := T^T a T in place: only the four rows and columns that T mixes are
  !> touched.
  pure subroutine rotate_to_global(c, s, a, k2)
    real(dp), intent(in) :: c, s
    real(dp), intent(inout) :: a(:, :)   !< square, at most 12 x 12
    integer, intent(in) :: k2
    real(dp) :: r1(12), r2(12)   ! fixed size: an automatic array would take the heap on every call
    integer :: k, n
    n = size(a, 1)
    do k = 1, k2, k2 - 1
      r1(:n) = c*a(k, :) - s*a(k + 1, :)
      r2(:n) = s*a(k, :) + c*a(k + 1, :)
      a(k, :) = r1(:n)
      a(k + 1, :) = r2(:n)
    end do
    do k = 1, k2, k2 - 1
      r1(:n) = c*a(:, k) - s*a(:, k + 1)
      r2(:n) = s*a(:, k) + c*a(:, k + 1)
      a(:, k) = r1(:n)
      a(:, k + 1) = r2(:n)
    end do
  end subroutine rotate_to_global

  !> J_b p: (u, w) -> (-w, u) at both nodes, zero elsewhere (T_phi = -J_b T).
  pure function jb_times(p, k2) result(r)
    real(dp), intent(in) :: p(:)
    integer, intent(in) :: k2
    real(dp) :: r(size(p))
    r = 0.0_dp
    r(1) = -p(2)
    r(2) = p(1)
    r(k2) = -p(k2 + 1)
    r(k2 + 1) = p(k2)
  end function jb_times

  !> The local vectors of an evaluation: p = T q, v = T q_dot (the q_dot part
  !> of p_dot) and J_b p, J_b v, J_b^2 p.
  pure subroutine frame_vectors(c, s, q, qd, k2, p, v, jp, jv, j2p)
    real(dp), intent(in) :: c, s, q(:), qd(:)
    integer, intent(in) :: k2
    real(dp), intent(out) :: p(:), v(:), jp(:), jv(:), j2p(:)
    p = to_local(c, s, q, k2)
    v = to_local(c, s, qd, k2)
    jp = jb_times(p, k2)
    jv = jb_times(v, k2)
    j2p = jb_times(jp, k2)
  end subroutine frame_vectors

  !> A global (x, y) in the element frame: A^T (x, y).
  pure function in_frame(c, s, x, y) result(r)
    real(dp), intent(in) :: c, s, x, y
    real(dp) :: r(2)
    r(1) = c*x + s*y
    r(2) = -s*x + c*y
  end function in_frame

  !> An evaluation's local results into the global frame: force = T^T fp,
  !> tangent = T^T kp T (when asked for), mass := T^T mass T (want_m).
  pure subroutine to_global_results(c, s, k2, fp, force, want_m, mass, kp, tangent)
    real(dp), intent(in) :: c, s, fp(:), kp(:, :)
    integer, intent(in) :: k2
    real(dp), intent(out) :: force(:)
    logical, intent(in) :: want_m
    real(dp), intent(inout) :: mass(:, :)
    real(dp), intent(out), optional :: tangent(:, :)
    force = to_global(c, s, fp, k2)
    if (present(tangent)) then
      tangent = kp
      call rotate_to_global(c, s, tangent, k2)
    end if
    if (want_m) call rotate_to_global(c, s, mass, k2)
  end subroutine to_global_results

  !> fp -= the internal force fint and, with beta > 0, the stiffness-
  !> proportional damping force beta fdamp (fdamp = K_t p_rel).
  pure subroutine subtract_elastic_forces(fp, fint, fdamp, beta)
    real(dp), intent(inout) :: fp(:)
    real(dp), intent(in) :: fint(:), fdamp(:), beta
    fp = fp - fint
    if (beta > 0.0_dp) fp = fp - beta*fdamp
  end subroutine subtract_elastic_forces

  ! ------------------------------------------------------------ inertia

  !> Force of the translational inertia (exact: KE is quadratic in (q, q_dot),
  !> so every term of its Lagrange equations is a constant matrix,
  !> doc/element.md section 3): acc0 = the local rigid acceleration of end 1,
  !> cp = (centrifugal matrix) p; the Coriolis and Euler terms with coupling.
  pure function translational_force(load0, load1, coupling, cp, p, v, acc0, phi_d, phi_dd, rhoa, with_coupling) &
    result(fp)
    real(dp), intent(in) :: load0(:, :), load1(:, :), coupling(:, :), cp(:), p(:), v(:), acc0(2)
    real(dp), intent(in) :: phi_d, phi_dd, rhoa
    logical, intent(in) :: with_coupling
    real(dp) :: fp(size(p))
    fp = -rhoa*(matmul(load0, acc0) + load1(:, 1)*(-phi_d**2) + load1(:, 2)*phi_dd + phi_d**2*cp)
    if (with_coupling) fp = fp - rhoa*matmul(coupling, phi_dd*p + 2.0_dp*phi_d*v)
  end function translational_force

  !> p_dd minus T q_dd: the centrifugal part, with coupling also the Euler and
  !> Coriolis parts.
  pure function frame_acceleration(j2p, jp, jv, phi_d, phi_dd, with_coupling) result(pdd_nm)
    real(dp), intent(in) :: j2p(:), jp(:), jv(:), phi_d, phi_dd
    logical, intent(in) :: with_coupling
    real(dp) :: pdd_nm(size(j2p))
    pdd_nm = phi_d**2*j2p
    if (with_coupling) pdd_nm = pdd_nm - phi_dd*jp - 2.0_dp*phi_d*jv
  end function frame_acceleration

  !> Rotary inertia with the linear section angle theta = phi + w_x
  !> (constant integrals): mp += rho I int gw gw^T (want_m), fp -= its force.
  pure subroutine add_linear_rotary(rot_linear, rot_load, rhoi, phi_dd, pdd_nm, want_m, mp, fp)
    real(dp), intent(in) :: rot_linear(:, :), rot_load(:), rhoi, phi_dd, pdd_nm(:)
    logical, intent(in) :: want_m
    real(dp), intent(inout) :: mp(:, :), fp(:)
    if (want_m) mp = mp + rhoi*rot_linear
    fp = fp - rhoi*(phi_dd*rot_load + matmul(rot_linear, pdd_nm))
  end subroutine add_linear_rotary

  !> The translational kinetic energy at one point (x, weight w) of a direct
  !> quadrature (K3, K6): rho A w |r_dot|^2 / 2 with r_dot in the element
  !> frame = R1_dot (vloc) + rho_dot + phi_dot J rho, rho = (x + u, w).
  pure real(dp) function point_kinetic_energy(rhoa, w, x, vloc, su, sw, p, pd, phi_d) result(ke)
    real(dp), intent(in) :: rhoa, w, x, vloc(2), su(:), sw(:), p(:), pd(:), phi_d
    real(dp) :: rdot(2)
    rdot(1) = vloc(1) + dot_product(su, pd) - phi_d*dot_product(sw, p)
    rdot(2) = vloc(2) + dot_product(sw, pd) + phi_d*(x + dot_product(su, p))
    ke = 0.5_dp*rhoa*w*(rdot(1)**2 + rdot(2)**2)
  end function point_kinetic_energy

  ! ------------------------------------------------ constant integrals

  !> One point (x, weight w) of the rule for the constant integrals, with the
  !> interpolation u = su.p, w = sw.p and the gradients gu, gw, gww of
  !> (u_x, w_x, w_xx): int S^T S, int S^T J S (into g2), int S^T, int x S^T,
  !> the linear stiffness (e1a = E1 A, e1i = E1 I) and the linear rotary terms.
  pure subroutine add_constant_integrals(w, x, su, sw, gu, gw, gww, e1a, e1i, mass_trans, g2, load0, load1, &
                                         k_linear, rot_linear, rot_load)
    real(dp), intent(in) :: w, x, su(:), sw(:), gu(:), gw(:), gww(:), e1a, e1i
    real(dp), intent(inout) :: mass_trans(:, :), g2(:, :), load0(:, :), load1(:, :), k_linear(:, :)
    real(dp), intent(inout) :: rot_linear(:, :), rot_load(:)
    mass_trans = mass_trans + w*(outer(su, su) + outer(sw, sw))
    g2 = g2 + w*(outer(sw, su) - outer(su, sw))             ! int S^T J S, J = [0 -1; 1 0]
    load0(:, 1) = load0(:, 1) + w*su
    load0(:, 2) = load0(:, 2) + w*sw
    load1(:, 1) = load1(:, 1) + w*x*su
    load1(:, 2) = load1(:, 2) + w*x*sw
    k_linear = k_linear + w*(e1a*outer(gu, gu) + e1i*outer(gww, gww))
    rot_linear = rot_linear + w*outer(gw, gw)
    rot_load = rot_load + w*gw
  end subroutine add_constant_integrals

  !> The coupling int S^T (J S - S J_b) and centrifugal int S^T (S J_b^2 - S
  !> - 2 J S J_b) matrices from int S^T S and g2 = int S^T J S.
  pure subroutine rotating_frame_integrals(mass_trans, g2, k2, coupling, centrifugal)
    real(dp), intent(in) :: mass_trans(:, :), g2(:, :)
    integer, intent(in) :: k2
    real(dp), intent(out) :: coupling(:, :), centrifugal(:, :)
    real(dp) :: jb(size(g2, 1), size(g2, 1))
    jb = 0.0_dp
    jb(1, 2) = -1.0_dp
    jb(2, 1) = 1.0_dp
    jb(k2, k2 + 1) = -1.0_dp
    jb(k2 + 1, k2) = 1.0_dp
    coupling = g2 - matmul(mass_trans, jb)
    centrifugal = matmul(mass_trans, matmul(jb, jb)) - mass_trans - 2.0_dp*matmul(g2, jb)
  end subroutine rotating_frame_integrals

  ! ------------------------------------------------- nonlinear stations

  !> One station (weight wg, G = d(strain variables)/dp, 12 x 4: the
  !> consistent element's DOFs and its strain variables (u_x, w_x, w_xx,
  !> u_xx); gt = g^T, tabulated) of the internal force f = G (N de + M dk), the tangent
  !> K = G H G^T (want_k) and K prel (want_damp).  de is what multiplies N in
  !> the force, de_true the true gradient, he the derivative of de; tangent =
  !> dN, dM by (eps, kappa) from the section.
  pure subroutine add_station_terms(wg, g, gt, axial_force, moment, tangent, de, de_true, dk, he, hk, prel, want_k, &
                                    want_damp, fint, fdamp, kp)
    integer, parameter :: n = 12, m = 4
    real(dp), intent(in) :: wg, g(n, m), gt(m, n), axial_force, moment, tangent(2, 2)
    real(dp), intent(in) :: de(m), de_true(m), dk(m), he(m, m), hk(m, m), prel(n)
    logical, intent(in) :: want_k, want_damp
    real(dp), intent(inout) :: fint(n), fdamp(n), kp(n, n)
    ! This is the innermost loop of every planar model evaluation: the products
    ! are written out over fixed-size contiguous arrays (matmul and automatic
    ! arrays of assumed-shape operands take the heap on every call).  Every
    ! sum over k = 1 .. m runs in matmul's order, ((t1 + t2) + t3) + t4, for
    ! each output entry, written out over the whole column so that the
    ! compiler computes several independent entries per instruction and keeps
    ! the partial sums in registers (the sums over k of one entry cannot be
    ! reordered without changing the result's last bits).
    real(dp) :: h(m, m), f(m), tn(m), tk(m)
    real(dp) :: gh(n, m), pg(m), hp(m)
    integer :: i, j, k
    f = axial_force*de + moment*dk
    fint = fint + wg*(((g(:, 1)*f(1) + g(:, 2)*f(2)) + g(:, 3)*f(3)) + g(:, 4)*f(4))
    if (.not. (want_k .or. want_damp)) return
    tn = tangent(1, 1)*de_true + tangent(1, 2)*dk
    tk = tangent(2, 1)*de_true + tangent(2, 2)*dk
    do j = 1, m
      do i = 1, m
        h(i, j) = de(i)*tn(j) + dk(i)*tk(j) + axial_force*he(i, j) + moment*hk(i, j)
      end do
    end do
    if (want_k) then
      do j = 1, m
        gh(:, j) = wg*(((g(:, 1)*h(1, j) + g(:, 2)*h(2, j)) + g(:, 3)*h(3, j)) + g(:, 4)*h(4, j))
      end do
      do j = 1, n
        kp(:, j) = kp(:, j) + (((gh(:, 1)*g(j, 1) + gh(:, 2)*g(j, 2)) + gh(:, 3)*g(j, 3)) + gh(:, 4)*g(j, 4))
      end do
    end if
    if (want_damp) then
      pg = 0.0_dp
      do k = 1, n
        pg = pg + prel(k)*gt(:, k)
      end do
      hp = ((h(:, 1)*pg(1) + h(:, 2)*pg(2)) + h(:, 3)*pg(3)) + h(:, 4)*pg(4)
      fdamp = fdamp + wg*(((g(:, 1)*hp(1) + g(:, 2)*hp(2)) + g(:, 3)*hp(3)) + g(:, 4)*hp(4))
    end if
  end subroutine add_station_terms

  !> a := a + c x x^T (the rotary mass of one station, n DOFs), in place: the
  !> same sums as a + c*outer(x, x) without its temporary.
  pure subroutine add_rank_one(n, a, c, x)
    integer, intent(in) :: n
    real(dp), intent(inout) :: a(n, n)
    real(dp), intent(in) :: c, x(n)
    integer :: i, j
    do j = 1, n
      do i = 1, n
        a(i, j) = a(i, j) + c*(x(i)*x(j))
      end do
    end do
  end subroutine add_rank_one

  !> The exact section angle theta = phi + atan2(b, a) (K8), a = 1 + u_x,
  !> b = w_x, at a station with gradients gu, gw: d theta/d(a, b) = (xa, xb)
  !> and the velocity-product term quad of theta_dd.  With coupling, the rates
  !> are pd = p_dot; without, the Coriolis cross term between T q_dot (v) and
  !> phi_dot J_b p (jp) is left out.
  pure subroutine exact_angle_terms(a, b, gu, gw, v, jp, pd, phi_d, coupling, xa, xb, quad)
    real(dp), intent(in) :: a, b, gu(:), gw(:), v(:), jp(:), pd(:), phi_d
    logical, intent(in) :: coupling
    real(dp), intent(out) :: xa, xb, quad
    real(dp) :: r2, r4, xaa, xab, xbb, ua, ub, ja, jbb
    r2 = a*a + b*b
    r4 = r2*r2
    xa = -b/r2
    xb = a/r2
    xaa = 2.0_dp*a*b/r4
    xab = (b*b - a*a)/r4
    xbb = -xaa
    if (coupling) then
      ua = dot_product(gu, pd)
      ub = dot_product(gw, pd)
      quad = xaa*ua*ua + 2.0_dp*xab*ua*ub + xbb*ub*ub
    else
      ua = dot_product(gu, v)
      ub = dot_product(gw, v)
      ja = dot_product(gu, jp)
      jbb = dot_product(gw, jp)
      quad = xaa*ua*ua + 2.0_dp*xab*ua*ub + xbb*ub*ub &
             + phi_d**2*(xaa*ja*ja + 2.0_dp*xab*ja*jbb + xbb*jbb*jbb)
    end if
  end subroutine exact_angle_terms
end module planar_beam_kernels
