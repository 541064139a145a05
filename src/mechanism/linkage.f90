!> The description of a single-degree-of-freedom planar linkage: joints (the
!> points where link ends meet, some of them fixed to the ground), links (beams
!> running between two joints, each split into finite elements) and the crank
!> driver.  Four-bar, slider-crank and inverted slider-crank are data, not code.
!>
!> The deck group &mechanism is flat (gfortran cannot read derived types with
!> allocatable components from a namelist); its variables are the components of
!> mechanism_input_t, whose default initialisation *is* the documented default
!> (doc/mechanism_deck.md).  build_mechanism validates every value, naming the
!> variable and the value, and returns the checked, indexed mechanism_t.
!> Reading and echoing &mechanism: module linkage_deck; the summary text of the
!> output header: module linkage_report; the default material:
!> module reference_materials.
module linkage
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str, lower
  use reference_materials, only: tennant_aluminium_e1, tennant_aluminium_e2, tennant_aluminium_m, &
    tennant_aluminium_rho
  implicit none
  private
  public :: max_links, max_joints, coordinate_unset
  public :: joint_pin, joint_ground_pin, joint_clamp, joint_slider_fixed, joint_slider_link, joint_free
  public :: profile_constant, profile_spinup, branch_open
  public :: mechanism_input_t, input_issue_t, mechanism_t, link_t, joint_t, driver_t
  public :: build_mechanism, driver_angle, joint_type_name

  integer, parameter :: max_links = 40              !< size of the &mechanism link arrays
  integer, parameter :: max_joints = 60             !< size of the &mechanism joint arrays
  integer, parameter :: max_elements_per_link = 200
  !> "Not given" marker for joint coordinates (a real coordinate is never this).
  real(dp), parameter :: coordinate_unset = -1.0e30_dp

  integer, parameter :: joint_pin = 1           !< pin between two or more links
  integer, parameter :: joint_ground_pin = 2    !< pin between links and the ground
  integer, parameter :: joint_clamp = 3         !< crank end clamped to the driving shaft
  integer, parameter :: joint_slider_fixed = 4  !< link end(s) on a block sliding on a fixed straight guide
  integer, parameter :: joint_slider_link = 5   !< pivoting sleeve through which a link slides
  integer, parameter :: joint_free = 0          !< free end of a single link (rotating cantilever)
  ! (the codes 0-4 are those of module correlation_table)
  character(len=12), parameter :: joint_type_names(0:5) = [character(len=12) :: &
    'free', 'pin', 'ground_pin', 'clamp', 'slider_fixed', 'slider_link']

  integer, parameter :: profile_constant = 1, profile_spinup = 2
  integer, parameter :: branch_open = 1, branch_crossed = -1

  !> The flat contents of &mechanism, with the documented defaults.
  type :: mechanism_input_t
    integer :: n_joints = 0
    character(len=16) :: joint_name(max_joints) = ''
    character(len=16) :: joint_type(max_joints) = ''
    real(dp) :: joint_x(max_joints) = coordinate_unset
    real(dp) :: joint_y(max_joints) = coordinate_unset
    real(dp) :: joint_guide_deg(max_joints) = 0.0_dp
    integer :: joint_sliding_link(max_joints) = 0
    character(len=8) :: joint_branch(max_joints) = ''
    real(dp) :: joint_mass(max_joints) = 0.0_dp
    integer :: n_links = 0
    character(len=16) :: link_name(max_links) = ''
    integer :: link_joint1(max_links) = 0
    integer :: link_joint2(max_links) = 0
    real(dp) :: link_length(max_links) = 0.0_dp
    real(dp) :: link_b(max_links) = 0.25_dp
    real(dp) :: link_h(max_links) = 1.0_dp
    real(dp) :: link_area(max_links) = 0.0_dp
    real(dp) :: link_inertia(max_links) = 0.0_dp
    character(len=12) :: link_section(max_links) = 'rectangle'
    real(dp) :: link_c(max_links) = 0.0_dp
    real(dp) :: link_wall(max_links) = 0.0_dp
    real(dp) :: link_e1(max_links) = tennant_aluminium_e1
    real(dp) :: link_e2(max_links) = tennant_aluminium_e2
    real(dp) :: link_m(max_links) = tennant_aluminium_m
    real(dp) :: link_rho(max_links) = tennant_aluminium_rho
    integer :: link_n_elements(max_links) = 1
    ! counterweight: a rigid point mass on an arm clamped to the link at its
    ! end 1 (a ground pivot), at (cw_x, cw_y) in the link's frame
    real(dp) :: link_cw_mass(max_links) = 0.0_dp
    real(dp) :: link_cw_x(max_links) = 0.0_dp
    real(dp) :: link_cw_y(max_links) = 0.0_dp
    integer :: driver_link = 1
    real(dp) :: omega = 0.0_dp
    real(dp) :: theta0_deg = 0.0_dp
    character(len=16) :: profile = 'constant'
    real(dp) :: spinup_time = 0.0_dp
    character(len=8) :: branch = 'open'
    real(dp) :: toggle_rcond = 1.0e-7_dp
    real(dp) :: link_strength(max_links) = 0.0_dp   !< allowable stress (0 = not given: no check)
  end type mechanism_input_t

  !> An invalid input value, in parts (variable, value as text, rule broken).
  type :: input_issue_t
    character(len=:), allocatable :: variable, value, rule
  end type input_issue_t

  !> A link: a straight beam from the joint at its end 1 to the joint at its
  !> end 2.  Its reference line runs from end 1 to end 2; its elements split
  !> the (active) length evenly.
  type :: link_t
    character(len=16) :: name = ''
    integer :: joint(2) = 0
    real(dp) :: length = 0.0_dp       !< fixed length; for a sliding link its physical length (0 = not given)
    logical :: sliding = .false.      !< slides through a sleeve: its active length varies
    integer :: sleeve_end = 0         !< end (1 or 2) at the sleeve, if sliding
    !> b, h: the rectangle; for another shape the rectangle with its A and I
    !> (h = sqrt(12 I/A), b = A/h), which is all a linear-elastic beam needs.
    real(dp) :: b = 0.0_dp, h = 0.0_dp, area = 0.0_dp, inertia = 0.0_dp
    character(len=12) :: section = 'rectangle'
    real(dp) :: fibre = 0.0_dp        !< outer-fibre distance c from the neutral axis (stresses)
    real(dp) :: e1 = 0.0_dp, e2 = 0.0_dp, m = 0.0_dp, rho = 0.0_dp
    integer :: n_elements = 0
    integer :: first_element = 0      !< global number of its first element
    real(dp) :: cw_mass = 0.0_dp      !< counterweight mass (0: none)
    real(dp) :: cw_x = 0.0_dp, cw_y = 0.0_dp   !< its position from end 1, along and across the link
    real(dp) :: strength = 0.0_dp     !< allowable stress of its material (0: not given)
  end type link_t

  !> A joint: a point of the mechanism where link ends meet.
  type :: joint_t
    character(len=16) :: name = ''
    integer :: kind = -1
    logical :: grounded = .false.     !< its position is a fixed ground point
    logical :: has_position = .false. !< x, y were given (ground point, or reference position)
    real(dp) :: x = 0.0_dp, y = 0.0_dp
    real(dp) :: guide(2) = [1.0_dp, 0.0_dp]   !< slider_fixed: unit direction of the guide
    integer :: sliding_link = 0       !< slider_link: the link sliding through the sleeve
    integer :: branch = 0             !< +1 open, -1 crossed, 0 = the mechanism's branch
    real(dp) :: mass = 0.0_dp         !< lumped mass at the joint (slider block, sleeve)
    integer :: n_links = 0
    integer, allocatable :: link(:)      !< links meeting here ...
    integer, allocatable :: link_end(:)  !< ... and which of their ends (1 or 2)
  end type joint_t

  !> The crank: the angle of the driver link (end 1 to end 2) from global X is
  !> theta(t) = theta0 + (profile).
  type :: driver_t
    integer :: link = 0
    real(dp) :: omega = 0.0_dp        !< rad/s, positive counter-clockwise
    real(dp) :: theta0 = 0.0_dp       !< rad
    integer :: profile = profile_constant
    real(dp) :: spinup_time = 0.0_dp  !< s (spinup profile)
  end type driver_t

  type :: mechanism_t
    integer :: n_joints = 0, n_links = 0, n_elements = 0
    type(joint_t), allocatable :: joints(:)
    type(link_t), allocatable :: links(:)
    type(driver_t) :: driver
    integer :: branch = branch_open
    real(dp) :: toggle_rcond = 1.0e-7_dp
    real(dp) :: length_scale = 1.0_dp  !< mean link length, scales tolerances
    type(mechanism_input_t) :: input   !< as given, for the echo and for redesign
  end type mechanism_t

