!> The deck's system of units (&run units = 'in-lbf-s', 'SI' or 'none') and
!> the unit labels of the output in it.  The program computes in whatever
!> consistent units the deck uses; the system decides only the labels the
!> output prints, the default material of the links and the range the
!> plausibility checks judge a material by.
!>
!> Every output text is written with the labels of in-lbf-s (in, psi, lb,
!> lb in); `labelled` turns them into the run's system:
!>
!>     call set_unit_system('si')
!>     labelled('bending moment (lb in), force (lb)')   ! 'bending moment (N m), force (N)'
!>
!> A label is recognised only where a unit stands: 'psi', 'lb' and 'lb in'
!> as whole words, 'in' in parentheses ('(in)', '(in;', '(in,') and in
!> 'in/s', 'lb/in^n' and 'lb s^2/in^4'.  With 'none' the labels are dropped.
module unit_system
  use kinds, only: dp
  use strings, only: lower
  implicit none
  private
  public :: set_unit_system, unit_system_name, labelled, unit_systems, wave_speed_range

  character(len=8), parameter :: unit_systems(3) = [character(len=8) :: 'in-lbf-s', 'si', 'none']
  character(len=8), save :: current = 'in-lbf-s'

  !> in-lbf-s label and its SI counterpart, longest first (matched in order)
  character(len=12), parameter :: from(8) = [character(len=12) :: 'lb s^2/in^4', 'lb/in^', 'lb in', 'in/s^2', &
                                             'in/s', 'psi', 'lb', 'in']
  character(len=12), parameter :: to_si(8) = [character(len=12) :: 'kg/m^3', 'N/m^', 'N m', 'm/s^2', 'm/s', 'Pa', &
                                               'N', 'm']

contains

  !> 'in-lbf-s', 'si' or 'none' (any case); anything else leaves the system as it was.
  subroutine set_unit_system(name)
    character(len=*), intent(in) :: name
    if (any(unit_systems == lower(trim(adjustl(name))))) current = lower(trim(adjustl(name)))
  end subroutine set_unit_system

  !> The run's system: 'in-lbf-s' (the default), 'si' or 'none'.
  function unit_system_name() result(name)
    character(len=:), allocatable :: name
    name = trim(current)
  end function unit_system_name

  !> The range of the bar wave speed sqrt(E/rho) of engineering solids
  !> (about 1,000 to 13,000 m/s: stiff polymers to beryllium) in the system's
  !> speed unit: m/s for 'si', in/s otherwise.
  subroutine wave_speed_range(system, lo, hi)
    character(len=*), intent(in) :: system
    real(dp), intent(out) :: lo, hi
    lo = 1000.0_dp
    hi = 13000.0_dp
    if (system /= 'si') then
      lo = lo/0.0254_dp
      hi = hi/0.0254_dp
    end if
  end subroutine wave_speed_range

  !> `text` with its in-lbf-s unit labels in the run's system.
  function labelled(text) result(s)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: s
    integer :: k, i, n
    if (current == 'in-lbf-s') then
      s = text
      return
    end if
    s = ''
    k = 1
    do while (k <= len(text))
      i = label_at(text, k)
      if (i == 0) then
        s = s//text(k:k)
        k = k + 1
        cycle
      end if
      n = len_trim(from(i))
      if (current == 'si') then
        s = s//trim(to_si(i))
        k = k + n
      else
        call drop_label(text, k, n, s)
      end if
    end do
  end function labelled

  !> Which label (index into `from`) stands at text(k:), 0 if none.
  integer function label_at(text, k) result(found)
    character(len=*), intent(in) :: text
    integer, intent(in) :: k
    integer :: i, n
    found = 0
    if (k > 1) then
      if (is_word_char(text(k - 1:k - 1))) return
    end if
    do i = 1, size(from)
      n = len_trim(from(i))
      if (k + n - 1 > len(text)) cycle
      if (text(k:k + n - 1) /= from(i)(1:n)) cycle
      if (k + n <= len(text) .and. from(i)(n:n) /= '^') then   ! (a '^' is followed by its power)
        if (is_word_char(text(k + n:k + n))) cycle     ! psi1, inch, lbs
      end if
      if (from(i) == 'in') then                        ! 'in' is a unit only in parentheses
        if (k == 1) cycle
        if (text(k - 1:k - 1) /= '(') cycle
      end if
      found = i
      return
    end do
  end function label_at

  logical pure function is_word_char(c)
    character(len=1), intent(in) :: c
    is_word_char = scan(c, 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_') == 1
  end function is_word_char

  !> Drop the label text(k:k+n-1) (units 'none'): '(psi)' goes with its
  !> parentheses, '(psi; more' keeps '(more', ' psi at' becomes ' at'.
  subroutine drop_label(text, k, n, s)
    character(len=*), intent(in) :: text
    integer, intent(inout) :: k
    integer, intent(in) :: n
    character(len=:), allocatable, intent(inout) :: s
    integer :: e
    e = k + n                                   ! the first character after the label
    if (len(s) > 0 .and. s(len(s):len(s)) == '(') then
      if (e <= len(text)) then
        if (text(e:e) == ')') then              ! '(psi)': the parentheses and the blank before them go too
          s = s(1:len(s) - 1)
          if (len(s) > 0) then
            if (s(len(s):len(s)) == ' ') s = s(1:len(s) - 1)
          end if
          k = e + 1
          return
        end if
        if (scan(text(e:e), ';,:') == 1) then   ! '(psi; more': the separator and its blank go too
          e = e + 1
          if (e <= len(text)) then
            if (text(e:e) == ' ') e = e + 1
          end if
        end if
      end if
      k = e
      return
    end if
    if (len(s) > 0) then                        ! ' psi at': the blank before the label goes
      if (s(len(s):len(s)) == ' ') s = s(1:len(s) - 1)
    end if
    k = e
  end subroutine drop_label
end module unit_system
