!> DLSODE for a transient analysis, as &transient asks for it: started on the
!> interleaved state (displacements and rates with their own absolute
!> tolerances, the model's band half-widths), its Newton matrix named in the
!> header, the start frequencies and the integrator's part of the cost footer.
!> Shared by every transient analysis (planar `transient_analysis`, `spatial_analysis`)
!> so that a new one adds its model, not another copy of these steps.
module transient_integration
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use table_output, only: table_t
  use lsode_solver, only: lsode_t, lsode_counters_t, ode_system_t, mf_adams, mf_bdf_full_user, mf_bdf_band_user, &
                          mf_bdf_band_fd, mf_bdf_full_fd
  use linalg, only: sym_generalized_eig, band_generalized_eig, band_eigenvector, dense_to_lower_band
  use band_kernels, only: band_cholesky_inplace, band_cholesky_substitute, band_cholesky_inverse_diagonal
  use transient_settings, only: transient_settings_t
  implicit none
  private
  public :: start_integrator, write_start_frequencies, write_integration_cost, choose_solver_settings

  integer, parameter :: n_modes_reported = 5

  ! The rule of the solver settings a deck leaves out (doc/transient.md, "Default solver settings").
  integer, parameter :: crank_harmonics = 10         !< harmonics of the crank speed the run resolves
  real(dp), parameter :: mode_share = 0.01_dp        !< a mode whose static share is >= this fraction is resolved
  real(dp), parameter :: atol_fraction = 1.0e-6_dp   !< atol / the static deflection
  !> the same for BDF of order 2, whose rates are held more loosely (choose_atol)
  real(dp), parameter :: atol_fraction_order2 = 3.0e-7_dp
  real(dp), parameter :: stiff_ratio = 5.0_dp        !< highest / resolved frequency beyond which BDF is cheaper
  real(dp), parameter :: order2_ratio = 100.0_dp     !< ... beyond which BDF 3-5 meet undamped modes in their unstable band
  real(dp), parameter :: zeta_bdf5 = 0.62_dp         !< cos(51.8 deg): BDF5's A(alpha) sector holds modes damped beyond it
  real(dp), parameter :: fallback_atol = 1.0e-9_dp   !< atol of a model that nothing loads or displaces
  !> a mode with w^2 below this fraction of the largest is free (round-off:
  !> a joint with clearance before contact, a sliding link)
  real(dp), parameter :: free_mode = 1.0e-12_dp
  integer, parameter :: load_samples = 37            !< times at which the rigid-body load is sampled

  !> The model's static response to its loads over a run, sampled time by
  !> time by the driver (it owns M and K):
  !>     call load%start(n, y0, t0, t_end[, kd])
  !>     do while (load%next(t)): M, K of the model at q = 0 and time t; call load%add(model, t, M, K, err)
  !>     call choose_solver_settings(out, s, load, crank_omega, contact, err)
  type, public :: static_load_t
    private
    real(dp) :: q_static = 0.0_dp               !< largest component of a static deflection or the initial displacement
    real(dp), allocatable :: w2(:)              !< the largest square of each natural frequency met
    real(dp), allocatable :: share(:)           !< the largest displacement each mode carries
    real(dp), allocatable :: q0(:)              !< the initial displacement
    real(dp) :: t0 = 0.0_dp, t_end = 0.0_dp
    integer :: n_samples = 0, done = 0
    integer :: kd = -1                          !< half-bandwidth of M and K (< 0: dense)
  contains
    procedure :: start => start_load
    procedure :: next => next_load_time
    procedure :: add => add_load_sample
  end type static_load_t

contains

  !> DLSODE at t0 for n states of a model whose M and K have half-bandwidth kd.
  subroutine start_integrator(out, s, kd, t0, n, ode, err)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(in) :: s
    integer, intent(in) :: kd, n
    real(dp), intent(in) :: t0
    type(lsode_t), intent(inout) :: ode
    type(error_t), intent(inout) :: err
    real(dp) :: atol_vector(n)
    integer :: ml
    ml = min(2*kd + 1, n - 1)    ! the band of M and K in the interleaved state
    atol_vector(1::2) = s%atol
    atol_vector(2::2) = s%atol_rate
    call ode%init(n, t0, s%mf, s%rtol, atol_vector, err, ml=ml, mu=ml, max_steps=s%max_steps)
    if (err%failed()) return
    if (s%max_order > 0) then
      call ode%limit_order(s%max_order)     ! DLSODE's MAXORD (optional input, IOPT = 1)
      call out%comment('DLSODE order limited to '//str(s%max_order))
    end if
    if (s%mf == mf_bdf_full_user .or. s%mf == mf_bdf_band_user) then
      call out%comment('BDF Newton matrix: the model''s banded N x N elimination M + (h el0 beta + (h el0)^2) K_t, '// &
                       'half-bandwidth '//str(kd)//' (doc/transient.md)')
    else if (s%mf == mf_bdf_band_fd) then
      call out%comment('banded BDF: finite-difference Jacobian truncated to half-bandwidths ml = mu = '// &
                       str(ml)//' (the band of M and K in the interleaved state)')
    end if
  end subroutine start_integrator

  !> The solver settings the deck left out (method 'auto', atol, atol_rate,
  !> max_order < 0), chosen from the model, one header line each with why
  !> (doc/transient.md, "Default solver settings"):
  !>  - the static deflection q_s under the rigid-body inertia and external
  !>    loads, sampled over the run's span, and the initial displacement:
  !>    atol = atol_fraction * max |q_s|; atol_rate = atol times a frequency
  !>    (choose_atol);
  !>  - the frequencies the run must resolve: crank_harmonics harmonics of the
  !>    crank speed and every mode that carries at least mode_share of q_s
  !>    (the load's own content; the axial modes carry almost none);
  !>  - the stiffness: the fastest rate of the model (the highest natural
  !>    frequency, or beta w^2 of an overdamped mode) over the highest
  !>    frequency the run resolves; beyond stiff_ratio Adams' stability
  !>    limit, not its accuracy, sets its step, and BDF with the model's
  !>    Newton matrix is cheaper;
  !>  - BDF 3-5 amplify lightly damped modes near the imaginary axis: beyond
  !>    order2_ratio, modes with damping ratio below zeta_bdf5 lie there at
  !>    the run's steps, and order 2 (A-stable) is chosen with the method.
  !> A deck's method keeps DLSODE's orders, and a deck's atol is its
  !> atol_rate too unless it gives one: then a note says what the rule
  !> would choose.  load: the model's static response over the run
  !> (static_load_t); crank_omega: the crank's speed (0: none); contact:
  !> joints with clearance (their contact stiffness is not in K: always
  !> stiff).
  subroutine choose_solver_settings(out, s, load, crank_omega, contact, err)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(inout) :: s
    type(static_load_t), intent(in) :: load
    real(dp), intent(in) :: crank_omega
    logical, intent(in) :: contact
    type(error_t), intent(inout) :: err
    real(dp) :: q_static, w_resolve, w_mode, w_max, w_fast, ratio, zeta_max
    integer :: n_resolved, n
    character(len=:), allocatable :: why
    logical :: method_chosen, stiff, order2
    if (err%failed()) return
    method_chosen = s%method == 'auto'
    n = size(load%w2)
    q_static = load%q_static
    w_max = sqrt(max(load%w2(n), 0.0_dp))
    n_resolved = 0
    if (q_static > 0.0_dp) n_resolved = count(load%share >= mode_share*q_static .and. load%w2 > free_mode*load%w2(n))
    w_mode = 0.0_dp
    if (n_resolved > 0) w_mode = sqrt(maxval(load%w2, mask=load%share >= mode_share*q_static .and. &
                                             load%w2 > free_mode*load%w2(n)))
    if (w_mode <= 0.0_dp .and. crank_omega <= 0.0_dp) w_mode = sqrt(max(load%w2(1), 0.0_dp))
    w_resolve = max(crank_harmonics*crank_omega, w_mode)
    ! the fastest decay or oscillation rate: a mode damped beyond critical (zeta = beta w/2 > 1) decays at about beta w^2
    w_fast = max(w_max, s%damping_beta*w_max**2)
    ratio = w_fast/max(w_resolve, tiny(1.0_dp))
    why = 'the fastest rate of the model, '//str(w_fast, 4)//' 1/s, is '//str(ratio, 3)//' times the highest '// &
          'the run resolves, '//str(w_resolve, 4)//' rad/s (of '//str(crank_harmonics)//' crank harmonics and '// &
          'the '//str(n_resolved)//' modes carrying '//str(nint(100*mode_share))//' % or more of the static deflection)'
    stiff = ratio > stiff_ratio .or. contact
    if (contact) why = why//'; joints with clearance add contact stiffness'
    if (method_chosen) then
      s%method = merge('bdf  ', 'adams', stiff)
      s%mf = merge(mf_bdf_full_user, mf_adams, stiff)
      if (stiff) then
        call out%comment('method = ''bdf'' (chosen): '//why//': stiff, Adams would step at its stability limit')
      else
        call out%comment('method = ''adams'' (chosen): '//why//': not stiff')
      end if
    end if
    zeta_max = 0.5_dp*s%damping_beta*w_max
    order2 = s%mf /= mf_adams .and. ratio > order2_ratio .and. zeta_max < zeta_bdf5
    if (s%max_order < 0) then
      s%max_order = 0
      if (order2 .and. method_chosen) then
        s%max_order = 2
        call out%comment('max_order = 2 (chosen): the natural frequencies reach '//str(ratio, 3)//' times the '// &
                         'highest the run resolves with damping ratios below '//str(zeta_bdf5, 2)//': such modes '// &
                         'lie near the imaginary axis at the run''s steps, where BDF 3-5 amplify them')
      else if (order2) then
        call out%comment('note: the natural frequencies reach '//str(ratio, 3)//' times the highest the run '// &
                         'resolves with damping ratios below '//str(zeta_bdf5, 2)//': BDF 3-5 amplify such modes; '// &
                         'max_order = 2 is often far cheaper')
      end if
    end if
    if (s%atol < 0.0_dp) then
      call choose_atol(out, s, q_static, w_max, w_resolve)
    else if (abs(s%atol_rate - s%atol) <= 0.0_dp .and. stiff .and. s%atol*w_resolve > 1.0e2_dp*s%atol_rate) then
      call out%comment('note: atol_rate = atol = '//str(s%atol_rate, 3)//' holds the rates (per second) to the '// &
                       'displacements'' tolerance; atol times the highest frequency the run resolves ('// &
                       str(s%atol*w_resolve, 3)//') is often far cheaper at the same peaks')
    end if
  end subroutine choose_solver_settings

  !> atol and, unless the deck gives it, atol_rate (choose_solver_settings):
  !> the displacements to atol_fraction of the static deflection; the rates
  !> to atol times the highest frequency the run resolves, w_r.  BDF 3-5 and
  !> Adams need these rates: their error test is what holds a spurious growth
  !> of the undamped stiff modes (measured: an undamped clamped beam from its
  !> first mode missed a stress peak by 11 % at order 5 with looser rates).
  !> BDF of order 2 (A-stable) cannot amplify a mode: the rates then go to
  !> atol times sqrt(w_r w_max), halfway on a log scale to the highest
  !> natural frequency (the spin-up beam: 7.6 times fewer steps than with
  !> atol w_r; atol w_max, the loosest, moved a large-amplitude pinned beam's
  !> membrane stress peak by 1.6 %, the geometric mean by 0.8 %).  With those
  !> looser rates the displacements are held 3 times tighter (the spin-up
  !> beam's tip-element stress peak: 1.6 % off at 1e-6 of the static
  !> deflection, 0.15 % at 3e-7 and 0.25 % at 1e-7, for 17 % more CPU).
  subroutine choose_atol(out, s, q_static, w_max, w_resolve)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(inout) :: s
    real(dp), intent(in) :: q_static, w_max, w_resolve
    real(dp) :: fraction
    logical :: order2
    order2 = s%mf /= mf_adams .and. s%max_order > 0 .and. s%max_order <= 2
    fraction = merge(atol_fraction_order2, atol_fraction, order2)
    if (q_static > 0.0_dp) then
      s%atol = fraction*q_static
      call out%comment('atol = '//str(s%atol, 3)//' (chosen): '//str(fraction, 2)//' of the static '// &
                       'deflection under the rigid-body inertia and external loads and of the initial '// &
                       'displacement, '//str(q_static, 4))
    else
      s%atol = fallback_atol
      call out%comment('atol = '//str(s%atol, 3)//' (chosen): nothing loads or displaces the model')
    end if
    if (s%atol_rate >= 0.0_dp) return
    if (order2) then
      s%atol_rate = s%atol*sqrt(max(w_max*w_resolve, 1.0_dp))
      call out%comment('atol_rate = '//str(s%atol_rate, 3)//' (chosen): atol times '// &
                       str(sqrt(max(w_max*w_resolve, 1.0_dp)), 4)//' rad/s, the geometric mean of the highest '// &
                       'natural frequency and the highest the run resolves: BDF of order 2 cannot amplify a mode, '// &
                       'and the stiff modes'' rates need not be resolved')
    else
      s%atol_rate = s%atol*max(w_resolve, 1.0_dp)
      call out%comment('atol_rate = '//str(s%atol_rate, 3)//' (chosen): atol times the highest frequency the '// &
                       'run resolves, '//str(w_resolve, 4)//' rad/s')
    end if
  end subroutine choose_atol

  !> n unknowns, the initial state y0 (interleaved), the run's span; kd: the
  !> half-bandwidth of M and K, whose modes are then found by the banded
  !> solver (band_generalized_eig: O(n^2 kd) instead of O(n^3)).
  subroutine start_load(self, n, y0, t0, t_end, kd)
    class(static_load_t), intent(inout) :: self
    integer, intent(in) :: n
    real(dp), intent(in) :: y0(:), t0, t_end
    integer, intent(in), optional :: kd
    self%kd = -1
    if (present(kd)) self%kd = kd
    self%q0 = y0(1::2)
    self%q_static = maxval(abs(self%q0))
    allocate(self%w2(n), self%share(n))
    self%w2 = 0.0_dp
    self%share = 0.0_dp
    self%t0 = t0
    self%t_end = t_end
    self%n_samples = sample_count(n)
    self%done = 0
  end subroutine start_load

  !> The next sample time t (load_samples over [t0, t_end], fewer for a model
  !> whose order makes each sample's eigenproblem costly); false when done.
  logical function next_load_time(self, t) result(more)
    class(static_load_t), intent(in) :: self
    real(dp), intent(out) :: t
    more = self%done < self%n_samples
    t = self%t0 + (self%t_end - self%t0)*self%done/real(max(self%n_samples - 1, 1), dp)
  end function next_load_time

  !> The sample at time t: M and K of the model at q = 0 (its degrees of
  !> freedom turn with the rigid-body motion, so M and K are the time's), the
  !> accelerations a at the rigid-body state (rhs at y = 0); the static
  !> deflection K^-1 M a mode by mode (free modes carry none) and each mode's
  !> largest displacement in it (and, at the first sample, in the initial
  !> displacement).  A banded model's shapes are found from the lowest up,
  !> until no higher mode can reach the rule's share (banded_shapes).
  subroutine add_load_sample(self, model, t, mass, stiff, err)
    class(static_load_t), intent(inout) :: self
    class(ode_system_t), intent(inout) :: model
    real(dp), intent(in) :: t, mass(:, :), stiff(:, :)
    type(error_t), intent(inout) :: err
    real(dp) :: shapes(size(self%w2), size(self%w2)), w2(size(self%w2)), peak(size(self%w2)), &
                scale(size(self%w2)), modal(size(self%w2)), y(2*size(self%w2)), ydot(2*size(self%w2)), &
                f(size(self%w2)), q_static
    integer :: k, n_shapes
    logical :: bounded
    y = 0.0_dp
    call model%rhs(t, y, ydot)
    if (model%err%failed()) then
      call err%set('', model%err%text())
      return
    end if
    f = matmul(ydot(2::2), mass)
    bounded = .false.
    n_shapes = size(w2)
    if (self%kd >= 0 .and. self%kd < size(w2) - 1) then
      call band_generalized_eig(stiff, mass, self%kd, w2, err)
      if (err%failed()) return
      call banded_shapes(self, mass, stiff, f, w2, shapes, n_shapes, q_static, bounded, err)
    else
      call sym_generalized_eig(stiff, mass, w2, err, shapes)
    end if
    if (err%failed()) return
    self%w2 = max(self%w2, w2)
    peak = 0.0_dp
    peak(:n_shapes) = [(maxval(abs(shapes(:, k))), k = 1, n_shapes)]
    scale = 0.0_dp
    where (w2 > free_mode*w2(size(w2))) scale = 1.0_dp/w2
    if (self%done == 0) self%share(:n_shapes) = abs(matmul(matmul(self%q0, mass), shapes(:, :n_shapes)))*peak(:n_shapes)
    modal = 0.0_dp
    modal(:n_shapes) = matmul(f, shapes(:, :n_shapes))*scale(:n_shapes)
    self%share(:n_shapes) = max(self%share(:n_shapes), abs(modal(:n_shapes))*peak(:n_shapes))
    if (bounded) then
      self%q_static = max(self%q_static, q_static)
    else
      self%q_static = max(self%q_static, maxval(abs(matmul(shapes, modal))))
    end if
    self%done = self%done + 1
  end subroutine add_load_sample

  !> The shapes of the lowest n_shapes modes of a banded model, ascending,
  !> until no higher mode can carry mode_share of the static deflection
  !> (doc/transient.md, "Default solver settings"), and this sample's static
  !> deflection q_static = max |K^-1 f| (f = M a).  An M-normalised mode phi
  !> has |phi_i| <= d = max_i sqrt((M^-1)_ii), and the modes k > m together
  !> hold sum_k>m (phi_k^T g)^2 = g^T M^-1 g - sum_k<=m (phi_k^T g)^2 = r_m(g)^2
  !> of any g.  So mode k > m carries at most d r_m(f) / w_k^2 of the load's
  !> deflection (|phi^T f| max|phi| / w^2) and, at the first sample, d
  !> r_m(K q0) / w_k^2 of the initial displacement q0 (|phi^T M q0| =
  !> |phi^T K q0| / w^2): the search stops when that bound at w_m+1 is below
  !> half of mode_share times the largest deflection known so far (the
  !> rule's q_s can only grow).  bounded = .false. (every shape found, and
  !> q_static not set) when K is not positive definite or has free modes.
  subroutine banded_shapes(self, mass, stiff, f, w2, shapes, n_shapes, q_static, bounded, err)
    class(static_load_t), intent(in) :: self
    real(dp), intent(in) :: mass(:, :), stiff(:, :), f(:), w2(:)
    real(dp), intent(out) :: shapes(:, :), q_static
    integer, intent(out) :: n_shapes
    logical, intent(out) :: bounded
    type(error_t), intent(inout) :: err
    real(dp) :: mb(self%kd + 1, size(f)), kb(self%kd + 1, size(f)), d(size(f)), x(size(f)), g0(size(f)), &
                r2(2), floor(2), threshold, d_max
    integer :: info, k, n
    n = size(f)
    shapes = 0.0_dp
    q_static = 0.0_dp
    n_shapes = n
    call dense_to_lower_band(mass, self%kd, mb)
    call dense_to_lower_band(stiff, self%kd, kb)
    call band_cholesky_inplace(mb, self%kd, info)
    bounded = info == 0
    if (bounded) then
      call band_cholesky_inplace(kb, self%kd, info)
      bounded = info == 0 .and. w2(1) > free_mode*w2(n)
    end if
    if (.not. bounded) then
      do k = 1, n
        call band_eigenvector(stiff, mass, self%kd, w2, k, shapes, err)
        if (err%failed()) return
      end do
      return
    end if
    x = f
    call band_cholesky_substitute(kb, self%kd, x)
    q_static = maxval(abs(x))
    threshold = 0.5_dp*mode_share*max(self%q_static, q_static)
    g0 = 0.0_dp
    if (self%done == 0) g0 = matmul(stiff, self%q0)
    x = f
    call band_cholesky_substitute(mb, self%kd, x)
    r2(1) = dot_product(f, x)
    x = g0
    call band_cholesky_substitute(mb, self%kd, x)
    r2(2) = dot_product(g0, x)
    floor = 1.0e3_dp*epsilon(1.0_dp)*r2           ! the round-off of the subtractions below
    call band_cholesky_inverse_diagonal(mb, self%kd, d)
    d_max = sqrt(maxval(d))
    n_shapes = 0
    do k = 1, n
      if (d_max*sqrt(maxval(max(r2, 0.0_dp) + floor)) < threshold*w2(k)) exit
      call band_eigenvector(stiff, mass, self%kd, w2, k, shapes, err)
      if (err%failed()) return
      n_shapes = k
      r2(1) = r2(1) - dot_product(shapes(:, k), f)**2
      r2(2) = r2(2) - dot_product(shapes(:, k), g0)**2
    end do
  end subroutine banded_shapes

  !> The number of times the load is sampled at: load_samples, fewer for a
  !> model whose order n makes each sample's eigenproblem (n^3) costly.
  pure integer function sample_count(n)
    integer, intent(in) :: n
    sample_count = max(5, min(load_samples, int(load_samples*(60.0_dp/max(n, 1))**3)))
  end function sample_count

  !> The header line of the lowest natural frequencies at the start position.
  subroutine write_start_frequencies(out, omega_n)
    type(table_t), intent(inout) :: out
    real(dp), intent(in) :: omega_n(:)
    character(len=:), allocatable :: line
    integer :: k
    line = 'natural frequencies of the linearised structure at the start position (rad/s):'
    do k = 1, min(n_modes_reported, size(omega_n))
      line = line//' '//str(omega_n(k), 6)
    end do
    call out%comment(line)
  end subroutine write_start_frequencies

  !> The integrator's cost lines: CPU time, DLSODE's counters, the model's
  !> banded Newton matrix (its Cholesky + LU count and LU count) and mass
  !> factorizations.  The caller adds its model's own work after them.
  subroutine write_integration_cost(out, s, c, cpu, revolutions_done, newton_factorizations, newton_lu, &
                                    mass_factorizations)
    type(table_t), intent(inout) :: out
    type(transient_settings_t), intent(in) :: s
    type(lsode_counters_t), intent(in) :: c
    real(dp), intent(in) :: cpu, revolutions_done
    integer, intent(in) :: newton_factorizations, newton_lu, mass_factorizations
    ! DLSODE rebuilds the Jacobian after a failed corrector; at a third of the
    ! steps its finite differences are too poor (fuzz seed 9: bdf_fd with the
    ! consistent element at atol 1e-12 took 1000 times bdf's CPU)
    if ((s%mf == mf_bdf_full_fd .or. s%mf == mf_bdf_band_fd) .and. c%steps >= 1000 .and. 3*c%jac_evals > c%steps) &
      call out%summary('warning', trim(s%method)//' rebuilt its finite-difference Jacobian at '// &
                       str(c%jac_evals)//' of '//str(c%steps)//' steps: its differences are poor at these '// &
                       'tolerances; method = ''bdf'' (analytic Jacobian) or a larger atol is far cheaper')
    call out%cost('cpu_seconds_integration', str(cpu, 4))
    if (revolutions_done > 0.0_dp) call out%cost('cpu_seconds_per_revolution', str(cpu/revolutions_done, 4))
    call out%cost('method', trim(s%method)//' (DLSODE MF='//str(s%mf)//')')
    call out%cost('steps', str(c%steps))
    call out%cost('rhs_evaluations', str(c%rhs_evals))
    call out%cost('jacobian_evaluations', str(c%jac_evals))
    call out%cost('lu_factorizations', str(c%lu_factorizations))
    if (c%model_newton) call out%cost('newton_matrix', 'banded N x N, '//str(newton_factorizations - newton_lu)// &
                                      ' Cholesky and '//str(newton_lu)//' LU factorizations')
    call out%cost('mass_factorizations', str(mass_factorizations))
  end subroutine write_integration_cost
end module transient_integration