contains

  pure function joint_type_name(kind) result(name)
    integer, intent(in) :: kind
    character(len=:), allocatable :: name
    if (kind >= lbound(joint_type_names, 1) .and. kind <= ubound(joint_type_names, 1)) then
      name = trim(joint_type_names(kind))
    else
      name = 'unknown'
    end if
  end function joint_type_name

  pure function idx(name, i) result(s)
    character(len=*), intent(in) :: name
    integer, intent(in) :: i
    character(len=:), allocatable :: s
    s = name//'('//str(i)//')'
  end function idx

  pure function quoted(s) result(q)
    character(len=*), intent(in) :: s
    character(len=:), allocatable :: q
    q = "'"//trim(s)//"'"
  end function quoted

  logical pure function is_set(x)
    real(dp), intent(in) :: x
    is_set = x > 0.5_dp*coordinate_unset
  end function is_set

  logical pure function finite(x)
    real(dp), intent(in) :: x
    finite = ieee_is_finite(x)
  end function finite

  !> Validate the flat input and build the indexed mechanism.  Any failure is
  !> an input error (err%code = 2) naming the variable and its value; the
  !> checks run in the order of the phases below and stop at the first failure.
  subroutine build_mechanism(inp, mech, err, issue)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(out) :: mech
    type(error_t), intent(inout) :: err
    type(input_issue_t), intent(out), optional :: issue   !< the failure's parts, for the deck reader
    type(input_issue_t) :: found
    integer :: i, k
    mech%input = inp
    call check_counts(inp, found)
    if (.not. failed(found)) then
      mech%n_joints = inp%n_joints
      mech%n_links = inp%n_links
      allocate(mech%joints(inp%n_joints), mech%links(inp%n_links))
      call check_all_finite(inp, found)
    end if
    if (.not. failed(found)) call check_ranges(inp, found)
    if (.not. failed(found)) call build_joints(inp, mech, found)
    if (.not. failed(found)) call build_links(inp, mech, found)
    if (.not. failed(found)) then
      call link_incidence(inp, mech)
      call build_driver(inp, mech, found)
    end if
    if (.not. failed(found)) call apply_joint_rules(inp, mech, found)
    if (.not. failed(found)) call set_lengths(inp, mech, found)
    if (.not. failed(found)) call check_driver_pivot(inp, mech, found)
    if (.not. failed(found)) call check_mobility(mech, found)
    if (failed(found)) then
      call err%set('&mechanism', found%variable//' = '//found%value//': '//found%rule, code=2)
      if (present(issue)) issue = found
      return
    end if
    ! global element numbering, link by link
    k = 0
    do i = 1, mech%n_links
      mech%links(i)%first_element = k + 1
      k = k + mech%links(i)%n_elements
    end do
    mech%n_elements = k
  end subroutine build_mechanism

  !> Record an input error naming the variable, its value and the rule.
  pure subroutine bad(found, variable, value, rule)
    type(input_issue_t), intent(inout) :: found
    character(len=*), intent(in) :: variable, value, rule
    found%variable = trim(variable)
    found%value = trim(value)
    found%rule = trim(rule)
  end subroutine bad

  !> The name of the next joint or link after `earlier`: the deck's, or
  !> prefix and number when blank; an issue if an earlier one has it.
  pure subroutine take_name(given, prefix, earlier, what, name, found)
    character(len=*), intent(in) :: given, prefix, earlier(:), what
    character(len=*), intent(out) :: name
    type(input_issue_t), intent(inout) :: found
    integer :: i, k
    i = size(earlier) + 1
    name = adjustl(given)
    if (len_trim(name) == 0) name = prefix//str(i)
    k = findloc(earlier, name, dim=1)
    if (k > 0) call bad(found, idx(what//'_name', i), quoted(name), 'is already the name of '//what//' '//str(k))
  end subroutine take_name

  !> Record an issue unless x > 0 (a NaN included), if none is recorded yet.
  pure subroutine need_positive(found, name, i, x, rule)
    type(input_issue_t), intent(inout) :: found
    character(len=*), intent(in) :: name, rule
    integer, intent(in) :: i
    real(dp), intent(in) :: x
    if (failed(found)) return
    if (.not. (x > 0.0_dp)) call bad(found, idx(name, i), str(x), rule)
  end subroutine need_positive

  logical pure function failed(found)
    type(input_issue_t), intent(in) :: found
    failed = allocated(found%variable)
  end function failed

  pure subroutine check_counts(inp, found)
    type(mechanism_input_t), intent(in) :: inp
    type(input_issue_t), intent(inout) :: found
    if (inp%n_joints < 2 .or. inp%n_joints > max_joints) then
      call bad(found, 'n_joints', str(inp%n_joints), 'must be between 2 and '//str(max_joints)); return
    end if
    if (inp%n_links < 1 .or. inp%n_links > max_links) then
      call bad(found, 'n_links', str(inp%n_links), 'must be between 1 and '//str(max_links)); return
    end if
  end subroutine check_counts

  !> Every real input of the joints and links in use, and the driver's,
  !> is finite (before any comparison: NaN comparisons trap in debug builds).
  subroutine check_all_finite(inp, found)
    type(mechanism_input_t), intent(in) :: inp
    type(input_issue_t), intent(inout) :: found
    integer :: q
    do q = 1, inp%n_joints
      if (.not. finite_at(found, 'joint_x', q, inp%joint_x(q))) return
      if (.not. finite_at(found, 'joint_y', q, inp%joint_y(q))) return
      if (.not. finite_at(found, 'joint_guide_deg', q, inp%joint_guide_deg(q))) return
      if (.not. finite_at(found, 'joint_mass', q, inp%joint_mass(q))) return
    end do
    do q = 1, inp%n_links
      if (.not. finite_at(found, 'link_length', q, inp%link_length(q))) return
      if (.not. finite_at(found, 'link_b', q, inp%link_b(q))) return
      if (.not. finite_at(found, 'link_h', q, inp%link_h(q))) return
      if (.not. finite_at(found, 'link_area', q, inp%link_area(q))) return
      if (.not. finite_at(found, 'link_inertia', q, inp%link_inertia(q))) return
      if (.not. finite_at(found, 'link_c', q, inp%link_c(q))) return
      if (.not. finite_at(found, 'link_wall', q, inp%link_wall(q))) return
      if (.not. finite_at(found, 'link_e1', q, inp%link_e1(q))) return
      if (.not. finite_at(found, 'link_e2', q, inp%link_e2(q))) return
      if (.not. finite_at(found, 'link_m', q, inp%link_m(q))) return
      if (.not. finite_at(found, 'link_rho', q, inp%link_rho(q))) return
      if (.not. finite_at(found, 'link_cw_mass', q, inp%link_cw_mass(q))) return
      if (.not. finite_at(found, 'link_cw_x', q, inp%link_cw_x(q))) return
      if (.not. finite_at(found, 'link_cw_y', q, inp%link_cw_y(q))) return
      if (.not. finite_at(found, 'link_strength', q, inp%link_strength(q))) return
      if (inp%link_strength(q) < 0.0_dp) then
        call bad(found, idx('link_strength', q), str(inp%link_strength(q)), 'must be >= 0 (an allowable '// &
                 'stress; 0 = not given)'); return
      end if
    end do
    if (.not. finite_at(found, 'omega', 0, inp%omega)) return
    if (.not. finite_at(found, 'theta0_deg', 0, inp%theta0_deg)) return
    if (.not. finite_at(found, 'spinup_time', 0, inp%spinup_time)) return
    if (.not. finite_at(found, 'toggle_rcond', 0, inp%toggle_rcond)) return
  end subroutine check_all_finite

  logical function finite_at(found, name, q, x) result(ok)
    type(input_issue_t), intent(inout) :: found
    character(len=*), intent(in) :: name
    integer, intent(in) :: q
    real(dp), intent(in) :: x
    ok = finite(x)
    if (ok) return
    if (q > 0) then
      call bad(found, idx(name, q), str(x), 'must be a finite number')
    else
      call bad(found, name, str(x), 'must be a finite number')
    end if
  end function finite_at

  !> Physical ranges of the driver and of sizes (doc/mechanism_deck.md):
  !> a crank angle beyond ten turns or a speed beyond 1e5 rad/s is a typing
  !> error, and a speed below 1e-6 rad/s (one turn in 70 days) cannot be
  !> tabulated per revolution.
  subroutine check_ranges(inp, found)
    type(mechanism_input_t), intent(in) :: inp
    type(input_issue_t), intent(inout) :: found
    integer :: q
    if (abs(inp%omega) > 1.0e5_dp .or. (abs(inp%omega) > 0.0_dp .and. abs(inp%omega) < 1.0e-6_dp)) then
      call bad(found, 'omega', str(inp%omega), 'must be 0 or have a magnitude in [1e-6, 1e5] rad/s'); return
    end if
    if (abs(inp%theta0_deg) > 3600.0_dp) then
      call bad(found, 'theta0_deg', str(inp%theta0_deg), 'must lie in [-3600, 3600] degrees'); return
    end if
    if (abs(inp%spinup_time) > 1.0e6_dp) then
      call bad(found, 'spinup_time', str(inp%spinup_time), 'must be at most 1e6 s'); return
    end if
    do q = 1, inp%n_joints
      if (abs(inp%joint_guide_deg(q)) > 3600.0_dp) then
        call bad(found, idx('joint_guide_deg', q), str(inp%joint_guide_deg(q)), 'must lie in [-3600, 3600] degrees'); return
      end if
      if (is_set(inp%joint_x(q)) .and. (abs(inp%joint_x(q)) > 1.0e8_dp .or. abs(inp%joint_y(q)) > 1.0e8_dp)) then
        call bad(found, idx('joint_x', q), str(inp%joint_x(q))//', '//str(inp%joint_y(q)), &
                 'coordinates must lie in [-1e8, 1e8]'); return
      end if
    end do
    do q = 1, inp%n_links
      if (inp%link_length(q) > 1.0e8_dp .or. (inp%link_length(q) > 0.0_dp .and. inp%link_length(q) < 1.0e-8_dp)) then
        call bad(found, idx('link_length', q), str(inp%link_length(q)), 'must be 0 (from the joints) or in [1e-8, 1e8]'); return
      end if
      if (inp%link_b(q) > 1.0e8_dp .or. inp%link_h(q) > 1.0e8_dp .or. &
          (inp%link_b(q) > 0.0_dp .and. inp%link_b(q) < 1.0e-8_dp) .or. &
          (inp%link_h(q) > 0.0_dp .and. inp%link_h(q) < 1.0e-8_dp)) then
        call bad(found, idx('link_h', q)//', '//idx('link_b', q), str(inp%link_h(q))//', '//str(inp%link_b(q)), &
                 'section sizes must lie in [1e-8, 1e8]'); return
      end if
      if (inp%link_rho(q) > 1.0e10_dp .or. inp%link_e1(q) > 1.0e20_dp .or. inp%link_e2(q) > 1.0e30_dp) then
        call bad(found, idx('link_e1', q), str(inp%link_e1(q)), 'material constants beyond any material '// &
                 '(rho <= 1e10, E1 <= 1e20, E2 <= 1e30)'); return
      end if
      ! E1/rho is the square of the bar wave speed: 1e2..1e18 holds every
      ! solid in any consistent units (m/s: 1e4..4e8, mm/s: 1e10..4e14);
      ! outside it the model's frequencies over- or underflow (written as
      ! products: E1/rho itself overflows for a subnormal rho)
      ! (nested: .and. does not short-circuit, and 1e18*rho overflows for rho = -1e300)
      if (inp%link_rho(q) > 0.0_dp .and. inp%link_e1(q) > 0.0_dp) then
        if (inp%link_e1(q) > 1.0e18_dp*inp%link_rho(q) .or. inp%link_e1(q) < 1.0e2_dp*inp%link_rho(q)) then
          call bad(found, idx('link_e1', q)//', '//idx('link_rho', q), str(inp%link_e1(q))//', '// &
                   str(inp%link_rho(q)), 'E1/rho (the squared bar wave speed) must lie in [1e2, 1e18]'); return
        end if
      end if
    end do
  end subroutine check_ranges

  !> Joints: kind, name, ground coordinates, options.
  subroutine build_joints(inp, mech, found)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(inout) :: mech
    type(input_issue_t), intent(inout) :: found
    integer :: j, k
    character(len=16) :: word
    do j = 1, mech%n_joints
      associate (jt => mech%joints(j))
        word = lower(adjustl(inp%joint_type(j)))
        jt%kind = findloc(joint_type_names, word, dim=1) - 1 + lbound(joint_type_names, 1)
        if (jt%kind < lbound(joint_type_names, 1)) then
          call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), &
                   'must be one of pin, ground_pin, clamp, slider_fixed, slider_link, free'); return
        end if
        call take_name(inp%joint_name(j), 'J', [(mech%joints(k)%name, k = 1, j - 1)], 'joint', jt%name, found)
        if (failed(found)) return
        if (is_set(inp%joint_x(j)) .neqv. is_set(inp%joint_y(j))) then
          call bad(found, idx('joint_x', j)//', '//idx('joint_y', j), 'only one given', &
                   'give both coordinates of joint '//trim(jt%name)//' or neither'); return
        end if
        jt%has_position = is_set(inp%joint_x(j))
        if (jt%has_position) then
          if (.not. (finite(inp%joint_x(j)) .and. finite(inp%joint_y(j)))) then
            call bad(found, idx('joint_x', j), str(inp%joint_x(j)), 'coordinates must be finite'); return
          end if
          jt%x = inp%joint_x(j)
          jt%y = inp%joint_y(j)
        end if
        if (.not. finite(inp%joint_guide_deg(j))) then
          call bad(found, idx('joint_guide_deg', j), str(inp%joint_guide_deg(j)), 'must be finite'); return
        end if
        jt%guide = [cos(inp%joint_guide_deg(j)*pi/180.0_dp), sin(inp%joint_guide_deg(j)*pi/180.0_dp)]
        select case (lower(adjustl(inp%joint_branch(j))))
        case ('')
          jt%branch = 0
        case ('open')
          jt%branch = branch_open
        case ('crossed')
          jt%branch = branch_crossed
        case default
          call bad(found, idx('joint_branch', j), quoted(inp%joint_branch(j)), &
                   "must be 'open', 'crossed' or empty (use branch)"); return
        end select
        ! 1e10 bounds it like link_rho: m c^2 of a larger one overflows (fuzz seed 11, case 24093)
        if (.not. (inp%joint_mass(j) >= 0.0_dp .and. inp%joint_mass(j) <= 1.0e10_dp)) then
          call bad(found, idx('joint_mass', j), str(inp%joint_mass(j)), 'must lie in [0, 1e10]'); return
        end if
        jt%mass = inp%joint_mass(j)
        if (inp%joint_sliding_link(j) /= 0 .and. jt%kind /= joint_slider_link) then
          call bad(found, idx('joint_sliding_link', j), str(inp%joint_sliding_link(j)), &
                   'only a slider_link joint has a sliding link (joint '//trim(jt%name)//' is '// &
                   joint_type_name(jt%kind)//')'); return
        end if
        jt%sliding_link = inp%joint_sliding_link(j)
      end associate
    end do
  end subroutine build_joints

  !> Links: topology, section, material, mesh.
  subroutine build_links(inp, mech, found)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(inout) :: mech
    type(input_issue_t), intent(inout) :: found
    integer :: i, k
    do i = 1, mech%n_links
      associate (lk => mech%links(i))
        call take_name(inp%link_name(i), 'link', [(mech%links(k)%name, k = 1, i - 1)], 'link', lk%name, found)
        if (failed(found)) return
        if (inp%link_joint1(i) < 1 .or. inp%link_joint1(i) > mech%n_joints) then
          call bad(found, idx('link_joint1', i), str(inp%link_joint1(i)), &
                   'must be a joint number 1..'//str(mech%n_joints)); return
        end if
        if (inp%link_joint2(i) < 1 .or. inp%link_joint2(i) > mech%n_joints) then
          call bad(found, idx('link_joint2', i), str(inp%link_joint2(i)), &
                   'must be a joint number 1..'//str(mech%n_joints)); return
        end if
        if (inp%link_joint1(i) == inp%link_joint2(i)) then
          call bad(found, idx('link_joint2', i), str(inp%link_joint2(i)), 'a link must join two different joints'); return
        end if
        lk%joint = [inp%link_joint1(i), inp%link_joint2(i)]
        call set_section(inp, i, lk, found)
        if (failed(found)) return
        if (.not. (inp%link_e1(i) > 0.0_dp .and. finite(inp%link_e1(i)))) then
          call bad(found, idx('link_e1', i), str(inp%link_e1(i)), 'the modulus A must be > 0'); return
        end if
        if (.not. (inp%link_e2(i) >= 0.0_dp .and. finite(inp%link_e2(i)))) then
          call bad(found, idx('link_e2', i), str(inp%link_e2(i)), 'the nonlinear coefficient B must be >= 0'); return
        end if
        if (.not. (inp%link_m(i) > 1.0_dp .and. inp%link_m(i) <= 20.0_dp)) then
          call bad(found, idx('link_m', i), str(inp%link_m(i)), 'the exponent m must be in (1, 20]'); return
        end if
        if (.not. (inp%link_rho(i) > 0.0_dp .and. finite(inp%link_rho(i)))) then
          call bad(found, idx('link_rho', i), str(inp%link_rho(i)), 'the mass density must be > 0'); return
        end if
        lk%e1 = inp%link_e1(i)
        lk%e2 = inp%link_e2(i)
        lk%m = inp%link_m(i)
        lk%rho = inp%link_rho(i)
        if (inp%link_n_elements(i) < 1 .or. inp%link_n_elements(i) > max_elements_per_link) then
          call bad(found, idx('link_n_elements', i), str(inp%link_n_elements(i)), &
                   'must be between 1 and '//str(max_elements_per_link)); return
        end if
        lk%n_elements = inp%link_n_elements(i)
        if (.not. inp%link_cw_mass(i) >= 0.0_dp) then
          call bad(found, idx('link_cw_mass', i), str(inp%link_cw_mass(i)), 'a counterweight mass must be >= 0'); return
        end if
        if (inp%link_cw_mass(i) > 0.0_dp .and. all(mech%joints(lk%joint(1))%kind /= [joint_clamp, joint_ground_pin])) &
          then
          call bad(found, idx('link_cw_mass', i), str(inp%link_cw_mass(i)), 'a counterweight sits at end 1 of its link, '// &
                   'which must be a ground pivot (clamp or ground_pin): joint '//trim(mech%joints(lk%joint(1))%name)// &
                   ' is '//joint_type_name(mech%joints(lk%joint(1))%kind)); return
        end if
        lk%cw_mass = inp%link_cw_mass(i)
        lk%cw_x = inp%link_cw_x(i)
        lk%cw_y = inp%link_cw_y(i)
        lk%strength = inp%link_strength(i)
        if (.not. (inp%link_length(i) >= 0.0_dp .and. finite(inp%link_length(i)))) then
          call bad(found, idx('link_length', i), str(inp%link_length(i)), 'must be > 0 (or 0 to take it from joint coordinates)')
          return
        end if
      end associate
    end do
  end subroutine build_links

  !> The section of link q: A, I, the outer-fibre distance c and the
  !> equivalent rectangle b x h (the same A and I).
  subroutine set_section(inp, q, lk, found)
    type(mechanism_input_t), intent(in) :: inp
    integer, intent(in) :: q
    type(link_t), intent(inout) :: lk
    type(input_issue_t), intent(inout) :: found
    real(dp) :: d, di
    lk%section = lower(adjustl(inp%link_section(q)))
    select case (lk%section)
    case ('rectangle')
      if (inp%link_area(q) > 0.0_dp .or. inp%link_inertia(q) > 0.0_dp .or. inp%link_c(q) > 0.0_dp) then
        call bad(found, idx('link_area', q)//', '//idx('link_inertia', q)//', '//idx('link_c', q), 'given', &
                 'a rectangle is given by link_b and link_h; for a section given by A, I and c set '// &
                 idx('link_section', q)//' = ''general'''); return
      end if
      call need_positive(found, 'link_b', q, inp%link_b(q), 'the section width must be > 0')
      call need_positive(found, 'link_h', q, inp%link_h(q), 'the section height must be > 0')
      if (failed(found)) return
      lk%b = inp%link_b(q)
      lk%h = inp%link_h(q)
      lk%area = lk%b*lk%h
      lk%inertia = lk%b*lk%h**3/12.0_dp
      lk%fibre = 0.5_dp*lk%h
      return
    case ('circle', 'tube')
      d = inp%link_h(q)
      call need_positive(found, 'link_h', q, d, 'the outer diameter of a '//trim(lk%section)//' must be > 0')
      if (failed(found)) return
      di = 0.0_dp
      if (lk%section == 'tube') then
        if (.not. (inp%link_wall(q) > 0.0_dp .and. inp%link_wall(q) < 0.5_dp*d)) then
          call bad(found, idx('link_wall', q), str(inp%link_wall(q)), 'the wall of a tube must be > 0 and < half '// &
                   'its outer diameter link_h'); return
        end if
        di = d - 2.0_dp*inp%link_wall(q)
      end if
      lk%area = 0.25_dp*pi*(d**2 - di**2)
      lk%inertia = pi*(d**4 - di**4)/64.0_dp
      lk%fibre = 0.5_dp*d
    case ('general')
      call need_positive(found, 'link_area', q, inp%link_area(q), 'a general section needs its area A > 0')
      call need_positive(found, 'link_inertia', q, inp%link_inertia(q), 'a general section needs I > 0')
      call need_positive(found, 'link_c', q, inp%link_c(q), 'a general section needs its outer-fibre distance '// &
                         'c > 0 (for stresses)')
      if (failed(found)) return
      ! the size ranges of b and h, squared and to the fourth power, and
      ! I <= c^2 A (no section has its radius of gyration beyond its
      ! outer fibre); without them 12 I/A overflowed for I = 1.8e308
      if (inp%link_area(q) < 1.0e-16_dp .or. inp%link_area(q) > 1.0e16_dp) then
        call bad(found, idx('link_area', q), str(inp%link_area(q)), 'must lie in [1e-16, 1e16]'); return
      end if
      if (inp%link_c(q) < 1.0e-8_dp .or. inp%link_c(q) > 1.0e8_dp) then
        call bad(found, idx('link_c', q), str(inp%link_c(q)), 'must lie in [1e-8, 1e8]'); return
      end if
      if (inp%link_inertia(q) > inp%link_c(q)**2*inp%link_area(q) .or. inp%link_inertia(q) < 1.0e-32_dp) then
        call bad(found, idx('link_inertia', q), str(inp%link_inertia(q)), 'must lie in [1e-32, c^2 A = '// &
                 str(inp%link_c(q)**2*inp%link_area(q))//']: no section has its radius of gyration beyond its '// &
                 'outer fibre c'); return
      end if
      lk%area = inp%link_area(q)
      lk%inertia = inp%link_inertia(q)
      lk%fibre = inp%link_c(q)
    case default
      call bad(found, idx('link_section', q), quoted(inp%link_section(q)), &
               "must be 'rectangle', 'circle', 'tube' or 'general'"); return
    end select
    lk%h = sqrt(12.0_dp*lk%inertia/lk%area)
    lk%b = lk%area/lk%h
  end subroutine set_section

  !> Incidence: which link ends meet at each joint.
  pure subroutine link_incidence(inp, mech)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(inout) :: mech
    integer :: i, j, e
    do j = 1, mech%n_joints
      mech%joints(j)%n_links = count(inp%link_joint1(1:mech%n_links) == j) + count(inp%link_joint2(1:mech%n_links) == j)
      allocate(mech%joints(j)%link(mech%joints(j)%n_links), mech%joints(j)%link_end(mech%joints(j)%n_links))
      mech%joints(j)%n_links = 0
    end do
    do i = 1, mech%n_links
      do e = 1, 2
        j = mech%links(i)%joint(e)
        associate (jt => mech%joints(j))
          jt%n_links = jt%n_links + 1
          jt%link(jt%n_links) = i
          jt%link_end(jt%n_links) = e
        end associate
      end do
    end do
  end subroutine link_incidence

  !> The driver (crank), its profile, the assembly branch.
  subroutine build_driver(inp, mech, found)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(inout) :: mech
    type(input_issue_t), intent(inout) :: found
    if (inp%driver_link < 0 .or. inp%driver_link > mech%n_links) then
      call bad(found, 'driver_link', str(inp%driver_link), 'must be a link number 1..'//str(mech%n_links)// &
               ', or 0 for a structure without a driver'); return
    end if
    mech%driver%link = inp%driver_link
    if (.not. finite(inp%omega)) then
      call bad(found, 'omega', str(inp%omega), 'must be finite'); return
    end if
    ! driver_link = 0: a structure at rest (beams with immovable ends)
    if (inp%driver_link == 0 .and. abs(inp%omega) > 0.0_dp) then
      call bad(found, 'omega', str(inp%omega), 'a structure without a driver (driver_link = 0) does not move: '// &
               'omega must be 0'); return
    end if
    if (.not. finite(inp%theta0_deg)) then
      call bad(found, 'theta0_deg', str(inp%theta0_deg), 'must be finite'); return
    end if
    mech%driver%omega = inp%omega
    mech%driver%theta0 = inp%theta0_deg*pi/180.0_dp
    select case (lower(adjustl(inp%profile)))
    case ('constant')
      mech%driver%profile = profile_constant
    case ('spinup')
      mech%driver%profile = profile_spinup
      if (.not. (inp%spinup_time > 0.0_dp .and. finite(inp%spinup_time))) then
        call bad(found, 'spinup_time', str(inp%spinup_time), "must be > 0 with profile = 'spinup'"); return
      end if
    case default
      call bad(found, 'profile', quoted(inp%profile), "must be 'constant' or 'spinup'"); return
    end select
    mech%driver%spinup_time = inp%spinup_time

    select case (lower(adjustl(inp%branch)))
    case ('open')
      mech%branch = branch_open
    case ('crossed')
      mech%branch = branch_crossed
    case default
      call bad(found, 'branch', quoted(inp%branch), "must be 'open' or 'crossed'"); return
    end select
    if (.not. (inp%toggle_rcond > 0.0_dp .and. inp%toggle_rcond < 1.0_dp)) then
      call bad(found, 'toggle_rcond', str(inp%toggle_rcond), 'must be in (0, 1)'); return
    end if
    mech%toggle_rcond = inp%toggle_rcond
  end subroutine build_driver

  !> Rules per joint type (what each joins, which are on the ground).
  subroutine apply_joint_rules(inp, mech, found)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(inout) :: mech
    type(input_issue_t), intent(inout) :: found
    integer :: i, j, n_clamp, n_carriers
    n_clamp = 0
    do j = 1, mech%n_joints
      associate (jt => mech%joints(j))
        select case (jt%kind)
        case (joint_pin)
          if (jt%n_links < 2) then
            call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), 'pin '//trim(jt%name)//' joins '// &
                     str(jt%n_links)//' link end(s); a pin joins two or more (a lone link end is '//quoted('free')//')')
            return
          end if
        case (joint_free)
          if (jt%n_links /= 1) then
            call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), 'free end '//trim(jt%name)//' must belong to '// &
                     'exactly one link, not '//str(jt%n_links)); return
          end if
        case (joint_ground_pin, joint_slider_fixed)
          jt%grounded = jt%kind == joint_ground_pin
          if (jt%n_links < 1) then
            call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), 'joint '//trim(jt%name)//' joins no link'); return
          end if
        case (joint_clamp)
          jt%grounded = .true.
          n_clamp = n_clamp + 1
          if (inp%driver_link == 0) then
            ! without a driver a clamp is a built-in end (one or more link ends)
            if (jt%n_links < 1) then
              call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), 'joint '//trim(jt%name)//' joins no link')
              return
            end if
          else if (n_clamp > 1) then
            call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), 'only one clamp (the driving shaft) is allowed')
            return
          else if (jt%n_links /= 1 .or. inp%link_joint1(inp%driver_link) /= j) then
            call bad(found, idx('joint_type', j), quoted(inp%joint_type(j)), 'the clamp '//trim(jt%name)// &
                     ' must hold exactly one link end, end 1 of the driver link (link_joint1(driver_link))'); return
          end if
        case (joint_slider_link)
          i = jt%sliding_link
          if (i < 1 .or. i > mech%n_links) then
            call bad(found, idx('joint_sliding_link', j), str(i), 'slider_link '//trim(jt%name)// &
                     ' needs the number of the link sliding through it (1..'//str(mech%n_links)//')'); return
          end if
          if (all(mech%links(i)%joint /= j)) then
            call bad(found, idx('joint_sliding_link', j), str(i), 'link '//trim(mech%links(i)%name)// &
                     ' must have joint '//trim(jt%name)//' as link_joint1 or link_joint2'); return
          end if
          if (mech%links(i)%sliding) then
            call bad(found, idx('joint_sliding_link', j), str(i), 'link '//trim(mech%links(i)%name)// &
                     ' already slides through another sleeve'); return
          end if
          mech%links(i)%sliding = .true.
          mech%links(i)%sleeve_end = findloc(mech%links(i)%joint, j, dim=1)
          ! Without other links carrying it, the sleeve pivots on the ground.
          n_carriers = jt%n_links - 1
          jt%grounded = n_carriers == 0
        end select
        if ((jt%grounded .or. jt%kind == joint_slider_fixed) .and. .not. jt%has_position) then
          call bad(found, idx('joint_x', j)//', '//idx('joint_y', j), 'not given', &
                   'joint '//trim(jt%name)//' ('//joint_type_name(jt%kind)//') is on the ground: give its coordinates')
          return
        end if
      end associate
    end do
  end subroutine apply_joint_rules

  !> Lengths (a sliding link's length is its physical length, optional) and
  !> the length scale of the tolerances.
  subroutine set_lengths(inp, mech, found)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(inout) :: mech
    type(input_issue_t), intent(inout) :: found
    integer :: i, n_fixed
    real(dp) :: total, dx, dy
    total = 0.0_dp
    n_fixed = 0
    do i = 1, mech%n_links
      associate (lk => mech%links(i))
        lk%length = inp%link_length(i)
        if (.not. lk%sliding .and. .not. lk%length > 0.0_dp) then
          if (mech%joints(lk%joint(1))%has_position .and. mech%joints(lk%joint(2))%has_position) then
            dx = mech%joints(lk%joint(2))%x - mech%joints(lk%joint(1))%x
            dy = mech%joints(lk%joint(2))%y - mech%joints(lk%joint(1))%y
            lk%length = hypot(dx, dy)
          end if
          if (.not. lk%length > 0.0_dp) then
            call bad(found, idx('link_length', i), str(inp%link_length(i)), 'link '//trim(lk%name)// &
                     ' needs a length > 0, or the coordinates of both its joints'); return
          end if
          ! the range of a given link_length holds for one taken from the joints
          if (lk%length < 1.0e-8_dp .or. lk%length > 1.0e8_dp) then
            call bad(found, idx('joint_x', lk%joint(2))//', '//idx('joint_y', lk%joint(2)), &
                     str(mech%joints(lk%joint(2))%x)//', '//str(mech%joints(lk%joint(2))%y), 'link '// &
                     trim(lk%name)//' taken from its joints is '//str(lk%length)//' long: it must lie in [1e-8, 1e8]')
            return
          end if
        end if
        if (lk%length > 0.0_dp) then
          total = total + lk%length
          n_fixed = n_fixed + 1
        end if
      end associate
    end do
    if (n_fixed > 0) mech%length_scale = total/n_fixed
    call check_length_ratio(mech, found)
  end subroutine set_lengths

  !> A link shorter than 1e-3 of the longest one is refused: its elements'
  !> bending stiffness (EI/l^3) would exceed the longest link's by more than
  !> 1e9, leaving the Newton matrices under seven digits, and the highest
  !> frequency it adds makes every integrator crawl (fuzz seed 11, case 11423:
  !> a 5e-6 in crank against an 11 in coupler ran for minutes at t = 6e-16).
  subroutine check_length_ratio(mech, found)
    type(mechanism_t), intent(in) :: mech
    type(input_issue_t), intent(inout) :: found
    real(dp), parameter :: min_ratio = 1.0e-3_dp
    real(dp) :: longest
    integer :: i
    if (failed(found)) return
    longest = maxval(mech%links(1:mech%n_links)%length)
    do i = 1, mech%n_links
      associate (lk => mech%links(i))
        if (lk%sliding .or. .not. lk%length > 0.0_dp) cycle
        if (lk%length < min_ratio*longest) then
          call bad(found, idx('link_length', i), str(lk%length), 'link '//trim(lk%name)//' is shorter than 1e-3 of '// &
                   'the longest link ('//str(longest)//'): the stiffness ratio of their elements would exceed 1e9'); return
        end if
      end associate
    end do
  end subroutine check_length_ratio

  !> The driver turns about a ground point.
  subroutine check_driver_pivot(inp, mech, found)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t), intent(in) :: mech
    type(input_issue_t), intent(inout) :: found
    integer :: k
    if (mech%driver%link > 0) then
      associate (dl => mech%links(mech%driver%link))
        if (dl%sliding) then
          call bad(found, 'driver_link', str(inp%driver_link), 'the driver '//trim(dl%name)// &
                   ' cannot be a link that slides through a sleeve'); return
        end if
        k = mech%joints(dl%joint(1))%kind
        if (k /= joint_clamp .and. k /= joint_ground_pin) then
          call bad(found, 'driver_link', str(inp%driver_link), 'end 1 of the driver '//trim(dl%name)//' (joint '// &
                   trim(mech%joints(dl%joint(1))%name)//') must be a clamp or ground_pin: the crank turns about it'); return
        end if
        if (mech%joints(dl%joint(2))%grounded) then
          call bad(found, 'driver_link', str(inp%driver_link), 'the driver '//trim(dl%name)// &
                   ' joins two ground points and cannot turn'); return
        end if
      end associate
    end if
  end subroutine check_driver_pivot

  !> Mobility: unknowns (2 per joint, 1 angle per link, 1 active length per
  !> sliding link, 1 slide per guided joint) minus equations (2 per link, 2 per
  !> ground point, 2 per guided joint) must leave the one the crank takes.
  subroutine check_mobility(mech, found)
    type(mechanism_t), intent(in) :: mech
    type(input_issue_t), intent(inout) :: found
    integer :: dof, n_unknowns, n_equations
    n_unknowns = 2*mech%n_joints + mech%n_links + count(mech%links%sliding) + count(mech%joints%kind == joint_slider_fixed)
    n_equations = 2*mech%n_links + 2*count(mech%joints%grounded) + 2*count(mech%joints%kind == joint_slider_fixed)
    dof = n_unknowns - n_equations
    if (mech%driver%link == 0) then
      ! A structure: no motion left (0), or statically indeterminate (< 0,
      ! e.g. a beam between two ground points); the lengths must then fit.
      if (dof > 0) then
        call bad(found, 'driver_link', '0', 'a structure without a driver must not move, but the linkage has '// &
                 str(dof)//' degree(s) of freedom (Gruebler count: '//str(n_unknowns)//' coordinates, '// &
                 str(n_equations)//' constraints)'); return
      end if
    else if (dof /= 1) then
      call bad(found, 'n_links, n_joints, joint_type', 'the linkage', 'has '//str(dof)//' degrees of freedom '// &
               '(Gruebler count: '//str(n_unknowns)//' coordinates, '//str(n_equations)// &
               ' constraints); flexmech needs exactly one, taken by the crank'); return
    end if
  end subroutine check_mobility

  !> Crank angle and its first two time derivatives at time t.
  !> 'constant':  theta = theta0 + omega t.
  !> 'spinup' (cycloidal, tau = t/T): theta_d = omega (tau - sin(2 pi tau)/(2 pi)) for 0 <= t <= T,
  !> so theta_dd = (omega/T)(1 - cos(2 pi tau)) vanishes at both ends and the
  !> jerk is continuous; at rest before t = 0, constant omega after T.
  pure subroutine driver_angle(drv, t, theta, theta_d, theta_dd)
    type(driver_t), intent(in) :: drv
    real(dp), intent(in) :: t
    real(dp), intent(out) :: theta, theta_d, theta_dd
    real(dp) :: tau, period
    select case (drv%profile)
    case (profile_spinup)
      period = drv%spinup_time
      if (t <= 0.0_dp) then
        theta = drv%theta0
        theta_d = 0.0_dp
        theta_dd = 0.0_dp
      else if (t < period) then
        tau = t/period
        theta = drv%theta0 + drv%omega*period*(0.5_dp*tau**2 - (1.0_dp - cos(2.0_dp*pi*tau))/(4.0_dp*pi**2))
        theta_d = drv%omega*(tau - sin(2.0_dp*pi*tau)/(2.0_dp*pi))
        theta_dd = drv%omega/period*(1.0_dp - cos(2.0_dp*pi*tau))
      else
        theta = drv%theta0 + drv%omega*(0.5_dp*period + (t - period))
        theta_d = drv%omega
        theta_dd = 0.0_dp
      end if
    case default
      theta = drv%theta0 + drv%omega*t
      theta_d = drv%omega
      theta_dd = 0.0_dp
    end select
  end subroutine driver_angle
end module linkage
