!> Tests of the variable correlation table (module correlation_table).
module test_correlation_table_suite
  use kinds, only: dp
  use error_status, only: error_t
  use correlation_table
  use assertions
  use mechanism_fixtures, only: fourbar_ends
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('fourbar_one_element_per_link_has_ten_unknowns', test_fourbar_one_element)
    call run_test('fourbar_pins_share_translations_not_slopes', test_fourbar_sharing)
    call run_test('elements_in_a_link_share_all_node_dofs', test_multi_element_link)
    call run_test('bandwidth_grows_with_nothing_but_the_chain', test_bandwidth)
    call run_test('links_drawn_against_the_chain_keep_a_narrow_band', test_bandwidth_reversed_rocker)
    call run_test('scatter_is_transpose_of_gather', test_scatter_transpose)
    call run_test('slider_translation_follows_guide', test_slider)
    call run_test('fully_held_structure_is_an_error', test_no_free_dof)
    call run_test('six_dofs_per_node_for_the_consistent_element', test_axial_dofs)
    call run_test('shear_angle_dofs_follow_slope_and_curvature_rules', test_alpha_rules)
    call run_test('sleeve_end_takes_the_sleeve_displacement_across_the_link', test_sleeve_carried)
    call run_test('ground_sleeve_end_slides_along_the_link', test_sleeve_ground)
    call run_test('sleeve_map_rates_match_fd', test_sleeve_rates)
    call run_test('bad_sleeve_ends_are_rejected', test_bad_sleeves)
    call run_test('base_table_filled_by_hand_as_the_spatial_model_does', test_base_table)
  end subroutine run_all

  !> crank (clamp A, pin B), coupler (pin B, pin C), rocker (pin C, ground pin D)
  subroutine fourbar(n_each, table, err, axial)
    integer, intent(in) :: n_each
    type(correlation_table_t), intent(out) :: table
    type(error_t), intent(inout) :: err
    logical, intent(in), optional :: axial
    type(link_end_t) :: ends(2, 3)
    ends = fourbar_ends(.false.)
    call table%build([n_each, n_each, n_each], ends, err, axial_dofs=axial)
  end subroutine fourbar

  !> axial_dofs (doc/correlation_table.md): [U W th m ux uxx] per node; the
  !> four-bar with one element per link has 27 unknowns: A clamped (m, ux, uxx),
  !> B and C 2 shared translations each, every link end at a pin or at D its own
  !> th, m, ux, uxx (4 x 5 ends); a second element per link adds 6 per link.
  !> The rules for U, W, th are those of Kear's table; scatter = gather^T.
  subroutine test_axial_dofs()
    type(correlation_table_t) :: t, k
    type(error_t) :: err
    real(dp) :: qg(60), fe(12), lhs, rhs
    integer :: i
    call fourbar(1, t, err, axial=.true.)
    call assert_true(.not. err%failed(), err%text())
    call assert_equal(t%node_dofs(), 6, 'six DOFs per node')
    call assert_equal(t%element_dofs(), 12, 'twelve per element')
    call assert_equal(t%n_unknowns(), 27, 'global unknowns')
    call assert_true(all(t%unknowns_of([1, 2, 3], 1) == 0) .and. all(t%unknowns_of([4, 5, 6], 1) > 0), &
                     'A: U = W = th = 0; m, ux, uxx free')
    call assert_true(all(t%unknowns_of([7, 8], 1) == t%unknowns_of([1, 2], 2)), 'B translations shared')
    call assert_true(all(t%unknowns_of([10, 11, 12], 2) > 0) .and. all(t%unknowns_of([4, 5, 6], 2) > 0), &
                     'pins: m, ux, uxx free')
    call assert_true(all(t%unknowns_of([7, 8], 3) == 0) .and. all(t%unknowns_of([9, 10, 11, 12], 3) > 0), &
                     'D: U = W = 0; th, m, ux, uxx free')
    call fourbar(1, k, err)
    do i = 1, 3
      call assert_true(all((t%unknowns_of([1, 2, 3, 7, 8, 9], i) > 0) .eqv. (k%unknowns_of([1, 2, 3, 5, 6, 7], i) > 0)), &
                       'U, W, th held where Kear''s table holds them')
    end do
    call fourbar(2, t, err, axial=.true.)
    call assert_equal(t%n_unknowns(), 27 + 18, 'a second element per link adds an interior node of 6')
    ! scatter is the transpose of gather: fe . (C qg) = (C^T fe) . qg
    do i = 1, 60
      qg(i) = sin(1.3_dp*i)
    end do
    do i = 1, 12
      fe(i) = cos(0.7_dp*i)
    end do
    lhs = dot_product(fe, t%gather(3, qg(1:t%n_unknowns())))
    block
      real(dp) :: fg(t%n_unknowns())
      fg = 0.0_dp
      call t%scatter_add(3, fe, fg)
      rhs = dot_product(fg, qg(1:t%n_unknowns()))
    end block
    call assert_close(lhs, rhs, 1.0e-13_dp, 'scatter = gather^T with 12 DOFs')
  end subroutine test_axial_dofs

  !> FORMULATION.md §6: A clamped (m free), B and C shared translations with a
  !> slope per link, D pinned to ground (th free): 10 unknowns.
  subroutine test_fourbar_one_element()
    type(correlation_table_t) :: t
    type(error_t) :: err
    call fourbar(1, t, err)
    call assert_true(.not. err%failed(), err%text())
    call assert_equal(t%n_unknowns(), 10, 'global unknowns of the 3-element four-bar')
    call assert_equal(count(t%unknowns(1) > 0), 4, 'crank: m at A, U W th at B')
    call assert_true(all(t%unknowns_of([1, 2, 3], 1) == 0) .and. t%unknown(4, 1) > 0, &
                     'A is clamped: U = W = th = 0, m free')
    call assert_true(t%unknown(8, 2) == 0 .and. t%unknown(4, 2) == 0, 'no curvature DOF at pins B, C of the coupler')
    call assert_true(all(t%unknowns_of([5, 6], 3) == 0) .and. t%unknown(7, 3) > 0 .and. t%unknown(8, 3) == 0, &
                     'D: U = W = 0, th free, m = 0')
  end subroutine test_fourbar_one_element

  subroutine test_fourbar_sharing()
    type(correlation_table_t) :: t
    type(error_t) :: err
    call fourbar(1, t, err)
    call assert_true(all(t%unknowns_of([5, 6], 1) == t%unknowns_of([1, 2], 2)), &
                     'B translations shared by crank and coupler')
    call assert_true(t%unknown(7, 1) /= t%unknown(3, 2), 'slopes at B independent')
    call assert_true(all(t%unknowns_of([5, 6], 2) == t%unknowns_of([1, 2], 3)), &
                     'C translations shared by coupler and rocker')
  end subroutine test_fourbar_sharing

  !> n elements per link: each interior node adds 4 unknowns.
  subroutine test_multi_element_link()
    type(correlation_table_t) :: t
    type(error_t) :: err
    call fourbar(4, t, err)
    call assert_equal(t%n_unknowns(), 10 + 3*3*4, 'four elements per link')
    call assert_true(all(t%unknowns_of([5, 6, 7, 8], 1) == t%unknowns_of([1, 2, 3, 4], 2)), &
                     'elements 1 and 2 of the crank share a node')
    call assert_true(all(t%unknowns_of([5, 6, 7, 8], 1) > 0), 'interior node fully free')
  end subroutine test_multi_element_link

  !> Numbering along the chain keeps the band narrow and independent of mesh size.
  subroutine test_bandwidth()
    type(correlation_table_t) :: t2, t16
    type(error_t) :: err
    call fourbar(2, t2, err)
    call fourbar(16, t16, err)
    call assert_true(t16%band() <= 7, 'half-bandwidth of a chain stays <= 7 with 16 elements per link')
    call assert_true(t2%band() <= 7, 'half-bandwidth of a chain stays <= 7 with 2 elements per link')
  end subroutine test_bandwidth

  !> The rocker drawn from its ground pivot D to the coupler pin C (as in the
  !> decks): numbered link by link its last node couples to C, numbered with
  !> the coupler, and the band grows with the mesh (checked); the reverse
  !> Cuthill-McKee renumbering keeps it at most 7 for any mesh, and the table
  !> stays a valid table (same sharing, every unknown used).
  subroutine test_bandwidth_reversed_rocker()
    type(correlation_table_t) :: t
    type(error_t) :: err
    type(link_end_t) :: ends(2, 3)
    integer :: n_each, seen(200), e, k
    ends = fourbar_ends(.true.)
    do n_each = 1, 16, 5
      call t%build([n_each, n_each, n_each], ends, err, reduce_band=.true.)
      call assert_true(.not. err%failed(), err%text())
      call assert_true(t%band() <= 7, 'half-bandwidth <= 7 with the rocker drawn D -> C')
      call assert_equal(t%n_unknowns(), 10 + 3*4*(n_each - 1), 'unknowns')
      call assert_true(all(t%unknowns_of([5, 6], 2*n_each) == t%unknowns_of([5, 6], 3*n_each)), &
                       'C shared by coupler and rocker ends')
      seen = 0
      do e = 1, t%n_elements()
        do k = 1, 8
          if (t%unknown(k, e) > 0) seen(t%unknown(k, e)) = 1
        end do
      end do
      call assert_equal(sum(seen), t%n_unknowns(), 'every unknown appears in the table')
      t = correlation_table_t()
    end do
    call t%build([16, 16, 16], ends, err)
    call assert_true(t%band() > 50, 'without renumbering the band spans the rocker')
  end subroutine test_bandwidth_reversed_rocker

  subroutine test_scatter_transpose()
    type(correlation_table_t) :: t
    type(error_t) :: err
    real(dp) :: qg(40), fe(8), fg(40), lhs, rhs
    integer :: e, i
    call fourbar(3, t, err)
    do i = 1, t%n_unknowns()
      qg(i) = sin(1.3_dp*i)
    end do
    do e = 1, t%n_elements()
      fe = [(cos(0.7_dp*i + e), i = 1, 8)]
      fg = 0.0_dp
      call t%scatter_add(e, fe, fg)
      lhs = dot_product(fe, t%gather(e, qg(1:t%n_unknowns())))
      rhs = dot_product(fg(1:t%n_unknowns()), qg(1:t%n_unknowns()))
      call assert_close(lhs, rhs, 1.0e-13_dp, 'fe . (T qg) = (T^T fe) . qg')
    end do
  end subroutine test_scatter_transpose

  !> The base table as a model with its own joint rules fills it (the
  !> spatial model): three 4-DOF elements in a chain sharing their middle
  !> DOFs, one DOF held, one shared with coefficient -1.  gather_pair must
  !> equal gather of each vector, the band is the widest element's index
  !> spread, and the listing holds every label.
  subroutine test_base_table()
    type(correlation_base_t) :: t
    real(dp) :: q(7), qd(7), qe(4), qde(4)
    integer :: e, g(7)
    character(len=160) :: lines(2)
    call t%start_table(3, 4)
    do e = 1, 7
      g(e) = t%new_unknown('u'//achar(iachar('0') + e))
    end do
    ! nodes of two DOFs [0 g1] [g2 g3] [g4 g5] [g6 g7]; element 2 takes its
    ! start node's second DOF with coefficient -1
    call t%join_nodes(1, reshape([0, g], [2, 4]), reshape([(1.0_dp, e = 1, 8)], [2, 4]))
    call t%join_nodes(2, reshape(g(2:5), [2, 2]), reshape([1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp], [2, 2]))
    call t%finish_band()
    call assert_equal(t%n_unknowns(), 7, 'seven unknowns')
    call assert_equal(t%band(), 3, 'band: largest index spread of one element')
    q = [(sin(1.1_dp*e), e = 1, 7)]
    qd = [(cos(0.9_dp*e), e = 1, 7)]
    do e = 1, 3
      call t%gather_pair(e, q, qd, qe, qde)
      call assert_all_close(qe, t%gather(e, q), 0.0_dp, 0.0_dp, 'gather_pair displacements = gather')
      call assert_all_close(qde, t%gather(e, qd), 0.0_dp, 0.0_dp, 'gather_pair rates = gather')
    end do
    qe = t%gather(2, q)
    call assert_close(qe(2), -q(3), 0.0_dp, 'coefficient -1 applied')
    call t%list_unknowns(8, lines)
    call assert_true(index(lines(1), 'u1') > 0 .and. index(lines(1), 'u4') > 0 .and. index(lines(2), 'u7') > 0, &
                     'four labels to a line: '//trim(lines(1)))
  end subroutine test_base_table

  subroutine test_slider()
    type(correlation_table_t) :: t
    type(error_t) :: err
    type(link_end_t) :: ends(2, 2)
    real(dp) :: qg(20), qe(8)
    real(dp), parameter :: alpha = 0.3_dp
    ! slider-crank: crank clamped, coupler ends on a slider guided at alpha
    ends(1, 1) = link_end_t(joint_clamp, 0, 0.0_dp)
    ends(2, 1) = link_end_t(joint_pin, 1, 0.0_dp)
    ends(1, 2) = link_end_t(joint_pin, 1, 0.0_dp)
    ends(2, 2) = link_end_t(joint_slider_fixed, 2, alpha)
    call t%build([1, 1], ends, err)
    call assert_true(.not. err%failed(), err%text())
    qg = 0.0_dp
    qg(t%unknown(5, 2)) = 2.0_dp
    qe = t%gather(2, qg(1:t%n_unknowns()))
    call assert_close(qe(5), 2.0_dp*cos(alpha), 1.0e-15_dp, 'slider U = s cos(alpha)')
    call assert_close(qe(6), 2.0_dp*sin(alpha), 1.0e-15_dp, 'slider W = s sin(alpha)')
    call assert_equal(t%n_unknowns(), 1 + 2 + 1 + 1 + 1 + 1, 'slider-crank unknowns')
  end subroutine test_slider

  subroutine test_no_free_dof()
    type(correlation_table_t) :: t
    type(error_t) :: err
    type(link_end_t) :: ends(2, 1)
    ends(1, 1) = link_end_t(joint_ground_pin, 0, 0.0_dp)
    ends(2, 1) = link_end_t(joint_ground_pin, 0, 0.0_dp)
    call t%build([1], ends, err)
    call assert_true(.not. err%failed(), 'a pinned-pinned beam has its two slopes free')
    call assert_equal(t%n_unknowns(), 2, 'pinned-pinned single element: th1, th2')
  end subroutine test_no_free_dof

  !> 14-DOF four-bar: alpha follows th (0 at the clamp, own elsewhere), psi
  !> follows m (own at the clamp, 0 at pins), lam always own: 10 + 12 unknowns.
  subroutine test_alpha_rules()
    type(correlation_table_t) :: tt
    type(error_t) :: err
    type(link_end_t) :: ends(2, 3)
    ends(:, 1) = [link_end_t(joint_clamp, 1), link_end_t(joint_pin, 2)]
    ends(:, 2) = [link_end_t(joint_pin, 2), link_end_t(joint_pin, 3)]
    ends(:, 3) = [link_end_t(joint_ground_pin, 4), link_end_t(joint_pin, 3)]
    call tt%build([1, 1, 1], ends, err, shear_dofs=.true.)
    call assert_true(.not. err%failed(), 'build')
    call assert_equal(tt%element_dofs(), 14, 'element DOFs')
    call assert_equal(tt%n_unknowns(), 22, 'unknowns')
    ! node A (clamp): U W th a held; m psi lam own
    call assert_true(all(tt%unknowns_of([1, 2, 3, 5], 1) == 0) .and. all(tt%unknowns_of([4, 6, 7], 1) > 0), 'clamp')
    ! node B of the crank (pin): U W th a lam own; m psi held
    call assert_true(all(tt%unknowns_of([8, 9, 10, 12, 14], 1) > 0) .and. all(tt%unknowns_of([11, 13], 1) == 0), 'pin')
    ! the coupler shares B's translations, not its slope or shear angle
    call assert_true(all(tt%unknowns_of([1, 2], 2) == tt%unknowns_of([8, 9], 1)), 'pin shares U, W')
    call assert_true(tt%unknown(3, 2) /= tt%unknown(10, 1) .and. tt%unknown(5, 2) /= tt%unknown(12, 1), 'own th, a')
    ! ground pin D: U W m psi held; th a lam own
    call assert_true(all(tt%unknowns_of([1, 2, 4, 6], 3) == 0) .and. all(tt%unknowns_of([3, 5, 7], 3) > 0), &
                     'ground pin')
  end subroutine test_alpha_rules

  !> Inverted slider-crank with the sleeve on the crank pin B: link 2 runs
  !> from the ground pin D to the sleeve.  Local (u2, w2) of link 2's end at
  !> the sleeve: w2 = -sin(phi) U_s + cos(phi) W_s (the sleeve's displacement
  !> across link 2), u2 = s (its own axial unknown).  Exact (1e-15).
  subroutine test_sleeve_carried()
    type(correlation_table_t) :: tt
    type(error_t) :: err
    type(link_end_t) :: ends(2, 2)
    real(dp) :: c0(16, 16), c1(16, 16), c2(16, 16), q(8), qe(8), phi, us, ws, s, uw(2), qg(16)
    integer :: ng, e, i, g(16), sleeve(3)
    ends(:, 1) = [link_end_t(joint_clamp, 1), link_end_t(joint_pin, 2)]
    ends(:, 2) = [link_end_t(joint_ground_pin, 3), link_end_t(joint_sleeve, 2, carried=.true.)]
    call tt%build([1, 1], ends, err)
    call assert_true(.not. err%failed(), 'build')
    e = 2
    call assert_true(tt%is_sleeve_element(e), 'sleeve element')
    phi = 0.7_dp
    call tt%element_map(e, phi, 3.0_dp, -5.0_dp, ng, c0, c1, c2)
    q = [(0.01_dp*i, i = 1, 8)]
    call assert_equal(size(tt%globals_of(e)), ng, 'element_map''s columns')
    g(1:ng) = tt%globals_of(e)
    do i = 1, ng
      qg(i) = q(g(i))
    end do
    qe = matmul(c0(1:8, 1:ng), qg(1:ng))
    sleeve = tt%sleeve_unknowns(e)
    s = q(sleeve(1))
    us = q(sleeve(2))
    ws = q(sleeve(3))
    uw = [cos(phi)*qe(5) + sin(phi)*qe(6), -sin(phi)*qe(5) + cos(phi)*qe(6)]
    call assert_close(uw(1), s, 1.0e-15_dp, 'axial = s')
    call assert_close(uw(2), -sin(phi)*us + cos(phi)*ws, 1.0e-15_dp, 'transverse = sleeve across the link')
    call assert_equal(sleeve(2), tt%unknown(5, 1), 'the sleeve moves with the crank pin')
  end subroutine test_sleeve_carried

  subroutine test_sleeve_ground()
    type(correlation_table_t) :: tt
    type(error_t) :: err
    type(link_end_t) :: ends(2, 2)
    real(dp) :: c0(16, 16), c1(16, 16), c2(16, 16), phi
    integer :: ng, js, sleeve(3)
    ends(:, 1) = [link_end_t(joint_clamp, 1), link_end_t(joint_pin, 2)]
    ends(:, 2) = [link_end_t(joint_pin, 2), link_end_t(joint_sleeve, 3, carried=.false.)]
    call tt%build([1, 1], ends, err)
    call assert_true(.not. err%failed(), 'build')
    phi = -1.2_dp
    call tt%element_map(2, phi, 0.0_dp, 0.0_dp, ng, c0, c1, c2)
    sleeve = tt%sleeve_unknowns(2)
    js = findloc(tt%globals_of(2), sleeve(1), dim=1)
    call assert_all_close(c0(5:6, js), [cos(phi), sin(phi)], 0.0_dp, 1.0e-15_dp, '(U2, W2) = s u(phi)')
    call assert_true(all(sleeve(2:3) == 0), 'no sleeve translation unknowns')
    call assert_equal(ng, 5, 'globals: B U, B W, th1, s, th2')
  end subroutine test_sleeve_ground

  !> C_d = dC/dt and C_dd against central differences along
  !> phi(t) = 0.4 + 30 t + 200 t^2 (h = 1e-5; 1e-6 relative).
  subroutine test_sleeve_rates()
    type(correlation_table_t) :: tt
    type(error_t) :: err
    type(link_end_t) :: ends(2, 2)
    real(dp) :: c0(16, 16), c1(16, 16), c2(16, 16), cp(16, 16), cm(16, 16), d1(16, 16), d2(16, 16)
    real(dp), parameter :: t = 0.01_dp, h = 1.0e-5_dp
    integer :: ng
    ends(:, 1) = [link_end_t(joint_clamp, 1), link_end_t(joint_pin, 2)]
    ends(:, 2) = [link_end_t(joint_ground_pin, 3), link_end_t(joint_sleeve, 2, carried=.true.)]
    call tt%build([1, 1], ends, err)
    c0 = 0.0_dp; c1 = 0.0_dp; c2 = 0.0_dp; cp = 0.0_dp; cm = 0.0_dp
    call tt%element_map(2, ph(t), pd(t), 400.0_dp, ng, c0, c1, c2)
    call tt%element_map(2, ph(t + h), pd(t + h), 400.0_dp, ng, cp, d1, d2)
    call tt%element_map(2, ph(t - h), pd(t - h), 400.0_dp, ng, cm, d1, d2)
    call assert_all_close(reshape(c1(1:8, 1:ng), [8*ng]), reshape((cp(1:8, 1:ng) - cm(1:8, 1:ng))/(2*h), [8*ng]), &
                          0.0_dp, 1.0e-6_dp*maxval(abs(c1)), 'C_d')
    call assert_all_close(reshape(c2(1:8, 1:ng), [8*ng]), &
                          reshape((cp(1:8, 1:ng) - 2*c0(1:8, 1:ng) + cm(1:8, 1:ng))/(h*h), [8*ng]), &
                          0.0_dp, 1.0e-5_dp*maxval(abs(c2)), 'C_dd')
  contains
    real(dp) function ph(tt_)
      real(dp), intent(in) :: tt_
      ph = 0.4_dp + 30.0_dp*tt_ + 200.0_dp*tt_*tt_
    end function ph
    real(dp) function pd(tt_)
      real(dp), intent(in) :: tt_
      pd = 30.0_dp + 400.0_dp*tt_
    end function pd
  end subroutine test_sleeve_rates

  subroutine test_bad_sleeves()
    type(correlation_table_t) :: a, b
    type(error_t) :: err
    type(link_end_t) :: ends(2, 2)
    ends(:, 1) = [link_end_t(joint_clamp, 1), link_end_t(joint_pin, 2)]
    ends(:, 2) = [link_end_t(joint_sleeve, 3), link_end_t(joint_pin, 2)]
    call a%build([1, 1], ends, err)
    call assert_true(err%failed(), 'sleeve at end 1')
    call err%clear()
    ends(:, 2) = [link_end_t(joint_pin, 2), link_end_t(joint_sleeve, 3)]
    call b%build([1, 2], ends, err)
    call assert_true(err%failed(), 'sliding link with two elements')
  end subroutine test_bad_sleeves

end module test_correlation_table_suite

program test_correlation_table
  use test_correlation_table_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_correlation_table')
end program test_correlation_table
