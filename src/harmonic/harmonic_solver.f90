!> The harmonic-series steady state of Tennant (1985) after Bahgat and
!> Willmert (T26-T28), with the outer iteration on the nonlinear stiffness.
!>
!>   (T28) 2N samples per crank revolution, t_k = k T / (2N), k = 0 .. 2N-1
!>   (T27) F(t_k) = sum_n A_n cos(n w t_k) + B_n sin(n w t_k), B_0 = 0: the
!>         square collocation system is the discrete Fourier transform of the
!>         samples, with harmonics n = 0 .. N and B_N = 0 (sin(N w t_k) = 0
!>         at every sample)
!>   (T26) Q(t) = sum_{n=0}^{N'} (K(t) - n^2 w^2 M(t))^-1 (A_n cos n w t + B_n sin n w t)
!>         truncated after N' <= N harmonics
!>
!> How K(t) and M(t) enter (T26) the paper does not say.  The reading
!> implemented here (doc/steady_state.md §3) is the literal one: at each time
!> t the matrices of that instant are used ("frozen coefficients"), K = K_e(t)
!> + K_n(Q(t), t).  C Q_d is neglected as in the paper; with
!> velocity_terms = .true. it is kept, F_eff(t_k) = F(t_k) - C(t_k) Q_d(t_k)
!> with Q_d from the trigonometric interpolant of Q at the samples.
!>
!> Outer iteration (T §3.8): K_n = 0 first (the linear analysis); then K_n is
!> the paper's secant evaluated with the previous Q, until the largest change
!> of Q relative to |Q| is below outer_tol.  Without C Q_d the equations at
!> different times are independent, so the iteration runs time by time; the
!> change reported for iteration i is the largest over all times.
!>
!> Each (K - n^2 w^2 M) is equilibrated by D = diag(K)^(-1/2) and factored by
!> LU; in the linear pass (K = K_e) also its reciprocal condition number:
!> rcond(K - n^2 w^2 M)/rcond(K) near zero means the harmonic n w sits on a
!> natural frequency of the frozen structure (resonance): reported, and
!> flagged below resonance_ratio.
module harmonic_solver
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use small_dense, only: dense_lu_t
  use periodic_system, only: periodic_system_t, nonlinear_info_t
  implicit none
  private
  public :: harmonic_settings_t, harmonic_report_t, harmonic_solve, fourier_coefficients, max_outer_limit
  public :: harmonic_diagnosis

  integer, parameter :: max_outer_limit = 200
  integer, parameter :: cache_limit = 400000     !< doubles of sample M, K kept without C Q_d

  type :: harmonic_settings_t
    integer :: n_harmonics = 8             !< N: 2N samples per revolution
    integer :: n_kept = 0                  !< N' harmonics kept in (T26); 0 = N
    logical :: velocity_terms = .false.    !< keep C Q_d (the paper drops it)
    real(dp) :: outer_tol = 1.0e-5_dp      !< relative change of Q that ends the outer iteration
    integer :: max_outer = 30
    real(dp) :: resonance_ratio = 1.0e-2_dp !< flag rcond(K - n^2 w^2 M)/rcond(K) below this
  end type harmonic_settings_t

  type :: harmonic_report_t
    integer :: n_samples = 0
    integer :: n_kept = 0
    integer :: outer_iterations = 0        !< nonlinear updates of K_n (largest over the times)
    logical :: converged = .true.
    real(dp) :: change(0:max_outer_limit) = 0.0_dp   !< largest relative change of Q at each iteration
    integer :: velocity_iterations = 0     !< iterations on the samples with C Q_d kept
    real(dp) :: velocity_change(max_outer_limit) = 0.0_dp
    integer :: factorizations = 0
    real(dp) :: min_rcond = huge(1.0_dp)   !< of the equilibrated K - n^2 w^2 M
    real(dp) :: worst_ratio = huge(1.0_dp) !< smallest rcond(K - n^2 w^2 M)/rcond(K), n >= 1
    integer :: worst_harmonic = 0
    real(dp) :: worst_time = 0.0_dp
    logical :: near_resonance = .false.
    real(dp) :: max_abs_strain = 0.0_dp
    real(dp) :: strain_time = 0.0_dp
    integer :: strain_element = 0
    logical :: beyond_peak = .false.
  end type harmonic_report_t

  !> One revolution's samples (T28) and the coefficients (T27) of the
  !> forcing (of F - C Q_d when C Q_d is kept): what the series (T26) at
  !> every time reads.
  type :: revolution_samples_t
    integer :: nh = 0                          !< N harmonics
    integer :: ns = 0                          !< 2N samples
    integer :: keep = 0                        !< N' harmonics kept in (T26)
    real(dp) :: period = 0.0_dp
    real(dp), allocatable :: f(:, :)           !< (n, 0:ns-1) F(t_k)
    real(dp), allocatable :: a(:, :), b(:, :)  !< (n, 0:nh) the coefficients
    real(dp), allocatable :: m(:, :, :), k(:, :, :), c(:, :, :)   !< (n, n, 0:ns-1) M, K, C(t_k) where kept
  end type revolution_samples_t

contains

  !> The square collocation (T27) on 2N samples: f(:, k) = F(t_k) ->
  !> a(:, 0:N), b(:, 0:N) with b(:, 0) = b(:, N) = 0.
  pure subroutine fourier_coefficients(f, nh, a, b)
    real(dp), intent(in) :: f(:, 0:)
    integer, intent(in) :: nh
    real(dp), intent(out) :: a(:, 0:), b(:, 0:)
    integer :: n, k, ns
    real(dp) :: ang
    ns = 2*nh
    a(:, 0:nh) = 0.0_dp
    b(:, 0:nh) = 0.0_dp
    do k = 0, ns - 1
      a(:, 0) = a(:, 0) + f(:, k)
      do n = 1, nh - 1
        ang = two_pi*real(n*k, dp)/real(ns, dp)
        a(:, n) = a(:, n) + f(:, k)*cos(ang)
        b(:, n) = b(:, n) + f(:, k)*sin(ang)
      end do
      a(:, nh) = a(:, nh) + f(:, k)*real(1 - 2*mod(k, 2), dp)
    end do
    a(:, 0) = a(:, 0)/ns
    a(:, 1:nh - 1) = a(:, 1:nh - 1)*(2.0_dp/ns)
    b(:, 1:nh - 1) = b(:, 1:nh - 1)*(2.0_dp/ns)
    a(:, nh) = a(:, nh)/ns
  end subroutine fourier_coefficients

  !> Steady state Q(t) at the given times: the revolution's samples and
  !> the forcing's coefficients (T27, T28; with C Q_d kept, the iteration on
  !> the samples), then the series (T26) and the outer iteration at each time.
  subroutine harmonic_solve(sys, s, times, q, rep, err)
    class(periodic_system_t), intent(inout) :: sys
    type(harmonic_settings_t), intent(in) :: s
    real(dp), intent(in) :: times(:)
    real(dp), intent(out) :: q(:, :)
    type(harmonic_report_t), intent(out) :: rep
    type(error_t), intent(inout) :: err
    type(revolution_samples_t) :: smp
    integer :: j

    smp%nh = s%n_harmonics
    smp%ns = 2*smp%nh
    smp%keep = s%n_kept
    if (smp%keep <= 0 .or. smp%keep > smp%nh) smp%keep = smp%nh
    rep%n_samples = smp%ns
    rep%n_kept = smp%keep
    if (smp%nh < 1) then
      call err%set('harmonic series', 'needs at least one harmonic'); return
    end if
    if (size(q, 1) /= sys%n .or. size(q, 2) /= size(times)) then
      call err%set('harmonic series', 'result array has the wrong shape'); return
    end if
    smp%period = sys%period()
    call sample_revolution(sys, s, smp, err)
    if (err%failed()) return
    if (s%velocity_terms) then
      call velocity_phase(sys, s, smp, rep, err)
      if (err%failed()) return
    end if
    rep%change = 0.0_dp
    do j = 1, size(times)
      call steady_at(sys, s, smp, times(j), q(:, j), rep, err)
      if (err%failed()) return
    end do
  end subroutine harmonic_solve

  !> (T27), (T28): forcing at 2N equally spaced times of one revolution and
  !> its coefficients; M and K of the samples are kept for small systems
  !> (output times often are sample times) and whenever C Q_d is kept.
  subroutine sample_revolution(sys, s, smp, err)
    class(periodic_system_t), intent(inout) :: sys
    type(harmonic_settings_t), intent(in) :: s
    type(revolution_samples_t), intent(inout) :: smp
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: m(:, :), c(:, :), k(:, :), f(:)
    integer :: n, ns, kk
    n = sys%n
    ns = smp%ns
    allocate(smp%f(n, 0:ns - 1), smp%a(n, 0:smp%nh), smp%b(n, 0:smp%nh), m(n, n), c(n, n), k(n, n), f(n))
    if (s%velocity_terms .or. n*n*ns <= cache_limit) allocate(smp%m(n, n, 0:ns - 1), smp%k(n, n, 0:ns - 1))
    if (s%velocity_terms) allocate(smp%c(n, n, 0:ns - 1))
    do kk = 0, ns - 1
      call sys%set_time(kk*smp%period/ns, err)
      if (err%failed()) return
      call sys%linear_terms(m, c, k, f, s%velocity_terms)
      smp%f(:, kk) = f
      if (allocated(smp%m)) then
        smp%m(:, :, kk) = m
        smp%k(:, :, kk) = k
      end if
      if (s%velocity_terms) smp%c(:, :, kk) = c
    end do
    call fourier_coefficients(smp%f, smp%nh, smp%a, smp%b)
  end subroutine sample_revolution

  !> (T26) at time t: the linear pass, then the outer iteration on K_n
  !> (T §3.8) until the change of Q is below outer_tol; qt = Q(t).
  subroutine steady_at(sys, s, smp, t, qt, rep, err)
    class(periodic_system_t), intent(inout) :: sys
    type(harmonic_settings_t), intent(in) :: s
    type(revolution_samples_t), intent(in) :: smp
    real(dp), intent(in) :: t
    real(dp), intent(out) :: qt(:)
    type(harmonic_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: m(:, :), c(:, :), k(:, :), kn(:, :), f(:), qold(:), qnew(:), fn(:)
    real(dp) :: ch, scale
    integer :: n, kk, it
    type(nonlinear_info_t) :: info
    n = sys%n
    allocate(m(n, n), c(n, n), k(n, n), kn(n, n), f(n), qold(n), qnew(n), fn(n))
    call sys%set_time(t, err)
    if (err%failed()) return
    kk = sample_index(smp, t)
    if (kk >= 0 .and. allocated(smp%m)) then
      m = smp%m(:, :, kk)
      k = smp%k(:, :, kk)
    else
      call sys%linear_terms(m, c, k, f, s%velocity_terms)
    end if
    call series(sys, s, smp, t, k, m, qold, .true., rep, err)
    if (err%failed()) return
    qt = qold
    if (.not. sys%is_nonlinear()) return
    scale = maxval(abs(qold))
    do it = 1, s%max_outer
      call sys%nonlinear_terms(qold, fn, info, secant=kn)
      call series(sys, s, smp, t, k + kn, m, qnew, .false., rep, err)
      if (err%failed()) return
      scale = max(scale, maxval(abs(qnew)))
      ch = 0.0_dp
      if (scale > 0.0_dp) ch = maxval(abs(qnew - qold))/scale
      rep%change(it) = max(rep%change(it), ch)
      qold = qnew
      if (ch <= s%outer_tol) exit
    end do
    if (it > s%max_outer) then
      rep%converged = .false.
      it = s%max_outer
    end if
    rep%outer_iterations = max(rep%outer_iterations, it)
    qt = qold
    call note_strain(rep, info, t)
  end subroutine steady_at

  !> The sample k with t_k = tt (to round-off) or -1.
  integer function sample_index(smp, tt) result(ks)
    type(revolution_samples_t), intent(in) :: smp
    real(dp), intent(in) :: tt
    integer :: i
    ks = -1
    do i = 0, smp%ns - 1
      if (abs(tt - i*smp%period/smp%ns) <= 1.0e-12_dp*smp%period) then
        ks = i
        return
      end if
    end do
  end function sample_index

  !> (T26) with the matrices of time tt.
  subroutine series(sys, s, smp, tt, kmat, mmat, qq, with_rcond, rep, err)
    class(periodic_system_t), intent(in) :: sys
    type(harmonic_settings_t), intent(in) :: s
    type(revolution_samples_t), intent(in) :: smp
    real(dp), intent(in) :: tt, kmat(:, :), mmat(:, :)
    real(dp), intent(out) :: qq(:)
    logical, intent(in) :: with_rcond
    type(harmonic_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    call harmonic_sum(tt, sys%omega, smp%keep, kmat, mmat, smp%a, smp%b, qq, rep, s%resonance_ratio, with_rcond, err)
  end subroutine series

  !> The largest strain so far and where, and whether any passed the peak.
  subroutine note_strain(rep, inf, tt)
    type(harmonic_report_t), intent(inout) :: rep
    type(nonlinear_info_t), intent(in) :: inf
    real(dp), intent(in) :: tt
    if (inf%max_abs_strain > rep%max_abs_strain) then
      rep%max_abs_strain = inf%max_abs_strain
      rep%strain_time = tt
      rep%strain_element = inf%element
    end if
    rep%beyond_peak = rep%beyond_peak .or. inf%beyond_peak
  end subroutine note_strain

  !> C Q_d kept: iterate on the samples, F_eff = F - C Q_d, Q_d from the
  !> trigonometric interpolant of Q at the samples; then (a, b) describe F_eff.
  subroutine velocity_phase(sys, s, smp, rep, err)
    class(periodic_system_t), intent(inout) :: sys
    type(harmonic_settings_t), intent(in) :: s
    type(revolution_samples_t), intent(inout) :: smp
    type(harmonic_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: qs(:, :), qsn(:, :), qd(:, :), feff(:, :), aq(:, :), bq(:, :), kn(:, :), fn(:)
    real(dp) :: chv, sc
    integer :: itv, kq, nn, n, nh, ns
    type(nonlinear_info_t) :: info
    n = sys%n
    nh = smp%nh
    ns = smp%ns
    allocate(qs(n, 0:ns - 1), qsn(n, 0:ns - 1), qd(n, 0:ns - 1), feff(n, 0:ns - 1), aq(n, 0:nh), bq(n, 0:nh), &
             kn(n, n), fn(n))
    qs = 0.0_dp
    do itv = 1, s%max_outer
      ! spectral derivative of the samples (the Nyquist term has zero slope there)
      call fourier_coefficients(qs, nh, aq, bq)
      qd = 0.0_dp
      do kq = 0, ns - 1
        do nn = 1, nh - 1
          qd(:, kq) = qd(:, kq) + (nn*sys%omega)*(-aq(:, nn)*sin(two_pi*nn*kq/real(ns, dp)) + &
                                                  bq(:, nn)*cos(two_pi*nn*kq/real(ns, dp)))
        end do
        feff(:, kq) = smp%f(:, kq) - matmul(smp%c(:, :, kq), qd(:, kq))
      end do
      call fourier_coefficients(feff, nh, smp%a, smp%b)
      do kq = 0, ns - 1
        kn = 0.0_dp
        if (sys%is_nonlinear() .and. itv > 1) then
          call sys%set_time(kq*smp%period/ns, err)
          if (err%failed()) return
          call sys%nonlinear_terms(qs(:, kq), fn, info, secant=kn)
        end if
        call series(sys, s, smp, kq*smp%period/ns, smp%k(:, :, kq) + kn, smp%m(:, :, kq), qsn(:, kq), itv == 1, &
                    rep, err)
        if (err%failed()) return
      end do
      sc = maxval(abs(qsn))
      chv = 0.0_dp
      if (sc > 0.0_dp) chv = maxval(abs(qsn - qs))/sc
      rep%velocity_change(itv) = chv
      qs = qsn
      if (chv <= s%outer_tol .and. itv > 1) exit
    end do
    rep%velocity_iterations = min(itv, s%max_outer)
    if (itv > s%max_outer) rep%converged = .false.
  end subroutine velocity_phase

  !> Q = sum_{n=0}^{keep} (K - n^2 w^2 M)^-1 (a_n cos n w t + b_n sin n w t),
  !> equilibrated by D = diag(K)^(-1/2); with_rcond: conditioning into rep.
  subroutine harmonic_sum(t, omega, keep, kmat, mmat, a, b, q, rep, resonance_ratio, with_rcond, err)
    real(dp), intent(in) :: t, omega, kmat(:, :), mmat(:, :), a(:, 0:), b(:, 0:), resonance_ratio
    integer, intent(in) :: keep
    real(dp), intent(out) :: q(:)
    type(harmonic_report_t), intent(inout) :: rep
    logical, intent(in) :: with_rcond
    type(error_t), intent(inout) :: err
    real(dp) :: d(size(q)), kd(size(q), size(q)), md(size(q), size(q)), rhs(size(q)), rc, rc0, w2, ratio
    type(dense_lu_t) :: lu
    integer :: nn, i, j, n
    n = size(q)
    do i = 1, n
      d(i) = abs(kmat(i, i))
      if (d(i) > 0.0_dp) then
        d(i) = 1.0_dp/sqrt(d(i))
      else
        d(i) = 1.0_dp
      end if
    end do
    do j = 1, n
      kd(:, j) = d*kmat(:, j)*d(j)
      md(:, j) = d*mmat(:, j)*d(j)
    end do
    q = 0.0_dp
    rc0 = 1.0_dp
    do nn = 0, keep
      w2 = (nn*omega)**2
      call lu%factor_shifted(kd, md, w2, err)
      rep%factorizations = rep%factorizations + 1
      if (err%failed()) then
        rep%near_resonance = .true.
        rep%worst_ratio = 0.0_dp
        rep%worst_harmonic = nn
        rep%worst_time = t
        call err%set('harmonic series', 'K - n^2 w^2 M is exactly singular for harmonic n = '//str(nn)// &
                     ' at t = '//str(t)//' s: resonance')
        return
      end if
      if (with_rcond) then
        rc = lu%rcond()
        rep%min_rcond = min(rep%min_rcond, rc)
        if (nn == 0) then
          rc0 = rc
        else
          ratio = rc/rc0
          if (ratio < rep%worst_ratio) then
            rep%worst_ratio = ratio
            rep%worst_harmonic = nn
            rep%worst_time = t
          end if
          if (ratio < resonance_ratio) rep%near_resonance = .true.
        end if
      end if
      rhs = d*(a(:, nn)*cos(nn*omega*t) + b(:, nn)*sin(nn*omega*t))
      call lu%solve(rhs)
      q = q + d*rhs
    end do
  end subroutine harmonic_sum

  !> A harmonic-series steady state that must not be printed, as an error:
  !> strain past the Ramberg-Osgood peak, no convergence, near resonance.
  subroutine harmonic_diagnosis(hs, rep, omega, allow_resonance, allow_beyond_peak, err)
    type(harmonic_settings_t), intent(in) :: hs
    type(harmonic_report_t), intent(in) :: rep
    real(dp), intent(in) :: omega
    logical, intent(in) :: allow_resonance, allow_beyond_peak
    type(error_t), intent(inout) :: err
    if (rep%beyond_peak .and. .not. allow_beyond_peak) then
      call err%set('harmonic series', 'strain '//str(rep%max_abs_strain, 5)//' in element '// &
                   str(rep%strain_element)//' passes the peak of the Ramberg-Osgood law (the material has no '// &
                   'stable meaning beyond it) at crank speed '//str(omega, 6)//' rad/s; the steady state is not '// &
                   'printed (allow_beyond_peak = .true. prints it anyway)')
    else if (.not. rep%converged) then
      call err%set('harmonic series', 'the outer iteration on K_n did not converge in '// &
                   str(hs%max_outer)//' iterations (last change '// &
                   str(rep%change(hs%max_outer), 3)//') at crank speed '//str(omega, 6)//' rad/s')
    else if (rep%near_resonance .and. .not. allow_resonance) then
      call err%set('harmonic series', 'near resonance at crank speed '//str(omega, 6)//' rad/s: K - n^2 w^2 M '// &
                   'is nearly singular for harmonic n = '//str(rep%worst_harmonic)//' ('// &
                   str(rep%worst_harmonic*omega, 6)//' rad/s) at crank angle '// &
                   str(modulo(rep%worst_time*omega*180.0_dp/pi, 360.0_dp), 5)//' deg (rcond/rcond(K) = '// &
                   str(rep%worst_ratio, 3)//' < resonance_ratio = '//str(hs%resonance_ratio, 3)// &
                   '); the steady state is not printed (allow_resonance = .true. prints it anyway)')
    end if
  end subroutine harmonic_diagnosis
end module harmonic_solver
