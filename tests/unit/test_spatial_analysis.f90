!> Tests of the `spatial` analysis driver (module spatial_analysis) through a
!> deck: the &transient integrator settings it shares with the planar
!> analysis (module transient_integration) take effect.
module test_spatial_analysis_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_runner, only: start_suite, run_text, has_line, summary_value, line_length
  use spatial_analysis, only: run_spatial
  use assertions
  implicit none
  private
  public :: run_all

  !> The planar-limit four-bar of inputs/spatial_fourbar_planar_100.nml over a
  !> tenth of a revolution, Adams at rtol 1e-8.
  character(len=*), parameter :: deck = &
    "&run analysis = 'spatial' /|" // &
    "&spatial_mechanism crank_pivot = 0, 0, 0, crank_axis = 0, 0, 1, crank_pin = 5, 0, 0, " // &
    "rocker_pivot = 10, 0, 0, rocker_axis = 0, 0, 1, rocker_length = 10.5, coupler_length = 11.0, " // &
    "branch = 1, joint_b = 'revolute', joint_c = 'revolute', omega = 100.0, link_n_elements = 3*1, " // &
    "link_section = 3*'rectangular', link_depth = 3*1.0, link_width = 3*0.25 /|" // &
    "&effects stretching = F, curvature = F, material = F, rotary_inertia = F, coupling = F /|"

contains

  subroutine run_all()
    call start_suite('test_spatial_analysis', run_spatial)
    call run_test('max_order_limits_dlsode_order', test_max_order)
  end subroutine run_all

  !> &transient max_order = 2 holds Adams at second order: the header says so
  !> and the steps grow (at rtol 1e-8 order 2 takes 5.7 times the steps of
  !> the default orders up to 12 on this deck: 39422 against 6959; a factor 3
  !> leaves margin and fails if the limit were ignored, as the spatial
  !> analysis did before transient_integration).
  subroutine test_max_order()
    type(error_t) :: err
    character(len=line_length), allocatable :: lines(:)
    real(dp) :: steps_default, steps_order2
    call run_text(deck//"&transient method = 'adams', rtol = 1e-8, atol = 1e-12, revolutions = 0.1, " // &
                  "output_step_deg = 6 /", err, lines)
    call assert_true(.not. err%failed(), 'default order runs: '//err%text())
    call assert_true(.not. has_line(lines, 'DLSODE order limited'), 'no order limit by default')
    steps_default = summary_value(lines, '# cost: steps =')
    call run_text(deck//"&transient method = 'adams', rtol = 1e-8, atol = 1e-12, revolutions = 0.1, " // &
                  "output_step_deg = 6, max_order = 2 /", err, lines)
    call assert_true(.not. err%failed(), 'max_order = 2 runs: '//err%text())
    call assert_true(has_line(lines, 'DLSODE order limited to 2'), 'header names the order limit')
    steps_order2 = summary_value(lines, '# cost: steps =')
    call assert_true(steps_default < huge(1.0_dp) .and. steps_order2 > 3.0_dp*steps_default, &
                     'order 2 takes far more steps than the default orders')
  end subroutine test_max_order
end module test_spatial_analysis_suite

program test_spatial_analysis
  use test_spatial_analysis_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_spatial_analysis')
end program test_spatial_analysis
