!> Plausibility warnings: input that runs but describes no real mechanism,
!> or a result beyond what the deck says the material bears.  A warning is
!> printed in the output (a '# warning:' line) and on stderr and never
!> changes the result; each says what to check (doc/failure_modes.md).
!>
!> - material: the bar wave speed sqrt(E1/rho) of each link outside the
!>   range of engineering solids (about 1,000 to 13,000 m/s), judged in the
!>   deck's system of units (&run units; not judged with 'none', a deck in
!>   units of its own, e.g. dimensionless).  A weight density given for the mass density (link_rho = 0.283
!>   lb/in^3 for steel instead of 7.33e-4 lb s^2/in^4) gives 386 times the
!>   density and a wave speed 20 times too low.
!> - strength: a link's peak |stress| above its link_strength (when given).
!> - crank speed: an undamped run whose crank speed is above the lowest
!>   natural frequency of the mechanism frozen at its start position (the
!>   structure then passes through a resonance on its way up, and without
!>   damping the start-up transient never decays).
module plausibility
  use kinds, only: dp
  use strings, only: str
  use table_output, only: table_t
  use linkage, only: mechanism_t
  use unit_system, only: unit_system_name, wave_speed_range
  implicit none
  private
  public :: warn_materials, warn_strength, wave_speed_warning, strength_warning, crank_speed_warning

contains

  !> Every link's material against the range of engineering solids.
  subroutine warn_materials(out, mech)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    integer :: k
    character(len=:), allocatable :: text
    do k = 1, mech%n_links
      text = wave_speed_warning(trim(mech%links(k)%name), mech%links(k)%e1, mech%links(k)%rho, unit_system_name())
      if (len(text) > 0) call out%warning(text)
    end do
  end subroutine warn_materials

  !> Every link's peak |stress| (over its elements; `peak(e)` by global
  !> element) against its link_strength, when given.
  subroutine warn_strength(out, mech, peak)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: peak(:)
    integer :: k, first, last
    character(len=:), allocatable :: text
    do k = 1, mech%n_links
      first = mech%links(k)%first_element
      last = first + mech%links(k)%n_elements - 1
      if (first < 1 .or. last > size(peak)) cycle
      text = strength_warning(trim(mech%links(k)%name), maxval(peak(first:last)), mech%links(k)%strength)
      if (len(text) > 0) call out%warning(text)
    end do
  end subroutine warn_strength

  !> '' or the warning for a link whose wave speed sqrt(e1/rho) lies outside
  !> the range of engineering solids in `system` ('in-lbf-s', 'si', 'none').
  function wave_speed_warning(link, e1, rho, system) result(text)
    character(len=*), intent(in) :: link, system
    real(dp), intent(in) :: e1, rho
    character(len=:), allocatable :: text, speed_unit
    real(dp) :: c, lo, hi
    text = ''
    if (system == 'none') return         ! no system of units: nothing to judge a speed by
    if (.not. (e1 > 0.0_dp .and. rho > 0.0_dp)) return
    c = sqrt(e1/rho)
    call wave_speed_range(system, lo, hi)
    if (c >= lo .and. c <= hi) return
    if (system == 'si') then
      speed_unit = ' m/s'
    else
      speed_unit = ' in/s'
    end if
    text = 'link '//link//': its wave speed sqrt(link_e1/link_rho) = '//str(c, 5)//speed_unit// &
           ' is outside the range of engineering solids ('//str(lo, 5)//' to '//str(hi, 5)//speed_unit// &
           '): check that link_e1 and link_rho are in the deck''s units'
    if (system == 'si') then
      text = text//' (E in Pa, rho a mass density in kg/m^3)'
    else
      text = text//' (in-lbf-s: E in lb/in^2, rho a mass density in lb s^2/in^4: a weight density in lb/in^3 '// &
             'divided by g = 386.09 in/s^2)'
    end if
  end function wave_speed_warning

  !> '' or the warning for a peak |stress| above the link's strength (0: not given).
  function strength_warning(link, peak, strength) result(text)
    character(len=*), intent(in) :: link
    real(dp), intent(in) :: peak, strength
    character(len=:), allocatable :: text
    text = ''
    if (.not. (strength > 0.0_dp) .or. .not. (peak > strength)) return
    text = 'link '//link//': peak |stress| '//str(peak, 6)//' psi is above its link_strength '//str(strength, 6)// &
           ' psi ('//str(peak/strength, 3)//' times): the link would yield or break; check the section, the '// &
           'material and the crank speed, or that link_strength is in the deck''s units'
  end function strength_warning

  !> '' or the warning for an undamped run with the crank faster than the
  !> lowest natural frequency omega_1 of the frozen mechanism.
  function crank_speed_warning(omega, omega_1, damping_beta) result(text)
    real(dp), intent(in) :: omega, omega_1, damping_beta
    character(len=:), allocatable :: text
    text = ''
    if (damping_beta > 0.0_dp .or. .not. (omega_1 > 0.0_dp) .or. .not. (abs(omega) > omega_1)) return
    text = 'the crank speed '//str(abs(omega), 6)//' rad/s is above the lowest natural frequency '// &
           str(omega_1, 6)//' rad/s of the mechanism frozen at its start position, and the run has no damping: '// &
           'the links run above their first resonance, where the undamped start-up transient never decays; '// &
           'check the crank speed, the section and the material, or add damping (damping_beta in &transient)'
  end function crank_speed_warning
end module plausibility
