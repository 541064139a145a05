!> Shaking force of a planar mechanism: the rate of the total linear momentum
!> of every moving mass, dp/dt = F, which the frame supplies through the
!> ground pivots (the frame feels -F).  Counterweights that keep the total
!> centre of mass still make it vanish (full force balance, R.S. Berkof and
!> G.G. Lowen, J. Eng. Ind. 91 (1969) 53-60).
!>
!> F = d^2/dt^2 (sum m r) is split in two:
!>   rigid part, exact from the rigid-body accelerations of the element
!>     frames (module kinematics): a uniform element of mass m and length L
!>     has its centre at r1 + e L/2, e = (cos phi, sin phi), so
!>     m a = m (r1_dd + (phi_dd e_perp - phi_d^2 e) L/2); a counterweight at
!>     c (link frame) on a ground pivot: m (phi_dd c_perp - phi_d^2 c);
!>   elastic part, the second derivative of the first moment of the
!>     deformation S(t) = sum rho A int R(phi) (u, w) dx + counterweight arms
!>     turned by the end slope, taken over the steady revolution by
!>     trigonometric interpolation of S at evenly spaced samples (S is
!>     periodic and smooth; the rigid part is not approximated at all).
!> Links sliding through a sleeve and tapered sections are not covered
!> (the caller checks: `shaking_supported`).
module shaking_force
  use kinds, only: dp, pi
  use linkage, only: mechanism_t, joint_slider_link
  use steady_model, only: steady_model_t
  implicit none
  private
  public :: rigid_momentum_rate, elastic_first_moment, periodic_second_derivative, periodic_derivatives, &
            shaking_supported

  !> 3-point Gauss-Legendre on [0, 1]: exact for the quintic w and linear u
  real(dp), parameter :: gx(3) = [0.5_dp - 0.5_dp*sqrt(0.6_dp), 0.5_dp, 0.5_dp + 0.5_dp*sqrt(0.6_dp)]
  real(dp), parameter :: gw(3) = [5.0_dp/18.0_dp, 8.0_dp/18.0_dp, 5.0_dp/18.0_dp]

