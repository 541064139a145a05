!> Pin joints with radial clearance in the planar mechanism model
!> (doc/clearance.md).  At such a joint the journal (the end of the joint's
!> second link) no longer shares the translations of the bearing (the end of
!> the first link, or the ground for a ground pin): its global X/Y elastic
!> translations become two extra global unknowns, and the contact-force law
!> (module contact_law) acts between the two pairs when the relative position
!> e = q_journal - q_bearing leaves the clearance circle |e| <= c.
!>
!> The split is a post-processing of the built correlation table
!> (split_journal): the two new unknowns are numbered right after the
!> journal node's own slope unknown, so they sit beside the unknowns they
!> couple with and the half-bandwidth grows by at most two.
module joint_clearance
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use correlation_table, only: correlation_table_t
  use contact_law, only: contact_law_t, normal_force, friction_force
  use band_kernels, only: add_pair_band
  implicit none
  private
  public :: clearance_joint_t, split_journal, contact_state, add_contact_forces, contact_blocks, add_pair_block, &
            pair_dofs

  !> One clearance joint of the model.
  type :: clearance_joint_t
    integer :: joint = 0                 !< joint index in the mechanism
    character(len=16) :: name = ''
    real(dp) :: clearance = 0.0_dp       !< radial clearance c (in)
    real(dp) :: journal_radius = 0.0_dp  !< for the sliding speed of friction (in)
    type(contact_law_t) :: law
    integer :: bearing(2) = 0            !< global unknowns of the bearing's X, Y translation (0: ground)
    integer :: journal(2) = 0            !< the journal's own unknowns (the split)
    integer :: element_bearing = 0       !< elements whose rigid rotation rates give the sliding speed
    integer :: element_journal = 0       !< (0: ground)
    integer :: journal_node = 0          !< node (1, 2) of element_journal at the joint
    integer :: bearing_node = 0          !< node (1, 2) of element_bearing at the joint
    real(dp) :: v_impact = 1.0_dp        !< approach speed of the current contact (set at its onset)
  end type clearance_joint_t

