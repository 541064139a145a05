!> Tests of what `flexmech plot` reads to draw the deformed mechanism and to
!> label its axes: the units of the column descriptions, and the link shapes
!> of a transient, a steady and a spatial run with `shape_points` (the link
!> points that the run evaluates with the elements' shape functions), checked
!> against the run's own end and joint columns, which are computed without the
!> link points, and against the interpolation (a clamped one-element link's
!> points lie on a quintic through the clamp with zero value there); the
!> drawn links are bent by nonzero shape columns and straight by zero ones.
module test_plot_shapes_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use run_output, only: run_output_t, read_run_output, column_index, column_unit
  use linkage, only: mechanism_t
  use linkage_deck, only: read_mechanism
  use kinematics, only: kinematics_t
  use transient_analysis, only: run_transient
  use steady_analysis, only: run_steady
  use spatial_analysis, only: run_spatial
  use spatial_kinematics, only: link_crank, link_coupler, link_rocker
  use linalg, only: solve_linear
  use plot_animation, only: link_shapes, link_shape_t, nice_factor, drawn_frame
  use plot_spatial, only: spatial_link_shapes, spatial_shape_3d_t, spatial_frame
  use deck_runner, only: scratch_path, write_deck, analysis_runner
  use assertions
  implicit none
  private
  public :: run_all

  !> The damped four-bar of inputs/fourbar_150_damped.nml over a third of a
  !> revolution, two elements on the coupler, 4 intervals per element drawn.
  character(len=*), parameter :: deck_text = &
    "&run analysis = 'transient', title = 'shape points' /|" // &
    "&mechanism n_joints = 4, joint_name = 'A', 'B', 'C', 'D', joint_type = 'clamp', 'pin', 'pin', 'ground_pin'," // &
    " joint_x(1) = 0.0, joint_y(1) = 0.0, joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3," // &
    " link_name = 'crank', 'coupler', 'rocker', link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3," // &
    " link_length = 5.0, 11.0, 10.5, link_b = 3*0.25, link_h = 3*1.0, link_n_elements = 1, 2, 1," // &
    " driver_link = 1, omega = 150.0, branch = 'open' /|" // &
    "&transient method = 'bdf', rtol = 1e-7, atol = 1e-11, revolutions = 0.35, output_step_deg = 5," // &
    " damping_beta = 1e-5, shape_points = 4 /"

  !> The linear four-bar of T Figs. 5-8 (inputs/tennant_fig5_exact.nml), the
  !> coupler of two elements, both solutions, 8 intervals per element drawn.
  character(len=*), parameter :: steady_text = &
    "&run analysis = 'steady', title = 'steady shape points' /|" // &
    "&mechanism n_joints = 4, joint_name = 'A', 'B', 'C', 'D', joint_type = 'clamp', 'pin', 'pin', 'ground_pin'," // &
    " joint_x(1) = 0.0, joint_y(1) = 0.0, joint_x(4) = 10.0, joint_y(4) = 0.0, n_links = 3," // &
    " link_name = 'crank', 'coupler', 'rocker', link_joint1 = 1, 2, 4, link_joint2 = 2, 3, 3," // &
    " link_length = 5.0, 11.0, 10.5, link_n_elements = 1, 2, 1, driver_link = 1, omega = 150.0 /|" // &
    "&steady method = 'both', n_harmonics = 6, damping_beta = 1.0e-5, rtol = 1e-8, atol = 1e-12," // &
    " output_step_deg = 10.0, shape_points = 8 /|" // &
    "&tennant d_k = 0, d_b = 0, d_g = 0, shear = F /"

  !> The RSSR four-bar of inputs/spatial_rssr_100.nml over a fifth of a
  !> revolution, 8 intervals per element drawn.
  character(len=*), parameter :: spatial_text = &
    "&run analysis = 'spatial', title = 'spatial shape points' /|" // &
    "&spatial_mechanism crank_pivot = 0.0, 0.0, 0.0, crank_axis = 0.0, 0.0, 1.0, crank_pin = 6.0, 0.0, 0.0," // &
    " rocker_pivot = 0.0, 20.0, 12.0, rocker_axis = 1.0, 0.0, 0.0, rocker_length = 12.0, coupler_length = 24.0," // &
    " branch = 1, joint_b = 'spherical', joint_c = 'spherical', omega = 100.0, link_n_elements = 1, 2, 1," // &
    " link_section = 3*'circular', link_radius = 3*0.25 /|" // &
    "&transient method = 'bdf_band', rtol = 1e-7, atol = 1e-11, revolutions = 0.2, output_step_deg = 9.0," // &
    " damping_beta = 1.0e-6, shape_points = 8 /|" // &
    "&effects stretching = T, curvature = T, material = T, rotary_inertia = T, coupling = T," // &
    " formulation = 'consistent' /|" // &
    "&spatial_loads initial_static = T /"

  !> The steady run, made once for the tests that read it.
  type(run_output_t), save :: steady_out
  type(mechanism_t), save :: steady_mech
  logical, save :: steady_done = .false.

contains

  subroutine run_all()
    call run_test('units_from_the_column_descriptions', test_units)
    call run_test('shape_columns_meet_the_end_and_joint_columns', test_shapes)
    call run_test('nice_factor_is_1_2_5_at_most_x', test_factor)
    call run_test('steady_shape_columns_meet_the_ends_and_the_interpolation', test_steady_shapes)
    call run_test('steady_links_drawn_bent_by_their_shape_columns', test_steady_drawn)
    call run_test('spatial_shape_columns_meet_the_joints_and_the_interpolation', test_spatial_shapes)
  end subroutine run_all

  !> The default run's descriptions: 'sigma_max_e<k> = ... (psi) (the
  !> outer-fibre stress ...)', '<joint>_U ... (in)'; a steady run's '(in; T's
  !> U~1 is B_U ...)'; nothing for a key no description names.
  subroutine test_units()
    type(run_output_t) :: out
    type(error_t) :: err
    call read_run_output('reference_outputs/fourbar_150_damped.out', out, err)
    call assert_true(.not. err%failed(), 'read the transient output')
    call assert_equal(column_unit(out, 'sigma_max_e'), 'psi', 'stress unit, not the remark after it')
    call assert_equal(column_unit(out, '_U'), 'in', 'joint displacement unit')
    call assert_equal(column_unit(out, '_u_end'), 'in', 'link end unit')
    call assert_equal(column_unit(out, 'no_such_column'), '', 'no description: no unit')
    call read_run_output('reference_outputs/tennant_fig3_linear.out', out, err)
    call assert_true(.not. err%failed(), 'read the steady output')
    call assert_equal(column_unit(out, '_U'), 'in', 'the unit before a remark inside the parentheses')
  end subroutine test_units

  !> Every link is drawn bent, its points sorted from end 1 to end 2, 4 per
  !> element; at end 2 a link's shape point is its end columns u_end, w_end;
  !> at the clamp A the crank's is zero; the coupler's end 1 rotated by its
  !> rigid-body angle is the joint B's global U, W.
  subroutine test_shapes()
    type(run_output_t) :: out
    type(error_t) :: err
    type(deck_t) :: deck, again
    type(table_t) :: table
    type(mechanism_t) :: mech
    type(link_shape_t), allocatable :: shapes(:)
    type(kinematics_t) :: kin
    character(len=:), allocatable :: stem, label
    real(dp) :: ex(2), ey(2), uw(2), p1(2), p2(2), scale
    integer :: i, r, u, n
    stem = scratch_path('plot_shapes')
    call write_deck(stem//'.nml', deck_text)
    call deck%open(stem//'.nml', err)
    call table%open(stem//'.out', err)
    call run_transient(deck, table, err)
    call assert_true(.not. err%failed(), 'the run')
    call table%commit(err)
    call deck%close()
    call again%open(stem//'.nml', err)
    call read_mechanism(again, mech, err)
    call again%close()
    call read_run_output(stem//'.out', out, err)
    call assert_true(.not. err%failed(), 'read the run back')
    call link_shapes(out, mech, shapes, label)
    call assert_equal(label, '|stress| (outer fibre)', 'colour: the outer-fibre stress (no sigma_b columns)')
    do i = 1, 3
      call assert_true(shapes(i)%bent, 'link drawn bent')
      n = 4*mech%links(i)%n_elements + 1
      call assert_equal(size(shapes(i)%s), n, 'points of the link')
      call assert_true(all(shapes(i)%s(2:) > shapes(i)%s(:n - 1)), 'points sorted')
    end do
    call assert_equal(out%names(shapes(2)%jsig(3))%s, 'sigma_max_e2', 'coupler s = 0.25: its first element')
    call assert_equal(out%names(shapes(2)%jsig(7))%s, 'sigma_max_e3', 'coupler s = 0.75: its second element')
    scale = maxval(abs(out%data(:, column_index(out, 'B_U'))))
    call assert_true(scale > 1.0e-4_dp, 'the run deforms')
    call kin%init(mech, err)
    do r = 2, size(out%data, 1)
      do i = 1, 3
        n = size(shapes(i)%s)
        call assert_close(out%data(r, shapes(i)%ju(n)), &
          out%data(r, column_index(out, trim(mech%links(i)%name)//'_u_end')), 1.0e-9_dp*scale, 'u at end 2')
        call assert_close(out%data(r, shapes(i)%jw(n)), &
          out%data(r, column_index(out, trim(mech%links(i)%name)//'_w_end')), 1.0e-9_dp*scale, 'w at end 2')
      end do
      call assert_close(abs(out%data(r, shapes(1)%ju(1))) + abs(out%data(r, shapes(1)%jw(1))), 0.0_dp, &
                        1.0e-12_dp*scale, 'the crank held at the clamp')
      call kin%solve(out%data(r, column_index(out, 't')), err)
      p1 = kin%joint_position(2)
      p2 = kin%joint_position(3)
      ex = (p2 - p1)/norm2(p2 - p1)
      ey = [-ex(2), ex(1)]
      uw = out%data(r, shapes(2)%ju(1))*ex + out%data(r, shapes(2)%jw(1))*ey
      call assert_close(uw(1), out%data(r, column_index(out, 'B_U')), 1.0e-6_dp*scale, 'coupler end 1 = B, X')
      call assert_close(uw(2), out%data(r, column_index(out, 'B_W')), 1.0e-6_dp*scale, 'coupler end 1 = B, Y')
    end do
    open(newunit=u, file=stem//'.nml', status='old')
    close(u, status='delete')
    open(newunit=u, file=stem//'.out', status='old')
    close(u, status='delete')
  end subroutine test_shapes

  !> Writes the deck text, runs `analysis` on it and reads the output back
  !> (and its mechanism, for a planar one); both files removed.
  subroutine run_and_read(name, text, analysis, out, mech)
    character(len=*), intent(in) :: name, text
    procedure(analysis_runner) :: analysis
    type(run_output_t), intent(out) :: out
    type(mechanism_t), intent(out), optional :: mech
    type(deck_t) :: deck, again
    type(table_t) :: table
    type(error_t) :: err
    character(len=:), allocatable :: stem
    integer :: u
    stem = scratch_path(name)
    call write_deck(stem//'.nml', text)
    call deck%open(stem//'.nml', err)
    call table%open(stem//'.out', err)
    call analysis(deck, table, err)
    call assert_true(.not. err%failed(), 'the run of '//name)
    call table%commit(err)
    call deck%close()
    if (present(mech)) then
      call again%open(stem//'.nml', err)
      call read_mechanism(again, mech, err)
      call again%close()
    end if
    call read_run_output(stem//'.out', out, err)
    call assert_true(.not. err%failed(), 'read the output of '//name//' back')
    open(newunit=u, file=stem//'.nml', status='old')
    close(u, status='delete')
    open(newunit=u, file=stem//'.out', status='old')
    close(u, status='delete')
  end subroutine run_and_read

  !> The output and mechanism of the steady deck (run at the first call).
  subroutine steady_run(out, mech)
    type(run_output_t), intent(out) :: out
    type(mechanism_t), intent(out) :: mech
    if (.not. steady_done) call run_and_read('plot_steady_shapes', steady_text, run_steady, steady_out, steady_mech)
    steady_done = .true.
    out = steady_out
    mech = steady_mech
  end subroutine steady_run

  !> The points v(k) at s(k) = (k-1)/8 of a one-element link clamped at s = 0
  !> lie on a polynomial of degree 5 with v(0) = 0 (u linear, w a quintic
  !> Hermite; the spatial element's u, v, w quintics): fitted on s = 2/8,
  !> 4/8, 5/8, 6/8, 1, it gives the other points to round-off of the fit.
  subroutine check_quintic(s, v, message)
    real(dp), intent(in) :: s(:), v(:)
    character(len=*), intent(in) :: message
    integer, parameter :: fit(5) = [3, 5, 6, 7, 9], other(3) = [2, 4, 8]
    real(dp) :: a(5, 5), c(5)
    integer :: i, j
    type(error_t) :: err
    call assert_equal(size(s), 9, message//': 9 points')
    if (size(s) /= 9) return
    call assert_close(v(1), 0.0_dp, 1.0e-14_dp, message//': zero at the clamp')
    do i = 1, 5
      do j = 1, 5
        a(i, j) = s(fit(i))**j
      end do
    end do
    c = v(fit)
    call solve_linear(a, c, err)
    do i = 1, 3
      call assert_close(sum([(c(j)*s(other(i))**j, j = 1, 5)]), v(other(i)), 1.0e-7_dp*maxval(abs(v)) + 1.0e-15_dp, &
                        message//': on the quintic through the clamp')
    end do
  end subroutine check_quintic

  !> Largest distance of the points p(:, k) from the line through the first
  !> and the last.
  pure real(dp) function off_chord(p) result(dist)
    real(dp), intent(in) :: p(:, :)
    real(dp) :: c(3), r(3), e(3)
    integer :: k, n
    n = size(p, 2)
    c = 0.0_dp
    c(1:size(p, 1)) = p(:, n) - p(:, 1)
    dist = 0.0_dp
    do k = 1, n
      r = 0.0_dp
      r(1:size(p, 1)) = p(:, k) - p(:, 1)
      e = [c(2)*r(3) - c(3)*r(2), c(3)*r(1) - c(1)*r(3), c(1)*r(2) - c(2)*r(1)]
      dist = max(dist, norm2(e)/norm2(c))
    end do
  end function off_chord

  !> A steady run with shape_points: every link bent, 8 points per element,
  !> both solutions; at end 2 the points are u_end, w_end (and _exact); the
  !> clamped crank's u and w lie on a quintic through the clamp.
  subroutine test_steady_shapes()
    type(run_output_t) :: out
    type(mechanism_t) :: mech
    type(link_shape_t), allocatable :: shapes(:)
    character(len=:), allocatable :: label, nm
    integer :: i, r, n
    real(dp) :: scale
    character(len=6), parameter :: suffix(2) = ['      ', '_exact']
    integer :: k
    call steady_run(out, mech)
    call link_shapes(out, mech, shapes, label)
    do i = 1, 3
      call assert_true(shapes(i)%bent, 'steady link drawn bent')
      call assert_equal(size(shapes(i)%s), 8*mech%links(i)%n_elements + 1, 'points of the link')
    end do
    call assert_true(column_index(out, 'coupler_s0.5_w_exact') > 0, 'the exact solution''s shape columns')
    scale = maxval(abs(out%data(:, column_index(out, 'C_U'))))
    call assert_true(scale > 1.0e-3_dp, 'the run deforms')
    do k = 1, 2
      do r = 1, size(out%data, 1)
        do i = 1, 3
          nm = trim(mech%links(i)%name)
          call assert_close(out%data(r, column_index(out, nm//'_s1_u'//trim(suffix(k)))), &
            out%data(r, column_index(out, nm//'_u_end'//trim(suffix(k)))), 1.0e-12_dp*scale, 'u at end 2')
          call assert_close(out%data(r, column_index(out, nm//'_s1_w'//trim(suffix(k)))), &
            out%data(r, column_index(out, nm//'_w_end'//trim(suffix(k)))), 1.0e-12_dp*scale, 'w at end 2')
        end do
      end do
    end do
    n = size(shapes(1)%s)
    do r = 1, size(out%data, 1)
      call check_quintic(shapes(1)%s, out%data(r, shapes(1)%jw), 'crank w')
      call check_quintic(shapes(1)%s, out%data(r, shapes(1)%ju), 'crank u')
      call assert_close(maxval(abs(out%data(r, shapes(1)%ju) - shapes(1)%s*out%data(r, shapes(1)%ju(n)))), 0.0_dp, &
                        1.0e-12_dp*scale, 'the crank''s u linear (Tennant''s element)')
    end do
  end subroutine test_steady_shapes

  !> The drawn coupler of a steady run is off its chord by about its own
  !> bending (the shape columns' w off the line of its end values); with the
  !> shape columns zeroed it is straight.
  subroutine test_steady_drawn()
    type(run_output_t) :: out
    type(mechanism_t) :: mech
    type(link_shape_t), allocatable :: shapes(:)
    type(error_t) :: err
    character(len=:), allocatable :: label
    real(dp), allocatable :: drawn(:, :, :)
    real(dp), allocatable :: w(:)
    real(dp) :: bend, best
    integer :: r, row, i, n
    call steady_run(out, mech)
    call link_shapes(out, mech, shapes, label)
    n = size(shapes(2)%s)
    best = -1.0_dp
    row = 1
    do r = 1, size(out%data, 1)       ! the row where the coupler bends most
      w = out%data(r, shapes(2)%jw)
      bend = maxval(abs(w - ((1.0_dp - shapes(2)%s)*w(1) + shapes(2)%s*w(n))))
      if (bend > best) then
        best = bend
        row = r
      end if
    end do
    call assert_true(best > 1.0e-4_dp, 'the coupler bends')
    call drawn_frame(out, row, 1.0_dp, drawn, err)
    call assert_true(.not. err%failed(), 'drawn')
    call assert_true(off_chord(drawn(:, 1:n, 2)) > 0.5_dp*best, 'the drawn coupler is bent')
    call assert_true(off_chord(drawn(:, 1:n, 2)) < 2.0_dp*best, 'by its own bending')
    do i = 1, 3
      out%data(:, shapes(i)%ju) = 0.0_dp
      out%data(:, shapes(i)%jw) = 0.0_dp
    end do
    call drawn_frame(out, row, 1.0_dp, drawn, err)
    do i = 1, 3
      call assert_true(off_chord(drawn(:, 1:size(shapes(i)%s), i)) < 1.0e-12_dp*11.0_dp, &
                       'zero shape columns: the drawn link is straight')
    end do
  end subroutine test_steady_drawn

  !> A spatial run with shape_points: the links' end points are the joints'
  !> translations (crank s = 1 and coupler s = 0: B; coupler and rocker s = 1:
  !> C), zero at A and D; the clamped crank's X, Y, Z on a quintic through A;
  !> the drawn coupler bent, and straight with the shape columns zeroed.
  subroutine test_spatial_shapes()
    type(run_output_t) :: out
    type(spatial_shape_3d_t) :: shapes(3)
    type(error_t) :: err
    real(dp), allocatable :: drawn(:, :, :)
    real(dp) :: scale, bend
    integer :: r, k, n(3), i
    character(len=1), parameter :: axis(3) = ['X', 'Y', 'Z']
    call run_and_read('plot_spatial_shapes', spatial_text, run_spatial, out)
    call spatial_link_shapes(out, [1, 2, 1], shapes)
    do i = 1, 3
      call assert_true(shapes(i)%bent, 'spatial link drawn bent')
      n(i) = size(shapes(i)%s)
    end do
    call assert_equal(n(link_coupler), 17, 'the coupler''s points: 2 elements')
    scale = maxval(abs(out%data(:, column_index(out, 'C_UX'))))
    call assert_true(scale > 1.0e-3_dp, 'the run deforms')
    do r = 1, size(out%data, 1)
      do k = 1, 3
        associate (b => out%data(r, column_index(out, 'B_U'//axis(k))), c => out%data(r, column_index(out, 'C_U'//axis(k))))
          call assert_close(out%data(r, shapes(link_crank)%cols(k, n(1))), b, 1.0e-12_dp*scale, 'crank end 2 = B')
          call assert_close(out%data(r, shapes(link_coupler)%cols(k, 1)), b, 1.0e-12_dp*scale, 'coupler end 1 = B')
          call assert_close(out%data(r, shapes(link_coupler)%cols(k, n(2))), c, 1.0e-12_dp*scale, 'coupler end 2 = C')
          call assert_close(out%data(r, shapes(link_rocker)%cols(k, n(3))), c, 1.0e-12_dp*scale, 'rocker end 2 = C')
        end associate
        call assert_close(out%data(r, shapes(link_rocker)%cols(k, 1)), 0.0_dp, 1.0e-15_dp, 'rocker held at D')
        call check_quintic(shapes(link_crank)%s, out%data(r, shapes(link_crank)%cols(k, :)), 'crank '//axis(k))
      end do
    end do
    r = size(out%data, 1)
    bend = 0.0_dp
    call spatial_frame(out, r, 1.0_dp, drawn, err)
    call assert_true(.not. err%failed(), 'drawn')
    bend = off_chord(drawn(:, :, link_coupler))
    call assert_true(bend > 1.0e-3_dp, 'the drawn coupler is bent')
    do i = 1, 3
      out%data(:, shapes(i)%cols(1, :)) = 0.0_dp
      out%data(:, shapes(i)%cols(2, :)) = 0.0_dp
      out%data(:, shapes(i)%cols(3, :)) = 0.0_dp
    end do
    call spatial_frame(out, r, 1.0_dp, drawn, err)
    do i = 1, 3
      call assert_true(off_chord(drawn(:, 1:n(i), i)) < 1.0e-12_dp*24.0_dp, &
                       'zero shape columns: the drawn link is straight')
    end do
  end subroutine test_spatial_shapes

  subroutine test_factor()
    call assert_rel_close(nice_factor(37.0_dp), 20.0_dp, 1.0e-15_dp, '37 -> 20')
    call assert_rel_close(nice_factor(0.6_dp), 0.5_dp, 1.0e-15_dp, '0.6 -> 0.5')
    call assert_rel_close(nice_factor(1999.0_dp), 1000.0_dp, 1.0e-15_dp, '1999 -> 1000')
  end subroutine test_factor
end module test_plot_shapes_suite

program test_plot_shapes
  use test_plot_shapes_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_plot_shapes')
end program test_plot_shapes
