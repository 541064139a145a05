!> Cross-section of the spatial beam (doc/spatial.md, "Section"): geometry,
!> St. Venant torsion constant, and the Ramberg-Osgood resultants of the
!> fibre strain
!>
!>     eps_f(y, z) = eps - y kappa_z + z kappa_y
!>
!> over the section: energy per unit length, (N, M_y, M_z) = d energy /
!> d(eps, kappa_y, kappa_z) and the 3 x 3 tangent.  The linear (E1) part is in
!> closed form; the E2 part by a product rule that is exact for odd integer
!> m <= 5 (polynomial integrand of degree m+1 <= 6) and accurate to
!> truncation otherwise.  Shear and torsion stay linear: the shear terms of
!> paper E's strain energy are illegible in the report's OCR (doc/spatial.md).
module spatial_section
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use quadrature, only: gauss_legendre, gauss_legendre_interval
  use material_law, only: ramberg_osgood_t, ro_stress, ro_tangent, has_odd_integer_exponent
  use linalg, only: outer
  implicit none
  private
  public :: spatial_section_t, section_rectangular, section_circular
  public :: spatial_section_init, spatial_section_resultants, rectangle_torsion_constant
  public :: section_extreme_fibre_strain

  integer, parameter :: section_rectangular = 1, section_circular = 2

  type :: spatial_section_t
    integer :: shape = section_rectangular
    real(dp) :: depth_y = 0.0_dp     !< rectangle: extent along local y (bending in the x-y plane)
    real(dp) :: width_z = 0.0_dp     !< rectangle: extent along local z
    real(dp) :: radius = 0.0_dp      !< circle
    real(dp) :: area = 0.0_dp
    real(dp) :: iy = 0.0_dp          !< int z^2 dA (bending in the x-z plane)
    real(dp) :: iz = 0.0_dp          !< int y^2 dA (bending in the x-y plane)
    real(dp) :: ip = 0.0_dp          !< polar moment iy + iz (torsional inertia)
    real(dp) :: torsion_j = 0.0_dp   !< St. Venant torsion constant
    real(dp), allocatable :: py(:), pz(:), pw(:)   !< quadrature points and weights (sum pw = area)
  end type spatial_section_t

