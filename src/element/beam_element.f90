!> The planar beam element the mechanism model assembles: Kear's printed
!> element (linear u, quintic w, 8 DOFs; formulations 'exact' and 'kear1987')
!> or the consistent element (quintic u and w, 12 DOFs; 'consistent'), both
!> extensions of the planar element contract (planar_element_t): mass,
!> force, tangent, energies, stresses, point loads -- so that assembly sees
!> elements only through it and the correlation table (doc/element.md
!> section 15).  A model holds one dynamic type: its elements are allocated
!> from the mold resolve_formulation returns and set up by
!> beam_element_init; each procedure here is one call of the contract.
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
  use element_effects, only: element_effects_t
  use planar_element, only: planar_element_t, rigid_state_t, element_eval_info_t, stress_report_t, &
                            beam_tangent_stiffness => planar_tangent_stiffness, &
                            beam_internal_force => planar_internal_force, &
                            beam_strain_energy => planar_strain_energy, &
                            beam_stress_recovery => planar_stress_recovery, &
                            beam_stress_report => planar_stress_report, &
                            beam_station_strains => planar_station_strains
  use kear_element, only: kear_element_t, formulation_from_name
  use consistent_element, only: consistent_element_t
  implicit none
  private
  public :: planar_element_t, resolve_formulation
  public :: beam_element_init, beam_element_eval, beam_tangent_stiffness, beam_internal_force
  public :: beam_strain_energy, beam_kinetic_energy, beam_stress_recovery, beam_stress_report, beam_local_displacement
  public :: beam_point_load, beam_section_strains, beam_station_strains, beam_mass_constant_in_q
  public :: beam_linear_strain

  character(len=*), parameter :: formulation_names = "'default', 'consistent', 'exact' or 'kear1987'"

contains

  !> Deck name -> the mold of the model's elements (Kear's element with its
  !> formulation, or the consistent element); 'default' resolves with the
  !> stretching switch.  resolved is the name in effect.
  subroutine resolve_formulation(name, effects, mold, resolved, err)
    character(len=*), intent(in) :: name
    type(element_effects_t), intent(in) :: effects
    class(planar_element_t), allocatable, intent(out) :: mold
    character(len=:), allocatable, intent(out) :: resolved
    type(error_t), intent(inout) :: err
    type(kear_element_t) :: kear
    type(consistent_element_t) :: consistent
    resolved = lower(trim(adjustl(name)))
    if (resolved == 'default' .or. len(resolved) == 0) then
      resolved = merge('consistent', 'exact     ', effects%stretching)
      resolved = trim(resolved)
    end if
    if (resolved == 'consistent') then
      allocate(mold, source=consistent)
    else
      call formulation_from_name(resolved, kear%formulation, err)
      if (err%failed()) then
        call err%set('formulation', "unknown formulation '"//trim(name)//"' (expected "//formulation_names//")")
        return
      end if
      allocate(mold, source=kear)
    end if
  end subroutine resolve_formulation

  !> Set up an element allocated from resolve_formulation's mold: its
  !> properties and constant integrals.
  pure subroutine beam_element_init(el, length, width, depth, material, effects, err, &
                                    damping_beta, n_gauss, fibre_distance)
    class(planar_element_t), intent(inout) :: el
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta
    real(dp), intent(in), optional :: fibre_distance   !< outer-fibre distance for stresses (default t/2)
    call el%init(length, width, depth, material, effects, err, n_gauss=n_gauss, damping_beta=damping_beta, &
                 fibre_distance=fibre_distance)
  end subroutine beam_element_init

  !> M_e, F_e and optionally K_t (planar_element's eval: mass_wanted,
  !> peak_wanted and force_wanted skip what a caller does not need).
  pure subroutine beam_element_eval(el, q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, &
                                    force_wanted)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in), contiguous :: q(:), qd(:)
    type(rigid_state_t), intent(in) :: rb
    real(dp), intent(out), contiguous :: mass(:, :), force(:)
    type(element_eval_info_t), intent(out) :: info
    real(dp), intent(out), optional, contiguous :: tangent(:, :)
    logical, intent(in), optional :: mass_wanted, peak_wanted, force_wanted
    call el%eval(q, qd, rb, mass, force, info, tangent, mass_wanted, peak_wanted, force_wanted)
  end subroutine beam_element_eval

  !> Whether the element's mass matrix is independent of q.
  pure logical function beam_mass_constant_in_q(el) result(constant)
    class(planar_element_t), intent(in) :: el
    constant = el%mass_constant_in_q()
  end function beam_mass_constant_in_q

  !> Whether the element is the linear strain model (no strain effect on):
  !> K_t constant in the element frame.
  pure logical function beam_linear_strain(el) result(linear)
    class(planar_element_t), intent(in) :: el
    linear = el%linear_strain()
  end function beam_linear_strain

  pure real(dp) function beam_kinetic_energy(el, q, qd, rb) result(ke)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), qd(:)
    type(rigid_state_t), intent(in) :: rb
    ke = el%kinetic_energy(q, qd, rb)
  end function beam_kinetic_energy

  !> Local elastic displacements (u, w) at x = e l.
  pure function beam_local_displacement(el, q, phi, e) result(uw)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e
    real(dp) :: uw(2)
    uw = el%local_displacement(q, phi, e)
  end function beam_local_displacement

  !> Axial strain and curvature at x = e l for global element DOFs q.
  pure subroutine beam_section_strains(el, q, phi, e, eps_n, kap)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e
    real(dp), intent(out) :: eps_n, kap
    call el%section_strains(el%local_dofs(q, phi), e, eps_n, kap)
  end subroutine beam_section_strains

  !> Generalized force of a point force f (global X, Y components) and a
  !> counter-clockwise moment mz applied at x = e l of the element, and
  !> optionally dQ/dq (planar_element's point_load).
  pure subroutine beam_point_load(el, q, phi, e, f, mz, gen, dgen)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:), phi, e, f(2), mz
    real(dp), intent(out) :: gen(:)
    real(dp), intent(out), optional :: dgen(:, :)
    call el%point_load(q, phi, e, f, mz, gen, dgen)
  end subroutine beam_point_load
end module beam_element
