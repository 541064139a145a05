!> A fast scientific formatter for output rows: d significant digits
!> (3 <= d <= 12) as ' -1.2345678E+002' (the layout of Fortran's
!> ES(d+7).(d-1)E3, which numpy.loadtxt and gnuplot read), about five times
!> cheaper than the formatted WRITE of gfortran (whose correctly rounded
!> conversion dominated a cheap transient run's CPU at fine output steps).
!>
!> The mantissa is nint(|v| 10^(d-1-e)) in 64-bit integers; the scaling is
!> exact to a few units in the last place of a double, so the last printed
!> digit can differ from the correctly rounded one only when |v| lies within
!> ~1e-16 10^d of a rounding tie: about 1e-8 of the values at d = 8, 1e-4
!> at d = 12 (tests/unit/test_fast_format.f90).  Finite values only.
!>
!> format_es_exact is the correctly rounded conversion (ties to even, as
!> the C library's printf that gfortran's formatted WRITE calls): the
!> value's binary mantissa M 2^b times 5^k is an integer of at most 117 bits,
!> so 10^k |v| = M 5^k 2^(b+k) is rounded to an integer by a shift; the
!> string is the one WRITE with ES(d+7).(d-1)E3 gives, character for
!> character, at a tenth of its cost.  Values it cannot scale exactly that
!> way (|v| < 1e-12 or >= 1e16 at d = 16, zero, subnormal) report .false.
!> and are left to the caller's WRITE.
module fast_format
  use, intrinsic :: iso_fortran_env, only: int64
  use kinds, only: dp
  implicit none
  private
  public :: format_es, format_es_exact, es_width, min_digits, max_digits

  integer, parameter :: min_digits = 3, max_digits = 12
  !> Powers of ten exact in a double.
  real(dp), parameter :: pow10(0:22) = [1.0e0_dp, 1.0e1_dp, 1.0e2_dp, 1.0e3_dp, 1.0e4_dp, 1.0e5_dp, 1.0e6_dp, &
    1.0e7_dp, 1.0e8_dp, 1.0e9_dp, 1.0e10_dp, 1.0e11_dp, 1.0e12_dp, 1.0e13_dp, 1.0e14_dp, 1.0e15_dp, 1.0e16_dp, &
    1.0e17_dp, 1.0e18_dp, 1.0e19_dp, 1.0e20_dp, 1.0e21_dp, 1.0e22_dp]

  !> The 128-bit integers of the exact conversion.
  integer, parameter :: i16 = selected_int_kind(38)
  !> The largest k of 5^k in the exact conversion (5^27 < 2^63: M 5^k < 2^116).
  integer, parameter :: max_k = 27
  integer :: k_
  !> 5^k, k = 0 .. max_k.
  integer(i16), parameter :: pow5(0:max_k) = [(5_i16**k_, k_ = 0, max_k)]

contains

  !> Characters of one value: d + 7 (sign, digit, point, d - 1 digits, E, sign, 3 digits).
  pure integer function es_width(d)
    integer, intent(in) :: d
    es_width = d + 7
  end function es_width

  !> v with d significant digits into s(1:d+7).
  pure subroutine format_es(v, d, s)
    real(dp), intent(in) :: v
    integer, intent(in) :: d
    character(len=*), intent(inout) :: s
    integer(int64) :: m, top
    integer :: e
    real(dp) :: a
    a = abs(v)
    top = 10_int64**d
    if (a > 0.0_dp) then
      e = floor(log10(a))
      m = nint(scaled(a, d - 1 - e), int64)
      if (m >= top) then                       ! log10 rounded up to the next decade, or 9.99.. rounded up
        e = e + 1
        m = nint(scaled(a, d - 1 - e), int64)
      else if (m < top/10) then
        e = e - 1
        m = nint(scaled(a, d - 1 - e), int64)
      end if
      if (m >= top) then                       ! 9.999..5 -> 10.00: one more decade
        m = m/10
        e = e + 1
      end if
    else
      e = 0
      m = 0
    end if
    call write_es(v < 0.0_dp, m, e, d, s)
  end subroutine format_es

  !> The string of the d-digit mantissa m (10^(d-1) <= m < 10^d, or 0) and
  !> decimal exponent e, with a minus sign if negative, into s(1:d+7).
  pure subroutine write_es(negative, m, e, d, s)
    logical, intent(in) :: negative
    integer(int64), intent(in) :: m
    integer, intent(in) :: e, d
    character(len=*), intent(inout) :: s
    integer(int64) :: r
    integer :: i, ae
    s(1:1) = merge('-', ' ', negative)
    r = m
    do i = d + 2, 4, -1                        ! the d - 1 digits after the point, right to left
      s(i:i) = achar(48 + int(mod(r, 10_int64)))
      r = r/10
    end do
    s(2:3) = achar(48 + int(r))//'.'
    s(d + 3:d + 4) = 'E'//merge('-', '+', e < 0)
    ae = abs(e)
    do i = d + 7, d + 5, -1
      s(i:i) = achar(48 + mod(ae, 10))
      ae = ae/10
    end do
  end subroutine write_es

  !> v with d significant digits (d <= 17) into s(1:d+7), correctly
  !> rounded (ties to even); done = .false. (s untouched) where the exact
  !> scaling does not apply (see the module's description).
  pure subroutine format_es_exact(v, d, s, done)
    real(dp), intent(in) :: v
    integer, intent(in) :: d
    character(len=*), intent(inout) :: s
    logical, intent(out) :: done
    integer(int64) :: mant
    integer(i16) :: top, n
    integer :: e, b, tries
    real(dp) :: a
    logical :: ok
    done = .false.
    a = abs(v)
    if (.not. (a >= tiny(1.0_dp) .and. a <= huge(1.0_dp))) return
    mant = int(scale(fraction(a), digits(a)), int64)     ! a = mant 2^b exactly
    b = exponent(a) - digits(a)
    top = shiftl(pow5(d), d)                   ! 10^d
    e = floor(log10(a))
    do tries = 1, 3
      call scaled_exact(mant, b, d - 1 - e, n, ok)
      if (.not. ok) return
      if (n >= top) then
        if (n == top) then                     ! 9.99..5 rounded up to the next decade
          n = top/10
          e = e + 1
          exit
        end if
        e = e + 1
      else if (n < top/10) then
        e = e - 1
      else
        exit
      end if
    end do
    if (n >= top .or. n < top/10) return
    call write_es(v < 0.0_dp, int(n, int64), e, d, s)
    done = .true.
  end subroutine format_es_exact

  !> n = mant 2^b 10^k rounded to the nearest integer, ties to even, for
  !> 0 <= k <= max_k; .false. outside that range or where n would not fit.
  pure subroutine scaled_exact(mant, b, k, n, ok)
    integer(int64), intent(in) :: mant
    integer, intent(in) :: b, k
    integer(i16), intent(out) :: n
    logical, intent(out) :: ok
    integer(i16) :: x, rest, half
    integer :: sh
    ok = .false.
    n = 0
    if (k < 0 .or. k > max_k) return
    x = int(mant, i16)*pow5(k)                 ! < 2^53 5^27 < 2^116
    sh = b + k                                 ! n = x 2^sh
    if (sh >= 0) then
      if (sh > 10) return                      ! far above any d-digit integer
      n = shiftl(x, sh)
    else
      sh = -sh
      if (sh > 120) return
      n = shifta(x, sh)
      rest = x - shiftl(n, sh)
      half = shiftl(1_i16, sh - 1)
      if (rest > half .or. (rest == half .and. btest(n, 0))) n = n + 1
    end if
    ok = .true.
  end subroutine scaled_exact

  !> a 10^k without overflow or loss for |k| up to ~650 (tabulated powers).
  pure real(dp) function scaled(a, k) result(x)
    real(dp), intent(in) :: a
    integer, intent(in) :: k
    integer :: r
    x = a
    r = k
    do while (r > 22)
      x = x*pow10(22)
      r = r - 22
    end do
    do while (r < -22)
      x = x/pow10(22)
      r = r + 22
    end do
    if (r >= 0) then
      x = x*pow10(r)
    else
      x = x/pow10(-r)
    end if
  end function scaled
end module fast_format
