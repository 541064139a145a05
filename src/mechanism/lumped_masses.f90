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

  !> Joint masses: mass, element and node (1, 2) carrying each.
  type :: joint_masses_t
    real(dp), allocatable :: mass(:)
    integer, allocatable :: element(:), node(:)
  end type joint_masses_t

  !> Counterweights: element (its node 1 is the pivot), mass m, J = m |c|^2,
  !> first moment m c in the link's frame.
  type :: counterweights_t
    integer, allocatable :: element(:)
    real(dp), allocatable :: mass(:), inertia(:), moment(:, :)
  end type counterweights_t

contains

  subroutine place_joint_masses(mech, pm)
    type(mechanism_t), intent(in) :: mech
    type(joint_masses_t), intent(out) :: pm
    integer :: j, i, link
    allocate(pm%mass(0), pm%element(0), pm%node(0))
    do j = 1, mech%n_joints
      associate (jt => mech%joints(j))
        if (.not. jt%mass > 0.0_dp) cycle
        do i = 1, jt%n_links
          if (jt%kind == joint_slider_link .and. jt%link(i) == jt%sliding_link) cycle
          link = jt%link(i)
          if (jt%link_end(i) == 1) then
            pm%element = [pm%element, mech%links(link)%first_element]
          else
            pm%element = [pm%element, mech%links(link)%first_element + mech%links(link)%n_elements - 1]
          end if
          pm%node = [pm%node, jt%link_end(i)]
          pm%mass = [pm%mass, jt%mass]
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
    allocate(cw%element(0), cw%mass(0), cw%inertia(0), cw%moment(2, 0))
    do k = 1, mech%n_links
      associate (lk => mech%links(k))
        if (.not. lk%cw_mass > 0.0_dp) cycle
        if (lk%sliding) then
          call err%set('counterweight', 'a counterweight on a link sliding through a sleeve is not modelled', 2)
          return
        end if
        cw%element = [cw%element, lk%first_element]
        cw%mass = [cw%mass, lk%cw_mass]
        cw%inertia = [cw%inertia, lk%cw_mass*(lk%cw_x**2 + lk%cw_y**2)]
        cw%moment = reshape([cw%moment, lk%cw_mass*[lk%cw_x, lk%cw_y]], [2, size(cw%element)])
      end associate
    end do
  end subroutine place_counterweights
end module lumped_masses
