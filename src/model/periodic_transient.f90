!> The transient analysis run to its periodic state: a transient model (the
!> planar mechanism_model or the spatial spatial_model, DLSODE) integrated
!> revolution after revolution from a given state until the response repeats, as the
!> transient analysis' stop_when_periodic does, for callers that need the
!> periodic response itself (the design analysis' 'transient' evaluator,
!> the spatial design).
!>
!>     call transient_to_periodic(model, s, y, times, q, rep, err [, omega])
!>
!> omega: the crank speed (rad/s); left out, a planar model's driver speed.
!>
!> y: the interleaved state (q, q_d) at t = 0 (zeros: from rest; the previous
!> design's periodic state: a warm start); on return the state at the start
!> of the last revolution, i.e. the periodic state at t = 0 (mod T).  times:
!> ascending sample times in [0, T); q(:, k): the unknowns at times(k) in
!> the last revolution.
!>
!> The test, once per revolution: the largest change of any unknown at any
!> sample from the previous revolution, relative to that unknown's peak over
!> the revolution, at most s%tolerance.  Peaks below 1e-3 of the largest one,
!> or below 10 atol / tolerance, count as that floor: an unknown near
!> round-off, or a change within ten times the integration's absolute
!> tolerance, is integration noise and does not decide.  It is
!> stricter than the transient analysis' comparison of peaks (a phase drift
!> with an unchanged peak passes that one, not this one).  With a
!> contraction rho of the transient per revolution (stiffness-proportional
!> damping), the distance from the periodic orbit is about
!> change rho / (1 - rho): the caller's tolerance should be well below the
!> accuracy it needs.
module periodic_transient
  use kinds, only: dp, two_pi
  use error_status, only: error_t
  use strings, only: str
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_adams, mf_bdf_band_user
  use second_order_model, only: second_order_model_t
  use mechanism_model, only: mechanism_model_t
  implicit none
  private
  public :: periodic_transient_settings_t, periodic_transient_report_t, transient_to_periodic, matching_unknowns

  type :: periodic_transient_settings_t
    real(dp) :: tolerance = 1.0e-6_dp     !< largest relative change per revolution (stop_when_periodic)
    integer :: max_revolutions = 200      !< not periodic by then: a failure
    real(dp) :: rtol = 1.0e-7_dp          !< DLSODE relative tolerance
    real(dp) :: atol = 1.0e-11_dp         !< DLSODE absolute tolerance (displacements; rates too by default)
    real(dp) :: atol_rate = -1.0_dp       !< of the rates; < 0: atol
    logical :: bdf = .true.               !< banded BDF with the model's Newton matrix; else Adams
    integer :: max_steps = 200000         !< DLSODE steps per call (as shooting's per revolution)
  end type periodic_transient_settings_t

  type :: periodic_transient_report_t
    logical :: periodic = .false.
    integer :: revolutions = 0            !< revolutions integrated
    real(dp) :: change = -1.0_dp          !< the last revolution's change (-1: fewer than two)
    integer :: steps = 0, rhs_evaluations = 0
  end type periodic_transient_report_t

contains

  subroutine transient_to_periodic(model, s, y, times, q, rep, err, omega)
    class(second_order_model_t), intent(inout), target :: model
    type(periodic_transient_settings_t), intent(in) :: s
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: times(:)
    real(dp), intent(out) :: q(:, :)
    type(periodic_transient_report_t), intent(out) :: rep
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: omega
    type(lsode_t) :: ode
    type(lsode_counters_t) :: c
    real(dp) :: prev(size(q, 1), size(q, 2)), y_start(size(y)), peak(size(q, 1))
    real(dp) :: period, t0, floor, speed, atol(size(y))
    integer :: r, k, ml, mf
    if (err%failed()) return
    speed = 0.0_dp
    if (present(omega)) then
      speed = omega
    else
      select type (model)
      class is (mechanism_model_t)
        speed = model%kin%mech%driver%omega
      end select
    end if
    if (.not. speed > 0.0_dp) then
      call err%set('transient to periodic', 'needs a crank turning at a constant speed > 0')
      return
    end if
    period = two_pi/speed
    mf = mf_adams
    if (s%bdf) mf = mf_bdf_band_user
    ml = min(2*model%kd + 1, size(y) - 1)
    atol(1::2) = s%atol
    atol(2::2) = merge(s%atol_rate, s%atol, s%atol_rate >= 0.0_dp)
    call ode%init(size(y), 0.0_dp, mf, s%rtol, atol, err, ml=ml, mu=ml, max_steps=s%max_steps)
    if (err%failed()) return
    y_start = y
    do r = 1, s%max_revolutions
      t0 = (r - 1)*period
      y_start = y
      do k = 1, size(times)
        call ode%integrate_to(model, y, t0 + times(k), err)
        if (err%failed()) exit
        q(:, k) = y(1::2)
      end do
      if (.not. err%failed()) call ode%integrate_to(model, y, r*period, err)
      if (err%failed()) then
        call err%add_context('transient to the periodic state, revolution '//str(r))
        exit
      end if
      rep%revolutions = r
      if (r > 1) then
        peak = maxval(abs(q), dim=2)
        floor = max(1.0e-3_dp*maxval(peak), 10.0_dp*s%atol/s%tolerance)
        rep%change = maxval(maxval(abs(q - prev), dim=2)/max(peak, floor))
        if (rep%change <= s%tolerance) then
          rep%periodic = .true.
          exit
        end if
      end if
      prev = q
    end do
    c = ode%counters()
    rep%steps = c%steps
    rep%rhs_evaluations = c%rhs_evals
    ! the periodic state at t = 0 (mod T): the start of the last revolution
    y = y_start
    if (err%failed() .or. rep%periodic) return
    call err%set('transient to periodic', 'not periodic after '//str(rep%revolutions)//' revolutions: the last '// &
                 'changed by '//str(rep%change, 4)//' > '//str(s%tolerance, 4)//' (stop_when_periodic)', 3)
  end subroutine transient_to_periodic

  !> For each name of `from`, its position in `to` (0: none): the transient
  !> and the steady model may number the same unknowns differently.
  pure function matching_unknowns(from, to) result(at)
    character(len=*), intent(in) :: from(:), to(:)
    integer :: at(size(from))
    integer :: i, k
    at = 0
    do i = 1, size(from)
      do k = 1, size(to)
        if (from(i) == to(k)) at(i) = k
      end do
    end do
  end function matching_unknowns
end module periodic_transient
