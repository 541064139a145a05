!> Bearing forces of the joints of a planar flexible mechanism over its
!> steady revolution: the force a pin carries, for the design objectives on
!> joint forces (doc/design.md, "Joint-bearing forces").
!>
!> Each element's equation of motion taken alone (the steady model, T25),
!>     M_e q_dd_e + C_e q_d_e + K_e q_e + f_n,e(q_e) = F_e + r_e,
!> gives r_e, the generalized force of everything outside the element on
!> it; its rows of an end node's global translations are the X, Y force of
!> the joint on that link end (the finite-element nodal force, exact in the
!> element's interpolation; module joint_reactions does the same for the
!> transient model).  F_e holds the rigid-body inertia, so r_e is the whole
!> force, rigid and elastic.  A counterweight on an arm clamped to its link
!> at a ground pivot is carried by that pivot: its m a_cw (the arm turned
!> by the end's elastic slope) is added to the pivot's force.
!>
!> The bearing force of joint j: at a ground pivot, the force of the ground
!> on the mechanism there (the sum over the link ends it holds: the frame
!> feels its opposite, and the ground pivots' forces add up to the shaking
!> force); at a pin between links, the force of the pin on the first link
!> that meets there (the second gets its opposite).
!>
!> The rates q_d, q_dd come from the periodic samples of q by trigonometric
!> interpolation (shaking_force's periodic_derivatives), so that any
!> evaluator's samples, and the perturbed samples of the design
!> sensitivities, give the forces the same way.  No gravity (the steady
!> model has none); links sliding through a sleeve are not covered (the
!> settings refuse them, as for the shaking force).
module joint_bearing
  use kinds, only: dp
  use linkage, only: mechanism_t
  use steady_model, only: steady_model_t
  use tennant_element, only: tennant_linear_terms, tennant_nonlinear_terms, tennant_info_t, tennant_max_dof
  implicit none
  private
  public :: bearing_forces

contains

  !> X, Y bearing force of each of the joints at the model's current time
  !> for the global displacements q and their rates qd, qdd.
  function bearing_forces(model, mech, joints, q, qd, qdd) result(f)
    type(steady_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: joints(:)
    real(dp), intent(in) :: q(:), qd(:), qdd(:)
    real(dp) :: f(2, size(joints))
    integer :: k, j, i, n_ends
    f = 0.0_dp
    do k = 1, size(joints)
      j = joints(k)
      n_ends = merge(mech%joints(j)%n_links, 1, mech%joints(j)%grounded)
      do i = 1, n_ends
        f(:, k) = f(:, k) + end_force(model, mech, mech%joints(j)%link(i), mech%joints(j)%link_end(i), q, qd, qdd)
      end do
    end do
  end function bearing_forces

  !> The force of its joint on end `which` (1, 2) of link `link`, with the
  !> link's counterweight at end 1.
  function end_force(model, mech, link, which, q, qd, qdd) result(force)
    type(steady_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: link, which
    real(dp), intent(in) :: q(:), qd(:), qdd(:)
    real(dp) :: force(2)
    real(dp), dimension(tennant_max_dof, tennant_max_dof) :: me, ce, ke
    real(dp), dimension(tennant_max_dof) :: fe, fn, qe, qde, qdde, r
    type(tennant_info_t) :: info
    integer :: e, nd, row
    real(dp) :: psi, psi_d, psi_dd, arm(2)
    associate (lk => mech%links(link))
      e = lk%first_element
      if (which == 2) e = e + lk%n_elements - 1
      nd = model%el(e)%nd
      call tennant_linear_terms(model%el(e), model%fs(e), me, ce, ke, fe, .true.)
      qe(1:nd) = model%element_q(e, q)
      qde(1:nd) = model%element_q(e, qd)
      qdde(1:nd) = model%element_q(e, qdd)
      r(1:nd) = matmul(me(1:nd, 1:nd), qdde(1:nd)) + matmul(ce(1:nd, 1:nd), qde(1:nd)) + &
                matmul(ke(1:nd, 1:nd), qe(1:nd)) - fe(1:nd)
      if (model%nonlinear .and. model%el(e)%nonlinear) then
        call tennant_nonlinear_terms(model%el(e), qe(1:nd), model%fs(e), fn, info)
        r(1:nd) = r(1:nd) + fn(1:nd)
      end if
      row = merge(0, model%el(e)%nn, which == 1)
      force = r(row + 1:row + 2)
      if (which == 1 .and. lk%cw_mass > 0.0_dp) then
        ! the arm at psi = phi + w_x: m (a_end + psi_dd arm_perp - psi_d^2 arm)
        associate (fs => model%fs(e))
          psi = fs%phi + qe(3)
          psi_d = fs%phi_d + qde(3)
          psi_dd = fs%phi_dd + qdde(3)
          arm = [cos(psi)*lk%cw_x - sin(psi)*lk%cw_y, sin(psi)*lk%cw_x + cos(psi)*lk%cw_y]
          force = force + lk%cw_mass*([fs%x1_dd, fs%y1_dd] + qdde(1:2) + psi_dd*[-arm(2), arm(1)] - psi_d**2*arm)
        end associate
      end if
    end associate
  end function end_force
end module joint_bearing
