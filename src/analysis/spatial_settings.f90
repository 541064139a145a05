!> The &spatial_mechanism group of a spatial deck (doc/spatial.md, "Deck"):
!> the single-loop spatial four-bar (RSSR, RSUR/RUSR with one universal
!> joint, or the planar four-bar with revolute joints), its driver and its three links.  Every value is checked
!> here (code 2 on bad input); the geometry is then checked by
!> spatial_fourbar_init.
module spatial_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t, input_error_in
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use material_law, only: ramberg_osgood_t
  use reference_materials, only: tennant_aluminium_e1, tennant_aluminium_e2, tennant_aluminium_m, &
    tennant_aluminium_rho
  use spatial_section, only: spatial_section_init, section_rectangular, section_circular
  use spatial_kinematics, only: spatial_fourbar_t, spatial_fourbar_init, spatial_fourbar_set_universal
  use spatial_model, only: spatial_link_t, spatial_joint_spherical, spatial_joint_revolute, spatial_joint_universal
  implicit none
  private
  public :: spatial_input_t, read_spatial_mechanism, spatial_mechanism_group, build_spatial, write_spatial_mechanism

  !> The group as read; the default initialisation is the documented defaults (doc/decks.md).
  type :: spatial_input_t
    real(dp) :: crank_pivot(3) = 0.0_dp, crank_axis(3) = [0.0_dp, 0.0_dp, 1.0_dp], crank_pin(3) = 0.0_dp
    real(dp) :: rocker_pivot(3) = 0.0_dp, rocker_axis(3) = [0.0_dp, 0.0_dp, 1.0_dp]
    real(dp) :: rocker_length = 0.0_dp, coupler_length = 0.0_dp
    integer :: branch = 1
    character(len=16) :: joint_b = 'spherical', joint_c = 'spherical'
    real(dp) :: universal_axis(3) = [0.0_dp, 0.0_dp, 1.0_dp]   !< in the crank's (B) or rocker's (C) frame
    real(dp) :: omega = 0.0_dp, theta0_deg = 0.0_dp
    integer :: link_n_elements(3) = 1
    character(len=16) :: link_section(3) = 'rectangular'
    real(dp) :: link_depth(3) = 1.0_dp, link_width(3) = 0.25_dp, link_radius(3) = 0.0_dp
    real(dp) :: link_e1(3) = tennant_aluminium_e1, link_e2(3) = tennant_aluminium_e2, link_m(3) = tennant_aluminium_m
    real(dp) :: link_rho(3) = tennant_aluminium_rho, link_poisson(3) = 0.33_dp
  end type spatial_input_t

  ! staging variables of the namelist group
  real(dp) :: crank_pivot(3), crank_axis(3), crank_pin(3), rocker_pivot(3), rocker_axis(3)
  real(dp) :: rocker_length, coupler_length, omega, theta0_deg
  integer :: branch, link_n_elements(3)
  character(len=16) :: joint_b, joint_c, link_section(3)
  real(dp) :: universal_axis(3)
  real(dp) :: link_depth(3), link_width(3), link_radius(3), link_e1(3), link_e2(3), link_m(3), link_rho(3), &
              link_poisson(3)
  namelist /spatial_mechanism/ crank_pivot, crank_axis, crank_pin, rocker_pivot, rocker_axis, rocker_length, &
    coupler_length, branch, joint_b, joint_c, universal_axis, omega, theta0_deg, link_n_elements, link_section, &
    link_depth, link_width, link_radius, link_e1, link_e2, link_m, link_rho, link_poisson

  character(len=*), parameter :: g = 'spatial_mechanism'

