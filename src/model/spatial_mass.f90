!> The spatial model's mass solve M(t) x = f with a constant banded factor
!> (doc/spatial.md, "Cost").  M(t) changes with time only through the
!> rotations of the element frames: M = sum_e C_e^T T_e M_p T_e^T C_e.  In
!> the coordinates x~ = T^T x, where T rotates every vector triple of unknowns
!> that belongs to one link alone into that link's frame, every entry of
!> M~ = T^T M T is constant except the rows and columns of the few joint
!> unknowns J shared between links (the translations of B and C, revolute
!> rotations, the rocker pivot's rotation).  With A = M~ on the other
!> unknowns (J rows and columns replaced by the identity; constant, factored
!> once), B = M~(:, J) and C = M~(J, J):
!>   x~_J = S^-1 (f~_J - B^T A^-1 f~),  x~ = A^-1 f~ - A^-1 B x~_J,
!>   S = C - B^T A^-1 B  (|J| x |J|, SPD as a Schur complement of SPD M~).
!> B(:, j) = sum over the element triples touching j of P_p r, with P_p
!> constant (the M_p columns of the triple, scattered) and r = R_e^T d the
!> triple's coefficients in the element frame: A^-1 P_p and P_p^T A^-1 P_q
!> are precomputed, so a new time costs a few 3 x 3 products and a small
!> Cholesky, and a solve one banded solve plus O(N |J|).  The same
!> arithmetic as the banded Cholesky of M(t), exact to round-off.
!> A is block diagonal: the links are apart once J is out, and in a link's
!> frame M_p couples u's, v's, w's and the twist's functions only with their
!> own.  Its factor and solves work in an order that keeps each block together
!> (component_order): the band narrows (16 -> 5 for Kear's elements) and the
!> nonzero arithmetic is the same, in the same order.
module spatial_mass
  use kinds, only: dp
  use band_kernels, only: band_cholesky_inplace, band_cholesky_substitute
  use spatial_beam, only: spatial_beam_t, spatial_rigid_t
  use spatial_correlation, only: spatial_table_t, sdofs
  implicit none
  private
  public :: spatial_mass_t

  integer, parameter :: first(4) = [1, 4, 11, 14]   !< element DOF of each vector triple

  type :: spatial_mass_t
    logical :: active = .false.           !< .false.: the structure is not supported (the model factors M(t))
    integer :: n = 0, kd = 0, nj = 0, ntri = 0, npair = 0
    integer :: kda = 0                    !< half-bandwidth of A in the block order
    integer, allocatable :: perm(:), pos(:)   !< block order: position -> unknown, unknown -> position
    real(dp), allocatable :: afac(:, :)   !< (kda+1, n) Cholesky factor of A in the block order
    integer, allocatable :: tri(:, :), tri_el(:)   !< owned triples: (3, ntri) unknowns; an element of the owning link
    integer, allocatable :: jlist(:), jpos(:)      !< J unknowns; unknown -> index in J (0: not in J)
    integer, allocatable :: pair_el(:), pair_b(:)  !< element triples touching J ("pairs" p)
    integer, allocatable :: slot_j(:)              !< (3 npair): J index of component c of pair p, slot 3(p-1)+c (0: none)
    real(dp), allocatable :: slot_d(:)             !< its coefficient
    integer, allocatable :: p_n(:), p_idx(:, :)    !< nonzero rows of P_p: count, positions (sdofs, npair)
    real(dp), allocatable :: p_val(:, :, :)        !< (sdofs, 3, npair) their values
    real(dp), allocatable :: w(:, :, :)            !< (n, 3, npair): A^-1 P_p (block order)
    integer, allocatable :: w_lo(:, :), w_hi(:, :) !< (3, npair): its nonzero range (within the pair's blocks)
    real(dp), allocatable :: h(:, :)               !< (3 npair, 3 npair): [same element] M_p blocks - P_p^T A^-1 P_q
    integer, allocatable :: h_lo(:), h_hi(:)       !< nonzero rows of H's columns of pair p (the pairs of its link)
    integer, allocatable :: pj_n(:), pj(:, :)      !< the distinct J unknowns of each pair (up to 3)
    real(dp), allocatable :: e(:, :, :)            !< (3, 3, npair): E_p(:, jj) = R_p^T d_(p, jj) at the last update
    real(dp), allocatable :: he(:, :)              !< (3 npair, nj) work: H E
    real(dp), allocatable :: rp(:, :, :)           !< (3, 3, npair): element rotation of each pair at the last update
    real(dp), allocatable :: schur(:, :)           !< (nj, nj) Cholesky factor of S (lower)
  contains
    procedure :: init
    procedure :: update
    procedure :: solve
  end type spatial_mass_t

contains

  !> Classify the unknowns, factor A, precompute A^-1 P and P^T A^-1 P.
  !> Leaves active = .false. if an unknown of J is also reached through a
  !> DOF that does not rotate (not met by the four-bar's joint rules).
  subroutine init(self, table, el, link_of, n, kd)
    class(spatial_mass_t), intent(inout) :: self
    type(spatial_table_t), intent(in) :: table
    type(spatial_beam_t), intent(in) :: el(:)
    integer, intent(in) :: link_of(:), n, kd
    integer :: e, b, i, j, gi, gj, kind(n), owner(n), info
    logical :: rot(4), ok
    real(dp), allocatable :: a(:, :)
    self%active = .false.
    self%n = n
    self%kd = kd
    call classify(table, el, link_of, kind, ok)
    if (.not. ok) return
    self%nj = count(kind == 3)
    allocate(self%jpos(n))
    self%jpos = 0
    self%jlist = pack([(i, i=1, n)], kind == 3)
    do j = 1, self%nj
      self%jpos(self%jlist(j)) = j
    end do
    ! owned triples (one entry per triple: its first element)
    allocate(self%tri(3, n), self%tri_el(n))
    self%ntri = 0
    owner = 0                                      ! reused: unknown already in a listed triple
    do e = 1, size(el)
      rot = rotating(el(e))
      do b = 1, 4
        if (.not. rot(b)) cycle
        associate (m => table%unknowns_of(first(b) + [0, 1, 2], e))
          if (all(m > 0)) then
            if (all(kind(m) == 2) .and. owner(m(1)) == 0) then
              self%ntri = self%ntri + 1
              self%tri(:, self%ntri) = m
              self%tri_el(self%ntri) = e
              owner(m) = 1
            end if
          end if
        end associate
      end do
    end do
    if (any(kind == 2 .and. owner == 0)) return       ! an owned unknown outside a whole triple
    ! A: M~ without J, identity on J (original order), then in the block order
    allocate(a(kd + 1, n))
    a = 0.0_dp
    do e = 1, size(el)
      do j = 1, sdofs
        gj = table%unknown(j, e)
        if (gj == 0) cycle
        if (self%jpos(gj) > 0) cycle
        do i = 1, sdofs
          gi = table%unknown(i, e)
          if (gi < gj) cycle
          if (self%jpos(gi) > 0) cycle
          a(1 + gi - gj, gj) = a(1 + gi - gj, gj) + table%coefficient(i, e)*el(e)%mass0(i, j)*table%coefficient(j, e)
        end do
      end do
    end do
    do j = 1, self%nj
      a(1, self%jlist(j)) = 1.0_dp
    end do
    allocate(self%perm(n), self%pos(n))
    call component_order(a, kd, self%perm, self%pos, self%kda)
    allocate(self%afac(self%kda + 1, n))
    self%afac = 0.0_dp
    do j = 1, n
      do i = j, min(n, j + kd)
        if (abs(a(1 + i - j, j)) <= 0.0_dp .and. i > j) cycle
        gi = max(self%pos(i), self%pos(j))
        gj = min(self%pos(i), self%pos(j))
        self%afac(1 + gi - gj, gj) = a(1 + i - j, j)
      end do
    end do
    call band_cholesky_inplace(self%afac, self%kda, info)
    ok = info == 0
    if (.not. ok) return
    call precompute_pairs(self, table, el)
    self%active = .true.
  end subroutine init

  !> kind of each unknown: 0 unseen, 1 reached through non-rotating DOFs
  !> only, 2 in a vector triple of one link (owned), 3 joint (J); ok =
  !> .false. if an owned or joint unknown is also reached unrotated.
  subroutine classify(table, el, link_of, kind, ok)
    type(spatial_table_t), intent(in) :: table
    type(spatial_beam_t), intent(in) :: el(:)
    integer, intent(in) :: link_of(:)
    integer, intent(out) :: kind(:)
    logical, intent(out) :: ok
    integer :: e, b, c, i, gi, owner(size(kind))
    logical :: rot(4), changed
    ok = .false.
    ! kind: 0 unseen, 1 only in non-rotating DOFs, 2 in a candidate owned triple, 3 joint (J)
    kind = 0
    owner = 0
    do e = 1, size(el)
      rot = rotating(el(e))
      do i = 1, sdofs
        gi = table%unknown(i, e)
        if (gi == 0) cycle
        if (kind(gi) == 0) kind(gi) = 1
      end do
      do b = 1, 4
        if (.not. rot(b)) cycle
        associate (m => table%unknowns_of(first(b) + [0, 1, 2], e), cf => table%coefficients_of(first(b) + [0, 1, 2], e))
          if (all(m > 0) .and. maxval(abs(cf - 1.0_dp)) <= 0.0_dp .and. m(1) /= m(2) .and. m(2) /= m(3) &
              .and. m(1) /= m(3)) then
            do c = 1, 3
              if (kind(m(c)) == 3) cycle
              if (owner(m(c)) /= 0 .and. owner(m(c)) /= link_of(e)) then
                kind(m(c)) = 3                    ! shared between links
              else
                kind(m(c)) = 2
                owner(m(c)) = link_of(e)
              end if
            end do
          else
            do c = 1, 3
              if (m(c) > 0) kind(m(c)) = 3
            end do
          end if
        end associate
      end do
    end do
    ! a triple is owned only if all its unknowns are (repeat until no triple changes)
    changed = .true.
    do while (changed)
      changed = .false.
      do e = 1, size(el)
        rot = rotating(el(e))
        do b = 1, 4
          if (.not. rot(b)) cycle
          associate (m => table%unknowns_of(first(b) + [0, 1, 2], e))
            do c = 1, 3
              if (m(c) == 0) cycle
              if (kind(m(c)) /= 3 .and. (any(m == 0) .or. any(kind(max(m, 1)) == 3))) then
                kind(m(c)) = 3
                changed = .true.
              end if
            end do
          end associate
        end do
      end do
    end do
    do e = 1, size(el)
      rot = rotating(el(e))
      do i = 1, sdofs
        gi = table%unknown(i, e)
        if (gi == 0) cycle
        b = triple_of(i)
        if (b == 0) then
          if (kind(gi) == 3 .or. kind(gi) == 2) return      ! reached unrotated too: not supported
        else if (.not. rot(b)) then
          if (kind(gi) == 3 .or. kind(gi) == 2) return
        end if
      end do
    end do
    ok = .true.
  end subroutine classify

  !> The element triples touching J ("pairs"), their components' J unknowns
  !> ("slots"), P_p, A^-1 P_p and H = [same element] M_p blocks - P^T A^-1 P.
  subroutine precompute_pairs(self, table, el)
    class(spatial_mass_t), intent(inout) :: self
    type(spatial_table_t), intent(in) :: table
    type(spatial_beam_t), intent(in) :: el(:)
    integer :: e, b, c, i, j, gi, k, np, n, kd
    logical :: rot(4)
    integer, allocatable :: pe(:), pb(:)
    n = self%n
    kd = self%kda
    ! element triples touching J ("pairs") and their components' J unknowns ("slots")
    allocate(pe(4*size(el)), pb(4*size(el)))
    np = 0
    do e = 1, size(el)
      rot = rotating(el(e))
      do b = 1, 4
        if (.not. rot(b)) cycle
        associate (m => table%unknowns_of(first(b) + [0, 1, 2], e))
          if (.not. any(m > 0)) cycle
          if (self%jpos(maxval(m)) == 0) cycle
          np = np + 1
          pe(np) = e
          pb(np) = b
        end associate
      end do
    end do
    self%npair = np
    self%pair_el = pe(1:np)
    self%pair_b = pb(1:np)
    allocate(self%slot_j(3*np), self%slot_d(3*np), self%p_n(np), self%p_idx(sdofs, np), self%p_val(sdofs, 3, np), &
             self%w(n, 3, np), self%h(3*np, 3*np), self%rp(3, 3, np), self%schur(self%nj, self%nj), &
             self%pj_n(np), self%pj(3, np), self%e(3, 3, np), self%he(3*np, self%nj), &
             self%w_lo(3, np), self%w_hi(3, np), self%h_lo(np), self%h_hi(np))
    self%pj_n = 0
    self%slot_j = 0
    self%slot_d = 0.0_dp
    self%p_n = 0
    self%w = 0.0_dp
    do k = 1, np
      e = self%pair_el(k)
      b = first(self%pair_b(k))
      do c = 1, 3
        gi = table%unknown(b + c - 1, e)
        if (gi == 0) cycle
        self%slot_j(3*(k - 1) + c) = self%jpos(gi)
        self%slot_d(3*(k - 1) + c) = table%coefficient(b + c - 1, e)
        if (.not. any(self%pj(1:self%pj_n(k), k) == self%jpos(gi))) then
          self%pj_n(k) = self%pj_n(k) + 1
          self%pj(self%pj_n(k), k) = self%jpos(gi)
        end if
      end do
      do i = 1, sdofs                                  ! P_p: the triple's M_p columns, non-J rows
        gi = table%unknown(i, e)
        if (gi == 0) cycle
        if (self%jpos(gi) > 0) cycle
        self%p_n(k) = self%p_n(k) + 1
        self%p_idx(self%p_n(k), k) = self%pos(gi)
        self%p_val(self%p_n(k), :, k) = table%coefficient(i, e)*el(e)%mass0(i, b:b + 2)
        self%w(self%pos(gi), :, k) = self%w(self%pos(gi), :, k) + self%p_val(self%p_n(k), :, k)
      end do
      do c = 1, 3
        call band_cholesky_substitute(self%afac, kd, self%w(:, c, k))
        self%w_lo(c, k) = findloc(abs(self%w(:, c, k)) > 0.0_dp, .true., 1)
        self%w_hi(c, k) = findloc(abs(self%w(:, c, k)) > 0.0_dp, .true., 1, back=.true.)
        if (self%w_lo(c, k) == 0) self%w_lo(c, k) = 1                 ! (empty: w_hi = 0)
      end do
    end do
    do k = 1, np
      do j = 1, np
        do c = 1, 3
          do i = 1, 3
            self%h(3*(k - 1) + i, 3*(j - 1) + c) = &
              -sum(self%p_val(1:self%p_n(k), i, k)*self%w(self%p_idx(1:self%p_n(k), k), c, j))
          end do
        end do
        if (self%pair_el(k) == self%pair_el(j)) self%h(3*k - 2:3*k, 3*j - 2:3*j) = self%h(3*k - 2:3*k, 3*j - 2:3*j) &
          + el(self%pair_el(k))%mass0(first(self%pair_b(k)):first(self%pair_b(k)) + 2, &
                                      first(self%pair_b(j)):first(self%pair_b(j)) + 2)
      end do
    end do
    do k = 1, np
      self%h_lo(k) = findloc(any(abs(self%h(:, 3*k - 2:3*k)) > 0.0_dp, 2), .true., 1)
      self%h_hi(k) = findloc(any(abs(self%h(:, 3*k - 2:3*k)) > 0.0_dp, 2), .true., 1, back=.true.)
      if (self%h_lo(k) == 0) self%h_lo(k) = 1                           ! (empty: h_hi = 0)
    end do
  end subroutine precompute_pairs


  !> S at the rigid state rb(:) (element frames), factored; ok = .false. if
  !> S is not positive definite.  S = E^T H E: H (constant) on the pairs'
  !> element-frame components, E_p = R_p^T d the coefficients of their J unknowns.
  subroutine update(self, rb, ok)
    class(spatial_mass_t), intent(inout) :: self
    type(spatial_rigid_t), intent(in) :: rb(:)
    logical, intent(out) :: ok
    integer :: k, m, c, jj, j, i, r
    real(dp) :: s
    ! E: per pair, the element-frame coefficients of its J unknowns (3 x up to 3)
    self%e = 0.0_dp
    do k = 1, self%npair
      self%rp(:, :, k) = rb(self%pair_el(k))%rot
      do c = 1, 3
        j = self%slot_j(3*(k - 1) + c)
        if (j == 0) cycle
        jj = findloc(self%pj(1:self%pj_n(k), k), j, 1)
        self%e(:, jj, k) = self%e(:, jj, k) + self%slot_d(3*(k - 1) + c)*self%rp(c, :, k)
      end do
    end do
    ! S = E^T H E (lower triangle), E sparse: H E, then E^T (H E)
    self%he = 0.0_dp
    do k = 1, self%npair
      do jj = 1, self%pj_n(k)
        j = self%pj(jj, k)
        do m = 1, 3                    ! E is sparse in a planar linkage (R^T e_z = e_z): skip its zeros
          if (abs(self%e(m, jj, k)) <= 0.0_dp) cycle
          associate (lo => self%h_lo(k), hi => self%h_hi(k))
            self%he(lo:hi, j) = self%he(lo:hi, j) + self%h(lo:hi, 3*(k - 1) + m)*self%e(m, jj, k)
          end associate
        end do
      end do
    end do
    self%schur = 0.0_dp
    do k = 1, self%npair
      do jj = 1, self%pj_n(k)
        j = self%pj(jj, k)
        do m = 1, 3
          if (abs(self%e(m, jj, k)) <= 0.0_dp) cycle
          r = 3*(k - 1) + m
          do i = j, self%nj
            self%schur(i, j) = self%schur(i, j) + self%e(m, jj, k)*self%he(r, i)
          end do
        end do
      end do
    end do
    ok = .false.                                         ! dense Cholesky of the small S (lower)
    do j = 1, self%nj                                    ! (sums in index order, as sum() does)
      s = 0.0_dp
      do m = 1, j - 1
        s = s + self%schur(j, m)**2
      end do
      s = self%schur(j, j) - s
      if (.not. (s > 0.0_dp)) return
      self%schur(j, j) = sqrt(s)
      do i = j + 1, self%nj
        s = 0.0_dp
        do m = 1, j - 1
          s = s + self%schur(i, m)*self%schur(j, m)
        end do
        self%schur(i, j) = (self%schur(i, j) - s)/self%schur(j, j)
      end do
    end do
    ok = .true.
  end subroutine update

  !> x := M(t)^-1 x with the S of the last update (rb: the same rigid state).
  subroutine solve(self, rb, x)
    class(spatial_mass_t), intent(in) :: self
    type(spatial_rigid_t), intent(in) :: rb(:)
    real(dp), intent(inout), contiguous :: x(:)
    real(dp) :: fj(self%nj), z(3), v(3), u(3), r(3, 3), y(self%n)
    integer :: t, j, k, i, c, sl
    do t = 1, self%ntri                                  ! f~ = T^T f
      r = rb(self%tri_el(t))%rot
      v = x(self%tri(:, t))
      x(self%tri(:, t)) = [dot_product(r(:, 1), v), dot_product(r(:, 2), v), dot_product(r(:, 3), v)]
    end do
    fj = x(self%jlist)
    x(self%jlist) = 0.0_dp
    y = x(self%perm)                                     ! (the block order)
    call band_cholesky_substitute(self%afac, self%kda, y)          ! y = A^-1 f~ (zero on J)
    do k = 1, self%npair                                 ! f_J - B^T y
      z = 0.0_dp
      do i = 1, self%p_n(k)
        z = z + self%p_val(i, :, k)*y(self%p_idx(i, k))
      end do
      v = matmul(self%rp(:, :, k), z)
      do c = 1, 3
        sl = 3*(k - 1) + c
        if (self%slot_j(sl) > 0) fj(self%slot_j(sl)) = fj(self%slot_j(sl)) - self%slot_d(sl)*v(c)
      end do
    end do
    do j = 1, self%nj                                    ! x_J = S^-1 (f_J - B^T y)
      fj(j) = (fj(j) - dot_product(self%schur(j, 1:j - 1), fj(1:j - 1)))/self%schur(j, j)
    end do
    do j = self%nj, 1, -1
      fj(j) = (fj(j) - dot_product(self%schur(j + 1:self%nj, j), fj(j + 1:self%nj)))/self%schur(j, j)
    end do
    do k = 1, self%npair                                 ! x~ = y - A^-1 B x_J
      do c = 1, 3
        sl = 3*(k - 1) + c
        v(c) = 0.0_dp
        if (self%slot_j(sl) > 0) v(c) = self%slot_d(sl)*fj(self%slot_j(sl))
      end do
      u = matmul(v, self%rp(:, :, k))                    ! R^T v
      do c = 1, 3                                        ! (zero for the normal of a planar linkage)
        if (abs(u(c)) > 0.0_dp) y(self%w_lo(c, k):self%w_hi(c, k)) = y(self%w_lo(c, k):self%w_hi(c, k)) &
                                                                    - self%w(self%w_lo(c, k):self%w_hi(c, k), c, k)*u(c)
      end do
    end do
    x(self%perm) = y
    x(self%jlist) = fj
    do t = 1, self%ntri                                  ! x = T x~
      r = rb(self%tri_el(t))%rot
      v = x(self%tri(:, t))
      x(self%tri(:, t)) = r(:, 1)*v(1) + r(:, 2)*v(2) + r(:, 3)*v(3)
    end do
  end subroutine solve

  !> An order of the unknowns (perm: position -> unknown, pos its inverse)
  !> that keeps each connected component of the graph of ab (lower band
  !> storage, half-bandwidth kd) together, in its original order, the
  !> components ordered by their first unknown; kdp the half-bandwidth there.
  !> The Cholesky factor of a block diagonal matrix is block diagonal: in this
  !> order it does the same nonzero operations in the same order as in the
  !> original one, without the zeros between the blocks.
  pure subroutine component_order(ab, kd, perm, pos, kdp)
    real(dp), intent(in) :: ab(:, :)
    integer, intent(in) :: kd
    integer, intent(out) :: perm(:), pos(:), kdp
    integer :: n, i, j, ri, rj, k, root(size(perm)), next(size(perm)), last(size(perm))
    n = size(ab, 2)
    root = [(i, i=1, n)]                         ! union-find, the root a component's first unknown
    do j = 1, n
      do i = j + 1, min(n, j + kd)
        if (abs(ab(1 + i - j, j)) <= 0.0_dp) cycle
        ri = i
        do while (root(ri) /= ri)
          ri = root(ri)
        end do
        rj = j
        do while (root(rj) /= rj)
          rj = root(rj)
        end do
        root(max(ri, rj)) = min(ri, rj)
      end do
    end do
    next = 0                                     ! each component's unknowns as a list, in order
    last = 0
    do i = 1, n
      ri = i
      do while (root(ri) /= ri)
        ri = root(ri)
      end do
      root(i) = ri
      if (ri /= i) next(last(ri)) = i
      last(ri) = i
    end do
    k = 0
    do i = 1, n
      if (root(i) /= i) cycle
      j = i
      do while (j /= 0)
        k = k + 1
        perm(k) = j
        pos(j) = k
        j = next(j)
      end do
    end do
    kdp = 0
    do j = 1, n
      do i = j + 1, min(n, j + kd)
        if (abs(ab(1 + i - j, j)) > 0.0_dp) kdp = max(kdp, abs(pos(i) - pos(j)))
      end do
    end do
  end subroutine component_order

  !> Which of the element's four vector triples rotate with its frame.
  pure function rotating(el) result(r)
    type(spatial_beam_t), intent(in) :: el
    logical :: r(4)
    r = [.true., .not. el%local_rotation(1), .true., .not. el%local_rotation(2)]
  end function rotating

  !> The vector triple (1..4) an element DOF belongs to, 0 for the others.
  pure integer function triple_of(i) result(b)
    integer, intent(in) :: i
    b = 0
    do b = 4, 1, -1
      if (i >= first(b) .and. i <= first(b) + 2) return
    end do
    b = 0
  end function triple_of
end module spatial_mass
