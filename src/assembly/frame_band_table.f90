!> A global band matrix assembled from planar element matrices that are
!> constant in their element frames (Kear's element with linear strains and
!> a mass independent of q), tabulated once as a function of the element
!> angles.  The global matrix of element e is T(phi)^T L T(phi): an entry
!> between two node translations is a c^2 + b cs + g s^2 = (a + g)/2 +
!> (a - g)/2 cos 2phi + b/2 sin 2phi, one between a translation and a slope
!> or curvature DOF d c + e s, the others constant (c, s = cos phi, sin phi).
!> The table holds the constant band and the two coefficients of each varying
!> entry (correlation coefficients folded in): the matrix at new angles then
!> costs two multiply-adds per varying entry instead of an element
!> evaluation, two 8 x 8 rotations and a scatter per element
!> (doc/transient.md, "Cost of a right-hand side").
!>
!>     band = const + sum over entries k of coef(1, k) basis(ib(k), e) +
!>            coef(2, k) basis(ib(k) + 1, e),   e = elem(k),
!>
!> with the basis [cos phi, sin phi, cos 2phi, sin 2phi] of each element
!> (angle_basis).  T is kear_element's: p = T q with p1 = c q1 + s q2,
!> p2 = -s q1 + c q2, the same at DOFs 5, 6, the identity elsewhere.
module frame_band_table
  use kinds, only: dp
  use correlation_table, only: correlation_base_t
  implicit none
  private
  public :: frame_table_t, frame_matrix, angle_basis

  !> Filled by start, add_element and finish; read by frame_matrix.
  type :: frame_table_t
    private
    integer :: rows = 0                  !< rows of the band storage
    integer :: n_varying = 0             !< entries that vary with the element angles
    real(dp), allocatable :: const(:)    !< the constant band, column-major
    integer, allocatable :: pos(:)       !< entry's position in the band array, column-major
    integer, allocatable :: base(:)      !< its basis pair's position in basis(4, n_elements), minus 1
    real(dp), allocatable :: coef(:, :)
  contains
    procedure :: start
    procedure :: add_element
    procedure :: finish
  end type frame_table_t

