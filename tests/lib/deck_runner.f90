!> Running an analysis on a deck written by a test: the deck text ('|'
!> separates lines) goes to a scratch file under $TMPDIR, the analysis runs
!> through its driver, and the output comes back as lines.  One home for what
!> the analysis suites used to copy: a suite names itself and its analysis
!> once (start_suite), then runs deck texts with run_text.
module deck_runner
  use kinds, only: dp
  use c_library, only: c_getpid
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use run_settings, only: analysis_runner => analysis_driver
  implicit none
  private
  public :: scratch_path, write_deck, run_deck, analysis_runner
  public :: open_deck_text, close_deck_text
  public :: has_line, summary_value, count_rows, line_length
  public :: start_suite, suite_stem, run_text

  integer, parameter :: line_length = 2048

  !> The running suite's scratch stem and analysis (one suite per executable).
  character(len=:), allocatable, save :: stem
  procedure(analysis_runner), pointer, save :: suite_analysis => null()

contains

  !> Name the suite's scratch files after `name` and, for run_text, its analysis.
  subroutine start_suite(name, analysis)
    character(len=*), intent(in) :: name
    procedure(analysis_runner), optional :: analysis
    stem = scratch_path(name)
    if (present(analysis)) suite_analysis => analysis
  end subroutine start_suite

  !> The scratch stem start_suite set (stem.nml, stem.out and side files).
  function suite_stem() result(path)
    character(len=:), allocatable :: path
    path = stem
  end function suite_stem

  !> The deck `text` ('|' separates lines) through the suite's analysis;
  !> output lines back (run_deck on the suite's stem).
  subroutine run_text(text, err, lines)
    character(len=*), intent(in) :: text
    type(error_t), intent(inout) :: err
    character(len=line_length), allocatable, intent(out) :: lines(:)
    call run_deck(suite_analysis, stem, text, err, lines)
  end subroutine run_text

  !> $TMPDIR/flexmech_<name>_<pid> (or /tmp/...): the process id keeps two
  !> test runs at once (two checkouts, two optimisation levels) apart.
  function scratch_path(name) result(path)
    character(len=*), intent(in) :: name
    character(len=:), allocatable :: path
    character(len=256) :: tmp
    character(len=16) :: pid
    integer :: length, status
    call get_environment_variable('TMPDIR', tmp, length, status)
    if (status /= 0 .or. length == 0) tmp = '/tmp'
    write(pid, '(i0)') c_getpid()
    path = trim(tmp)//'/flexmech_'//name//'_'//trim(pid)
  end function scratch_path

  !> Write `text` ('|' separates lines) to `path`.
  subroutine write_deck(path, text)
    character(len=*), intent(in) :: path, text
    integer :: u, i, j
    open(newunit=u, file=path, status='replace', action='write')
    i = 1
    do
      j = index(text(i:), '|')
      if (j == 0) then
        write(u, '(a)') text(i:)
        exit
      end if
      write(u, '(a)') text(i:i + j - 2)
      i = i + j
    end do
    close(u)
  end subroutine write_deck

  !> Write the deck, run `analysis` on it into stem.out, return the output
  !> lines (none when the output was discarded for an input error); both
  !> files are removed.
  subroutine run_deck(analysis, stem, text, err, lines)
    procedure(analysis_runner) :: analysis
    character(len=*), intent(in) :: stem, text
    type(error_t), intent(inout) :: err
    character(len=line_length), allocatable, intent(out) :: lines(:)
    type(deck_t) :: deck
    type(table_t) :: out
    type(error_t) :: cerr
    integer :: u, i, n, ios
    character(len=line_length) :: line
    call write_deck(stem//'.nml', text)
    call deck%open(stem//'.nml', err)
    call out%open(stem//'.out', cerr)
    if (.not. err%failed()) call analysis(deck, out, err)
    call deck%close()
    allocate(lines(0))
    if (err%failed() .and. err%code == 2) then
      call out%discard()
    else
      call out%commit(cerr)
      open(newunit=u, file=stem//'.out', status='old', action='read')
      n = 0
      do
        read(u, '(a)', iostat=ios) line
        if (ios /= 0) exit
        n = n + 1
      end do
      rewind(u)
      deallocate(lines)
      allocate(lines(n))
      do i = 1, n
        read(u, '(a)') lines(i)
      end do
      close(u, status='delete')
    end if
    open(newunit=u, file=stem//'.nml', status='old')
    close(u, status='delete')
  end subroutine run_deck

  !> Write the deck text ('|' between lines) to stem.nml and open it, for a
  !> settings reader the test calls itself (close_deck_text after it).
  subroutine open_deck_text(stem, text, deck, err)
    character(len=*), intent(in) :: stem, text
    type(deck_t), intent(inout) :: deck
    type(error_t), intent(inout) :: err
    call write_deck(stem//'.nml', text)
    call deck%open(stem//'.nml', err)
  end subroutine open_deck_text

  !> Close the deck open_deck_text opened and remove stem.nml.
  subroutine close_deck_text(stem, deck)
    character(len=*), intent(in) :: stem
    type(deck_t), intent(inout) :: deck
    integer :: u
    call deck%close()
    open(newunit=u, file=stem//'.nml', status='old')
    close(u, status='delete')
  end subroutine close_deck_text

  logical function has_line(lines, fragment)
    character(len=*), intent(in) :: lines(:), fragment
    integer :: i
    has_line = .false.
    do i = 1, size(lines)
      if (index(lines(i), fragment) > 0) then
        has_line = .true.
        return
      end if
    end do
  end function has_line

  !> The number after `key` on the first line that starts with it (huge if none).
  real(dp) function summary_value(lines, key) result(v)
    character(len=*), intent(in) :: lines(:), key
    integer :: i, ios
    v = huge(1.0_dp)
    do i = 1, size(lines)
      if (index(lines(i), key) == 1) then
        read(lines(i)(len(key) + 1:), *, iostat=ios) v
        if (ios /= 0) v = huge(1.0_dp)
        return
      end if
    end do
  end function summary_value

  !> Data rows (neither '#' lines nor blank).
  integer function count_rows(lines) result(n)
    character(len=*), intent(in) :: lines(:)
    integer :: i
    n = 0
    do i = 1, size(lines)
      if (lines(i)(1:1) /= '#' .and. len_trim(lines(i)) > 0) n = n + 1
    end do
  end function count_rows
end module deck_runner
