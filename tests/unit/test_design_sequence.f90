!> Tests of the design loop's pieces (module design_sequence): the step back
!> of a rejected proposal to where its violated constraints, modelled along
!> the step as quadratics, reach their aim.
module test_design_sequence_suite
  use kinds, only: dp
  use design_sequence, only: step_back
  use assertions
  implicit none
  private
  public :: run_all

  real(dp), parameter :: margin = 5.0e-4_dp

contains

  subroutine run_all()
    call run_test('step_back_lands_on_the_aim_of_a_quadratic_constraint', test_quadratic)
    call run_test('step_back_takes_the_first_constraint_to_reach_its_aim', test_two_constraints)
    call run_test('step_back_declines_for_an_active_or_unviolated_constraint', test_declines)
  end subroutine run_all

  !> g(t) = g0 + a t + c t^2 exactly (convex, linear and concave): the
  !> returned t puts g on the aim -margin to round-off (1e-12 of the
  !> constraint's scale), and just before t the constraint is still inside
  !> it (the first crossing, not the second root).
  subroutine test_quadratic()
    real(dp) :: g0(3), a(3), c(3), t
    integer :: i
    g0 = [-0.467_dp, -0.3_dp, -0.5_dp]
    a = [0.2_dp, 0.4_dp, 1.0_dp]
    c = [0.3_dp, 0.0_dp, -0.4_dp]
    do i = 1, 3
      t = step_back([g0(i)], [a(i)], [g0(i) + a(i) + c(i)], margin)
      call assert_true(t > 0.0_dp .and. t < 1.0_dp, 'a fraction of the step')
      call assert_close(g0(i) + a(i)*t + c(i)*t**2, -margin, 1.0e-12_dp, 'g on its aim at t')
      t = t*(1.0_dp - 1.0e-6_dp)
      call assert_true(g0(i) + a(i)*t + c(i)*t**2 < -margin, 'inside the aim just before t')
    end do
  end subroutine test_quadratic

  !> Two violated constraints: the step stops where the first reaches its
  !> aim (the smaller of the single-constraint fractions, 1e-14).
  subroutine test_two_constraints()
    real(dp) :: t, t1, t2
    t1 = step_back([-0.4_dp], [0.1_dp], [0.05_dp], margin)
    t2 = step_back([-0.2_dp], [0.3_dp], [0.2_dp], margin)
    t = step_back([-0.4_dp, -0.2_dp], [0.1_dp, 0.3_dp], [0.05_dp, 0.2_dp], margin)
    call assert_true(abs(t1 - t2) > 0.1_dp, 'the two fractions differ')
    call assert_close(t, min(t1, t2), 1.0e-14_dp, 'the smaller fraction')
  end subroutine test_two_constraints

  !> No step back when a violated constraint is already at its aim at x_k
  !> (an active constraint: any t > 0 breaks it in the model) or when no
  !> constraint is violated at the proposal (nothing to cut back for).
  subroutine test_declines()
    call assert_close(step_back([-0.4_dp, -1.0e-4_dp], [0.1_dp, 0.0_dp], [0.05_dp, 0.01_dp], margin), 0.0_dp, 0.0_dp, &
                      'active constraint')
    call assert_close(step_back([-0.4_dp], [0.1_dp], [-0.1_dp], margin), 0.0_dp, 0.0_dp, 'nothing violated')
  end subroutine test_declines
end module test_design_sequence_suite

program test_design_sequence
  use test_design_sequence_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_design_sequence')
end program test_design_sequence
