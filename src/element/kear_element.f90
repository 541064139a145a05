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
!> effect switches and the checks are in doc/element.md.  This module binds
!> the element's interpolation, its station loop and its strain measures to
!> the planar element contract (planar_element), which evaluates M_e and F_e
!> and precomputes the constant integrals once per element.  All procedures
!> are pure functions of their arguments.
module kear_element
  use kinds, only: dp
  use linalg, only: outer
  use error_status, only: error_t
  use strings, only: str
  use name_table, only: name_of, code_of
  use shape_functions, only: quintic_hermite, linear_lagrange
  use element_effects, only: element_effects_t
  use material_law, only: ramberg_osgood_t, section_resultants_t, section_response
  use planar_element, only: planar_element_t, rigid_state_t, element_eval_info_t, init_planar_element, &
                            start_strain_terms, finish_strain_terms
  use planar_beam_kernels, only: rotate_to_global, frame_vectors, in_frame, translational_force, frame_acceleration, &
                                 add_linear_rotary, subtract_elastic_forces, to_global_results, exact_angle_terms, &
                                 add_rank_one
  implicit none
  private
  public :: formulation_exact, formulation_kear1987
  public :: kear_element_t, kear_element_init
  public :: formulation_from_name, formulation_name

  integer, parameter :: kear_ndof = 8
  integer, parameter :: nd = kear_ndof
  integer, parameter :: n_strain = 3               !< strain variables u_x, w_x, w_xx
  integer, parameter :: formulation_exact = 1      !< exact Lagrange equations of (K3), (K16)
  integer, parameter :: formulation_kear1987 = 2   !< as printed: (K9), (K11), (K20), (K23)
  character(len=*), parameter :: formulation_table(2) = [character(len=8) :: 'exact', 'kear1987']

  !> One element: the planar element's properties and integrals (local DOF
  !> order p = [u1 w1 th1 m1 u2 w2 th2 m2]; strain variables (u_x, w_x, w_xx))
  !> and the formulation of its equations.
  type, extends(planar_element_t) :: kear_element_t
    integer :: formulation = formulation_exact
  contains
    procedure :: init => kear_init
    procedure :: eval => kear_eval
    procedure, nopass :: n_dofs => kear_n_dofs
    procedure, nopass :: axial_dofs => kear_axial_dofs
    procedure :: interpolation => kear_interpolation
    procedure :: strain_terms => kear_strain_terms
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

  !> Build an element of the given formulation (default exact) and
  !> precompute its constant integrals.
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
    if (present(formulation)) el%formulation = formulation
    call kear_init(el, length, width, depth, material, effects, err, n_gauss, damping_beta, objective_damping, &
                   fibre_distance)
  end subroutine kear_element_init

  !> planar_element_t's init: the element's formulation (kept) checked.
  pure subroutine kear_init(el, length, width, depth, material, effects, err, n_gauss, damping_beta, &
                            objective_damping, fibre_distance)
    class(kear_element_t), intent(inout) :: el
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta
    logical, intent(in), optional :: objective_damping
    real(dp), intent(in), optional :: fibre_distance
    if (el%formulation /= formulation_exact .and. el%formulation /= formulation_kear1987) then
      call err%set('kear_element_init', 'unknown formulation code '//str(el%formulation)); return
    end if
    el%printed_angle = el%formulation == formulation_kear1987
    call init_planar_element(el, 'kear_element_init', length, width, depth, material, effects, err, n_gauss, &
                             damping_beta, objective_damping, fibre_distance)
  end subroutine kear_init

  pure integer function kear_n_dofs()
    kear_n_dofs = kear_ndof
  end function kear_n_dofs

  !> Kear's u is linear on the element: no axial slope DOFs.
  pure logical function kear_axial_dofs()
    kear_axial_dofs = .false.
  end function kear_axial_dofs

  !> The interpolation (K26) at x = e l: linear n1, n2 for u at DOFs 1, 5,
  !> quintic h1..h6 for w at DOFs 2, 3, 4, 6, 7, 8; g = d(u_x, w_x, w_xx)/dp.
  pure subroutine kear_interpolation(el, e, su, sw, g)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: e
    real(dp), intent(out) :: su(:), sw(:)
    real(dp), intent(out), optional :: g(:, :)
    real(dp) :: n(2), h(6), hx(6), hxx(6)
    call linear_lagrange(e, el%length, n)
    su = 0.0_dp
    su(1) = n(1)
    su(5) = n(2)
    if (.not. present(g)) then
      call quintic_hermite(e, el%length, h)
      call spread_w(h, sw)
      return
    end if
    call quintic_hermite(e, el%length, h, hx, hxx)
    call spread_w(h, sw)
    g(:, 1) = 0.0_dp                                   ! u_x = (u2 - u1)/l, constant
    g(1, 1) = -1.0_dp/el%length
    g(5, 1) = 1.0_dp/el%length
    call spread_w(hx, g(:, 2))
    call spread_w(hxx, g(:, 3))
  end subroutine kear_interpolation

  !> planar_element_t's eval in this element's sizes (planar_evaluation.inc).
  pure subroutine kear_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, force_wanted)
    class(kear_element_t), intent(in) :: el
    include 'planar_evaluation.inc'
  end subroutine kear_eval

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

  ! ------------------------------------------------------------ strain terms

  !> planar_element_t's strain_terms: the station loop in fixed sizes.
  pure subroutine kear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in), contiguous :: p(:), prel(:)
    logical, intent(in) :: want_k, want_damp
    type(element_eval_info_t), intent(inout) :: info
    real(dp), intent(out), contiguous :: fint(:), fdamp(:)
    real(dp), intent(out) :: kp(size(p), size(p))
    call station_loop(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
  end subroutine kear_strain_terms

  !> Internal force, tangent K_pp (if want_k) and K_pp prel (if want_damp)
  !> by Gauss quadrature along the element, local DOFs p; the strain energy
  !> and the largest strain added to info.  Per station everything lives in the 3-space
  !> (a, b, c) = (1+u_x, w_x, w_xx): f = G (N de + M dk),  K = G H G^T,
  !> G = [gu gw gww] (8 x 3).
  pure subroutine station_loop(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(8), prel(8)
    logical, intent(in) :: want_k, want_damp
    type(element_eval_info_t), intent(inout) :: info
    real(dp), intent(out) :: fint(8), fdamp(8), kp(8, 8)
    real(dp) :: g(8, 3), h3(3, 3), f3(3), ux, e, ht, tn(3), tk(3), gh(8, 3)
    type(strain_point_t) :: sp
    type(section_resultants_t) :: res
    integer :: i
    fint = 0.0_dp
    fdamp = 0.0_dp
    kp = 0.0_dp
    ht = 0.5_dp*el%depth
    g(:, 1) = el%g(:, 1, 1)                     ! u_x's gradient: the same at every station
    ux = dot_product(g(:, 1), p)
    do i = 1, el%n_gauss
      g(:, 2) = el%g(:, 2, i)
      g(:, 3) = el%g(:, 3, i)
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
  end subroutine station_loop

  !> Axial strain eps_n and curvature kappa at x = e l from LOCAL nodal
  !> values p, with the element's switches.
  pure subroutine kear_section_strains(el, p, e, eps_n, kap)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:), e
    real(dp), intent(out) :: eps_n, kap
    real(dp) :: su(8), sw(8), g(8, 3)
    type(strain_point_t) :: sp
    call kear_interpolation(el, e, su, sw, g)
    call strain_state(el, dot_product(g(:, 1), p), dot_product(g(:, 2), p), dot_product(g(:, 3), p), &
                      .false., sp)
    eps_n = sp%eps
    kap = sp%kap
  end subroutine kear_section_strains

  !> Axial strain and curvature at every stress station from LOCAL nodal
  !> values p (the tabulated gradients gst: u_x, w_x, w_xx).
  pure subroutine kear_station_strains(el, p, eps_n, kap)
    class(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: p(:)
    real(dp), intent(out) :: eps_n(0:), kap(0:)
    type(strain_point_t) :: sp
    integer :: i
    do i = 0, el%n_gauss + 1
      call strain_state(el, dot_product(el%gst(1, :, i), p), dot_product(el%gst(2, :, i), p), &
                        dot_product(el%gst(3, :, i), p), .false., sp)
      eps_n(i) = sp%eps
      kap(i) = sp%kap
    end do
  end subroutine kear_station_strains

  ! ------------------------------------------------------------ internals

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

  !> Place the six w-functions at local DOFs 2,3,4,6,7,8.
  pure subroutine spread_w(h, sw)
    real(dp), intent(in) :: h(6)
    real(dp), intent(out) :: sw(8)
    sw = [0.0_dp, h(1), h(2), h(3), 0.0_dp, h(4), h(5), h(6)]
  end subroutine spread_w
end module kear_element
