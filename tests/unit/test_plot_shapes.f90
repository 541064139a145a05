!> Tests of what `flexmech plot` reads to draw the deformed mechanism and to
!> label its axes: the units of the column descriptions, and the link shapes
!> of a transient run with `shape_points` (the link points that the run
!> evaluates with the elements' shape functions), checked against the run's
!> own end and joint columns, which are computed without the link points.
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
  use plot_animation, only: link_shapes, link_shape_t, nice_factor
  use deck_runner, only: scratch_path, write_deck
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

contains

  subroutine run_all()
    call run_test('units_from_the_column_descriptions', test_units)
    call run_test('shape_columns_meet_the_end_and_joint_columns', test_shapes)
    call run_test('nice_factor_is_1_2_5_at_most_x', test_factor)
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
