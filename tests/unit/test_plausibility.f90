!> The plausibility warnings (module plausibility): each fires on the input
!> it is for and stays silent on real materials and safe runs.
module test_plausibility_suite
  use kinds, only: dp
  use plausibility, only: wave_speed_warning, strength_warning, crank_speed_warning
  use reference_materials, only: default_link_material
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('wave_speed_of_real_materials_is_silent', test_real_materials)
    call run_test('weight_density_for_mass_density_warns', test_weight_density)
    call run_test('strength_warns_above_the_allowable_only', test_strength)
    call run_test('crank_above_first_frequency_undamped_warns', test_crank_speed)
  end subroutine run_all

  !> The default aluminium in in-lbf-s and in SI, steel (E 30e6 psi, rho
  !> 7.33e-4 lb s^2/in^4; 2.07e11 Pa, 7850 kg/m^3): no warning; any system
  !> 'none' is not judged.
  subroutine test_real_materials()
    real(dp) :: e1, e2, rho
    call default_link_material('in-lbf-s', e1, e2, rho)
    call assert_equal(wave_speed_warning('crank', e1, rho, 'in-lbf-s'), '', 'aluminium, in-lbf-s')
    call default_link_material('si', e1, e2, rho)
    call assert_rel_close(rho, 2710.2_dp, 1.0e-4_dp, 'the default aluminium in kg/m^3')
    call assert_equal(wave_speed_warning('crank', e1, rho, 'si'), '', 'aluminium, SI')
    call assert_equal(wave_speed_warning('crank', 30.0e6_dp, 7.33e-4_dp, 'in-lbf-s'), '', 'steel, in-lbf-s')
    call assert_equal(wave_speed_warning('crank', 2.07e11_dp, 7850.0_dp, 'si'), '', 'steel, SI')
    call assert_equal(wave_speed_warning('crank', 1.0_dp, 1.0_dp, 'none'), '', 'no system: not judged')
  end subroutine test_real_materials

  !> link_rho = 0.283 (steel's weight density in lb/in^3): a wave speed 20
  !> times too low; an SI deck read as in-lbf-s is flagged too.
  subroutine test_weight_density()
    character(len=:), allocatable :: w
    w = wave_speed_warning('crank', 30.0e6_dp, 0.283_dp, 'in-lbf-s')
    call assert_true(index(w, 'link crank') > 0 .and. index(w, 'link_rho') > 0 .and. &
                     index(w, 'divided by g = 386.09') > 0, 'weight density: says what to check: '//w)
    w = wave_speed_warning('beam', 6.9e10_dp, 2766.67_dp, 'in-lbf-s')
    call assert_true(len(w) > 0, 'an SI material in an in-lbf-s deck')
    w = wave_speed_warning('beam', 10.87e6_dp, 2.536e-4_dp, 'si')
    call assert_true(len(w) > 0 .and. index(w, 'kg/m^3') > 0, 'an in-lbf-s material in an SI deck: '//w)
  end subroutine test_weight_density

  subroutine test_strength()
    call assert_true(index(strength_warning('crank', 41000.0_dp, 40000.0_dp), 'link_strength') > 0, 'above')
    call assert_equal(strength_warning('crank', 39000.0_dp, 40000.0_dp), '', 'below')
    call assert_equal(strength_warning('crank', 1.0e9_dp, 0.0_dp), '', 'no strength given')
  end subroutine test_strength

  !> Tennant's four-bar at 150 rad/s has omega_1 = 43.8 rad/s at its start.
  subroutine test_crank_speed()
    character(len=:), allocatable :: w
    w = crank_speed_warning(150.0_dp, 43.8_dp, 0.0_dp)
    call assert_true(index(w, 'damping_beta') > 0 .and. index(w, 'above the lowest natural frequency') > 0, &
                     'undamped above omega_1: '//w)
    call assert_equal(crank_speed_warning(150.0_dp, 43.8_dp, 1.0e-5_dp), '', 'damped')
    call assert_equal(crank_speed_warning(30.0_dp, 43.8_dp, 0.0_dp), '', 'below omega_1')
    call assert_true(len(crank_speed_warning(-150.0_dp, 43.8_dp, 0.0_dp)) > 0, 'either sense of turning')
  end subroutine test_crank_speed
end module test_plausibility_suite

program test_plausibility
  use test_plausibility_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_plausibility')
end program test_plausibility
