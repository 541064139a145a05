!> The &sweep group: one deck variable varied over a list or a range of values.
!>
!>     &sweep group = 'mechanism', variable = 'omega', first = 50, last = 400, n_points = 36 /
!>     &sweep group = 'transient', variable = 'rtol', values = 1e-3, 1e-5, 1e-7, 1e-9 /
!>     &sweep group = 'mechanism', variable = 'link_n_elements(1:3)', values = 1, 2, 4, 8 /
!>
!> `variable` is a namelist designator of that group: a name, or an array
!> section name(a:b), which receives the value in every element.  The value
!> itself is checked by the analysis of each point (a point with a value out
!> of the variable's range ends with exit status 2 and is reported in the
!> summary; the other points run).
module sweep_settings
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t, invalid_value, group_read_t
  use deck_checks, only: check_real, check_reals, check_integer, check_choice
  use table_output, only: table_t
  implicit none
  private
  public :: sweep_settings_t, read_sweep_settings, echo_sweep_settings, max_sweep_values, sweep_groups

  integer, parameter :: max_sweep_values = 1000
  integer, parameter :: name_len = 64
  !> Groups whose variables a sweep may vary.
  character(len=20), parameter :: sweep_groups(15) = [character(len=20) :: 'mechanism', 'transient', &
    'effects', 'loads', 'clearance', 'steady', 'tennant', 'optimize', 'problem_data', 'design', 'lsode_check', &
    'spatial_mechanism', 'spatial_loads', 'general_mechanism', 'kinematics']

  real(dp), parameter :: unset = huge(1.0_dp)   !< values, first, last not given

  !> The group's values; the default initialisation is the documented
  !> defaults (doc/decks.md).  The points are `values` as given, or the
  !> range first..last of n_points; after the read `values` holds them.
  type :: sweep_settings_t
    character(len=name_len) :: group = ''
    character(len=name_len) :: variable = ''
    real(dp), allocatable :: values(:)          !< the points, in order
    real(dp) :: first = unset
    real(dp) :: last = unset
    integer :: n_points = 0
    character(len=16) :: spacing = 'linear'
    character(len=256) :: points_dir = ''
  end type sweep_settings_t

  ! staging variables of the namelist group
  character(len=name_len) :: group, variable
  real(dp) :: values(max_sweep_values), first, last
  integer :: n_points
  character(len=16) :: spacing
  character(len=256) :: points_dir
  namelist /sweep/ group, variable, values, first, last, n_points, spacing, points_dir

