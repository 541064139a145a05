!> The variable correlation table for Tennant's elements: the rules of module
!> correlation_table (doc/correlation_table.md) for the 8-DOF slender element,
!> extended to the shear-angle DOFs of the 14-DOF element and to the end of a
!> link that slides through a sleeve on a rotating link or on the ground.
!>
!> Node DOFs: U W th m [a psi lam] (a = alpha, psi = alpha_x, lam = alpha_xx).
!> The shear angle follows the rotation-type DOF th, its derivative psi (which
!> carries the bending moment, T12: eps = y alpha_x) follows the moment-type
!> DOF m, and lam (the shear-force-type DOF) is always free:
!>   interior node  all own (consecutive elements of a link share all DOFs)
!>   pin            U, W shared; th, a own; m = psi = 0; lam own
!>   ground_pin     U = W = 0; th, a own; m = psi = 0; lam own
!>   clamp          U = W = th = 0, a = 0; m, psi, lam own
!>   slider_fixed   U = s cos(g), W = s sin(g); th, a own; m = psi = 0; lam own
!>   free           all own
!>   sleeve end     (end 2 of a link sliding through a slider_link joint) the
!>                  link's local axial displacement u2 is an own unknown s; its
!>                  local transverse displacement is the sleeve's displacement
!>                  (U_s, W_s) across the link:  w2 = -sin(phi) U_s + cos(phi) W_s
!>                  (T22: the driver link's deformation in the output link's
!>                  axes), so (U2, W2) = s u(phi) + (u_perp . (U_s, W_s)) u_perp;
!>                  th, a own; m = psi = 0; lam own.
!> Links that end at a slider_link joint without sliding through it carry the
!> sleeve and are pinned to it (U_s, W_s shared); with no such link the sleeve
!> pivots on the ground (U_s = W_s = 0).  Unknowns are numbered as in
!> correlation_table: link by link, node by node, a pin's translations when the
!> pin is first met, so the 8-DOF table equals correlation_table's.
module tennant_table
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  implicit none
  private
  public :: tennant_table_t, table_end_t
  public :: end_free, end_pin, end_ground_pin, end_clamp, end_slider_fixed, end_sleeve

  ! the codes of module correlation_table (and linkage), plus the sleeve end
  integer, parameter :: end_free = 0, end_pin = 1, end_ground_pin = 2, end_clamp = 3, end_slider_fixed = 4
  integer, parameter :: end_sleeve = 5
  character(len=*), parameter :: dof_names(7) = ['U  ', 'W  ', 'th ', 'm  ', 'a  ', 'psi', 'lam']

  !> How one end of one link is attached.  Ends with the same joint id > 0
  !> and kind end_pin share their translations; a sleeve end names its
  !> joint, whose translations are those of the carriers pinned there
  !> (`carried`) or zero.
  type :: table_end_t
    integer :: kind = end_free
    integer :: joint = 0
    real(dp) :: guide_angle = 0.0_dp
    logical :: carried = .false.
  end type table_end_t

  type :: tennant_table_t
    integer :: nd = 8, nn = 4
    integer :: n_links = 0, n_elements = 0, n_global = 0
    integer :: half_bandwidth = 0
    integer, allocatable :: link_of_element(:)
    integer, allocatable :: first_element(:)        !< (n_links + 1)
    integer, allocatable :: map(:, :)               !< (nd, n_elements): global index, 0 = held at zero
    real(dp), allocatable :: coef(:, :)             !< element DOF = coef * global
    integer, allocatable :: sleeve_s(:)             !< (n_elements) axial unknown of a sleeve end at node 2 (0: none)
    integer, allocatable :: sleeve_u(:), sleeve_w(:) !< the sleeve's translations (0: on the ground)
    integer, allocatable :: glob(:, :)              !< (nd + 1, n_elements) globals an element uses
    integer, allocatable :: n_glob(:)
    character(len=24), allocatable :: label(:)
  contains
    procedure :: build
    procedure :: element_map
    procedure :: describe
    procedure :: is_sleeve_element
  end type tennant_table_t

