!> The fast row formatter (src/io/fast_format.f90) against gfortran's
!> correctly rounded ES(d+7).(d-1)E3 conversion.
module test_fast_format_suite
  use kinds, only: dp
  use fast_format, only: format_es, format_es_exact, es_width
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('random_values_match_the_fortran_es_format', test_random)
    call run_test('edge_values_round_and_carry_like_fortran', test_edges)
    call run_test('exact_conversion_is_the_fortran_string', test_exact)
  end subroutine run_all

  !> 200,000 values with magnitudes 1e-300..1e300 and 1e-3..1e3 (both
  !> signs; a fixed seed), d = 3, 6, 8, 12: the string equals Fortran's
  !> except where the value lies within the scaling's few ulps of a rounding
  !> tie: at most 2 values for d <= 8 (expected ~1e-8 of them; measured 0),
  !> 1e-3 of them for d = 12 (measured 2e-5); and any
  !> difference is one unit of the last digit.  Read back, every string is
  !> within half a unit of its last digit of the value (plus the tie slack).
  subroutine test_random()
    integer, parameter :: n = 200000, ds(4) = [3, 6, 8, 12]
    real(dp) :: r(2), v, back, ref_back, unit_last
    character(len=40) :: fast, ref, fmt
    integer :: k, i, d, n_diff, n_bad
    call seed_random(7919, 17)
    do k = 1, size(ds)
      d = ds(k)
      fmt = es_format(d)
      n_diff = 0
      n_bad = 0
      do i = 1, n
        call random_number(r)
        if (mod(i, 2) == 0) then
          v = 10.0_dp**(600.0_dp*r(1) - 300.0_dp)
        else
          v = 10.0_dp**(6.0_dp*r(1) - 3.0_dp)
        end if
        if (r(2) < 0.5_dp) v = -v
        fast = ''
        call format_es(v, d, fast)
        write(ref, fmt) v
        if (fast(1:es_width(d)) /= ref(1:es_width(d))) then
          n_diff = n_diff + 1
          read(fast, *) back
          read(ref, *) ref_back
          unit_last = 10.0_dp**(floor(log10(abs(ref_back))) - d + 1)
          if (abs(back - ref_back) > 1.01_dp*unit_last) n_bad = n_bad + 1
        end if
      end do
      write(*, '(4x,a,i2,a,i0,a,i0)') 'd = ', d, ': strings differing from Fortran''s ', n_diff, ' of ', n
      call assert_equal(n_bad, 0, 'differences larger than one unit of the last digit, d = '//trim(adjustl(fmt)))
      if (d <= 8) then
        call assert_true(n_diff <= 2, 'd <= 8: (almost) always Fortran''s string (expected ~1e-8 of the values)')
      else
        call assert_true(n_diff <= n/1000, 'd = 12: at most 1e-3 of the values near a tie')
      end if
    end do
  end subroutine test_random

  !> The exact conversion at d = 16 (the rows' default) and 17: 400,000
  !> values with magnitudes 1e-14..1e18 (both signs, a fixed seed), values
  !> on decimal rounding ties (2^50 + 1/2: 17 digits ending in 5, ties to
  !> even), decade edges and small integers: every string it gives is
  !> Fortran's, character for character, and it gives one for every value
  !> in 10^(d-28)..10^d (1e-12..1e16 at d = 16; the rest are left to WRITE).
  subroutine test_exact()
    integer, parameter :: n = 400000, ds(2) = [16, 17]
    real(dp), parameter :: fixed(10) = [2.0_dp**50 + 0.5_dp, 2.0_dp**50 + 1.5_dp, 9.9999999999999995_dp, &
      1.0e-12_dp, 9.999999999999999e15_dp, 1440.25_dp, 0.1_dp, 1.0_dp, 5.0e-5_dp, 123456789.0_dp]
    real(dp) :: r(2), v
    character(len=40) :: fast, ref, fmt
    integer :: k, i, d, n_diff, n_left
    logical :: done
    call seed_random(104729, 3)
    do k = 1, size(ds)
      d = ds(k)
      fmt = es_format(d)
      n_diff = 0
      n_left = 0
      do i = 1, n + size(fixed)
        if (i <= size(fixed)) then
          v = fixed(min(i, size(fixed)))
        else
          call random_number(r)
          v = 10.0_dp**(32.0_dp*r(1) - 14.0_dp)
          if (r(2) < 0.5_dp) v = -v
        end if
        fast = ''
        call format_es_exact(v, d, fast, done)
        if (.not. done) then
          if (abs(v) >= 10.0_dp**(d - 28) .and. abs(v) < 10.0_dp**d) n_left = n_left + 1
          cycle
        end if
        write(ref, fmt) v
        if (fast(1:es_width(d)) /= ref(1:es_width(d))) n_diff = n_diff + 1
      end do
      write(*, '(4x,a,i2,a,i0,a,i0)') 'd = ', d, ': exact strings differing from Fortran''s ', n_diff, ' of ', n
      call assert_equal(n_diff, 0, 'the exact conversion is Fortran''s string, d = '//trim(adjustl(fmt)))
      call assert_equal(n_left, 0, 'every value in 10^(d-28)..10^d converted, d = '//trim(adjustl(fmt)))
    end do
  end subroutine test_exact

  !> A fixed seed of the random numbers: a i + b, i = 1 .. its size.
  subroutine seed_random(a, b)
    integer, intent(in) :: a, b
    integer :: n_seed, i
    integer, allocatable :: seed(:)
    call random_seed(size=n_seed)
    allocate(seed(n_seed))
    seed = [(a*i + b, i = 1, n_seed)]
    call random_seed(put=seed)
  end subroutine seed_random

  !> '(es<d+7>.<d-1>e3)': Fortran's format of d significant digits.
  function es_format(d) result(fmt)
    integer, intent(in) :: d
    character(len=40) :: fmt
    write(fmt, '(a,i0,a,i0,a)') '(es', d + 7, '.', d - 1, 'e3)'
  end function es_format

  subroutine test_edges()
    call check(0.0_dp, 8, ' 0.0000000E+000')
    call check(9.99999995_dp, 8, ' 1.0000000E+001')
    call check(-9.9999999e5_dp, 8, '-9.9999999E+005')
    call check(1.0e-310_dp, 6, ' 1.00000E-310')
    call check(1.7976931348623157e308_dp, 8, ' 1.7976931E+308')
    call check(123.456_dp, 3, ' 1.23E+002')
    call check(1.0_dp, 12, ' 1.00000000000E+000')
  contains
    subroutine check(v, d, want)
      real(dp), intent(in) :: v
      integer, intent(in) :: d
      character(len=*), intent(in) :: want
      character(len=40) :: s
      s = ''
      call format_es(v, d, s)
      call assert_equal(trim(s), want, 'format of '//want)
    end subroutine check
  end subroutine test_edges
end module test_fast_format_suite

program test_fast_format
  use test_fast_format_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_fast_format')
end program test_fast_format
