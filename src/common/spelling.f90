!> The name a user probably meant: the candidate nearest a misspelled word
!> in edit distance (insertions, deletions, substitutions and transpositions
!> of neighbours each count 1: the optimal-string-alignment distance).
!>
!>     nearest_name('transients', ['run      ', 'transient'])   ! 'transient'
!>     nearest_name('xyz', ['run', 'tennant'])                  ! '' (nothing close)
module spelling
  use strings, only: lower
  implicit none
  private
  public :: edit_distance, nearest_name

  integer, parameter :: max_distance = 2   !< farther than this is not a misspelling

contains

  !> Edits that turn a into b (case counts; compare lower-case words).
  pure integer function edit_distance(a, b) result(d)
    character(len=*), intent(in) :: a, b
    integer :: m(0:len(a), 0:len(b)), i, j, cost
    do i = 0, len(a)
      m(i, 0) = i
    end do
    do j = 0, len(b)
      m(0, j) = j
    end do
    do i = 1, len(a)
      do j = 1, len(b)
        cost = merge(0, 1, a(i:i) == b(j:j))
        m(i, j) = min(m(i - 1, j) + 1, m(i, j - 1) + 1, m(i - 1, j - 1) + cost)
        if (i > 1 .and. j > 1) then
          if (a(i:i) == b(j - 1:j - 1) .and. a(i - 1:i - 1) == b(j:j)) m(i, j) = min(m(i, j), m(max(i - 2, 0), max(j - 2, 0)) + 1)
        end if
      end do
    end do
    d = m(len(a), len(b))
  end function edit_distance

  !> The candidate nearest `word` (case ignored, trimmed), '' when none is
  !> within two edits or the word is too short for the edits to mean a
  !> misspelling (fewer characters than edits plus one).  The first of equals wins.
  pure function nearest_name(word, candidates) result(best)
    character(len=*), intent(in) :: word
    character(len=*), intent(in) :: candidates(:)
    character(len=:), allocatable :: best, w
    integer :: i, d, best_d
    best = ''
    w = lower(trim(adjustl(word)))
    best_d = max_distance + 1
    do i = 1, size(candidates)
      if (len_trim(candidates(i)) == 0) cycle
      d = edit_distance(w, lower(trim(adjustl(candidates(i)))))
      if (d == 0) cycle         ! the word itself is not a suggestion
      if (d < best_d .and. d < len(w)) then
        best_d = d
        best = lower(trim(adjustl(candidates(i))))
      end if
    end do
  end function nearest_name
end module spelling
