!> The groups of a transient deck together: &mechanism, &transient and
!> &effects, &loads, &clearance read in turn (each checked by its own
!> reader), then the one validation step of the rules that join two groups,
!> and the echo of every group in the output header.
module transient_deck
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value
  use table_output, only: table_t
  use linkage, only: mechanism_t
  use linkage_deck, only: read_mechanism, check_section_rules, echo_mechanism
  use external_loads, only: loads_input_t
  use loads_settings, only: read_loads, echo_loads
  use transient_settings, only: transient_settings_t, read_transient_settings, echo_transient_settings
  use clearance_run, only: clearance_monitor_t
  implicit none
  private
  public :: read_transient_deck, echo_transient_deck

contains

  !> Read every group of the deck, each checked as it is read, then the
  !> checks across groups.
  subroutine read_transient_deck(deck, mech, s, loads_in, clearance, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(out) :: mech
    type(transient_settings_t), intent(out) :: s
    type(loads_input_t), intent(out) :: loads_in
    type(clearance_monitor_t), intent(inout) :: clearance
    type(error_t), intent(inout) :: err
    call read_mechanism(deck, mech, err)
    if (err%failed()) return
    call read_transient_settings(deck, s, err)
    if (err%failed()) return
    call read_loads(deck, loads_in, err)
    if (err%failed()) return
    call clearance%read(deck, mech, err)
    if (err%failed()) return
    call check_across_groups(deck, mech, s, clearance%active, err)
  end subroutine read_transient_deck

  !> The rules that join &mechanism, &transient/&effects and &clearance
  !> (those of &clearance against the joints are its reader's, which takes
  !> the mechanism; those that need the built model, the driver's).
  !> clearance: some joint of &clearance has a clearance.
  subroutine check_across_groups(deck, mech, s, clearance, err)
    type(deck_t), intent(in) :: deck
    type(mechanism_t), intent(in) :: mech
    type(transient_settings_t), intent(in) :: s
    logical, intent(in) :: clearance
    type(error_t), intent(inout) :: err
    integer :: k
    call check_section_rules(deck, mech, s%effects%material, .false., err)
    if (err%failed()) return
    if (mech%driver%omega <= 0.0_dp .and. (s%t_end <= 0.0_dp .or. s%output_step_t <= 0.0_dp)) then
      call invalid_value(deck, 'transient', 't_end', str(s%t_end), &
        'the crank does not turn (omega = 0): give t_end > 0 and output_step_t > 0 to set the time span', err)
      return
    end if
    if (s%stop_when_periodic > 0.0_dp .and. .not. mech%driver%omega > 0.0_dp) then
      call invalid_value(deck, 'transient', 'stop_when_periodic', str(s%stop_when_periodic), &
                         'needs a turning crank (omega > 0): periodicity is judged per revolution', err)
      return
    end if
    if (clearance .and. s%initial == 'mode') then
      call invalid_value(deck, 'transient', 'initial', '''mode''', 'a mode of the pinned structure is not a '// &
                         'state of a linkage with clearance; start from ''rigid''', err)
      return
    end if
    do k = 1, size(s%point_link)
      if (len_trim(s%point_link(k)) == 0) cycle
      if (.not. any(mech%links(1:mech%n_links)%name == s%point_link(k))) then
        call invalid_value(deck, 'transient', 'point_link('//str(k)//')', ''''//trim(s%point_link(k))//'''', &
                           'is not a link of &mechanism', err)
        return
      end if
    end do
  end subroutine check_across_groups

  !> The effective input of every group read, in the header.
  subroutine echo_transient_deck(out, mech, loads_in, clearance)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(loads_input_t), intent(in) :: loads_in
    type(clearance_monitor_t), intent(in) :: clearance
    call echo_mechanism(mech, out)
    call echo_transient_settings(out)
    call clearance%echo(out)
    call echo_loads(loads_in, out)
  end subroutine echo_transient_deck
end module transient_deck
