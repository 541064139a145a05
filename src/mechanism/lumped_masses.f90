!> The lumped masses of a linkage, placed on its elements once for every
!> model (transient, steady, periodic), by one rule each:
!>
!> - A joint's mass (a slider block, a sleeve) rides on the end of the
!>   joint's first link that is not the link sliding through a sleeve (a
!>   ground sleeve, whose only link slides, carries none: it does not move):
!>   node 1 of the link's first element at its end 1, node 2 of its last
!>   element at end 2.
!> - A counterweight (link_cw_mass, on an arm clamped to the link at its end
!>   1, a ground pivot) sits on the link's first element, with J = m |c|^2
!>   about the pivot and m c in the link's frame; on a link sliding through a
!>   sleeve it is not modelled (an input error, status 2).
module lumped_masses
  use kinds, only: dp
  use error_status, only: error_t
  use linkage, only: mechanism_t, joint_slider_link
  implicit none
  private
  public :: joint_masses_t, counterweights_t, place_joint_masses, place_counterweights

  !> Joint masses: mass, element and node (1, 2) carrying each, one entry
  !> per mass (the three lists hold together: private, read by entry).
  type :: joint_masses_t
    private
    real(dp), allocatable :: masses(:)
    integer, allocatable :: elements(:), nodes(:)
  contains
    procedure :: count => joint_mass_count
    procedure :: mass => joint_mass
    procedure :: element => joint_mass_element
    procedure :: node => joint_mass_node
    procedure :: mass_at
  end type joint_masses_t

  !> Counterweights: element (its node 1 is the pivot), mass m, J = m |c|^2,
  !> first moment m c in the link's frame; one entry per counterweight.
  type :: counterweights_t
    private
    integer, allocatable :: elements(:)
    real(dp), allocatable :: masses(:), inertias(:), moments(:, :)
  contains
    procedure :: count => counterweight_count
    procedure :: element => counterweight_element
    procedure :: mass => counterweight_mass
    procedure :: inertia => counterweight_inertia
    procedure :: moment => counterweight_moment
  end type counterweights_t

contains

  subroutine place_joint_masses(mech, pm)
    type(mechanism_t), intent(in) :: mech
    type(joint_masses_t), intent(out) :: pm
    integer :: j, i, link
    allocate(pm%masses(0), pm%elements(0), pm%nodes(0))
    do j = 1, mech%n_joints
      associate (jt => mech%joints(j))
        if (.not. jt%mass > 0.0_dp) cycle
        do i = 1, jt%n_links
          if (jt%kind == joint_slider_link .and. jt%link(i) == jt%sliding_link) cycle
          link = jt%link(i)
          if (jt%link_end(i) == 1) then
            pm%elements = [pm%elements, mech%links(link)%first_element]
          else
            pm%elements = [pm%elements, mech%links(link)%first_element + mech%links(link)%n_elements - 1]
          end if
          pm%nodes = [pm%nodes, jt%link_end(i)]
          pm%masses = [pm%masses, jt%mass]
          exit
        end do
      end associate
    end do
  end subroutine place_joint_masses

  subroutine place_counterweights(mech, cw, err)
    type(mechanism_t), intent(in) :: mech
    type(counterweights_t), intent(out) :: cw
    type(error_t), intent(inout) :: err
    integer :: k
    allocate(cw%elements(0), cw%masses(0), cw%inertias(0), cw%moments(2, 0))
    do k = 1, mech%n_links
      associate (lk => mech%links(k))
        if (.not. lk%cw_mass > 0.0_dp) cycle
        if (lk%sliding) then
          call err%set('counterweight', 'a counterweight on a link sliding through a sleeve is not modelled', 2)
          return
        end if
        cw%elements = [cw%elements, lk%first_element]
        cw%masses = [cw%masses, lk%cw_mass]
        cw%inertias = [cw%inertias, lk%cw_mass*(lk%cw_x**2 + lk%cw_y**2)]
        cw%moments = reshape([cw%moments, lk%cw_mass*[lk%cw_x, lk%cw_y]], [2, size(cw%elements)])
      end associate
    end do
  end subroutine place_counterweights

  !> The number of joint masses (0 before they are placed).
  pure integer function joint_mass_count(self)
    class(joint_masses_t), intent(in) :: self
    joint_mass_count = 0
    if (allocated(self%masses)) joint_mass_count = size(self%masses)
  end function joint_mass_count

  !> The mass of joint mass k.
  pure real(dp) function joint_mass(self, k)
    class(joint_masses_t), intent(in) :: self
    integer, intent(in) :: k
    joint_mass = self%masses(k)
  end function joint_mass

  !> The element carrying joint mass k.
  pure integer function joint_mass_element(self, k)
    class(joint_masses_t), intent(in) :: self
    integer, intent(in) :: k
    joint_mass_element = self%elements(k)
  end function joint_mass_element

  !> The node (1, 2) of its element carrying joint mass k.
  pure integer function joint_mass_node(self, k)
    class(joint_masses_t), intent(in) :: self
    integer, intent(in) :: k
    joint_mass_node = self%nodes(k)
  end function joint_mass_node

  !> The joint masses at node `node` of element e, summed (0 if none).
  pure real(dp) function mass_at(self, e, node)
    class(joint_masses_t), intent(in) :: self
    integer, intent(in) :: e, node
    mass_at = 0.0_dp
    if (allocated(self%masses)) mass_at = sum(self%masses, mask=self%elements == e .and. self%nodes == node)
  end function mass_at

  !> The number of counterweights (0 before they are placed).
  pure integer function counterweight_count(self)
    class(counterweights_t), intent(in) :: self
    counterweight_count = 0
    if (allocated(self%masses)) counterweight_count = size(self%masses)
  end function counterweight_count

  !> The element whose node 1 is counterweight k's pivot.
  pure integer function counterweight_element(self, k)
    class(counterweights_t), intent(in) :: self
    integer, intent(in) :: k
    counterweight_element = self%elements(k)
  end function counterweight_element

  !> The mass m of counterweight k.
  pure real(dp) function counterweight_mass(self, k)
    class(counterweights_t), intent(in) :: self
    integer, intent(in) :: k
    counterweight_mass = self%masses(k)
  end function counterweight_mass

  !> J = m |c|^2 of counterweight k about its pivot.
  pure real(dp) function counterweight_inertia(self, k)
    class(counterweights_t), intent(in) :: self
    integer, intent(in) :: k
    counterweight_inertia = self%inertias(k)
  end function counterweight_inertia

  !> The first moment m c of counterweight k in its link's frame.
  pure function counterweight_moment(self, k) result(mc)
    class(counterweights_t), intent(in) :: self
    integer, intent(in) :: k
    real(dp) :: mc(2)
    mc = self%moments(:, k)
  end function counterweight_moment
end module lumped_masses
