!> DLSODE's Newton (chord) iteration matrix P = I - h*el0*J, in our code: the
!> contracts of ODEPACK's DPREPJ (form and factor P at the predicted y) and
!> DSOLSY (solve P x = b in place), which DSTODE calls through the external
!> names `dprepj` and `dsolsy` (src/ode/odepack_hooks.f90).  The two ODEPACK
!> files are not compiled (Makefile ODEPACK_FILES); DSTODE, DLSODE and the rest
!> are unchanged.
!>
!> The system may shorten DLSODE's Jacobian age limit MSBP (steps between
!> Jacobians, DLSODE's 20: `jacobian_steps`); this routine sets it.  A system
!> whose Newton matrix ages at a rate that depends on the problem (the
!> mechanism model's turns with the links, and turns out of date faster the
!> finer the mesh) asks instead for a bound on the chord iteration's
!> contraction factor (`jacobian_contraction`): every second and later
!> corrector iteration measures the factor theta = |dx_m| / |dx_m-1| (DSTODE's
!> weighted norm), theta / age estimates its growth per step of age (it grows
!> linearly with the age of the matrix; doc/transient.md), and MSBP becomes
!> the age at which the estimate reaches the bound, between 2 and
!> `jacobian_steps`.  Re-forming the matrix before the iteration fails saves
!> the failed iterations, the retry and the lower BDF order that follow one.
!>
!> Routes, by what lsode_solver set up:
!> - the model's own Newton matrix (lsode_solver's `active_newton_is_model`):
!>   the system factors and solves P in its own structure (for the mechanism
!>   model the banded N x N elimination of the 2N x 2N P, doc/transient.md);
!>   DLSODE sees MITER = 3 only so that WM is N + 2 long;
!> - MITER = 1, 2: dense J from the user's JAC or by forward differences, dense LU;
!> - MITER = 4, 5: banded J from JAC or by grouped forward differences
!>   (Curtis, Powell & Reid 1974), banded LU.
!> WM(1) holds sqrt(uround) (set by DLSODE), WM(3:) the factored matrix in
!> LAPACK's dense or general band layout, IWM(1:2) = ML, MU, IWM(21:) pivots.
!> Difference increments as documented for DLSODE: r_j = max(sqrt(uround)
!> |y_j|, r0 / ewt_j), r0 = 1000 |h| uround N ||f||_wrms (ewt holds the
!> reciprocal weights).
module lsode_newton
  use kinds, only: dp
  use error_status, only: error_t
  use linalg, only: lu_factor, lu_solve, band_lu_factor, band_lu_solve
  use lsode_solver, only: active, active_newton_is_model, rhs_f77, jac_f77
  use dlsode_state, only: h, el0, tn, uround, n, miter, nje, nfe, ierpj, iersl, jcur, msbp, nst, nslp, &
                          lewt, lwm, crate
  implicit none
  private
  public :: prepare_newton_matrix, solve_newton_matrix

  ! The adaptive age limit (one integration at a time: DLSODE is not re-entrant).
  real(dp), save :: theta_bound = 0.0_dp     !< the system's jacobian_contraction (0: off)
  integer, save :: longest_age = 0            !< the system's jacobian_steps
  real(dp), save :: growth = 0.0_dp           !< contraction factor per step of age, running estimate
  real(dp), save :: fresh = 0.0_dp            !< contraction factor of a matrix of the current step, running estimate
  logical, save :: just_formed = .false.      !< a matrix was formed since the last solve
  real(dp), save :: last_norm = 0.0_dp        !< weighted norm of the previous correction
  real(dp), save :: last_tn = 0.0_dp          !< ... and the time, step count and matrix it belonged to
  integer, save :: last_nst = -1, last_nje = -1
  !> DSTODE's contraction estimate CRATE for a matrix just formed, at least:
  !> DLSODE puts 0.7, so that a step right after a new matrix needs a second
  !> iteration whenever the first correction is not already below the test;
  !> a measured estimate (`fresh`) replaces it, not below this floor.
  real(dp), parameter :: fresh_floor = 0.1_dp

