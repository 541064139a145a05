!> The variable correlation table (the papers' term): for every element degree
!> of freedom, the global unknown it equals, times a coefficient; 0 means the
!> DOF is held at zero by a support or a moment-free pin.
!>
!> Element DOFs are [U1 W1 th1 m1 U2 W2 th2 m2]: global X/Y elastic
!> translations, then slope and curvature relative to the link's reference
!> line, at the element's start and end node.  The rules (the report's
!> four-bar assembly, generalised; see doc/correlation_table.md):
!>  - inside a link, consecutive elements share all four DOFs of their common
!>    node (the quintic element is C2 along a straight link);
!>  - 'pin' joining link ends: the translations U, W are shared, each link keeps
!>    its own slope th, and m = 0 (no moment through a pin);
!>  - 'ground_pin': U = W = 0, th free, m = 0;
!>  - 'clamp' (driving shaft, or a built-in end): U = W = th = 0, m free;
!>  - 'slider_fixed': the end moves along a fixed guide at angle alpha:
!>    U = s cos(alpha), W = s sin(alpha) with one global unknown s; th free, m = 0;
!>  - 'free': all four DOFs free (a free end carries no moment either, but
!>    m = 0 is a natural condition there, not imposed).
!> Two layers extend the node DOFs, one table for every model:
!>  - axial_dofs (the consistent element): [ux uxx] at every node, free at
!>    every link end together with m;
!>  - shear_dofs (Tennant's 14-DOF element): [a psi lam], the shear angle,
!>    its derivative and second derivative; a follows th (0 at a clamp), psi
!>    follows m (own at a clamp or free end, else 0), lam is always own.
!> and one more attachment, for Tennant's slider_link joint:
!>  - 'sleeve' (end 2 of a link sliding through a sleeve): the link's local
!>    axial displacement is an own unknown s and its transverse displacement
!>    is the sleeve's (U_s, W_s) across the link (T22), so the element map
!>    depends on the link angle (element_map); th, a own; m = psi = 0. Links
!>    that carry the sleeve are pinned to it (U_s, W_s shared, `carried`);
!>    with no carrier the sleeve pivots on the ground (U_s = W_s = 0).
module correlation_table
  use kinds, only: dp
  use band_assembly, only: add_to_lower_band, add_to_newton_bands
  use error_status, only: error_t
  use strings, only: str
  implicit none
  private
  public :: correlation_base_t, correlation_table_t, link_end_t
  public :: joint_free, joint_pin, joint_ground_pin, joint_clamp, joint_slider_fixed, joint_sleeve

  integer, parameter :: dofs_per_element = 8
  integer, parameter :: joint_free = 0, joint_pin = 1, joint_ground_pin = 2, joint_clamp = 3, &
                        joint_slider_fixed = 4, joint_sleeve = 5
  character(len=*), parameter :: axial_names(6) = ['U  ', 'W  ', 'th ', 'm  ', 'ux ', 'uxx']
  character(len=*), parameter :: shear_names(7) = ['U  ', 'W  ', 'th ', 'm  ', 'a  ', 'psi', 'lam']

  !> How one end of one link is attached.  Link ends with the same `joint`
  !> id > 0 and kind joint_pin share their translations; a sleeve end names
  !> its joint, whose translations are those of the carriers pinned there.
  type :: link_end_t
    integer :: kind = joint_free
    integer :: joint = 0
    real(dp) :: guide_angle = 0.0_dp   !< slider_fixed: guide direction from +X (rad)
    logical :: carried = .false.       !< sleeve: carried by a moving link (else on the ground)
  end type link_end_t

  !> The table itself, for elements of any number of DOFs: every element DOF
  !> equals coef times one global unknown, or is held at zero (map = 0); the
  !> unknowns' labels; gather, scatter and the half-bandwidth.  The planar
  !> rules below (correlation_table_t%build) and the spatial model's joint
  !> rules (spatial_correlation: spatial_table_t) fill it.  The map, its
  !> coefficients, the labels, the number of unknowns and the half-bandwidth
  !> hold together (one label per unknown, the band of the map), so they are
  !> private: read through unknown, coefficient, unknowns, coefficients,
  !> label_of, n_unknowns and band, changed only by the table's own rules.
  type :: correlation_base_t
    integer, private :: n_elem = 0
    integer, private :: el_dofs = dofs_per_element         !< 2 * node_dofs
    integer, private :: n_global = 0
    integer, private :: half_bandwidth = 0                  !< of assembled M and K
    integer, allocatable, private :: map(:, :)              !< (element_dofs, n_elements) global index, 0 = held at zero
    real(dp), allocatable, private :: coef(:, :)            !< (element_dofs, n_elements) element DOF = coef * global
    character(len=24), allocatable, private :: label(:)     !< (n_global) e.g. 'L2 N1 U' or 'J3 s'
  contains
    procedure :: start_table
    procedure :: new_unknown
    procedure :: shared_unknowns
    procedure :: join_nodes
    procedure :: finish_band
    procedure :: widen_band
    procedure :: split_translations
    procedure :: n_elements
    procedure :: element_dofs
    procedure :: n_unknowns
    procedure :: band
    procedure :: unknown
    procedure :: coefficient
    procedure :: unknowns
    procedure :: coefficients
    procedure :: unknowns_of
    procedure :: coefficients_of
    procedure :: label_of
    procedure :: labels
    procedure :: add_lower_band
    procedure :: add_newton_bands
    procedure :: gather
    procedure :: gather_pair
    procedure :: scatter_add
    procedure :: scatter_add_matrix
    procedure :: list_unknowns
    procedure :: table_lines
  end type correlation_base_t

  !> The planar table: links of Kear's, the consistent or Tennant's elements
  !> joined by the planar joint rules above.
  type, extends(correlation_base_t) :: correlation_table_t
    private
    integer :: n_link = 0
    integer :: n_node_dofs = 4                     !< 4: [U W th m] (Kear); 6: also [ux uxx]; 7: also [a psi lam]
    integer, allocatable :: link_of_el(:)          !< (n_elements)
    integer, allocatable :: first_el(:)            !< (n_links + 1): elements of link k are first(k):first(k+1)-1
    integer, allocatable :: sleeve_s(:)            !< (n_elements) axial unknown of a sleeve end at node 2 (0: none)
    integer, allocatable :: sleeve_u(:), sleeve_w(:) !< the sleeve's translations (0: on the ground)
    integer, allocatable :: glob(:, :)             !< (element_dofs + 2, n_elements) globals an element uses
    integer, allocatable :: n_glob(:)              !< (n_elements)
  contains
    procedure, public :: build
    procedure, public :: n_links
    procedure, public :: node_dofs
    procedure, public :: first_element
    procedure, public :: globals_of
    procedure, public :: sleeve_unknowns
    procedure, public :: element_map
    procedure, public :: is_sleeve_element
    procedure, public :: describe
  end type correlation_table_t

contains

  !> Build the table for links with `n_elem(k)` elements each and end
  !> attachments `ends(1:2, k)` (1 = the link's start, 2 = its end).
  !> Unknowns are numbered link by link, node by node (the papers' order);
  !> with reduce_band they are renumbered to narrow the band of M and K.
  !> With axial_dofs every node also carries the local axial strain u_x and
  !> its derivative u_xx (the consistent element's quintic u, doc/element.md);
  !> the curvature-like DOFs m, ux, uxx are then free at every link end (a
  !> pin's zero moment is a natural condition of that element). With
  !> shear_dofs every node carries Tennant's shear-angle DOFs [a psi lam].
  subroutine build(self, n_elem, ends, err, reduce_band, axial_dofs, shear_dofs)
    class(correlation_table_t), intent(out) :: self
    integer, intent(in) :: n_elem(:)
    type(link_end_t), intent(in) :: ends(:, :)
    type(error_t), intent(inout) :: err
    logical, intent(in), optional :: reduce_band   !< renumber by reverse Cuthill-McKee when it narrows the band
    logical, intent(in), optional :: axial_dofs    !< six DOFs per node [U W th m ux uxx]
    logical, intent(in), optional :: shear_dofs    !< seven DOFs per node [U W th m a psi lam]
    integer :: k, j, n_links, nd
    integer, allocatable :: joint_dofs(:, :), node_map(:, :)
    real(dp), allocatable :: node_coef(:, :)

    n_links = size(n_elem)
    call check_ends(n_elem, ends, err)
    if (err%failed()) return
    self%n_node_dofs = 4
    if (present(axial_dofs)) then
      if (axial_dofs) self%n_node_dofs = 6
    end if
    if (present(shear_dofs)) then
      if (shear_dofs) self%n_node_dofs = 7
    end if
    nd = self%n_node_dofs
    call lay_out_links(self, n_elem)

    ! joint_dofs(:, jid): a joint's shared unknowns (U, W of a pin; s of a slider)
    allocate(joint_dofs(2, max(0, maxval(ends%joint))), node_map(nd, 0:maxval(n_elem)), &
             node_coef(nd, 0:maxval(n_elem)))
    joint_dofs = 0
    do k = 1, n_links
      call end_node(self, joint_dofs, ends(1, k), k, 1, self%first_el(k), node_map(:, 0), node_coef(:, 0))
      do j = 1, n_elem(k) - 1
        call interior_node(self, k, j + 1, node_map(:, j), node_coef(:, j))
      end do
      call end_node(self, joint_dofs, ends(2, k), k, n_elem(k) + 1, self%first_el(k + 1) - 1, &
                    node_map(:, n_elem(k)), node_coef(:, n_elem(k)))
      call self%join_nodes(self%first_el(k), node_map(:, 0:n_elem(k)), node_coef(:, 0:n_elem(k)))
    end do
    if (self%n_global == 0) then
      call err%set('correlation table', 'the supports leave no free degree of freedom')
      return
    end if
    call collect_globals(self)
    if (present(reduce_band)) then
      ! (a sleeve couples unknowns the map does not show: keep its numbering)
      if (reduce_band .and. all(self%sleeve_s == 0)) call reduce_bandwidth(self)
    end if
  end subroutine build

  !> Links and their elements, and the empty table (no sleeve ends yet).
  subroutine lay_out_links(self, n_elem)
    type(correlation_table_t), intent(inout) :: self
    integer, intent(in) :: n_elem(:)
    integer :: k
    self%el_dofs = 2*self%n_node_dofs
    self%n_link = size(n_elem)
    self%n_elem = sum(n_elem)
    allocate(self%first_el(self%n_link + 1), self%link_of_el(self%n_elem))
    self%first_el(1) = 1
    do k = 1, self%n_link
      self%first_el(k + 1) = self%first_el(k) + n_elem(k)
      self%link_of_el(self%first_el(k):self%first_el(k + 1) - 1) = k
    end do
    call self%start_table(self%n_elem, self%el_dofs)
    allocate(self%sleeve_s(self%n_elem), self%sleeve_u(self%n_elem), self%sleeve_w(self%n_elem))
    self%sleeve_s = 0
    self%sleeve_u = 0
    self%sleeve_w = 0
  end subroutine lay_out_links

  !> The name of node DOF d in a table of nd DOFs per node.
  pure character(len=3) function node_dof_name(nd, d)
    integer, intent(in) :: nd, d
    if (nd == 7) then
      node_dof_name = shear_names(d)
    else
      node_dof_name = axial_names(d)
    end if
  end function node_dof_name

  !> A node inside a link (or a free end): all its DOFs are own unknowns.
  subroutine interior_node(self, link, node, dofs, coefs)
    type(correlation_table_t), intent(inout) :: self
    integer, intent(in) :: link, node
    integer, intent(out) :: dofs(:)
    real(dp), intent(out) :: coefs(:)
    integer :: d
    do d = 1, size(dofs)
      dofs(d) = self%new_unknown('L'//str(link)//' N'//str(node)//' '//trim(node_dof_name(self%n_node_dofs, d)))
    end do
    coefs = 1.0_dp
  end subroutine interior_node

  !> The node DOFs of a link end by its attachment's rule (module header);
  !> ee is the element the end belongs to (a sleeve's unknowns are per element).
  subroutine end_node(self, joint_dofs, attach, link, node, ee, dofs, coefs)
    type(correlation_table_t), intent(inout) :: self
    integer, intent(inout) :: joint_dofs(:, :)
    type(link_end_t), intent(in) :: attach
    integer, intent(in) :: link, node, ee
    integer, intent(out) :: dofs(:)
    real(dp), intent(out) :: coefs(:)
    character(len=:), allocatable :: where
    character(len=24) :: pin_labels(2), slider_label(1)
    integer :: jid, d
    jid = attach%joint
    where = 'L'//str(link)//' N'//str(node)
    pin_labels(1) = 'J'//str(jid)//' U'
    pin_labels(2) = 'J'//str(jid)//' W'
    slider_label(1) = 'J'//str(jid)//' s'
    dofs = 0
    coefs = 0.0_dp
    select case (attach%kind)
    case (joint_free)
      call interior_node(self, link, node, dofs, coefs)
      return
    case (joint_pin)
      call self%shared_unknowns(joint_dofs(:, jid), pin_labels)
      dofs(1:2) = joint_dofs(:, jid)
      dofs(3) = self%new_unknown(where//' th')
      coefs(1:3) = 1.0_dp
    case (joint_ground_pin)
      dofs(3) = self%new_unknown(where//' th')
      coefs(3) = 1.0_dp
    case (joint_clamp)
      dofs(4) = self%new_unknown(where//' m')
      coefs(4) = 1.0_dp
    case (joint_slider_fixed)
      ! one unknown s along the guide: U = s cos(alpha), W = s sin(alpha)
      if (jid > 0) then
        call self%shared_unknowns(joint_dofs(1:1, jid), slider_label)
        dofs(1:2) = joint_dofs(1, jid)
      else
        dofs(1:2) = self%new_unknown(where//' s')
      end if
      coefs(1:2) = [cos(attach%guide_angle), sin(attach%guide_angle)]
      dofs(3) = self%new_unknown(where//' th')
      coefs(3) = 1.0_dp
    case (joint_sleeve)
      ! (U2, W2) depend on the link angle: element_map builds them; map(U2)
      ! records the axial unknown for the printed table
      self%sleeve_s(ee) = self%new_unknown(where//' s (sleeve)')
      if (attach%carried) then
        call self%shared_unknowns(joint_dofs(:, jid), pin_labels)
        self%sleeve_u(ee) = joint_dofs(1, jid)
        self%sleeve_w(ee) = joint_dofs(2, jid)
      end if
      dofs(1) = self%sleeve_s(ee)
      coefs(1) = 1.0_dp
      dofs(3) = self%new_unknown(where//' th')
      coefs(3) = 1.0_dp
    end select
    if (self%n_node_dofs == 6) then
      ! consistent element: curvature and axial-strain DOFs free at every end
      do d = 4, 6
        if (dofs(d) == 0) dofs(d) = self%new_unknown(where//' '//trim(axial_names(d)))
        coefs(d) = 1.0_dp
      end do
    else if (self%n_node_dofs == 7) then
      ! shear angle a follows th, psi follows m, lam is always own
      if (attach%kind /= joint_clamp) then
        dofs(5) = self%new_unknown(where//' a')
        coefs(5) = 1.0_dp
      else
        dofs(6) = self%new_unknown(where//' psi')
        coefs(6) = 1.0_dp
      end if
      dofs(7) = self%new_unknown(where//' lam')
      coefs(7) = 1.0_dp
    end if
  end subroutine end_node

  !> Shape and joint ids of the end descriptions; a sleeve is end 2 of a
  !> one-element link (its length varies with the sleeve, T24).
  subroutine check_ends(n_elem, ends, err)
    integer, intent(in) :: n_elem(:)
    type(link_end_t), intent(in) :: ends(:, :)
    type(error_t), intent(inout) :: err
    integer :: k, side
    if (size(ends, 1) /= 2 .or. size(ends, 2) /= size(n_elem)) then
      call err%set('correlation table', 'need two end descriptions per link')
      return
    end if
    if (any(n_elem < 1)) then
      call err%set('correlation table', 'every link needs at least one element')
      return
    end if
    do k = 1, size(n_elem)
      do side = 1, 2
        if (any(ends(side, k)%kind == [joint_pin, joint_sleeve]) .and. ends(side, k)%joint <= 0) then
          call err%set('correlation table', 'link '//str(k)//' end '//str(side)//' needs a joint id')
          return
        end if
      end do
      if (ends(1, k)%kind == joint_sleeve) then
        call err%set('correlation table', 'link '//str(k)//': the sleeve must be at end 2 of the sliding link')
        return
      end if
      if (ends(2, k)%kind == joint_sleeve .and. n_elem(k) /= 1) then
        call err%set('correlation table', 'link '//str(k)//' slides through a sleeve: it must be one element '// &
                     '(its length varies with the sleeve, T24)')
        return
      end if
    end do
  end subroutine check_ends

  !> The globals each element uses (a sleeve element also uses the sleeve's
  !> U_s, W_s) and the half-bandwidth they give.
  subroutine collect_globals(self)
    type(correlation_table_t), intent(inout) :: self
    integer :: e, i
    if (allocated(self%glob)) deallocate(self%glob, self%n_glob)
    allocate(self%glob(self%el_dofs + 2, self%n_elem), self%n_glob(self%n_elem))
    self%glob = 0
    self%n_glob = 0
    self%half_bandwidth = 0
    do e = 1, self%n_elem
      do i = 1, self%el_dofs
        call add_glob(e, self%map(i, e))
      end do
      call add_glob(e, self%sleeve_u(e))
      call add_glob(e, self%sleeve_w(e))
      if (self%n_glob(e) > 0) self%half_bandwidth = max(self%half_bandwidth, &
        maxval(self%glob(1:self%n_glob(e), e)) - minval(self%glob(1:self%n_glob(e), e)))
    end do
  contains
    subroutine add_glob(ee, g)
      integer, intent(in) :: ee, g
      if (g <= 0) return
      if (any(self%glob(1:self%n_glob(ee), ee) == g)) return
      self%n_glob(ee) = self%n_glob(ee) + 1
      self%glob(self%n_glob(ee), ee) = g
    end subroutine add_glob
  end subroutine collect_globals

  !> Half-bandwidth of the assembled matrices for a given numbering.
  pure integer function bandwidth(map) result(kd)
    integer, intent(in) :: map(:, :)
    integer :: e
    kd = 0
    do e = 1, size(map, 2)
      if (any(map(:, e) > 0)) kd = max(kd, maxval(map(:, e)) - minval(map(:, e), mask=map(:, e) > 0))
    end do
  end function bandwidth

  !> Renumber the global unknowns by reverse Cuthill-McKee when that narrows
  !> the band.  Numbering link by link keeps a chain of links narrow only if
  !> every link runs away from the joint it shares with the links before it;
  !> a link drawn towards that joint (a rocker from its ground pivot D to the
  !> coupler pin C) would couple its last node to unknowns numbered long
  !> before, and the band would grow with the number of elements.
  subroutine reduce_bandwidth(self)
    type(correlation_table_t), intent(inout) :: self
    integer, allocatable :: degree(:), start(:), adj(:), order(:), new_index(:), fill(:), new_map(:, :), all_unknowns(:)
    logical, allocatable :: placed(:)
    integer :: n, e, i, j, a, b, head, tail, root, v, best
    character(len=24), allocatable :: new_label(:)
    n = self%n_global
    ! adjacency of the unknowns (two unknowns of one element are coupled), in CSR form
    allocate(degree(n), start(n + 1))
    degree = 0
    do e = 1, self%n_elem
      do i = 1, self%el_dofs
        do j = 1, self%el_dofs
          a = self%map(i, e)
          b = self%map(j, e)
          if (a > 0 .and. b > 0 .and. a /= b) degree(a) = degree(a) + 1
        end do
      end do
    end do
    start(1) = 1
    do i = 1, n
      start(i + 1) = start(i) + degree(i)
    end do
    allocate(adj(max(1, start(n + 1) - 1)), fill(n))
    fill = start(1:n)
    do e = 1, self%n_elem
      do i = 1, self%el_dofs
        do j = 1, self%el_dofs
          a = self%map(i, e)
          b = self%map(j, e)
          if (a > 0 .and. b > 0 .and. a /= b) then
            adj(fill(a)) = b
            fill(a) = fill(a) + 1
          end if
        end do
      end do
    end do
    ! Cuthill-McKee from a lowest-degree unknown of every component, then reversed
    allocate(order(n), placed(n))
    all_unknowns = [(i, i=1, n)]
    placed = .false.
    tail = 0
    do while (tail < n)
      root = least_degree(all_unknowns, degree, placed)
      tail = tail + 1
      order(tail) = root
      placed(root) = .true.
      head = tail
      do while (head <= tail)
        v = order(head)
        head = head + 1
        ! append the unplaced neighbours of v, lowest degree first
        do
          best = least_degree(adj(start(v):start(v + 1) - 1), degree, placed)
          if (best == 0) exit
          tail = tail + 1
          order(tail) = best
          placed(best) = .true.
        end do
      end do
    end do
    allocate(new_index(n))
    do i = 1, n
      new_index(order(n + 1 - i)) = i
    end do
    new_map = self%map
    do e = 1, self%n_elem
      do i = 1, self%el_dofs
        if (self%map(i, e) > 0) new_map(i, e) = new_index(self%map(i, e))
      end do
    end do
    if (bandwidth(new_map) >= self%half_bandwidth) return
    allocate(new_label(n))
    do i = 1, n
      new_label(new_index(i)) = self%label(i)
    end do
    self%map = new_map
    self%label = new_label
    call collect_globals(self)
  end subroutine reduce_bandwidth

  !> The first unplaced candidate of least degree (0: all are placed).
  pure integer function least_degree(candidates, degree, placed) result(best)
    integer, intent(in) :: candidates(:), degree(:)
    logical, intent(in) :: placed(:)
    integer :: k, m
    best = 0
    do k = 1, size(candidates)
      m = candidates(k)
      if (placed(m)) cycle
      if (best == 0) then
        best = m
      else if (degree(m) < degree(best)) then
        best = m
      end if
    end do
  end function least_degree

  !> An empty table of n_elements elements with element_dofs DOFs each:
  !> every DOF held at zero, no global unknowns yet.
  subroutine start_table(self, n_elements, element_dofs)
    class(correlation_base_t), intent(inout) :: self
    integer, intent(in) :: n_elements, element_dofs
    self%n_elem = n_elements
    self%el_dofs = element_dofs
    self%n_global = 0
    if (allocated(self%map)) deallocate(self%map)
    if (allocated(self%coef)) deallocate(self%coef)
    if (allocated(self%label)) deallocate(self%label)
    allocate(self%map(element_dofs, n_elements), self%coef(element_dofs, n_elements), self%label(0))
    self%map = 0
    self%coef = 0.0_dp
  end subroutine start_table

  !> A fresh global unknown with its label (such as 'crank N2 RZ').
  integer function new_unknown(self, text) result(g)
    class(correlation_base_t), intent(inout) :: self
    character(len=*), intent(in) :: text
    self%n_global = self%n_global + 1
    self%label = [character(len=24) :: self%label, text]
    g = self%n_global
  end function new_unknown

  !> A joint's shared unknowns, created with their labels at the joint's
  !> first visit (ids still 0); later visits find them in ids.
  subroutine shared_unknowns(self, ids, labels)
    class(correlation_base_t), intent(inout) :: self
    integer, intent(inout) :: ids(:)
    character(len=*), intent(in) :: labels(:)
    integer :: i
    if (ids(1) /= 0) return
    do i = 1, size(ids)
      ids(i) = self%new_unknown(labels(i))
    end do
  end subroutine shared_unknowns

  !> The elements of one link from its nodes 0..n (node_map(:, j): the node
  !> DOFs' global unknowns, node_coef their coefficients): element
  !> first_element + j - 1 joins nodes j - 1 and j.
  subroutine join_nodes(self, first_element, node_map, node_coef)
    class(correlation_base_t), intent(inout) :: self
    integer, intent(in) :: first_element
    integer, intent(in) :: node_map(:, 0:)
    real(dp), intent(in) :: node_coef(:, 0:)
    integer :: j, nd
    nd = size(node_map, 1)
    do j = 1, ubound(node_map, 2)
      self%map(1:nd, first_element + j - 1) = node_map(:, j - 1)
      self%coef(1:nd, first_element + j - 1) = node_coef(:, j - 1)
      self%map(nd + 1:2*nd, first_element + j - 1) = node_map(:, j)
      self%coef(nd + 1:2*nd, first_element + j - 1) = node_coef(:, j)
    end do
  end subroutine join_nodes

  !> The half-bandwidth of the assembled matrices, from the map alone.
  subroutine finish_band(self)
    class(correlation_base_t), intent(inout) :: self
    self%half_bandwidth = bandwidth(self%map)
  end subroutine finish_band

  !> The half-bandwidth at least kd (couplings between unknowns that no
  !> element joins, such as a clearance joint's contact).
  subroutine widen_band(self, kd)
    class(correlation_base_t), intent(inout) :: self
    integer, intent(in) :: kd
    self%half_bandwidth = max(self%half_bandwidth, kd)
  end subroutine widen_band

  !> Give element DOFs first and first + 1 of element e (a node's two
  !> translations) their own two global unknowns, labelled `labels`,
  !> numbered after the largest of their old unknowns and the DOF first + 2
  !> (the node's slope); every unknown numbered after that moves up by two.
  !> old: the unknowns the DOFs had (0: held at zero), new: their own ones.
  !> Refused when the DOFs are not plain unknowns (coefficient 1) or nothing
  !> precedes them to number after.
  subroutine split_translations(self, e, first, labels, old, new, err)
    class(correlation_base_t), intent(inout) :: self
    integer, intent(in) :: e, first
    character(len=*), intent(in) :: labels(2)
    integer, intent(out) :: old(2), new(2)
    type(error_t), intent(inout) :: err
    integer :: p
    character(len=24), allocatable :: label(:)
    old = self%map(first:first + 1, e)
    new = 0
    if (any(abs(self%coef(first:first + 1, e) - 1.0_dp) > 0.0_dp .and. old > 0)) then
      call err%set('', 'the node''s translations are not plain unknowns')
      return
    end if
    p = max(maxval(old), self%map(first + 2, e))
    if (p <= 0) then
      call err%set('', 'the node has no free unknown to number after')
      return
    end if
    where (self%map > p) self%map = self%map + 2
    ! the old unknowns (numbered <= p) stay as they were
    new = [p + 1, p + 2]
    self%map(first:first + 1, e) = new
    self%coef(first:first + 1, e) = 1.0_dp
    allocate(label(self%n_global + 2))
    label(1:p) = self%label(1:p)
    label(p + 1:p + 2) = labels
    label(p + 3:) = self%label(p + 1:self%n_global)
    call move_alloc(label, self%label)
    self%n_global = self%n_global + 2
    self%half_bandwidth = bandwidth(self%map)
  end subroutine split_translations

  !> The number of elements.
  pure integer function n_elements(self)
    class(correlation_base_t), intent(in) :: self
    n_elements = self%n_elem
  end function n_elements

  !> The DOFs of one element (twice the DOFs of a node).
  pure integer function element_dofs(self)
    class(correlation_base_t), intent(in) :: self
    element_dofs = self%el_dofs
  end function element_dofs

  !> The number of global unknowns.
  pure integer function n_unknowns(self)
    class(correlation_base_t), intent(in) :: self
    n_unknowns = self%n_global
  end function n_unknowns

  !> The half-bandwidth of the assembled matrices.
  pure integer function band(self)
    class(correlation_base_t), intent(in) :: self
    band = self%half_bandwidth
  end function band

  !> The global unknown of DOF i of element e (0: held at zero).
  pure integer function unknown(self, i, e)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: i, e
    unknown = self%map(i, e)
  end function unknown

  !> The coefficient of DOF i of element e: DOF = coefficient * unknown.
  pure real(dp) function coefficient(self, i, e)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: i, e
    coefficient = self%coef(i, e)
  end function coefficient

  !> The global unknowns of element e's DOFs (0: held at zero).
  pure function unknowns(self, e) result(g)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    integer :: g(self%el_dofs)
    g = self%map(:, e)
  end function unknowns

  !> The global unknowns of element e's DOFs dofs (0: held at zero).
  pure function unknowns_of(self, dofs, e) result(g)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: dofs(:), e
    integer :: g(size(dofs))
    g = self%map(dofs, e)
  end function unknowns_of

  !> The coefficients of element e's DOFs dofs.
  pure function coefficients_of(self, dofs, e) result(c)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: dofs(:), e
    real(dp) :: c(size(dofs))
    c = self%coef(dofs, e)
  end function coefficients_of

  !> The coefficients of element e's DOFs.
  pure function coefficients(self, e) result(c)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp) :: c(self%el_dofs)
    c = self%coef(:, e)
  end function coefficients

  !> The label of global unknown g (such as 'L2 N1 U').
  pure character(len=24) function label_of(self, g)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: g
    label_of = self%label(g)
  end function label_of

  !> The labels of all global unknowns, in their order.
  pure function labels(self) result(l)
    class(correlation_base_t), intent(in) :: self
    character(len=24) :: l(self%n_global)
    l = self%label
  end function labels

  !> Element e's symmetric matrix me into the global lower band storage band
  !> (module band_assembly).
  pure subroutine add_lower_band(self, e, me, band)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: me(:, :)
    real(dp), intent(inout) :: band(:, :)
    call add_to_lower_band(band, me, self%map(:, e), self%coef(:, e))
  end subroutine add_lower_band

  !> Element e's M and K_t into the Newton matrix's bands (band_assembly's
  !> add_to_newton_bands).
  pure subroutine add_newton_bands(self, e, me, ke, kd, mass_lower, stiff_band)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e, kd
    real(dp), intent(in) :: me(:, :), ke(:, :)
    real(dp), intent(inout) :: mass_lower(:, :), stiff_band(:, :)
    call add_to_newton_bands(mass_lower, stiff_band, kd, me, ke, self%map(:, e), self%coef(:, e))
  end subroutine add_newton_bands

  !> Element DOF vector from the global vector.
  pure function gather(self, e, qg) result(qe)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: qg(:)
    real(dp) :: qe(self%el_dofs)
    integer :: i
    do i = 1, self%el_dofs
      if (self%map(i, e) > 0) then
        qe(i) = self%coef(i, e)*qg(self%map(i, e))
      else
        qe(i) = 0.0_dp
      end if
    end do
  end function gather

  !> gather of two global vectors (displacements and rates) in one pass.
  pure subroutine gather_pair(self, e, q, qd, qe, qde)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: q(:), qd(:)
    real(dp), intent(out) :: qe(:), qde(:)
    integer :: i, g
    do i = 1, self%el_dofs
      g = self%map(i, e)
      if (g > 0) then
        qe(i) = self%coef(i, e)*q(g)
        qde(i) = self%coef(i, e)*qd(g)
      else
        qe(i) = 0.0_dp
        qde(i) = 0.0_dp
      end if
    end do
  end subroutine gather_pair

  !> fg += T_e^T fe  (the transpose of gather).
  pure subroutine scatter_add(self, e, fe, fg)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: fe(:)
    real(dp), intent(inout) :: fg(:)
    integer :: i
    do i = 1, self%el_dofs
      if (self%map(i, e) > 0) fg(self%map(i, e)) = fg(self%map(i, e)) + self%coef(i, e)*fe(i)
    end do
  end subroutine scatter_add

  !> Dense A += T_e^T Ae T_e.
  pure subroutine scatter_add_matrix(self, e, ae, ag)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: ae(:, :)
    real(dp), intent(inout) :: ag(:, :)
    integer :: i, j, gi, gj
    do j = 1, self%el_dofs
      gj = self%map(j, e)
      if (gj == 0) cycle
      do i = 1, self%el_dofs
        gi = self%map(i, e)
        if (gi == 0) cycle
        ag(gi, gj) = ag(gi, gj) + self%coef(i, e)*ae(i, j)*self%coef(j, e)
      end do
    end do
  end subroutine scatter_add_matrix

  !> The header's list of global unknowns, four to a line, each label in
  !> label_width characters: (n_global + 3)/4 lines.
  subroutine list_unknowns(self, label_width, lines)
    class(correlation_base_t), intent(in) :: self
    integer, intent(in) :: label_width
    character(len=*), intent(inout) :: lines(:)
    character(len=32) :: fmt
    integer :: i, g
    write(fmt, '(a,i0,a)') '(2x,i4,": ",a', label_width, ')'
    do i = 1, (self%n_global + 3)/4
      lines(i) = ''
      do g = 4*(i - 1) + 1, min(4*i, self%n_global)
        write(lines(i)(len_trim(lines(i)) + 1:), fmt) g, self%label(g)
      end do
    end do
  end subroutine list_unknowns

  !> The header's table: the head lines, one row per element, then the
  !> global unknowns (list_unknowns).
  subroutine table_lines(self, head, rows, label_width, lines)
    class(correlation_base_t), intent(in) :: self
    character(len=*), intent(in) :: head(:), rows(:)
    integer, intent(in) :: label_width
    character(len=160), allocatable, intent(out) :: lines(:)
    integer :: n_head, n_rows
    n_head = size(head)
    n_rows = size(rows)
    allocate(lines(n_head + n_rows + 1 + (self%n_global + 3)/4))
    lines(1:n_head) = head
    lines(n_head + 1:n_head + n_rows) = rows
    lines(n_head + n_rows + 1) = '  global unknowns:'
    call self%list_unknowns(label_width, lines(n_head + n_rows + 2:))
  end subroutine table_lines

  !> The number of links.
  pure integer function n_links(self)
    class(correlation_table_t), intent(in) :: self
    n_links = self%n_link
  end function n_links

  !> The DOFs of one node: 4 [U W th m], 6 (also [ux uxx]) or 7 (also [a psi lam]).
  pure integer function node_dofs(self)
    class(correlation_table_t), intent(in) :: self
    node_dofs = self%n_node_dofs
  end function node_dofs

  !> The first element of link k (k = n_links + 1: one past the last element).
  pure integer function first_element(self, k)
    class(correlation_table_t), intent(in) :: self
    integer, intent(in) :: k
    first_element = self%first_el(k)
  end function first_element

  !> The global unknowns element e uses, in element_map's column order (a
  !> sleeve element also uses the sleeve's U_s, W_s).
  pure function globals_of(self, e) result(g)
    class(correlation_table_t), intent(in) :: self
    integer, intent(in) :: e
    integer :: g(self%n_glob(e))
    g = self%glob(1:self%n_glob(e), e)
  end function globals_of

  !> A sleeve end of element e: its axial unknown s and the sleeve's
  !> translations U_s, W_s (0: none, or on the ground).
  pure function sleeve_unknowns(self, e) result(g)
    class(correlation_table_t), intent(in) :: self
    integer, intent(in) :: e
    integer :: g(3)
    g = [self%sleeve_s(e), self%sleeve_u(e), self%sleeve_w(e)]
  end function sleeve_unknowns

  logical pure function is_sleeve_element(self, e)
    class(correlation_table_t), intent(in) :: self
    integer, intent(in) :: e
    is_sleeve_element = self%sleeve_s(e) > 0
  end function is_sleeve_element

  !> The map of element e as a dense matrix: q_e = C Q(glob(1:ng)), with its
  !> time derivatives (nonzero only for a sleeve end, where C depends on the
  !> sliding link's angle phi).
  pure subroutine element_map(self, e, phi, phi_d, phi_dd, ng, c0, c1, c2)
    class(correlation_table_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: phi, phi_d, phi_dd
    integer, intent(out) :: ng
    real(dp), intent(out) :: c0(:, :), c1(:, :), c2(:, :)
    integer :: i, col, js, ju, jw, iu
    real(dp) :: c, s, c2a, s2a, dphi(2, 3), ddphi(2, 3)
    ng = self%n_glob(e)
    c0(1:self%el_dofs, 1:ng) = 0.0_dp
    c1(1:self%el_dofs, 1:ng) = 0.0_dp
    c2(1:self%el_dofs, 1:ng) = 0.0_dp
    do i = 1, self%el_dofs
      if (self%map(i, e) == 0) cycle
      col = findloc(self%glob(1:ng, e), self%map(i, e), dim=1)
      c0(i, col) = self%coef(i, e)
    end do
    if (self%sleeve_s(e) == 0) return
    ! sleeve at node 2: (U2, W2) = s u(phi) + (u_perp . (U_s, W_s)) u_perp
    iu = self%n_node_dofs + 1
    c = cos(phi)
    s = sin(phi)
    c2a = cos(2.0_dp*phi)
    s2a = sin(2.0_dp*phi)
    js = findloc(self%glob(1:ng, e), self%sleeve_s(e), dim=1)
    c0(iu:iu + 1, js) = [c, s]
    dphi(:, 1) = [-s, c]
    ddphi(:, 1) = [-c, -s]
    if (self%sleeve_u(e) > 0) then
      ju = findloc(self%glob(1:ng, e), self%sleeve_u(e), dim=1)
      jw = findloc(self%glob(1:ng, e), self%sleeve_w(e), dim=1)
      c0(iu:iu + 1, ju) = [0.5_dp*(1.0_dp - c2a), -0.5_dp*s2a]
      c0(iu:iu + 1, jw) = [-0.5_dp*s2a, 0.5_dp*(1.0_dp + c2a)]
      dphi(:, 2) = [s2a, -c2a]
      dphi(:, 3) = [-c2a, -s2a]
      ddphi(:, 2) = [2.0_dp*c2a, 2.0_dp*s2a]
      ddphi(:, 3) = [2.0_dp*s2a, -2.0_dp*c2a]
      c1(iu:iu + 1, ju) = phi_d*dphi(:, 2)
      c1(iu:iu + 1, jw) = phi_d*dphi(:, 3)
      c2(iu:iu + 1, ju) = phi_d*phi_d*ddphi(:, 2) + phi_dd*dphi(:, 2)
      c2(iu:iu + 1, jw) = phi_d*phi_d*ddphi(:, 3) + phi_dd*dphi(:, 3)
    end if
    c1(iu:iu + 1, js) = phi_d*dphi(:, 1)
    c2(iu:iu + 1, js) = phi_d*phi_d*ddphi(:, 1) + phi_dd*dphi(:, 1)
  end subroutine element_map

  !> The table as text lines, for the output header: one line per element
  !> with the global unknown of each element DOF (0 = held at zero), then the
  !> list of global unknowns.
  subroutine describe(self, lines)
    class(correlation_table_t), intent(in) :: self
    character(len=160), allocatable, intent(out) :: lines(:)
    character(len=160) :: head(3), rows(self%n_elem)
    integer :: e, nd
    character(len=160) :: l
    write(head(1), '(a,i0,a,i0,a,i0,a,i0)') 'variable correlation table: ', self%n_elem, ' elements of ', &
      self%el_dofs, ' DOFs, ', self%n_global, ' global unknowns, half-bandwidth ', self%half_bandwidth
    nd = self%n_node_dofs
    select case (nd)
    case (6)
      head(2) = '  element link :   U1   W1  th1   m1  ux1 uxx1   U2   W2  th2   m2  ux2 uxx2   (global unknown; ' &
                //'0 = held at zero)'
    case (7)
      head(2) = '  element link :   U1   W1  th1   m1   a1 psi1 lam1   U2   W2  th2   m2   a2 psi2 lam2   (global ' &
                //'unknown; 0 = held at zero)'
    case default
      head(2) = '  element link :   U1   W1  th1   m1   U2   W2  th2   m2   (global unknown; 0 = held at zero)'
    end select
    head(3) = '  ----------------------------------------------------------------------'
    do e = 1, self%n_elem
      write(l, '(2x,i7,i5,a,14i5)') e, self%link_of_el(e), ' :', self%map(:, e)
      if (self%sleeve_s(e) > 0 .and. self%sleeve_u(e) > 0) then
        write(l(len_trim(l) + 1:), '(a,i0,a,i0,a,i0,a)') '  (sleeve: U2, W2 from s = ', self%sleeve_s(e), &
          ' and U_s, W_s = ', self%sleeve_u(e), ', ', self%sleeve_w(e), ')'
      else if (self%sleeve_s(e) > 0) then
        write(l(len_trim(l) + 1:), '(a,i0,a)') '  (ground sleeve: U2, W2 = s u(phi), s = ', self%sleeve_s(e), ')'
      else if (any(self%map(1:2, e) > 0 .and. self%map(1:2, e) == self%map([2, 1], e)) .or. &
               any(self%map(nd + 1:nd + 2, e) > 0 .and. self%map(nd + 1:nd + 2, e) == self%map([nd + 2, nd + 1], e))) then
        l = trim(l)//'  (slider: U, W = s * guide direction)'
      end if
      rows(e) = l
    end do
    call self%table_lines(head, rows, 18, lines)
  end subroutine describe
end module correlation_table
