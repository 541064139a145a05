!> What Kear's element and the consistent element share above the kernels
!> (doc/element.md): the abstract planar_element_t both extend, the static
!> terms (internal force, tangent stiffness, strain energy) and the stress
!> recovery written once over the steps each element binds -- its nonlinear
!> station terms, the linear model's K p and its section strains -- and the
!> types of the element contract (rigid-body state, an evaluation's
!> by-products, the stress report).
!>
!> The evaluation of M_e and F_e stays in each element, in its fixed sizes: it
!> is the transient analysis' hot path, and written once for any size it cost
!> 4 to 8 % of a transient deck's instructions (runtime-size loops in place of
!> the unrolled 8 x 8 and 12 x 12 products).
module planar_element
  use kinds, only: dp
  use beam_properties, only: beam_properties_t
  use material_law, only: ramberg_osgood_t, ro_stress
  use planar_beam_kernels, only: to_local, to_global, rotate_to_global
  implicit none
  private
  public :: planar_element_t, rigid_state_t, kear_eval_info_t, stress_report_t
  public :: planar_internal_force, planar_tangent_stiffness, planar_strain_energy, planar_stress_recovery
  public :: planar_station_strains, station_x_over_l
  public :: is_linear_strain

  integer, parameter :: max_dofs = 12   !< the consistent element's; work arrays of this size stay off the heap

  !> Rigid-body state of the element reference line (from kinematics).
  type :: rigid_state_t
    real(dp) :: x1 = 0.0_dp, y1 = 0.0_dp, phi = 0.0_dp            !< end 1 and inclination
    real(dp) :: x1_d = 0.0_dp, y1_d = 0.0_dp, phi_d = 0.0_dp      !< first time derivatives
    real(dp) :: x1_dd = 0.0_dp, y1_dd = 0.0_dp, phi_dd = 0.0_dp   !< second time derivatives
  end type rigid_state_t

  !> By-products of one evaluation.
  type :: kear_eval_info_t
    real(dp) :: strain_energy = 0.0_dp
    real(dp) :: max_abs_strain = 0.0_dp     !< over the Gauss points and both outer fibres
    real(dp) :: x_over_l_max_strain = 0.0_dp
    logical :: beyond_peak = .false.        !< material on and max |eps| > eps*
    integer :: n_nonlinear_points = 0       !< cost proxy: nonlinear integrand evaluations
  contains
    procedure :: note_strain
  end type kear_eval_info_t

  !> Stress recovery at the element ends and the Gauss points, both fibres.
  type :: stress_report_t
    real(dp) :: max_abs_stress = 0.0_dp
    real(dp) :: stress = 0.0_dp              !< signed sigma at that point
    real(dp) :: stress_x_over_l = 0.0_dp
    integer :: stress_fibre = 0              !< +1: y = +t/2,  -1: y = -t/2
    real(dp) :: max_abs_strain = 0.0_dp
    real(dp) :: strain = 0.0_dp
    real(dp) :: strain_x_over_l = 0.0_dp
    integer :: strain_fibre = 0
    real(dp) :: eps_star = huge(1.0_dp)
    logical :: beyond_peak = .false.
  end type stress_report_t

  !> A planar element: its properties, the layout of its local DOFs (node 2's
  !> (u, w) at node2, node2 + 1) and the stations of its nonlinear integrals;
  !> the extensions hold their constant integrals and bind their
  !> interpolation's steps.
  type, abstract, extends(beam_properties_t) :: planar_element_t
    integer :: node2 = 0                               !< local DOF of node 2's u (then w)
    real(dp), allocatable :: xg(:), wg(:)              !< stations on [0, l] and weights
    !> (DOFs, strain variables, 0:n_gauss + 1): the gradients of the strain
    !> variables at the stress stations (station_x_over_l), tabulated once
    real(dp), allocatable :: gs(:, :, :)
  contains
    procedure(strain_terms_i), deferred :: strain_terms
    procedure(linear_force_i), deferred :: linear_force
    procedure(section_strains_i), deferred :: section_strains
    procedure(station_strains_i), deferred :: station_strains
  end type planar_element_t

  abstract interface
    !> Strain energy, internal force fint, tangent kp (if want_k) and kp prel
    !> (if want_damp) by the element's quadrature; local DOFs p.
    pure subroutine strain_terms_i(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
      import :: planar_element_t, kear_eval_info_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: p(:), prel(:)
      logical, intent(in) :: want_k, want_damp
      type(kear_eval_info_t), intent(inout) :: info
      real(dp), intent(out) :: fint(:), fdamp(:), kp(size(p), size(p))
    end subroutine strain_terms_i

    !> The linear model's internal force fint = K p and (want_k) its K.
    pure subroutine linear_force_i(el, p, want_k, fint, kp)
      import :: planar_element_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: p(:)
      logical, intent(in) :: want_k
      real(dp), intent(out) :: fint(:), kp(size(p), size(p))
    end subroutine linear_force_i

    !> Axial strain and curvature at x = e l from local nodal values p.
    pure subroutine section_strains_i(el, p, e, eps_n, kap)
      import :: planar_element_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: p(:), e
      real(dp), intent(out) :: eps_n, kap
    end subroutine section_strains_i

    !> Axial strain and curvature at stress station i (0 .. n_gauss + 1,
    !> station_x_over_l) from local nodal values p, by the tabulated gs.
    pure subroutine station_strains_i(el, p, i, eps_n, kap)
      import :: planar_element_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: p(:)
      integer, intent(in) :: i
      real(dp), intent(out) :: eps_n, kap
    end subroutine station_strains_i
  end interface

contains

  !> Internal force dSE/dq (kear1987: the printed (K17) with (K20), (K24)).
  pure subroutine planar_internal_force(el, q, phi, f)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: f(:)
    real(dp) :: fint(max_dofs), kp(max_dofs*max_dofs), se
    call static_strain_terms(el, q, phi, .false., fint, kp, se)
    f = to_global(cos(phi), sin(phi), fint(:size(q)), el%node2)
  end subroutine planar_internal_force

  !> K_t = d(internal force)/dq, analytic.
  pure subroutine planar_tangent_stiffness(el, q, phi, kt)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: kt(:, :)
    real(dp) :: fint(max_dofs), se
    call static_strain_terms(el, q, phi, .true., fint, kt, se)
    call rotate_to_global(cos(phi), sin(phi), kt, el%node2)
  end subroutine planar_tangent_stiffness

  !> Strain energy (K16) with the element's quadrature.
  pure real(dp) function planar_strain_energy(el, q, phi) result(se)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp) :: fint(max_dofs), kp(max_dofs*max_dofs)
    call static_strain_terms(el, q, phi, .false., fint, kp, se)
  end function planar_strain_energy

  !> Internal force fint = dSE/dp (local), with want_k the tangent kp, and the
  !> strain energy se at (q, phi), without the motion (the static terms of
  !> the internal force, the tangent stiffness and the strain energy).
  pure subroutine static_strain_terms(el, q, phi, want_k, fint, kp, se)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    logical, intent(in) :: want_k
    real(dp), intent(out) :: fint(max_dofs), kp(size(q), size(q)), se
    real(dp) :: p(max_dofs), fdamp(max_dofs)
    type(kear_eval_info_t) :: info
    integer :: n
    n = size(q)
    p(:n) = to_local(cos(phi), sin(phi), q, el%node2)
    if (is_linear_strain(el)) then
      call el%linear_force(p(:n), want_k, fint(:n), kp)
      se = 0.5_dp*dot_product(p(:n), fint(:n))
    else
      call el%strain_terms(p(:n), p(:n), want_k, .false., info, fint(:n), fdamp(:n), kp)
      se = info%strain_energy
    end if
  end subroutine static_strain_terms

  !> No strain effect on: the linear model (K p, constant K).
  logical pure function is_linear_strain(el)
    class(planar_element_t), intent(in) :: el
    is_linear_strain = .not. (el%effects%stretching .or. el%effects%curvature .or. el%effects%material)
  end function is_linear_strain

  ! ------------------------------------------------------ stress recovery

  !> Fibre strain and stress at y = +-t/2 at x = 0, the Gauss points and
  !> x = l; the maxima of |sigma| and |eps| and where they occur.  The
  !> material switch decides the law; beyond_peak needs it on.
  pure function planar_stress_recovery(el, q, phi) result(rep)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    type(stress_report_t) :: rep
    real(dp) :: eps_n(0:el%n_gauss + 1), kap(0:el%n_gauss + 1)
    call planar_station_strains(el, q, phi, eps_n, kap)
    rep = stress_report(el%beam_properties_t, el%xg, eps_n, kap)
  end function planar_stress_recovery

  !> Axial strain and curvature at every stress station (0 .. n_gauss + 1)
  !> for the global element DOFs q: one rotation, the tabulated gradients.
  pure subroutine planar_station_strains(el, q, phi, eps_n, kap)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: eps_n(0:), kap(0:)
    real(dp) :: p(max_dofs)
    integer :: i
    p(:size(q)) = to_local(cos(phi), sin(phi), q, el%node2)
    do i = 0, el%n_gauss + 1
      call el%station_strains(p(:size(q)), i, eps_n(i), kap(i))
    end do
  end subroutine planar_station_strains

  !> The stress report of the stations i = 0 .. n_gauss + 1 (station_x_over_l)
  !> from their axial strain and curvature.
  pure function stress_report(props, xg, eps_n, kap) result(rep)
    type(beam_properties_t), intent(in) :: props
    real(dp), intent(in) :: xg(:), eps_n(0:), kap(0:)
    type(stress_report_t) :: rep
    type(ramberg_osgood_t) :: law
    integer :: i
    call start_stress_report(props, law, rep)
    do i = 0, props%n_gauss + 1
      call add_station_fibres(law, props%fibre, eps_n(i), kap(i), station_x_over_l(props, xg, i), rep)
    end do
    rep%beyond_peak = props%effects%material .and. rep%max_abs_strain > props%eps_star
  end function stress_report

  !> The law of the stress recovery (E2 = 0 with the material switch off) and
  !> an empty report.
  pure subroutine start_stress_report(props, law, rep)
    type(beam_properties_t), intent(in) :: props
    type(ramberg_osgood_t), intent(out) :: law
    type(stress_report_t), intent(out) :: rep
    law = props%material
    if (.not. props%effects%material) law%e2 = 0.0_dp
    rep%eps_star = props%eps_star
    rep%max_abs_stress = -1.0_dp
    rep%max_abs_strain = -1.0_dp
  end subroutine start_stress_report

  !> x/l of stress station i: 0 (end 1), the Gauss points xg(1..n_gauss), 1 (end 2).
  pure real(dp) function station_x_over_l(props, xg, i) result(eo)
    type(beam_properties_t), intent(in) :: props
    real(dp), intent(in) :: xg(:)
    integer, intent(in) :: i
    if (i == 0) then
      eo = 0.0_dp
    else if (i == props%n_gauss + 1) then
      eo = 1.0_dp
    else
      eo = xg(i)/props%length
    end if
  end function station_x_over_l

  !> Both outer fibres (y = +c, then -c) of the station at x/l = eo into the
  !> report's maxima of |sigma| and |eps| (K14).
  pure subroutine add_station_fibres(law, fibre, eps_n, kap, eo, rep)
    type(ramberg_osgood_t), intent(in) :: law
    real(dp), intent(in) :: fibre, eps_n, kap, eo
    type(stress_report_t), intent(inout) :: rep
    real(dp) :: eps, sig
    integer :: k, fib
    do k = 1, 2
      fib = 3 - 2*k                                      ! +1, then -1
      eps = eps_n - real(fib, dp)*fibre*kap              ! (K14), y = +-c
      sig = ro_stress(law, eps)
      call keep_larger(sig, eo, fib, rep%max_abs_stress, rep%stress, rep%stress_x_over_l, rep%stress_fibre)
      call keep_larger(eps, eo, fib, rep%max_abs_strain, rep%strain, rep%strain_x_over_l, rep%strain_fibre)
    end do
  end subroutine add_station_fibres

  !> A report's peak |value| and where it stands: replaced when |value| is larger.
  pure subroutine keep_larger(value, eo, fib, peak, signed, x_over_l, fibre)
    real(dp), intent(in) :: value, eo
    integer, intent(in) :: fib
    real(dp), intent(inout) :: peak, signed, x_over_l
    integer, intent(inout) :: fibre
    if (abs(value) > peak) then
      peak = abs(value)
      signed = value
      x_over_l = eo
      fibre = fib
    end if
  end subroutine keep_larger

  !> An evaluation's largest strain e (> 0) and where it stands (x/l).
  pure subroutine note_strain(info, e, x_over_l)
    class(kear_eval_info_t), intent(inout) :: info
    real(dp), intent(in) :: e, x_over_l
    if (e > info%max_abs_strain) then
      info%max_abs_strain = e
      info%x_over_l_max_strain = x_over_l
    end if
  end subroutine note_strain
end module planar_element