contains

  !> DPREPJ's contract: NJE + 1, JCUR = 1, IERPJ = 0 (1 when P is singular
  !> or the model stopped: DSTODE then retries with a smaller step and gives up
  !> after MXNCF tries); NFE counts difference quotients.
  subroutine prepare_newton_matrix(neq, y, ewt, ftem, savf, wm, iwm, f, jac)
    integer, intent(in) :: neq(*)
    real(dp), intent(inout) :: y(*), ftem(*), wm(*)
    real(dp), intent(in) :: ewt(*), savf(*)
    integer, intent(inout) :: iwm(*)
    procedure(rhs_f77) :: f
    procedure(jac_f77) :: jac
    logical :: ok
    integer :: steps
    nje = nje + 1
    ierpj = 0
    jcur = 1
    steps = active%jacobian_steps          ! DLSODE resets MSBP to 20 for every new problem
    if (steps > 0) msbp = steps
    longest_age = merge(steps, 20, steps > 0)
    theta_bound = active%jacobian_contraction
    if (nst == 0) then                       ! a new problem
      growth = 0.0_dp
      fresh = 0.0_dp
    end if
    just_formed = .true.
    if (theta_bound > 0.0_dp .and. growth > 0.0_dp) msbp = age_limit()
    if (active_newton_is_model) then
      call active%newton_factor(tn, y(1:n), h*el0, ok)
    else
      select case (miter)
      case (1, 2)
        call dense_matrix(neq, n, y, ewt, ftem, savf, wm(1), wm(3), iwm(21), f, jac, ok)
      case (4, 5)
        call band_matrix(neq, n, iwm(1), iwm(2), y, ewt, ftem, savf, wm(1), wm(3), iwm(21), f, jac, ok)
      case default
        ok = .false.          ! MITER = 3 (diagonal J) is not offered by lsode_solver
      end select
    end if
    if (.not. ok) ierpj = 1
  end subroutine prepare_newton_matrix

  !> DSOLSY's contract: x := P^-1 x, IERSL = 0.  A failure is reported as
  !> IERSL = 1 (recoverable: DSTODE re-forms P or cuts the step and gives up
  !> after MXNCF tries, ISTATE = -5), never IERSL < 0: DSTODE turns that into
  !> KFLAG = -3, which DLSODE does not handle (it retries the step forever).
  subroutine solve_newton_matrix(wm, iwm, x)
    real(dp), intent(in) :: wm(*)
    integer, intent(in) :: iwm(*)
    real(dp), intent(inout) :: x(*)
    iersl = 0
    if (active_newton_is_model) then
      call active%newton_solve(x(1:n))
      if (active%err%failed()) iersl = 1      ! the model stopped (integrate_to reports why)
    else
      select case (miter)
      case (1, 2)
        call dense_solve(n, wm(3), iwm(21), x)
      case (4, 5)
        call band_solve(n, iwm(1), iwm(2), wm(3), iwm(21), x)
      case default
        iersl = 1
      end select
    end if
    if (theta_bound > 0.0_dp .and. iersl == 0) then
      ! DSTODE has just put CRATE = 0.7 for a new matrix: our estimate instead
      if (just_formed) crate = max(fresh_floor, fresh)
      call note_contraction(wm, x)
    end if
    just_formed = .false.
  end subroutine solve_newton_matrix

  !> After a corrector solve: when it is the second or a later iteration of
  !> the step with the same matrix, theta = |x| / |previous x| (DSTODE's
  !> weighted RMS norm; EWT holds the reciprocal weights and lies after WM in
  !> DLSODE's RWORK) updates the estimate for a matrix of this age (running
  !> means, weight 0.3 on the new value): `fresh` at age 0 (NST - NSLP), the
  !> growth theta / age at age 1 and more; MSBP follows the growth for the
  !> decision at the next step.
  subroutine note_contraction(wm, x)
    real(dp), intent(in) :: wm(*), x(*)
    real(dp) :: norm, theta
    integer :: age
    norm = sqrt(sum((x(1:n)*wm(lewt - lwm + 1:lewt - lwm + n))**2)/n)
    age = nst - nslp
    if (nst == last_nst .and. nje == last_nje .and. .not. (tn < last_tn .or. tn > last_tn) .and. &
        last_norm > 0.0_dp) then
      theta = min(norm/last_norm, 1.0_dp)
      if (age == 0) then
        fresh = running(fresh, theta)
      else
        growth = running(growth, theta/age)
        msbp = age_limit()
      end if
    end if
    last_norm = norm
    last_tn = tn
    last_nst = nst
    last_nje = nje
  end subroutine note_contraction

  pure real(dp) function running(mean, value)
    real(dp), intent(in) :: mean, value
    running = value
    if (mean > 0.0_dp) running = 0.7_dp*mean + 0.3_dp*value
  end function running

  !> The age (steps) at which the estimated contraction factor reaches the
  !> bound, in [2, longest_age] (2: a measurement needs a matrix a step old).
  integer function age_limit() result(steps)
    if (growth*longest_age <= theta_bound) then
      steps = longest_age                    ! (also growth = 0: a step that needed no correction)
    else
      steps = max(2, int(theta_bound/growth))
    end if
  end function age_limit

  ! ------------------------------------------------------------------ dense

  subroutine dense_matrix(neq, nn, y, ewt, ftem, savf, srur, p, ipiv, f, jac, ok)
    integer, intent(in) :: neq(*), nn
    real(dp), intent(inout) :: y(nn), ftem(nn)
    real(dp), intent(in) :: ewt(nn), savf(nn), srur
    real(dp), intent(out) :: p(nn, nn)
    integer, intent(out) :: ipiv(nn)
    procedure(rhs_f77) :: f
    procedure(jac_f77) :: jac
    logical, intent(out) :: ok
    type(error_t) :: err
    real(dp) :: r0, yj, r
    integer :: j
    p = 0.0_dp
    if (miter == 1) then
      call jac(neq, tn, y, 0, 0, p, nn)
    else
      r0 = increment_floor(nn, savf, ewt)
      do j = 1, nn
        yj = y(j)
        r = max(srur*abs(yj), r0/ewt(j))
        y(j) = yj + r
        call f(neq, tn, y, ftem)
        p(:, j) = (ftem - savf)/r
        y(j) = yj
      end do
      nfe = nfe + nn
    end if
    p = -(h*el0)*p
    do j = 1, nn
      p(j, j) = p(j, j) + 1.0_dp
    end do
    call lu_factor(p, ipiv, err)
    ok = .not. err%failed()
  end subroutine dense_matrix

  subroutine dense_solve(nn, p, ipiv, x)
    integer, intent(in) :: nn
    real(dp), intent(in) :: p(nn, nn)
    integer, intent(in) :: ipiv(nn)
    real(dp), intent(inout) :: x(nn)
    type(error_t) :: err
    call lu_solve(p, ipiv, x, err)
    if (err%failed()) iersl = 1
  end subroutine dense_solve

  ! ------------------------------------------------------------------ banded

  !> P in LAPACK general band storage ab(ml + mu + 1 + i - j, j) (the first ml
  !> rows are DGBTRF's fill-in); JAC writes its band at row ml + 1.
  subroutine band_matrix(neq, nn, ml, mu, y, ewt, ftem, savf, srur, ab, ipiv, f, jac, ok)
    integer, intent(in) :: neq(*), nn, ml, mu
    real(dp), intent(inout) :: y(nn), ftem(nn)
    real(dp), intent(in) :: ewt(nn), savf(nn), srur
    real(dp), intent(out) :: ab(2*ml + mu + 1, nn)
    integer, intent(out) :: ipiv(nn)
    procedure(rhs_f77) :: f
    procedure(jac_f77) :: jac
    logical, intent(out) :: ok
    type(error_t) :: err
    real(dp) :: r0, inc(nn), y0(nn)
    integer :: j, j0, width, d
    d = ml + mu + 1                          ! row of the diagonal
    ab = 0.0_dp
    if (miter == 4) then
      call jac(neq, tn, y, ml, mu, ab(ml + 1, 1), 2*ml + mu + 1)
    else
      ! columns j0, j0 + width, ... share no row of the band: one RHS per group
      width = ml + mu + 1
      r0 = increment_floor(nn, savf, ewt)
      y0 = y(1:nn)
      inc = max(srur*abs(y0), r0/ewt(1:nn))
      do j0 = 1, min(width, nn)
        y(j0:nn:width) = y0(j0:nn:width) + inc(j0:nn:width)
        call f(neq, tn, y, ftem)
        y(j0:nn:width) = y0(j0:nn:width)
        do j = j0, nn, width
          ab(d + max(1, j - mu) - j:d + min(nn, j + ml) - j, j) = &
            (ftem(max(1, j - mu):min(nn, j + ml)) - savf(max(1, j - mu):min(nn, j + ml)))/inc(j)
        end do
      end do
      nfe = nfe + min(width, nn)
    end if
    ab(ml + 1:, :) = -(h*el0)*ab(ml + 1:, :)
    ab(d, :) = ab(d, :) + 1.0_dp
    call band_lu_factor(ab, ml, mu, ipiv, err)
    ok = .not. err%failed()
  end subroutine band_matrix

  subroutine band_solve(nn, ml, mu, ab, ipiv, x)
    integer, intent(in) :: nn, ml, mu
    real(dp), intent(in) :: ab(2*ml + mu + 1, nn)
    integer, intent(in) :: ipiv(nn)
    real(dp), intent(inout) :: x(nn)
    type(error_t) :: err
    call band_lu_solve(ab, ml, mu, ipiv, x, err)
    if (err%failed()) iersl = 1
  end subroutine band_solve

  !> r0 = 1000 |h| uround N ||f||_wrms, or 1 when f vanishes.
  real(dp) function increment_floor(nn, savf, ewt) result(r0)
    integer, intent(in) :: nn
    real(dp), intent(in) :: savf(nn), ewt(nn)
    r0 = 1000.0_dp*abs(h)*uround*nn*sqrt(sum((savf*ewt)**2)/nn)
    if (.not. r0 > 0.0_dp) r0 = 1.0_dp
  end function increment_floor
end module lsode_newton
