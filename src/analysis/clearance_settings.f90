!> The &clearance group of a transient deck (doc/clearance.md): radial
!> clearance, contact stiffness, restitution and friction per joint (arrays
!> indexed like the joints of &mechanism), and the contact law's common
!> constants.  Absent or all clearances zero: the pinned analysis, unchanged.
module clearance_settings
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_choice
  use table_output, only: table_t
  use linkage, only: mechanism_t, max_joints, joint_pin, joint_ground_pin, joint_slider_link, joint_type_name
  use contact_law, only: law_names
  implicit none
  private
  public :: clearance_settings_t, read_clearance_settings, echo_clearance_settings

  type :: clearance_settings_t
    logical :: found = .false.
    real(dp) :: clearance(max_joints) = 0.0_dp        !< radial clearance c (in); 0 = pinned
    real(dp) :: stiffness(max_joints) = 0.0_dp        !< contact stiffness K (lb/in^exponent)
    real(dp) :: restitution(max_joints) = 0.9_dp      !< coefficient of restitution e
    real(dp) :: friction(max_joints) = 0.0_dp         !< Coulomb coefficient mu
    real(dp) :: journal_radius(max_joints) = 0.0_dp   !< journal radius (in), for the sliding speed
    character(len=20) :: law = 'lankarani_nikravesh'
    real(dp) :: exponent = 1.5_dp
    real(dp) :: friction_speed = 0.1_dp               !< v_s of the tanh friction (in/s)
    real(dp) :: impact_speed = 1.0_dp                 !< approach speeds >= it are impacts (in/s)
  end type clearance_settings_t

  ! staging variables of &clearance
  real(dp) :: joint_clearance(max_joints), joint_stiffness(max_joints), joint_restitution(max_joints), &
              joint_friction(max_joints), journal_radius(max_joints), exponent, friction_speed, impact_speed
  character(len=20) :: law
  namelist /clearance/ joint_clearance, joint_stiffness, joint_restitution, joint_friction, journal_radius, law, &
    exponent, friction_speed, impact_speed

