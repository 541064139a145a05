!> The linkage in words, for the output header: joints, links, driver and
!> branch, and what kind of four-bar or slider-crank it is (Grashof's rule).
module linkage_report
  use kinds, only: dp
  use strings, only: str, compact
  use linkage, only: mechanism_t, joint_type_name, joint_clamp, joint_ground_pin, joint_pin, joint_slider_fixed, &
    joint_slider_link, profile_spinup, branch_open
  implicit none
  private
  public :: mechanism_summary, classify_mechanism

contains

  !> Recognise four-bars and slider-cranks and say whether the crank can turn
  !> fully (Grashof's rule; crank radius plus offset against the rod length).
  !> Empty for other linkages.
  pure function classify_mechanism(mech) result(text)
    type(mechanism_t), intent(in) :: mech
    character(len=:), allocatable :: text
    integer :: j, g(2), ng, np, nsf, crank, i
    real(dp) :: bars(4), s, l, pq, r, rod, offset, sgn
    integer :: shortest
    character(len=:), allocatable :: who
    text = ''
    crank = mech%driver%link
    if (crank == 0) return
    ng = 0; np = 0; nsf = 0; i = 0; g = 0
    do j = 1, mech%n_joints
      select case (mech%joints(j)%kind)
      case (joint_clamp, joint_ground_pin)
        ng = ng + 1
        if (ng <= 2) g(ng) = j
      case (joint_pin)
        if (mech%joints(j)%n_links == 2) np = np + 1
      case (joint_slider_fixed)
        nsf = nsf + 1
        if (nsf == 1) i = j
      end select
    end do
    if (mech%n_links == 3 .and. mech%n_joints == 4 .and. ng == 2 .and. np == 2 .and. &
        .not. any(mech%links%sliding)) then
      bars(1:3) = mech%links%length
      bars(4) = hypot(mech%joints(g(2))%x - mech%joints(g(1))%x, mech%joints(g(2))%y - mech%joints(g(1))%y)
      s = minval(bars)
      l = maxval(bars)
      pq = sum(bars) - s - l
      shortest = minloc(bars, dim=1)
      if (s + l < pq) then
        if (shortest == crank) then
          who = 'crank-rocker: the crank turns fully'
        else if (shortest == 4) then
          who = 'double-crank (drag link): the crank turns fully'
        else if (any(mech%links(shortest)%joint == g(1)) .or. any(mech%links(shortest)%joint == g(2))) then
          who = 'rocker-crank: the output link turns fully, the crank cannot'
        else
          who = 'Grashof double-rocker: the crank cannot turn fully'
        end if
        text = 'four-bar, Grashof (s + l = '//compact(s + l)//' < p + q = '//compact(pq)//'), '//who
      else if (s + l > pq) then
        text = 'four-bar, non-Grashof triple-rocker (s + l = '//compact(s + l)//' > p + q = '//compact(pq)// &
               '): the crank cannot turn fully'
      else
        text = 'four-bar, change point (s + l = p + q = '//compact(pq)//'): toggle positions where the branches meet'
      end if
    else if (mech%n_links == 2 .and. mech%n_joints == 3 .and. ng == 1 .and. nsf == 1 .and. np == 1) then
      r = mech%links(crank)%length
      rod = mech%links(3 - crank)%length
      ! offset of the guide line from the crank pivot
      sgn = (mech%joints(g(1))%x - mech%joints(i)%x)*mech%joints(i)%guide(2) - &
            (mech%joints(g(1))%y - mech%joints(i)%y)*mech%joints(i)%guide(1)
      offset = abs(sgn)
      if (rod > r + offset) then
        text = 'slider-crank (crank '//compact(r)//', rod '//compact(rod)//', offset '//compact(offset)// &
               '): the crank turns fully'
      else
        text = 'slider-crank (crank '//compact(r)//', rod '//compact(rod)//', offset '//compact(offset)// &
               '): rod <= crank + offset, the crank cannot turn fully'
      end if
    end if
  end function classify_mechanism


  !> Lines for the output header: joints, links, driver, branch, classification.
  function mechanism_summary(mech) result(lines)
    type(mechanism_t), intent(in) :: mech
    character(len=200), allocatable :: lines(:)
    character(len=:), allocatable :: s, cls
    integer :: j, i, k, n
    n = 0
    allocate(lines(mech%n_joints + mech%n_links + 4))
    if (mech%driver%link == 0) then
      call add('structure: '//str(mech%n_joints)//' joints, '//str(mech%n_links)//' links, '// &
               str(mech%n_elements)//' elements, no driver: it does not move (rigid-body state at rest)')
    else
      call add('mechanism: '//str(mech%n_joints)//' joints, '//str(mech%n_links)//' links, '// &
               str(mech%n_elements)//' elements, one degree of freedom (the crank)')
    end if
    do j = 1, mech%n_joints
      associate (jt => mech%joints(j))
        s = 'joint '//trim(jt%name)//': '//joint_type_name(jt%kind)
        if (jt%grounded .or. jt%kind == joint_slider_fixed) s = s//' at ('//compact(jt%x)//', '//compact(jt%y)//')'
        if (jt%kind == joint_slider_fixed) s = s//', guide '//compact(mech%input%joint_guide_deg(j))//' deg'
        if (jt%kind == joint_slider_link) then
          s = s//', sleeve for '//trim(mech%links(jt%sliding_link)%name)
          if (jt%grounded) s = s//' pivoting on the ground'
        end if
        if (jt%mass > 0.0_dp) s = s//', mass '//compact(jt%mass)
        s = s//'; link ends:'
        do k = 1, jt%n_links
          s = s//' '//trim(mech%links(jt%link(k))%name)//'.'//str(jt%link_end(k))
        end do
        call add(s)
      end associate
    end do
    do i = 1, mech%n_links
      associate (lk => mech%links(i))
        s = 'link '//trim(lk%name)//': '//trim(mech%joints(lk%joint(1))%name)//'-'// &
            trim(mech%joints(lk%joint(2))%name)
        if (lk%sliding) then
          s = s//', slides (active length varies'
          if (lk%length > 0.0_dp) s = s//', physical length '//compact(lk%length)
          s = s//')'
        else
          s = s//', length '//compact(lk%length)
        end if
        s = s//', '//str(lk%n_elements)//' element(s); b '//compact(lk%b)//', h '//compact(lk%h)//', A '// &
            compact(lk%area)//', I '//compact(lk%inertia)//'; E1 '//compact(lk%e1)//', E2 '//compact(lk%e2)// &
            ', m '//compact(lk%m)//', rho '//compact(lk%rho)
        call add(s)
      end associate
    end do
    associate (d => mech%driver)
      if (d%link == 0) then
        s = 'driver: none (driver_link = 0)'
      else
        s = 'driver: link '//trim(mech%links(d%link)%name)//', omega '//compact(d%omega)//' rad/s, theta0 '// &
            compact(mech%input%theta0_deg)//' deg, profile '
        if (d%profile == profile_spinup) then
          s = s//'spinup over '//compact(d%spinup_time)//' s (cycloidal)'
        else
          s = s//'constant'
        end if
      end if
    end associate
    call add(s)
    if (mech%branch == branch_open) then
      call add('assembly branch: open')
    else
      call add('assembly branch: crossed')
    end if
    cls = classify_mechanism(mech)
    if (len(cls) > 0) call add(cls)
    lines = lines(1:n)
  contains
    subroutine add(text)
      character(len=*), intent(in) :: text
      n = n + 1
      lines(n) = text
    end subroutine add
  end function mechanism_summary

end module linkage_report
