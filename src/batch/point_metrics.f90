!> The numbers of one run's footer, for a sweep summary row: every
!> '# summary: KEY = VALUE' and '# cost: KEY = VALUE' line whose value starts
!> with a number becomes a named value (KEY in lower case, words joined by
!> '_'; cost keys prefixed 'cost_'; a value of several numbers gives KEY_1,
!> KEY_2, ...).  Text values (status = converged, steady state = stable ...)
!> are kept as notes for the summary's comment lines.
module point_metrics
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: lower, starts_with, str
  use run_output, only: run_output_t, read_run_output
  implicit none
  private
  public :: metric_t, read_point_metrics, metric_name

  type :: metric_t
    character(len=:), allocatable :: name
    real(dp) :: value = 0.0_dp
  end type metric_t

contains

  subroutine read_point_metrics(path, metrics, notes, err)
    character(len=*), intent(in) :: path
    type(metric_t), allocatable, intent(out) :: metrics(:)
    character(len=:), allocatable, intent(out) :: notes
    type(error_t), intent(inout) :: err
    type(run_output_t) :: out
    integer :: i, eq
    character(len=:), allocatable :: line, key
    allocate(metrics(0))
    notes = ''
    call read_run_output(path, out, err)
    if (err%failed()) return
    do i = 1, size(out%footer)
      line = out%footer(i)%s
      eq = index(line, ' = ')
      if (eq == 0) cycle
      if (starts_with(line, 'summary:')) then
        key = line(9:eq - 1)
      else
        key = 'cost '//line(6:eq - 1)
      end if
      call add_values(metric_name(key), adjustl(line(eq + 3:)), metrics, notes)
    end do
  end subroutine read_point_metrics

  subroutine add_values(name, text, metrics, notes)
    character(len=*), intent(in) :: name, text
    type(metric_t), allocatable, intent(inout) :: metrics(:)
    character(len=:), allocatable, intent(inout) :: notes
    real(dp) :: x(16)
    integer :: n, k
    n = leading_numbers(text, x)
    if (n == 0) then
      if (len_trim(text) <= 40 .and. len(notes) < 400 .and. .not. starts_with(name, 'cost_')) &
        notes = notes//'; '//name//' = '//trim(text)
      return
    end if
    if (n == 1) then
      call append_metric(metrics, name, x(1))
    else
      do k = 1, n
        call append_metric(metrics, name//'_'//str(k), x(k))
      end do
    end if
  end subroutine add_values

  subroutine append_metric(metrics, name, value)
    type(metric_t), allocatable, intent(inout) :: metrics(:)
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: value
    type(metric_t), allocatable :: longer(:)
    integer :: i
    allocate(longer(size(metrics) + 1))
    do i = 1, size(metrics)
      call move_alloc(metrics(i)%name, longer(i)%name)
      longer(i)%value = metrics(i)%value
    end do
    longer(size(longer))%name = name
    longer(size(longer))%value = value
    call move_alloc(longer, metrics)
  end subroutine append_metric

  !> How many of the first words of `text` are numbers (all words must be
  !> numbers for more than one to count), their values in x.
  integer function leading_numbers(text, x) result(n)
    character(len=*), intent(in) :: text
    real(dp), intent(out) :: x(:)
    integer :: a, b, ios, words
    logical :: all_numbers
    n = 0
    words = 0
    all_numbers = .true.
    a = 1
    do while (a <= len_trim(text))
      if (text(a:a) == ' ') then
        a = a + 1
        cycle
      end if
      b = index(text(a:)//' ', ' ') + a - 2
      words = words + 1
      if (n < size(x) .and. scan(text(a:b), '0123456789') > 0 .and. &
          verify(text(a:b), '0123456789+-.eEdD') == 0) then
        read(text(a:b), *, iostat=ios) x(n + 1)
        if (ios == 0) then
          n = n + 1
        else
          all_numbers = .false.
        end if
      else
        all_numbers = .false.
      end if
      if (.not. all_numbers) exit
      a = b + 1
    end do
    if (.not. all_numbers) n = min(n, 1)
  end function leading_numbers

  !> 'element 1 peak |stress| (exact periodic)' -> 'element_1_peak_stress_exact_periodic'
  pure function metric_name(key) result(s)
    character(len=*), intent(in) :: key
    character(len=:), allocatable :: s
    character(len=:), allocatable :: k
    integer :: i
    logical :: gap
    k = lower(trim(adjustl(key)))
    s = ''
    gap = .false.
    do i = 1, len(k)
      if (scan(k(i:i), 'abcdefghijklmnopqrstuvwxyz0123456789') > 0) then
        if (gap .and. len(s) > 0) s = s//'_'
        s = s//k(i:i)
        gap = .false.
      else
        gap = .true.
      end if
    end do
  end function metric_name
end module point_metrics