contains

  !> Give the translations of node `node` (1, 2) of element e their own two
  !> global unknowns, numbered after the node's slope unknown; every unknown
  !> numbered after that moves up by two.  cj%bearing gets the unknowns the
  !> node had (0 for a ground pin), cj%journal the new ones.
  subroutine split_journal(table, e, node, cj, err)
    type(correlation_table_t), intent(inout) :: table
    integer, intent(in) :: e, node
    type(clearance_joint_t), intent(inout) :: cj
    type(error_t), intent(inout) :: err
    call table%split_translations(e, 1 + table%node_dofs()*(node - 1), &
                                  ['J'//str(cj%joint)//' U journal', 'J'//str(cj%joint)//' W journal'], &
                                  cj%bearing, cj%journal, err)
    if (err%failed()) then
      call err%add_context('clearance joint '//trim(cj%name))
      return
    end if
    call table%widen_band(pair_span(cj))
  end subroutine split_journal

  !> Distance between the farthest unknowns the contact couples.
  pure integer function pair_span(cj) result(span)
    type(clearance_joint_t), intent(in) :: cj
    integer :: d(4)
    d = [cj%bearing, cj%journal]
    span = maxval(d) - minval(d, mask=d > 0)
  end function pair_span

  !> Relative position e and velocity of journal and bearing, penetration
  !> |e| - c and its rate, contact normal.
  pure subroutine contact_state(cj, q, qd, e, ed, delta, delta_d, n)
    type(clearance_joint_t), intent(in) :: cj
    real(dp), intent(in) :: q(:), qd(:)
    real(dp), intent(out) :: e(2), ed(2), delta, delta_d, n(2)
    real(dp) :: r
    integer :: i
    do i = 1, 2
      e(i) = q(cj%journal(i))
      ed(i) = qd(cj%journal(i))
      if (cj%bearing(i) > 0) then
        e(i) = e(i) - q(cj%bearing(i))
        ed(i) = ed(i) - qd(cj%bearing(i))
      end if
    end do
    r = sqrt(e(1)**2 + e(2)**2)
    delta = r - cj%clearance
    if (r > 0.0_dp) then
      n = e/r
    else
      n = [1.0_dp, 0.0_dp]
    end if
    delta_d = n(1)*ed(1) + n(2)*ed(2)
  end subroutine contact_state

  !> Contact forces on the journal (f_e = -F_n n + F_t t) and the bearing
  !> (-f_e) added to the global force; F_n and F_t returned.  spin = the rigid
  !> rotation rate of the journal's link minus the bearing's (rad/s).
  subroutine add_contact_forces(cj, q, qd, spin, force, fn, ft)
    type(clearance_joint_t), intent(in) :: cj
    real(dp), intent(in) :: q(:), qd(:), spin
    real(dp), intent(inout) :: force(:)
    real(dp), intent(out) :: fn
    real(dp), intent(out), optional :: ft
    real(dp) :: e(2), ed(2), delta, delta_d, n(2), t(2), d1, d2, f_t, dft, fe(2)
    integer :: i
    call contact_state(cj, q, qd, e, ed, delta, delta_d, n)
    fn = 0.0_dp
    if (present(ft)) ft = 0.0_dp
    if (.not. delta > 0.0_dp) return
    call normal_force(cj%law, delta, delta_d, cj%v_impact, fn, d1, d2)
    t = [-n(2), n(1)]
    call friction_force(cj%law, fn, t(1)*ed(1) + t(2)*ed(2) + cj%journal_radius*spin, f_t, dft)
    if (present(ft)) ft = f_t
    fe = -fn*n + f_t*t
    do i = 1, 2
      force(cj%journal(i)) = force(cj%journal(i)) + fe(i)
      if (cj%bearing(i) > 0) force(cj%bearing(i)) = force(cj%bearing(i)) - fe(i)
    end do
  end subroutine add_contact_forces

  !> Stiffness and damping of the contact in e (2 x 2, symmetric): the
  !> Newton matrix's approximation
  !>     K = dF_n/d delta n n^T + F_n/|e| (I - n n^T),   C = dF_n/d delta' n n^T - dF_t/dv_t t t^T
  !> (the unsymmetric terms of the rotating normal acting on the rate are
  !> left out, like the gyroscopic terms of the elements: the chord
  !> iteration needs only an approximation).  Zero out of contact.
  pure subroutine contact_blocks(cj, q, qd, spin, k, c)
    type(clearance_joint_t), intent(in) :: cj
    real(dp), intent(in) :: q(:), qd(:), spin
    real(dp), intent(out) :: k(2, 2), c(2, 2)
    real(dp) :: e(2), ed(2), delta, delta_d, n(2), t(2), fn, d1, d2, ft, dft, nn(2, 2), r
    call contact_state(cj, q, qd, e, ed, delta, delta_d, n)
    k = 0.0_dp
    c = 0.0_dp
    if (.not. delta > 0.0_dp) return
    call normal_force(cj%law, delta, delta_d, cj%v_impact, fn, d1, d2)
    t = [-n(2), n(1)]
    call friction_force(cj%law, fn, t(1)*ed(1) + t(2)*ed(2) + cj%journal_radius*spin, ft, dft)
    nn = spread(n, 2, 2)*spread(n, 1, 2)
    r = cj%clearance + delta
    k = d1*nn + fn/r*(reshape([1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 2]) - nn)
    c = d2*nn - dft*spread(t, 2, 2)*spread(t, 1, 2)
  end subroutine contact_blocks

  !> band += s * G for the 4 x 4 G = [[B, -B], [-B, B]] of a 2 x 2 block B in
  !> e = q_journal - q_bearing (band_kernels' add_pair_band).
  pure subroutine add_pair_block(cj, blk, s, band, off, lower)
    type(clearance_joint_t), intent(in) :: cj
    real(dp), intent(in) :: blk(2, 2), s
    real(dp), intent(inout) :: band(:, :)
    integer, intent(in) :: off
    logical, intent(in) :: lower
    call add_pair_band(pair_dofs(cj), blk, s, band, off, lower)
  end subroutine add_pair_block

  !> The four unknowns of the contact's e = q_journal - q_bearing (0: ground).
  pure function pair_dofs(cj) result(d)
    type(clearance_joint_t), intent(in) :: cj
    integer :: d(4)
    d = [cj%journal, cj%bearing]
  end function pair_dofs
end module joint_clearance
