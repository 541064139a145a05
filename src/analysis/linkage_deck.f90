!> The deck side of the linkage description: the flat namelist group
!> &mechanism (gfortran cannot read derived types with allocatable components
!> from a namelist, so its variables are staged through mechanism_input_t, whose
!> default initialisation *is* the documented default, doc/mechanism_deck.md),
!> its echo, and the one section rule every analysis applies to the deck.
module linkage_deck
  use strings, only: str
  use error_status, only: error_t
  use deck_reader, only: deck_t, invalid_value, group_read_t, write_group
  use table_output, only: table_t
  use linkage, only: mechanism_input_t, input_issue_t, mechanism_t, build_mechanism, max_links, max_joints
  use kinds, only: dp
  use reference_materials, only: default_link_material
  use unit_system, only: unit_system_name
  implicit none
  private
  public :: read_mechanism, echo_mechanism, write_mechanism_group, check_section_rules

  ! Staging variables of the deck group &mechanism (module variables because
  ! the deck reader's callback receives only the unit; see read_mechanism).
  integer :: n_joints, n_links, driver_link
  character(len=16) :: joint_name(max_joints), joint_type(max_joints), link_name(max_links), profile
  real(dp) :: joint_x(max_joints), joint_y(max_joints), joint_guide_deg(max_joints), joint_mass(max_joints)
  integer :: joint_sliding_link(max_joints), link_joint1(max_links), link_joint2(max_links), link_n_elements(max_links)
  character(len=8) :: joint_branch(max_joints), branch
  real(dp) :: link_length(max_links), link_b(max_links), link_h(max_links), link_area(max_links), &
              link_inertia(max_links), link_e1(max_links), link_e2(max_links), link_m(max_links), link_rho(max_links)
  character(len=12) :: link_section(max_links)
  real(dp) :: link_c(max_links), link_wall(max_links)
  real(dp) :: omega, theta0_deg, spinup_time, toggle_rcond
  real(dp) :: link_cw_mass(max_links), link_cw_x(max_links), link_cw_y(max_links), link_strength(max_links)
  namelist /mechanism/ n_joints, joint_name, joint_type, joint_x, joint_y, joint_guide_deg, &
    joint_sliding_link, joint_branch, joint_mass, &
    n_links, link_name, link_joint1, link_joint2, link_length, link_b, link_h, &
    link_area, link_inertia, link_section, link_c, link_wall, link_e1, link_e2, link_m, link_rho, link_n_elements, &
    driver_link, omega, theta0_deg, profile, spinup_time, branch, toggle_rcond, &
    link_cw_mass, link_cw_x, link_cw_y, link_strength

contains


  !> The one rule for sections that are not rectangles, shared by every
  !> analysis: the Ramberg-Osgood law is integrated through a rectangular
  !> depth (Kear K16-K17, Tennant T6) and Tennant's shear angle assumes a
  !> rectangle, so a circle, tube or general section is a linear-elastic beam
  !> given by A, I and c.  A link that breaks the rule is an input error.
  subroutine check_section_rules(deck, mech, material, shear, err)
    type(deck_t), intent(in) :: deck
    type(mechanism_t), intent(in) :: mech
    logical, intent(in) :: material, shear
    type(error_t), intent(inout) :: err
    integer :: i
    if (err%failed() .or. .not. (material .or. shear)) return
    do i = 1, mech%n_links
      if (mech%links(i)%section == 'rectangle') cycle
      if (material) then
        call invalid_value(deck, 'mechanism', 'link_section('//str(i)//')', "'"//trim(mech%links(i)%section)//"'", &
          'the material effect integrates the Ramberg-Osgood law through a rectangular depth: a '// &
          trim(mech%links(i)%section)//' section needs it off (a linear-elastic beam of A, I and c)', err)
      else
        call invalid_value(deck, 'mechanism', 'link_section('//str(i)//')', "'"//trim(mech%links(i)%section)//"'", &
          'the shear angle of Tennant''s element assumes a rectangle: a '//trim(mech%links(i)%section)// &
          ' section needs shear off', err)
      end if
      return
    end do
  end subroutine check_section_rules

  !> Read &mechanism (required), validate the flat input and build the
  !> indexed mechanism.  Invalid values are reported with their deck line.
  subroutine read_mechanism(deck, mech, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(out) :: mech
    type(error_t), intent(inout) :: err
    type(mechanism_input_t) :: inp
    type(input_issue_t) :: issue
    logical :: found
    call stage_from(inp)
    call default_material()
    call deck%read_group('mechanism', mechanism_group, required=.true., found=found, err=err)
    if (err%failed()) return
    inp = mechanism_input_t(n_joints=n_joints, joint_name=joint_name, joint_type=joint_type, joint_x=joint_x, &
      joint_y=joint_y, joint_guide_deg=joint_guide_deg, joint_sliding_link=joint_sliding_link, &
      joint_branch=joint_branch, joint_mass=joint_mass, n_links=n_links, link_name=link_name, &
      link_joint1=link_joint1, link_joint2=link_joint2, link_length=link_length, link_b=link_b, link_h=link_h, &
      link_area=link_area, link_inertia=link_inertia, link_section=link_section, link_c=link_c, link_wall=link_wall, &
      link_e1=link_e1, link_e2=link_e2, link_m=link_m, link_rho=link_rho, link_n_elements=link_n_elements, &
      link_cw_mass=link_cw_mass, link_cw_x=link_cw_x, link_cw_y=link_cw_y, link_strength=link_strength, &
      driver_link=driver_link, omega=omega, &
      theta0_deg=theta0_deg, profile=profile, spinup_time=spinup_time, branch=branch, toggle_rcond=toggle_rcond)
    call build_mechanism(inp, mech, err, issue)
    if (err%failed() .and. allocated(issue%variable)) then
      call err%clear()
      call invalid_value(deck, 'mechanism', issue%variable, issue%value, issue%rule, err)
    end if
  end subroutine read_mechanism

  !> The &mechanism group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine mechanism_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=mechanism, delim='apostrophe')
    else
      read(r%unit, nml=mechanism, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine mechanism_group

  !> Echo the mechanism's effective input, the group &mechanism, into an output.
  subroutine echo_mechanism(mech, out)
    type(mechanism_t), intent(in) :: mech
    type(table_t), intent(inout) :: out
    call stage_from(mech%input)
    call out%echo_group(mechanism_group)
  end subroutine echo_mechanism

  !> Write the mechanism's effective input as the group &mechanism of a deck.
  subroutine write_mechanism_group(mech, unit)
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: unit
    call stage_from(mech%input)
    call write_group(mechanism_group, unit)
  end subroutine write_mechanism_group

  !> The default link material in the run's system of units.
  subroutine default_material()
    real(dp) :: e1, e2, rho
    call default_link_material(unit_system_name(), e1, e2, rho)
    link_e1 = e1
    link_e2 = e2
    link_rho = rho
  end subroutine default_material

  subroutine stage_from(inp)
    type(mechanism_input_t), intent(in) :: inp
    n_joints = inp%n_joints
    joint_name = inp%joint_name
    joint_type = inp%joint_type
    joint_x = inp%joint_x
    joint_y = inp%joint_y
    joint_guide_deg = inp%joint_guide_deg
    joint_sliding_link = inp%joint_sliding_link
    joint_branch = inp%joint_branch
    joint_mass = inp%joint_mass
    n_links = inp%n_links
    link_name = inp%link_name
    link_joint1 = inp%link_joint1
    link_joint2 = inp%link_joint2
    link_length = inp%link_length
    link_b = inp%link_b
    link_h = inp%link_h
    link_area = inp%link_area
    link_inertia = inp%link_inertia
    link_section = inp%link_section
    link_c = inp%link_c
    link_wall = inp%link_wall
    link_e1 = inp%link_e1
    link_e2 = inp%link_e2
    link_m = inp%link_m
    link_rho = inp%link_rho
    link_n_elements = inp%link_n_elements
    link_cw_mass = inp%link_cw_mass
    link_cw_x = inp%link_cw_x
    link_cw_y = inp%link_cw_y
    link_strength = inp%link_strength
    driver_link = inp%driver_link
    omega = inp%omega
    theta0_deg = inp%theta0_deg
    profile = inp%profile
    spinup_time = inp%spinup_time
    branch = inp%branch
    toggle_rcond = inp%toggle_rcond
  end subroutine stage_from
end module linkage_deck
