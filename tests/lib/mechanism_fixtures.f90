!> The planar mechanisms the suites build, as a deck would describe them
!> (mechanism_input_t): one four-bar, one slider-crank and the two inverted
!> slider-cranks (a sleeve on the crank pin, a sleeve on the ground).  Only
!> the geometry: each suite adds its masses, meshes, speeds and names.  And
!> the four-bar's link ends as the correlation table takes them.
module mechanism_fixtures
  use kinds, only: dp
  use linkage, only: mechanism_input_t, coordinate_unset
  use correlation_table, only: link_end_t, joint_clamp, joint_pin, joint_ground_pin
  implicit none
  private
  public :: fourbar_abcd, slider_crank_input, whitworth_input, ground_sleeve_input, fourbar_ends

contains

  !> Four-bar A-B-C-D: crank AB = a clamped at A = (0, 0), coupler BC = b,
  !> rocker DC = c pinned at D = (d, 0). The rocker runs from D to C, so its
  !> angle is Norton's theta4.
  function fourbar_abcd(a, b, c, d) result(inp)
    real(dp), intent(in) :: a, b, c, d
    type(mechanism_input_t) :: inp
    inp%n_joints = 4
    inp%joint_name(1:4) = [character(len=16) :: 'A', 'B', 'C', 'D']
    inp%joint_type(1:4) = [character(len=16) :: 'clamp', 'pin', 'pin', 'ground_pin']
    inp%joint_x(1) = 0.0_dp
    inp%joint_y(1) = 0.0_dp
    inp%joint_x(4) = d
    inp%joint_y(4) = 0.0_dp
    inp%n_links = 3
    inp%link_name(1:3) = [character(len=16) :: 'crank', 'coupler', 'rocker']
    inp%link_joint1(1:3) = [1, 2, 4]
    inp%link_joint2(1:3) = [2, 3, 3]
    inp%link_length(1:3) = [a, b, c]
  end function fourbar_abcd

  !> The four-bar's link ends for correlation_table%build: crank (clamp A,
  !> pin B), coupler (pin B, pin C), rocker (pin C, ground pin D), or with
  !> `rocker_from_d` the rocker drawn from D to C as the decks draw it.
  function fourbar_ends(rocker_from_d) result(ends)
    logical, intent(in) :: rocker_from_d
    type(link_end_t) :: ends(2, 3)
    ends(1, 1) = link_end_t(joint_clamp, 0, 0.0_dp)
    ends(2, 1) = link_end_t(joint_pin, 1, 0.0_dp)
    ends(1, 2) = link_end_t(joint_pin, 1, 0.0_dp)
    ends(2, 2) = link_end_t(joint_pin, 2, 0.0_dp)
    ends(1, 3) = link_end_t(joint_pin, 2, 0.0_dp)
    ends(2, 3) = link_end_t(joint_ground_pin, 0, 0.0_dp)
    if (rocker_from_d) ends(:, 3) = ends(2:1:-1, 3)
  end function fourbar_ends

  !> Slider-crank: crank r clamped at A = (0, 0), rod l to the block on a
  !> fixed guide through (0, e) (guide angle 0 unless the suite sets one).
  function slider_crank_input(r, l, e) result(inp)
    real(dp), intent(in) :: r, l, e
    type(mechanism_input_t) :: inp
    inp%n_joints = 3
    inp%joint_type(1:3) = [character(len=16) :: 'clamp', 'pin', 'slider_fixed']
    inp%joint_x(1:3) = [0.0_dp, coordinate_unset, 0.0_dp]
    inp%joint_y(1:3) = [0.0_dp, coordinate_unset, e]
    inp%n_links = 2
    inp%link_joint1(1:2) = [1, 2]
    inp%link_joint2(1:2) = [2, 3]
    inp%link_length(1:2) = [r, l]
  end function slider_crank_input

  !> Whitworth (inverted slider-crank, sleeve carried): crank AB = r clamped
  !> at A = (0, 0); the lever from the ground pin D = (0, -d) slides through a
  !> sleeve on the crank pin B (its length follows the motion).
  function whitworth_input(r, d) result(inp)
    real(dp), intent(in) :: r, d
    type(mechanism_input_t) :: inp
    inp%n_joints = 3
    inp%joint_type(1:3) = [character(len=16) :: 'clamp', 'slider_link', 'ground_pin']
    inp%joint_x(1) = 0.0_dp
    inp%joint_y(1) = 0.0_dp
    inp%joint_x(3) = 0.0_dp
    inp%joint_y(3) = -d
    inp%joint_sliding_link(2) = 2
    inp%n_links = 2
    inp%link_joint1(1:2) = [1, 3]
    inp%link_joint2(1:2) = [2, 2]
    inp%link_length(1:2) = [r, 0.0_dp]
  end function whitworth_input

  !> Oscillating cylinder (inverted slider-crank, sleeve on the ground):
  !> crank AB = r clamped at A = (0, 0); the rod of length l pinned at B
  !> slides through a sleeve pivoting on the ground at C = (c, 0).
  function ground_sleeve_input(r, l, c) result(inp)
    real(dp), intent(in) :: r, l, c
    type(mechanism_input_t) :: inp
    inp%n_joints = 3
    inp%joint_type(1:3) = [character(len=16) :: 'clamp', 'pin', 'slider_link']
    inp%joint_x(1) = 0.0_dp
    inp%joint_y(1) = 0.0_dp
    inp%joint_x(3) = c
    inp%joint_y(3) = 0.0_dp
    inp%joint_sliding_link(3) = 2
    inp%n_links = 2
    inp%link_joint1(1:2) = [1, 2]
    inp%link_joint2(1:2) = [2, 3]
    inp%link_length(1:2) = [r, l]
  end function ground_sleeve_input
end module mechanism_fixtures
