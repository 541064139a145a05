!> The derivative checks of the beam-element contract (module beam_element),
!> shared by the element suites (test_kear_element, test_consistent_element):
!> each element's internal force is the gradient of its strain energy, its
!> tangent the Jacobian of that force, and its inertial operator Lagrange's
!> equations of its kinetic energy -- all against finite differences, on the
!> soft unit element of element_fixtures.  A new element gets them by
!> calling them with its formulation name.
module element_checks
  use kinds, only: dp
  use error_status, only: error_t
  use element_effects, only: element_effects_t, effects_all_on, effects_summary
  use planar_element, only: planar_element_t, rigid_state_t, element_eval_info_t
  use beam_element, only: resolve_formulation, beam_element_init, beam_element_eval, beam_internal_force, &
                          beam_strain_energy, beam_kinetic_energy, beam_tangent_stiffness
  use element_fixtures, only: soft, l_u, b_u, t_u, rigid_at
  use fd_checks, only: fd_gradient, fd_jacobian
  use lagrange_check, only: fd_lagrange
  use assertions, only: assert_true, assert_all_close
  implicit none
  private
  public :: unit_beam, check_force_is_gradient, check_tangent_is_jacobian, check_inertia_is_lagrange

  !> The element and frame angle under check, read by the module procedures
  !> the finite differences call (module procedures, not internal ones: an
  !> internal procedure passed as an argument needs an executable stack for
  !> gfortran's trampoline, and this module is linked into every test).
  class(planar_element_t), allocatable, save :: checked
  real(dp), save :: checked_phi = 0.0_dp

contains

  !> The soft unit element of `formulation` ('exact', 'kear1987' or
  !> 'consistent', as in a deck) with `effects`.
  function unit_beam(formulation, effects) result(el)
    character(len=*), intent(in) :: formulation
    type(element_effects_t), intent(in) :: effects
    class(planar_element_t), allocatable :: el
    character(len=:), allocatable :: resolved
    type(error_t) :: err
    call resolve_formulation(formulation, effects, el, resolved, err)
    if (.not. err%failed()) call beam_element_init(el, l_u, b_u, t_u, soft, effects, err)
    if (err%failed()) call assert_true(.false., 'unit element: '//err%text())
  end function unit_beam

  !> The element under check: a copy of el.
  subroutine set_checked(el)
    class(planar_element_t), intent(in) :: el
    if (allocated(checked)) deallocate(checked)
    allocate(checked, source=el)
  end subroutine set_checked

  !> dSE/dq by 4th-order differences (h = 1e-4: truncation ~h^4, round-off
  !> ~1e-16 SE/h) against the analytic internal force at the strongly
  !> deformed state q, phi = 0.7, each nonlinear effect alone (stretching,
  !> curvature, material) and all on: agreement to 1e-8 of the largest
  !> component.
  subroutine check_force_is_gradient(formulation, q)
    character(len=*), intent(in) :: formulation
    real(dp), intent(in) :: q(:)
    type(element_effects_t) :: fx(4)
    real(dp) :: f(size(q)), g(size(q))
    integer :: k
    fx(1) = element_effects_t(stretching=.true.)
    fx(2) = element_effects_t(curvature=.true.)
    fx(3) = element_effects_t(material=.true.)
    fx(4) = effects_all_on()
    checked_phi = 0.7_dp
    do k = 1, 4
      call set_checked(unit_beam(formulation, fx(k)))
      call beam_internal_force(checked, q, checked_phi, f)
      g = fd_gradient(checked_strain_energy, q, 1.0e-4_dp)
      call assert_all_close(f, g, 0.0_dp, 1.0e-8_dp*maxval(abs(g)), 'dSE/dq: '//effects_summary(fx(k)))
    end do
  end subroutine check_force_is_gradient

  !> d(internal force)/dq by 4th-order differences (h = 1e-4) against the
  !> analytic K_t of `el` at q, phi = -0.4: 1e-7 of max|K|; unless
  !> symmetric = .false. (Kear's printed formulation), K_t is symmetric (a
  !> Hessian) to 1e-12 of max|K|.
  subroutine check_tangent_is_jacobian(el, q, label, symmetric)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: q(:)
    character(len=*), intent(in) :: label
    logical, intent(in), optional :: symmetric
    real(dp) :: kt(size(q), size(q)), kfd(size(q), size(q))
    call set_checked(el)
    checked_phi = -0.4_dp
    call beam_tangent_stiffness(checked, q, checked_phi, kt)
    call fd_jacobian(checked_internal_force, q, 1.0e-4_dp, kfd)
    call assert_all_close(reshape(kt, [size(kt)]), reshape(kfd, [size(kfd)]), 0.0_dp, 1.0e-7_dp*maxval(abs(kfd)), &
                          'K_t vs FD Jacobian: '//label)
    if (present(symmetric)) then
      if (.not. symmetric) return
    end if
    call assert_true(maxval(abs(kt - transpose(kt))) <= 1.0e-12_dp*maxval(abs(kt)), 'K_t symmetric: '//label)
  end subroutine check_tangent_is_jacobian

  !> The inertial operator M qdd - F - dSE/dq of the element against
  !> Lagrange's equations d/dt dT/dqdot - dT/dq of its kinetic energy,
  !> evaluated directly from the positions, by the finite differences of
  !> lagrange_check along q(t) = q + qd s + qdd s^2/2, with the prescribed
  !> rigid motion rigid_at (phi, X1, Y1 all accelerating) at t = 0.37:
  !> 1e-7 of the largest component (the differences' accuracy); all effects
  !> on, the linear section angle (curvature off) and the linear model
  !> (coupling only).
  subroutine check_inertia_is_lagrange(formulation, q, qd, qdd)
    character(len=*), intent(in) :: formulation
    real(dp), intent(in) :: q(:), qd(:), qdd(:)
    real(dp), parameter :: t = 0.37_dp
    character(len=12), parameter :: label(3) = [character(len=12) :: 'all on', 'linear angle', 'linear model']
    type(element_effects_t) :: fx(3)
    type(rigid_state_t) :: rb
    type(element_eval_info_t) :: info
    real(dp) :: op(size(q)), lag(size(q)), m(size(q), size(q)), f(size(q)), fint(size(q))
    integer :: k
    fx(1) = effects_all_on()
    fx(2) = element_effects_t(stretching=.true., rotary_inertia=.true., coupling=.true.)
    fx(3) = element_effects_t(coupling=.true.)
    do k = 1, 3
      call set_checked(unit_beam(formulation, fx(k)))
      rb = rigid_at(t)
      call beam_element_eval(checked, q, qd, rb, m, f, info)
      call beam_internal_force(checked, q, rb%phi, fint)
      op = matmul(m, qdd) - f - fint
      lag = fd_lagrange(checked_kinetic_energy, q, qd, qdd, t)
      call assert_all_close(op, lag, 0.0_dp, 1.0e-7_dp*maxval(abs(lag)), 'Lagrange operator: '//trim(label(k)))
    end do
  end subroutine check_inertia_is_lagrange

  real(dp) function checked_strain_energy(q) result(se)
    real(dp), intent(in) :: q(:)
    se = beam_strain_energy(checked, q, checked_phi)
  end function checked_strain_energy

  subroutine checked_internal_force(q, f)
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: f(:)
    call beam_internal_force(checked, q, checked_phi, f)
  end subroutine checked_internal_force

  !> The kinetic energy under the prescribed rigid motion rigid_at(t).
  real(dp) function checked_kinetic_energy(q, qd, t) result(ke)
    real(dp), intent(in) :: q(:), qd(:), t
    ke = beam_kinetic_energy(checked, q, qd, rigid_at(t))
  end function checked_kinetic_energy
end module element_checks