contains

  !> An empty table with room for every varying entry of n_elements elements
  !> (at most two per entry of an 8 x 8 element matrix): appending one at a
  !> time by concatenation cost O(n^2) at set-up (0.5 s at 32 elements per link).
  subroutine start(ft, rows, n, n_elements)
    class(frame_table_t), intent(out) :: ft
    integer, intent(in) :: rows, n, n_elements
    ft%rows = rows
    allocate(ft%const(rows*n), ft%pos(128*n_elements), ft%base(128*n_elements), ft%coef(2, 128*n_elements))
    ft%const = 0.0_dp
  end subroutine start

  !> The table cut to its n_varying entries.
  subroutine finish(ft)
    class(frame_table_t), intent(inout) :: ft
    ft%pos = ft%pos(1:ft%n_varying)
    ft%base = ft%base(1:ft%n_varying)
    ft%coef = ft%coef(:, 1:ft%n_varying)
  end subroutine finish

  !> Element e's entries of T^T l T (through the correlation table: element
  !> DOF i = coef(i) times global unknown map(i), 0 = held at zero): lower
  !> band storage (lower, kd+1 rows) or general band storage (2kd+1 rows).
  subroutine add_element(ft, table, e, l, kd, lower)
    class(frame_table_t), intent(inout) :: ft
    class(correlation_base_t), intent(in) :: table
    integer, intent(in) :: e, kd
    real(dp), intent(in) :: l(8, 8)
    logical, intent(in) :: lower
    real(dp) :: f(6), cij, varying(2, 2), coef(8)
    integer :: i, j, gi, gj, r, k, map(8)
    map = table%unknowns(e)
    coef = table%coefficients(e)
    do j = 1, 8
      gj = map(j)
      if (gj == 0) cycle
      do i = 1, 8
        gi = map(i)
        if (gi == 0 .or. (lower .and. gi < gj)) cycle
        r = merge(1 + gi - gj, kd + 1 + gi - gj, lower)
        cij = coef(i)*coef(j)
        f = cij*frame_form(l, i, j)                    ! [c^2, cs, s^2, c, s, 1]
        ft%const(r + (gj - 1)*ft%rows) = ft%const(r + (gj - 1)*ft%rows) + f(6) + 0.5_dp*(f(1) + f(3))
        varying(:, 1) = [f(4), f(5)]                   ! cos phi, sin phi
        varying(:, 2) = [0.5_dp*(f(1) - f(3)), 0.5_dp*f(2)]   ! cos 2phi, sin 2phi
        do k = 1, 2
          if (.not. (abs(varying(1, k)) > 0.0_dp .or. abs(varying(2, k)) > 0.0_dp)) cycle
          ft%n_varying = ft%n_varying + 1
          ft%pos(ft%n_varying) = r + (gj - 1)*ft%rows
          ft%base(ft%n_varying) = 4*(e - 1) + 2*(k - 1)
          ft%coef(:, ft%n_varying) = varying(:, k)
        end do
      end do
    end do
  end subroutine add_element

  !> Entry (i, j) of T^T L T as coefficients of [c^2, cs, s^2, c, s, 1].
  pure function frame_form(l, i, j) result(f)
    real(dp), intent(in) :: l(8, 8)
    integer, intent(in) :: i, j
    real(dp) :: f(6)
    integer :: k, m, a(3), b(3)
    f = 0.0_dp
    do m = 1, 8
      b = t_entry(m, j)
      if (all(b == 0)) cycle
      do k = 1, 8
        a = t_entry(k, i)
        if (all(a == 0)) cycle
        f = f + l(k, m)*real([a(1)*b(1), a(1)*b(2) + a(2)*b(1), a(2)*b(2), a(1)*b(3) + a(3)*b(1), &
                              a(2)*b(3) + a(3)*b(2), a(3)*b(3)], dp)
      end do
    end do
  end function frame_form

  !> T(k, i) as coefficients of (c, s, 1).
  pure function t_entry(k, i) result(w)
    integer, intent(in) :: k, i
    integer :: w(3)
    w = 0
    if (k == 1 .or. k == 2 .or. k == 5 .or. k == 6) then
      if (i == k) then
        w(1) = 1                                     ! c on the diagonal of each pair
      else if ((k == 1 .and. i == 2) .or. (k == 5 .and. i == 6)) then
        w(2) = 1                                     ! p1 = c q1 + s q2
      else if ((k == 2 .and. i == 1) .or. (k == 6 .and. i == 5)) then
        w(2) = -1                                    ! p2 = -s q1 + c q2
      end if
    else if (i == k) then
      w(3) = 1
    end if
  end function t_entry

  !> band = the table's matrix at the element angles of basis (arrays of
  !> the table's shape, addressed by position).
  pure subroutine frame_matrix(ft, basis, band)
    type(frame_table_t), intent(in) :: ft
    real(dp), intent(in) :: basis(*)
    real(dp), intent(out) :: band(size(ft%const))
    integer :: k, b, i
    band = ft%const
    do k = 1, size(ft%pos)
      i = ft%pos(k)
      b = ft%base(k)
      band(i) = band(i) + (ft%coef(1, k)*basis(b + 1) + ft%coef(2, k)*basis(b + 2))
    end do
  end subroutine frame_matrix

  !> The basis [cos phi, sin phi, cos 2phi, sin 2phi] of an element at angle phi.
  pure function angle_basis(phi) result(basis)
    real(dp), intent(in) :: phi
    real(dp) :: basis(4), c, s
    c = cos(phi)
    s = sin(phi)
    basis = [c, s, (c - s)*(c + s), 2.0_dp*c*s]
  end function angle_basis
end module frame_band_table
