!> Tests of the spatial four-bar kinematics (module spatial_kinematics):
!> the RSSR linkage with perpendicular crank and rocker axes against the
!> closed form, loop closure, rates against differences of positions, link
!> frames against differences of the rotation matrices, branch, toggle and
!> non-assembly messages; the universal joint (RSUR, RUSR): the coupler frame
!> from the cross's axes, the relative angular velocity in the plane of the
!> two axes, rates by differences, the locked joint named by crank angle.
module test_spatial_kinematics_suite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use spatial_kinematics
  use linalg, only: cross
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('rssr_newton_equals_closed_form', test_closed_form)
    call run_test('rssr_rates_are_derivatives_of_positions', test_rates)
    call run_test('link_frames_and_angular_rates', test_frames)
    call run_test('branch_toggle_and_non_assembly_named_by_crank_angle', test_failures)
    call run_test('far_jumps_in_crank_angle_keep_the_branch', test_far_jumps)
    call run_test('universal_joint_coupler_frame_and_rates', test_universal)
    call run_test('universal_joint_lock_named_by_crank_angle', test_universal_lock)
  end subroutine run_all

  !> RSSR: crank axis Z through the origin, crank 1.5; rocker axis X through
  !> (0, 5, 3), rocker 3; coupler 6 (assembles at every crank angle,
  !> max |S|/R = 0.56).
  subroutine rssr(m, branch)
    type(spatial_fourbar_t), intent(out) :: m
    integer, intent(in) :: branch
    type(error_t) :: err
    call spatial_fourbar_init(m, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 2.0_dp], [1.5_dp, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 5.0_dp, 3.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 3.0_dp, 6.0_dp, branch, err)
    call assert_true(.not. err%failed(), 'init: '//err%text())
  end subroutine rssr

  !> Newton (analytic Jacobian, warm start from the previous angle) vs the
  !> closed form psi = atan2(Q,P) + branch acos(S/R), 1e-10 rad over two
  !> turns in 5 degree steps, both branches; |C - B| = L and |C - D| = rho
  !> to 1e-12 relative; C in the rocker plane.
  subroutine test_closed_form()
    type(spatial_fourbar_t) :: m
    type(spatial_pose_t) :: pose
    type(error_t) :: err
    real(dp) :: theta, psi_cf
    integer :: k, status, br
    do br = -1, 1, 2
      call rssr(m, br)
      do k = 0, 144
        theta = real(k, dp)*5.0_dp*pi/180.0_dp
        call spatial_fourbar_solve(m, theta, 1.0_dp, 0.0_dp, pose, err)
        call assert_true(.not. err%failed(), 'solve: '//err%text())
        call rocker_angle_closed_form(m, theta, psi_cf, status)
        call assert_equal(status, 0, 'closed form assembles')
        call assert_close(modulo(pose%psi - psi_cf + pi, 2.0_dp*pi) - pi, 0.0_dp, 1.0e-10_dp, 'psi Newton = closed form')
        call assert_rel_close(norm2(pose%c - pose%b), 6.0_dp, 1.0e-12_dp, 'coupler length')
        call assert_rel_close(norm2(pose%c - [0.0_dp, 5.0_dp, 3.0_dp]), 3.0_dp, 1.0e-12_dp, 'rocker length')
        call assert_close(pose%c(1), 0.0_dp, 1.0e-12_dp, 'C in the rocker plane x = 0')
        call assert_true(pose%iterations <= 6, 'warm-started Newton converges in a few steps')
      end do
    end do
    ! the two branches are different assemblies (the coupler reaches the
    ! circle at its two intersection points)
    call rssr(m, 1)
    call spatial_fourbar_solve(m, 0.3_dp, 1.0_dp, 0.0_dp, pose, err)
    psi_cf = pose%psi
    call rssr(m, -1)
    call spatial_fourbar_solve(m, 0.3_dp, 1.0_dp, 0.0_dp, pose, err)
    call assert_true(abs(sin(pose%psi - psi_cf)) > 0.1_dp, 'branches differ')
  end subroutine test_closed_form

  !> psi_d, psi_dd, B and C rates vs central differences in time of the
  !> positions (theta = theta0 + w t + a t^2/2), h = 1e-5 s: truncation
  !> ~h^2 |psi'''| ~ 1e-8 of the scale; tolerance 1e-6 relative to scale.
  subroutine test_rates()
    type(spatial_fourbar_t) :: m
    type(spatial_pose_t) :: p0, pp, pm
    type(error_t) :: err
    real(dp), parameter :: th0 = 1.1_dp, w = 40.0_dp, acc = 900.0_dp, h = 1.0e-5_dp
    call rssr(m, 1)
    call spatial_fourbar_solve(m, th0, w, acc, p0, err)
    call spatial_fourbar_solve(m, th0 + w*h + 0.5_dp*acc*h*h, w + acc*h, acc, pp, err)
    call spatial_fourbar_solve(m, th0 - w*h + 0.5_dp*acc*h*h, w - acc*h, acc, pm, err)
    call assert_rel_close(p0%psi_d, (pp%psi - pm%psi)/(2.0_dp*h), 1.0e-6_dp, 'psi_d')
    call assert_rel_close(p0%psi_dd, (pp%psi_d - pm%psi_d)/(2.0_dp*h), 1.0e-6_dp, 'psi_dd')
    call assert_all_close(p0%c_d, (pp%c - pm%c)/(2.0_dp*h), 0.0_dp, 1.0e-6_dp*norm2(p0%c_d), 'C_d')
    call assert_all_close(p0%c_dd, (pp%c_d - pm%c_d)/(2.0_dp*h), 0.0_dp, 1.0e-6_dp*norm2(p0%c_dd), 'C_dd')
    call assert_all_close(p0%b_dd, (pp%b_d - pm%b_d)/(2.0_dp*h), 0.0_dp, 1.0e-6_dp*norm2(p0%b_dd), 'B_dd')
  end subroutine test_rates

  !> Each frame orthonormal and right-handed (1e-13), x along its link,
  !> skew(omega) = R_dot R^T and alpha = omega_dot by central differences
  !> (1e-6 relative, as above).
  subroutine test_frames()
    type(spatial_fourbar_t) :: m
    type(spatial_pose_t) :: p0, pp, pm
    type(error_t) :: err
    real(dp), parameter :: th0 = 2.3_dp, w = 40.0_dp, acc = -700.0_dp, h = 1.0e-5_dp
    real(dp) :: rd(3, 3), om(3, 3), r(3, 3), eye(3, 3)
    integer :: k, i
    call rssr(m, 1)
    call spatial_fourbar_solve(m, th0, w, acc, p0, err)
    call spatial_fourbar_solve(m, th0 + w*h + 0.5_dp*acc*h*h, w + acc*h, acc, pp, err)
    call spatial_fourbar_solve(m, th0 - w*h + 0.5_dp*acc*h*h, w - acc*h, acc, pm, err)
    eye = 0.0_dp
    do i = 1, 3
      eye(i, i) = 1.0_dp
    end do
    do k = 1, 3
      r = p0%rot(:, :, k)
      call assert_all_close(reshape(matmul(transpose(r), r), [9]), reshape(eye, [9]), 0.0_dp, 1.0e-13_dp, &
                            'orthonormal')
      call assert_all_close(cross(r(:, 1), r(:, 2)), r(:, 3), 0.0_dp, 1.0e-13_dp, 'right-handed')
      rd = (pp%rot(:, :, k) - pm%rot(:, :, k))/(2.0_dp*h)
      om = matmul(rd, transpose(r))
      call assert_all_close([om(3, 2), om(1, 3), om(2, 1)], p0%omega(:, k), 0.0_dp, &
                            1.0e-6_dp*norm2(p0%omega(:, k)), 'omega from R_dot R^T')
      call assert_all_close((pp%omega(:, k) - pm%omega(:, k))/(2.0_dp*h), p0%alpha(:, k), 0.0_dp, &
                            1.0e-6_dp*norm2(p0%alpha(:, k)), 'alpha = omega_dot')
    end do
    call assert_all_close(p0%rot(:, 1, link_coupler), (p0%c - p0%b)/6.0_dp, 0.0_dp, 1.0e-14_dp, 'coupler x')
    call assert_all_close(p0%rot(:, 3, link_rocker), [1.0_dp, 0.0_dp, 0.0_dp], 0.0_dp, 1.0e-14_dp, 'rocker z = d')
  end subroutine test_frames

  !> The integrator may sample far from its last time (a solver-settings pass
  !> over a long run): a solve after a jump of many turns lands on the deck's
  !> branch, on both branches, equal to the closed form.
  subroutine test_far_jumps()
    type(spatial_fourbar_t) :: m
    type(spatial_pose_t) :: pose
    type(error_t) :: err
    real(dp) :: psi_cf, theta
    integer :: k, status, br
    do br = -1, 1, 2
      ! Tennant's four-bar in the plane z = 0 (crank 5, coupler 11, rocker
      ! 10.5, ground 10), whose rocker swings widely: a stale guess from far
      ! away lies nearer the other branch's root at some angles
      call spatial_fourbar_init(m, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [5.0_dp, 0.0_dp, 0.0_dp], &
                                [10.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], 10.5_dp, 11.0_dp, br, err)
      call assert_true(.not. err%failed(), 'init: '//err%text())
      do k = 1, 720
        ! from a solve at 14 pi (the end of a seven-turn run) back to 1, 2, ... 360 deg
        theta = merge(14.0_dp*pi, real(k/2, dp)*pi/180.0_dp, mod(k, 2) == 1)
        call spatial_fourbar_solve(m, theta, 1.0_dp, 0.0_dp, pose, err)
        call assert_true(.not. err%failed(), 'solve after a jump: '//err%text())
        call err%clear()
        call rocker_angle_closed_form(m, theta, psi_cf, status)
        call assert_close(modulo(pose%psi - psi_cf + pi, 2.0_dp*pi) - pi, 0.0_dp, 1.0e-10_dp, 'branch kept')
      end do
    end do
  end subroutine test_far_jumps

  !> Non-assembly: coupler 2 cannot reach (named crank angle); toggle: a
  !> coupler length at which S = R at theta = 0 exactly (the crank pin's
  !> distance to the circle); bad geometry rejected by init.
  subroutine test_failures()
    type(spatial_fourbar_t) :: m
    type(spatial_pose_t) :: pose
    type(error_t) :: err
    real(dp) :: dist
    call spatial_fourbar_init(m, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [1.5_dp, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 5.0_dp, 3.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 3.0_dp, 2.0_dp, 1, err)
    call spatial_fourbar_solve(m, 0.5_dp, 1.0_dp, 0.0_dp, pose, err)
    call assert_true(err%failed() .and. index(err%text(), 'does not assemble') > 0 .and. &
                     index(err%text(), '28.6478') > 0, 'non-assembly named: '//err%text())
    call err%clear()
    ! toggle at theta = 0: coupler length = largest distance from B0 to the circle
    ! B0 = (1.5, 0, 0), circle x = 0 centre (0,5,3) radius 3: farthest point
    dist = sqrt(1.5_dp**2 + (sqrt(5.0_dp**2 + 3.0_dp**2) + 3.0_dp)**2)
    call spatial_fourbar_init(m, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [1.5_dp, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 5.0_dp, 3.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 3.0_dp, dist, 1, err)
    call spatial_fourbar_solve(m, 0.0_dp, 1.0_dp, 0.0_dp, pose, err)
    call assert_true(err%failed() .and. (index(err%text(), 'toggle') > 0 .or. index(err%text(), 'assemble') > 0) &
                     .and. index(err%text(), 'crank angle 0') > 0, 'toggle named: '//err%text())
    call err%clear()
    call spatial_fourbar_init(m, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [1.5_dp, 0.0_dp, 0.0_dp], &
                              [0.0_dp, 5.0_dp, 3.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 0.0_dp, 6.0_dp, 1, err)
    call assert_true(err%failed() .and. index(err%text(), 'positive') > 0, 'zero rocker: '//err%text())
    call err%clear()
    call spatial_fourbar_init(m, [0.0_dp, 0.0_dp, 0.0_dp], [0.0_dp, 0.0_dp, 1.0_dp], [1.5_dp, 0.0_dp, 0.2_dp], &
                              [0.0_dp, 5.0_dp, 3.0_dp], [1.0_dp, 0.0_dp, 0.0_dp], 3.0_dp, 6.0_dp, 1, err)
    call assert_true(err%failed() .and. index(err%text(), 'plane') > 0, 'pin off the crank plane: '//err%text())
  end subroutine test_failures
  !> RSUR (cross axis fixed in the rocker, at C) and RUSR (in the crank, at B)
  !> on the RSSR above, skew axes in the link frames.  Over two turns in 5
  !> degree steps: the loop closure is the RSSR's (psi equal), the coupler
  !> frame orthonormal with x = BC/L (1e-13), its z (the cross's second axis,
  !> fixed in the coupler) normal to the link-fixed axis u (1e-12).  The
  !> property the construction does not use: a universal joint lets the
  !> coupler turn relative to the link about u and z only, so the relative
  !> angular velocity has no component along u x z (1e-10 of its size).
  !> Rates: omega from R_dot R^T and alpha = omega_dot by central differences
  !> (1e-6 relative, as test_frames).
  subroutine test_universal()
    type(spatial_fourbar_t) :: m, ref
    type(spatial_pose_t) :: p0, pp, pm, pr
    type(error_t) :: err
    real(dp), parameter :: w = 40.0_dp, acc = -700.0_dp, h = 1.0e-5_dp
    real(dp) :: u(3), z(3), wrel(3), r(3, 3), rd(3, 3), om(3, 3), theta, th0
    integer :: side, k, lk
    do side = 1, 2
      call rssr(m, 1)
      call rssr(ref, 1)
      if (side == 1) then
        call spatial_fourbar_set_universal(m, .true., [0.0_dp, 1.0_dp, 1.0_dp], err)
        lk = link_rocker
      else
        call spatial_fourbar_set_universal(m, .false., [0.3_dp, 0.5_dp, 1.0_dp], err)
        lk = link_crank
      end if
      call assert_true(.not. err%failed(), 'set universal')
      do k = 0, 144
        theta = real(k, dp)*5.0_dp*pi/180.0_dp
        call spatial_fourbar_solve(m, theta, w, acc, p0, err)
        call spatial_fourbar_solve(ref, theta, w, acc, pr, err)
        call assert_true(.not. err%failed(), 'solve: '//err%text())
        call assert_close(p0%psi, pr%psi, 1.0e-12_dp, 'loop closure as the RSSR')
        r = p0%rot(:, :, link_coupler)
        call assert_all_close(reshape(matmul(transpose(r), r), [9]), [1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, &
                              0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], 0.0_dp, 1.0e-13_dp, 'coupler frame orthonormal')
        call assert_all_close(r(:, 1), (p0%c - p0%b)/6.0_dp, 0.0_dp, 1.0e-13_dp, 'coupler x = BC/L')
        u = matmul(p0%rot(:, :, lk), m%u_local)
        z = r(:, 3)
        call assert_close(dot_product(z, u), 0.0_dp, 1.0e-12_dp, 'cross axes normal')
        wrel = p0%omega(:, link_coupler) - p0%omega(:, lk)
        call assert_close(dot_product(wrel, cross(u, z)), 0.0_dp, 1.0e-10_dp*norm2(wrel), &
                          'relative rotation about the cross axes only')
      end do
      th0 = 2.3_dp
      call spatial_fourbar_solve(m, th0, w, acc, p0, err)
      call spatial_fourbar_solve(m, th0 + w*h + 0.5_dp*acc*h*h, w + acc*h, acc, pp, err)
      call spatial_fourbar_solve(m, th0 - w*h + 0.5_dp*acc*h*h, w - acc*h, acc, pm, err)
      r = p0%rot(:, :, link_coupler)
      rd = (pp%rot(:, :, link_coupler) - pm%rot(:, :, link_coupler))/(2.0_dp*h)
      om = matmul(rd, transpose(r))
      call assert_all_close([om(3, 2), om(1, 3), om(2, 1)], p0%omega(:, link_coupler), 0.0_dp, &
                            1.0e-6_dp*norm2(p0%omega(:, link_coupler)), 'coupler omega from R_dot R^T')
      call assert_all_close((pp%omega(:, link_coupler) - pm%omega(:, link_coupler))/(2.0_dp*h), &
                            p0%alpha(:, link_coupler), 0.0_dp, 1.0e-6_dp*norm2(p0%alpha(:, link_coupler)), &
                            'coupler alpha = omega_dot')
      ! the universal joint changes the coupler's spin, not its axis: the RSSR's frame differs
      call spatial_fourbar_solve(ref, th0, w, acc, pr, err)
      call assert_true(abs(dot_product(pr%rot(:, 3, link_coupler), u)) > 1.0e-3_dp, 'the RSSR frame is another spin')
    end do
  end subroutine test_universal

  !> The cross's axis in the rocker chosen along BC at theta = 0: the joint
  !> locks there, named by crank angle; a zero axis is refused.
  subroutine test_universal_lock()
    type(spatial_fourbar_t) :: m
    type(spatial_pose_t) :: pose
    type(error_t) :: err
    real(dp) :: ul(3)
    call rssr(m, 1)
    call spatial_fourbar_solve(m, 0.0_dp, 1.0_dp, 0.0_dp, pose, err)
    ul = matmul(transpose(pose%rot(:, :, link_rocker)), pose%rot(:, 1, link_coupler))
    call rssr(m, 1)
    call spatial_fourbar_set_universal(m, .true., ul, err)
    call spatial_fourbar_solve(m, 0.0_dp, 1.0_dp, 0.0_dp, pose, err)
    call assert_true(err%failed() .and. index(err%text(), 'universal joint at C locks') > 0 .and. &
                     index(err%text(), 'crank angle 0') > 0, 'lock named: '//err%text())
    call err%clear()
    call spatial_fourbar_set_universal(m, .false., [0.0_dp, 0.0_dp, 0.0_dp], err)
    call assert_true(err%failed() .and. index(err%text(), 'nonzero') > 0, 'zero axis: '//err%text())
  end subroutine test_universal_lock
end module test_spatial_kinematics_suite

program test_spatial_kinematics
  use test_spatial_kinematics_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_spatial_kinematics')
end program test_spatial_kinematics
