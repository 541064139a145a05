!> The &steady and &tennant groups of a steady-state deck: which solver (the
!> paper's harmonic series, the exact periodic solution by shooting, or both),
!> their settings, the output grid and damping; and Tennant's element: the
!> tracing constants, shear angle, inertia terms, shear modulus and sections.
module steady_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t, write_group
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  use linkage, only: max_links
  use tennant_element, only: tennant_options_t, tennant_max_sections
  use steady_model, only: link_sections_t
  use harmonic_solver, only: harmonic_settings_t, max_outer_limit
  use lsode_solver, only: max_steps_ceiling, max_steps_reason
  use periodic_shooting, only: shooting_settings_t, max_newton_limit
  use transient_settings, only: max_shape_points
  implicit none
  private
  public :: steady_settings_t, read_steady_settings, echo_steady_settings, write_steady_groups

  integer, parameter :: ms = tennant_max_sections

  !> The two groups' values; the default initialisation is the documented
  !> defaults (doc/decks.md), those of the solvers' and the element's types.
  type :: steady_settings_t
    character(len=16) :: method = 'harmonic'      !< 'harmonic', 'shooting' or 'both'
    character(len=16) :: integrator = 'bdf'       !< the shooting's DLSODE: 'bdf' or 'adams'
    type(harmonic_settings_t) :: harmonic         !< the harmonic series' defaults
    type(shooting_settings_t) :: shooting = shooting_settings_t(bdf=.true.)   !< BDF: integrator = 'bdf'
    real(dp) :: output_step_deg = 5.0_dp
    integer :: shape_points = 0                   !< > 0: link points every 1/shape_points of each element (drawn shapes)
    logical :: allow_resonance = .false.          !< print a steady state even near resonance
    logical :: allow_beyond_peak = .false.        !< print it even where a strain passes the R-O peak
    type(tennant_options_t) :: element
    type(link_sections_t) :: sections(max_links)
  end type steady_settings_t

  ! staging variables of the namelist groups
  character(len=16) :: method, integrator
  integer :: n_harmonics, harmonics_kept, max_outer, max_newton, max_steps, n_gauss, shape_points
  logical :: velocity_terms, allow_resonance, allow_beyond_peak, shear, rotary_inertia, shear_inertia
  real(dp) :: outer_tol, resonance_ratio, output_step_deg, damping_beta, rtol, atol, newton_tol, &
              unit_circle_tol, singular_rcond
  real(dp) :: d_k, d_b, d_g, shear_modulus, poisson, shear_factor
  integer :: n_sections(max_links)
  real(dp) :: section_end(max_links, ms), section_b(max_links, ms), section_h(max_links, ms)
  namelist /steady/ method, n_harmonics, harmonics_kept, velocity_terms, outer_tol, max_outer, resonance_ratio, &
    allow_resonance, allow_beyond_peak, output_step_deg, damping_beta, integrator, rtol, atol, newton_tol, max_newton, max_steps, &
    unit_circle_tol, singular_rcond, shape_points
  namelist /tennant/ d_k, d_b, d_g, shear, rotary_inertia, shear_inertia, shear_modulus, poisson, shear_factor, &
    n_gauss, n_sections, section_end, section_b, section_h

contains

  subroutine read_steady_settings(deck, n_links, s, err)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: n_links
    type(steady_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    type(steady_settings_t) :: defaults
    logical :: found
    integer :: k

    call stage_from(defaults)
    call deck%read_group('steady', steady_group, .false., found, err)
    if (err%failed()) return
    call deck%read_group('tennant', tennant_group, .false., found, err)
    if (err%failed()) return

    s = steady_settings_t(method=method, integrator=integrator, output_step_deg=output_step_deg, shape_points=shape_points, &
      allow_resonance=allow_resonance, allow_beyond_peak=allow_beyond_peak, &
      harmonic=harmonic_settings_t(n_harmonics, harmonics_kept, velocity_terms, outer_tol, max_outer, resonance_ratio), &
      shooting=shooting_settings_t(rtol=rtol, atol=atol, newton_tol=newton_tol, max_newton=max_newton, &
                                   max_steps=max_steps, unit_circle_tol=unit_circle_tol, singular_rcond=singular_rcond, &
                                   bdf=integrator == 'bdf'), &
      element=tennant_options_t(d_k=d_k, d_b=d_b, d_g=d_g, shear=shear, rotary_inertia=rotary_inertia, &
                                shear_inertia=shear_inertia, shear_modulus=shear_modulus, poisson=poisson, &
                                shear_factor=shear_factor, n_gauss=n_gauss, damping_beta=damping_beta))
    do k = 1, max_links
      s%sections(k)%n = n_sections(k)
      if (n_sections(k) > 0 .and. n_sections(k) <= ms) then
        s%sections(k)%f1(1:n_sections(k)) = section_end(k, 1:n_sections(k))
        s%sections(k)%b(1:n_sections(k)) = section_b(k, 1:n_sections(k))
        s%sections(k)%h(1:n_sections(k)) = section_h(k, 1:n_sections(k))
      end if
    end do
    call validate(deck, n_links, s, err)
  end subroutine read_steady_settings

  subroutine validate(deck, n_links, s, err)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: n_links
    type(steady_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'steady', t = 'tennant'
    character(len=*), parameter :: tracing = 'a tracing constant: 0 = off, 1 = on'
    integer :: k, j
    call check_choice(deck, g, 'method', s%method, [character(len=16) :: 'harmonic', 'shooting', 'both'], err)
    call check_integer(deck, g, 'n_harmonics', s%harmonic%n_harmonics, err, at_least=1, at_most=256)
    call check_integer(deck, g, 'harmonics_kept', s%harmonic%n_kept, err, at_least=0, &
                       at_most=max(0, s%harmonic%n_harmonics), why='0 = all')
    call check_real(deck, g, 'outer_tol', s%harmonic%outer_tol, err, at_least=1.0e-14_dp, below=1.0_dp, &
                    why='relative change of the outer iteration; below 1e-14 it is round-off')
    call check_integer(deck, g, 'max_outer', s%harmonic%max_outer, err, at_least=1, at_most=max_outer_limit)
    call check_real(deck, g, 'resonance_ratio', s%harmonic%resonance_ratio, err, at_least=0.0_dp, below=1.0_dp)
    call check_real(deck, g, 'output_step_deg', s%output_step_deg, err, at_least=1.0e-3_dp, at_most=360.0_dp, &
                    why='below 1e-3 degrees a revolution has over 3.6e5 rows')
    call check_integer(deck, g, 'shape_points', s%shape_points, err, at_least=0, at_most=max_shape_points, &
                       why='intervals per element of the drawn shape (0 = none)')
    call check_real(deck, g, 'damping_beta', s%element%damping_beta, err, at_least=0.0_dp, below=1.0_dp, why='seconds')
    call check_choice(deck, g, 'integrator', s%integrator, [character(len=16) :: 'bdf', 'adams'], err)
    call check_real(deck, g, 'rtol', s%shooting%rtol, err, at_least=1.0e-14_dp, below=1.0e-2_dp, &
                    why='a relative error tolerance; below 1e-14 DLSODE works at round-off')
    call check_real(deck, g, 'atol', s%shooting%atol, err, at_least=1.0e-30_dp, at_most=1.0e10_dp, &
                    why='below 1e-30 DLSODE''s error weights overflow')
    call check_real(deck, g, 'newton_tol', s%shooting%newton_tol, err, at_least=1.0e-15_dp, below=1.0_dp)
    call check_integer(deck, g, 'max_newton', s%shooting%max_newton, err, at_least=1, at_most=max_newton_limit)
    call check_integer(deck, g, 'max_steps', s%shooting%max_steps, err, at_least=1, at_most=max_steps_ceiling, &
                       why=max_steps_reason)
    call check_real(deck, g, 'unit_circle_tol', s%shooting%unit_circle_tol, err, at_least=0.0_dp, at_most=1.0_dp, &
                    why='distance of a Floquet multiplier modulus from 1')
    call check_real(deck, g, 'singular_rcond', s%shooting%singular_rcond, err, at_least=0.0_dp, below=1.0_dp)
    call check_real(deck, t, 'd_k', s%element%d_k, err, at_least=0.0_dp, at_most=1.0_dp, why=tracing)
    call check_real(deck, t, 'd_b', s%element%d_b, err, at_least=0.0_dp, at_most=1.0_dp, why=tracing)
    call check_real(deck, t, 'd_g', s%element%d_g, err, at_least=0.0_dp, at_most=1.0_dp, why=tracing)
    call check_real(deck, t, 'shear_modulus', s%element%shear_modulus, err, at_least=0.0_dp, at_most=1.0e20_dp, &
                    why='0 = E1/(2(1 + poisson))')
    call check_real(deck, t, 'poisson', s%element%poisson, err, above=-1.0_dp, below=0.5_dp)
    call check_real(deck, t, 'shear_factor', s%element%shear_factor, err, above=0.0_dp, at_most=1.0_dp)
    call check_integer(deck, t, 'n_gauss', s%element%n_gauss, err, at_least=6, at_most=64)
    if (err%failed()) return
    do k = 1, max_links
      associate (sc => s%sections(k))
        if (sc%n == 0) cycle
        if (k > n_links) then
          call invalid_value(deck, t, 'n_sections('//str(k)//')', str(sc%n), 'there are only '//str(n_links)// &
                             ' links', err); return
        end if
        if (sc%n < 1 .or. sc%n > ms) then
          call invalid_value(deck, t, 'n_sections('//str(k)//')', str(sc%n), 'must lie in 0..'//str(ms), err); return
        end if
        call check_reals(deck, t, 'section_b('//str(k)//',:)', sc%b(1:sc%n), err, above=0.0_dp, at_most=1.0e8_dp)
        call check_reals(deck, t, 'section_h('//str(k)//',:)', sc%h(1:sc%n), err, above=0.0_dp, at_most=1.0e8_dp)
        call check_reals(deck, t, 'section_end('//str(k)//',:)', sc%f1(1:sc%n), err, above=0.0_dp, at_most=1.0_dp, &
                         why='a section ends at a fraction of the link')
        if (err%failed()) return
        do j = 1, sc%n
          if (.not. (sc%b(j) > 0.0_dp .and. sc%h(j) > 0.0_dp)) then
            call invalid_value(deck, t, 'section_b('//str(k)//','//str(j)//'), section_h('//str(k)//','//str(j)//')', &
                               str(sc%b(j))//', '//str(sc%h(j)), 'section width and depth must be > 0', err); return
          end if
          if (.not. (sc%f1(j) > 0.0_dp .and. sc%f1(j) <= 1.0_dp)) then
            call invalid_value(deck, t, 'section_end('//str(k)//','//str(j)//')', str(sc%f1(j)), &
                               'a section ends at a fraction of the link in (0, 1]', err); return
          end if
        end do
        do j = 2, sc%n
          if (.not. (sc%f1(j) > sc%f1(j - 1))) then
            call invalid_value(deck, t, 'section_end('//str(k)//','//str(j)//')', str(sc%f1(j)), &
                               'section ends must increase along the link', err); return
          end if
        end do
        if (abs(sc%f1(sc%n) - 1.0_dp) > 1.0e-12_dp) then
          call invalid_value(deck, t, 'section_end('//str(k)//','//str(sc%n)//')', str(sc%f1(sc%n)), &
                             'the last section must end at the link''s end 2 (1.0)', err); return
        end if
      end associate
    end do
  end subroutine validate

  !> The namelist variables of both groups from a settings value (the defaults
  !> before a read).
  subroutine stage_from(s)
    type(steady_settings_t), intent(in) :: s
    integer :: k
    method = s%method
    n_harmonics = s%harmonic%n_harmonics
    harmonics_kept = s%harmonic%n_kept
    velocity_terms = s%harmonic%velocity_terms
    outer_tol = s%harmonic%outer_tol
    max_outer = s%harmonic%max_outer
    resonance_ratio = s%harmonic%resonance_ratio
    allow_resonance = s%allow_resonance
    allow_beyond_peak = s%allow_beyond_peak
    output_step_deg = s%output_step_deg
    shape_points = s%shape_points
    damping_beta = s%element%damping_beta
    integrator = s%integrator
    rtol = s%shooting%rtol
    atol = s%shooting%atol
    newton_tol = s%shooting%newton_tol
    max_newton = s%shooting%max_newton
    max_steps = s%shooting%max_steps
    unit_circle_tol = s%shooting%unit_circle_tol
    singular_rcond = s%shooting%singular_rcond
    d_k = s%element%d_k
    d_b = s%element%d_b
    d_g = s%element%d_g
    shear = s%element%shear
    rotary_inertia = s%element%rotary_inertia
    shear_inertia = s%element%shear_inertia
    shear_modulus = s%element%shear_modulus
    poisson = s%element%poisson
    shear_factor = s%element%shear_factor
    n_gauss = s%element%n_gauss
    do k = 1, max_links
      n_sections(k) = s%sections(k)%n
      section_end(k, :) = s%sections(k)%f1
      section_b(k, :) = s%sections(k)%b
      section_h(k, :) = s%sections(k)%h
    end do
  end subroutine stage_from

  subroutine echo_steady_settings(out)
    type(table_t), intent(inout) :: out
    call out%echo_group(steady_group)
    call out%echo_group(tennant_group)
  end subroutine echo_steady_settings

  !> The &steady and &tennant groups as read, with method set, for a deck
  !> written by the program (the design analysis' final deck).
  subroutine write_steady_groups(unit, method_text)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: method_text
    character(len=16) :: method_read
    method_read = method
    method = method_text
    call write_group(steady_group, unit)
    call write_group(tennant_group, unit)
    method = method_read
  end subroutine write_steady_groups

  !> The &steady group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine steady_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=steady, delim='apostrophe')
    else
      read(r%unit, nml=steady, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine steady_group

  !> The &tennant group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine tennant_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=tennant, delim='apostrophe')
    else
      read(r%unit, nml=tennant, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine tennant_group
end module steady_settings
