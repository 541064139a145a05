!> Tests of a clearance joint at unit level (module joint_clearance): the
!> split of the journal's unknowns in the correlation table, the contact
!> force for a prescribed journal position and motion against the Hertz law
!> (action and reaction), the Newton-matrix blocks against difference
!> quotients, and an oblique impact of a journal in a bearing (restitution
!> along the normal, Coulomb's impulse along the tangent).
module test_joint_clearance_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use correlation_table
  use contact_law, only: contact_law_t, contact_law_init
  use joint_clearance
  use lsode_solver, only: ode_system_t, lsode_t, mf_adams
  use element_effects, only: element_effects_t
  use mechanism_model, only: mechanism_model_t
  use transient_fixtures, only: fourbar_input, make_model
  use assertions
  use mechanism_fixtures, only: fourbar_ends
  implicit none
  private
  public :: run_all

  !> A journal of mass m in a fixed bearing (ground): state (ex, ex', ey, ey').
  type, extends(ode_system_t) :: journal_t
    type(clearance_joint_t) :: cj
    real(dp) :: mass = 1.0_dp
  contains
    procedure :: rhs => journal_rhs
  end type journal_t

contains

  subroutine run_all()
    call run_test('split_gives_the_journal_two_own_unknowns_beside_its_slope', test_split)
    call run_test('contact_force_is_hertz_along_the_normal_action_reaction', test_prescribed_force)
    call run_test('newton_blocks_equal_difference_jacobians_of_the_force', test_blocks)
    call run_test('oblique_impact_restitution_and_friction_impulse', test_oblique_impact)
    call run_test('friction_turns_the_link_ends_by_r_ft_in_the_model', test_friction_moment)
  end subroutine run_all

  !> The four-bar (clamp A, pins B and C, ground pin D, one element per
  !> link): clearance at C with the rocker (link 3, start node at C) as
  !> journal.  The rocker's C translations get two new unknowns, the
  !> coupler keeps the old ones; 12 unknowns; the half-bandwidth grows by at
  !> most two; gather/scatter stay transposes.
  subroutine test_split()
    type(correlation_table_t) :: t
    type(link_end_t) :: ends(2, 3)
    type(error_t) :: err
    type(clearance_joint_t) :: cj
    integer :: kd0, old(2), e
    real(dp) :: qg(12), fe(8), lhs, rhs
    ends = fourbar_ends(.false.)
    call t%build([1, 1, 1], ends, err)
    kd0 = t%band()
    old = t%unknowns_of([5, 6], 2)
    call assert_true(all(t%unknowns_of([1, 2], 3) == old), 'pinned: rocker and coupler share C')
    cj%joint = 2
    cj%name = 'C'
    call split_journal(t, 3, 1, cj, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_equal(t%n_unknowns(), 12, 'two more unknowns')
    call assert_true(all(cj%bearing == old), 'the bearing (coupler end) keeps its unknowns')
    call assert_true(all(t%unknowns_of([5, 6], 2) == old), 'coupler map unchanged')
    call assert_true(all(t%unknowns_of([1, 2], 3) == cj%journal), 'rocker C translations are the journal''s')
    call assert_true(cj%journal(1) == max(maxval(old), t%unknown(3, 3)) + 1 .and. cj%journal(2) == cj%journal(1) + 1, &
                     'numbered right after the bearing''s and the rocker''s unknowns at C')
    call assert_true(all(cj%journal /= old), 'journal and bearing separate')
    call assert_true(t%band() <= kd0 + 2, 'half-bandwidth grows by at most two')
    call assert_true(index(t%label_of(cj%journal(1)), 'journal') > 0, 'labelled')
    call assert_equal(size(t%labels()), 12, 'one label per unknown')
    do e = 1, t%n_elements()       ! every unknown 1..12 used exactly where expected
      call assert_true(maxval(t%unknowns(e)) <= 12, 'map within the new size')
    end do
    call random_number(qg)
    call random_number(fe)
    lhs = 0.0_dp
    do e = 1, 3
      lhs = lhs + dot_product(fe, t%gather(e, qg))
    end do
    rhs = 0.0_dp
    block
      real(dp) :: fg(12)
      fg = 0.0_dp
      do e = 1, 3
        call t%scatter_add(e, fe, fg)
      end do
      rhs = dot_product(fg, qg)
    end block
    call assert_close(lhs, rhs, 1.0e-13_dp, 'scatter = gather^T after the split')
  end subroutine test_split

  !> A joint with unknowns bearing (1, 2), journal (3, 4): the journal held at
  !> c + delta from the bearing in directions all round the circle, at rest
  !> and moving radially: F = K delta^1.5 (1 + chi delta'/v_impact) along -n
  !> on the journal, the opposite on the bearing (sum zero).
  subroutine test_prescribed_force()
    type(clearance_joint_t) :: cj
    type(error_t) :: err
    real(dp) :: q(4), qd(4), f(4), fn, a, delta, n(2)
    integer :: i
    cj%bearing = [1, 2]
    cj%journal = [3, 4]
    cj%clearance = 0.005_dp
    cj%v_impact = 20.0_dp
    call contact_law_init(cj%law, 'lankarani_nikravesh', 3.0e7_dp, 1.5_dp, 0.8_dp, 0.0_dp, 0.1_dp, err)
    do i = 0, 7
      a = i*pi/4.0_dp + 0.1_dp
      n = [cos(a), sin(a)]
      delta = 2.0e-4_dp*(1 + i)
      q(1:2) = [1.0e-3_dp, -2.0e-3_dp]
      q(3:4) = q(1:2) + (cj%clearance + delta)*n
      qd = 0.0_dp
      f = 0.0_dp
      call add_contact_forces(cj, q, qd, 0.0_dp, f, fn)
      call assert_rel_close(fn, 3.0e7_dp*delta**1.5_dp, 1.0e-12_dp, 'Hertz at rest')
      call assert_all_close(f(3:4), -fn*n, 1.0e-12_dp, 1.0e-9_dp, 'on the journal: -F n')
      call assert_all_close(f(1:2), -f(3:4), 0.0_dp, 0.0_dp, 'on the bearing: the reaction')
      ! moving apart radially at 5 in/s (the bearing moves too: only the relative rate counts)
      qd(1:2) = [3.0_dp, 1.0_dp]
      qd(3:4) = qd(1:2) + 5.0_dp*n
      f = 0.0_dp
      call add_contact_forces(cj, q, qd, 0.0_dp, f, fn)
      call assert_rel_close(fn, 3.0e7_dp*delta**1.5_dp*(1.0_dp + 0.75_dp*(1.0_dp - 0.64_dp)*5.0_dp/20.0_dp), &
                            1.0e-12_dp, 'damped: 1 + chi delta''/v_impact')
    end do
    q(3:4) = q(1:2) + 0.9_dp*cj%clearance*[0.6_dp, 0.8_dp]
    f = 0.0_dp
    call add_contact_forces(cj, q, qd, 0.0_dp, f, fn)
    call assert_true(abs(fn) + sum(abs(f)) <= 0.0_dp, 'inside the clearance: no force')
  end subroutine test_prescribed_force

  !> K = -d f_journal/d e and C = -d f_journal/d e' by central differences,
  !> at rest (no rate terms: the blocks are then the exact Jacobian) with
  !> friction on, for a sliding journal (the tangential rate term).
  subroutine test_blocks()
    type(clearance_joint_t) :: cj
    type(error_t) :: err
    real(dp) :: q(4), qd(4), k(2, 2), c(2, 2), kd(2, 2), cd(2, 2)
    cj%bearing = [1, 2]
    cj%journal = [3, 4]
    cj%clearance = 0.005_dp
    cj%v_impact = 20.0_dp
    call contact_law_init(cj%law, 'lankarani_nikravesh', 3.0e7_dp, 1.5_dp, 0.8_dp, 0.2_dp, 0.1_dp, err)
    q = [0.0_dp, 0.0_dp, 0.0054_dp*cos(0.3_dp), 0.0054_dp*sin(0.3_dp)]
    qd = [0.0_dp, 0.0_dp, -0.02_dp*sin(0.3_dp), 0.02_dp*cos(0.3_dp)]   ! sliding at 0.02 in/s, no normal rate
    call contact_blocks(cj, q, qd, 0.0_dp, k, c)
    cd = journal_fd(.true., 1.0e-6_dp)
    ! the friction force also follows F_n's rate term, mu tanh(v_t/v_s) dF_n/d delta' t n^T,
    ! unsymmetric and left out: relative to the friction slope mu F_n/v_s it is
    ! chi v_s/v_impact = 1.35e-3 here; 2e-3 of the largest entry covers it
    call assert_all_close(reshape(c, [4]), reshape(cd, [4]), 0.0_dp, 2.0e-3_dp*maxval(abs(cd)), &
                          'C: normal damping and friction slope')
    cj%law%friction = 0.0_dp
    call contact_blocks(cj, q, qd, 0.0_dp, k, c)
    kd = journal_fd(.false., 1.0e-9_dp)
    ! the sliding rate turns the normal rate with the normal: a term of
    ! order F_n chi/v_impact * 0.02/c left out; 1e-3 of K covers it
    call assert_all_close(reshape(k, [4]), reshape(kd, [4]), 1.0e-3_dp, 1.0e-3_dp*maxval(abs(kd)), &
                          'K: Hertz slope along n, F_n/|e| across')
    call assert_close(k(1, 2), k(2, 1), 0.0_dp, 'K symmetric')
  contains
    !> -d f_journal/d e (or d e' with `rate`) by central differences of step h.
    function journal_fd(rate, h) result(d)
      logical, intent(in) :: rate
      real(dp), intent(in) :: h
      real(dp) :: d(2, 2), e(4), fp(4), fm(4), fn
      integer :: j
      do j = 1, 2
        e = 0.0_dp
        e(2 + j) = h
        fp = 0.0_dp
        fm = 0.0_dp
        if (rate) then
          call add_contact_forces(cj, q, qd + e, 0.0_dp, fp, fn)
          call add_contact_forces(cj, q, qd - e, 0.0_dp, fm, fn)
        else
          call add_contact_forces(cj, q + e, qd, 0.0_dp, fp, fn)
          call add_contact_forces(cj, q - e, qd, 0.0_dp, fm, fn)
        end if
        d(:, j) = -(fp(3:4) - fm(3:4))/(2*h)
      end do
    end function journal_fd
  end subroutine test_blocks

  subroutine journal_rhs(self, t, y, ydot)
    class(journal_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    real(dp) :: f(2), fn
    f = 0.0_dp
    call add_contact_forces(self%cj, y([1, 3]), y([2, 4]), 0.0_dp, f, fn)
    ydot = [y(2), f(1)/self%mass, y(4), f(2)/self%mass]
    if (.false.) ydot(1) = t
  end subroutine journal_rhs

  !> A journal (m = 0.01) in a fixed bearing of large clearance (c = 10 in, the
  !> wall flat over the contact: it turns by ~5e-5 rad), starting 1e-3 in from
  !> the wall and hitting it at 10 in/s along the normal while sliding at
  !> 10 in/s.  The calibrated law with e = 0.8 and mu = 0.3: afterwards the
  !> normal speed is -e v, the tangential speed w - mu (1 + e) v (Coulomb's
  !> impulse mu times the normal impulse m (1 + e) v; the sliding never stops).
  !> Tolerance 1e-3 of the speeds: the wall's turn over the contact (5e-5),
  !> the tanh friction at 4 in/s sliding and v_s = 1e-3 (exact to e^-8000).
  subroutine test_oblique_impact()
    type(journal_t), target :: sys
    type(lsode_t) :: ode
    type(error_t) :: err
    real(dp) :: y(4)
    sys%mass = 0.01_dp
    sys%cj%journal = [1, 2]
    sys%cj%bearing = [0, 0]
    sys%cj%clearance = 10.0_dp
    sys%cj%v_impact = 10.0_dp
    call contact_law_init(sys%cj%law, 'calibrated', 1.0e8_dp, 1.5_dp, 0.8_dp, 0.3_dp, 1.0e-3_dp, err)
    call assert_true(.not. err%failed(), err%text())
    y = [10.0_dp - 1.0e-3_dp, 10.0_dp, 0.0_dp, 10.0_dp]
    call ode%init(4, 0.0_dp, mf_adams, 1.0e-10_dp, [1.0e-14_dp], err, max_steps=200000)
    call ode%integrate_to(sys, y, 2.0e-3_dp, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_true(y(1) < 10.0_dp, 'the journal left the wall')
    call assert_close(y(2), -8.0_dp, 1.0e-2_dp, 'normal speed -e v')
    call assert_close(y(4), 10.0_dp - 0.3_dp*1.8_dp*10.0_dp, 1.0e-2_dp, 'tangential speed w - mu (1+e) v')
  end subroutine test_oblique_impact
  !> The four-bar model (Kear's linear element) with clearance at C: journal
  !> the rocker's end 2 (element 3), bearing the coupler's end 2 (element 2).
  !> The journal pressed 1e-4 in into the wall along +X (F_n = K delta^1.5 =
  !> 10 lb, no normal rate) and sliding along +Y at 100 in/s, far above v_s
  !> and the rigid spin r (phi_rocker' - phi_coupler') ~ 25 in/s, so that
  !> F_t = -mu F_n with r = 0 and r = 0.25 alike.  With r = 0.25 the model's
  !> force differs only by the moments r F_t = -0.75 lb in on the rocker's
  !> slope at C and +0.75 on the coupler's (for the linear element an end
  !> moment's generalized force is the moment itself on the end slope).
  subroutine test_friction_moment()
    type(mechanism_model_t), target :: model
    type(clearance_joint_t) :: cj
    type(error_t) :: err
    logical :: ok
    real(dp), allocatable :: q(:), qd(:), qdd(:), f0(:), f1(:), want(:)
    cj%joint = 3
    cj%name = 'C'
    cj%clearance = 0.005_dp
    cj%v_impact = 10.0_dp
    cj%element_journal = 3
    cj%journal_node = 2
    cj%element_bearing = 2
    cj%bearing_node = 2
    call contact_law_init(cj%law, 'lankarani_nikravesh', 1.0e7_dp, 1.5_dp, 0.9_dp, 0.3_dp, 1.0e-3_dp, err)
    call assert_true(.not. err%failed(), err%text())
    call make_model(fourbar_input(1, 150.0_dp, 0.0_dp), element_effects_t(), 0.0_dp, model, ok, table=.false., &
                    clearance=[cj])
    call assert_true(ok, 'four-bar model with clearance at C')
    allocate(q(model%n), qd(model%n), qdd(model%n), want(model%n), f0(model%n), f1(model%n))
    q = 0.0_dp
    qd = 0.0_dp
    q(model%clearance(1)%journal) = [0.005_dp + 1.0e-4_dp, 0.0_dp]
    qd(model%clearance(1)%journal) = [0.0_dp, 100.0_dp]
    call model%accelerations(0.0_dp, q, qd, qdd)
    f0 = model%force
    model%clearance(1)%journal_radius = 0.25_dp
    call model%accelerations(0.0_dp, q, qd, qdd)
    f1 = model%force
    call assert_true(.not. model%err%failed(), model%err%text())
    want = 0.0_dp
    want(model%table%unknown(7, 3)) = -0.75_dp
    want(model%table%unknown(7, 2)) = 0.75_dp
    call assert_all_close(f1 - f0, want, 0.0_dp, 1.0e-12_dp, 'friction moments on the slopes at C only')
  end subroutine test_friction_moment
end module test_joint_clearance_suite

program test_joint_clearance
  use test_joint_clearance_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_joint_clearance')
end program test_joint_clearance
