!> Kear's planar beam element (1986-87, K1-K34; doc/element.md): exact axial
!> stretch and curvature, Ramberg-Osgood material integrated through the
!> depth in closed form, exact rotary inertia, K26 interpolation.
!>
!> Element DOFs  q = [U1 W1 th1 m1 U2 W2 th2 m2]:  U, W global X/Y elastic
!> translations of the nodes, th = local slope w_x, m = local w_xx.  The local
!> nodal values p = T(phi) q rotate (U, W) into the element frame (K26).
!>
!> The element returns, for given nodal values, nodal rates and rigid-body
!> state of its reference line, the mass matrix M_e(q) and the force vector
!> F_e(q, qdot, t) such that  M_e qddot = F_e  is its part of Lagrange's
!> equations (K1, K2):
!>
!>   M_e = rho int( A B^T B + I theta_q theta_q^T ) dx
!>   F_e = -dSE/dq - rho int[ A B^T (c_dd + B_dd q + 2 B_d q_d)
!>                            + I theta_q (theta_dd - theta_q . q_dd) ] dx
!>         - beta K_t(q) pdot_rel
!>
!> Derivation, the printed simplifications (formulation = kear1987), the
!> effect switches and the checks are in doc/element.md.  All procedures are
!> pure functions of their arguments; kear_element_init precomputes the
!> constant integrals of the linear model once per element.
module kear_element
  use kinds, only: dp
  use linalg, only: outer
  use error_status, only: error_t
  use strings, only: str
  use name_table, only: name_of, code_of
  use quadrature, only: gauss_legendre_interval
  use shape_functions, only: quintic_hermite, linear_lagrange
  use beam_properties, only: element_effects_t, init_beam_properties
  use material_law, only: ramberg_osgood_t, section_resultants_t, section_response
  use planar_element, only: planar_element_t, rigid_state_t, kear_eval_info_t, stress_report_t, is_linear_strain, &
                            kear_internal_force => planar_internal_force, &
                            kear_tangent_stiffness => planar_tangent_stiffness, &
                            kear_strain_energy => planar_strain_energy, kear_stress_recovery => planar_stress_recovery, &
                            station_x_over_l
  use planar_beam_kernels, only: to_local, rotate_to_global, jb_times, frame_vectors, in_frame, &
                                 translational_force, frame_acceleration, add_linear_rotary, point_kinetic_energy, &
                                 subtract_elastic_forces, to_global_results, &
                                 add_constant_integrals, rotating_frame_integrals, exact_angle_terms, add_rank_one
  implicit none
  private
  public :: kear_ndof, formulation_exact, formulation_kear1987
  public :: element_effects_t, rigid_state_t, kear_element_t, kear_eval_info_t, stress_report_t
  public :: kear_element_init, kear_element_eval, kear_internal_force, kear_tangent_stiffness
  public :: kear_strain_energy, kear_kinetic_energy, kear_stress_recovery, kear_section_strains
  public :: kear_local_dofs, kear_local_displacement
  public :: formulation_from_name, formulation_name, effects_all_on, effects_summary

  integer, parameter :: kear_ndof = 8
  integer, parameter :: formulation_exact = 1      !< exact Lagrange equations of (K3), (K16)
  integer, parameter :: formulation_kear1987 = 2   !< as printed: (K9), (K11), (K20), (K23)
  character(len=*), parameter :: formulation_table(2) = [character(len=8) :: 'exact', 'kear1987']
  integer, parameter :: n_exact = 6                !< Gauss points exact for the linear integrals (degree <= 11)
  integer, parameter :: node2 = 5                  !< local DOF of node 2's u (then w)

  !> One element: geometry, material, switches and precomputed integrals.
  !> Arrays in the local DOF order p = [u1 w1 th1 m1 u2 w2 th2 m2].
  type, extends(planar_element_t) :: kear_element_t
    integer :: formulation = formulation_exact
    ! constant integrals (exact rule)
    real(dp) :: mass_trans(8, 8) = 0.0_dp   !< int S^T S
    real(dp) :: coupling(8, 8) = 0.0_dp     !< int S^T (J S - S J_b)
    real(dp) :: centrifugal(8, 8) = 0.0_dp  !< int S^T (S J_b^2 - S - 2 J S J_b)
    real(dp) :: load0(8, 2) = 0.0_dp        !< int S^T dx
    real(dp) :: load1(8, 2) = 0.0_dp        !< int x S^T dx
    real(dp) :: k_linear(8, 8) = 0.0_dp     !< E1 A int gu gu^T + E1 I int gww gww^T
    real(dp) :: rot_linear(8, 8) = 0.0_dp   !< int gw gw^T (rotary mass, linear angle)
    real(dp) :: rot_load(8) = 0.0_dp        !< int gw dx
    real(dp) :: gu(8) = 0.0_dp              !< d u_x / d p (constant for linear n1, n2)
    ! at the nonlinear-integral stations (planar_element_t's xg, wg)
    real(dp), allocatable :: gw(:, :)       !< d w_x / d p at the points (8, n)
    real(dp), allocatable :: gww(:, :)      !< d w_xx / d p at the points (8, n)
  contains
    procedure :: strain_terms => kear_strain_terms
    procedure :: linear_force => kear_linear_force
    procedure :: section_strains => kear_section_strains
    procedure :: station_strains => kear_station_strains
  end type kear_element_t

  !> Strain state at one station, derivatives with respect to (a, b, c) =
  !> (1 + u_x, w_x, w_xx).  de_used is what multiplies N in the internal
  !> force ((K20) in kear1987, the true gradient otherwise).
  type :: strain_point_t
    real(dp) :: eps = 0.0_dp, kap = 0.0_dp
    real(dp) :: de_true(3) = 0.0_dp, de_used(3) = 0.0_dp, dk(3) = 0.0_dp
    real(dp) :: he_used(3, 3) = 0.0_dp, hk(3, 3) = 0.0_dp
  end type strain_point_t

contains

  ! ------------------------------------------------------------------ set-up

  !> Build an element and precompute its constant integrals.
  pure subroutine kear_element_init(el, length, width, depth, material, effects, err, &
                                    formulation, n_gauss, damping_beta, objective_damping, fibre_distance)
    type(kear_element_t), intent(out) :: el
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: formulation, n_gauss
    real(dp), intent(in), optional :: damping_beta
    logical, intent(in), optional :: objective_damping
    real(dp), intent(in), optional :: fibre_distance   !< c of a section given by A, I, c (default t/2)
    real(dp) :: x(n_exact), w(n_exact), n(2), nx(2), h(6), hx(6), hxx(6)
    real(dp) :: su(8), sw(8), gw(8), gww(8), g2(8, 8)
    integer :: i

    call init_beam_properties(el%beam_properties_t, 'kear_element_init', length, width, depth, material, effects, &
                              err, n_gauss, damping_beta, objective_damping, fibre_distance)
    if (err%failed()) return
    el%node2 = node2
    if (present(formulation)) el%formulation = formulation
    if (el%formulation /= formulation_exact .and. el%formulation /= formulation_kear1987) then
      call err%set('kear_element_init', 'unknown formulation code '//str(el%formulation)); return
    end if

    ! constant integrals, 6-point rule: S^T S has degree 10 (h_i h_j), the rest less
    el%gu = 0.0_dp
    el%gu(1) = -1.0_dp/length
    el%gu(5) = 1.0_dp/length
    g2 = 0.0_dp
    call gauss_legendre_interval(n_exact, 0.0_dp, length, x, w)
    do i = 1, n_exact
      call linear_lagrange(x(i)/length, length, n, nx)
      call quintic_hermite(x(i)/length, length, h, hx, hxx)
      su = 0.0_dp
      su(1) = n(1)
      su(5) = n(2)
      call spread_w(h, sw)
      call spread_w(hx, gw)
      call spread_w(hxx, gww)
      call add_constant_integrals(w(i), x(i), su, sw, el%gu, gw, gww, material%e1*el%area, material%e1*el%inertia, &
                                  el%mass_trans, g2, el%load0, el%load1, el%k_linear, el%rot_linear, el%rot_load)
    end do
    call rotating_frame_integrals(el%mass_trans, g2, node2, el%coupling, el%centrifugal)

    ! stations for the nonlinear integrals
    allocate(el%xg(el%n_gauss), el%wg(el%n_gauss), el%gw(8, el%n_gauss), el%gww(8, el%n_gauss))
    call gauss_legendre_interval(el%n_gauss, 0.0_dp, length, el%xg, el%wg)
    do i = 1, el%n_gauss
      call quintic_hermite(el%xg(i)/length, length, h, hx, hxx)
      call spread_w(hx, el%gw(:, i))
      call spread_w(hxx, el%gww(:, i))
    end do
    allocate(el%gs(8, 3, 0:el%n_gauss + 1))
    do i = 0, el%n_gauss + 1
      call quintic_hermite(station_x_over_l(el%beam_properties_t, el%xg, i), length, h, hx, hxx)
      el%gs(:, 1, i) = el%gu
      call spread_w(hx, el%gs(:, 2, i))
      call spread_w(hxx, el%gs(:, 3, i))
    end do
  end subroutine kear_element_init

  !> 'exact' or 'kear1987' (case-insensitive).
  pure subroutine formulation_from_name(name, code, err)
    character(len=*), intent(in) :: name
    integer, intent(out) :: code
    type(error_t), intent(inout) :: err
    code = code_of(formulation_table, name, formulation_exact, 0)
    if (code == 0) call err%set('formulation', "unknown formulation '"//trim(name)//"' (expected exact or kear1987)")
  end subroutine formulation_from_name

  pure function formulation_name(code) result(name)
    integer, intent(in) :: code
    character(len=:), allocatable :: name
    name = name_of(formulation_table, code, formulation_exact, 'unknown')
  end function formulation_name

  pure function effects_all_on() result(fx)
    type(element_effects_t) :: fx
    fx = element_effects_t(.true., .true., .true., .true., .true.)
  end function effects_all_on

  !> One line for output headers, e.g. "stretching=T curvature=F ...".
  pure function effects_summary(fx) result(line)
    type(element_effects_t), intent(in) :: fx
    character(len=:), allocatable :: line
    line = 'stretching='//tf(fx%stretching)//' curvature='//tf(fx%curvature)//' material=' &
           //tf(fx%material)//' rotary_inertia='//tf(fx%rotary_inertia)//' coupling='//tf(fx%coupling)
  end function effects_summary

  pure function tf(b) result(c)
    logical, intent(in) :: b
    character(len=1) :: c
    c = merge('T', 'F', b)
  end function tf

  ! ---------------------------------------------------------- main routine

  !> Mass matrix and force vector of Lagrange's equations (K1, K2, K11, K17).
  !> Optionally the tangent stiffness K_t = d^2 SE / dq^2 (kear1987: the
  !> Jacobian of its internal force, not symmetric).
  !> peak_wanted = .false.: the linear model's strain peak (info%max_abs_strain,
  !> only informative: it cannot pass the material's peak) is not computed.
  !> force_wanted = .false. (with tangent): the linear model's force is not
  !> computed (left undefined; the Newton matrix needs M and K_t only).
  pure subroutine kear_element_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, &
                                    force_wanted)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: q(8), qd(8)
    type(rigid_state_t), intent(in) :: rb
    real(dp), intent(out) :: mass(8, 8), force(8)
    type(kear_eval_info_t), intent(out) :: info
    real(dp), intent(out), optional :: tangent(8, 8)
    logical, intent(in), optional :: mass_wanted     !< .false.: mass not computed (M depends on t only)
    logical, intent(in), optional :: peak_wanted, force_wanted
    real(dp) :: c, s, p(8), v(8), jp(8), jv(8), j2p(8), pdd_nm(8), prel(8)
    real(dp) :: fp(8), kp(8, 8), fint(8), fdamp(8), cp(8), acc0(2), rhoa, rhoi
    logical :: linear_strain, want_k, want_m

    c = cos(rb%phi)
    s = sin(rb%phi)
    want_m = .true.
    if (present(mass_wanted)) want_m = mass_wanted
    if (present(force_wanted) .and. present(tangent)) then
      if (.not. force_wanted .and. is_linear_strain(el) .and. .not. (el%effects%rotary_inertia .and. &
          el%effects%curvature)) then
        ! M and K_t of the linear strain model do not depend on q or q_dot
        if (want_m) then
          mass = el%material%rho*el%area*el%mass_trans
          if (el%effects%rotary_inertia) mass = mass + el%material%rho*el%inertia*el%rot_linear
          call rotate_to_global(c, s, mass, node2)
        end if
        tangent = el%k_linear
        call rotate_to_global(c, s, tangent, node2)
        return
      end if
    end if
    call frame_vectors(c, s, q, qd, node2, p, v, jp, jv, j2p)
    rhoa = el%material%rho*el%area
    rhoi = el%material%rho*el%inertia

    ! translational inertia; local rigid acceleration of end 1 (A^T R1_dd)
    acc0 = in_frame(c, s, rb%x1_dd, rb%y1_dd)
    if (want_m) mass = rhoa*el%mass_trans               ! local until rotated at the end
    prel = v
    if (el%objective_damping) prel = v - rb%phi_d*jp      ! p_dot: strain rates see this
    linear_strain = .not. (el%effects%stretching .or. el%effects%curvature .or. el%effects%material)
    if (linear_strain) then                                ! K p, K p_rel and C p in one pass
      call linear_forces(el%k_linear, el%centrifugal, p, prel, el%beta > 0.0_dp, fint, fdamp, cp)
    else
      cp = matmul(el%centrifugal, p)
    end if
    fp = translational_force(el%load0, el%load1, el%coupling, cp, p, v, acc0, rb%phi_d, rb%phi_dd, rhoa, &
                             el%effects%coupling)

    ! strain energy, internal force, damping
    want_k = present(tangent)
    if (linear_strain) then
      info%strain_energy = 0.5_dp*dot_product(p, fint)
      call subtract_elastic_forces(fp, fint, fdamp, el%beta)
      if (want_k) kp = el%k_linear
      if (present(peak_wanted)) then
        if (peak_wanted) call linear_strain_peak(el, p, info)
      else
        call linear_strain_peak(el, p, info)
      end if
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
        if (.not. want_m) mass = 0.0_dp        ! (a caller's choice: this M depends on q)
        call rotary_nonlinear(el, p, v, jp, pdd_nm, rb%phi_d, rb%phi_dd, rhoi, mass, fp, info)
      end if
    end if

    call to_global_results(c, s, node2, fp, force, want_m, mass, kp, tangent)
  end subroutine kear_element_eval

  !> fint = K p, (if damped) fdamp = K prel and cp = C p in one pass (the
  !> same sums, in the same order, as matmul).
  pure subroutine linear_forces(k, cen, p, prel, damped, fint, fdamp, cp)
    real(dp), intent(in) :: k(8, 8), cen(8, 8), p(8), prel(8)
    logical, intent(in) :: damped
    real(dp), intent(out) :: fint(8), fdamp(8), cp(8)
    integer :: j
    fint = 0.0_dp
    fdamp = 0.0_dp
    cp = 0.0_dp
    if (damped) then
      do j = 1, 8
        fint = fint + k(:, j)*p(j)
        fdamp = fdamp + k(:, j)*prel(j)
        cp = cp + cen(:, j)*p(j)
      end do
    else
      do j = 1, 8
        fint = fint + k(:, j)*p(j)
        cp = cp + cen(:, j)*p(j)
      end do
    end if
  end subroutine linear_forces

  !> planar_element_t's strain_terms: nonlinear_strain_terms (fixed sizes).
  pure subroutine kear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:), prel(:)
    logical, intent(in) :: want_k, want_damp
    type(kear_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(:), fdamp(:), kp(size(p), size(p))
    call nonlinear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
  end subroutine kear_strain_terms

  !> planar_element_t's linear_force: K p and K.
  pure subroutine kear_linear_force(el, p, want_k, fint, kp)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:)
    logical, intent(in) :: want_k
    real(dp), intent(out) :: fint(:), kp(size(p), size(p))
    real(dp) :: pl(kear_ndof)
    pl = p                                   ! fixed size: matmul's sums as before
    fint = matmul(el%k_linear, pl)
    if (want_k) kp = el%k_linear
  end subroutine kear_linear_force

  !> Kinetic energy (K3) of the element, evaluated directly from the
  !> positions (K5) and section angle (K8), independent of the precomputed
  !> matrices: translational part by an 8-point rule (exact), rotary part by
  !> the element's rule (as in the equations of motion).  With the
  !> curvature switch off the section angle is phi + w_x; kear1987 uses
  !> theta_dot of (K9).
  pure real(dp) function kear_kinetic_energy(el, q, qd, rb) result(ke)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: q(8), qd(8)
    type(rigid_state_t), intent(in) :: rb
    integer, parameter :: nt = 8
    real(dp) :: c, s, p(8), pd(8), x(nt), w(nt), n(2), h(6), hx(6), su(8), sw(8), gw(8)
    real(dp) :: vloc(2), a, b, ad, bd, thd, r2
    integer :: i
    c = cos(rb%phi)
    s = sin(rb%phi)
    p = to_local(c, s, q, node2)
    pd = to_local(c, s, qd, node2) - rb%phi_d*jb_times(p, node2)        ! p_dot = T q_dot + T_dot q
    vloc = in_frame(c, s, rb%x1_d, rb%y1_d)
    ke = 0.0_dp
    call gauss_legendre_interval(nt, 0.0_dp, el%length, x, w)
    do i = 1, nt
      call linear_lagrange(x(i)/el%length, el%length, n)
      call quintic_hermite(x(i)/el%length, el%length, h)
      su = 0.0_dp
      su(1) = n(1)
      su(5) = n(2)
      call spread_w(h, sw)
      ! r_dot in the element frame (K6): R1_dot + rho_dot + phi_dot J rho
      ke = ke + point_kinetic_energy(el%material%rho*el%area, w(i), x(i), vloc, su, sw, p, pd, rb%phi_d)
    end do
    if (el%effects%rotary_inertia) then
      do i = 1, el%n_gauss
        call quintic_hermite(el%xg(i)/el%length, el%length, h, hx)
        call spread_w(hx, gw)
        a = 1.0_dp + dot_product(el%gu, p)
        b = dot_product(gw, p)
        ad = dot_product(el%gu, pd)
        bd = dot_product(gw, pd)
        if (.not. el%effects%curvature) then
          thd = rb%phi_d + bd
        else if (el%formulation == formulation_kear1987) then
          thd = rb%phi_d + bd*a - b*ad                        ! (K9) as printed
        else
          r2 = a*a + b*b
          thd = rb%phi_d + (bd*a - b*ad)/r2                   ! exact derivative of (K8)
        end if
        ke = ke + 0.5_dp*el%material%rho*el%inertia*el%wg(i)*thd**2
      end do
    end if
  end function kear_kinetic_energy

  !> Axial strain eps_n and curvature kappa at x = e l from LOCAL nodal
  !> values p (see kear_local_dofs), with the element's switches.
  pure subroutine kear_section_strains(el, p, e, eps_n, kap)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:), e
    real(dp), intent(out) :: eps_n, kap
    real(dp) :: h(6), hx(6), hxx(6), gw(8), gww(8)
    type(strain_point_t) :: sp
    call quintic_hermite(e, el%length, h, hx, hxx)
    call spread_w(hx, gw)
    call spread_w(hxx, gww)
    call strain_state(el, dot_product(el%gu, p), dot_product(gw, p), dot_product(gww, p), &
                      .false., sp)
    eps_n = sp%eps
    kap = sp%kap
  end subroutine kear_section_strains

  !> Axial strain and curvature at stress station i from LOCAL nodal values p
  !> (the tabulated gradients gs: u_x, w_x, w_xx).
  pure subroutine kear_station_strains(el, p, i, eps_n, kap)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:)
    integer, intent(in) :: i
    real(dp), intent(out) :: eps_n, kap
    type(strain_point_t) :: sp
    call strain_state(el, dot_product(el%gs(:, 1, i), p), dot_product(el%gs(:, 2, i), p), &
                      dot_product(el%gs(:, 3, i), p), .false., sp)
    eps_n = sp%eps
    kap = sp%kap
  end subroutine kear_station_strains

  !> Local nodal values p = T(phi) q = [u1 w1 th1 m1 u2 w2 th2 m2].
  pure function kear_local_dofs(phi, q) result(p)
    real(dp), intent(in) :: phi, q(8)
    real(dp) :: p(8)
    p = to_local(cos(phi), sin(phi), q, node2)
  end function kear_local_dofs

  !> Local elastic displacements (u, w) at x = e l (K26).
  pure function kear_local_displacement(el, q, phi, e) result(uw)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: q(8), phi, e
    real(dp) :: uw(2)
    real(dp) :: p(8), n(2), h(6), sw(8)
    p = to_local(cos(phi), sin(phi), q, node2)
    call linear_lagrange(e, el%length, n)
    call quintic_hermite(e, el%length, h)
    call spread_w(h, sw)
    uw(1) = n(1)*p(1) + n(2)*p(5)
    uw(2) = dot_product(sw, p)
  end function kear_local_displacement

  ! ------------------------------------------------------------ internals

  !> Linear model: max |eps| = |u_x| + t/2 |w_xx| at the Gauss points.
  pure subroutine linear_strain_peak(el, p, info)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(8)
    type(kear_eval_info_t), intent(inout) :: info
    real(dp) :: ux, e
    integer :: i
    ux = abs(dot_product(el%gu, p))
    info%max_abs_strain = 0.0_dp
    do i = 1, el%n_gauss
      e = ux + 0.5_dp*el%depth*abs(dot_product(el%gww(:, i), p))
      call info%note_strain(e, el%xg(i)/el%length)
    end do
    info%beyond_peak = .false.            ! material switch off: no peak in the law
  end subroutine linear_strain_peak

  !> Strain energy, internal force, tangent K_pp (if want_k) and K_pp prel
  !> (if want_damp) by Gauss quadrature along the element; local DOFs p.
  !> Per station everything lives in the 3-space (a, b, c) = (1+u_x, w_x, w_xx):
  !> f = G (N de + M dk),  K = G H G^T,  G = [gu gw gww] (8 x 3).
  pure subroutine nonlinear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(8), prel(8)
    logical, intent(in) :: want_k, want_damp
    type(kear_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(8), fdamp(8), kp(8, 8)
    real(dp) :: g(8, 3), h3(3, 3), f3(3), ux, e, ht, tn(3), tk(3), gh(8, 3)
    type(strain_point_t) :: sp
    type(section_resultants_t) :: res
    integer :: i
    fint = 0.0_dp
    fdamp = 0.0_dp
    kp = 0.0_dp
    info%strain_energy = 0.0_dp
    info%max_abs_strain = 0.0_dp
    ht = 0.5_dp*el%depth
    ux = dot_product(el%gu, p)
    g(:, 1) = el%gu
    do i = 1, el%n_gauss
      g(:, 2) = el%gw(:, i)
      g(:, 3) = el%gww(:, i)
      call strain_state(el, ux, dot_product(g(:, 2), p), dot_product(g(:, 3), p), .true., sp)
      res = section_response(el%material, el%area, el%depth, sp%eps, sp%kap, el%effects%material)
      info%strain_energy = info%strain_energy + el%wg(i)*res%energy
      ! the station's terms written here with fixed sizes (planar_beam_kernels'
      ! add_station_terms does the same for any size): the compiler unrolls
      ! these 8 x 3 products, and this loop is the transient analysis' hot path
      f3 = res%axial_force*sp%de_used + res%moment*sp%dk            ! (K17)
      fint = fint + el%wg(i)*matmul(g, f3)
      if (want_k .or. want_damp) then
        tn = res%tangent(1, 1)*sp%de_true + res%tangent(1, 2)*sp%dk  ! dN/d(a,b,c)
        tk = res%tangent(2, 1)*sp%de_true + res%tangent(2, 2)*sp%dk  ! dM/d(a,b,c)
        h3 = outer(sp%de_used, tn) + outer(sp%dk, tk) + res%axial_force*sp%he_used + res%moment*sp%hk
        if (want_k) then
          gh = el%wg(i)*matmul(g, h3)
          kp = kp + matmul(gh, transpose(g))
        end if
        if (want_damp) fdamp = fdamp + el%wg(i)*matmul(g, matmul(h3, matmul(prel, g)))
      end if
      e = abs(sp%eps) + ht*abs(sp%kap)
      if (e > info%max_abs_strain) then           ! info%note_strain, written here: a call to
        info%max_abs_strain = e                   ! another module is not inlined, and this
        info%x_over_l_max_strain = el%xg(i)/el%length   ! loop is the hot path
      end if
    end do
    info%n_nonlinear_points = info%n_nonlinear_points + el%n_gauss
    info%beyond_peak = el%effects%material .and. info%max_abs_strain > el%eps_star
  end subroutine nonlinear_strain_terms

  !> Axial strain and curvature at a station from (a, b, c) = (1+u_x, w_x, w_xx),
  !> with first (and if derivs, second) derivatives.  u_xx = 0 for the linear
  !> axial interpolation of (K26), so the u_xx terms of (K23), (K24) vanish.
  pure subroutine strain_state(el, ux, b, c, derivs, sp)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: ux, b, c      !< u_x, w_x, w_xx
    logical, intent(in) :: derivs
    type(strain_point_t), intent(out) :: sp
    real(dp) :: a, r2, r, r3, r5, r7
    logical :: kear
    kear = el%formulation == formulation_kear1987
    a = 1.0_dp + ux
    r2 = a*a + b*b
    r = sqrt(r2)
    ! axial strain
    if (el%effects%stretching) then
      ! (K19) eps_n = r - 1, written without the cancellation of r - 1 so that a
      ! small strain keeps its relative accuracy (DLSODE's error test sees it)
      sp%eps = (ux*(2.0_dp + ux) + b*b)/(r + 1.0_dp)
      if (derivs) then
        sp%de_true = [a/r, b/r, 0.0_dp]
        if (kear) then
          sp%de_used = [a, b, 0.0_dp]                       ! (K20) as printed
          sp%he_used(1, 1) = 1.0_dp
          sp%he_used(2, 2) = 1.0_dp
        else
          sp%de_used = sp%de_true
          r3 = r2*r
          sp%he_used(1, 1) = b*b/r3
          sp%he_used(1, 2) = -a*b/r3
          sp%he_used(2, 1) = -a*b/r3
          sp%he_used(2, 2) = a*a/r3
        end if
      end if
    else
      sp%eps = ux                                           ! eps_n = u_x
      if (derivs) then
        sp%de_true = [1.0_dp, 0.0_dp, 0.0_dp]
        sp%de_used = sp%de_true
      end if
    end if
    ! curvature
    if (.not. el%effects%curvature) then
      sp%kap = c                                            ! kappa = w_xx
      if (derivs) sp%dk = [0.0_dp, 0.0_dp, 1.0_dp]
    else if (kear) then
      sp%kap = c*a                                          ! (K23) as printed, u_xx = 0
      if (derivs) then
        sp%dk = [c, 0.0_dp, a]                              ! (K24)
        sp%hk(1, 3) = 1.0_dp
        sp%hk(3, 1) = 1.0_dp
      end if
    else
      r3 = r2*r
      sp%kap = c*a/r3                                       ! exact curvature, u_xx = 0
      if (derivs) then
        r5 = r3*r2
        r7 = r5*r2
        sp%dk = [c*(b*b - 2.0_dp*a*a)/r5, -3.0_dp*c*a*b/r5, a/r3]
        sp%hk(1, 1) = c*a*(6.0_dp*a*a - 9.0_dp*b*b)/r7
        sp%hk(1, 2) = c*b*(12.0_dp*a*a - 3.0_dp*b*b)/r7
        sp%hk(2, 2) = -3.0_dp*c*a*(a*a - 4.0_dp*b*b)/r7
        sp%hk(1, 3) = (b*b - 2.0_dp*a*a)/r5
        sp%hk(2, 3) = -3.0_dp*a*b/r5
        sp%hk(2, 1) = sp%hk(1, 2)
        sp%hk(3, 1) = sp%hk(1, 3)
        sp%hk(3, 2) = sp%hk(2, 3)
      end if
    end if
  end subroutine strain_state

  !> Rotary inertia with the nonlinear section angle (curvature switch on):
  !> exact theta = phi + atan2(w_x, 1+u_x) (K8), or kear1987's (K9)/(K11).
  !> Adds rho I int theta_q theta_q^T to mp and -rho I int theta_q (theta_dd -
  !> theta_q.q_dd) to fp (local DOFs).
  pure subroutine rotary_nonlinear(el, p, v, jp, pdd_nm, phi_d, phi_dd, rhoi, mp, fp, info)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(8), v(8), jp(8), pdd_nm(8), phi_d, phi_dd, rhoi
    real(dp), intent(inout) :: mp(8, 8), fp(8)
    type(kear_eval_info_t), intent(inout) :: info
    real(dp) :: a, b, xa, xb, tq(8), acc, quad, pd(8)
    integer :: i
    logical :: kear
    kear = el%formulation == formulation_kear1987
    a = 1.0_dp + dot_product(el%gu, p)
    pd = v - phi_d*jp
    do i = 1, el%n_gauss
      b = dot_product(el%gw(:, i), p)
      if (kear) then
        xa = -b                                  ! (K9), (K11): no 1/((1+u_x)^2 + w_x^2)
        xb = a
        quad = 0.0_dp                            ! (K11) omits the velocity-product term
      else
        call exact_angle_terms(a, b, el%gu, el%gw(:, i), v, jp, pd, phi_d, el%effects%coupling, xa, xb, quad)
      end if
      tq = xa*el%gu + xb*el%gw(:, i)             ! d theta / d p
      acc = phi_dd + dot_product(tq, pdd_nm) + quad
      call add_rank_one(8, mp, rhoi*el%wg(i), tq)
      fp = fp - rhoi*el%wg(i)*acc*tq
    end do
    info%n_nonlinear_points = info%n_nonlinear_points + el%n_gauss
  end subroutine rotary_nonlinear

  !> Place the six w-functions at local DOFs 2,3,4,6,7,8.
  pure subroutine spread_w(h, sw)
    real(dp), intent(in) :: h(6)
    real(dp), intent(out) :: sw(8)
    sw = [0.0_dp, h(1), h(2), h(3), 0.0_dp, h(4), h(5), h(6)]
  end subroutine spread_w





end module kear_element
