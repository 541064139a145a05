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
!> with S (2 x 12) in place of Kear's 2 x 8 interpolation: this module binds
!> the interpolation, the station loop and the strain measures to the planar
!> element contract (planar_element), which evaluates them.  All procedures
!> are pure.
module consistent_element
  use kinds, only: dp
  use error_status, only: error_t
  use shape_functions, only: quintic_hermite
  use material_law, only: ramberg_osgood_t, section_resultants_t, section_response
  use element_effects, only: element_effects_t
  use planar_element, only: planar_element_t, rigid_state_t, element_eval_info_t, init_planar_element, &
                            start_strain_terms, finish_strain_terms
  use planar_beam_kernels, only: add_station_terms, rotate_to_global, frame_vectors, in_frame, translational_force, &
                                 frame_acceleration, add_linear_rotary, subtract_elastic_forces, to_global_results, &
                                 exact_angle_terms, add_rank_one
  implicit none
  private
  public :: consistent_element_t, consistent_element_init

  integer, parameter :: consistent_ndof = 12
  integer, parameter :: nd = consistent_ndof
  integer, parameter :: n_strain = 4     !< strain variables u_x, w_x, w_xx, u_xx

  !> One element: the planar element's properties and integrals, local DOF
  !> order p = [u1 w1 th1 m1 a1 b1 u2 w2 th2 m2 a2 b2], strain variables
  !> (u_x, w_x, w_xx, u_xx).
  type, extends(planar_element_t) :: consistent_element_t
  contains
    procedure :: init => consistent_init
    procedure :: eval => consistent_eval
    procedure, nopass :: n_dofs => consistent_n_dofs
    procedure, nopass :: axial_dofs => consistent_axial_dofs
    procedure :: interpolation => consistent_interpolation
    procedure :: strain_terms => consistent_strain_terms
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

  !> Build an element and precompute its constant integrals.
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
    call consistent_init(el, length, width, depth, material, effects, err, n_gauss, damping_beta, &
                         objective_damping, fibre_distance)
  end subroutine consistent_element_init

  !> planar_element_t's init.
  pure subroutine consistent_init(el, length, width, depth, material, effects, err, n_gauss, damping_beta, &
                                  objective_damping, fibre_distance)
    class(consistent_element_t), intent(inout) :: el
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta
    logical, intent(in), optional :: objective_damping
    real(dp), intent(in), optional :: fibre_distance
    call init_planar_element(el, 'consistent_element_init', length, width, depth, material, effects, err, &
                             n_gauss, damping_beta, objective_damping, fibre_distance)
  end subroutine consistent_init

  !> planar_element_t's eval in this element's sizes (planar_evaluation.inc).
  pure subroutine consistent_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, force_wanted)
    class(consistent_element_t), intent(in) :: el
    include 'planar_evaluation.inc'
  end subroutine consistent_eval

  pure integer function consistent_n_dofs()
    consistent_n_dofs = consistent_ndof
  end function consistent_n_dofs

  !> The nodes carry u_x and u_xx (a, b) besides u, w, w_x, w_xx.
  pure logical function consistent_axial_dofs()
    consistent_axial_dofs = .true.
  end function consistent_axial_dofs

  !> Interpolation at x = e l: u = su.p, w = sw.p, both quintic Hermite, and
  !> the gradients g(:, 1:4) of (u_x, w_x, w_xx, u_xx) with respect to p.
  pure subroutine consistent_interpolation(el, e, su, sw, g)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: e
    real(dp), intent(out) :: su(:), sw(:)
    real(dp), intent(out), optional :: g(:, :)
    real(dp) :: h(6), hx(6), hxx(6)
    if (.not. present(g)) then
      call quintic_hermite(e, el%length, h)
      su = spread_u(h)
      sw = spread_w(h)
      return
    end if
    call quintic_hermite(e, el%length, h, hx, hxx)
    su = spread_u(h)
    sw = spread_w(h)
    g(:, 1) = spread_u(hx)
    g(:, 2) = spread_w(hx)
    g(:, 3) = spread_w(hxx)
    g(:, 4) = spread_u(hxx)
  end subroutine consistent_interpolation

  !> planar_element_t's strain_terms: the station loop in fixed sizes.
  pure subroutine consistent_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in), contiguous :: p(:), prel(:)
    logical, intent(in) :: want_k, want_damp
    type(element_eval_info_t), intent(inout) :: info
    real(dp), intent(out), contiguous :: fint(:), fdamp(:)
    real(dp), intent(out) :: kp(size(p), size(p))
    call station_loop(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
  end subroutine consistent_strain_terms

  !> Internal force, tangent K_pp (want_k) and K_pp prel (want_damp); the
  !> strain energy and the largest strain added to info.  Per station f = G (N de + M dk),
  !> K = G H G^T with G = [gu gw gww guu] (12 x 4).
  pure subroutine station_loop(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(nd), prel(nd)
    logical, intent(in) :: want_k, want_damp
    type(element_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(nd), fdamp(nd), kp(nd, nd)
    real(dp) :: e, ht
    type(strain_point_t) :: sp
    type(section_resultants_t) :: res
    integer :: i
    fint = 0.0_dp
    fdamp = 0.0_dp
    kp = 0.0_dp
    ht = 0.5_dp*el%depth
    do i = 1, el%n_gauss
      associate (g => el%g(:, :, i))
        call strain_state(el, strain_variables(p, el%gt(:, :, i)), sp)
        res = section_response(el%material, el%area, el%depth, sp%eps, sp%kap, el%effects%material)
        info%strain_energy = info%strain_energy + el%wg(i)*res%energy
        call add_station_terms(el%wg(i), g, el%gt(:, :, i), res%axial_force, res%moment, res%tangent, sp%de, sp%de, sp%dk, sp%he, &
                               sp%hk, prel, want_k, want_damp, fint, fdamp, kp)
      end associate
      e = abs(sp%eps) + ht*abs(sp%kap)
      call info%note_strain(e, el%xg(i)/el%length)
    end do
  end subroutine station_loop

  !> Axial strain and curvature at x = e l from LOCAL nodal values p.
  pure subroutine consistent_section_strains(el, p, e, eps_n, kap)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:), e
    real(dp), intent(out) :: eps_n, kap
    real(dp) :: pl(nd), su(nd), sw(nd), g(nd, 4)
    pl = p
    call consistent_interpolation(el, e, su, sw, g)
    call strain_values(el, strain_variables(pl, transpose(g)), eps_n, kap)
  end subroutine consistent_section_strains

  !> Axial strain and curvature at every stress station from LOCAL nodal
  !> values p (the tabulated gradients gst).
  pure subroutine consistent_station_strains(el, p, eps_n, kap)
    class(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:)
    real(dp), intent(out) :: eps_n(0:), kap(0:)
    real(dp) :: pl(nd)
    integer :: i
    pl = p
    do i = 0, el%n_gauss + 1
      call strain_values(el, strain_variables(pl, el%gst(:, :, i)), eps_n(i), kap(i))
    end do
  end subroutine consistent_station_strains

  ! ------------------------------------------------------------ internals

  !> z = (u_x, w_x, w_xx, u_xx) = p^T g at a station from the transposed
  !> gradients gt = g^T (4 x 12): each z(k) summed in matmul's order
  !> j = 1, 2, ..., the four at once (matmul on a section of the tabulated
  !> gradients takes a heap temporary on every call).
  pure function strain_variables(p, gt) result(z)
    real(dp), intent(in) :: p(nd), gt(4, nd)
    real(dp) :: z(4)
    integer :: j
    z = 0.0_dp
    do j = 1, nd
      z = z + p(j)*gt(:, j)
    end do
  end function strain_variables

  !> eps_n and kappa from z = (u_x, w_x, w_xx, u_xx), (a, b, c, d) =
  !> (1 + u_x, w_x, w_xx, u_xx):
  !>   eps_n = sqrt(a^2 + b^2) - 1          (stretching on; off: u_x)
  !>   kappa = (c a - b d)/(a^2 + b^2)^1.5  (curvature on; off: w_xx)
  pure subroutine strain_values(el, z, eps, kap)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: z(4)
    real(dp), intent(out) :: eps, kap
    real(dp) :: a, b, r2, r
    a = 1.0_dp + z(1)
    b = z(2)
    r2 = a*a + b*b
    r = sqrt(r2)
    if (el%effects%stretching) then
      eps = (z(1)*(2.0_dp + z(1)) + b*b)/(r + 1.0_dp)      ! r - 1 without cancellation
    else
      eps = z(1)
    end if
    if (el%effects%curvature) then
      kap = (z(3)*a - b*z(4))*(1.0_dp/(r2*r))
    else
      kap = z(3)
    end if
  end subroutine strain_values

  !> strain_values' eps_n and kappa with their derivatives in (a, b, c, d).
  pure subroutine strain_state(el, z, sp)
    type(consistent_element_t), intent(in) :: el
    real(dp), intent(in) :: z(4)
    type(strain_point_t), intent(out) :: sp
    real(dp) :: a, b, c, d, r2, r, r3, f, fa, fb, faa, fab, fbb, n, r5, r7
    call strain_values(el, z, sp%eps, sp%kap)
    a = 1.0_dp + z(1)
    b = z(2)
    c = z(3)
    d = z(4)
    r2 = a*a + b*b
    r = sqrt(r2)
    r3 = r2*r
    if (el%effects%stretching) then
      sp%de = [a/r, b/r, 0.0_dp, 0.0_dp]
      sp%he(1, 1) = b*b/r3
      sp%he(1, 2) = -a*b/r3
      sp%he(2, 1) = -a*b/r3
      sp%he(2, 2) = a*a/r3
    else
      sp%de = [1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
    end if
    if (.not. el%effects%curvature) then
      sp%dk = [0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp]
      return
    end if
    n = c*a - b*d
    f = 1.0_dp/r3
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
