!> What engineers compare a flexible-mechanism run with, computed from the
!> model's state: the section resultants and stresses of every element, and
!> the displacement of named points of a link with its deflection relative
!> to the deformed chord.  (Joint forces: src/model/joint_reactions.f90.)
!>
!> Section quantities at a station x of an element, from the axial strain
!> eps_n and curvature kappa the element uses (beam_station_strains, from
!> the element's shape gradients tabulated at those stations) and
!> its material law, outer fibres y = +-c (c the link's fibre distance):
!>   N = axial force, M = bending moment (material integrated through the
!>       depth, as in the element: material_law%section_response);
!>   outer-fibre stresses s+- = sigma(eps_n -+ c kappa);
!>   axial stress   = (s+ + s-)/2,   bending stress = (s- - s+)/2,
!> so that axial + bending and axial - bending are the two outer-fibre
!> stresses (the analysis' sigma_max column is the larger in magnitude); for
!> a linear material axial = N/A and bending = M c/I.  An element's value of
!> each is the signed value of largest magnitude over the stations of its
!> stress recovery (both ends and the element's Gauss points).
module transient_response
  use kinds, only: dp
  use quadrature, only: max_gauss_points
  use material_law, only: ramberg_osgood_t, ro_stress, section_response, section_resultants_t
  use beam_element, only: planar_element_t, beam_section_strains, beam_station_strains, beam_local_displacement, &
                          beam_stress_report
  use planar_element, only: stress_report_t
  use linkage, only: mechanism_t
  use mechanism_model, only: mechanism_model_t
  implicit none
  private
  public :: section_values_t, section_at, element_section_peaks, element_stresses_and_sections
  public :: link_point_t, link_point_response

  integer, parameter :: max_stations = max_gauss_points + 2   !< ends and Gauss points of an element

  !> Section quantities at one station, or an element's peaks (signed).
  type :: section_values_t
    real(dp) :: axial_force = 0.0_dp       !< N
    real(dp) :: moment = 0.0_dp            !< M = EI kappa for a linear material
    real(dp) :: axial_stress = 0.0_dp      !< (s+ + s-)/2
    real(dp) :: bending_stress = 0.0_dp    !< (s- - s+)/2
  end type section_values_t

  !> A point of a link and its response.
  type :: link_point_t
    integer :: link = 0
    real(dp) :: s = 0.5_dp                 !< position along the link, 0 (end 1) .. 1 (end 2)
    real(dp) :: u = 0.0_dp, w = 0.0_dp     !< elastic axial, transverse displacement in the link's rigid axes
    real(dp) :: chord = 0.0_dp             !< transverse distance from the deformed chord (end 1 to end 2), + to the left
  end type link_point_t

contains

  !> Section quantities of element e at x = xi l for the global displacements q.
  pure function section_at(model, e, q, xi) result(v)
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:), xi
    type(section_values_t) :: v
    real(dp) :: eps_n, kap
    call beam_section_strains(model%el(e), model%table%gather(e, q), model%rb(e)%phi, xi, eps_n, kap)
    v = station(model%el(e), eps_n, kap)
  end function section_at

  !> Section quantities from the axial strain and curvature of a station.
  pure function station(el, eps_n, kap) result(v)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: eps_n, kap
    type(section_values_t) :: v
    type(ramberg_osgood_t) :: law
    type(section_resultants_t) :: res
    real(dp) :: s_plus, s_minus
    law = el%material
    if (.not. el%effects%material) law%e2 = 0.0_dp   ! as the element: off = linear, no power evaluated
    res = section_response(law, el%area, el%depth, eps_n, kap, el%effects%material)
    v%axial_force = res%axial_force
    v%moment = res%moment
    s_plus = ro_stress(law, eps_n - el%fibre*kap)
    s_minus = ro_stress(law, eps_n + el%fibre*kap)
    v%axial_stress = 0.5_dp*(s_plus + s_minus)
    v%bending_stress = 0.5_dp*(s_minus - s_plus)
  end function station

  !> Each section quantity's signed value of largest magnitude over element
  !> e's stations (ends and Gauss points, as its stress recovery): the
  !> strains of all stations from one rotation and the tabulated gradients.
  pure function element_section_peaks(model, e, q) result(pk)
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:)
    type(section_values_t) :: pk
    real(dp) :: eps_n(0:max_stations - 1), kap(0:max_stations - 1)
    integer :: ng
    associate (el => model%el(e))
      ng = el%n_gauss
      call beam_station_strains(el, model%table%gather(e, q), model%rb(e)%phi, eps_n(:ng + 1), kap(:ng + 1))
      pk = section_peaks(el, eps_n(:ng + 1), kap(:ng + 1))
    end associate
  end function element_section_peaks

  !> Every element's stress report (the model's element_stresses) and section
  !> peaks (element_section_peaks) from one evaluation of its station
  !> strains; for a model without links sliding through sleeves (those have
  !> no section columns).
  pure subroutine element_stresses_and_sections(model, q, reports, sections)
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: q(:)
    type(stress_report_t), intent(out) :: reports(:)
    type(section_values_t), intent(out) :: sections(:)
    real(dp) :: eps_n(0:max_stations - 1), kap(0:max_stations - 1)
    integer :: e, ng
    do e = 1, size(model%el)
      associate (el => model%el(e))
        ng = el%n_gauss
        call beam_station_strains(el, model%table%gather(e, q), model%rb(e)%phi, eps_n(:ng + 1), kap(:ng + 1))
        reports(e) = beam_stress_report(el, eps_n(:ng + 1), kap(:ng + 1))
        sections(e) = section_peaks(el, eps_n(:ng + 1), kap(:ng + 1))
      end associate
    end do
  end subroutine element_stresses_and_sections

  !> Each section quantity's signed value of largest magnitude over the
  !> stations 0 .. n_gauss + 1 of element el with the strains eps_n, kap.
  pure function section_peaks(el, eps_n, kap) result(pk)
    class(planar_element_t), intent(in) :: el
    real(dp), intent(in) :: eps_n(0:), kap(0:)
    type(section_values_t) :: pk
    type(section_values_t) :: v
    integer :: i
    do i = 0, size(eps_n) - 1
      v = station(el, eps_n(i), kap(i))
      if (abs(v%axial_force) > abs(pk%axial_force)) pk%axial_force = v%axial_force
      if (abs(v%moment) > abs(pk%moment)) pk%moment = v%moment
      if (abs(v%axial_stress) > abs(pk%axial_stress)) pk%axial_stress = v%axial_stress
      if (abs(v%bending_stress) > abs(pk%bending_stress)) pk%bending_stress = v%bending_stress
    end do
  end function section_peaks

  !> Elastic displacement (u, w) of point p (p%link, p%s) in the link's
  !> rigid-body axes and its transverse distance from the deformed chord:
  !> with the deformed ends r1 = (u1, w1), r2 = (L + u2, w2) and the point
  !> r = (s L + u, w) in those axes, chord = (r2 - r1) x (r - r1) / |r2 - r1|.
  !> The link's elements are collinear (one straight link), so their local
  !> axes are the link's.
  pure subroutine link_point_response(model, mech, q, p)
    type(mechanism_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: q(:)
    type(link_point_t), intent(inout) :: p
    real(dp) :: uw1(2), uw2(2), r1(2), r2(2), r(2), d(2), length, xi
    integer :: first, n, k
    first = mech%links(p%link)%first_element
    n = mech%links(p%link)%n_elements
    length = sum(model%el(first:first + n - 1)%length)
    uw1 = local_uw(first, 0.0_dp)
    uw2 = local_uw(first + n - 1, 1.0_dp)
    k = min(n - 1, int(p%s*n))                     ! element k+1 holds the point
    xi = p%s*n - k
    associate (uw => local_uw(first + k, xi))
      p%u = uw(1)
      p%w = uw(2)
    end associate
    r1 = uw1
    r2 = [length + uw2(1), uw2(2)]
    r = [p%s*length + p%u, p%w]
    d = r2 - r1
    p%chord = (d(1)*(r(2) - r1(2)) - d(2)*(r(1) - r1(1)))/norm2(d)
  contains
    pure function local_uw(e, x) result(uw)
      integer, intent(in) :: e
      real(dp), intent(in) :: x
      real(dp) :: uw(2)
      uw = beam_local_displacement(model%el(e), model%table%gather(e, q), model%rb(e)%phi, x)
    end function local_uw
  end subroutine link_point_response
end module transient_response
