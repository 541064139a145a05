!> The deck group &general_links (doc/general_mechanism.md, "Flexible
!> analysis"): the section, material and mesh of every link of the
!> &general_mechanism, by link number, with the documented defaults (the
!> &spatial_mechanism's: a 1 x 0.25 in rectangular aluminium bar, Tennant's
!> Ramberg-Osgood constants, one element a link).  Every value is checked
!> here (code 2 naming deck, group, variable and line).
module general_links_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t, input_error_in
  use deck_checks, only: check_reals, check_integer, check_choice
  use table_output, only: table_t
  use material_law, only: ramberg_osgood_t
  use reference_materials, only: tennant_aluminium_e1, tennant_aluminium_e2, tennant_aluminium_m, &
    tennant_aluminium_rho
  use spatial_section, only: spatial_section_init, section_rectangular, section_circular
  use spatial_model, only: spatial_link_t
  use general_mechanism, only: max_glinks
  implicit none
  private
  public :: general_links_input_t, read_general_links, echo_general_links, build_general_links

  !> The group as read; the default initialisation is the documented defaults.
  type :: general_links_input_t
    integer :: link_n_elements(max_glinks) = 1
    character(len=16) :: link_section(max_glinks) = 'rectangular'
    real(dp) :: link_depth(max_glinks) = 1.0_dp, link_width(max_glinks) = 0.25_dp, link_radius(max_glinks) = 0.0_dp
    real(dp) :: link_e1(max_glinks) = tennant_aluminium_e1, link_e2(max_glinks) = tennant_aluminium_e2
    real(dp) :: link_m(max_glinks) = tennant_aluminium_m, link_rho(max_glinks) = tennant_aluminium_rho
    real(dp) :: link_poisson(max_glinks) = 0.33_dp
  end type general_links_input_t

  character(len=*), parameter :: g = 'general_links'

  ! staging variables of the namelist group
  integer :: link_n_elements(max_glinks)
  character(len=16) :: link_section(max_glinks)
  real(dp) :: link_depth(max_glinks), link_width(max_glinks), link_radius(max_glinks), link_e1(max_glinks), &
              link_e2(max_glinks), link_m(max_glinks), link_rho(max_glinks), link_poisson(max_glinks)
  namelist /general_links/ link_n_elements, link_section, link_depth, link_width, link_radius, link_e1, link_e2, &
    link_m, link_rho, link_poisson

contains

  !> Read &general_links (optional: the defaults) and check the values of links 1..n_links.
  subroutine read_general_links(deck, n_links, s, err)
    type(deck_t), intent(inout) :: deck
    integer, intent(in) :: n_links
    type(general_links_input_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    logical :: found
    call stage_from(s)
    call deck%read_group(g, general_links_group, .false., found, err)
    if (err%failed()) return
    s = general_links_input_t(link_n_elements, link_section, link_depth, link_width, link_radius, link_e1, &
                              link_e2, link_m, link_rho, link_poisson)
    call validate(deck, n_links, s, err)
  end subroutine read_general_links

  subroutine stage_from(s)
    type(general_links_input_t), intent(in) :: s
    link_n_elements = s%link_n_elements
    link_section = s%link_section
    link_depth = s%link_depth
    link_width = s%link_width
    link_radius = s%link_radius
    link_e1 = s%link_e1
    link_e2 = s%link_e2
    link_m = s%link_m
    link_rho = s%link_rho
    link_poisson = s%link_poisson
  end subroutine stage_from

  !> The ranges of &spatial_mechanism's link values (doc/decks.md).
  subroutine validate(deck, n, s, err)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: n
    type(general_links_input_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    integer :: k
    do k = 1, n
      call check_integer(deck, g, 'link_n_elements('//str(k)//')', s%link_n_elements(k), err, at_least=1, &
                         at_most=200)
      call check_choice(deck, g, 'link_section('//str(k)//')', s%link_section(k), &
                        [character(16) :: 'rectangular', 'circular'], err)
    end do
    call check_reals(deck, g, 'link_depth', s%link_depth(1:n), err, at_least=1.0e-8_dp, at_most=100.0_dp)
    call check_reals(deck, g, 'link_width', s%link_width(1:n), err, at_least=1.0e-8_dp, at_most=100.0_dp)
    call check_reals(deck, g, 'link_radius', s%link_radius(1:n), err, at_least=0.0_dp, at_most=100.0_dp)
    call check_reals(deck, g, 'link_e1', s%link_e1(1:n), err, above=0.0_dp, at_most=1.0e9_dp)
    call check_reals(deck, g, 'link_e2', s%link_e2(1:n), err, at_least=0.0_dp, at_most=1.0e15_dp)
    call check_reals(deck, g, 'link_m', s%link_m(1:n), err, above=1.0_dp, at_most=9.0_dp)
    call check_reals(deck, g, 'link_rho', s%link_rho(1:n), err, at_least=1.0e-12_dp, at_most=1.0_dp, &
                     why='a subnormal density overflows E1/rho')
    call check_reals(deck, g, 'link_poisson', s%link_poisson(1:n), err, above=-1.0_dp, below=0.5_dp)
    do k = 1, n
      if (err%failed()) exit
      if (s%link_section(k) == 'circular' .and. .not. s%link_radius(k) > 0.0_dp) &
        call invalid_value(deck, g, 'link_radius('//str(k)//')', str(s%link_radius(k)), &
                           'a circular link needs a radius > 0', err)
    end do
  end subroutine validate

  !> Section, material and element count of links 1..n.
  subroutine build_general_links(deck, s, n, links, err)
    type(deck_t), intent(in) :: deck
    type(general_links_input_t), intent(in) :: s
    integer, intent(in) :: n
    type(spatial_link_t), allocatable, intent(out) :: links(:)
    type(error_t), intent(inout) :: err
    integer :: k
    type(ramberg_osgood_t) :: mat
    allocate(links(n))
    do k = 1, n
      mat = ramberg_osgood_t(s%link_e1(k), s%link_e2(k), s%link_m(k), s%link_rho(k))
      links(k)%n_elements = s%link_n_elements(k)
      links(k)%material = mat
      links(k)%shear_modulus = s%link_e1(k)/(2.0_dp*(1.0_dp + s%link_poisson(k)))
      if (s%link_section(k) == 'circular') then
        call spatial_section_init(links(k)%sec, section_circular, [s%link_radius(k)], mat, err)
      else
        call spatial_section_init(links(k)%sec, section_rectangular, [s%link_depth(k), s%link_width(k)], mat, err)
      end if
      if (err%failed()) then
        call err%add_context('link '//str(k))
        call input_error_in(deck, g, err)
        return
      end if
    end do
  end subroutine build_general_links

  !> Echo the effective values into an output's header.
  subroutine echo_general_links(s, out)
    type(general_links_input_t), intent(in) :: s
    type(table_t), intent(inout) :: out
    call stage_from(s)
    call out%echo_group(general_links_group)
  end subroutine echo_general_links

  !> The group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine general_links_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=general_links, delim='apostrophe')
    else
      read(r%unit, nml=general_links, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine general_links_group
end module general_links_settings
