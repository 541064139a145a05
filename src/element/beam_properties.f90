!> What every planar beam element holds before its own integrals: geometry,
!> section, material, effect switches and the settings of its nonlinear
!> integrals. Kear's element and the consistent element extend this type, so
!> their set-up and its checks are written once.
module beam_properties
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use quadrature, only: max_gauss_points
  use material_law, only: ramberg_osgood_t, validate_material, peak_strain
  use element_effects, only: element_effects_t
  implicit none
  private
  public :: beam_properties_t, init_beam_properties

  type :: beam_properties_t
    real(dp) :: length = 0.0_dp, width = 0.0_dp, depth = 0.0_dp
    real(dp) :: area = 0.0_dp, inertia = 0.0_dp        !< A = b t, I = b t^3/12 (K4)
    real(dp) :: fibre = 0.0_dp                          !< outer-fibre distance c for stresses (t/2 for a rectangle)
    type(ramberg_osgood_t) :: material
    type(element_effects_t) :: effects
    integer :: n_gauss = 8                              !< points for the nonlinear integrals (doc/element.md)
    real(dp) :: beta = 0.0_dp                           !< stiffness-proportional damping
    logical :: objective_damping = .true.               !< damp strain rates, not global q_dot
    real(dp) :: eps_star = huge(1.0_dp)                 !< peak strain of the material law
  end type beam_properties_t

contains

  !> Check and store the properties; `routine` names the element's set-up
  !> in the messages.
  pure subroutine init_beam_properties(self, routine, length, width, depth, material, effects, err, &
                                       n_gauss, damping_beta, objective_damping, fibre_distance)
    type(beam_properties_t), intent(inout) :: self
    character(len=*), intent(in) :: routine
    real(dp), intent(in) :: length, width, depth
    type(ramberg_osgood_t), intent(in) :: material
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: n_gauss
    real(dp), intent(in), optional :: damping_beta
    logical, intent(in), optional :: objective_damping
    real(dp), intent(in), optional :: fibre_distance   !< c of a section given by A, I, c (default t/2)
    if (.not. (length > 0.0_dp)) then
      call err%set(routine, 'element length must be positive, got '//str(length)); return
    end if
    if (.not. (width > 0.0_dp .and. depth > 0.0_dp)) then
      call err%set(routine, 'section width and depth must be positive, got b = '//str(width)//', t = '//str(depth))
      return
    end if
    call validate_material(material, err)
    if (err%failed()) then
      call err%add_context(routine); return
    end if
    self%length = length
    self%width = width
    self%depth = depth
    self%area = width*depth
    self%inertia = width*depth**3/12.0_dp
    self%fibre = 0.5_dp*depth
    if (present(fibre_distance)) self%fibre = fibre_distance
    self%material = material
    self%effects = effects
    if (present(n_gauss)) self%n_gauss = n_gauss
    if (self%n_gauss < 2 .or. self%n_gauss > max_gauss_points) then
      call err%set(routine, 'n_gauss must be in 2..'//str(max_gauss_points)//', got '//str(self%n_gauss)); return
    end if
    if (present(damping_beta)) self%beta = damping_beta
    if (.not. (self%beta >= 0.0_dp)) then
      call err%set(routine, 'damping beta must be >= 0, got '//str(self%beta)); return
    end if
    if (present(objective_damping)) self%objective_damping = objective_damping
    self%eps_star = peak_strain(material)
  end subroutine init_beam_properties
end module beam_properties
