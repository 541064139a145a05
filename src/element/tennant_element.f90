!> Tennant's planar beam element (1985, T1-T30; doc/steady_state.md): linear axial u,
!> quintic Hermite transverse w with nodal deflection, slope and curvature
!> (T17, T18), an optional shear angle alpha interpolated like w (T19, the
!> 14-DOF element), the tracing constants D_k (material), D_b (curvature) and
!> D_g (stretching) of (T12)-(T15), rotatory inertia (T3), the kinetic energy
!> of bending associated with shear (T4), sections of constant area along the
!> element (piecewise integrals, §3.4), slider masses at the ends, and a
!> length Delta(t) that may vary in time (slider on a rotating link, T24).
!>
!> Element DOFs (T23):
!>   slender  q = [U1 W1 th1 m1  U2 W2 th2 m2]
!>   shear    q = [U1 W1 th1 m1 a1 psi1 lam1  U2 W2 th2 m2 a2 psi2 lam2]
!> U, W are GLOBAL X/Y elastic translations (T22 with phi = -gamma, so that
!> links share them at pins); th = w_x, m = w_xx, a = alpha, psi = alpha_x,
!> lam = alpha_xx are local and not rotated.
!>
!> Lagrange's equations of the element (T24, T25) have the form
!>
!>     M(t) q_dd + C(t) q_d + K_e(t) q + f_n(q, t) = F(t)
!>
!> M, C, K_e and F depend on time through the rigid-body motion only; the
!> nonlinearity is confined to the strain energy: f_n = f_int(q) - K_lin q.
!> `tennant_linear_terms` returns M, C, K_e, F; `tennant_nonlinear_terms`
!> returns f_n, the paper's secant matrix K_n (K_n q = f_n) and the tangent
!> d f_n / d q.  Derivation and decisions: doc/steady_state.md §2.  All
!> procedures are pure; constant integrals are computed once per element
!> (every evaluation for an element whose length varies).
module tennant_element
  use kinds, only: dp
  use linalg, only: outer
  use error_status, only: error_t
  use strings, only: str
  use quadrature, only: gauss_legendre, gauss_legendre_interval
  use shape_functions, only: quintic_hermite
  use frame_motion, only: frame_state_t => motion_t   ! (the element frame: end 1, angle, length and rates, T1)
  use material_law, only: ramberg_osgood_t, section_resultants_t, validate_material, section_response, &
                          ro_stress, peak_strain, has_odd_integer_exponent
  implicit none
  private
  public :: tennant_max_dof, tennant_max_sections
  public :: tennant_options_t, tennant_section_t, frame_state_t, tennant_element_t, tennant_info_t
  public :: tennant_stress_t
  public :: tennant_element_init, tennant_linear_terms, tennant_nonlinear_terms, tennant_internal_force
  public :: tennant_kinetic_energy, tennant_strain_energy, tennant_stress_recovery
  public :: tennant_local_field, shape_rates

  integer, parameter :: tennant_max_dof = 14
  integer, parameter :: tennant_max_sections = 16
  integer, parameter :: nmax = tennant_max_dof
  integer, parameter :: n_exact = 6          !< Gauss points per section: exact for degree <= 11
  integer, parameter :: n_depth = 16         !< depth points of the secant for non-odd m, per side of the neutral fibre
  integer, parameter :: n_stress_samples = 40
  !> powers of Delta in the six quintic Hermite functions (T21)
  integer, parameter :: hpow(6) = [0, 1, 2, 0, 1, 2]

  !> The paper's switches.  D_k = D_b = D_g = 0 is the linear analysis.
  type :: tennant_options_t
    real(dp) :: d_k = 0.0_dp              !< material nonlinearity (B term of T6, T7)
    real(dp) :: d_b = 0.0_dp              !< curvature-displacement nonlinearity (T10, T12)
    real(dp) :: d_g = 0.0_dp              !< stretching of the neutral axis (T12)
    logical :: shear = .false.            !< shear angle alpha: 14-DOF element (T13, T19)
    logical :: rotary_inertia = .true.    !< rho I (gamma_t + w_xt)^2 / 2 of (T3)
    logical :: shear_inertia = .true.     !< rho I alpha_t^2 / 2 of (T4); only with shear
    real(dp) :: shear_modulus = 0.0_dp    !< G_xy; 0 = E1 / (2 (1 + poisson))
    real(dp) :: poisson = 0.33_dp
    real(dp) :: shear_factor = 1.0_dp     !< k in k G A (w_x + alpha)^2 / 2; T integrates b dy: k = 1
    integer :: n_gauss = 8                !< points per section for the nonlinear integrals
    real(dp) :: damping_beta = 0.0_dp     !< stiffness-proportional damping on local nodal rates (s)
  end type tennant_options_t

  !> A section of constant width b and depth h from fraction e0 to e1 of the
  !> element length (T §3.4).
  type :: tennant_section_t
    real(dp) :: e0 = 0.0_dp, e1 = 1.0_dp
    real(dp) :: b = 0.0_dp, h = 0.0_dp
  end type tennant_section_t

  !> Constant local integrals at one length (local DOF order, nodal values p).
  type :: local_matrices_t
    real(dp) :: g1(nmax, nmax) = 0.0_dp    !< int rho A S^T S
    real(dp) :: g2(nmax, nmax) = 0.0_dp    !< int rho A S^T J S
    real(dp) :: l0(nmax, 2) = 0.0_dp       !< int rho A S^T
    real(dp) :: l1(nmax, 2) = 0.0_dp       !< int rho A x S^T
    real(dp) :: rot(nmax, nmax) = 0.0_dp   !< int rho I g_w g_w^T (rotatory inertia)
    real(dp) :: r0(nmax) = 0.0_dp          !< int rho I g_w
    real(dp) :: mb(nmax, nmax) = 0.0_dp    !< int rho I s_a s_a^T (T4)
    real(dp) :: k_lin(nmax, nmax) = 0.0_dp !< linear elastic stiffness, with shear
    real(dp) :: k_ba(nmax, nmax) = 0.0_dp  !< its axial and bending part
    ! moving-length terms (zero for a fixed length): shape-function rates at fixed x
    real(dp) :: gt(nmax, nmax) = 0.0_dp, gtt(nmax, nmax) = 0.0_dp, gjt(nmax, nmax) = 0.0_dp
    real(dp) :: rt(nmax, nmax) = 0.0_dp, rtt(nmax, nmax) = 0.0_dp
    real(dp) :: mbt(nmax, nmax) = 0.0_dp, mbtt(nmax, nmax) = 0.0_dp
  end type local_matrices_t

  type :: tennant_element_t
    integer :: nd = 8                     !< DOFs: 8 slender, 14 with shear angle
    integer :: nn = 4                     !< DOFs per node
    logical :: sliding = .false.          !< length varies in time (slider on a rotating link)
    real(dp) :: length = 0.0_dp           !< length of the cached integrals
    type(ramberg_osgood_t) :: material
    type(tennant_options_t) :: opt
    real(dp) :: shear_modulus = 0.0_dp
    real(dp) :: node_mass(2) = 0.0_dp     !< slider masses M1, M2 at the ends (T Fig. 1)
    integer :: n_sections = 1
    real(dp) :: sec_e0(tennant_max_sections) = 0.0_dp, sec_e1(tennant_max_sections) = 1.0_dp
    real(dp) :: sec_b(tennant_max_sections) = 0.0_dp, sec_h(tennant_max_sections) = 0.0_dp
    real(dp) :: fibre_ratio = 1.0_dp      !< c/(h/2): outer fibre of a section given by A, I, c (1 for a rectangle)
    logical :: nonlinear = .false.        !< some tracing constant is on
    real(dp) :: eps_star = huge(1.0_dp)   !< peak strain of the material law (with D_k)
    type(local_matrices_t) :: lm
    ! combinations for a fixed length: M, C/phi_d, K_e parts per phi_dd and phi_d^2, K_lin J_b
    real(dp) :: m_loc(nmax, nmax) = 0.0_dp, c1_loc(nmax, nmax) = 0.0_dp
    real(dp) :: k_eul(nmax, nmax) = 0.0_dp, k_cen(nmax, nmax) = 0.0_dp, k_lin_jb(nmax, nmax) = 0.0_dp
    integer :: n_st = 0                   !< nonlinear stations (n_gauss per section)
    real(dp), allocatable :: st_w(:), st_area(:), st_depth(:)
    real(dp), allocatable :: st_gu(:, :), st_gw(:, :), st_gk(:, :)
  end type tennant_element_t

  !> By-products of a nonlinear evaluation.
  type :: tennant_info_t
    real(dp) :: max_abs_strain = 0.0_dp
    real(dp) :: x_over_l_max_strain = 0.0_dp
    logical :: beyond_peak = .false.
    integer :: n_points = 0               !< nonlinear integrand evaluations (cost measure)
  end type tennant_info_t

  !> Maximum stress in an element (T §3.9).
  type :: tennant_stress_t
    real(dp) :: max_abs_stress = 0.0_dp
    real(dp) :: stress = 0.0_dp
    real(dp) :: x_over_l = 0.0_dp
    integer :: fibre = 0                  !< +1: y = +h/2, -1: y = -h/2
    real(dp) :: max_abs_strain = 0.0_dp
    logical :: beyond_peak = .false.
  end type tennant_stress_t