contains

  !> Read and check &clearance (optional).  Every value is checked; a joint
  !> with c > 0 must be a pin between two links or a ground pin of one link.
  subroutine read_clearance_settings(deck, mech, s, err)
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(clearance_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    character(len=*), parameter :: g = 'clearance'
    integer :: j, nj
    call stage_from(s)
    call deck%read_group(g, clearance_group, .false., s%found, err)
    if (err%failed() .or. .not. s%found) return
    s = clearance_settings_t(found=s%found, clearance=joint_clearance, stiffness=joint_stiffness, &
                             restitution=joint_restitution, friction=joint_friction, journal_radius=journal_radius, &
                             law=law, exponent=exponent, friction_speed=friction_speed, impact_speed=impact_speed)
    nj = mech%n_joints
    call check_reals(deck, g, 'joint_clearance', s%clearance, err, at_least=0.0_dp, at_most=0.05_dp*mech%length_scale, &
                     why='a radial clearance (in): small against the links (5% of their mean length) for the '// &
                     'rigid-body motion of the pinned linkage to stay the reference')
    call check_reals(deck, g, 'joint_stiffness', s%stiffness, err, at_least=0.0_dp, at_most=1.0e15_dp, &
                     why='contact stiffness K (lb/in^exponent); steel on steel, 1/4 in pin: about 3e7')
    call check_reals(deck, g, 'joint_restitution', s%restitution, err, at_least=0.0_dp, at_most=1.0_dp, &
                     why='a coefficient of restitution')
    call check_reals(deck, g, 'joint_friction', s%friction, err, at_least=0.0_dp, at_most=2.0_dp, &
                     why='a Coulomb friction coefficient')
    call check_reals(deck, g, 'journal_radius', s%journal_radius, err, at_least=0.0_dp, &
                     at_most=0.5_dp*mech%length_scale, why='the pin radius (in), for the sliding speed of friction')
    call check_choice(deck, g, 'law', s%law, law_names, err)
    call check_real(deck, g, 'exponent', s%exponent, err, at_least=1.0_dp, at_most=3.0_dp, &
                    why='the force exponent: 1.5 Hertz, 1 linear; the force must be C1 at first touch for n > 1')
    call check_real(deck, g, 'friction_speed', s%friction_speed, err, above=0.0_dp, at_most=1.0e3_dp, &
                    why='in/s: the sliding speed over which tanh friction rises to mu F_n')
    call check_real(deck, g, 'impact_speed', s%impact_speed, err, above=0.0_dp, at_most=1.0e4_dp, &
                    why='in/s: slower contacts are not impacts (no restart) and use it as their reference speed')
    if (err%failed()) return
    do j = 1, max_joints
      if (.not. s%clearance(j) > 0.0_dp) cycle
      if (j > nj) then
        call invalid_value(deck, g, 'joint_clearance('//str(j)//')', str(s%clearance(j)), &
                           'the mechanism has only '//str(nj)//' joints', err)
        return
      end if
      ! (the model's split_journal renumbers the table's map, not a sleeve element's own unknowns)
      if (any(mech%joints(1:nj)%kind == joint_slider_link)) then
        call invalid_value(deck, g, 'joint_clearance('//str(j)//')', str(s%clearance(j)), 'joint clearances are '// &
                           'not modelled in a mechanism with a link sliding through a sleeve (slider_link)', err)
        return
      end if
      ! a counterweight turns about a fixed pivot (the model's register_counterweights)
      if (any(mech%links(1:mech%n_links)%cw_mass > 0.0_dp .and. mech%links(1:mech%n_links)%joint(1) == j)) then
        call invalid_value(deck, g, 'joint_clearance('//str(j)//')', str(s%clearance(j)), 'joint '// &
                           trim(mech%joints(j)%name)//' is the pivot of a counterweight: a clearance there is '// &
                           'not modelled (the counterweight turns about a fixed pivot)', err)
        return
      end if
      associate (jt => mech%joints(j))
        if (.not. ((jt%kind == joint_pin .and. jt%n_links == 2) .or. (jt%kind == joint_ground_pin .and. &
                                                                       jt%n_links == 1))) then
          call invalid_value(deck, g, 'joint_clearance('//str(j)//')', str(s%clearance(j)), 'joint '//trim(jt%name)// &
            ' is a '//joint_type_name(jt%kind)//' joining '//str(jt%n_links)//' link(s): clearance is modelled at a pin '// &
            'between two links or a ground pin of one link', err)
          return
        end if
      end associate
      if (.not. s%stiffness(j) > 0.0_dp) then
        call invalid_value(deck, g, 'joint_stiffness('//str(j)//')', str(s%stiffness(j)), &
                           'a clearance joint needs a contact stiffness > 0', err)
        return
      end if
      ! e = 1e-300 gave a factor of 1.6e300 and contact forces that overflow
      if (s%law == 'flores' .and. s%restitution(j) < 0.01_dp) then
        call invalid_value(deck, g, 'joint_restitution('//str(j)//')', str(s%restitution(j)), &
                           'the flores law needs e >= 0.01 (its factor 8(1-e)/(5e) grows like 1/e)', err)
        return
      end if
      if (s%law == 'calibrated' .and. s%restitution(j) < 0.01_dp) then
        call invalid_value(deck, g, 'joint_restitution('//str(j)//')', str(s%restitution(j)), &
                           'the calibrated law needs e >= 0.01 (its factor grows like 1/e)', err)
        return
      end if
    end do
  end subroutine read_clearance_settings

  !> Echo &clearance when the deck has it (a deck without it is echoed as before).
  subroutine echo_clearance_settings(s, out)
    type(clearance_settings_t), intent(in) :: s
    type(table_t), intent(inout) :: out
    if (.not. s%found) return
    call stage_from(s)
    call out%echo_group(clearance_group)
  end subroutine echo_clearance_settings

  subroutine stage_from(s)
    type(clearance_settings_t), intent(in) :: s
    joint_clearance = s%clearance
    joint_stiffness = s%stiffness
    joint_restitution = s%restitution
    joint_friction = s%friction
    journal_radius = s%journal_radius
    law = s%law
    exponent = s%exponent
    friction_speed = s%friction_speed
    impact_speed = s%impact_speed
  end subroutine stage_from

  !> The &clearance group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine clearance_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=clearance, delim='apostrophe')
    else
      read(r%unit, nml=clearance, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine clearance_group
end module clearance_settings
