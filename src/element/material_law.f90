!> Ramberg-Osgood-type material of Tennant (T6, T7) and Kear (K12, K13):
!>
!>     sigma = E1 eps - E2 eps |eps|^(m-1)                         (K13)
!>     W(eps) = E1 eps^2/2 - E2 |eps|^(m+1)/(m+1)     (strain-energy density)
!>
!> and its integral through the depth t of a rectangular b x t section with the
!> fibre strain eps = eps_n - y kappa (K14), which gives the section resultants
!> used by the element: energy per unit length, axial force N, bending moment
!> M = dW/dkappa and their tangent D = d(N,M)/d(eps_n,kappa) (K16, K17).
!>
!> Thickness integration: for odd integer m the integrand is a polynomial and
!> the integral is done in closed form (binomial expansion of the fibre
!> strain, the 0/0-free form of (K16)); for any other m > 1 by the exact
!> antiderivative of |eps|^(m+1) (the (K16) form, generalised), switching to
!> a 16-point Gauss rule where that form would cancel (small curvature);
!> both are accurate to round-off (doc/element.md).
module material_law
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use quadrature, only: gauss_legendre
  implicit none
  private
  public :: ramberg_osgood_t, section_resultants_t
  public :: validate_material, ro_stress, ro_tangent, ro_energy_density
  public :: peak_strain, peak_stress, has_odd_integer_exponent
  public :: section_response, section_response_quadrature

  !> Material constants.  E2 = 0 is a linear-elastic material.
  type :: ramberg_osgood_t
    real(dp) :: e1 = 0.0_dp     !< initial modulus (T's A), psi
    real(dp) :: e2 = 0.0_dp     !< nonlinear coefficient (T's B), psi
    real(dp) :: m = 3.0_dp      !< exponent (K15: m = 3)
    real(dp) :: rho = 0.0_dp    !< mass density, lb-s^2/in^4
  end type ramberg_osgood_t

  !> Resultants of a b x t section per unit length of beam.
  type :: section_resultants_t
    real(dp) :: energy = 0.0_dp         !< integral of W over the section
    real(dp) :: axial_force = 0.0_dp    !< N = d energy / d eps_n
    real(dp) :: moment = 0.0_dp         !< M = d energy / d kappa = -integral(y sigma dA)
    real(dp) :: tangent(2, 2) = 0.0_dp  !< d(N, M)/d(eps_n, kappa), symmetric
  end type section_resultants_t

  integer, parameter :: n_smooth_gauss = 16    !< non-odd m, strain of one sign (power_mean)

contains

  !> Check the constants; the message names the bad value.
  pure subroutine validate_material(mat, err)
    type(ramberg_osgood_t), intent(in) :: mat
    type(error_t), intent(inout) :: err
    if (.not. (mat%e1 > 0.0_dp)) then
      call err%set('material', 'E1 must be positive, got '//str(mat%e1))
    else if (.not. (mat%e2 >= 0.0_dp)) then
      call err%set('material', 'E2 must be >= 0, got '//str(mat%e2))
    else if (.not. (mat%m > 1.0_dp)) then
      call err%set('material', 'exponent m must be > 1 (the law needs a peak), got '//str(mat%m))
    else if (.not. (mat%rho >= 0.0_dp)) then
      call err%set('material', 'density rho must be >= 0, got '//str(mat%rho))
    end if
  end subroutine validate_material

  !> True when m is an odd integer (then |eps|^(m-1) eps = eps^m, a polynomial).
  logical pure function has_odd_integer_exponent(mat)
    type(ramberg_osgood_t), intent(in) :: mat
    has_odd_integer_exponent = abs(mat%m - anint(mat%m)) <= 8.0_dp*epsilon(1.0_dp)*mat%m &
                               .and. mod(nint(mat%m), 2) == 1
  end function has_odd_integer_exponent

  !> sigma(eps), Kear eq. (K13).  E2 = 0 (the material effect off) is the
  !> linear law, without the power (it was 5 % of a linear run's CPU).
  elemental real(dp) function ro_stress(mat, eps) result(sigma)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: eps
    sigma = mat%e1*eps
    if (mat%e2 > 0.0_dp) sigma = sigma - mat%e2*eps*abs(eps)**(mat%m - 1.0_dp)
  end function ro_stress

  !> d sigma / d eps = E1 - m E2 |eps|^(m-1).
  elemental real(dp) function ro_tangent(mat, eps) result(et)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: eps
    et = mat%e1
    if (mat%e2 > 0.0_dp) et = et - mat%m*mat%e2*abs(eps)**(mat%m - 1.0_dp)
  end function ro_tangent

  !> W(eps) = integral_0^eps sigma = E1 eps^2/2 - E2 |eps|^(m+1)/(m+1).
  elemental real(dp) function ro_energy_density(mat, eps) result(w)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: eps
    w = 0.5_dp*mat%e1*eps*eps
    if (mat%e2 > 0.0_dp) w = w - mat%e2*abs(eps)**(mat%m + 1.0_dp)/(mat%m + 1.0_dp)
  end function ro_energy_density

  !> eps* = (E1/(m E2))^(1/(m-1)), where d sigma/d eps = 0; huge() if E2 = 0.
  !> In logarithms where E1/(m E2) would overflow (fuzz seed 9: a tracing
  !> constant d_k = 4.9e-324 made E2 subnormal and trapped).
  pure real(dp) function peak_strain(mat)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp) :: log_ratio
    if (.not. mat%e2 > 0.0_dp) then
      peak_strain = huge(1.0_dp)
      return
    end if
    log_ratio = log(mat%e1) - log(mat%m) - log(mat%e2)
    if (log_ratio < log(huge(1.0_dp)) - 1.0_dp) then
      peak_strain = (mat%e1/(mat%m*mat%e2))**(1.0_dp/(mat%m - 1.0_dp))
    else if (log_ratio/(mat%m - 1.0_dp) < log(huge(1.0_dp)) - 1.0_dp) then
      peak_strain = exp(log_ratio/(mat%m - 1.0_dp))
    else
      peak_strain = huge(1.0_dp)
    end if
  end function peak_strain

  !> sigma(eps*) = E1 eps* (1 - 1/m); huge() if E2 = 0.
  pure real(dp) function peak_stress(mat)
    type(ramberg_osgood_t), intent(in) :: mat
    if (mat%e2 > 0.0_dp) then
      peak_stress = ro_stress(mat, peak_strain(mat))
    else
      peak_stress = huge(1.0_dp)
    end if
  end function peak_stress

  !> Section resultants for fibre strain eps_n - y kappa, y in [-t/2, t/2],
  !> area A = b t.  nonlinear = .false. drops the E2 term (material switch off).
  !> Odd integer m: closed form (K16, K17 in polynomial form); otherwise
  !> the antiderivative form (power_mean).
  pure function section_response(mat, area, depth, eps_n, kappa, nonlinear) result(res)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: area, depth, eps_n, kappa
    logical, intent(in) :: nonlinear
    type(section_resultants_t) :: res
    real(dp) :: s, ht, e2n, s2, mm
    integer :: m
    ! with eta = 2y/t in [-1, 1]: eps = eps_n - eta s,  s = t kappa / 2
    ht = 0.5_dp*depth
    s = ht*kappa
    ! linear part: E1 (eps_n^2 + s^2/3)/2 per unit area
    res%energy = 0.5_dp*mat%e1*(eps_n*eps_n + s*s/3.0_dp)
    res%axial_force = mat%e1*eps_n
    res%moment = ht*mat%e1*s/3.0_dp
    res%tangent(1, 1) = mat%e1
    res%tangent(1, 2) = 0.0_dp
    res%tangent(2, 2) = ht*ht*mat%e1/3.0_dp
    if (nonlinear .and. mat%e2 > 0.0_dp) then
      if (has_odd_integer_exponent(mat)) then
        m = nint(mat%m)
        if (m == 3) then
          ! Kear (K16)/(K17), polynomial form without the 0/0 at kappa = 0
          e2n = eps_n*eps_n
          s2 = s*s
          res%energy = res%energy - 0.25_dp*mat%e2*(e2n*e2n + 2.0_dp*e2n*s2 + 0.2_dp*s2*s2)
          res%axial_force = res%axial_force - mat%e2*eps_n*(e2n + s2)
          res%moment = res%moment - ht*mat%e2*s*(e2n + 0.2_dp*s2)
          res%tangent(1, 1) = res%tangent(1, 1) - 3.0_dp*mat%e2*(e2n + s2/3.0_dp)
          res%tangent(1, 2) = res%tangent(1, 2) - 2.0_dp*ht*mat%e2*eps_n*s
          res%tangent(2, 2) = res%tangent(2, 2) - ht*ht*mat%e2*(e2n + 0.6_dp*s2)
        else
          mm = real(m, dp)
          res%energy = res%energy - mat%e2/(mm + 1.0_dp)*eta_moment(m + 1, 0, eps_n, s)
          res%axial_force = res%axial_force - mat%e2*eta_moment(m, 0, eps_n, s)
          res%moment = res%moment + ht*mat%e2*eta_moment(m, 1, eps_n, s)
          res%tangent(1, 1) = res%tangent(1, 1) - mm*mat%e2*eta_moment(m - 1, 0, eps_n, s)
          res%tangent(1, 2) = res%tangent(1, 2) + ht*mm*mat%e2*eta_moment(m - 1, 1, eps_n, s)
          res%tangent(2, 2) = res%tangent(2, 2) - ht*ht*mm*mat%e2*eta_moment(m - 1, 2, eps_n, s)
        end if
      else
        call power_law_nonlinear(mat, ht, eps_n, s, res)
      end if
    end if
    res%tangent(2, 1) = res%tangent(1, 2)
    res%energy = area*res%energy
    res%axial_force = area*res%axial_force
    res%moment = area*res%moment
    res%tangent = area*res%tangent
  end function section_response

  !> <eta^l (eps_n - eta s)^j>, the mean over eta in [-1, 1]; binomial
  !> expansion with <eta^k> = 1/(k+1) for even k, 0 for odd k.
  pure real(dp) function eta_moment(j, l, eps_n, s) result(mom)
    integer, intent(in) :: j, l
    real(dp), intent(in) :: eps_n, s
    integer :: k
    real(dp) :: binom
    mom = 0.0_dp
    binom = 1.0_dp
    do k = 0, j
      if (k > 0) binom = binom*real(j - k + 1, dp)/real(k, dp)
      if (mod(k + l, 2) == 0) then
        mom = mom + binom*eps_n**(j - k)*(-s)**k/real(k + l + 1, dp)
      end if
    end do
  end function eta_moment

  !> E2 part of the resultants for non-odd m, from the means
  !> <eta^l z^j |z|^r> of power_mean (z = eps_n - eta s).
  pure subroutine power_law_nonlinear(mat, ht, eps_n, s, res)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: ht, eps_n, s
    type(section_resultants_t), intent(inout) :: res
    real(dp) :: p
    p = mat%m
    res%energy = res%energy - mat%e2/(p + 1.0_dp)*power_mean(0, 0, p + 1.0_dp, eps_n, s)
    res%axial_force = res%axial_force - mat%e2*power_mean(0, 1, p - 1.0_dp, eps_n, s)
    res%moment = res%moment + ht*mat%e2*power_mean(1, 1, p - 1.0_dp, eps_n, s)
    res%tangent(1, 1) = res%tangent(1, 1) - p*mat%e2*power_mean(0, 0, p - 1.0_dp, eps_n, s)
    res%tangent(1, 2) = res%tangent(1, 2) + ht*p*mat%e2*power_mean(1, 0, p - 1.0_dp, eps_n, s)
    res%tangent(2, 2) = res%tangent(2, 2) - ht*ht*p*mat%e2*power_mean(2, 0, p - 1.0_dp, eps_n, s)
  end subroutine power_law_nonlinear

  !> <eta^l z^j |z|^r> over eta in [-1, 1], z = eps_n - eta s, r > -1.
  !> With eta = (eps_n - z)/s the integrand is a sum of z^i |z|^r, whose
  !> antiderivative is z^(i+1) |z|^r / (i+r+1) for either sign of z (the
  !> generalisation of Kear's (K16) form).  That difference quotient cancels
  !> when |s| << |eps_n|; there (|s| < |eps_n|/2) z keeps its sign, the
  !> integrand is analytic within a Bernstein ellipse of parameter >= 2+sqrt(3),
  !> and a 16-point Gauss rule is exact to round-off.
  pure real(dp) function power_mean(l, j, r, eps_n, s) result(mean)
    integer, intent(in) :: l, j
    real(dp), intent(in) :: r, eps_n, s
    real(dp) :: zp, zm, binom, xg(n_smooth_gauss), wg(n_smooth_gauss), z
    integer :: k, i
    if (abs(s) < 0.5_dp*abs(eps_n) .or. abs(s) <= tiny(1.0_dp)) then
      call gauss_legendre(n_smooth_gauss, xg, wg)
      mean = 0.0_dp
      do i = 1, n_smooth_gauss
        z = eps_n - xg(i)*s
        mean = mean + 0.5_dp*wg(i)*xg(i)**l*z**j*abs(z)**r
      end do
    else
      zp = eps_n + s            ! eta = -1
      zm = eps_n - s            ! eta = +1
      mean = 0.0_dp
      binom = 1.0_dp
      do k = 0, l
        if (k > 0) binom = binom*real(l - k + 1, dp)/real(k, dp)
        mean = mean + binom*eps_n**(l - k)*(-1.0_dp)**k &
                      *(zp**(k + j + 1)*abs(zp)**r - zm**(k + j + 1)*abs(zm)**r)/(real(k + j + 1, dp) + r)
      end do
      mean = mean/(2.0_dp*s**(l + 1))
    end if
  end function power_mean

  !> Reference: the same resultants by plain n-point Gauss-Legendre through
  !> the depth of the pointwise law (for tests and for checking new laws).
  pure function section_response_quadrature(mat, area, depth, eps_n, kappa, nonlinear, n) result(res)
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: area, depth, eps_n, kappa
    logical, intent(in) :: nonlinear
    integer, intent(in) :: n
    type(section_resultants_t) :: res
    type(ramberg_osgood_t) :: lin
    real(dp) :: xg(n), wg(n), y, eps, w, et, sig
    integer :: i
    lin = mat
    if (.not. nonlinear) lin%e2 = 0.0_dp
    call gauss_legendre(n, xg, wg)
    do i = 1, n
      y = 0.5_dp*depth*xg(i)
      w = area*0.5_dp*wg(i)                 ! b dy = A/t dy,  dy = t/2 d eta
      eps = eps_n - y*kappa
      sig = ro_stress(lin, eps)
      et = ro_tangent(lin, eps)
      res%energy = res%energy + w*ro_energy_density(lin, eps)
      res%axial_force = res%axial_force + w*sig
      res%moment = res%moment - w*y*sig
      res%tangent(1, 1) = res%tangent(1, 1) + w*et
      res%tangent(1, 2) = res%tangent(1, 2) - w*y*et
      res%tangent(2, 2) = res%tangent(2, 2) + w*y*y*et
    end do
    res%tangent(2, 1) = res%tangent(1, 2)
  end function section_response_quadrature
end module material_law
