!> The &run group every deck starts with: which analysis to run and a title.
module run_settings
  use error_status, only: error_t
  use deck_reader, only: deck_t, group_read_t
  use deck_layout, only: check_deck_layout
  use deck_checks, only: check_choice
  use strings, only: lower
  use unit_system, only: set_unit_system, unit_systems, unit_system_name
  use table_output, only: table_t
  use version, only: program_name, program_version
  implicit none
  private
  public :: read_run_settings, write_run_header, analysis_driver, check_deck_groups, analysis_groups, group_len, max_groups

  abstract interface
    !> An analysis driver (run_transient, run_steady, ...): the deck in, the
    !> output table filled, an error value out.
    subroutine analysis_driver(deck, out, err)
      import :: deck_t, table_t, error_t
      type(deck_t), intent(inout) :: deck
      type(table_t), intent(inout) :: out
      type(error_t), intent(inout) :: err
    end subroutine analysis_driver
  end interface

  !> The group's values; the default initialisation is the documented
  !> defaults (doc/decks.md).
  type :: run_settings_t
    character(len=32) :: analysis = ''        !< required: refused when blank or unknown (flexmech.f90)
    character(len=256) :: title = ''
    character(len=16) :: units = 'in-lbf-s'
  end type run_settings_t

  ! staging variables of &run
  character(len=32) :: analysis
  character(len=256) :: title
  character(len=16) :: units
  namelist /run/ analysis, title, units

  integer, parameter :: group_len = 20, max_groups = 7

contains

  !> The groups an analysis reads, &run first, blank entries after the last
  !> (all blank for an unknown analysis).  A sweep deck adds &sweep.
  pure function analysis_groups(name) result(groups)
    character(len=*), intent(in) :: name
    character(len=group_len) :: groups(max_groups)
    groups = ''
    select case (name)
    case ('transient')
      groups(1:6) = [character(len=group_len) :: 'run', 'mechanism', 'transient', 'effects', 'loads', 'clearance']
    case ('steady')
      groups(1:4) = [character(len=group_len) :: 'run', 'mechanism', 'steady', 'tennant']
    case ('optimize')
      groups(1:3) = [character(len=group_len) :: 'run', 'optimize', 'problem_data']
    case ('design')
      groups(1:5) = [character(len=group_len) :: 'run', 'mechanism', 'steady', 'tennant', 'design']
    case ('spatial')
      groups(1:5) = [character(len=group_len) :: 'run', 'spatial_mechanism', 'transient', 'effects', 'spatial_loads']
    case ('spatial_design')
      groups(1:5) = [character(len=group_len) :: 'run', 'spatial_mechanism', 'transient', 'effects', 'design']
    case ('lsode_check')
      groups(1:2) = [character(len=group_len) :: 'run', 'lsode_check']
    case ('kinematics')
      groups(1:3) = [character(len=group_len) :: 'run', 'general_mechanism', 'kinematics']
    case ('general_transient')
      groups(1:7) = [character(len=group_len) :: 'run', 'general_mechanism', 'general_links', 'transient', 'effects', &
                     'spatial_loads', 'general_support']
    end select
  end function analysis_groups

  !> The deck holds only groups the analysis reads, each once, and nothing
  !> but blanks and comments between them (deck_layout); `sweep`: a sweep
  !> deck, which has a &sweep group besides.
  subroutine check_deck_groups(deck, analysis_name, sweep, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: analysis_name
    logical, intent(in) :: sweep
    type(error_t), intent(inout) :: err
    character(len=group_len) :: known(1 + 9*max_groups), reads(max_groups)
    reads = analysis_groups(trim(analysis_name))
    if (len_trim(reads(1)) == 0) return   ! the name itself is refused elsewhere
    ! every group of the program, for the suggestion (repeats and blanks do no harm)
    known = [character(len=group_len) :: 'sweep', analysis_groups('transient'), analysis_groups('steady'), &
             analysis_groups('optimize'), analysis_groups('design'), analysis_groups('spatial'), &
             analysis_groups('spatial_design'), analysis_groups('lsode_check'), analysis_groups('kinematics'), &
             analysis_groups('general_transient')]
    if (sweep) then
      call check_deck_layout(deck, trim(analysis_name), [character(len=group_len) :: reads, 'sweep'], known, err)
    else
      call check_deck_layout(deck, trim(analysis_name), reads, known, err)
    end if
  end subroutine check_deck_groups

  subroutine read_run_settings(deck, analysis_out, title_out, err)
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(out) :: analysis_out, title_out
    type(error_t), intent(inout) :: err
    type(run_settings_t) :: defaults
    logical :: found
    call stage_from(defaults)
    call deck%read_group('run', run_group, .true., found, err)
    analysis_out = analysis
    title_out = title
    if (err%failed()) return
    call check_choice(deck, 'run', 'units', lower(units), unit_systems, err)
    if (.not. err%failed()) call set_unit_system(units)
  end subroutine read_run_settings

  !> The first lines of every output: program, deck, title, and the &run
  !> group as read (after read_run_settings).
  subroutine write_run_header(out, deck_path, title_text)
    type(table_t), intent(inout) :: out
    character(len=*), intent(in) :: deck_path, title_text
    character(len=:), allocatable :: system
    call out%comment(program_name//' '//program_version)
    call out%comment('deck: '//deck_path)
    if (len_trim(title_text) > 0) call out%comment('title: '//trim(title_text))
    if (unit_system_name() == 'none') then
      call out%comment('units: none (no unit labels: the deck''s own consistent units; time in s, angles in deg)')
    else      ! (written in in-lbf-s: table_t labels it in the run's system)
      system = unit_system_name()
      if (system == 'si') system = 'SI'
      call out%comment('units: '//system// &
                       ' (lengths (in), forces (lb), stresses (psi), mass densities (lb s^2/in^4); time in s, '// &
                       'angles in deg)')
    end if
    call out%comment('effective input (every value, defaults included):')
    call out%echo_group(run_group)
  end subroutine write_run_header

  !> The namelist variables from a settings value (the defaults before a read).
  subroutine stage_from(s)
    type(run_settings_t), intent(in) :: s
    analysis = s%analysis
    title = s%title
    units = s%units
  end subroutine stage_from

  !> The &run group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine run_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=run, delim='apostrophe')
    else
      read(r%unit, nml=run, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine run_group
end module run_settings
