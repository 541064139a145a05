!> The papers' effects ("tracing constants") every element of the program
!> reads: the planar elements (Kear's, the consistent one, Tennant's) and the
!> spatial beam.  All switches off is the linear analysis.
module element_effects
  implicit none
  private
  public :: element_effects_t, effects_all_on, effects_summary

  type :: element_effects_t
    logical :: stretching = .false.      !< exact axial strain (K19); off: eps_n = u_x
    logical :: curvature = .false.       !< exact curvature (K23) and section angle (K8); off: kappa = w_xx, theta = phi + w_x
    logical :: material = .false.        !< Ramberg-Osgood E2 term (K13); off: linear elastic E1
    logical :: rotary_inertia = .false.  !< rho I theta_dot^2 / 2 in (K3); off: dropped
    logical :: coupling = .false.        !< Coriolis and Euler terms of the elastic motion; off: dropped
  end type element_effects_t

contains

  pure function effects_all_on() result(fx)
    type(element_effects_t) :: fx
    fx = element_effects_t(.true., .true., .true., .true., .true.)
  end function effects_all_on

  !> One line for output headers, e.g. "stretching=T curvature=F ...".
  pure function effects_summary(fx) result(line)
    type(element_effects_t), intent(in) :: fx
    character(len=:), allocatable :: line
    line = 'stretching='//tf(fx%stretching)//' curvature='//tf(fx%curvature)//' material=' &
           //tf(fx%material)//' rotary_inertia='//tf(fx%rotary_inertia)//' coupling='//tf(fx%coupling)
  end function effects_summary

  pure function tf(b) result(c)
    logical, intent(in) :: b
    character(len=1) :: c
    c = merge('T', 'F', b)
  end function tf
end module element_effects
