! The routines ODEPACK documents as machine-dependent or user-replaceable, and
! our replacements of its Newton-matrix routines DPREPJ and DSOLSY.
! They are external procedures (not module procedures) because the legacy code
! calls them by their F77 names.

!> Machine constants for double precision, from Fortran intrinsics.
!> D1MACH(1) smallest positive normal, (2) largest, (3) b**(-t), (4) b**(1-t),
!> (5) log10(b).
function d1mach(i) result(value)
  use kinds, only: dp
  implicit none
  integer, intent(in) :: i
  real(dp) :: value
  select case (i)
  case (1)
    value = tiny(1.0_dp)
  case (2)
    value = huge(1.0_dp)
  case (3)
    value = epsilon(1.0_dp)/radix(1.0_dp)
  case (4)
    value = epsilon(1.0_dp)
  case (5)
    value = log10(real(radix(1.0_dp), dp))
  case default
    value = 0.0_dp
  end select
end function d1mach

!> ODEPACK's message handler, replaced so that LSODE's messages are routed into
!> flexmech's diagnostics (lsode_messages) rather than printed.  LEVEL = 2
!> (fatal in the original) cannot be continued from: it stops the program.
subroutine xerrwd(msg, nmes, nerr, level, ni, i1, i2, nr, r1, r2)
  use kinds, only: dp
  use lsode_messages, only: record_lsode_message
  implicit none
  integer, intent(in) :: nmes, nerr, level, ni, i1, i2, nr
  character(len=*), intent(in) :: msg
  real(dp), intent(in) :: r1, r2
  character(len=512) :: line
  integer :: n
  n = max(0, min(nmes, len(msg)))
  line = msg(1:n)
  if (ni >= 1) write(line, '(a,a,i0)') trim(line), ' I1=', i1
  if (ni >= 2) write(line, '(a,a,i0)') trim(line), ' I2=', i2
  if (nr >= 1) write(line, '(a,a,es14.6e3)') trim(line), ' R1=', r1
  if (nr >= 2) write(line, '(a,a,es14.6e3)') trim(line), ' R2=', r2
  call record_lsode_message(line)
  if (level >= 2) then
    write(*, '(a,i0,a)') 'flexmech: fatal ODEPACK error ', nerr, ': '//trim(line)
    error stop 3
  end if
end subroutine xerrwd

!> DLSODE's Newton matrix routines, replaced (module lsode_newton): form and
!> factor P = I - h*el0*J.  Arguments as DSTODE passes them (YH and NYH unused).
subroutine dprepj(neq, y, yh, nyh, ewt, ftem, savf, wm, iwm, f, jac)
  use kinds, only: dp
  use lsode_newton, only: prepare_newton_matrix
  use lsode_solver, only: rhs_f77, jac_f77
  implicit none
  integer, intent(in) :: neq(*), nyh
  real(dp), intent(inout) :: y(*), ftem(*), wm(*)
  real(dp), intent(in) :: yh(nyh, *), ewt(*), savf(*)
  integer, intent(inout) :: iwm(*)
  procedure(rhs_f77) :: f
  procedure(jac_f77) :: jac
  associate (unused_yh => yh(1, 1))
  end associate
  call prepare_newton_matrix(neq, y, ewt, ftem, savf, wm, iwm, f, jac)
end subroutine dprepj

!> Solve P x = b in place with the P of the last dprepj (TEM unused).
subroutine dsolsy(wm, iwm, x, tem)
  use kinds, only: dp
  use lsode_newton, only: solve_newton_matrix
  implicit none
  real(dp), intent(in) :: wm(*), tem(*)
  integer, intent(in) :: iwm(*)
  real(dp), intent(inout) :: x(*)
  associate (unused_tem => tem(1))
  end associate
  call solve_newton_matrix(wm, iwm, x)
end subroutine dsolsy
