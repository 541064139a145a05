!> Tests of the &steady and &tennant groups (module steady_settings):
!> documented defaults, values read into the solver and element settings,
!> sections, and rule violations named with code 2.
module test_steady_settings_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use deck_runner, only: start_suite, suite_stem, open_deck_text, close_deck_text
  use steady_settings, only: steady_settings_t, read_steady_settings
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call start_suite('test_steady_settings')
    call run_test('defaults_without_the_groups', test_defaults)
    call run_test('values_reach_the_solvers_and_the_element', test_values)
    call run_test('rule_violations_are_input_errors', test_violations)
  end subroutine run_all

  subroutine read_text(text, s, err)
    character(len=*), intent(in) :: text
    type(steady_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    call open_deck_text(suite_stem(), text, deck, err)
    if (.not. err%failed()) call read_steady_settings(deck, 3, s, err)
    call close_deck_text(suite_stem(), deck)
  end subroutine read_text

  subroutine test_defaults()
    type(steady_settings_t) :: s
    type(error_t) :: err
    call read_text('&run analysis = ''steady'' /', s, err)
    call assert_true(.not. err%failed(), 'read')
    call assert_equal(trim(s%method), 'harmonic', 'method')
    call assert_equal(s%harmonic%n_harmonics, 8, 'N')
    call assert_true(.not. s%harmonic%velocity_terms, 'C Q_dot neglected as in the paper')
    call assert_true(.not. s%element%shear, 'slender element')
    call assert_true(s%element%rotary_inertia, 'rotatory inertia on (T3)')
    call assert_close(s%element%d_k + s%element%d_b + s%element%d_g, 0.0_dp, 0.0_dp, 'linear')
    call assert_close(s%element%poisson, 0.33_dp, 0.0_dp, 'poisson')
    call assert_true(s%shooting%bdf, 'BDF shooting')
    call assert_equal(s%sections(1)%n, 0, 'uniform links')
  end subroutine test_defaults

  subroutine test_values()
    type(steady_settings_t) :: s
    type(error_t) :: err
    call read_text('&steady method = ''both'', n_harmonics = 12, harmonics_kept = 6, velocity_terms = T, '// &
                   'integrator = ''adams'', damping_beta = 1.0e-5 /|&tennant d_k = 1, shear = T, '// &
                   'shear_modulus = 4.0e6, n_sections(3) = 2, section_end(3,1:2) = 0.3, 1.0, '// &
                   'section_b(3,1:2) = 0.5, 0.25, section_h(3,1:2) = 1.0, 1.0 /', s, err)
    call assert_true(.not. err%failed(), 'read: '//err%text())
    call assert_equal(s%harmonic%n_harmonics, 12, 'N')
    call assert_equal(s%harmonic%n_kept, 6, 'kept')
    call assert_true(s%harmonic%velocity_terms, 'C kept')
    call assert_true(.not. s%shooting%bdf, 'adams')
    call assert_close(s%element%damping_beta, 1.0e-5_dp, 0.0_dp, 'beta')
    call assert_close(s%element%d_k, 1.0_dp, 0.0_dp, 'D_k')
    call assert_close(s%element%shear_modulus, 4.0e6_dp, 0.0_dp, 'G')
    call assert_equal(s%sections(3)%n, 2, 'sections')
    call assert_close(s%sections(3)%b(1), 0.5_dp, 0.0_dp, 'section width')
  end subroutine test_values

  subroutine test_violations()
    call bad('&steady n_harmonics = 0 /', 'n_harmonics')
    call bad('&steady harmonics_kept = 9 /', 'harmonics_kept')
    call bad('&steady method = ''galerkin'' /', 'method')
    call bad('&steady integrator = ''rk4'' /', 'integrator')
    call bad('&steady damping_beta = -1.0 /', 'damping_beta')
    call bad('&tennant d_b = -0.5 /', 'd_b')
    call bad('&tennant poisson = 0.6 /', 'poisson')
    call bad('&steady outer_tol = NaN /', 'outer_tol = NaN')
    call bad('&steady atol = Inf /', 'atol = Infinity')
    call bad('&steady rtol = 1e-300 /', 'rtol')
    call bad('&tennant shear_modulus = 1e309 /', 'shear_modulus')
    call bad('&tennant n_sections(1) = 2, section_end(1,1:2) = 0.5, 1.0, section_b(1,1:2) = 1, NaN, '// &
             'section_h(1,1:2) = 1, 1 /', 'section_b(1,2) = NaN')
    call bad('&tennant n_sections(5) = 1, section_end(5,1) = 1.0, section_b(5,1) = 1, section_h(5,1) = 1 /', &
             'n_sections(5)')
    call bad('&tennant n_sections(1) = 2, section_end(1,1:2) = 0.6, 0.4, section_b(1,1:2) = 1, 1, '// &
             'section_h(1,1:2) = 1, 1 /', 'section_end(1,2)')
  contains
    subroutine bad(text, name)
      character(len=*), intent(in) :: text, name
      type(steady_settings_t) :: s
      type(error_t) :: err
      call read_text(text, s, err)
      call assert_true(err%failed() .and. err%code == 2, name//' rejected')
      call assert_true(index(err%text(), name) > 0, 'message names '//name//': '//err%text())
    end subroutine bad
  end subroutine test_violations
end module test_steady_settings_suite

program test_steady_settings
  use assertions, only: finish_suite
  use test_steady_settings_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_steady_settings')
end program test_steady_settings
