!> The layout of a deck, checked before any group is read: every line lies
!> inside a group of the analysis, or is blank, or is a comment ('!').  A
!> group the analysis does not read, a group given twice and any other text
!> outside a group are input errors (the namelist reader would skip them in
!> silence), each named with its line and, for a misspelled group, the
!> group meant:
!>
!>     call check_deck_layout(deck, 'steady', [character(len=20) :: 'run', 'mechanism', 'steady', 'tennant'], &
!>                            known_groups, err)
module deck_layout
  use error_status, only: error_t
  use strings, only: str
  use spelling, only: nearest_name
  use deck_reader, only: deck_t, scan_line, shown_line, terminator_column, input_error_code
  implicit none
  private
  public :: check_deck_layout

contains

  !> `reads`: the groups the analysis reads; `known`: every group of the
  !> program (for the suggestion); blank entries in either are ignored.
  subroutine check_deck_layout(deck, analysis, reads, known, err)
    type(deck_t), intent(in) :: deck
    character(len=*), intent(in) :: analysis
    character(len=*), intent(in) :: reads(:), known(:)
    type(error_t), intent(inout) :: err
    character(len=:), allocatable :: l, where, current
    character(len=64) :: name
    integer :: i, j, k, e, col, opened_at(size(reads)), group_first
    logical :: inside
    if (err%failed()) return
    where = 'deck '''//deck%path//''''
    opened_at = 0
    inside = .false.
    group_first = 0
    current = ''
    do i = 1, size(deck%lines)
      l = trim(adjustl(scan_line(deck, i)))
      if (.not. inside) then
        if (len(l) == 0) cycle
        if (l(1:1) == '!') cycle
        if (l(1:1) /= '&') then
          call err%set(where, 'line '//str(i)//': "'//shown_line(deck, i)//'" is outside any group: '// &
                       'every setting belongs between a group''s &name and its closing ''/'''// &
                       group_beside(deck, i, current, group_first), input_error_code)
          return
        end if
        e = scan(l(2:), ' ,/!')          ! the name after the '&'
        if (e == 0) e = len(l)
        name = l(2:e)
        k = 0
        do j = 1, size(reads)     ! (not findloc: gfortran's does not pad to compare texts of unequal length)
          if (reads(j) == name) k = j
        end do
        if (k == 0) then
          call err%set(where, 'line '//str(i)//': group &'//trim(name)//' '//not_read(trim(name), analysis, reads, known), &
                       input_error_code)
          return
        end if
        if (opened_at(k) > 0) then
          call err%set(where, 'line '//str(i)//': group &'//trim(name)//' is given a second time (first on line '// &
                       str(opened_at(k))//'): give each group once', input_error_code)
          return
        end if
        opened_at(k) = i
        group_first = i
        current = trim(name)
        inside = .true.
        col = terminator_column(l, .true.)
      else
        col = terminator_column(l, .false.)
      end if
      if (col > len(l)) cycle
      inside = .false.
      ! after the '/': nothing but a comment
      l = trim(adjustl(l(col + 1:)))
      if (len(l) > 0) then
        if (l(1:1) /= '!') then
          call err%set(where, 'line '//str(i)//': "'//shown_line(deck, i)//'": the text after the ''/'' that '// &
                       'closes the group &'//current// &
                       ' is outside any group (put it before the ''/'')', input_error_code)
          return
        end if
      end if
    end do
    if (inside) call err%set(where//', group &'//current, &
                             'group starting on line '//str(group_first)//' is not closed with ''/''', input_error_code)
  end subroutine check_deck_layout

  !> Why a group is refused: misspelled, or another analysis's.
  function not_read(name, analysis, reads, known) result(s)
    character(len=*), intent(in) :: name, analysis
    character(len=*), intent(in) :: reads(:), known(:)
    character(len=:), allocatable :: s, near
    integer :: i
    logical :: known_name
    known_name = .false.
    do i = 1, size(known)
      known_name = known_name .or. known(i) == name
    end do
    if (known_name) then
      s = 'is not read by the '''//trim(analysis)//''' analysis'
    else
      s = 'is not a group of flexmech'
      near = nearest_name(name, reads)
      if (len(near) == 0) near = nearest_name(name, known)
      if (len(near) > 0) s = s//': did you mean &'//near//'?'
    end if
    s = s//' (the '''//trim(analysis)//''' analysis reads'
    do i = 1, size(reads)
      if (len_trim(reads(i)) == 0) cycle
      if (i > 1) s = s//','
      s = s//' &'//trim(reads(i))
    end do
    s = s//')'
  end function not_read

  !> ' (after the group ending ...)' context for text outside groups.
  !> Where a stray line stands: after the group opened on line group_first,
  !> else before the first group that follows it (so the message names a group).
  function group_beside(deck, i, current, group_first) result(s)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: i, group_first
    character(len=*), intent(in) :: current
    character(len=:), allocatable :: s, l
    integer :: j, e
    s = ''
    if (group_first > 0) then
      s = ' (it follows the group &'//current//' of line '//str(group_first)//')'
      return
    end if
    do j = i + 1, size(deck%lines)
      l = trim(adjustl(scan_line(deck, j)))
      if (len(l) < 2) cycle
      if (l(1:1) /= '&') cycle
      e = scan(l(2:), ' ,/!')
      if (e == 0) e = len(l)
      s = ' (it comes before the group &'//l(2:e)//' of line '//str(j)//')'
      return
    end do
  end function group_beside
end module deck_layout
