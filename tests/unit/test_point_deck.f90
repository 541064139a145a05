!> Tests of point_deck (the deck of one sweep point): values written so that
!> the namelist reader gets the double back exactly, array sections filled,
!> the override placed inside the group (after the deck's own value, so it
!> wins) also when the group ends on its first line or a quoted '/' precedes
!> the terminator, a missing group added, and the &sweep group dropped.
module test_point_deck_suite
  use kinds, only: dp
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use point_deck, only: write_point_deck, value_text, assignment_text
  use assertions
  use deck_runner, only: write_deck
  implicit none
  private
  public :: run_all

  real(dp) :: x, arr(4)
  character(len=32) :: name
  integer :: n
  namelist /grp/ x, arr, name, n

contains

  subroutine run_all()
    call run_test('values_read_back_exactly', test_values)
    call run_test('array_section_sets_every_element', test_section)
    call run_test('override_wins_and_sweep_is_dropped', test_override)
    call run_test('missing_group_is_added', test_missing_group)
  end subroutine run_all

  !> An integral value is written as an integer (an integer variable can
  !> read it); any other with 17 digits: the same double after reading.
  subroutine test_values()
    real(dp) :: v(4), back
    integer :: i, k
    character(len=:), allocatable :: text
    v = [150.0_dp, 1.0e-7_dp, 1.0_dp/3.0_dp, -2.5e12_dp]
    do i = 1, size(v)
      text = value_text(v(i))
      read(text, *) back
      call assert_close(back, v(i), 0.0_dp, 'value '//text//' reads back bit for bit')
    end do
    call assert_equal(value_text(150.0_dp), '150', 'integral value as an integer')
    text = value_text(4.0_dp)
    read(text, *) k
    call assert_equal(k, 4, 'an integer variable reads an integral value')
  end subroutine test_values

  subroutine test_section()
    integer :: u
    character(len=:), allocatable :: text
    text = assignment_text('arr(2:4)', 0.5_dp)
    call assert_equal(text(1:13), 'arr(2:4) = 3*', 'section: repeat count 3')
    arr = 0.0_dp
    open(newunit=u, status='scratch')
    write(u, '(a)') '&grp '//assignment_text('arr(2:4)', 0.5_dp)//' /'
    rewind(u)
    read(u, nml=grp)
    close(u)
    call assert_all_close(arr, [0.0_dp, 0.5_dp, 0.5_dp, 0.5_dp], 0.0_dp, 0.0_dp, 'elements 2-4 set, 1 kept')
  end subroutine test_section

  !> Write the deck `text` ('|' separates lines) to `path`, write its point
  !> deck with `variable` of &grp set to `value`, remove the input.
  subroutine point_from(path, text, variable, value, point, err)
    character(len=*), intent(in) :: path, text, variable, point
    real(dp), intent(in) :: value
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    integer :: u
    call write_deck(path, text)
    call deck%open(path, err)
    call write_point_deck(deck, 'grp', variable, value, point, err)
    call deck%close()
    open(newunit=u, file=path, status='old')
    close(u, status='delete')
  end subroutine point_from

  !> A group with a quoted '/' on its last line: the override goes before the
  !> real terminator; the deck's other values are kept; &sweep is gone.
  subroutine test_override()
    character(len=*), parameter :: path = 'test_point_deck_in.nml', point = 'test_point_deck_out.nml'
    type(error_t) :: err
    integer :: u, ios
    call point_from(path, '&run analysis = ''x'' /|&grp x = 1.0,|  n = 7, name = ''a/b'' /|'// &
                    '&sweep group = ''grp'', variable = ''x'', values = 2, 3 /', 'x', 2.25_dp, point, err)
    call assert_true(.not. err%failed(), 'written')
    x = 0.0_dp
    n = 0
    name = ''
    open(newunit=u, file=point, status='old')
    read(u, nml=grp, iostat=ios)
    call assert_equal(ios, 0, 'the point deck''s group reads')
    call assert_close(x, 2.25_dp, 0.0_dp, 'override wins over the deck''s x = 1.0')
    call assert_equal(n, 7, 'other values kept')
    call assert_equal(trim(name), 'a/b', 'quoted slash kept')
    rewind(u)
    call assert_true(.not. has_line(u, '&sweep'), '&sweep dropped')
    close(u, status='delete')
  end subroutine test_override

  subroutine test_missing_group()
    character(len=*), parameter :: path = 'test_point_deck_in2.nml', point = 'test_point_deck_out2.nml'
    type(error_t) :: err
    integer :: u, ios
    call point_from(path, '&run analysis = ''x'' /', 'n', 12.0_dp, point, err)
    n = 0
    open(newunit=u, file=point, status='old')
    read(u, nml=grp, iostat=ios)
    call assert_equal(ios, 0, 'the added group reads')
    call assert_equal(n, 12, 'integer variable set from an integral value')
    close(u, status='delete')
  end subroutine test_missing_group

  logical function has_line(u, start)
    integer, intent(in) :: u
    character(len=*), intent(in) :: start
    character(len=256) :: line
    integer :: ios
    has_line = .false.
    do
      read(u, '(a)', iostat=ios) line
      if (ios /= 0) return
      if (index(adjustl(line), start) == 1) has_line = .true.
    end do
  end function has_line
end module test_point_deck_suite

program test_point_deck
  use assertions, only: finish_suite
  use test_point_deck_suite, only: run_all
  implicit none
  call run_all()
  call finish_suite('test_point_deck')
end program test_point_deck
