!> Powell's conjugate-direction method (Powell 1964, with the usual rule for
!> discarding the direction of largest decrease), our own implementation.
!>
!> GNLC uses it as the fallback for the multiplier equations (B11): when
!> Newton-Raphson fails, H(lambda) = Sum g_i(lambda)^2 is minimised without
!> derivatives (Boston et al.: "Powell's method was used, but any available
!> technique could be applied").
!>
!> A function to minimise extends `powell_function_t` and implements `value`.
!> A point where the function is undefined should return a large finite value
!> (not Inf or NaN: the debug build traps invalid operations).
module powell_minimizer
  use kinds, only: dp
  implicit none
  private
  public :: powell_function_t, powell_options_t, powell_result_t, powell_minimize

  type, abstract :: powell_function_t
  contains
    procedure(value_interface), deferred :: value
  end type powell_function_t

  abstract interface
    function value_interface(self, x) result(f)
      import :: powell_function_t, dp
      class(powell_function_t), intent(inout) :: self
      real(dp), intent(in) :: x(:)
      real(dp) :: f
    end function value_interface
  end interface

  type :: powell_options_t
    integer :: max_iter = 200            !< outer iterations (one sweep over all directions each)
    integer :: max_evals = 20000         !< function evaluations in all
    real(dp) :: ftol = 1.0e-14_dp        !< relative decrease per sweep below which we stop
    real(dp) :: f_target = -huge(1.0_dp) !< stop as soon as f <= f_target (e.g. a root of H found)
    real(dp) :: initial_step = 1.0_dp    !< length of the first trial step along each direction
  end type powell_options_t

  type :: powell_result_t
    real(dp) :: f = 0.0_dp
    integer :: iterations = 0
    integer :: evaluations = 0
    logical :: converged = .false.       !< stopped on ftol or f_target, not on a limit
  end type powell_result_t

  real(dp), parameter :: golden = 1.618033988749895_dp   ! (1 + sqrt 5)/2
  real(dp), parameter :: cgold = 0.3819660112501051_dp   ! 2 - golden
  real(dp), parameter :: tiny_f = 1.0e-300_dp

contains

  !> Minimise fun over x (in: start, out: best point).  Directions start as
  !> the coordinate axes scaled by opts%initial_step.
  subroutine powell_minimize(fun, x, opts, res)
    class(powell_function_t), intent(inout) :: fun
    real(dp), intent(inout) :: x(:)
    type(powell_options_t), intent(in) :: opts
    type(powell_result_t), intent(out) :: res
    real(dp), allocatable :: u(:, :), x0(:), xe(:), d(:)
    real(dp) :: f, f0, fe, fprev, big, t
    integer :: n, i, ibig, iter

    n = size(x)
    allocate(u(n, n), x0(n), xe(n), d(n))
    u = 0.0_dp
    do i = 1, n
      u(i, i) = opts%initial_step
    end do
    f = fun%value(x)
    res%evaluations = 1
    if (f <= opts%f_target) then
      res%f = f
      res%converged = .true.
      return
    end if

    do iter = 1, opts%max_iter
      res%iterations = iter
      x0 = x
      f0 = f
      big = 0.0_dp
      ibig = 1
      do i = 1, n
        fprev = f
        call line_minimize(fun, x, u(:, i), f, res%evaluations)
        if (fprev - f > big) then
          big = fprev - f
          ibig = i
        end if
      end do
      if (f <= opts%f_target .or. 2.0_dp*(f0 - f) <= opts%ftol*(abs(f0) + abs(f)) + tiny_f) then
        res%converged = .true.
        exit
      end if
      if (res%evaluations >= opts%max_evals) exit
      ! Extrapolate along the net direction of the sweep; adopt it as a new
      ! conjugate direction unless that would make the set degenerate (Powell 1964).
      d = x - x0
      xe = x + d
      fe = fun%value(xe)
      res%evaluations = res%evaluations + 1
      if (fe < f0) then
        t = 2.0_dp*(f0 - 2.0_dp*f + fe)*(f0 - f - big)**2 - big*(f0 - fe)**2
        if (t < 0.0_dp) then
          call line_minimize(fun, x, d, f, res%evaluations)
          u(:, ibig) = u(:, n)
          u(:, n) = d
        end if
      end if
    end do
    res%f = f
  end subroutine powell_minimize

  !> Minimise f(x + a d) over a; on exit x = x + a* d and f = f(x).  The
  !> minimum is bracketed by golden-ratio expansion, then located by Brent's
  !> combination of golden sections and parabolic interpolation.
  subroutine line_minimize(fun, x, d, f, nev)
    class(powell_function_t), intent(inout) :: fun
    real(dp), intent(inout) :: x(:), f
    real(dp), intent(in) :: d(:)
    integer, intent(inout) :: nev
    real(dp) :: a, b, c, fa, fb, fc, tmp, amin, fmin
    integer :: k
    if (maxval(abs(d)) <= 0.0_dp) return
    a = 0.0_dp
    fa = f
    b = 1.0_dp
    fb = along(fun, x, d, b, nev)
    if (fb > fa) then       ! walk downhill from b towards a and beyond
      tmp = a; a = b; b = tmp
      tmp = fa; fa = fb; fb = tmp
    end if
    c = b + golden*(b - a)
    fc = along(fun, x, d, c, nev)
    do k = 1, 80
      if (fc >= fb) exit
      a = b; fa = fb
      b = c; fb = fc
      c = b + golden*(b - a)
      fc = along(fun, x, d, c, nev)
    end do
    if (fc < fb) then       ! no bracket within the expansion limit: keep the best point
      amin = c
      fmin = fc
    else
      call brent(fun, x, d, nev, min(a, c), max(a, c), b, fb, amin, fmin)
    end if
    if (fmin < f) then
      x = x + amin*d
      f = fmin
    end if
  end subroutine line_minimize

  !> f(x + alpha d), counted in nev.
  real(dp) function along(fun, x, d, alpha, nev)
    class(powell_function_t), intent(inout) :: fun
    real(dp), intent(in) :: x(:), d(:), alpha
    integer, intent(inout) :: nev
    along = fun%value(x + alpha*d)
    nev = nev + 1
  end function along

  !> Brent's minimiser of f(x + a d) over a in [lo, hi], starting from the
  !> interior point xb (f = fxb there).
  subroutine brent(fun, x, d, nev, lo, hi, xb, fxb, xmin, fxmin)
    class(powell_function_t), intent(inout) :: fun
    real(dp), intent(in) :: x(:), d(:)
    integer, intent(inout) :: nev
    real(dp), intent(in) :: lo, hi, xb, fxb
    real(dp), intent(out) :: xmin, fxmin
    real(dp), parameter :: rel = 1.0e-10_dp, abs_tol = 1.0e-14_dp
    real(dp) :: aa, bb, v, w, xx, fv, fw, fx, e, dd, u, fu, xm, tol1, tol2, p, q, r
    integer :: it
    aa = lo; bb = hi
    xx = xb; w = xb; v = xb
    fx = fxb; fw = fxb; fv = fxb
    e = 0.0_dp
    dd = 0.0_dp
    do it = 1, 100
      xm = 0.5_dp*(aa + bb)
      tol1 = rel*abs(xx) + abs_tol
      tol2 = 2.0_dp*tol1
      if (abs(xx - xm) <= tol2 - 0.5_dp*(bb - aa)) exit
      if (abs(e) > tol1) then
        ! parabola through (v, w, x); accepted only if it falls inside the
        ! interval and moves less than half the step before last
        r = (xx - w)*(fx - fv)
        q = (xx - v)*(fx - fw)
        p = (xx - v)*q - (xx - w)*r
        q = 2.0_dp*(q - r)
        if (q > 0.0_dp) p = -p
        q = abs(q)
        if (abs(p) >= abs(0.5_dp*q*e) .or. p <= q*(aa - xx) .or. p >= q*(bb - xx)) then
          e = merge(aa - xx, bb - xx, xx >= xm)
          dd = cgold*e
        else
          e = dd
          dd = p/q
          u = xx + dd
          if (u - aa < tol2 .or. bb - u < tol2) dd = sign(tol1, xm - xx)
        end if
      else
        e = merge(aa - xx, bb - xx, xx >= xm)
        dd = cgold*e
      end if
      if (abs(dd) >= tol1) then
        u = xx + dd
      else
        u = xx + sign(tol1, dd)
      end if
      fu = along(fun, x, d, u, nev)
      if (fu <= fx) then
        if (u >= xx) then
          aa = xx
        else
          bb = xx
        end if
        v = w; fv = fw
        w = xx; fw = fx
        xx = u; fx = fu
      else
        if (u < xx) then
          aa = u
        else
          bb = u
        end if
        if (fu <= fw .or. abs(w - xx) <= 0.0_dp) then
          v = w; fv = fw
          w = u; fw = fu
        else if (fu <= fv .or. abs(v - xx) <= 0.0_dp .or. abs(v - w) <= 0.0_dp) then
          v = u; fv = fu
        end if
      end if
    end do
    xmin = xx
    fxmin = fx
  end subroutine brent
end module powell_minimizer