contains

  ! ------------------------------------------------------------------ set-up

  pure real(dp) function default_shear_modulus(e1, poisson) result(g)
    real(dp), intent(in) :: e1, poisson
    g = e1/(2.0_dp*(1.0_dp + poisson))
  end function default_shear_modulus

  !> Build an element of the given length from sections tiling [0, 1] of it.
  pure subroutine tennant_element_init(el, length, sections, material, opt, err, node_mass, sliding, fibre_ratio)
    type(tennant_element_t), intent(out) :: el
    real(dp), intent(in) :: length
    type(tennant_section_t), intent(in) :: sections(:)
    type(ramberg_osgood_t), intent(in) :: material
    type(tennant_options_t), intent(in) :: opt
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: node_mass(2)
    real(dp), intent(in), optional :: fibre_ratio
    logical, intent(in), optional :: sliding
    integer :: k
    type(ramberg_osgood_t) :: mk

    if (.not. (length > 0.0_dp)) then
      call err%set('tennant element', 'length must be > 0, got '//str(length)); return
    end if
    if (size(sections) < 1 .or. size(sections) > tennant_max_sections) then
      call err%set('tennant element', 'needs 1 to '//str(tennant_max_sections)//' sections, got '// &
                   str(size(sections))); return
    end if
    do k = 1, size(sections)
      if (.not. (sections(k)%b > 0.0_dp .and. sections(k)%h > 0.0_dp)) then
        call err%set('tennant element', 'section '//str(k)//' needs width and depth > 0'); return
      end if
      if (.not. (sections(k)%e1 > sections(k)%e0)) then
        call err%set('tennant element', 'section '//str(k)//' is empty or reversed'); return
      end if
    end do
    do k = 2, size(sections)
      if (abs(sections(k)%e0 - sections(k - 1)%e1) > 1.0e-12_dp) then
        call err%set('tennant element', 'sections must follow each other without gaps'); return
      end if
    end do
    if (abs(sections(1)%e0) > 1.0e-12_dp .or. abs(sections(size(sections))%e1 - 1.0_dp) > 1.0e-12_dp) then
      call err%set('tennant element', 'sections must cover the element from e = 0 to 1'); return
    end if
    call validate_material(material, err)
    if (err%failed()) return
    if (any(.not. ([opt%d_k, opt%d_b, opt%d_g] >= 0.0_dp .and. [opt%d_k, opt%d_b, opt%d_g] <= 1.0_dp))) then
      call err%set('tennant element', 'tracing constants must lie in [0, 1]'); return
    end if
    if (opt%n_gauss < n_exact .or. opt%n_gauss > 64) then
      call err%set('tennant element', 'n_gauss must lie in 6..64, got '//str(opt%n_gauss)); return
    end if
    if (.not. (opt%damping_beta >= 0.0_dp)) then
      call err%set('tennant element', 'damping beta must be >= 0'); return
    end if
    if (opt%shear) then
      if (.not. (opt%shear_factor > 0.0_dp)) then
        call err%set('tennant element', 'shear factor must be > 0'); return
      end if
      if (.not. (opt%shear_modulus >= 0.0_dp)) then
        call err%set('tennant element', 'shear modulus must be >= 0 (0 = default)'); return
      end if
      if (opt%shear_modulus <= 0.0_dp .and. .not. (opt%poisson > -1.0_dp .and. opt%poisson < 0.5_dp)) then
        call err%set('tennant element', 'Poisson ratio must lie in (-1, 0.5)'); return
      end if
    end if

    el%length = length
    el%material = material
    el%opt = opt
    el%nd = merge(14, 8, opt%shear)
    el%nn = el%nd/2
    el%n_sections = size(sections)
    el%sec_e0(1:el%n_sections) = sections%e0
    el%sec_e1(1:el%n_sections) = sections%e1
    el%sec_b(1:el%n_sections) = sections%b
    el%sec_h(1:el%n_sections) = sections%h
    if (present(fibre_ratio)) el%fibre_ratio = fibre_ratio
    el%shear_modulus = opt%shear_modulus
    if (opt%shear .and. el%shear_modulus <= 0.0_dp) el%shear_modulus = default_shear_modulus(material%e1, opt%poisson)
    if (present(node_mass)) then
      if (any(.not. (node_mass >= 0.0_dp))) then
        call err%set('tennant element', 'slider masses must be >= 0'); return
      end if
      el%node_mass = node_mass
    end if
    if (present(sliding)) el%sliding = sliding
    if (el%sliding .and. el%n_sections > 1) then
      call err%set('tennant element', 'an element whose length varies (slider on a rotating link) must have '// &
                   'one uniform section'); return
    end if
    el%nonlinear = opt%d_k > 0.0_dp .or. opt%d_b > 0.0_dp .or. opt%d_g > 0.0_dp
    mk = material
    mk%e2 = opt%d_k*material%e2
    el%eps_star = peak_strain(mk)

    call build_matrices(el, length, 0.0_dp, 0.0_dp, el%lm)
    call precombine(el)
    if (el%nonlinear) call make_stations(el, length, el%n_st, el%st_w, el%st_area, el%st_depth, &
                                         el%st_gu, el%st_gw, el%st_gk)
  end subroutine tennant_element_init

  ! ------------------------------------------------------------------ shape vectors

  !> Shape vectors in the local DOF space at e = x / l: u = su.p, w = sw.p,
  !> alpha = sa.p; gu = du_x/dp, gw = dw_x/dp, gk = d kappa_lin/dp (w_xx,
  !> or -alpha_x with shear: T12 writes the bending strain y alpha_x),
  !> gs = d gamma_xy/dp = gw + sa (T13).
  pure subroutine station(el, e, l, su, sw, sa, gu, gw, gk, gs)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: e, l
    real(dp), intent(out), dimension(:) :: su, sw, sa, gu, gw, gk, gs
    real(dp) :: h(6), hx(6), hxx(6)
    integer :: iw(6), ia(6)
    call quintic_hermite(e, l, h, hx, hxx)
    su = 0.0_dp; sw = 0.0_dp; sa = 0.0_dp; gu = 0.0_dp; gw = 0.0_dp; gk = 0.0_dp; gs = 0.0_dp
    su(1) = 1.0_dp - e
    su(el%nn + 1) = e
    gu(1) = -1.0_dp/l
    gu(el%nn + 1) = 1.0_dp/l
    iw = w_slots(el)
    sw(iw) = h
    gw(iw) = hx
    if (el%opt%shear) then
      ia = a_slots(el)
      sa(ia) = h
      gk(ia) = -hx
      gs = gw + sa
    else
      gk(iw) = hxx
    end if
  end subroutine station

  pure function w_slots(el) result(iw)
    type(tennant_element_t), intent(in) :: el
    integer :: iw(6)
    iw = [2, 3, 4, el%nn + 2, el%nn + 3, el%nn + 4]
  end function w_slots

  pure function a_slots(el) result(ia)
    type(tennant_element_t), intent(in) :: el
    integer :: ia(6)
    ia = [5, 6, 7, el%nn + 5, el%nn + 6, el%nn + 7]
  end function a_slots

  !> Time derivatives at fixed x of a shape function Delta^k f(x/Delta) when
  !> the length Delta(t) varies (T24): with e = x/Delta,
  !>   d/dt  = Delta_d Delta^(k-1) (k f - e f')
  !>   d2/dt2 = Delta_d^2 Delta^(k-2) (k(k-1) f - 2(k-1) e f' + e^2 f'') + Delta_dd Delta^(k-1) (k f - e f')
  elemental subroutine shape_rates(k, f, fp, fpp, e, l, ld, ldd, vt, vtt)
    integer, intent(in) :: k
    real(dp), intent(in) :: f, fp, fpp, e, l, ld, ldd
    real(dp), intent(out) :: vt, vtt
    real(dp) :: d1, d2, rk
    rk = real(k, dp)
    d1 = l**(k - 1)*(rk*f - e*fp)
    d2 = l**(k - 2)*(rk*(rk - 1.0_dp)*f - 2.0_dp*(rk - 1.0_dp)*e*fp + e*e*fpp)
    vt = ld*d1
    vtt = ld*ld*d2 + ldd*d1
  end subroutine shape_rates

  !> Rates at fixed x of su, sw, sa and gw for a varying length.
  pure subroutine station_rates(el, e, l, ld, ldd, sut, swt, sat, gwt, sutt, swtt, satt, gwtt)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: e, l, ld, ldd
    real(dp), intent(out), dimension(:) :: sut, swt, sat, gwt, sutt, swtt, satt, gwtt
    real(dp) :: f(6), fp(6), fpp(6), fppp(6), vt(6), vtt(6), wt(6), wtt(6), ut(2), utt(2)
    call quintic_hermite(e, 1.0_dp, f, fp, fpp, fppp)
    sut = 0.0_dp; swt = 0.0_dp; sat = 0.0_dp; gwt = 0.0_dp
    sutt = 0.0_dp; swtt = 0.0_dp; satt = 0.0_dp; gwtt = 0.0_dp
    call shape_rates(0, [1.0_dp - e, e], [-1.0_dp, 1.0_dp], [0.0_dp, 0.0_dp], e, l, ld, ldd, ut, utt)
    sut([1, el%nn + 1]) = ut
    sutt([1, el%nn + 1]) = utt
    call shape_rates(hpow, f, fp, fpp, e, l, ld, ldd, vt, vtt)
    call shape_rates(hpow - 1, fp, fpp, fppp, e, l, ld, ldd, wt, wtt)
    swt(w_slots(el)) = vt
    swtt(w_slots(el)) = vtt
    gwt(w_slots(el)) = wt
    gwtt(w_slots(el)) = wtt
    if (el%opt%shear) then
      sat(a_slots(el)) = vt
      satt(a_slots(el)) = vtt
    end if
  end subroutine station_rates

  !> Section properties: rectangle b x h.
  pure subroutine section_props(el, k, area, inertia)
    type(tennant_element_t), intent(in) :: el
    integer, intent(in) :: k
    real(dp), intent(out) :: area, inertia
    area = el%sec_b(k)*el%sec_h(k)
    inertia = el%sec_b(k)*el%sec_h(k)**3/12.0_dp
  end subroutine section_props

  !> The constant integrals of the element at length l (exact 6-point rule per
  !> section); with a varying length also the integrals of the shape-function
  !> rates (ld, ldd).
  pure subroutine build_matrices(el, l, ld, ldd, lm)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: l, ld, ldd
    type(local_matrices_t), intent(out) :: lm
    real(dp) :: xg(n_exact), wg(n_exact), x, e, w, area, inertia, ra, ri, e1, kga
    real(dp), dimension(el%nd) :: su, sw, sa, gu, gw, gk, gs, sut, swt, sat, gwt, sutt, swtt, satt, gwtt
    integer :: k, i, n
    logical :: rates
    n = el%nd
    e1 = el%material%e1
    rates = el%sliding .and. (abs(ld) > 0.0_dp .or. abs(ldd) > 0.0_dp)
    do k = 1, el%n_sections
      call gauss_legendre_interval(n_exact, el%sec_e0(k)*l, el%sec_e1(k)*l, xg, wg)
      call section_props(el, k, area, inertia)
      ra = el%material%rho*area
      ri = el%material%rho*inertia
      kga = el%opt%shear_factor*el%shear_modulus*area
      do i = 1, n_exact
        x = xg(i)
        e = x/l
        w = wg(i)
        call station(el, e, l, su, sw, sa, gu, gw, gk, gs)
        lm%g1(1:n, 1:n) = lm%g1(1:n, 1:n) + (w*ra)*(outer(su, su) + outer(sw, sw))
        lm%g2(1:n, 1:n) = lm%g2(1:n, 1:n) + (w*ra)*(outer(sw, su) - outer(su, sw))
        lm%l0(1:n, 1) = lm%l0(1:n, 1) + (w*ra)*su
        lm%l0(1:n, 2) = lm%l0(1:n, 2) + (w*ra)*sw
        lm%l1(1:n, 1) = lm%l1(1:n, 1) + (w*ra*x)*su
        lm%l1(1:n, 2) = lm%l1(1:n, 2) + (w*ra*x)*sw
        if (el%opt%rotary_inertia) then
          lm%rot(1:n, 1:n) = lm%rot(1:n, 1:n) + (w*ri)*outer(gw, gw)
          lm%r0(1:n) = lm%r0(1:n) + (w*ri)*gw
        end if
        if (el%opt%shear .and. el%opt%shear_inertia) lm%mb(1:n, 1:n) = lm%mb(1:n, 1:n) + (w*ri)*outer(sa, sa)
        lm%k_ba(1:n, 1:n) = lm%k_ba(1:n, 1:n) + w*(e1*area*outer(gu, gu) + e1*inertia*outer(gk, gk))
        if (el%opt%shear) lm%k_lin(1:n, 1:n) = lm%k_lin(1:n, 1:n) + (w*kga)*outer(gs, gs)
        if (rates) then
          call station_rates(el, e, l, ld, ldd, sut, swt, sat, gwt, sutt, swtt, satt, gwtt)
          lm%gt(1:n, 1:n) = lm%gt(1:n, 1:n) + (w*ra)*(outer(su, sut) + outer(sw, swt))
          lm%gtt(1:n, 1:n) = lm%gtt(1:n, 1:n) + (w*ra)*(outer(su, sutt) + outer(sw, swtt))
          lm%gjt(1:n, 1:n) = lm%gjt(1:n, 1:n) + (w*ra)*(outer(sw, sut) - outer(su, swt))
          if (el%opt%rotary_inertia) then
            lm%rt(1:n, 1:n) = lm%rt(1:n, 1:n) + (w*ri)*outer(gw, gwt)
            lm%rtt(1:n, 1:n) = lm%rtt(1:n, 1:n) + (w*ri)*outer(gw, gwtt)
          end if
          if (el%opt%shear .and. el%opt%shear_inertia) then
            lm%mbt(1:n, 1:n) = lm%mbt(1:n, 1:n) + (w*ri)*outer(sa, sat)
            lm%mbtt(1:n, 1:n) = lm%mbtt(1:n, 1:n) + (w*ri)*outer(sa, satt)
          end if
        end if
      end do
    end do
    lm%k_lin = lm%k_lin + lm%k_ba
  end subroutine build_matrices

  !> Stations of the nonlinear integrals: n_gauss per section at length l.
  pure subroutine make_stations(el, l, n_st, sw_, sarea, sdepth, sgu, sgw, sgk)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: l
    integer, intent(out) :: n_st
    real(dp), allocatable, intent(out) :: sw_(:), sarea(:), sdepth(:), sgu(:, :), sgw(:, :), sgk(:, :)
    real(dp) :: xg(el%opt%n_gauss), wg(el%opt%n_gauss), area, inertia
    real(dp), dimension(el%nd) :: su, sw, sa, gs
    integer :: k, i, j, ng
    ng = el%opt%n_gauss
    n_st = ng*el%n_sections
    allocate(sw_(n_st), sarea(n_st), sdepth(n_st), sgu(el%nd, n_st), sgw(el%nd, n_st), sgk(el%nd, n_st))
    j = 0
    do k = 1, el%n_sections
      call gauss_legendre_interval(ng, el%sec_e0(k)*l, el%sec_e1(k)*l, xg, wg)
      call section_props(el, k, area, inertia)
      do i = 1, ng
        j = j + 1
        sw_(j) = wg(i)
        sarea(j) = area
        sdepth(j) = el%sec_h(k)
        call station(el, xg(i)/l, l, su, sw, sa, sgu(:, j), sgw(:, j), sgk(:, j), gs)
      end do
    end do
  end subroutine make_stations

  ! ------------------------------------------------------------------ local <-> global

  !> Local nodal values p = T(phi) q: (u, w) = A^T (U, W) at both nodes (T22).
  pure function tennant_local_dofs(el, phi, q) result(p)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: phi, q(:)
    real(dp) :: p(el%nd), c, s
    integer :: k, i
    c = cos(phi)
    s = sin(phi)
    p = q(1:el%nd)
    do k = 0, 1
      i = 1 + k*el%nn
      p(i) = c*q(i) + s*q(i + 1)
      p(i + 1) = -s*q(i) + c*q(i + 1)
    end do
  end function tennant_local_dofs

  !> T^T f (local forces to global).
  pure function to_global(el, c, s, f) result(g)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: c, s, f(:)
    real(dp) :: g(el%nd)
    integer :: k, i
    g = f(1:el%nd)
    do k = 0, 1
      i = 1 + k*el%nn
      g(i) = c*f(i) - s*f(i + 1)
      g(i + 1) = s*f(i) + c*f(i + 1)
    end do
  end function to_global

  !> a := T^T a T in place.
  pure subroutine rotate_matrix(el, c, s, a)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: c, s
    real(dp), intent(inout) :: a(:, :)
    real(dp) :: col(el%nd), row(el%nd)
    integer :: k, i, n
    n = el%nd
    do k = 0, 1
      i = 1 + k*el%nn
      col = a(1:n, i)
      a(1:n, i) = c*col - s*a(1:n, i + 1)
      a(1:n, i + 1) = s*col + c*a(1:n, i + 1)
    end do
    do k = 0, 1
      i = 1 + k*el%nn
      row = a(i, 1:n)
      a(i, 1:n) = c*row - s*a(i + 1, 1:n)
      a(i + 1, 1:n) = s*row + c*a(i + 1, 1:n)
    end do
  end subroutine rotate_matrix

  !> a J_b: J_b turns each translation pair (u, w) into (-w, u).
  pure function jb_right(el, a) result(r)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: a(:, :)
    real(dp) :: r(el%nd, el%nd)
    integer :: k, i, n
    n = el%nd
    r = 0.0_dp
    do k = 0, 1
      i = 1 + k*el%nn
      r(:, i) = a(1:n, i + 1)
      r(:, i + 1) = -a(1:n, i)
    end do
  end function jb_right

  !> a J_b^2 (= -a on the translation columns, 0 elsewhere): J_b applied twice
  !> (only copies and sign changes: the same values).
  pure function jb2_right(el, a) result(r)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: a(:, :)
    real(dp) :: r(el%nd, el%nd)
    r = jb_right(el, jb_right(el, a))
  end function jb2_right

  !> J_b^T v.
  pure function jbt(el, v) result(r)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: v(:)
    real(dp) :: r(el%nd)
    integer :: k, i
    r = 0.0_dp
    do k = 0, 1
      i = 1 + k*el%nn
      r(i) = v(i + 1)
      r(i + 1) = -v(i)
    end do
  end function jbt

  !> The phi-independent combinations of the constant integrals (fixed length):
  !>   M_loc = G1 + R + M_B + slider masses,   C_loc = phi_d C1,
  !>   K_loc = K_lin + phi_dd K_eul + phi_d^2 K_cen
  !> with C1 = 2 (G2 - G1 J_b) - 2 R J_b, K_eul = G2 - G1 J_b - R J_b,
  !> K_cen = G1 J_b^2 - G1 - 2 G2 J_b + R J_b^2 (see tennant_linear_terms).
  pure subroutine precombine(el)
    type(tennant_element_t), intent(inout) :: el
    integer :: n, k, i
    n = el%nd
    associate (lm => el%lm)
      el%m_loc(1:n, 1:n) = lm%g1(1:n, 1:n)
      el%k_eul(1:n, 1:n) = lm%g2(1:n, 1:n) - jb_right(el, lm%g1)
      el%k_cen(1:n, 1:n) = jb2_right(el, lm%g1) - lm%g1(1:n, 1:n) - 2.0_dp*jb_right(el, lm%g2)
      if (el%opt%rotary_inertia) then
        el%m_loc(1:n, 1:n) = el%m_loc(1:n, 1:n) + lm%rot(1:n, 1:n)
        el%k_eul(1:n, 1:n) = el%k_eul(1:n, 1:n) - jb_right(el, lm%rot)
        el%k_cen(1:n, 1:n) = el%k_cen(1:n, 1:n) + jb2_right(el, lm%rot)
      end if
      el%c1_loc(1:n, 1:n) = 2.0_dp*el%k_eul(1:n, 1:n)
      if (el%opt%shear .and. el%opt%shear_inertia) el%m_loc(1:n, 1:n) = el%m_loc(1:n, 1:n) + lm%mb(1:n, 1:n)
      do k = 0, 1
        do i = 1 + k*el%nn, 2 + k*el%nn
          el%m_loc(i, i) = el%m_loc(i, i) + el%node_mass(k + 1)
        end do
      end do
      el%k_lin_jb(1:n, 1:n) = jb_right(el, lm%k_lin)
    end associate
  end subroutine precombine

  ! ------------------------------------------------------------------ linear terms

  !> M, C, K_e and F of (T25) for this element at the frame state fs, in
  !> global DOFs.  Lagrange's equations of the kinetic energy (T3, T4) with
  !> r = R1 + A(phi) [(x + u), w]: translational inertia int rho A B^T r_dd,
  !> rotatory inertia rho I theta_dd theta_q (theta = gamma + w_x), shear
  !> inertia rho I alpha_dd alpha_q; with a varying length also the rates of
  !> the shape functions at fixed x and the moving upper limit of (T24).
  !> With_damping adds -beta K_lin p_dot_rel (C and a K part).
  pure subroutine tennant_linear_terms(el, fs, mass, damp, stiff, force, with_damping)
    type(tennant_element_t), intent(in) :: el
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: with_damping
    if (el%sliding) then
      call combine_moving(el, fs, mass, damp, stiff, force, with_damping)
    else
      call combine(el, el%lm, fs, mass, damp, stiff, force, with_damping)
    end if
  end subroutine tennant_linear_terms

  !> (A separate routine: its 25 kB of local integrals are only set up for a
  !> moving length.)
  pure subroutine combine_moving(el, fs, mass, damp, stiff, force, with_damping)
    type(tennant_element_t), intent(in) :: el
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: with_damping
    type(local_matrices_t) :: lm
    call build_matrices(el, fs%length, fs%length_d, fs%length_dd, lm)
    call combine(el, lm, fs, mass, damp, stiff, force, with_damping)
  end subroutine combine_moving

  pure subroutine combine(el, lm, fs, mass, damp, stiff, force, with_damping)
    type(tennant_element_t), intent(in) :: el
    type(local_matrices_t), intent(in) :: lm
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(out) :: mass(:, :), damp(:, :), stiff(:, :), force(:)
    logical, intent(in) :: with_damping
    real(dp) :: c, s, pd, pdd, ar(2), a2(2), l, ld, ldd
    real(dp) :: cc(el%nd, el%nd)
    integer :: n, i2
    n = el%nd
    c = cos(fs%phi)
    s = sin(fs%phi)
    pd = fs%phi_d
    pdd = fs%phi_dd
    l = fs%length
    ld = fs%length_d
    ldd = fs%length_dd
    ! rigid acceleration of end 1 in local axes
    ar = [c*fs%x1_dd + s*fs%y1_dd, -s*fs%x1_dd + c*fs%y1_dd]

    if (.not. el%sliding) then
      ! precombined constant matrices (precombine)
      mass(1:n, 1:n) = el%m_loc(1:n, 1:n)
      damp(1:n, 1:n) = pd*el%c1_loc(1:n, 1:n)
      stiff(1:n, 1:n) = el%lm%k_lin(1:n, 1:n) + pdd*el%k_eul(1:n, 1:n) + (pd*pd)*el%k_cen(1:n, 1:n)
      force(1:n) = -(lm%l0(1:n, 1)*ar(1) + lm%l0(1:n, 2)*ar(2) - (pd*pd)*lm%l1(1:n, 1) + pdd*lm%l1(1:n, 2))
      if (el%opt%rotary_inertia) force(1:n) = force(1:n) - pdd*lm%r0(1:n)
      if (el%node_mass(1) > 0.0_dp) force(1:2) = force(1:2) - el%node_mass(1)*ar
      if (el%node_mass(2) > 0.0_dp) then
        a2 = ar + [ldd - l*pd*pd, 2.0_dp*ld*pd + l*pdd]
        force(el%nn + 1:el%nn + 2) = force(el%nn + 1:el%nn + 2) - el%node_mass(2)*a2
      end if
      if (with_damping .and. el%opt%damping_beta > 0.0_dp) then
        damp(1:n, 1:n) = damp(1:n, 1:n) + el%opt%damping_beta*lm%k_lin(1:n, 1:n)
        stiff(1:n, 1:n) = stiff(1:n, 1:n) - (el%opt%damping_beta*pd)*el%k_lin_jb(1:n, 1:n)
      end if
      call rotate_matrix(el, c, s, mass)
      call rotate_matrix(el, c, s, damp)
      call rotate_matrix(el, c, s, stiff)
      force(1:n) = to_global(el, c, s, force)
      return
    end if

    ! translational inertia: Euler/Coriolis operator Cc = G2 - G1 J_b, centrifugal Kc
    cc = lm%g2(1:n, 1:n) - jb_right(el, lm%g1)
    mass(1:n, 1:n) = lm%g1(1:n, 1:n)
    damp(1:n, 1:n) = (2.0_dp*pd)*cc
    stiff(1:n, 1:n) = lm%k_lin(1:n, 1:n) + pdd*cc &
                      + (pd*pd)*(jb2_right(el, lm%g1) - lm%g1(1:n, 1:n) - 2.0_dp*jb_right(el, lm%g2))
    force(1:n) = -(lm%l0(1:n, 1)*ar(1) + lm%l0(1:n, 2)*ar(2) - (pd*pd)*lm%l1(1:n, 1) + pdd*lm%l1(1:n, 2))
    ! rotatory inertia (T3): theta = gamma + w_x
    if (el%opt%rotary_inertia) then
      mass(1:n, 1:n) = mass(1:n, 1:n) + lm%rot(1:n, 1:n)
      damp(1:n, 1:n) = damp(1:n, 1:n) - (2.0_dp*pd)*jb_right(el, lm%rot)
      stiff(1:n, 1:n) = stiff(1:n, 1:n) - pdd*jb_right(el, lm%rot) + (pd*pd)*jb2_right(el, lm%rot)
      force(1:n) = force(1:n) - pdd*lm%r0(1:n)
    end if
    ! bending kinetic energy of the shear angle (T4)
    if (el%opt%shear .and. el%opt%shear_inertia) mass(1:n, 1:n) = mass(1:n, 1:n) + lm%mb(1:n, 1:n)
    ! slider masses at the ends: 1/2 M |R_dot + (U_dot, W_dot)|^2
    if (el%node_mass(1) > 0.0_dp) then
      do i2 = 1, 2
        mass(i2, i2) = mass(i2, i2) + el%node_mass(1)
      end do
      force(1:2) = force(1:2) - el%node_mass(1)*ar
    end if
    if (el%node_mass(2) > 0.0_dp) then
      a2 = ar + [ldd - l*pd*pd, 2.0_dp*ld*pd + l*pdd]
      do i2 = el%nn + 1, el%nn + 2
        mass(i2, i2) = mass(i2, i2) + el%node_mass(2)
      end do
      force(el%nn + 1:el%nn + 2) = force(el%nn + 1:el%nn + 2) - el%node_mass(2)*a2
    end if
    ! a length that varies in time (T24)
    if (el%sliding) call add_moving_length_terms(el, lm, fs, c, s, damp, stiff, force)
    ! stiffness-proportional damping on the rates of the local nodal values
    if (with_damping .and. el%opt%damping_beta > 0.0_dp) then
      damp(1:n, 1:n) = damp(1:n, 1:n) + el%opt%damping_beta*lm%k_lin(1:n, 1:n)
      stiff(1:n, 1:n) = stiff(1:n, 1:n) - (el%opt%damping_beta*pd)*jb_right(el, lm%k_lin)
    end if

    call rotate_matrix(el, c, s, mass)
    call rotate_matrix(el, c, s, damp)
    call rotate_matrix(el, c, s, stiff)
    force(1:n) = to_global(el, c, s, force)
  end subroutine combine

  !> Terms of a length Delta(t) that varies (T24), in local DOFs: the rates of
  !> the shape functions at fixed x inside the element, and the moving upper
  !> limit, + Delta_d (d KE density / d q_dot) at x = Delta.
  pure subroutine add_moving_length_terms(el, lm, fs, c, s, damp, stiff, force)
    type(tennant_element_t), intent(in) :: el
    type(local_matrices_t), intent(in) :: lm
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(in) :: c, s
    real(dp), intent(inout) :: damp(:, :), stiff(:, :), force(:)
    real(dp), dimension(el%nd) :: su, sw, sa, gu, gw, gk, gs, sut, swt, sat, gwt, sutt, swtt, satt, gwtt
    real(dp) :: vr(2), area, inertia, ra, ri, pd, l, ld
    real(dp) :: sts(el%nd, el%nd)
    integer :: n
    n = el%nd
    pd = fs%phi_d
    l = fs%length
    ld = fs%length_d
    damp(1:n, 1:n) = damp(1:n, 1:n) + 2.0_dp*(lm%gt(1:n, 1:n) + lm%rt(1:n, 1:n) + lm%mbt(1:n, 1:n))
    stiff(1:n, 1:n) = stiff(1:n, 1:n) + lm%gtt(1:n, 1:n) + (2.0_dp*pd)*(lm%gjt(1:n, 1:n) - jb_right(el, lm%gt)) &
                      + lm%rtt(1:n, 1:n) - (2.0_dp*pd)*jb_right(el, lm%rt) + lm%mbtt(1:n, 1:n)
    if (.not. abs(ld) > 0.0_dp) return
    call station(el, 1.0_dp, l, su, sw, sa, gu, gw, gk, gs)
    call station_rates(el, 1.0_dp, l, ld, fs%length_dd, sut, swt, sat, gwt, sutt, swtt, satt, gwtt)
    call section_props(el, el%n_sections, area, inertia)
    ra = el%material%rho*area
    ri = el%material%rho*inertia
    vr = [c*fs%x1_d + s*fs%y1_d, -s*fs%x1_d + c*fs%y1_d]
    sts = outer(su, su) + outer(sw, sw)
    damp(1:n, 1:n) = damp(1:n, 1:n) + (ld*ra)*sts
    stiff(1:n, 1:n) = stiff(1:n, 1:n) + (ld*ra)*(outer(su, sut) + outer(sw, swt) &
                      + pd*(outer(sw, su) - outer(su, sw) - jb_right(el, sts)))
    force(1:n) = force(1:n) - (ld*ra)*(su*vr(1) + sw*(vr(2) + pd*l))
    if (el%opt%rotary_inertia) then
      damp(1:n, 1:n) = damp(1:n, 1:n) + (ld*ri)*outer(gw, gw)
      stiff(1:n, 1:n) = stiff(1:n, 1:n) + (ld*ri)*outer(gw, gwt - pd*jbt(el, gw))
      force(1:n) = force(1:n) - (ld*ri*pd)*gw
    end if
    if (el%opt%shear .and. el%opt%shear_inertia) then
      damp(1:n, 1:n) = damp(1:n, 1:n) + (ld*ri)*outer(sa, sa)
      stiff(1:n, 1:n) = stiff(1:n, 1:n) + (ld*ri)*outer(sa, sat)
    end if
  end subroutine add_moving_length_terms

  ! ------------------------------------------------------------------ nonlinear terms

  !> f_n = f_int(q) - K_lin q from the strain energy (T14, T15) with the
  !> tracing constants; optionally the paper's secant K_n (K_n q = f_n: the
  !> eps^(m-1) of the stiffness replaced by |eps|^(m-1), geometric factors at
  !> the current slope) and the tangent d f_n / d q.
  pure subroutine tennant_nonlinear_terms(el, q, fs, fn, info, secant, tangent)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:)
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(out) :: fn(:)
    type(tennant_info_t), intent(out) :: info
    real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    fn(1:el%nd) = 0.0_dp
    if (present(secant)) secant(1:el%nd, 1:el%nd) = 0.0_dp
    if (present(tangent)) tangent(1:el%nd, 1:el%nd) = 0.0_dp
    if (.not. el%nonlinear) return
    if (el%sliding) then
      call nonlinear_moving(el, q, fs, fn, info, secant, tangent)
    else
      call nonlinear_at_stations(el, el%n_st, el%st_w, el%st_area, el%st_depth, el%st_gu, el%st_gw, el%st_gk, &
                                 el%lm%k_ba, q, fs%phi, fn, info, secant, tangent)
    end if
  end subroutine tennant_nonlinear_terms

  pure subroutine nonlinear_moving(el, q, fs, fn, info, secant, tangent)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:)
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(out) :: fn(:)
    type(tennant_info_t), intent(out) :: info
    real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    real(dp), allocatable :: w_(:), area_(:), depth_(:), gu_(:, :), gw_(:, :), gk_(:, :)
    type(local_matrices_t) :: lm
    integer :: n_st
    call make_stations(el, fs%length, n_st, w_, area_, depth_, gu_, gw_, gk_)
    call build_matrices(el, fs%length, 0.0_dp, 0.0_dp, lm)
    call nonlinear_at_stations(el, n_st, w_, area_, depth_, gu_, gw_, gk_, lm%k_ba, q, fs%phi, fn, info, &
                               secant, tangent)
  end subroutine nonlinear_moving

  !> The nonlinear integrals at the stations: f = sum w (N de + M dk) - K_ba p
  !> (the linear axial and bending part, integrated exactly by both rules).
  pure subroutine nonlinear_at_stations(el, n_st, sw_, sarea, sdepth, sgu, sgw, sgk, kba, q, phi, fn, info, &
                                        secant, tangent)
    type(tennant_element_t), intent(in) :: el
    integer, intent(in) :: n_st
    real(dp), intent(in), contiguous :: sw_(:), sarea(:), sdepth(:), sgu(:, :), sgw(:, :), sgk(:, :), kba(:, :)
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: fn(:)
    type(tennant_info_t), intent(out) :: info
    real(dp), intent(out), optional :: secant(:, :), tangent(:, :)
    real(dp) :: p(el%nd), de(el%nd), dk(el%nd), ae(el%nd), ak(el%nd), f(el%nd), v1(el%nd), v2(el%nd)
    real(dp) :: ks(el%nd, el%nd), kt(el%nd, el%nd)
    real(dp) :: b, eu, k0, en, kap, q1, cb, cp, cpp, w, e1, dg, db, ds(2, 2), strain, c, s, gg, gk2
    type(section_resultants_t) :: res
    type(ramberg_osgood_t) :: mk
    integer :: j, i, n, j_max
    logical :: want_s, want_t
    want_s = present(secant)
    want_t = present(tangent)
    n = el%nd
    c = cos(phi)
    s = sin(phi)
    p = tennant_local_dofs(el, phi, q)
    mk = el%material
    mk%e2 = el%opt%d_k*el%material%e2
    e1 = el%material%e1
    dg = el%opt%d_g
    db = el%opt%d_b
    f = 0.0_dp
    if (want_s) ks = 0.0_dp
    if (want_t) kt = 0.0_dp
    j_max = 1
    do j = 1, n_st
      w = sw_(j)
      b = dot_product(sgw(:, j), p)
      eu = dot_product(sgu(:, j), p)
      k0 = dot_product(sgk(:, j), p)
      en = eu + 0.5_dp*dg*b*b                     ! (T12) axial part
      if (db > 0.0_dp) then
        q1 = 1.0_dp/(1.0_dp + db*b*b)
        cb = q1*sqrt(q1)                          ! (T10) curvature factor (1 + D_b w_x^2)^(-3/2)
        cp = -3.0_dp*db*b*cb*q1                   ! its derivative in w_x
      else
        q1 = 1.0_dp
        cb = 1.0_dp
        cp = 0.0_dp
      end if
      kap = cb*k0
      if (want_t) then
        res = section_response(mk, sarea(j), sdepth(j), en, kap, el%opt%d_k > 0.0_dp)
      else
        res = section_forces(mk, sarea(j), sdepth(j), en, kap, el%opt%d_k > 0.0_dp)
      end if
      de = sgu(:, j) + (dg*b)*sgw(:, j)           ! d eps_n / dp
      dk = cb*sgk(:, j) + (cp*k0)*sgw(:, j)       ! d kappa / dp
      f = f + (w*res%axial_force)*de + (w*res%moment)*dk
      strain = abs(en) + 0.5_dp*sdepth(j)*abs(kap)
      if (strain > info%max_abs_strain) then
        info%max_abs_strain = strain
        j_max = j
      end if
      if (want_s) then
        ! K_n: [de dk] D_s [ae ak]^T with eps_n = ae . p, kappa = ak . p
        ae = sgu(:, j) + (0.5_dp*dg*b)*sgw(:, j)
        ak = cb*sgk(:, j)
        ds = secant_section(mk, sarea(j), sdepth(j), en, kap)
        v1 = w*(ds(1, 1)*ae + ds(1, 2)*ak)
        v2 = w*(ds(2, 1)*ae + ds(2, 2)*ak)
        do i = 1, n
          ks(:, i) = ks(:, i) + de*v1(i) + dk*v2(i)
        end do
      end if
      if (want_t) then
        cpp = -3.0_dp*db*cb*q1 + 15.0_dp*db*db*b*b*cb*q1*q1
        v1 = w*(res%tangent(1, 1)*de + res%tangent(1, 2)*dk)
        v2 = w*(res%tangent(2, 1)*de + res%tangent(2, 2)*dk)
        gg = w*(res%axial_force*dg + res%moment*cpp*k0)
        gk2 = w*res%moment*cp
        do i = 1, n
          kt(:, i) = kt(:, i) + de*v1(i) + dk*v2(i) + sgw(:, j)*(gg*sgw(i, j) + gk2*sgk(i, j)) &
                     + sgk(:, j)*(gk2*sgw(i, j))
        end do
      end if
    end do
    f = f - matmul(kba(1:n, 1:n), p)
    info%n_points = n_st
    info%x_over_l_max_strain = real(j_max, dp)/real(max(n_st, 1), dp)
    info%beyond_peak = el%opt%d_k > 0.0_dp .and. info%max_abs_strain > el%eps_star
    fn(1:n) = to_global(el, c, s, f)
    if (want_s) then
      ks = ks - kba(1:n, 1:n)
      call rotate_matrix(el, c, s, ks)
      secant(1:n, 1:n) = ks
    end if
    if (want_t) then
      kt = kt - kba(1:n, 1:n)
      call rotate_matrix(el, c, s, kt)
      tangent(1:n, 1:n) = kt
    end if
  end subroutine nonlinear_at_stations

  !> N and M only (no energy, no tangent): the closed forms of module
  !> material_law for the linear law and m = 3, section_response otherwise.
  pure function section_forces(mat, area, depth, eps_n, kappa, nonlinear) result(res)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: area, depth, eps_n, kappa
    logical, intent(in) :: nonlinear
    type(section_resultants_t) :: res
    real(dp) :: ht, s, e2n, s2
    ht = 0.5_dp*depth
    s = ht*kappa
    if (.not. nonlinear .or. .not. mat%e2 > 0.0_dp) then
      res%axial_force = area*mat%e1*eps_n
      res%moment = area*ht*mat%e1*s/3.0_dp
    else if (abs(mat%m - 3.0_dp) <= 0.0_dp) then
      e2n = eps_n*eps_n
      s2 = s*s
      res%axial_force = area*(mat%e1*eps_n - mat%e2*eps_n*(e2n + s2))
      res%moment = area*ht*(mat%e1*s/3.0_dp - mat%e2*s*(e2n + 0.2_dp*s2))
    else
      res = section_response(mat, area, depth, eps_n, kappa, nonlinear)
    end if
  end function section_forces

  !> The paper's secant section stiffness: sigma = E_s eps with
  !> E_s = E1 - E2 |eps|^(m-1) (T6, T7 with the |eps|^(m-1) of §3.6), so that
  !> [N; M] = D_s [eps_n; kappa] exactly.  eps = eps_n - y kappa, y = (h/2) eta.
  pure function secant_section(mat, area, depth, eps_n, kappa) result(ds)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: area, depth, eps_n, kappa
    real(dp) :: ds(2, 2)
    real(dp) :: ht, s, mom(0:2)
    integer :: l
    ht = 0.5_dp*depth
    s = ht*kappa
    if (abs(mat%m - 3.0_dp) <= 0.0_dp) then
      ! m = 3: <(en - eta s)^2> = en^2 + s^2/3, <eta (.)^2> = -2 en s/3, <eta^2 (.)^2> = en^2/3 + s^2/5
      mom(0) = mat%e1 - mat%e2*(eps_n*eps_n + s*s/3.0_dp)
      mom(1) = mat%e2*2.0_dp*eps_n*s/3.0_dp
      mom(2) = mat%e1/3.0_dp - mat%e2*(eps_n*eps_n/3.0_dp + 0.2_dp*s*s)
    else
      do l = 0, 2
        mom(l) = mat%e1*eta_power_mean(l) - mat%e2*abs_power_mean(mat, l, eps_n, s)
      end do
    end if
    ds(1, 1) = area*mom(0)
    ds(1, 2) = -area*ht*mom(1)
    ds(2, 1) = ds(1, 2)
    ds(2, 2) = area*ht*ht*mom(2)
  end function secant_section

  pure real(dp) function eta_power_mean(k) result(v)
    integer, intent(in) :: k
    if (mod(k, 2) == 0) then
      v = 1.0_dp/real(k + 1, dp)
    else
      v = 0.0_dp
    end if
  end function eta_power_mean

  !> <eta^l |eps_n - eta s|^(m-1)> over eta in [-1, 1] (mean).  Odd integer m:
  !> a binomial sum (exact); otherwise Gauss-Legendre on each side of the
  !> neutral fibre, where the integrand is smooth.
  pure real(dp) function abs_power_mean(mat, l, en, s) result(v)
    type(ramberg_osgood_t), intent(in) :: mat
    integer, intent(in) :: l
    real(dp), intent(in) :: en, s
    integer :: j, k
    real(dp) :: binom, xg(n_depth), wg(n_depth), cuts(3), eta0
    integer :: np, ip, i
    if (.not. abs(mat%e2) > 0.0_dp) then
      v = 0.0_dp
      return
    end if
    if (has_odd_integer_exponent(mat)) then
      j = nint(mat%m) - 1                     ! even
      v = 0.0_dp
      binom = 1.0_dp
      do k = 0, j
        if (k > 0) binom = binom*real(j - k + 1, dp)/real(k, dp)
        v = v + binom*en**(j - k)*(-s)**k*eta_power_mean(k + l)
      end do
    else
      np = 2
      cuts(1) = -1.0_dp
      cuts(2) = 1.0_dp
      if (abs(s) > 0.0_dp) then
        eta0 = en/s
        if (abs(eta0) < 1.0_dp) then
          cuts = [-1.0_dp, eta0, 1.0_dp]
          np = 3
        end if
      end if
      v = 0.0_dp
      do ip = 1, np - 1
        call gauss_legendre_interval(n_depth, cuts(ip), cuts(ip + 1), xg, wg)
        do i = 1, n_depth
          v = v + 0.5_dp*wg(i)*xg(i)**l*abs(en - xg(i)*s)**(mat%m - 1.0_dp)
        end do
      end do
    end if
  end function abs_power_mean

  !> f_int = K_lin q + f_n (global): the gradient of the strain energy.
  pure subroutine tennant_internal_force(el, q, fs, f)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:)
    type(frame_state_t), intent(in) :: fs
    real(dp), intent(out) :: f(:)
    real(dp) :: fn(el%nd), kl(el%nd, el%nd)
    type(tennant_info_t) :: info
    type(local_matrices_t) :: lm
    real(dp) :: c, s
    c = cos(fs%phi)
    s = sin(fs%phi)
    if (el%sliding) then
      call build_matrices(el, fs%length, 0.0_dp, 0.0_dp, lm)
      kl = lm%k_lin(1:el%nd, 1:el%nd)
    else
      kl = el%lm%k_lin(1:el%nd, 1:el%nd)
    end if
    call rotate_matrix(el, c, s, kl)
    call tennant_nonlinear_terms(el, q, fs, fn, info)
    f(1:el%nd) = matmul(kl, q(1:el%nd)) + fn
  end subroutine tennant_internal_force

  ! ------------------------------------------------------------------ energies (independent of the matrices)

  !> Kinetic energy (T3) + (T4) + slider masses, evaluated from the position
  !> of the material points r = R1 + A(phi) [(x + u), w] with the material
  !> velocity at fixed x (10 Gauss points per section: exact).
  pure real(dp) function tennant_kinetic_energy(el, q, qd, fs) result(ke)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), qd(:)
    type(frame_state_t), intent(in) :: fs
    integer, parameter :: nk = 10
    real(dp) :: xg(nk), wg(nk), c, s, l, p(el%nd), pd(el%nd), x, e, area, inertia, v(2), vr(2), theta_d, alpha_d
    real(dp), dimension(el%nd) :: su, sw, sa, gu, gw, gk, gs, sut, swt, sat, gwt, sutt, swtt, satt, gwtt
    real(dp) :: r2d(2)
    integer :: k, i, j
    c = cos(fs%phi)
    s = sin(fs%phi)
    l = fs%length
    p = tennant_local_dofs(el, fs%phi, q)
    ! p_dot = T q_dot + (dT/dphi) phi_dot q
    pd = tennant_local_dofs(el, fs%phi, qd)
    do k = 0, 1
      j = 1 + k*el%nn
      pd(j) = pd(j) + fs%phi_d*(-s*q(j) + c*q(j + 1))
      pd(j + 1) = pd(j + 1) + fs%phi_d*(-c*q(j) - s*q(j + 1))
    end do
    vr = [c*fs%x1_d + s*fs%y1_d, -s*fs%x1_d + c*fs%y1_d]
    ke = 0.0_dp
    do k = 1, el%n_sections
      call gauss_legendre_interval(nk, el%sec_e0(k)*l, el%sec_e1(k)*l, xg, wg)
      call section_props(el, k, area, inertia)
      do i = 1, nk
        x = xg(i)
        e = x/l
        call station(el, e, l, su, sw, sa, gu, gw, gk, gs)
        if (el%sliding) then
          call station_rates(el, e, l, fs%length_d, fs%length_dd, sut, swt, sat, gwt, sutt, swtt, satt, gwtt)
        else
          sut = 0.0_dp; swt = 0.0_dp; sat = 0.0_dp; gwt = 0.0_dp
        end if
        ! local components of r_dot: A^T R1_dot + rho_dot + phi_dot J rho
        v(1) = vr(1) + dot_product(su, pd) + dot_product(sut, p) - fs%phi_d*dot_product(sw, p)
        v(2) = vr(2) + dot_product(sw, pd) + dot_product(swt, p) + fs%phi_d*(x + dot_product(su, p))
        ke = ke + 0.5_dp*wg(i)*el%material%rho*area*(v(1)**2 + v(2)**2)
        if (el%opt%rotary_inertia) then
          theta_d = fs%phi_d + dot_product(gw, pd) + dot_product(gwt, p)
          ke = ke + 0.5_dp*wg(i)*el%material%rho*inertia*theta_d**2
        end if
        if (el%opt%shear .and. el%opt%shear_inertia) then
          alpha_d = dot_product(sa, pd) + dot_product(sat, p)
          ke = ke + 0.5_dp*wg(i)*el%material%rho*inertia*alpha_d**2
        end if
      end do
    end do
    ! slider masses: their global velocity is R_dot + (U_dot, W_dot)
    ke = ke + 0.5_dp*el%node_mass(1)*((fs%x1_d + qd(1))**2 + (fs%y1_d + qd(2))**2)
    r2d = [fs%x1_d, fs%y1_d] + fs%length_d*[c, s] + l*fs%phi_d*[-s, c]
    j = el%nn + 1
    ke = ke + 0.5_dp*el%node_mass(2)*((r2d(1) + qd(j))**2 + (r2d(2) + qd(j + 1))**2)
  end function tennant_kinetic_energy

  !> Strain energy (T14, T15; T30 without shear angle) with the tracing
  !> constants, by the n_gauss rule of the nonlinear terms.
  pure real(dp) function tennant_strain_energy(el, q, fs) result(se)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:)
    type(frame_state_t), intent(in) :: fs
    real(dp) :: xg(el%opt%n_gauss), wg(el%opt%n_gauss), p(el%nd), l, area, inertia, b, en, kap, gam
    real(dp), dimension(el%nd) :: su, sw, sa, gu, gw, gk, gs
    type(ramberg_osgood_t) :: mk
    type(section_resultants_t) :: res
    integer :: k, i
    l = fs%length
    p = tennant_local_dofs(el, fs%phi, q)
    mk = el%material
    mk%e2 = el%opt%d_k*el%material%e2
    se = 0.0_dp
    do k = 1, el%n_sections
      call gauss_legendre_interval(el%opt%n_gauss, el%sec_e0(k)*l, el%sec_e1(k)*l, xg, wg)
      call section_props(el, k, area, inertia)
      do i = 1, el%opt%n_gauss
        call station(el, xg(i)/l, l, su, sw, sa, gu, gw, gk, gs)
        b = dot_product(gw, p)
        en = dot_product(gu, p) + 0.5_dp*el%opt%d_g*b*b
        kap = dot_product(gk, p)/(1.0_dp + el%opt%d_b*b*b)**1.5_dp
        res = section_response(mk, area, el%sec_h(k), en, kap, el%opt%d_k > 0.0_dp)
        se = se + wg(i)*res%energy
        if (el%opt%shear) then
          gam = dot_product(gs, p)
          se = se + 0.5_dp*wg(i)*el%opt%shear_factor*el%shear_modulus*area*gam*gam
        end if
      end do
    end do
  end function tennant_strain_energy

  ! ------------------------------------------------------------------ output

  !> Local (u, w, alpha) at fraction e of the element.
  pure function tennant_local_field(el, q, fs, e) result(uwa)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), e
    type(frame_state_t), intent(in) :: fs
    real(dp) :: uwa(3)
    real(dp), dimension(el%nd) :: p, su, sw, sa, gu, gw, gk, gs
    p = tennant_local_dofs(el, fs%phi, q)
    call station(el, e, fs%length, su, sw, sa, gu, gw, gk, gs)
    uwa = [dot_product(su, p), dot_product(sw, p), dot_product(sa, p)]
  end function tennant_local_field

  !> Maximum |stress| over the element (T §3.9): |eps| is largest at an outer
  !> fibre; sample both fibres at 41 stations and refine the best one by a
  !> golden-section search for d eps / dx = 0 between its neighbours.
  pure function tennant_stress_recovery(el, q, fs) result(rep)
    type(tennant_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:)
    type(frame_state_t), intent(in) :: fs
    type(tennant_stress_t) :: rep
    type(ramberg_osgood_t) :: mk
    real(dp) :: p(el%nd), e, sig, eps, best, a, b, x1, x2, f1, f2, eb
    real(dp), parameter :: gr = 0.6180339887498949_dp
    integer :: i, fib, fb, it, ib
    p = tennant_local_dofs(el, fs%phi, q)
    mk = el%material
    mk%e2 = el%opt%d_k*el%material%e2
    best = -1.0_dp
    ib = 0
    fb = 1
    do i = 0, n_stress_samples
      e = real(i, dp)/real(n_stress_samples, dp)
      do fib = 1, -1, -2
        eps = fibre_strain(e, fib)
        if (abs(eps) > best) then
          best = abs(eps)
          ib = i
          fb = fib
        end if
      end do
    end do
    ! golden section on |eps| of that fibre around the best sample
    a = max(0.0_dp, real(ib - 1, dp)/n_stress_samples)
    b = min(1.0_dp, real(ib + 1, dp)/n_stress_samples)
    x1 = b - gr*(b - a)
    x2 = a + gr*(b - a)
    f1 = abs(fibre_strain(x1, fb))
    f2 = abs(fibre_strain(x2, fb))
    do it = 1, 40
      if (f1 > f2) then
        b = x2; x2 = x1; f2 = f1
        x1 = b - gr*(b - a); f1 = abs(fibre_strain(x1, fb))
      else
        a = x1; x1 = x2; f1 = f2
        x2 = a + gr*(b - a); f2 = abs(fibre_strain(x2, fb))
      end if
    end do
    eb = real(ib, dp)/n_stress_samples
    e = 0.5_dp*(a + b)
    if (abs(fibre_strain(e, fb)) < best) e = eb
    eps = fibre_strain(e, fb)
    sig = ro_stress(mk, eps)
    rep%max_abs_stress = abs(sig)
    rep%stress = sig
    rep%x_over_l = e
    rep%fibre = fb
    rep%max_abs_strain = abs(eps)
    rep%beyond_peak = el%opt%d_k > 0.0_dp .and. abs(eps) > el%eps_star
  contains
    pure real(dp) function fibre_strain(ee, fibre) result(es)
      real(dp), intent(in) :: ee
      integer, intent(in) :: fibre
      real(dp), dimension(el%nd) :: su, sw, sa, gu, gw, gk, gs
      real(dp) :: bb, en, kap, depth
      integer :: k
      call station(el, ee, fs%length, su, sw, sa, gu, gw, gk, gs)
      bb = dot_product(gw, p)
      en = dot_product(gu, p) + 0.5_dp*el%opt%d_g*bb*bb
      kap = dot_product(gk, p)/(1.0_dp + el%opt%d_b*bb*bb)**1.5_dp
      depth = el%sec_h(el%n_sections)
      do k = 1, el%n_sections
        if (ee <= el%sec_e1(k)) then
          depth = el%sec_h(k)
          exit
        end if
      end do
      es = en - real(fibre, dp)*el%fibre_ratio*0.5_dp*depth*kap   ! eps = eps_n - y kappa at y = +-c
    end function fibre_strain
  end function tennant_stress_recovery
end module tennant_element