contains

  !> Empty when the shaking force can be computed; else why not.
  function shaking_supported(mech) result(why)
    type(mechanism_t), intent(in) :: mech
    character(len=:), allocatable :: why
    integer :: j
    why = ''
    do j = 1, mech%n_links
      if (mech%links(j)%sliding) why = 'a link slides through a sleeve (its mass moves along its frame)'
    end do
    do j = 1, mech%n_joints
      if (mech%joints(j)%mass > 0.0_dp .and. mech%joints(j)%kind == joint_slider_link) &
        why = 'a lumped mass sits on a sleeve'
    end do
  end function shaking_supported

  !> dp/dt of the rigid-body motion at the model's current time: links
  !> (uniform elements), counterweights and lumped joint masses.
  function rigid_momentum_rate(model, mech) result(f)
    type(steady_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    real(dp) :: f(2)
    real(dp) :: m, c(2), r1dd(2)
    integer :: i, e, j
    f = 0.0_dp
    do i = 1, mech%n_links
      associate (lk => mech%links(i))
        do e = lk%first_element, lk%first_element + lk%n_elements - 1
          m = lk%rho*lk%area*model%fs(e)%length
          f = f + m*point_acceleration(model, e, [0.5_dp*model%fs(e)%length, 0.0_dp])
        end do
        if (lk%cw_mass > 0.0_dp) f = f + lk%cw_mass*point_acceleration(model, lk%first_element, [lk%cw_x, lk%cw_y])
      end associate
    end do
    do j = 1, mech%n_joints
      if (.not. mech%joints(j)%mass > 0.0_dp) cycle
      ! the joint is end 1 or 2 of its first link
      i = mech%joints(j)%link(1)
      if (mech%joints(j)%link_end(1) == 1) then
        e = mech%links(i)%first_element
        c = 0.0_dp
      else
        e = mech%links(i)%first_element + mech%links(i)%n_elements - 1
        c = [model%fs(e)%length, 0.0_dp]
      end if
      r1dd = point_acceleration(model, e, c)
      f = f + mech%joints(j)%mass*r1dd
    end do
  end function rigid_momentum_rate

  !> Rigid-body acceleration of the point at c (element frame) of element e.
  pure function point_acceleration(model, e, c) result(a)
    type(steady_model_t), intent(in) :: model
    integer, intent(in) :: e
    real(dp), intent(in) :: c(2)
    real(dp) :: a(2), cg(2), co, si
    associate (fs => model%fs(e))
      co = cos(fs%phi)
      si = sin(fs%phi)
      cg = [co*c(1) - si*c(2), si*c(1) + co*c(2)]
      a = [fs%x1_dd, fs%y1_dd] + fs%phi_dd*[-cg(2), cg(1)] - fs%phi_d**2*cg
    end associate
  end function point_acceleration

  !> First moment of the deformation at the model's current time for the
  !> global displacements q: sum rho A int R(phi)(u, w) dx over the
  !> elements, counterweights' arm turned by the end slope w_x, joint masses
  !> moved with their node.
  function elastic_first_moment(model, mech, q) result(s)
    type(steady_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: q(:)
    real(dp) :: s(2)
    real(dp) :: uwa(3), co, si, loc(2), qe(14), a, c(2)
    integer :: i, e, k, j
    s = 0.0_dp
    do i = 1, mech%n_links
      associate (lk => mech%links(i))
        do e = lk%first_element, lk%first_element + lk%n_elements - 1
          co = cos(model%fs(e)%phi)
          si = sin(model%fs(e)%phi)
          loc = 0.0_dp
          do k = 1, 3
            uwa = model%local_field(e, q, gx(k))
            loc = loc + gw(k)*uwa(1:2)
          end do
          loc = lk%rho*lk%area*model%fs(e)%length*loc
          s = s + [co*loc(1) - si*loc(2), si*loc(1) + co*loc(2)]
        end do
        if (lk%cw_mass > 0.0_dp) then
          e = lk%first_element
          qe(1:model%el(e)%nd) = model%element_q(e, q)
          a = model%fs(e)%phi
          c = [lk%cw_x, lk%cw_y]
          s = s + lk%cw_mass*(qe(1:2) + rotate(c, a + qe(3)) - rotate(c, a))
        end if
      end associate
    end do
    do j = 1, mech%n_joints
      if (.not. mech%joints(j)%mass > 0.0_dp) cycle
      i = mech%joints(j)%link(1)
      if (mech%joints(j)%link_end(1) == 1) then
        e = mech%links(i)%first_element
        qe(1:model%el(e)%nd) = model%element_q(e, q)
        s = s + mech%joints(j)%mass*qe(1:2)
      else
        e = mech%links(i)%first_element + mech%links(i)%n_elements - 1
        qe(1:model%el(e)%nd) = model%element_q(e, q)
        k = model%el(e)%nd/2
        s = s + mech%joints(j)%mass*qe(k + 1:k + 2)
      end if
    end do
  end function elastic_first_moment

  pure function rotate(c, a) result(r)
    real(dp), intent(in) :: c(2), a
    real(dp) :: r(2)
    r = [cos(a)*c(1) - sin(a)*c(2), sin(a)*c(1) + cos(a)*c(2)]
  end function rotate

  !> d^2 s/dt^2 at the samples of one period (s(:, k) at t = (k - 1) T / N)
  !> by trigonometric interpolation (periodic_derivatives).
  function periodic_second_derivative(s, period) result(sdd)
    real(dp), intent(in) :: s(:, :), period
    real(dp) :: sdd(size(s, 1), size(s, 2))
    real(dp) :: sd(size(s, 1), size(s, 2))
    call periodic_derivatives(s, period, sd, sdd)
  end function periodic_second_derivative

  !> ds/dt and d^2 s/dt^2 at the samples of one period (s(:, k) at
  !> t = (k - 1) T / N) by trigonometric interpolation: the discrete Fourier
  !> coefficients times 2 pi j / T and -(2 pi j / T)^2, the Nyquist term of
  !> an even N dropped (it has no unique derivative).  O(N^2): N is a few
  !> dozen.
  subroutine periodic_derivatives(s, period, sd, sdd)
    real(dp), intent(in) :: s(:, :), period
    real(dp), intent(out) :: sd(:, :), sdd(:, :)
    real(dp) :: ac(size(s, 1)), as(size(s, 1)), w, arg
    integer :: n, j, k
    n = size(s, 2)
    sd = 0.0_dp
    sdd = 0.0_dp
    do j = 1, (n - 1)/2
      ac = 0.0_dp
      as = 0.0_dp
      do k = 1, n
        arg = 2.0_dp*pi*real(j*(k - 1), dp)/n
        ac = ac + s(:, k)*cos(arg)
        as = as + s(:, k)*sin(arg)
      end do
      ac = 2.0_dp*ac/n
      as = 2.0_dp*as/n
      w = 2.0_dp*pi*j/period
      do k = 1, n
        arg = 2.0_dp*pi*real(j*(k - 1), dp)/n
        sd(:, k) = sd(:, k) + w*(as*cos(arg) - ac*sin(arg))
        sdd(:, k) = sdd(:, k) - w**2*(ac*cos(arg) + as*sin(arg))
      end do
    end do
  end subroutine periodic_derivatives
end module shaking_force
