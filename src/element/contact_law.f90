!> Continuous contact-force law of a journal in a bearing with clearance
!> (doc/clearance.md): Hertz-type normal force with hysteresis damping
!>
!>     F_n = K delta^n max(0, 1 + chi delta_dot / v_impact),   delta > 0,
!>
!> (delta the penetration, v_impact the approach speed at the start of the
!> contact), and optional Coulomb friction smoothed near zero sliding speed,
!>
!>     F_t = -mu F_n tanh(v_t / v_s).
!>
!> The hysteresis factor chi comes from the coefficient of restitution e:
!>  - 'lankarani_nikravesh' (Lankarani & Nikravesh 1990): chi = 3 (1 - e^2)/4,
!>    derived for e near 1 (the effective restitution is within 1e-3 of e
!>    for e >= 0.98 only; measured in the unit test);
!>  - 'flores' (Flores, Machado, Silva & Martins 2011): chi = 8 (1 - e)/(5 e);
!>  - 'calibrated': chi solved so that one impact of the law itself restores
!>    exactly e: the dimensionless impact u'' = -u^n max(0, 1 + chi u'),
!>    u(0) = 0, u'(0) = 1 depends on chi and n only (scale delta by
!>    v_impact T and time by T = (m v_impact^(1-n) / K)^(1/(n+1))), so
!>    e(chi) is universal and is inverted once per law by bisection.
!> The max(0, .) keeps the contact from pulling (no adhesion).
module contact_law
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  implicit none
  private
  public :: contact_law_t, contact_law_init, normal_force, friction_force, impact_restitution
  public :: law_names

  integer, parameter :: law_lankarani_nikravesh = 1, law_flores = 2, law_calibrated = 3
  character(len=20), parameter :: law_names(3) = [character(len=20) :: 'lankarani_nikravesh', 'flores', 'calibrated']

  type :: contact_law_t
    integer :: law = law_lankarani_nikravesh
    real(dp) :: stiffness = 0.0_dp       !< K (force / length^n)
    real(dp) :: exponent = 1.5_dp        !< n (Hertz: 1.5)
    real(dp) :: restitution = 1.0_dp     !< e, as given
    real(dp) :: chi = 0.0_dp             !< hysteresis factor
    real(dp) :: friction = 0.0_dp        !< Coulomb coefficient mu (0: no friction)
    real(dp) :: friction_speed = 1.0_dp  !< v_s of the tanh regularisation (length/s)
  end type contact_law_t

