!> Tests of the placement of joint masses and counterweights on the elements
!> (module lumped_masses), the one rule the transient and the steady models
!> share: a joint mass rides on the first link end at the joint that is not
!> the link sliding through a sleeve, a ground sleeve carries none, a
!> counterweight sits on its link's first element and is refused (status 2)
!> on a sliding link.
module test_lumped_masses_suite
  use kinds, only: dp
  use error_status, only: error_t
  use linkage, only: mechanism_input_t, mechanism_t, build_mechanism
  use lumped_masses, only: joint_masses_t, counterweights_t, place_joint_masses, place_counterweights
  use assertions
  use mechanism_fixtures, only: whitworth_input, ground_sleeve_input
  implicit none
  private
  public :: run_all

contains

  subroutine run_all()
    call run_test('sleeve_mass_rides_on_the_carrier_not_the_sliding_link', test_sleeve_on_crank)
    call run_test('ground_sleeve_carries_no_mass_a_pin_mass_its_first_link', test_ground_sleeve)
    call run_test('counterweight_on_first_element_refused_on_sliding_link', test_counterweights)
  end subroutine run_all

  function built(inp) result(mech)
    type(mechanism_input_t), intent(in) :: inp
    type(mechanism_t) :: mech
    type(error_t) :: err
    call build_mechanism(inp, mech, err)
    call assert_true(.not. err%failed(), 'mechanism builds: '//err%text())
  end function built

  !> Whitworth: the sleeve on the crank pin B (joint 2) carries the lever; its
  !> mass rides on the crank's end 2, the last crank element's node 2.
  subroutine test_sleeve_on_crank()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(joint_masses_t) :: pm
    inp = whitworth_input(3.0_dp, 6.0_dp)
    inp%joint_mass(2) = 0.002_dp
    inp%link_n_elements(1:2) = [3, 2]
    mech = built(inp)
    call place_joint_masses(mech, pm)
    call assert_equal(pm%count(), 1, 'one joint mass')
    call assert_equal(pm%element(1), mech%links(1)%first_element + 2, 'on the last crank element')
    call assert_equal(pm%node(1), 2, 'at its node 2')
    call assert_close(pm%mass(1), 0.002_dp, 0.0_dp, 'the joint''s mass')
  end subroutine test_sleeve_on_crank

  !> Oscillating cylinder: the sleeve pivoting on the ground (joint 3) holds
  !> only the sliding rod and carries nothing; the pin B (joint 2) mass rides
  !> on the crank's end 2.
  subroutine test_ground_sleeve()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(joint_masses_t) :: pm
    inp = ground_sleeve_input(3.0_dp, 14.0_dp, 8.0_dp)
    inp%link_n_elements(1:2) = [2, 1]
    inp%joint_mass(3) = 0.001_dp
    mech = built(inp)
    call place_joint_masses(mech, pm)
    call assert_equal(pm%count(), 0, 'a ground sleeve carries no mass')
    inp%joint_mass(2) = 0.003_dp
    mech = built(inp)
    call place_joint_masses(mech, pm)
    call assert_equal(pm%count(), 1, 'the pin''s mass only')
    call assert_equal(pm%element(1), mech%links(1)%first_element + 1, 'on the crank''s second element')
    call assert_equal(pm%node(1), 2, 'at its node 2')
  end subroutine test_ground_sleeve

  !> A counterweight on the crank (end 1 clamped at the ground pivot A) sits
  !> on the crank's first element with J = m |c|^2 and m c; one on the lever
  !> sliding through the sleeve is refused with status 2.
  subroutine test_counterweights()
    type(mechanism_input_t) :: inp
    type(mechanism_t) :: mech
    type(counterweights_t) :: cw
    type(error_t) :: err
    real(dp) :: mc(2)
    inp = whitworth_input(3.0_dp, 6.0_dp)
    inp%link_cw_mass(1) = 0.01_dp
    inp%link_cw_x(1) = -2.0_dp
    inp%link_cw_y(1) = 0.5_dp
    mech = built(inp)
    call place_counterweights(mech, cw, err)
    call assert_true(.not. err%failed(), 'a crank counterweight is placed')
    call assert_equal(cw%count(), 1, 'one counterweight')
    call assert_equal(cw%element(1), mech%links(1)%first_element, 'on the crank''s first element')
    call assert_rel_close(cw%inertia(1), 0.01_dp*4.25_dp, 1.0e-14_dp, 'J = m |c|^2')
    mc = cw%moment(1)
    call assert_rel_close(mc(1), -0.02_dp, 1.0e-14_dp, 'm c_x')
    call assert_rel_close(mc(2), 0.005_dp, 1.0e-14_dp, 'm c_y')
    inp%link_cw_mass(2) = 0.01_dp
    mech = built(inp)
    call place_counterweights(mech, cw, err)
    call assert_true(err%failed(), 'a counterweight on the sliding lever is refused')
    call assert_equal(err%code, 2, 'as an input error')
  end subroutine test_counterweights
end module test_lumped_masses_suite

program test_lumped_masses
  use test_lumped_masses_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_lumped_masses')
end program test_lumped_masses
