!> Tests of point_metrics (the numbers of a run's footer for a sweep row),
!> on the reference output of tennant_fig5_exact (values known from its
!> footer), and of the name rule.
module test_point_metrics_suite
  use kinds, only: dp
  use error_status, only: error_t
  use point_metrics, only: metric_t, read_point_metrics, metric_name
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('names_from_summary_keys', test_names)
    call run_test('numbers_of_a_steady_footer', test_footer)
  end subroutine run_all

  subroutine test_names()
    call assert_equal(metric_name('element 1 peak |stress| (exact periodic)'), &
                      'element_1_peak_stress_exact_periodic', 'peak key')
    call assert_equal(metric_name('cost cpu_seconds_harmonic'), 'cost_cpu_seconds_harmonic', 'cost key')
    call assert_equal(metric_name('  Floquet multipliers, largest moduli'), 'floquet_multipliers_largest_moduli', &
                      'punctuation and case')
  end subroutine test_names

  !> The footer says: element 1 peak (harmonic series) = 39275.366 psi; six
  !> Floquet moduli, the largest 0.162755; 1 shooting Newton iteration.
  subroutine test_footer()
    type(metric_t), allocatable :: m(:)
    character(len=:), allocatable :: notes
    type(error_t) :: err
    allocate(m(0))   ! a defined descriptor (gfortran's -Wmaybe-uninitialized otherwise)
    call read_point_metrics('reference_outputs/tennant_fig5_exact.out', m, notes, err)
    call assert_true(.not. err%failed(), 'read')
    if (err%failed() .or. .not. allocated(m)) return   ! m is unallocated after a failed read
    call assert_close(value_of(m, 'element_1_peak_stress_harmonic_series'), 39275.366_dp, 0.0_dp, 'peak (as printed)')
    call assert_close(value_of(m, 'floquet_multipliers_largest_moduli_1'), 0.162755_dp, 0.0_dp, 'first modulus')
    call assert_close(value_of(m, 'floquet_multipliers_largest_moduli_6'), 0.766330e-4_dp, 0.0_dp, 'sixth modulus')
    call assert_close(value_of(m, 'shooting_newton_iterations'), 1.0_dp, 0.0_dp, 'number before "(converged)"')
    call assert_true(value_of(m, 'cost_total_cpu_seconds') > 0.0_dp, 'the cost footer is read')
    call assert_true(count_named(m, 'steady_state') == 0, 'a text value is not a number')
  end subroutine test_footer

  real(dp) function value_of(m, name)
    type(metric_t), intent(in) :: m(:)
    character(len=*), intent(in) :: name
    integer :: i
    value_of = -huge(1.0_dp)
    do i = 1, size(m)
      if (m(i)%name == name) value_of = m(i)%value
    end do
  end function value_of

  integer function count_named(m, name)
    type(metric_t), intent(in) :: m(:)
    character(len=*), intent(in) :: name
    integer :: i
    count_named = 0
    do i = 1, size(m)
      if (m(i)%name == name) count_named = count_named + 1
    end do
  end function count_named
end module test_point_metrics_suite

program test_point_metrics
  use assertions, only: finish_suite
  use test_point_metrics_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_point_metrics')
end program test_point_metrics