contains

  !> The law from its parameters; the hysteresis factor from e by the named law.
  subroutine contact_law_init(law, name, stiffness, exponent, restitution, friction, friction_speed, err)
    type(contact_law_t), intent(out) :: law
    character(len=*), intent(in) :: name
    real(dp), intent(in) :: stiffness, exponent, restitution, friction, friction_speed
    type(error_t), intent(inout) :: err
    law%law = findloc(law_names, name, dim=1)
    if (law%law == 0) then
      call err%set('contact law', 'unknown law '''//trim(name)//'''')
      return
    end if
    law = contact_law_t(law=law%law, stiffness=stiffness, exponent=exponent, restitution=restitution, &
                        friction=friction, friction_speed=friction_speed)
    select case (law%law)
    case (law_lankarani_nikravesh)
      law%chi = 0.75_dp*(1.0_dp - restitution**2)
    case (law_flores)
      if (.not. restitution > 0.0_dp) then
        call err%set('contact law', 'the Flores law needs a restitution coefficient > 0 (chi = 8(1-e)/(5e))')
        return
      end if
      law%chi = 1.6_dp*(1.0_dp - restitution)/restitution
    case (law_calibrated)
      law%chi = calibrated_chi(restitution, exponent, err)
    end select
  end subroutine contact_law_init

  !> Normal force and its derivatives by penetration and penetration rate;
  !> zero (and zero derivatives) out of contact.  v_impact > 0.
  pure subroutine normal_force(law, delta, delta_d, v_impact, f, df_ddelta, df_drate)
    type(contact_law_t), intent(in) :: law
    real(dp), intent(in) :: delta, delta_d, v_impact
    real(dp), intent(out) :: f, df_ddelta, df_drate
    real(dp) :: hertz, damp
    f = 0.0_dp
    df_ddelta = 0.0_dp
    df_drate = 0.0_dp
    if (.not. delta > 0.0_dp) return
    hertz = law%stiffness*delta**law%exponent
    damp = 1.0_dp + law%chi*delta_d/v_impact
    if (damp <= 0.0_dp) return
    f = hertz*damp
    df_ddelta = law%exponent*hertz/delta*damp
    df_drate = hertz*law%chi/v_impact
  end subroutine normal_force

  !> Tangential (friction) force for a normal force fn >= 0 and a sliding
  !> speed v_t, and its derivative by v_t.  tanh(v/v_s) reaches 0.995 of
  !> Coulomb's mu fn at 3 v_s and is smooth through v = 0 (no stick switch
  !> for the integrator to chatter on).
  pure subroutine friction_force(law, fn, v_t, ft, dft_dvt)
    type(contact_law_t), intent(in) :: law
    real(dp), intent(in) :: fn, v_t
    real(dp), intent(out) :: ft, dft_dvt
    real(dp) :: x
    ft = 0.0_dp
    dft_dvt = 0.0_dp
    if (.not. (law%friction > 0.0_dp .and. fn > 0.0_dp)) return
    x = v_t/law%friction_speed
    ft = -law%friction*fn*tanh(x)
    if (abs(x) < 20.0_dp) dft_dvt = -law%friction*fn/(law%friction_speed*cosh(x)**2)
  end subroutine friction_force

  !> Effective restitution of one impact of the law with hysteresis factor chi
  !> and exponent n: the dimensionless impact u'' = -u^n max(0, 1 + chi u'),
  !> u(0) = 0, u'(0) = 1, by classical Runge-Kutta with step h; the exit
  !> speed at u = 0 by cubic Hermite interpolation over the last step.
  !> The force is C1 at u = 0 for n > 1, so the step error is O(h^4) except
  !> over the entry and exit steps (about 1e-9 at h = 1e-3, n = 1.5).
  pure real(dp) function impact_restitution(chi, n, h) result(e)
    real(dp), intent(in) :: chi, n, h
    real(dp) :: u, v, un, vn, k(2, 4), t, s, a
    integer :: i
    u = 0.0_dp
    v = 1.0_dp
    t = 0.0_dp
    e = 0.0_dp
    do i = 1, 100000000
      k(:, 1) = rate(u, v)
      k(:, 2) = rate(u + 0.5_dp*h*k(1, 1), v + 0.5_dp*h*k(2, 1))
      k(:, 3) = rate(u + 0.5_dp*h*k(1, 2), v + 0.5_dp*h*k(2, 2))
      k(:, 4) = rate(u + h*k(1, 3), v + h*k(2, 3))
      un = u + h/6.0_dp*(k(1, 1) + 2.0_dp*k(1, 2) + 2.0_dp*k(1, 3) + k(1, 4))
      vn = v + h/6.0_dp*(k(2, 1) + 2.0_dp*k(2, 2) + 2.0_dp*k(2, 3) + k(2, 4))
      t = t + h
      if (un < 0.0_dp .and. i > 1) then
        ! root of the cubic Hermite u(s) on [0, 1] by bisection, then its slope
        s = exit_fraction(u, v*h, un, vn*h)
        a = hermite_slope(u, v*h, un, vn*h, s)/h
        e = -a
        return
      end if
      if (vn >= 0.0_dp .and. un <= 0.0_dp) return   ! stuck at u = 0: e = 0
      u = un
      v = vn
      if (t > 1.0e4_dp) then   ! a journal that never leaves (chi huge): no rebound
        e = max(0.0_dp, -v)
        return
      end if
    end do
  contains
    pure function rate(uu, vv) result(r)
      real(dp), intent(in) :: uu, vv
      real(dp) :: r(2)
      r(1) = vv
      r(2) = 0.0_dp
      if (uu > 0.0_dp) r(2) = -uu**n*max(0.0_dp, 1.0_dp + chi*vv)
    end function rate
  end function impact_restitution

  pure real(dp) function exit_fraction(u0, d0, u1, d1) result(s)
    real(dp), intent(in) :: u0, d0, u1, d1
    real(dp) :: lo, hi
    integer :: it
    lo = 0.0_dp
    hi = 1.0_dp
    do it = 1, 60
      s = 0.5_dp*(lo + hi)
      if (hermite_value(u0, d0, u1, d1, s) > 0.0_dp) then
        lo = s
      else
        hi = s
      end if
    end do
    s = 0.5_dp*(lo + hi)
  end function exit_fraction

  pure real(dp) function hermite_value(u0, d0, u1, d1, s) result(u)
    real(dp), intent(in) :: u0, d0, u1, d1, s
    u = (2*s**3 - 3*s**2 + 1)*u0 + (s**3 - 2*s**2 + s)*d0 + (-2*s**3 + 3*s**2)*u1 + (s**3 - s**2)*d1
  end function hermite_value

  pure real(dp) function hermite_slope(u0, d0, u1, d1, s) result(du)
    real(dp), intent(in) :: u0, d0, u1, d1, s
    du = (6*s**2 - 6*s)*u0 + (3*s**2 - 4*s + 1)*d0 + (-6*s**2 + 6*s)*u1 + (3*s**2 - 2*s)*d1
  end function hermite_slope

  !> chi with impact_restitution(chi, n) = e, by bisection (e decreases with
  !> chi; chi ~ 1/e for small e).  e in [0.01, 1].
  real(dp) function calibrated_chi(e, n, err) result(chi)
    real(dp), intent(in) :: e, n
    type(error_t), intent(inout) :: err
    real(dp), parameter :: h = 1.0e-3_dp
    real(dp) :: lo, hi
    integer :: it
    chi = 0.0_dp
    if (.not. (e >= 0.01_dp .and. e <= 1.0_dp)) then
      call err%set('contact law', 'the calibrated law needs 0.01 <= e <= 1, got '//str(e))
      return
    end if
    if (e >= 1.0_dp) return
    lo = 0.0_dp
    hi = 1.0_dp
    do while (impact_restitution(hi, n, h) > e)
      lo = hi
      hi = 2.0_dp*hi
    end do
    do it = 1, 48
      chi = 0.5_dp*(lo + hi)
      if (impact_restitution(chi, n, h) > e) then
        lo = chi
      else
        hi = chi
      end if
      if (hi - lo <= 1.0e-10_dp*hi) exit
    end do
    chi = 0.5_dp*(lo + hi)
  end function calibrated_chi
end module contact_law
