!> Tests of the correlation table for Tennant's elements (module
!> tennant_table): the 8-DOF table is correlation_table's, the shear-angle
!> rules, and the sleeve end's angle-dependent map.
module test_tennant_table_suite
  use kinds, only: dp
  use error_status, only: error_t
  use correlation_table, only: correlation_table_t, link_end_t
  use tennant_table
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('eight_dof_table_equals_correlation_table', test_equals_base)
    call run_test('shear_angle_dofs_follow_slope_and_curvature_rules', test_alpha_rules)
    call run_test('sleeve_end_takes_the_sleeve_displacement_across_the_link', test_sleeve_carried)
    call run_test('ground_sleeve_end_slides_along_the_link', test_sleeve_ground)
    call run_test('sleeve_map_rates_match_fd', test_sleeve_rates)
    call run_test('bad_sleeve_ends_are_rejected', test_bad_sleeves)
  end subroutine run_all

  !> Four-bar (clamp, pin, pin, ground pin), slider-crank (clamp, pin,
  !> slider_fixed) and a cantilever (clamp, free), 1 and 3 elements per link:
  !> identical map, coefficients, unknowns, labels and band width.
  subroutine test_equals_base()
    call compare([1, 1, 1], reshape([le(3, 1), le(1, 2), le(1, 2), le(1, 3), le(2, 4), le(1, 3)], [2, 3]), 'four-bar')
    call compare([3, 2, 3], reshape([le(3, 1), le(1, 2), le(1, 2), le(1, 3), le(2, 4), le(1, 3)], [2, 3]), &
                 'four-bar, several elements')
    call compare([1, 2], reshape([le(3, 1), le(1, 2), le(1, 2), le(4, 3, 0.3_dp)], [2, 2]), 'slider-crank')
    call compare([4], reshape([le(3, 1), le(0, 2)], [2, 1]), 'cantilever')
  contains
    function le(kind, joint, angle) result(e)
      integer, intent(in) :: kind, joint
      real(dp), intent(in), optional :: angle
      type(link_end_t) :: e
      e = link_end_t(kind, joint, 0.0_dp)
      if (present(angle)) e%guide_angle = angle
    end function le
    subroutine compare(n_elem, ends, label)
      integer, intent(in) :: n_elem(:)
      type(link_end_t), intent(in) :: ends(:, :)
      character(len=*), intent(in) :: label
      type(correlation_table_t) :: base
      type(tennant_table_t) :: tt
      type(table_end_t) :: te(size(ends, 1), size(ends, 2))
      type(error_t) :: err
      integer :: i, j
      do j = 1, size(ends, 2)
        do i = 1, 2
          te(i, j) = table_end_t(ends(i, j)%kind, ends(i, j)%joint, ends(i, j)%guide_angle)
        end do
      end do
      call base%build(n_elem, ends, err)
      call tt%build(n_elem, te, .false., err)
      call assert_true(.not. err%failed(), label//': build')
      call assert_equal(tt%n_global, base%n_global, label//': unknowns')
      call assert_equal(tt%half_bandwidth, base%half_bandwidth, label//': band')
      call assert_true(all(tt%map == base%map), label//': map')
      call assert_true(.not. any(abs(tt%coef - base%coef) > 0.0_dp), label//': coefficients')
      call assert_true(all(tt%label == base%label), label//': labels')
    end subroutine compare
  end subroutine test_equals_base

  !> 14-DOF four-bar: alpha follows th (0 at the clamp, own elsewhere), psi
  !> follows m (own at the clamp, 0 at pins), lam always own: 10 + 12 unknowns.
  subroutine test_alpha_rules()
    type(tennant_table_t) :: tt
    type(error_t) :: err
    type(table_end_t) :: ends(2, 3)
    ends(:, 1) = [table_end_t(end_clamp, 1), table_end_t(end_pin, 2)]
    ends(:, 2) = [table_end_t(end_pin, 2), table_end_t(end_pin, 3)]
    ends(:, 3) = [table_end_t(end_ground_pin, 4), table_end_t(end_pin, 3)]
    call tt%build([1, 1, 1], ends, .true., err)
    call assert_true(.not. err%failed(), 'build')
    call assert_equal(tt%nd, 14, 'element DOFs')
    call assert_equal(tt%n_global, 22, 'unknowns')
    ! node A (clamp): U W th a held; m psi lam own
    call assert_true(all(tt%map([1, 2, 3, 5], 1) == 0) .and. all(tt%map([4, 6, 7], 1) > 0), 'clamp')
    ! node B of the crank (pin): U W th a lam own; m psi held
    call assert_true(all(tt%map([8, 9, 10, 12, 14], 1) > 0) .and. all(tt%map([11, 13], 1) == 0), 'pin')
    ! the coupler shares B's translations, not its slope or shear angle
    call assert_true(all(tt%map(1:2, 2) == tt%map(8:9, 1)), 'pin shares U, W')
    call assert_true(tt%map(3, 2) /= tt%map(10, 1) .and. tt%map(5, 2) /= tt%map(12, 1), 'own th, a')
    ! ground pin D: U W m psi held; th a lam own
    call assert_true(all(tt%map([1, 2, 4, 6], 3) == 0) .and. all(tt%map([3, 5, 7], 3) > 0), 'ground pin')
  end subroutine test_alpha_rules

  !> Inverted slider-crank with the sleeve on the crank pin B: link 2 runs
  !> from the ground pin D to the sleeve.  Local (u2, w2) of link 2's end at
  !> the sleeve: w2 = -sin(phi) U_s + cos(phi) W_s (the sleeve's displacement
  !> across link 2), u2 = s (its own axial unknown).  Exact (1e-15).
  subroutine test_sleeve_carried()
    type(tennant_table_t) :: tt
    type(error_t) :: err
    type(table_end_t) :: ends(2, 2)
    real(dp) :: c0(16, 16), c1(16, 16), c2(16, 16), q(8), qe(8), phi, us, ws, s, uw(2), qg(16)
    integer :: ng, e, i
    ends(:, 1) = [table_end_t(end_clamp, 1), table_end_t(end_pin, 2)]
    ends(:, 2) = [table_end_t(end_ground_pin, 3), table_end_t(end_sleeve, 2, carried=.true.)]
    call tt%build([1, 1], ends, .false., err)
    call assert_true(.not. err%failed(), 'build')
    e = 2
    call assert_true(tt%is_sleeve_element(e), 'sleeve element')
    phi = 0.7_dp
    call tt%element_map(e, phi, 3.0_dp, -5.0_dp, ng, c0, c1, c2)
    q = [(0.01_dp*i, i = 1, 8)]
    do i = 1, ng
      qg(i) = q(tt%glob(i, e))
    end do
    qe = matmul(c0(1:8, 1:ng), qg(1:ng))
    us = q(tt%sleeve_u(e))
    ws = q(tt%sleeve_w(e))
    s = q(tt%sleeve_s(e))
    uw = [cos(phi)*qe(5) + sin(phi)*qe(6), -sin(phi)*qe(5) + cos(phi)*qe(6)]
    call assert_close(uw(1), s, 1.0e-15_dp, 'axial = s')
    call assert_close(uw(2), -sin(phi)*us + cos(phi)*ws, 1.0e-15_dp, 'transverse = sleeve across the link')
    call assert_equal(tt%sleeve_u(e), tt%map(5, 1), 'the sleeve moves with the crank pin')
  end subroutine test_sleeve_carried

  subroutine test_sleeve_ground()
    type(tennant_table_t) :: tt
    type(error_t) :: err
    type(table_end_t) :: ends(2, 2)
    real(dp) :: c0(16, 16), c1(16, 16), c2(16, 16), phi
    integer :: ng, js
    ends(:, 1) = [table_end_t(end_clamp, 1), table_end_t(end_pin, 2)]
    ends(:, 2) = [table_end_t(end_pin, 2), table_end_t(end_sleeve, 3, carried=.false.)]
    call tt%build([1, 1], ends, .false., err)
    call assert_true(.not. err%failed(), 'build')
    phi = -1.2_dp
    call tt%element_map(2, phi, 0.0_dp, 0.0_dp, ng, c0, c1, c2)
    js = findloc(tt%glob(1:ng, 2), tt%sleeve_s(2), dim=1)
    call assert_all_close(c0(5:6, js), [cos(phi), sin(phi)], 0.0_dp, 1.0e-15_dp, '(U2, W2) = s u(phi)')
    call assert_equal(tt%sleeve_u(2), 0, 'no sleeve translation unknowns')
    call assert_equal(ng, 5, 'globals: B U, B W, th1, s, th2')
  end subroutine test_sleeve_ground

  !> C_d = dC/dt and C_dd against central differences along
  !> phi(t) = 0.4 + 30 t + 200 t^2 (h = 1e-5; 1e-6 relative).
  subroutine test_sleeve_rates()
    type(tennant_table_t) :: tt
    type(error_t) :: err
    type(table_end_t) :: ends(2, 2)
    real(dp) :: c0(16, 16), c1(16, 16), c2(16, 16), cp(16, 16), cm(16, 16), d1(16, 16), d2(16, 16)
    real(dp), parameter :: t = 0.01_dp, h = 1.0e-5_dp
    integer :: ng
    ends(:, 1) = [table_end_t(end_clamp, 1), table_end_t(end_pin, 2)]
    ends(:, 2) = [table_end_t(end_ground_pin, 3), table_end_t(end_sleeve, 2, carried=.true.)]
    call tt%build([1, 1], ends, .false., err)
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
    type(tennant_table_t) :: a, b
    type(error_t) :: err
    type(table_end_t) :: ends(2, 2)
    ends(:, 1) = [table_end_t(end_clamp, 1), table_end_t(end_pin, 2)]
    ends(:, 2) = [table_end_t(end_sleeve, 3), table_end_t(end_pin, 2)]
    call a%build([1, 1], ends, .false., err)
    call assert_true(err%failed(), 'sleeve at end 1')
    call err%clear()
    ends(:, 2) = [table_end_t(end_pin, 2), table_end_t(end_sleeve, 3)]
    call b%build([1, 2], ends, .false., err)
    call assert_true(err%failed(), 'sliding link with two elements')
  end subroutine test_bad_sleeves
end module test_tennant_table_suite

program test_tennant_table
  use assertions, only: finish_suite
  use test_tennant_table_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_tennant_table')
end program test_tennant_table