contains

  !> Rectangle (depth_y x width_z) or circle (radius); builds the rule for
  !> the material's E2 term.
  pure subroutine spatial_section_init(sec, shape, dims, mat, err)
    type(spatial_section_t), intent(out) :: sec
    integer, intent(in) :: shape
    real(dp), intent(in) :: dims(:)      !< rectangle: [depth_y, width_z]; circle: [radius]
    type(ramberg_osgood_t), intent(in) :: mat
    type(error_t), intent(inout) :: err
    integer :: n, nt, i, j, k
    real(dp), allocatable :: x(:), w(:), xr(:), wr(:)
    real(dp) :: ang
    logical :: exact
    sec%shape = shape
    exact = has_odd_integer_exponent(mat) .and. mat%m < 5.5_dp
    select case (shape)
    case (section_rectangular)
      if (size(dims) /= 2) then
        call err%set('spatial_section_init', 'a rectangle needs depth and width'); return
      end if
      if (.not. (dims(1) > 0.0_dp .and. dims(2) > 0.0_dp)) then
        call err%set('spatial_section_init', 'rectangle sides must be positive, got '//str(dims(1)) &
                     //' x '//str(dims(2))); return
      end if
      sec%depth_y = dims(1)
      sec%width_z = dims(2)
      sec%area = dims(1)*dims(2)
      sec%iz = dims(2)*dims(1)**3/12.0_dp
      sec%iy = dims(1)*dims(2)**3/12.0_dp
      sec%torsion_j = rectangle_torsion_constant(dims(1), dims(2))
      n = merge(4, 10, exact)                 ! 4 points: exact to degree 7 in y and in z
      allocate(x(n), w(n), sec%py(n*n), sec%pz(n*n), sec%pw(n*n))
      call gauss_legendre(n, x, w)
      k = 0
      do j = 1, n
        do i = 1, n
          k = k + 1
          sec%py(k) = 0.5_dp*dims(1)*x(i)
          sec%pz(k) = 0.5_dp*dims(2)*x(j)
          sec%pw(k) = 0.25_dp*sec%area*w(i)*w(j)
        end do
      end do
    case (section_circular)
      if (size(dims) /= 1) then
        call err%set('spatial_section_init', 'a circle needs its radius'); return
      end if
      if (.not. (dims(1) > 0.0_dp)) then
        call err%set('spatial_section_init', 'radius must be positive, got '//str(dims(1))); return
      end if
      sec%radius = dims(1)
      sec%area = pi*dims(1)**2
      sec%iy = 0.25_dp*pi*dims(1)**4
      sec%iz = sec%iy
      sec%torsion_j = 0.5_dp*pi*dims(1)**4
      ! polar rule: Gauss in r (integrand r * poly(r) of degree <= 7 exact with 4),
      ! trapezoid in angle (exact for trigonometric degree < nt)
      n = merge(4, 10, exact)
      nt = merge(8, 24, exact)
      allocate(xr(n), wr(n), sec%py(n*nt), sec%pz(n*nt), sec%pw(n*nt))
      call gauss_legendre_interval(n, 0.0_dp, dims(1), xr, wr)
      k = 0
      do j = 1, nt
        ang = 2.0_dp*pi*(real(j, dp) - 0.5_dp)/real(nt, dp)
        do i = 1, n
          k = k + 1
          sec%py(k) = xr(i)*cos(ang)
          sec%pz(k) = xr(i)*sin(ang)
          sec%pw(k) = wr(i)*xr(i)*2.0_dp*pi/real(nt, dp)
        end do
      end do
    case default
      call err%set('spatial_section_init', 'unknown section shape code '//str(shape)); return
    end select
    sec%ip = sec%iy + sec%iz
  end subroutine spatial_section_init

  !> St. Venant torsion constant of an a x b rectangle (Timoshenko & Goodier,
  !> Theory of Elasticity, 3rd ed., section 109):
  !> J = t^3 s/3 (1 - 192 t/(pi^5 s) sum_{n odd} tanh(n pi s/(2t))/n^5),
  !> t the shorter side, s the longer.
  pure real(dp) function rectangle_torsion_constant(a, b) result(j)
    real(dp), intent(in) :: a, b
    real(dp) :: t, s, sm
    integer :: n
    t = min(a, b)
    s = max(a, b)
    sm = 0.0_dp
    do n = 1, 41, 2
      sm = sm + tanh(real(n, dp)*pi*s/(2.0_dp*t))/real(n, dp)**5
    end do
    j = t**3*s/3.0_dp*(1.0_dp - 192.0_dp*t/(pi**5*s)*sm)
  end function rectangle_torsion_constant

  !> Energy per unit length, gradient g = (N, M_y, M_z) with respect to
  !> s = (eps, kappa_y, kappa_z), and tangent dg/ds.  nonlinear = .false.
  !> drops the E2 term (material switch off).
  pure subroutine spatial_section_resultants(sec, mat, s, nonlinear, energy, g, h)
    type(spatial_section_t), intent(in) :: sec
    type(ramberg_osgood_t), intent(in) :: mat
    real(dp), intent(in) :: s(3)
    logical, intent(in) :: nonlinear
    real(dp), intent(out) :: energy, g(3), h(3, 3)
    real(dp) :: ef, a(3), sig, et, e2law
    type(ramberg_osgood_t) :: nl
    integer :: k
    ! linear part, closed form (the section is doubly symmetric)
    energy = 0.5_dp*mat%e1*(sec%area*s(1)**2 + sec%iy*s(2)**2 + sec%iz*s(3)**2)
    g = mat%e1*[sec%area*s(1), sec%iy*s(2), sec%iz*s(3)]
    h = 0.0_dp
    h(1, 1) = mat%e1*sec%area
    h(2, 2) = mat%e1*sec%iy
    h(3, 3) = mat%e1*sec%iz
    if (.not. (nonlinear .and. mat%e2 > 0.0_dp)) return
    ! E2 part: the law with E1 = 0 is -E2 eps |eps|^(m-1)
    nl = mat
    nl%e1 = 0.0_dp
    do k = 1, size(sec%pw)
      a = [1.0_dp, sec%pz(k), -sec%py(k)]
      ef = s(1) + a(2)*s(2) + a(3)*s(3)
      sig = ro_stress(nl, ef)
      et = ro_tangent(nl, ef)
      e2law = -mat%e2*abs(ef)**(mat%m + 1.0_dp)/(mat%m + 1.0_dp)
      energy = energy + sec%pw(k)*e2law
      g = g + sec%pw(k)*sig*a
      h = h + sec%pw(k)*et*outer(a, a)
    end do
  end subroutine spatial_section_resultants

  !> Largest |fibre strain| over the section for (eps, kappa_y, kappa_z) and
  !> the fibre where it occurs: corners of a rectangle, the point of the
  !> circle in the direction of the curvature vector.
  pure subroutine section_extreme_fibre_strain(sec, s, eps_max, y, z)
    type(spatial_section_t), intent(in) :: sec
    real(dp), intent(in) :: s(3)
    real(dp), intent(out) :: eps_max, y, z
    real(dp) :: e, kk, cy, cz
    integer :: i, j
    eps_max = -1.0_dp
    y = 0.0_dp
    z = 0.0_dp
    if (sec%shape == section_rectangular) then
      do i = -1, 1, 2
        do j = -1, 1, 2
          cy = 0.5_dp*real(i, dp)*sec%depth_y
          cz = 0.5_dp*real(j, dp)*sec%width_z
          e = s(1) - cy*s(3) + cz*s(2)
          if (abs(e) > eps_max) then
            eps_max = abs(e)
            y = cy
            z = cz
          end if
        end do
      end do
    else
      ! eps_f = eps + r (z ky - y kz): extreme where (y, z) is along +-(-kz, ky)
      kk = sqrt(s(2)**2 + s(3)**2)
      if (kk > 0.0_dp) then
        cy = -sec%radius*s(3)/kk
        cz = sec%radius*s(2)/kk
      else
        cy = sec%radius
        cz = 0.0_dp
      end if
      if (s(1) < 0.0_dp) then
        cy = -cy
        cz = -cz
      end if
      eps_max = abs(s(1) - cy*s(3) + cz*s(2))
      y = cy
      z = cz
    end if
  end subroutine section_extreme_fibre_strain
end module spatial_section
