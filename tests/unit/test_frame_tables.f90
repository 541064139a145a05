!> Tests of the mechanism model's frame tables (build_frame_tables): for
!> elements whose M and K_t are constant in the element frame, the global
!> band matrices from the tabulated quadratic forms in (cos phi, sin phi)
!> must equal the element-by-element route (evaluate, rotate, scatter) at
!> any time, and so must the accelerations.  The two routes differ only in
!> the order of the operations: 1e-12 of the largest entry is far above
!> their round-off and far below any wrong coefficient, sign or index
!> (which changes entries at order 1).
module test_frame_tables_suite
  use kinds, only: dp
  use element_effects, only: element_effects_t
  use mechanism_model, only: mechanism_model_t
  use transient_fixtures, only: fourbar_input, make_model
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('linear_fourbar_matrices_equal_element_route', test_linear)
    call run_test('linear_rotary_inertia_matrices_equal_element_route', test_rotary)
    call run_test('accelerations_equal_element_route', test_accelerations)
    call run_test('nonlinear_strains_use_no_tables', test_nonlinear)
  end subroutine run_all

  !> M and K_t by both routes at crank angles over a turn, q nonzero.
  subroutine compare_matrices(effects, label)
    type(element_effects_t), intent(in) :: effects
    character(len=*), intent(in) :: label
    type(mechanism_model_t) :: model
    real(dp), allocatable :: m1(:, :), k1(:, :), m2(:, :), k2(:, :), q(:)
    logical :: ok
    integer :: it, i
    real(dp) :: t
    call make_model(fourbar_input(2, 150.0_dp, 0.0_dp), effects, 1.0e-5_dp, model, ok)
    if (.not. ok) return
    call assert_true(model%frame_tables, label//': tables in use')
    allocate(m1(model%kd + 1, model%n), m2(model%kd + 1, model%n), k1(2*model%kd + 1, model%n), &
             k2(2*model%kd + 1, model%n), q(model%n))
    q = [(1.0e-3_dp*sin(real(7*i, dp)), i = 1, model%n)]
    do it = 0, 7
      t = real(it, dp)*0.37_dp/150.0_dp*6.0_dp          ! crank angles 0 ... 15.5 rad
      call model%set_time(t)
      model%frame_tables = .true.
      call model%assemble_band(q, m1, k1)
      model%frame_tables = .false.
      call model%assemble_band(q, m2, k2)
      call assert_all_close(reshape(m1, [size(m1)]), reshape(m2, [size(m2)]), 0.0_dp, 1.0e-12_dp*maxval(abs(m2)), &
        label//': M')
      call assert_all_close(reshape(k1, [size(k1)]), reshape(k2, [size(k2)]), 0.0_dp, 1.0e-12_dp*maxval(abs(k2)), &
        label//': K_t')
    end do
  end subroutine compare_matrices

  subroutine test_linear()
    call compare_matrices(element_effects_t(), 'linear')
  end subroutine test_linear

  !> Rotary inertia with the linear section angle: its mass is constant in
  !> the element frame too.
  subroutine test_rotary()
    type(element_effects_t) :: fx
    fx = element_effects_t()
    fx%rotary_inertia = .true.
    fx%coupling = .true.
    call compare_matrices(fx, 'rotary inertia')
  end subroutine test_rotary

  !> q_dd by both routes (the mass factor re-formed for each).
  subroutine test_accelerations()
    type(mechanism_model_t) :: model
    real(dp), allocatable :: q(:), qd(:), a1(:), a2(:)
    logical :: ok
    integer :: i
    call make_model(fourbar_input(2, 150.0_dp, 0.0_dp), element_effects_t(), 1.0e-5_dp, model, ok)
    if (.not. ok) return
    allocate(q(model%n), qd(model%n), a1(model%n), a2(model%n))
    q = [(1.0e-3_dp*sin(real(7*i, dp)), i = 1, model%n)]
    qd = [(0.3_dp*cos(real(5*i, dp)), i = 1, model%n)]
    model%frame_tables = .true.
    call model%accelerations(0.0123_dp, q, qd, a1)
    model%frame_tables = .false.
    model%mass_factored = .false.
    call model%accelerations(0.0123_dp, q, qd, a2)
    call assert_true(.not. model%err%failed(), 'accelerations evaluated')
    call assert_all_close(a1, a2, 0.0_dp, 1.0e-12_dp*maxval(abs(a2)), 'q_dd')
  end subroutine test_accelerations

  !> With exact stretching K_t depends on q: the element route is kept.
  subroutine test_nonlinear()
    type(mechanism_model_t) :: model
    type(element_effects_t) :: fx
    logical :: ok
    fx = element_effects_t()
    fx%stretching = .true.
    call make_model(fourbar_input(2, 150.0_dp, 0.0_dp), fx, 1.0e-5_dp, model, ok, formulation='exact')
    if (.not. ok) return
    call assert_true(.not. model%frame_tables, 'no tables with stretching')
  end subroutine test_nonlinear
end module test_frame_tables_suite

program test_frame_tables
  use assertions, only: finish_suite
  use test_frame_tables_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_frame_tables')
end program test_frame_tables
