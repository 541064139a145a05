!> The planar element contract (doc/element.md): the abstract type Kear's
!> element and the consistent element extend, and everything the two share
!> written once over the steps each element binds.  The models see planar
!> elements only through this type (beam_element's procedures) and the
!> correlation table.
!>
!> An element binds its set-up, its interpolation (u = su.p, w = sw.p and
!> the gradients of its strain variables at x = e l), its station loop of
!> the nonlinear strain terms (in its fixed sizes: 8 x 3 for Kear's, 12 x 4
!> for the consistent element) and its strain measures, and its eval, whose
!> body is planar_evaluation.inc compiled in the element's own sizes (the
!> transient analysis' hot path: one dynamic call per element evaluation,
!> none per Gauss point).  This module holds the constant integrals and
!> station tables, the start and finish of the strain terms, the static
!> terms, the kinetic energy, point loads, displacements and the stress
!> recovery, over the element's DOFs with work arrays of max_dofs that stay
!> off the heap.
module planar_element
  use kinds, only: dp
  use error_status, only: error_t
  use quadrature, only: gauss_legendre_interval
  use beam_properties, only: beam_properties_t, init_beam_properties
  use element_effects, only: element_effects_t
  use material_law, only: ramberg_osgood_t, ro_stress
  use planar_beam_kernels, only: to_local, to_global, rotate_to_global, jb_times, in_frame, point_kinetic_energy, &
                                 add_constant_integrals, rotating_frame_integrals
  implicit none
  private
  public :: planar_element_t, rigid_state_t, element_eval_info_t, stress_report_t
  public :: init_planar_element, start_strain_terms, finish_strain_terms
  public :: planar_internal_force, planar_tangent_stiffness, planar_strain_energy, planar_stress_recovery, &
            planar_stress_report
  public :: planar_station_strains, station_x_over_l

  integer, parameter :: max_dofs = 12   !< the consistent element's; work arrays of this size stay off the heap
  integer, parameter :: n_exact = 6     !< Gauss points exact for the constant integrals (degree <= 11)

  !> Rigid-body state of the element reference line (from kinematics).
  type :: rigid_state_t
    real(dp) :: x1 = 0.0_dp, y1 = 0.0_dp, phi = 0.0_dp            !< end 1 and inclination
    real(dp) :: x1_d = 0.0_dp, y1_d = 0.0_dp, phi_d = 0.0_dp      !< first time derivatives
    real(dp) :: x1_dd = 0.0_dp, y1_dd = 0.0_dp, phi_dd = 0.0_dp   !< second time derivatives
  end type rigid_state_t

  !> By-products of one evaluation.
  type :: element_eval_info_t
    real(dp) :: strain_energy = 0.0_dp
    real(dp) :: max_abs_strain = 0.0_dp     !< over the Gauss points and both outer fibres
    real(dp) :: x_over_l_max_strain = 0.0_dp
    logical :: beyond_peak = .false.        !< material on and max |eps| > eps*
    integer :: n_nonlinear_points = 0       !< cost proxy: nonlinear integrand evaluations
  contains
    procedure :: note_strain
  end type element_eval_info_t

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
  !> (u, w) at node2, node2 + 1), the stations of its nonlinear integrals with
  !> the gradients of its strain variables there, and the constant integrals
  !> of the linear terms, all in the local DOF order (set by
  !> init_planar_element, read-only afterwards).  The strain variables are
  !> (u_x, w_x, w_xx) and, for an element with axial slope DOFs, u_xx.
  type, abstract, extends(beam_properties_t) :: planar_element_t
    integer :: node2 = 0                               !< local DOF of node 2's u (then w)
    !> the section angle of the rotary inertia as printed in kear1987, (K9) and (K11)
    logical :: printed_angle = .false.
    real(dp), allocatable :: xg(:), wg(:)              !< stations on [0, l] and weights
    real(dp), allocatable :: g(:, :, :)                !< (DOFs, strain variables, n_gauss): gradients at xg
    !> (strain variables, DOFs, n_gauss): the same, transposed, so that the
    !> strain variables p^T g of a station are one short contiguous vector
    real(dp), allocatable :: gt(:, :, :)
    !> (strain variables, DOFs, 0:n_gauss + 1): the gradients at the stress
    !> stations (station_x_over_l), transposed as gt
    real(dp), allocatable :: gst(:, :, :)
    ! constant integrals (exact rule)
    real(dp), allocatable :: mass_trans(:, :)          !< int S^T S
    real(dp), allocatable :: coupling(:, :)            !< int S^T (J S - S J_b)
    real(dp), allocatable :: centrifugal(:, :)         !< int S^T (S J_b^2 - S - 2 J S J_b)
    real(dp), allocatable :: load0(:, :)               !< int S^T dx
    real(dp), allocatable :: load1(:, :)               !< int x S^T dx
    real(dp), allocatable :: k_linear(:, :)            !< E1 A int gu gu^T + E1 I int gww gww^T
    real(dp), allocatable :: rot_linear(:, :)          !< int gw gw^T (rotary mass, linear angle)
    real(dp), allocatable :: rot_load(:)               !< int gw dx
  contains
    procedure(init_i), deferred :: init
    procedure(n_dofs_i), deferred, nopass :: n_dofs
    procedure(axial_dofs_i), deferred, nopass :: axial_dofs
    procedure(interpolation_i), deferred :: interpolation
    procedure(strain_terms_i), deferred :: strain_terms
    procedure(section_strains_i), deferred :: section_strains
    procedure(station_strains_i), deferred :: station_strains
    procedure(eval_i), deferred :: eval
    procedure, non_overridable :: point_load => planar_point_load
    procedure, non_overridable :: local_displacement => planar_local_displacement
    procedure, non_overridable :: local_dofs
    procedure, non_overridable :: kinetic_energy => planar_kinetic_energy
    procedure, non_overridable :: mass_constant_in_q
    procedure, non_overridable :: linear_strain
  end type planar_element_t

  abstract interface
    !> Mass matrix, force vector and optionally the tangent of Lagrange's
    !> equations (planar_evaluation.inc, which each element includes).
    pure subroutine eval_i(el, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, force_wanted)
      import :: planar_element_t, rigid_state_t, element_eval_info_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in), contiguous :: q(:), qd(:)
      type(rigid_state_t), intent(in) :: rb
      real(dp), intent(out), contiguous :: mass(:, :), force(:)
      type(element_eval_info_t), intent(out) :: info
      real(dp), intent(out), optional, contiguous :: tangent(:, :)
      logical, intent(in), optional :: mass_wanted, peak_wanted, force_wanted
    end subroutine eval_i

    !> Build the element (an element of the mold's type, intent inout: the
    !> mold's settings, e.g. Kear's formulation, are kept), precompute its
    !> constant integrals (init_planar_element).
    pure subroutine init_i(el, length, width, depth, material, effects, err, n_gauss, damping_beta, &
                           objective_damping, fibre_distance)
      import :: planar_element_t, dp, ramberg_osgood_t, element_effects_t, error_t
      class(planar_element_t), intent(inout) :: el
      real(dp), intent(in) :: length, width, depth
      type(ramberg_osgood_t), intent(in) :: material
      type(element_effects_t), intent(in) :: effects
      type(error_t), intent(inout) :: err
      integer, intent(in), optional :: n_gauss
      real(dp), intent(in), optional :: damping_beta
      logical, intent(in), optional :: objective_damping
      real(dp), intent(in), optional :: fibre_distance   !< c of a section given by A, I, c (default t/2)
    end subroutine init_i

    !> Element DOFs (8: Kear's, 12: the consistent element).
    pure integer function n_dofs_i()
    end function n_dofs_i

    !> Whether the nodes carry axial slope DOFs (u_x, u_xx) besides (u, w, w_x, w_xx).
    pure logical function axial_dofs_i()
    end function axial_dofs_i

    !> The interpolation at x = e l: u = su.p, w = sw.p and (if present) the
    !> gradients g(:, k) of the strain variables (u_x, w_x, w_xx[, u_xx]) by p.
    pure subroutine interpolation_i(el, e, su, sw, g)
      import :: planar_element_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: e
      real(dp), intent(out) :: su(:), sw(:)
      real(dp), intent(out), optional :: g(:, :)
    end subroutine interpolation_i

    !> The stations' sums of the nonlinear strain terms: internal force fint,
    !> tangent kp (if want_k) and kp prel (if want_damp) for local DOFs p;
    !> strain energy and largest strain added to info (start_strain_terms).
    pure subroutine strain_terms_i(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
      import :: planar_element_t, element_eval_info_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in), contiguous :: p(:), prel(:)
      logical, intent(in) :: want_k, want_damp
      type(element_eval_info_t), intent(inout) :: info
      real(dp), intent(out), contiguous :: fint(:), fdamp(:)
      real(dp), intent(out) :: kp(size(p), size(p))
    end subroutine strain_terms_i

    !> Axial strain and curvature at x = e l from local nodal values p.
    pure subroutine section_strains_i(el, p, e, eps_n, kap)
      import :: planar_element_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: p(:), e
      real(dp), intent(out) :: eps_n, kap
    end subroutine section_strains_i

    !> Axial strain and curvature at every stress station i = 0 .. n_gauss + 1
    !> (station_x_over_l) from local nodal values p, by the tabulated gst.
    pure subroutine station_strains_i(el, p, eps_n, kap)
      import :: planar_element_t, dp
      class(planar_element_t), intent(in) :: el
      real(dp), intent(in) :: p(:)
      real(dp), intent(out) :: eps_n(0:), kap(0:)
    end subroutine station_strains_i
  end interface

contains

  ! ------------------------------------------------------------------ set-up

  !> The properties (init_beam_properties; routine names the element's set-up
  !> in the messages), the constant integrals by the exact 6-point rule (S^T S
  !> has degree 10) and the gradient tables at the stations, from the
  !> element's interpolation.
  pure subroutine init_planar_element(el, routine, length, width, depth, material, effects, err, &
                                      n_gauss, damping_beta, objective_damping, fibre_distance)
    class(planar_element_t), intent(inout) :: el
    character(len=*), intent(in) :: routine
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta
    logical, intent(in), optional :: objective_damping
    real(dp), intent(in), optional :: fibre_distance   !< c of a section given by A, I, c (default t/2)
    real(dp) :: x(n_exact), w(n_exact), su(max_dofs), sw(max_dofs), gp(max_dofs, 4)
    real(dp), allocatable :: g2(:, :)
    integer :: i, nd, nv

    call init_beam_properties(el%beam_properties_t, routine, length, width, depth, material, effects, &
                              err, n_gauss, damping_beta, objective_damping, fibre_distance)
    if (err%failed()) return
    nd = el%n_dofs()
    nv = merge(4, 3, el%axial_dofs())
    el%node2 = nd/2 + 1
    allocate(el%mass_trans(nd, nd), el%coupling(nd, nd), el%centrifugal(nd, nd), el%load0(nd, 2), &
             el%load1(nd, 2), el%k_linear(nd, nd), el%rot_linear(nd, nd), el%rot_load(nd), g2(nd, nd))
    el%mass_trans = 0.0_dp
    el%load0 = 0.0_dp
    el%load1 = 0.0_dp
    el%k_linear = 0.0_dp
    el%rot_linear = 0.0_dp
    el%rot_load = 0.0_dp
    g2 = 0.0_dp
    call gauss_legendre_interval(n_exact, 0.0_dp, length, x, w)
    do i = 1, n_exact
      call el%interpolation(x(i)/length, su(:nd), sw(:nd), gp(:nd, :nv))
      call add_constant_integrals(w(i), x(i), su(:nd), sw(:nd), gp(:nd, 1), gp(:nd, 2), gp(:nd, 3), &
                                  material%e1*el%area, material%e1*el%inertia, el%mass_trans, g2, el%load0, &
                                  el%load1, el%k_linear, el%rot_linear, el%rot_load)
    end do
    call rotating_frame_integrals(el%mass_trans, g2, el%node2, el%coupling, el%centrifugal)

    allocate(el%xg(el%n_gauss), el%wg(el%n_gauss), el%g(nd, nv, el%n_gauss), el%gt(nv, nd, el%n_gauss), &
             el%gst(nv, nd, 0:el%n_gauss + 1))
    call gauss_legendre_interval(el%n_gauss, 0.0_dp, length, el%xg, el%wg)
    do i = 1, el%n_gauss
      call el%interpolation(el%xg(i)/length, su(:nd), sw(:nd), el%g(:, :, i))
      el%gt(:, :, i) = transpose(el%g(:, :, i))
    end do
    do i = 0, el%n_gauss + 1
      call el%interpolation(station_x_over_l(el%beam_properties_t, el%xg, i), su(:nd), sw(:nd), gp(:nd, :nv))
      el%gst(:, :, i) = transpose(gp(:nd, :nv))
    end do
  end subroutine init_planar_element

  ! --------------------------------------------------------------- evaluation

  !> Whether the element is the linear strain model (no strain effect on:
  !> K p, constant K).
  logical pure function linear_strain(el)
    class(planar_element_t), intent(in) :: el
    linear_strain = .not. (el%effects%stretching .or. el%effects%curvature .or. el%effects%material)
  end function linear_strain

  !> Whether the mass matrix is independent of q (it depends on q only
  !> through the nonlinear section angle of the rotary inertia).
  logical pure function mass_constant_in_q(el)
    class(planar_element_t), intent(in) :: el
    mass_constant_in_q = .not. (el%effects%rotary_inertia .and. el%effects%curvature)
  end function mass_constant_in_q

  !> The nonlinear strain terms (K16, K17) of the static terms: the element's
  !> station loop between the evaluation's start and finish.
  pure subroutine nonlinear_strain_terms(el, p, prel, want_k, want_damp, info, fint, fdamp, kp)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in), contiguous :: p(:), prel(:)
    logical, intent(in) :: want_k, want_damp
    type(element_eval_info_t), intent(inout) :: info
    real(dp), intent(out), contiguous :: fint(:), fdamp(:)
    real(dp), intent(out) :: kp(size(p), size(p))
    call start_strain_terms(info)
    call el%strain_terms(p, prel, want_k, want_damp, info, fint, fdamp, kp)
    call finish_strain_terms(el, info)
  end subroutine nonlinear_strain_terms

  !> Before the station loop of the nonlinear strain terms: its sums in info.
  pure subroutine start_strain_terms(info)
    type(element_eval_info_t), intent(inout) :: info
    info%strain_energy = 0.0_dp
    info%max_abs_strain = 0.0_dp
  end subroutine start_strain_terms

  !> After the station loop: its cost and whether the material passed its peak.
  pure subroutine finish_strain_terms(el, info)
    class(planar_element_t), intent(in) :: el
    type(element_eval_info_t), intent(inout) :: info
    info%n_nonlinear_points = info%n_nonlinear_points + el%n_gauss
    info%beyond_peak = el%effects%material .and. info%max_abs_strain > el%eps_star
  end subroutine finish_strain_terms

  !> y = A x (the same sums, in the same order, as matmul).
  pure subroutine matvec(n, a, x, y)
    integer, intent(in) :: n
    real(dp), intent(in) :: a(n, n), x(n)
    real(dp), intent(out) :: y(n)
    real(dp) :: acc
    integer :: i, j
    do i = 1, n
      acc = 0.0_dp
      do j = 1, n
        acc = acc + a(i, j)*x(j)
      end do
      y(i) = acc
    end do
  end subroutine matvec

  ! ------------------------------------------------- energies, loads, fields

  !> Kinetic energy (K3) of the element, evaluated directly from the
  !> positions (K5) and section angle (K8), independent of the precomputed
  !> matrices (a check of them): translational part by an 8-point rule
  !> (exact), rotary part by the element's rule (as in the equations of
  !> motion).  With the curvature switch off the section angle is phi + w_x;
  !> printed_angle (kear1987) uses theta_dot of (K9).
  pure real(dp) function planar_kinetic_energy(el, q, qd, rb) result(ke)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), qd(:)
    type(rigid_state_t), intent(in) :: rb
    integer, parameter :: nt = 8
    real(dp) :: c, s, p(max_dofs), pd(max_dofs), x(nt), w(nt), su(max_dofs), sw(max_dofs)
    real(dp) :: vloc(2), a, b, ad, bd, thd
    integer :: i, n
    n = size(q)
    c = cos(rb%phi)
    s = sin(rb%phi)
    p(:n) = to_local(c, s, q, el%node2)
    pd(:n) = to_local(c, s, qd, el%node2) - rb%phi_d*jb_times(p(:n), el%node2)   ! p_dot = T q_dot + T_dot q
    vloc = in_frame(c, s, rb%x1_d, rb%y1_d)
    ke = 0.0_dp
    call gauss_legendre_interval(nt, 0.0_dp, el%length, x, w)
    do i = 1, nt
      call el%interpolation(x(i)/el%length, su(:n), sw(:n))
      ! r_dot in the element frame (K6): R1_dot + rho_dot + phi_dot J rho
      ke = ke + point_kinetic_energy(el%material%rho*el%area, w(i), x(i), vloc, su(:n), sw(:n), p(:n), pd(:n), &
                                     rb%phi_d)
    end do
    if (el%effects%rotary_inertia) then
      do i = 1, el%n_gauss
        a = 1.0_dp + dot_product(el%g(:, 1, i), p(:n))
        b = dot_product(el%g(:, 2, i), p(:n))
        ad = dot_product(el%g(:, 1, i), pd(:n))
        bd = dot_product(el%g(:, 2, i), pd(:n))
        if (.not. el%effects%curvature) then
          thd = rb%phi_d + bd
        else if (el%printed_angle) then
          thd = rb%phi_d + bd*a - b*ad                        ! (K9) as printed
        else
          thd = rb%phi_d + (bd*a - b*ad)/(a*a + b*b)          ! exact derivative of (K8)
        end if
        ke = ke + 0.5_dp*el%material%rho*el%inertia*el%wg(i)*thd**2
      end do
    end if
  end function planar_kinetic_energy

  !> Generalized force of a point force f (global X, Y components) and a
  !> counter-clockwise moment mz applied at x = e l of the element, and
  !> optionally dQ/dq.  The force is dead (fixed direction): its work is
  !> f . r.  The moment works through the section angle: exact
  !> theta = phi + atan2(w_x, 1 + u_x) with the curvature effect on, phi + w_x off.
  pure subroutine planar_point_load(el, q, phi, e, f, mz, gen, dgen)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e, f(2), mz
    real(dp), intent(out) :: gen(:)
    real(dp), intent(out), optional :: dgen(:, :)
    real(dp) :: c, s, p(max_dofs), su(max_dofs), sw(max_dofs), g(max_dofs, 4), fl(2), a, b, r2, r4
    real(dp) :: hp(max_dofs, max_dofs)
    integer :: i, j, n
    n = size(q)
    c = cos(phi)
    s = sin(phi)
    p(:n) = to_local(c, s, q, el%node2)
    call el%interpolation(e, su(:n), sw(:n), g(:n, :size(el%g, 2)))
    fl = [c*f(1) + s*f(2), -s*f(1) + c*f(2)]
    hp = 0.0_dp
    associate (gu => g(:n, 1), gw => g(:n, 2))
      if (el%effects%curvature) then
        a = 1.0_dp + dot_product(gu, p(:n))
        b = dot_product(gw, p(:n))
        r2 = a*a + b*b
        r4 = r2*r2
        gen = fl(1)*su(:n) + fl(2)*sw(:n) + mz*(-b*gu + a*gw)/r2
        do j = 1, n
          do i = 1, n
            hp(i, j) = mz*(2.0_dp*a*b/r4*(gu(i)*gu(j) - gw(i)*gw(j)) + (b*b - a*a)/r4*(gu(i)*gw(j) + gw(i)*gu(j)))
          end do
        end do
      else
        gen = fl(1)*su(:n) + fl(2)*sw(:n) + mz*gw              ! theta = phi + w_x
      end if
    end associate
    gen = to_global(c, s, gen, el%node2)
    if (present(dgen)) then
      dgen = hp(:n, :n)
      call rotate_to_global(c, s, dgen, el%node2)
    end if
  end subroutine planar_point_load

  !> Local nodal values p = T(phi) q (K26): the node translations in the
  !> element frame.
  pure function local_dofs(el, q, phi) result(p)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp) :: p(size(q))
    p = to_local(cos(phi), sin(phi), q, el%node2)
  end function local_dofs

  !> Local elastic displacements (u, w) at x = e l.
  pure function planar_local_displacement(el, q, phi, e) result(uw)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e
    real(dp) :: uw(2)
    real(dp) :: p(max_dofs), su(max_dofs), sw(max_dofs)
    integer :: n
    n = size(q)
    p(:n) = to_local(cos(phi), sin(phi), q, el%node2)
    call el%interpolation(e, su(:n), sw(:n))
    uw = [dot_product(su(:n), p(:n)), dot_product(sw(:n), p(:n))]
  end function planar_local_displacement

  ! ------------------------------------------------------------ static terms

  !> Internal force dSE/dq (kear1987: the printed (K17) with (K20), (K24)).
  pure subroutine planar_internal_force(el, q, phi, f)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: f(:)
    real(dp) :: fint(max_dofs), kp(max_dofs*max_dofs), se
    call static_strain_terms(el, size(q), q, phi, .false., fint, kp, se)
    f = to_global(cos(phi), sin(phi), fint(:size(q)), el%node2)
  end subroutine planar_internal_force

  !> K_t = d(internal force)/dq, analytic.
  pure subroutine planar_tangent_stiffness(el, q, phi, kt)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: kt(:, :)
    real(dp) :: fint(max_dofs), se
    call static_strain_terms(el, size(q), q, phi, .true., fint, kt, se)
    call rotate_to_global(cos(phi), sin(phi), kt, el%node2)
  end subroutine planar_tangent_stiffness

  !> Strain energy (K16) with the element's quadrature.
  pure real(dp) function planar_strain_energy(el, q, phi) result(se)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp) :: fint(max_dofs), kp(max_dofs*max_dofs)
    call static_strain_terms(el, size(q), q, phi, .false., fint, kp, se)
  end function planar_strain_energy

  !> Internal force fint = dSE/dp (local), with want_k the tangent kp, and the
  !> strain energy se at (q, phi), without the motion (the static terms of
  !> the internal force, the tangent stiffness and the strain energy).
  pure subroutine static_strain_terms(el, n, q, phi, want_k, fint, kp, se)
    class(planar_element_t), intent(in) :: el
    integer, intent(in) :: n
    real(dp), intent(in) :: q(n), phi
    logical, intent(in) :: want_k
    real(dp), intent(out) :: fint(n), kp(n, n), se
    real(dp) :: p(max_dofs), fdamp(max_dofs)
    type(element_eval_info_t) :: info
    p(:n) = to_local(cos(phi), sin(phi), q, el%node2)
    if (linear_strain(el)) then
      call matvec(n, el%k_linear, p, fint)
      if (want_k) kp = el%k_linear
      se = 0.5_dp*dot_product(p(:n), fint)
    else
      call nonlinear_strain_terms(el, p(:n), p(:n), want_k, .false., info, fint, fdamp(:n), kp)
      se = info%strain_energy
    end if
  end subroutine static_strain_terms

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
    rep = planar_stress_report(el, eps_n, kap)
  end function planar_stress_recovery

  !> planar_stress_recovery from the strains of the stations
  !> (planar_station_strains), for a caller that needs them for more.
  pure function planar_stress_report(el, eps_n, kap) result(rep)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: eps_n(0:), kap(0:)
    type(stress_report_t) :: rep
    rep = stress_report(el%beam_properties_t, el%xg, eps_n, kap)
  end function planar_stress_report

  !> Axial strain and curvature at every stress station (0 .. n_gauss + 1)
  !> for the global element DOFs q: one rotation, the tabulated gradients.
  pure subroutine planar_station_strains(el, q, phi, eps_n, kap)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: eps_n(0:), kap(0:)
    real(dp) :: p(max_dofs)
    p(:size(q)) = to_local(cos(phi), sin(phi), q, el%node2)
    call el%station_strains(p(:size(q)), eps_n, kap)
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
    class(element_eval_info_t), intent(inout) :: info
    real(dp), intent(in) :: e, x_over_l
    if (e > info%max_abs_strain) then
      info%max_abs_strain = e
      info%x_over_l_max_strain = x_over_l
    end if
  end subroutine note_strain
end module planar_element
