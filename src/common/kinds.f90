!> Working precision and the few constants every module needs.
module kinds
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private
  public :: dp, i8, pi, two_pi

  integer, parameter :: dp = real64   !< the one real kind of flexmech
  integer, parameter :: i8 = int64
  real(dp), parameter :: pi = 3.141592653589793238462643383279503_dp
  real(dp), parameter :: two_pi = 2.0_dp*pi
end module kinds