contains

  subroutine read_spatial_mechanism(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(spatial_input_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    logical :: found
    call stage_from(s)        ! (intent(out): the defaults)
    call deck%read_group(g, spatial_mechanism_group, .true., found, err)
    if (err%failed()) return
    s = spatial_input_t(crank_pivot, crank_axis, crank_pin, rocker_pivot, rocker_axis, rocker_length, &
                        coupler_length, branch, joint_b, joint_c, universal_axis, omega, theta0_deg, &
                        link_n_elements, link_section, link_depth, link_width, link_radius, link_e1, link_e2, link_m, &
                        link_rho, link_poisson)
    call validate(deck, s, err)
  end subroutine read_spatial_mechanism

  !> The namelist variables from a value of the group (the defaults before a read).
  subroutine stage_from(s)
    type(spatial_input_t), intent(in) :: s
    crank_pivot = s%crank_pivot
    crank_axis = s%crank_axis
    crank_pin = s%crank_pin
    rocker_pivot = s%rocker_pivot
    rocker_axis = s%rocker_axis
    rocker_length = s%rocker_length
    coupler_length = s%coupler_length
    branch = s%branch
    joint_b = s%joint_b
    joint_c = s%joint_c
    universal_axis = s%universal_axis
    omega = s%omega
    theta0_deg = s%theta0_deg
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

  !> Ranges (doc/decks.md): lengths and section sizes in [1e-8, 1e4] (a linkage,
  !> not a bridge); speeds below 1e5 rad/s; material constants positive
  !> (E2 >= 0), 1 < m <= 9 (the section rule is exact to m = 5 and
  !> accurate beyond), Poisson's ratio in (-1, 0.5) (G > 0).
  subroutine validate(deck, s, err)
    type(deck_t), intent(in) :: deck
    type(spatial_input_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    integer :: k
    call check_reals(deck, g, 'crank_pivot', s%crank_pivot, err, at_least=-1.0e4_dp, at_most=1.0e4_dp)
    call check_reals(deck, g, 'crank_axis', s%crank_axis, err, at_least=-1.0e4_dp, at_most=1.0e4_dp)
    call check_reals(deck, g, 'crank_pin', s%crank_pin, err, at_least=-1.0e4_dp, at_most=1.0e4_dp)
    call check_reals(deck, g, 'rocker_pivot', s%rocker_pivot, err, at_least=-1.0e4_dp, at_most=1.0e4_dp)
    call check_reals(deck, g, 'rocker_axis', s%rocker_axis, err, at_least=-1.0e4_dp, at_most=1.0e4_dp)
    call check_real(deck, g, 'rocker_length', s%rocker_length, err, at_least=1.0e-8_dp, at_most=1.0e4_dp)
    call check_real(deck, g, 'coupler_length', s%coupler_length, err, at_least=1.0e-8_dp, at_most=1.0e4_dp)
    call check_integer(deck, g, 'branch', s%branch, err, at_least=-1, at_most=1)
    if (.not. err%failed() .and. s%branch == 0) &
      call invalid_value(deck, g, 'branch', '0', 'must be +1 or -1 (the side of the coupler-rocker dyad)', err)
    call check_choice(deck, g, 'joint_b', s%joint_b, [character(16) :: 'spherical', 'revolute', 'universal'], err)
    call check_choice(deck, g, 'joint_c', s%joint_c, [character(16) :: 'spherical', 'revolute', 'universal'], err)
    if (.not. err%failed() .and. s%joint_b == 'universal' .and. s%joint_c /= 'spherical') &
      call invalid_value(deck, g, 'joint_c', trim(s%joint_c), 'with a universal joint at B, C must be spherical '// &
                         '(RUSR; two universal joints over-constrain the coupler''s spin)', err)
    if (.not. err%failed() .and. s%joint_c == 'universal' .and. s%joint_b /= 'spherical') &
      call invalid_value(deck, g, 'joint_b', trim(s%joint_b), 'with a universal joint at C, B must be spherical '// &
                         '(RSUR; two universal joints over-constrain the coupler''s spin)', err)
    call check_reals(deck, g, 'universal_axis', s%universal_axis, err, at_least=-1.0e4_dp, at_most=1.0e4_dp)
    if (.not. err%failed()) then   ! nested: .and. does not short-circuit, and norm2 of a NaN traps
      if (.not. norm2(s%universal_axis) > 1.0e-8_dp) &
        call invalid_value(deck, g, 'universal_axis', str(norm2(s%universal_axis)), 'must be a nonzero direction '// &
                           '(length > 1e-8)', err)
    end if
    ! the output is tabulated per revolution: below 1e-6 rad/s (a turn in 70
    ! days) 2 pi/omega overflows for a denormal speed (fuzz seed 11, case 27587)
    call check_real(deck, g, 'omega', s%omega, err, at_least=1.0e-6_dp, at_most=1.0e5_dp, why='constant crank speed')
    call check_real(deck, g, 'theta0_deg', s%theta0_deg, err, at_least=-3600.0_dp, at_most=3600.0_dp)
    do k = 1, 3
      call check_integer(deck, g, 'link_n_elements', s%link_n_elements(k), err, at_least=1, at_most=200)
      call check_choice(deck, g, 'link_section', s%link_section(k), [character(16) :: 'rectangular', 'circular'], &
                        err)
    end do
    call check_reals(deck, g, 'link_depth', s%link_depth, err, at_least=1.0e-8_dp, at_most=100.0_dp)
    call check_reals(deck, g, 'link_width', s%link_width, err, at_least=1.0e-8_dp, at_most=100.0_dp)
    call check_reals(deck, g, 'link_radius', s%link_radius, err, at_least=0.0_dp, at_most=100.0_dp)
    call check_reals(deck, g, 'link_e1', s%link_e1, err, above=0.0_dp, at_most=1.0e9_dp)
    call check_reals(deck, g, 'link_e2', s%link_e2, err, at_least=0.0_dp, at_most=1.0e15_dp)
    call check_reals(deck, g, 'link_m', s%link_m, err, above=1.0_dp, at_most=9.0_dp)
    call check_reals(deck, g, 'link_rho', s%link_rho, err, at_least=1.0e-12_dp, at_most=1.0_dp, &
                     why='a subnormal density overflows E1/rho')
    call check_reals(deck, g, 'link_poisson', s%link_poisson, err, above=-1.0_dp, below=0.5_dp)
    do k = 1, 3
      if (err%failed()) exit
      if (s%link_section(k) == 'circular' .and. .not. s%link_radius(k) > 0.0_dp) &
        call invalid_value(deck, g, 'link_radius', str(s%link_radius(k)), 'a circular link needs a radius > 0 '// &
                           '(link '//str(k)//')', err)
    end do
  end subroutine validate

  !> Kinematics and link data from the input; geometry errors are input errors.
  subroutine build_spatial(deck, s, kin, links, joint_b, joint_c, err)
    type(deck_t), intent(in) :: deck
    type(spatial_input_t), intent(in) :: s
    type(spatial_fourbar_t), intent(out) :: kin
    type(spatial_link_t), intent(out) :: links(3)
    integer, intent(out) :: joint_b, joint_c
    type(error_t), intent(inout) :: err
    integer :: k
    type(ramberg_osgood_t) :: mat
    call spatial_fourbar_init(kin, s%crank_pivot, s%crank_axis, s%crank_pin, s%rocker_pivot, s%rocker_axis, &
                              s%rocker_length, s%coupler_length, s%branch, err)
    do k = 1, 3
      if (err%failed()) exit
      mat = ramberg_osgood_t(s%link_e1(k), s%link_e2(k), s%link_m(k), s%link_rho(k))
      links(k)%n_elements = s%link_n_elements(k)
      links(k)%material = mat
      links(k)%shear_modulus = s%link_e1(k)/(2.0_dp*(1.0_dp + s%link_poisson(k)))
      if (s%link_section(k) == 'circular') then
        call spatial_section_init(links(k)%sec, section_circular, [s%link_radius(k)], mat, err)
      else
        call spatial_section_init(links(k)%sec, section_rectangular, [s%link_depth(k), s%link_width(k)], mat, err)
      end if
    end do
    joint_b = joint_kind(s%joint_b)
    joint_c = joint_kind(s%joint_c)
    if (.not. err%failed() .and. (joint_b == spatial_joint_universal .or. joint_c == spatial_joint_universal)) &
      call spatial_fourbar_set_universal(kin, joint_c == spatial_joint_universal, s%universal_axis, err)
    if (err%failed()) call input_error_in(deck, g, err)
  end subroutine build_spatial

  pure integer function joint_kind(name)
    character(len=*), intent(in) :: name
    select case (name)
    case ('revolute')
      joint_kind = spatial_joint_revolute
    case ('universal')
      joint_kind = spatial_joint_universal
    case default
      joint_kind = spatial_joint_spherical
    end select
  end function joint_kind

  !> The group with the values of s on unit u (a deck the design writes).
  subroutine write_spatial_mechanism(s, u)
    type(spatial_input_t), intent(in) :: s
    integer, intent(in) :: u
    call stage_from(s)
    write(u, nml=spatial_mechanism, delim='apostrophe')
  end subroutine write_spatial_mechanism

  !> The &spatial_mechanism group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine spatial_mechanism_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=spatial_mechanism, delim='apostrophe')
    else
      read(r%unit, nml=spatial_mechanism, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine spatial_mechanism_group
end module spatial_settings
