!> The planar beam element the mechanism model assembles: Kear's printed
!> element (linear u, quintic w, 8 DOFs; formulations 'exact' and 'kear1987')
!> or the consistent element (quintic u and w, 12 DOFs; 'consistent').  One
!> contract for both -- mass, force, tangent, energies, stresses, point loads
!> -- so that assembly sees elements only through it and the correlation
!> table (doc/element.md section 15).
!>
!> formulation = 'default' chooses the consistent element when exact
!> stretching is on (Kear's element locks in membrane then) and Kear's element
!> with the exact equations otherwise (the two have the same linear model
!> only in the limit; Kear's is cheaper and the reproduction).
module beam_element
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: lower
  use material_law, only: ramberg_osgood_t
  use shape_functions, only: quintic_hermite, linear_lagrange
  use kear_element, only: kear_element_t, element_effects_t, rigid_state_t, kear_eval_info_t, stress_report_t, &
                          kear_element_init, kear_element_eval, kear_tangent_stiffness, kear_internal_force, &
                          kear_strain_energy, kear_kinetic_energy, kear_stress_recovery, kear_local_displacement, &
                          kear_local_dofs, kear_section_strains, formulation_from_name
  use consistent_element, only: consistent_element_t, consistent_element_init, consistent_element_eval, &
                                consistent_tangent_stiffness, consistent_internal_force, consistent_strain_energy, &
                                consistent_kinetic_energy, consistent_stress_recovery, consistent_local_displacement, &
                                consistent_point_load, consistent_local_dofs, consistent_section_strains
  use planar_element, only: planar_station_strains
  implicit none
  private
  public :: beam_element_t, beam_element_init, beam_element_eval, beam_tangent_stiffness, beam_internal_force
  public :: beam_strain_energy, beam_kinetic_energy, beam_stress_recovery, beam_local_displacement
  public :: beam_point_load, beam_section_strains, beam_station_strains, resolve_formulation, formulation_names
  public :: element_kind_kear, element_kind_consistent, beam_mass_constant_in_q

  integer, parameter :: element_kind_kear = 1, element_kind_consistent = 2
  character(len=*), parameter :: formulation_names = "'default', 'consistent', 'exact' or 'kear1987'"

  type :: beam_element_t
    integer :: kind = element_kind_kear
    integer :: ndof = 8
    real(dp) :: length = 0.0_dp, depth = 0.0_dp
    real(dp) :: beta = 0.0_dp
    real(dp) :: eps_star = huge(1.0_dp)
    type(kear_element_t) :: kear
    type(consistent_element_t) :: cons
  end type beam_element_t

contains

  !> Deck name -> element kind (and Kear's formulation code); 'default'
  !> resolves with the stretching switch.  resolved is the name in effect.
  pure subroutine resolve_formulation(name, effects, kind, kear_code, resolved, err)
    character(len=*), intent(in) :: name
    type(element_effects_t), intent(in) :: effects
    integer, intent(out) :: kind, kear_code
    character(len=:), allocatable, intent(out) :: resolved
    type(error_t), intent(inout) :: err
    resolved = lower(trim(adjustl(name)))
    if (resolved == 'default' .or. len(resolved) == 0) then
      resolved = merge('consistent', 'exact     ', effects%stretching)
      resolved = trim(resolved)
    end if
    kind = element_kind_kear
    kear_code = 1
    if (resolved == 'consistent') then
      kind = element_kind_consistent
    else
      call formulation_from_name(resolved, kear_code, err)
      if (err%failed()) call err%set('formulation', "unknown formulation '"//trim(name)//"' (expected " &
                                     //formulation_names//")")
    end if
  end subroutine resolve_formulation

  pure subroutine beam_element_init(el, kind, length, width, depth, material, effects, err, &
                                    kear_code, damping_beta, n_gauss, fibre_distance)
    type(beam_element_t), intent(out) :: el
    integer, intent(in) :: kind
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: kear_code, n_gauss
    real(dp), intent(in), optional :: damping_beta
    real(dp), intent(in), optional :: fibre_distance   !< outer-fibre distance for stresses (default t/2)
    el%kind = kind
    if (kind == element_kind_consistent) then
      call consistent_element_init(el%cons, length, width, depth, material, effects, err, &
                                   n_gauss=n_gauss, damping_beta=damping_beta, fibre_distance=fibre_distance)
      el%ndof = 12
      el%beta = el%cons%beta
      el%eps_star = el%cons%eps_star
    else
      call kear_element_init(el%kear, length, width, depth, material, effects, err, &
                             formulation=kear_code, n_gauss=n_gauss, damping_beta=damping_beta, &
                             fibre_distance=fibre_distance)
      el%ndof = 8
      el%beta = el%kear%beta
      el%eps_star = el%kear%eps_star
    end if
    el%length = length
    el%depth = depth
  end subroutine beam_element_init

  !> mass_wanted = .false.: mass is not computed (left undefined).  Kear's
  !> element only: peak_wanted = .false. skips the linear model's strain peak,
  !> force_wanted = .false. (with tangent) its force (kear_element_eval).
  pure subroutine beam_element_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, &
                                    force_wanted)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), qd(:)
    type(rigid_state_t), intent(in) :: rb
    real(dp), intent(out) :: mass(:, :), force(:)
    type(kear_eval_info_t), intent(out) :: info
    real(dp), intent(out), optional :: tangent(:, :)
    logical, intent(in), optional :: mass_wanted, peak_wanted, force_wanted
    if (el%kind == element_kind_consistent) then
      call consistent_element_eval(el%cons, q, qd, rb, mass, force, info, tangent, mass_wanted)
    else
      call kear_element_eval(el%kear, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, force_wanted)
    end if
  end subroutine beam_element_eval

  !> Whether the element's mass matrix is independent of q (it depends on
  !> q only through the nonlinear section angle of the rotary inertia).
  pure logical function beam_mass_constant_in_q(el) result(constant)
    type(beam_element_t), intent(in) :: el
    type(element_effects_t) :: fx
    if (el%kind == element_kind_consistent) then
      fx = el%cons%effects
    else
      fx = el%kear%effects
    end if
    constant = .not. (fx%rotary_inertia .and. fx%curvature)
  end function beam_mass_constant_in_q

  pure subroutine beam_tangent_stiffness(el, q, phi, kt)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: kt(:, :)
    if (el%kind == element_kind_consistent) then
      call consistent_tangent_stiffness(el%cons, q, phi, kt)
    else
      call kear_tangent_stiffness(el%kear, q, phi, kt)
    end if
  end subroutine beam_tangent_stiffness

  pure subroutine beam_internal_force(el, q, phi, f)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: f(:)
    if (el%kind == element_kind_consistent) then
      call consistent_internal_force(el%cons, q, phi, f)
    else
      call kear_internal_force(el%kear, q, phi, f)
    end if
  end subroutine beam_internal_force


  pure real(dp) function beam_strain_energy(el, q, phi) result(se)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    if (el%kind == element_kind_consistent) then
      se = consistent_strain_energy(el%cons, q, phi)
    else
      se = kear_strain_energy(el%kear, q, phi)
    end if
  end function beam_strain_energy

  pure real(dp) function beam_kinetic_energy(el, q, qd, rb) result(ke)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), qd(:)
    type(rigid_state_t), intent(in) :: rb
    if (el%kind == element_kind_consistent) then
      ke = consistent_kinetic_energy(el%cons, q, qd, rb)
    else
      ke = kear_kinetic_energy(el%kear, q, qd, rb)
    end if
  end function beam_kinetic_energy

  pure function beam_stress_recovery(el, q, phi) result(rep)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    type(stress_report_t) :: rep
    if (el%kind == element_kind_consistent) then
      rep = consistent_stress_recovery(el%cons, q, phi)
    else
      rep = kear_stress_recovery(el%kear, q, phi)
    end if
  end function beam_stress_recovery

  !> Local elastic displacements (u, w) at x = e l.
  pure function beam_local_displacement(el, q, phi, e) result(uw)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e
    real(dp) :: uw(2)
    if (el%kind == element_kind_consistent) then
      uw = consistent_local_displacement(el%cons, q, phi, e)
    else
      uw = kear_local_displacement(el%kear, q, phi, e)
    end if
  end function beam_local_displacement

  !> Axial strain and curvature at x = e l for global element DOFs q.
  pure subroutine beam_section_strains(el, q, phi, e, eps_n, kap)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e
    real(dp), intent(out) :: eps_n, kap
    if (el%kind == element_kind_consistent) then
      call consistent_section_strains(el%cons, consistent_local_dofs(phi, q), e, eps_n, kap)
    else
      call kear_section_strains(el%kear, kear_local_dofs(phi, q), e, eps_n, kap)
    end if
  end subroutine beam_section_strains

  !> Axial strain and curvature at the element's stress stations (both ends
  !> and its Gauss points: 0 .. n_gauss + 1) for global element DOFs q.
  pure subroutine beam_station_strains(el, q, phi, eps_n, kap)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi
    real(dp), intent(out) :: eps_n(0:), kap(0:)
    if (el%kind == element_kind_consistent) then
      call planar_station_strains(el%cons, q, phi, eps_n, kap)
    else
      call planar_station_strains(el%kear, q, phi, eps_n, kap)
    end if
  end subroutine beam_station_strains

  !> Generalized force of a point force f (global X, Y components) and a
  !> counter-clockwise moment mz applied at x = e l of the element, and
  !> optionally dQ/dq.  The force is dead (fixed direction): its work is
  !> f . r.  The moment works through the section angle: exact
  !> theta = phi + atan2(w_x, 1 + u_x) with the curvature effect on, phi + w_x off.
  pure subroutine beam_point_load(el, q, phi, e, f, mz, gen, dgen)
    type(beam_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e, f(2), mz
    real(dp), intent(out) :: gen(:)
    real(dp), intent(out), optional :: dgen(:, :)
    if (el%kind == element_kind_consistent) then
      call consistent_point_load(el%cons, q, phi, e, f, mz, gen, dgen)
    else
      call kear_point_load(el%kear, q, phi, e, f, mz, gen, dgen)
    end if
  end subroutine beam_point_load

  !> beam_point_load for Kear's interpolation (n1, n2 for u, h1..h6 for w).
  pure subroutine kear_point_load(el, q, phi, e, f, mz, gen, dgen)
    type(kear_element_t), intent(in) :: el
    real(dp), intent(in) :: q(8), phi, e, f(2), mz
    real(dp), intent(out) :: gen(8)
    real(dp), intent(out), optional :: dgen(8, 8)
    real(dp) :: c, s, p(8), n(2), h(6), hx(6), su(8), sw(8), gu(8), gw(8), fl(2), a, b, r2, r4, hp(8, 8)
    integer :: i, j
    c = cos(phi)
    s = sin(phi)
    p = kear_local_dofs(phi, q)
    call linear_lagrange(e, el%length, n)
    call quintic_hermite(e, el%length, h, hx)
    su = [n(1), 0.0_dp, 0.0_dp, 0.0_dp, n(2), 0.0_dp, 0.0_dp, 0.0_dp]
    sw = [0.0_dp, h(1), h(2), h(3), 0.0_dp, h(4), h(5), h(6)]
    gu = [-1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]/el%length
    gw = [0.0_dp, hx(1), hx(2), hx(3), 0.0_dp, hx(4), hx(5), hx(6)]
    fl = [c*f(1) + s*f(2), -s*f(1) + c*f(2)]
    hp = 0.0_dp
    if (el%effects%curvature) then
      a = 1.0_dp + dot_product(gu, p)
      b = dot_product(gw, p)
      r2 = a*a + b*b
      r4 = r2*r2
      gen = fl(1)*su + fl(2)*sw + mz*(-b*gu + a*gw)/r2
      do j = 1, 8
        do i = 1, 8
          hp(i, j) = mz*(2.0_dp*a*b/r4*(gu(i)*gu(j) - gw(i)*gw(j)) + (b*b - a*a)/r4*(gu(i)*gw(j) + gw(i)*gu(j)))
        end do
      end do
    else
      gen = fl(1)*su + fl(2)*sw + mz*gw
    end if
    ! back to global DOFs: T^T rotates the translation pairs (1, 2) and (5, 6)
    call rotate_back(gen)
    if (present(dgen)) then
      do j = 1, 8
        call rotate_back(hp(:, j))
      end do
      hp = transpose(hp)
      do j = 1, 8
        call rotate_back(hp(:, j))
      end do
      dgen = transpose(hp)
    end if
  contains
    pure subroutine rotate_back(v)
      real(dp), intent(inout) :: v(8)
      real(dp) :: t1, t2
      integer :: k
      do k = 1, 5, 4
        t1 = c*v(k) - s*v(k + 1)
        t2 = s*v(k) + c*v(k + 1)
        v(k) = t1
        v(k + 1) = t2
      end do
    end subroutine rotate_back
  end subroutine kear_point_load
end module beam_element
