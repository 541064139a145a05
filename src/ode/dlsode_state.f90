!> DLSODE's COMMON block /DLS001/, declared once for our replacements of its
!> linear-algebra routines (lsode_newton).  The layout is DLSODE's, as
!> documented in dlsode.f (218 double precision then 37 integer words); only
!> the entries our routines read or set are public.  The names are DLSODE's.
module dlsode_state
  use kinds, only: dp
  implicit none
  private
  public :: h, el0, tn, uround, n, miter, nje, nfe, ierpj, iersl, jcur, msbp, nst, nslp, lewt, lwm, crate

  real(dp) :: conit, crate, el(13), elco(13, 12), hold, rmax, tesco(3, 12), &
              ccmax, el0, h, hmin, hmxi, hu, rc, tn, uround
  integer :: illin, init, lyh, lewt, lacor, lsavf, lwm, liwm, mxstep, mxhnil, nhnil, ntrep, nslast, &
             nyh, ialth, ipup, lmax, meo, nqnyh, nslp, &
             icf, ierpj, iersl, jcur, jstart, kflag, l, meth, miter, maxord, maxcor, msbp, mxncf, &
             n, nq, nst, nfe, nje, nqu
  common /dls001/ conit, crate, el, elco, hold, rmax, tesco, ccmax, el0, h, hmin, hmxi, hu, rc, tn, uround, &
                  illin, init, lyh, lewt, lacor, lsavf, lwm, liwm, mxstep, mxhnil, nhnil, ntrep, nslast, &
                  nyh, ialth, ipup, lmax, meo, nqnyh, nslp, &
                  icf, ierpj, iersl, jcur, jstart, kflag, l, meth, miter, maxord, maxcor, msbp, mxncf, &
                  n, nq, nst, nfe, nje, nqu
end module dlsode_state
