!> Validation of values read from a deck: one line per variable, naming the
!> value, the allowed range or choices and the reason.
!>
!>     call check_real(deck, 'transient', 'rtol', s%rtol, err, above=0.0_dp, below=0.1_dp, &
!>                     why='a relative tolerance')
!>     call check_integer(deck, 'transient', 'max_steps', s%max_steps, err, at_least=1)
!>     call check_choice(deck, 'transient', 'kinematics', s%kinematics, [character(16) :: 'table', 'direct'], err)
!>
!> A check does nothing once `err` holds an error, so a settings module lists
!> its checks one after another and reports the first failure.  Every real is
!> checked finite first (NaN and Inf are read by the namelist reader), and the
!> finiteness test uses ieee_is_finite, which raises no floating-point
!> exception: the debug build traps on an ordered comparison with NaN.
module deck_checks
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, compact
  use deck_reader, only: deck_t, invalid_value
  implicit none
  private
  public :: check_real, check_reals, check_integer, check_choice, all_finite

contains

  !> A real deck value: finite, then within the bounds given.  `above`/`below`
  !> are strict bounds, `at_least`/`at_most` inclusive ones.
  subroutine check_real(deck, group, name, value, err, above, at_least, below, at_most, why, or_zero)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group, name
    real(dp), intent(in) :: value
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: above, at_least, below, at_most
    character(len=*), intent(in), optional :: why
    logical, intent(in), optional :: or_zero     !< 0 (the effect off) allowed besides the range
    logical :: ok, zero_allowed
    character(len=:), allocatable :: range
    if (err%failed()) return
    if (.not. ieee_is_finite(value)) then
      call invalid_value(deck, group, name, str(value), 'must be a finite number'//reason(why), err)
      return
    end if
    zero_allowed = .false.
    if (present(or_zero)) zero_allowed = or_zero
    if (zero_allowed .and. .not. abs(value) > 0.0_dp) return
    ok = .true.
    if (present(above)) ok = ok .and. value > above
    if (present(at_least)) ok = ok .and. value >= at_least
    if (present(below)) ok = ok .and. value < below
    if (present(at_most)) ok = ok .and. value <= at_most
    if (ok) return
    range = range_text(above, at_least, below, at_most)
    if (zero_allowed) range = 'must be 0 or'//range(5:)     ! 'must lie in ...' -> 'must be 0 or lie in ...'
    call invalid_value(deck, group, name, str(value), range//reason(why), err)
  end subroutine check_real

  !> Every element of a real array deck value (named name(i), or name(k,i)
  !> when name is given as 'name(k,:)').
  subroutine check_reals(deck, group, name, values, err, above, at_least, below, at_most, why)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group, name
    real(dp), intent(in) :: values(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: above, at_least, below, at_most
    character(len=*), intent(in), optional :: why
    integer :: i, colon
    colon = index(name, ':)')      ! 'section_b(3,:)' names element i as 'section_b(3,i)'
    do i = 1, size(values)
      if (colon > 0) then
        call check_real(deck, group, name(1:colon - 1)//str(i)//')', values(i), err, above, at_least, below, at_most, why)
      else
        call check_real(deck, group, name//'('//str(i)//')', values(i), err, above, at_least, below, at_most, why)
      end if
      if (err%failed()) return
    end do
  end subroutine check_reals

  subroutine check_integer(deck, group, name, value, err, at_least, at_most, why)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group, name
    integer, intent(in) :: value
    type(error_t), intent(inout) :: err
    integer, intent(in), optional :: at_least, at_most
    character(len=*), intent(in), optional :: why
    logical :: ok
    character(len=:), allocatable :: rule
    if (err%failed()) return
    ok = .true.
    if (present(at_least)) ok = ok .and. value >= at_least
    if (present(at_most)) ok = ok .and. value <= at_most
    if (ok) return
    if (present(at_least) .and. present(at_most)) then
      rule = 'must lie in '//str(at_least)//'..'//str(at_most)
    else if (present(at_least)) then
      rule = 'must be >= '//str(at_least)
    else
      rule = 'must be <= '//str(at_most)
    end if
    call invalid_value(deck, group, name, str(value), rule//reason(why), err)
  end subroutine check_integer

  !> A text value that must be one of a list of choices (compared trimmed).
  subroutine check_choice(deck, group, name, value, choices, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: group, name, value
    character(len=*), intent(in) :: choices(:)
    type(error_t), intent(inout) :: err
    integer :: i
    character(len=:), allocatable :: listed
    if (err%failed()) return
    if (any(choices == value)) return
    listed = ''
    do i = 1, size(choices)
      if (i > 1) listed = listed//', '
      listed = listed//''''//trim(choices(i))//''''
    end do
    call invalid_value(deck, group, name, ''''//trim(value)//'''', 'must be one of '//listed, err)
  end subroutine check_choice

  !> True when every value is finite (for results and derived quantities).
  logical pure function all_finite(values)
    real(dp), intent(in) :: values(:)
    integer :: i
    all_finite = .true.
    do i = 1, size(values)
      if (.not. ieee_is_finite(values(i))) then
        all_finite = .false.
        return
      end if
    end do
  end function all_finite

  pure function range_text(above, at_least, below, at_most) result(s)
    real(dp), intent(in), optional :: above, at_least, below, at_most
    character(len=:), allocatable :: s, lo, hi
    lo = ''
    hi = ''
    if (present(above)) lo = '('//compact(above)
    if (present(at_least)) lo = '['//compact(at_least)
    if (present(below)) hi = compact(below)//')'
    if (present(at_most)) hi = compact(at_most)//']'
    if (len(lo) > 0 .and. len(hi) > 0) then
      s = 'must lie in '//lo//', '//hi
    else if (present(above)) then
      s = 'must be > '//compact(above)
    else if (present(at_least)) then
      s = 'must be >= '//compact(at_least)
    else if (present(below)) then
      s = 'must be < '//compact(below)
    else if (present(at_most)) then
      s = 'must be <= '//compact(at_most)
    else
      s = 'must be a finite number'
    end if
  end function range_text

  pure function reason(why) result(s)
    character(len=*), intent(in), optional :: why
    character(len=:), allocatable :: s
    s = ''
    if (present(why)) then
      if (len_trim(why) > 0) s = ' ('//trim(why)//')'
    end if
  end function reason
end module deck_checks
