!> Joint reaction forces of the flexible mechanism: the force (and moment)
!> every joint exerts on each link end it holds, and the force the ground
!> (or a slider's guide) exerts on a joint.  One routine for every user: the
!> transient analysis' reaction columns, and later counterweight (shaking
!> force) and joint-clearance (bearing force) work.
!>
!> How: each element's equation of motion, taken alone, is
!>     M_e q_dd_e = F_e(q, q_d, t) + Q_e + r_e
!> where r_e is the generalized force of everything outside the element on
!> it (mechanism_model%element_joint_force).  The rows of r_e that belong
!> to an end node's global translations (U, W) are the X, Y force on that
!> end; the slope row is the moment (the generalized force conjugate to the
!> section angle, exact in the linear section angle phi + w_x).  At a free
!> DOF shared by two ends the two r_e cancel (the assembled M q_dd = F), so
!> a pin's forces on its two links are equal and opposite and the moment
!> on a pinned end is zero, to round-off.  This is the finite-element nodal
!> force, not a derivative of the curvature (which would lose two orders).
!>
!> Usage (rigid states are set from t):
!>     type(joint_reactions_t) :: jr
!>     call jr%init(mech)                       ! once: the link ends at joints
!>     call jr%compute(model, t, q, qd, err [, qdd])
!>     jr%ends(k)%force, jr%ends(k)%moment      ! on link jr%ends(k)%link from joint jr%ends(k)%joint
!>     jr%support(:, j)                         ! X, Y force and moment of the ground on joint j
!> Without qdd, the accelerations are computed (one right-hand side).
!> doc/transient.md, "Joint reactions".
module joint_reactions
  use kinds, only: dp
  use error_status, only: error_t
  use linkage, only: mechanism_t, joint_slider_fixed, joint_slider_link
  use planar_element, only: rigid_state_t
  use mechanism_model, only: mechanism_model_t, counterweight_arm
  implicit none
  private
  public :: end_force_t, joint_reactions_t

  !> The action of one joint on one link end.
  type :: end_force_t
    integer :: joint = 0, link = 0, link_end = 0   !< joint, link and which end (1, 2)
    integer :: element = 0, node = 0               !< element and its node (1, 2) at that end
    real(dp) :: force(2) = 0.0_dp                  !< global X, Y force of the joint on the link end
    real(dp) :: moment = 0.0_dp                    !< counter-clockwise moment on it (a clamp's torque; 0 at a pin)
  end type end_force_t

  type :: joint_reactions_t
    type(end_force_t), allocatable :: ends(:)      !< every link end at a joint, joints in deck order
    logical, allocatable :: supported(:)           !< joint j is on the ground or on a slider guide
    real(dp), allocatable :: support(:, :)         !< (3, n_joints): X, Y force and moment of the ground/guide on joint j
  contains
    procedure :: init => reactions_init
    procedure :: compute => reactions_compute
  end type joint_reactions_t

contains

  !> The link ends of every joint (a link sliding through a sleeve is not held
  !> at a fixed point of its own and is left out).
  subroutine reactions_init(self, mech)
    class(joint_reactions_t), intent(inout) :: self
    type(mechanism_t), intent(in) :: mech
    integer :: j, i, link, n
    type(end_force_t) :: ef
    allocate(self%ends(0))
    do j = 1, mech%n_joints
      do i = 1, mech%joints(j)%n_links
        link = mech%joints(j)%link(i)
        if (mech%joints(j)%kind == joint_slider_link .and. link == mech%joints(j)%sliding_link) cycle
        ef%joint = j
        ef%link = link
        ef%link_end = mech%joints(j)%link_end(i)
        ef%node = ef%link_end
        ef%element = mech%links(link)%first_element
        if (ef%node == 2) ef%element = ef%element + mech%links(link)%n_elements - 1
        self%ends = [self%ends, ef]
      end do
    end do
    n = mech%n_joints
    allocate(self%supported(n), self%support(3, n))
    self%supported = mech%joints(1:n)%grounded .or. mech%joints(1:n)%kind == joint_slider_fixed
    self%support = 0.0_dp
  end subroutine reactions_init

  !> Forces at time t for the global displacements q and rates qd (and the
  !> accelerations qdd, computed from the model when absent).
  subroutine reactions_compute(self, model, t, q, qd, err, qdd)
    class(joint_reactions_t), intent(inout) :: self
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: t, q(:), qd(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: qdd(:)
    real(dp) :: acc(model%n), r(model%table%element_dofs())
    integer :: k, base, e, j
    if (present(qdd)) then
      acc = qdd
      call model%set_time(t)
    else
      call model%accelerations(t, q, qd, acc)
    end if
    if (model%err%failed()) then
      call err%set('joint reactions', model%err%text())
      return
    end if
    do k = 1, size(self%ends)
      call model%element_joint_force(self%ends(k)%element, t, q, qd, acc, r)
      base = model%table%node_dofs()*(self%ends(k)%node - 1)
      self%ends(k)%force = r(base + 1:base + 2)
      self%ends(k)%moment = r(base + 3)
    end do
    do k = 1, model%cw%count()
      call add_counterweight(self, model, k, q, qd, acc)
    end do
    ! ground or guide on joint j: G = sum of the joint's forces on its link
    ! ends + m_j (a_j - g) (the joint's own mass rides on its first link end)
    self%support = 0.0_dp
    do k = 1, size(self%ends)
      if (.not. self%supported(self%ends(k)%joint)) cycle
      self%support(1:2, self%ends(k)%joint) = self%support(1:2, self%ends(k)%joint) + self%ends(k)%force
      self%support(3, self%ends(k)%joint) = self%support(3, self%ends(k)%joint) + self%ends(k)%moment
    end do
    do k = 1, model%joint_mass%count()
      e = model%joint_mass%element(k)
      j = joint_at(self, e, model%joint_mass%node(k))
      if (j == 0) cycle
      if (.not. self%supported(j)) cycle
      self%support(1:2, j) = self%support(1:2, j) + model%joint_mass%mass(k)*(node_acceleration(model, e, &
                             model%joint_mass%node(k), acc) - model%gravity)
    end do
  end subroutine reactions_compute

  !> Counterweight k's arm is clamped to its link's end 1 at a ground pivot:
  !> the joint there carries the arm as well (m (a_cw - g) added to its force
  !> on the link end), and the arm's torque on the end, J psi_dd - the
  !> weight's moment (psi = phi + w_x), is the arm's, not the joint's.
  subroutine add_counterweight(self, model, k, q, qd, qdd)
    type(joint_reactions_t), intent(inout) :: self
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: k
    real(dp), intent(in) :: q(:), qd(:), qdd(:)
    real(dp) :: c, psi, psi_d, psi_dd, arm(2), torque_g
    integer :: e, g, i
    e = model%cw%element(k)
    g = model%table%unknown(3, e)
    psi = model%rb(e)%phi
    psi_d = model%rb(e)%phi_d
    psi_dd = model%rb(e)%phi_dd
    if (g > 0) then
      c = model%table%coefficient(3, e)
      psi = psi + c*q(g)
      psi_d = psi_d + c*qd(g)
      psi_dd = psi_dd + c*qdd(g)
    end if
    arm = counterweight_arm(model, k, psi)
    torque_g = -model%gravity(1)*arm(2) + model%gravity(2)*arm(1)
    do i = 1, size(self%ends)
      if (self%ends(i)%element /= e .or. self%ends(i)%node /= 1) cycle
      self%ends(i)%force = self%ends(i)%force + psi_dd*[-arm(2), arm(1)] - psi_d**2*arm - model%cw%mass(k)*model%gravity
      self%ends(i)%moment = self%ends(i)%moment + model%cw%inertia(k)*psi_dd - torque_g
    end do
  end subroutine add_counterweight

  !> The joint whose first listed link end is node `node` of element e (0: none).
  pure integer function joint_at(self, e, node) result(j)
    type(joint_reactions_t), intent(in) :: self
    integer, intent(in) :: e, node
    integer :: k
    j = 0
    do k = 1, size(self%ends)
      if (self%ends(k)%element == e .and. self%ends(k)%node == node) then
        j = self%ends(k)%joint
        return
      end if
    end do
  end function joint_at

  !> Total (rigid + elastic) acceleration of node `node` of element e.
  function node_acceleration(model, e, node, qdd) result(a)
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: e, node
    real(dp), intent(in) :: qdd(:)
    real(dp) :: a(2), c, s, qe(model%table%element_dofs())
    type(rigid_state_t) :: rb
    rb = model%rb(e)
    a = [rb%x1_dd, rb%y1_dd]
    if (node == 2) then
      c = cos(rb%phi)
      s = sin(rb%phi)
      a = a + model%el(e)%length*[-rb%phi_dd*s - rb%phi_d**2*c, rb%phi_dd*c - rb%phi_d**2*s]
    end if
    qe = model%table%gather(e, qdd)
    a = a + qe(model%table%node_dofs()*(node - 1) + 1:model%table%node_dofs()*(node - 1) + 2)
  end function node_acceleration
end module joint_reactions