contains

  !> Build the table for links with n_elem(k) elements and end attachments
  !> ends(1:2, k); shear = 14-DOF elements.
  subroutine build(self, n_elem, ends, shear, err)
    class(tennant_table_t), intent(out) :: self
    integer, intent(in) :: n_elem(:)
    type(table_end_t), intent(in) :: ends(:, :)
    logical, intent(in) :: shear
    type(error_t), intent(inout) :: err
    integer :: k, e, n_links, next, max_joint, side, i, lo, hi, nn
    integer, allocatable :: joint_u(:), joint_w(:), joint_kind(:)
    integer :: node(7)
    real(dp) :: c(7)

    n_links = size(n_elem)
    self%nd = merge(14, 8, shear)
    self%nn = self%nd/2
    nn = self%nn
    if (size(ends, 1) /= 2 .or. size(ends, 2) /= n_links) then
      call err%set('correlation table', 'need two end descriptions per link'); return
    end if
    if (any(n_elem < 1)) then
      call err%set('correlation table', 'every link needs at least one element'); return
    end if
    do k = 1, n_links
      do side = 1, 2
        if (any(ends(side, k)%kind == [end_pin, end_sleeve]) .and. ends(side, k)%joint <= 0) then
          call err%set('correlation table', 'link '//str(k)//' end '//str(side)//' needs a joint id'); return
        end if
      end do
      if (ends(1, k)%kind == end_sleeve) then
        call err%set('correlation table', 'link '//str(k)//': the sleeve must be at end 2 of the sliding link'); return
      end if
      if (ends(2, k)%kind == end_sleeve .and. n_elem(k) /= 1) then
        call err%set('correlation table', 'link '//str(k)//' slides through a sleeve: it must be one element '// &
                     '(its length varies with the sleeve, T24)'); return
      end if
    end do

    self%n_links = n_links
    self%n_elements = sum(n_elem)
    allocate(self%first_element(n_links + 1), self%link_of_element(self%n_elements))
    self%first_element(1) = 1
    do k = 1, n_links
      self%first_element(k + 1) = self%first_element(k) + n_elem(k)
      self%link_of_element(self%first_element(k):self%first_element(k + 1) - 1) = k
    end do
    allocate(self%map(self%nd, self%n_elements), self%coef(self%nd, self%n_elements))
    allocate(self%sleeve_s(self%n_elements), self%sleeve_u(self%n_elements), self%sleeve_w(self%n_elements))
    self%map = 0
    self%coef = 0.0_dp
    self%sleeve_s = 0
    self%sleeve_u = 0
    self%sleeve_w = 0
    allocate(self%label(0))
    max_joint = max(0, maxval(ends%joint))
    allocate(joint_u(max_joint), joint_w(max_joint), joint_kind(max_joint))
    joint_u = 0
    joint_w = 0
    joint_kind = -1

    next = 0
    do k = 1, n_links
      do e = self%first_element(k), self%first_element(k + 1) - 1
        if (e == self%first_element(k)) then
          call end_node(ends(1, k), k, 1, e, node, c)
        else
          node(1:nn) = self%map(nn + 1:2*nn, e - 1)
          c(1:nn) = self%coef(nn + 1:2*nn, e - 1)
        end if
        self%map(1:nn, e) = node(1:nn)
        self%coef(1:nn, e) = c(1:nn)
        if (e == self%first_element(k + 1) - 1) then
          call end_node(ends(2, k), k, n_elem(k) + 1, e, node, c)
        else
          call interior_node(k, e - self%first_element(k) + 2, node, c)
        end if
        self%map(nn + 1:2*nn, e) = node(1:nn)
        self%coef(nn + 1:2*nn, e) = c(1:nn)
      end do
    end do
    self%n_global = next

    ! globals of each element (a sleeve element also uses the sleeve's U_s, W_s)
    allocate(self%glob(self%nd + 2, self%n_elements), self%n_glob(self%n_elements))
    self%glob = 0
    self%n_glob = 0
    self%half_bandwidth = 0
    do e = 1, self%n_elements
      do i = 1, self%nd
        call add_glob(e, self%map(i, e))
      end do
      call add_glob(e, self%sleeve_u(e))
      call add_glob(e, self%sleeve_w(e))
      if (self%n_glob(e) > 0) then
        lo = minval(self%glob(1:self%n_glob(e), e))
        hi = maxval(self%glob(1:self%n_glob(e), e))
        self%half_bandwidth = max(self%half_bandwidth, hi - lo)
      end if
    end do
    if (self%n_global == 0) call err%set('correlation table', 'the supports leave no free degree of freedom')

  contains

    subroutine add_glob(ee, g)
      integer, intent(in) :: ee, g
      if (g <= 0) return
      if (any(self%glob(1:self%n_glob(ee), ee) == g)) return
      self%n_glob(ee) = self%n_glob(ee) + 1
      self%glob(self%n_glob(ee), ee) = g
    end subroutine add_glob

    integer function new_dof(text)
      character(len=*), intent(in) :: text
      next = next + 1
      self%label = [character(len=24) :: self%label, text]
      new_dof = next
    end function new_dof

    subroutine interior_node(link, nd_, dofs, coefs)
      integer, intent(in) :: link, nd_
      integer, intent(out) :: dofs(7)
      real(dp), intent(out) :: coefs(7)
      integer :: d
      dofs = 0
      do d = 1, nn
        dofs(d) = new_dof('L'//str(link)//' N'//str(nd_)//' '//trim(dof_names(d)))
      end do
      coefs = 1.0_dp
    end subroutine interior_node

    !> Shear-angle DOFs of an end: a own unless clamped, psi own only at a clamp
    !> or free end (where m is own too), lam own.
    subroutine alpha_dofs(where, a_own, psi_own, dofs, coefs)
      character(len=*), intent(in) :: where
      logical, intent(in) :: a_own, psi_own
      integer, intent(inout) :: dofs(7)
      real(dp), intent(inout) :: coefs(7)
      if (nn < 7) return
      if (a_own) then
        dofs(5) = new_dof(where//' a')
        coefs(5) = 1.0_dp
      end if
      if (psi_own) then
        dofs(6) = new_dof(where//' psi')
        coefs(6) = 1.0_dp
      end if
      dofs(7) = new_dof(where//' lam')
      coefs(7) = 1.0_dp
    end subroutine alpha_dofs

    subroutine end_node(attach, link, nd_, ee, dofs, coefs)
      type(table_end_t), intent(in) :: attach
      integer, intent(in) :: link, nd_, ee
      integer, intent(out) :: dofs(7)
      real(dp), intent(out) :: coefs(7)
      character(len=:), allocatable :: where
      integer :: jid
      where = 'L'//str(link)//' N'//str(nd_)
      dofs = 0
      coefs = 0.0_dp
      jid = attach%joint
      select case (attach%kind)
      case (end_free)
        call interior_node(link, nd_, dofs, coefs)
      case (end_pin)
        call pin_translations(jid)
        dofs(1:2) = [joint_u(jid), joint_w(jid)]
        dofs(3) = new_dof(where//' th')
        coefs(1:3) = 1.0_dp
        call alpha_dofs(where, .true., .false., dofs, coefs)
      case (end_ground_pin)
        dofs(3) = new_dof(where//' th')
        coefs(3) = 1.0_dp
        call alpha_dofs(where, .true., .false., dofs, coefs)
      case (end_clamp)
        dofs(4) = new_dof(where//' m')
        coefs(4) = 1.0_dp
        call alpha_dofs(where, .false., .true., dofs, coefs)
      case (end_slider_fixed)
        if (jid > 0) then
          if (joint_kind(jid) == -1) then
            joint_kind(jid) = end_slider_fixed
            joint_u(jid) = new_dof('J'//str(jid)//' s')
          end if
          dofs(1:2) = joint_u(jid)
        else
          dofs(1:2) = new_dof(where//' s')
        end if
        coefs(1:2) = [cos(attach%guide_angle), sin(attach%guide_angle)]
        dofs(3) = new_dof(where//' th')
        coefs(3) = 1.0_dp
        call alpha_dofs(where, .true., .false., dofs, coefs)
      case (end_sleeve)
        ! (U2, W2) depend on the link angle: element_map builds them; map(U2)
        ! records the axial unknown for the printed table
        self%sleeve_s(ee) = new_dof(where//' s (sleeve)')
        if (attach%carried) then
          call pin_translations(jid)
          self%sleeve_u(ee) = joint_u(jid)
          self%sleeve_w(ee) = joint_w(jid)
        end if
        dofs(1) = self%sleeve_s(ee)
        coefs(1) = 1.0_dp
        dofs(3) = new_dof(where//' th')
        coefs(3) = 1.0_dp
        call alpha_dofs(where, .true., .false., dofs, coefs)
      end select
    end subroutine end_node

    subroutine pin_translations(jid)
      integer, intent(in) :: jid
      if (joint_kind(jid) == -1) then
        joint_kind(jid) = end_pin
        joint_u(jid) = new_dof('J'//str(jid)//' U')
        joint_w(jid) = new_dof('J'//str(jid)//' W')
      end if
    end subroutine pin_translations
  end subroutine build

  logical pure function is_sleeve_element(self, e)
    class(tennant_table_t), intent(in) :: self
    integer, intent(in) :: e
    is_sleeve_element = self%sleeve_s(e) > 0
  end function is_sleeve_element

  !> The map of element e as a dense matrix: q_e = C Q(glob(1:ng)), with its
  !> time derivatives (nonzero only for a sleeve end, where C depends on the
  !> sliding link's angle phi).
  pure subroutine element_map(self, e, phi, phi_d, phi_dd, ng, c0, c1, c2)
    class(tennant_table_t), intent(in) :: self
    integer, intent(in) :: e
    real(dp), intent(in) :: phi, phi_d, phi_dd
    integer, intent(out) :: ng
    real(dp), intent(out) :: c0(:, :), c1(:, :), c2(:, :)
    integer :: i, col, js, ju, jw, iu
    real(dp) :: c, s, c2a, s2a, dphi(2, 3), ddphi(2, 3)
    ng = self%n_glob(e)
    c0(1:self%nd, 1:ng) = 0.0_dp
    c1(1:self%nd, 1:ng) = 0.0_dp
    c2(1:self%nd, 1:ng) = 0.0_dp
    do i = 1, self%nd
      if (self%map(i, e) == 0) cycle
      col = findloc(self%glob(1:ng, e), self%map(i, e), dim=1)
      c0(i, col) = self%coef(i, e)
    end do
    if (self%sleeve_s(e) == 0) return
    ! sleeve at node 2: (U2, W2) = s u(phi) + (u_perp . (U_s, W_s)) u_perp
    iu = self%nn + 1
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

  !> The table as text lines for the output header.
  subroutine describe(self, lines)
    class(tennant_table_t), intent(in) :: self
    character(len=200), allocatable, intent(out) :: lines(:)
    integer :: e, i, n, k
    character(len=200) :: l
    n = 3 + self%n_elements + 1 + (self%n_global + 3)/4
    allocate(lines(n))
    write(lines(1), '(a,i0,a,i0,a,i0,a,i0)') 'variable correlation table: ', self%n_elements, ' elements of ', &
      self%nd, ' DOFs, ', self%n_global, ' global unknowns, half-bandwidth ', self%half_bandwidth
    if (self%nd == 8) then
      lines(2) = '  element link :   U1   W1  th1   m1   U2   W2  th2   m2   (global unknown; 0 = held at zero)'
    else
      lines(2) = '  element link :   U1   W1  th1   m1   a1 psi1 lam1   U2   W2  th2   m2   a2 psi2 lam2'
    end if
    lines(3) = '  ----------------------------------------------------------------------'
    do e = 1, self%n_elements
      write(l, '(2x,i7,i5,a,14i5)') e, self%link_of_element(e), ' :', self%map(:, e)
      if (self%sleeve_s(e) > 0) then
        if (self%sleeve_u(e) > 0) then
          write(l(len_trim(l) + 1:), '(a,i0,a,i0,a,i0,a)') '  (sleeve: U2, W2 from s = ', self%sleeve_s(e), &
            ' and U_s, W_s = ', self%sleeve_u(e), ', ', self%sleeve_w(e), ')'
        else
          write(l(len_trim(l) + 1:), '(a,i0,a)') '  (ground sleeve: U2, W2 = s u(phi), s = ', self%sleeve_s(e), ')'
        end if
      else
        do k = 0, 1
          i = 1 + k*self%nn
          if (self%map(i, e) > 0 .and. self%map(i, e) == self%map(i + 1, e)) then
            l = trim(l)//'  (slider: U, W = s * guide direction)'
            exit
          end if
        end do
      end if
      lines(3 + e) = l
    end do
    lines(4 + self%n_elements) = '  global unknowns:'
    do i = 1, (self%n_global + 3)/4
      l = ''
      do e = 4*(i - 1) + 1, min(4*i, self%n_global)
        write(l(len_trim(l) + 1:), '(2x,i4,": ",a18)') e, self%label(e)
      end do
      lines(4 + self%n_elements + i) = l
    end do
  end subroutine describe
end module tennant_table