contains

  subroutine read_sweep_settings(deck, s, err)
    type(deck_t), intent(inout) :: deck
    type(sweep_settings_t), intent(out) :: s
    type(error_t), intent(inout) :: err
    logical :: found
    integer :: n
    call stage_from(s)        ! (intent(out): the defaults)
    call deck%read_group('sweep', sweep_group, .true., found, err)
    if (err%failed()) return
    s = sweep_settings_t(group=group, variable=variable, first=first, last=last, n_points=n_points, &
                         spacing=spacing, points_dir=points_dir)
    call check_choice(deck, 'sweep', 'group', group, sweep_groups, err)
    if (.not. err%failed() .and. .not. is_designator(trim(variable))) &
      call invalid_value(deck, 'sweep', 'variable', ''''//trim(variable)//'''', &
                         'must name a variable of the group: name or name(first:last)', err)
    call check_choice(deck, 'sweep', 'spacing', spacing, [character(len=16) :: 'linear', 'log'], err)
    if (err%failed()) return
    n = count_given(values)
    if (n > 0) then
      call check_reals(deck, 'sweep', 'values', values(1:n), err, why='the swept values')
      if (n_points /= 0 .and. .not. err%failed()) call invalid_value(deck, 'sweep', 'n_points', &
        '', 'give either values or first, last and n_points', err)
      if (err%failed()) return
      s%values = values(1:n)
    else
      call check_integer(deck, 'sweep', 'n_points', n_points, err, at_least=2, at_most=max_sweep_values, &
                         why='the number of points of the range first..last (or give values)')
      call check_real(deck, 'sweep', 'first', first, err, why='the first value of the range')
      call check_real(deck, 'sweep', 'last', last, err, why='the last value of the range')
      if (spacing == 'log') then
        call check_real(deck, 'sweep', 'first', first, err, above=0.0_dp, why='log spacing')
        call check_real(deck, 'sweep', 'last', last, err, above=0.0_dp, why='log spacing')
      end if
      if (err%failed()) return
      s%values = range_values(first, last, n_points, spacing == 'log')
    end if
  end subroutine read_sweep_settings

  !> Values given before the first unset entry.
  integer pure function count_given(v) result(n)
    real(dp), intent(in) :: v(:)
    do n = 0, size(v) - 1
      if (ieee_is_finite(v(n + 1))) then
        if (v(n + 1) >= unset) return
      end if
    end do
    n = size(v)
  end function count_given

  pure function range_values(a, b, n, logarithmic) result(v)
    real(dp), intent(in) :: a, b
    integer, intent(in) :: n
    logical, intent(in) :: logarithmic
    real(dp) :: v(n)
    integer :: i
    do i = 1, n
      if (logarithmic) then
        v(i) = exp(log(a) + (log(b) - log(a))*real(i - 1, dp)/real(n - 1, dp))
      else
        v(i) = a + (b - a)*real(i - 1, dp)/real(n - 1, dp)
      end if
    end do
    v = round_14(v)     ! 1e-6, not 9.9999999999999995e-7, in decks and tables
    v(1) = a            ! the ends exactly as written
    v(n) = b
  end function range_values

  !> x to 14 significant digits (exp(log) leaves a relative error of a few 1e-16).
  elemental real(dp) function round_14(x) result(r)
    real(dp), intent(in) :: x
    character(len=32) :: buf
    write(buf, '(es23.13e3)') x
    read(buf, *) r
  end function round_14

  !> name or name(i:j) with a letter first, then letters, digits, '_'.
  logical pure function is_designator(text)
    character(len=*), intent(in) :: text
    integer :: p
    is_designator = .false.
    if (len(text) == 0) return
    if (verify(text(1:1), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ') /= 0) return
    p = index(text, '(')
    if (p == 0) then
      is_designator = verify(text, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') == 0
      return
    end if
    if (verify(text(1:p - 1), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') /= 0) return
    if (text(len(text):) /= ')') return
    is_designator = is_subscript(text(p + 1:len(text) - 1))
  end function is_designator

  !> 'i' or 'i:j' with unsigned integers i, j.
  logical pure function is_subscript(text)
    character(len=*), intent(in) :: text
    integer :: c
    c = index(text, ':')
    if (c == 0) then
      is_subscript = len(text) > 0 .and. verify(text, '0123456789') == 0
    else
      is_subscript = c > 1 .and. c < len(text) .and. verify(text(1:c - 1), '0123456789') == 0 .and. &
                     verify(text(c + 1:), '0123456789') == 0
    end if
  end function is_subscript



  !> Echo the group with its points as the list `values` (a range given by
  !> first, last and n_points is echoed as the values it gave).
  subroutine echo_sweep_settings(s, out)
    type(sweep_settings_t), intent(in) :: s
    type(table_t), intent(inout) :: out
    call stage_from(sweep_settings_t(group=s%group, variable=s%variable, values=s%values, spacing=s%spacing, &
                                     points_dir=s%points_dir))
    call out%echo_group(sweep_group)
  end subroutine echo_sweep_settings

  !> The namelist variables from a settings value (the defaults before a read).
  subroutine stage_from(s)
    type(sweep_settings_t), intent(in) :: s
    group = s%group
    variable = s%variable
    values = unset
    if (allocated(s%values)) values(1:size(s%values)) = s%values
    first = s%first
    last = s%last
    n_points = s%n_points
    spacing = s%spacing
    points_dir = s%points_dir
  end subroutine stage_from

  !> The &sweep group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine sweep_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=sweep, delim='apostrophe')
    else
      read(r%unit, nml=sweep, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine sweep_group
end module sweep_settings
