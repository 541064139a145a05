!> The exact periodic steady state of a periodic system by shooting: Newton's
!> method on the one-revolution map y0 -> Phi_T(y0) of the first-order
!> equations y = (Q, Q_d),
!>
!>     Q_dd = M(t)^-1 (F(t) - C(t) Q_d - K_e(t) Q - f_n(Q, t)),
!>
!> integrated over one period T = 2 pi / omega by DLSODE (Adams) together
!> with the variational equations Y' = J(t, y) Y, Y(0) = I, so that
!> Y(T) = d Phi_T / d y0 is the monodromy matrix: Newton's Jacobian is
!> Y(T) - I, and at the periodic solution its eigenvalues are the Floquet
!> multipliers (|mu| <= 1 for all: the steady state is stable).  C Q_d and
!> damping are kept: this is the steady state that the harmonic series
!> approximates (doc/steady_state.md §4).
!>
!> For a linear system Y(T) does not depend on y0: one Newton step gives the
!> periodic solution; a state-only integration confirms it.
!>
!> method 'bdf' (for damped, stiff models) uses DLSODE's BDF with a banded
!> Jacobian (MF = 24): the augmented state [y, Y e_1, ..., Y e_2n] has the
!> block-diagonal Jacobian diag(J, J, ..., J), J = [0 I; -M^-1 K_t  -M^-1 C],
!> of half-bandwidth 2n - 1 (the coupling of Y to y through K_t(y) is left
!> out: the corrector only needs an approximation).  The flow factors
!> DLSODE's Newton matrix itself (lsode_solver's model route): one 2n x 2n
!> block I - h el0 J, applied to each of the 1 + 2n (+ parameters) blocks,
!> instead of a band LU of the whole augmented system (the same matrix; at
!> n = 10 the monodromy revolution's linear algebra is about 20 times less).
module periodic_shooting
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use progress, only: progress_t
  use lsode_solver, only: ode_system_t, lsode_t, lsode_counters_t, mf_adams, mf_bdf_band_user
  use linalg, only: lu_factor, lu_solve, eigenvalues_general
  use small_dense, only: dense_lu_t
  use periodic_system, only: periodic_system_t, nonlinear_info_t
  implicit none
  private
  public :: shooting_settings_t, shooting_report_t, shooting_solve, periodic_orbit, flow_t, max_newton_limit
  public :: shooting_diagnosis, orbit_sensitivity

  integer, parameter :: max_newton_limit = 50

  type :: shooting_settings_t
    real(dp) :: rtol = 1.0e-9_dp           !< DLSODE relative tolerance
    real(dp) :: atol = 1.0e-13_dp          !< DLSODE absolute tolerance (all components)
    integer :: max_newton = 12
    real(dp) :: newton_tol = 1.0e-6_dp     !< |Phi(y0) - y0| relative to |y| (Q and Q_d separately); >> rtol
    !> DLSODE steps per revolution: 3 times the most a shipped deck needs
    !> (68,000, the 295 rad/s tongue sweep at rtol 1e-10), about 8 CPU s of
    !> Adams steps; 2,000,000 let a deck run 40 s before saying it is stiff
    !> (fuzz seed 13, case 19517)
    integer :: max_steps = 200000
    real(dp) :: unit_circle_tol = 1.0e-3_dp !< |mu| > 1 + tol: unstable
    real(dp) :: singular_rcond = 1.0e-6_dp !< rcond |Y(T) - I| (energy units) below this: no isolated periodic solution
    logical :: bdf = .false.               !< BDF with a banded block Jacobian instead of Adams
  end type shooting_settings_t

  type :: shooting_report_t
    integer :: newton_iterations = 0
    logical :: converged = .false.
    real(dp) :: residual(0:max_newton_limit) = 0.0_dp
    real(dp), allocatable :: mult_re(:), mult_im(:)
    real(dp) :: max_multiplier = 0.0_dp
    logical :: stable = .true.
    real(dp) :: rcond_newton = huge(1.0_dp)   !< smallest rcond(Y(T) - I) |Y(T) - I| (energy units) met
    logical :: near_resonance = .false.
    integer :: steps = 0, rhs_evaluations = 0, revolutions = 0
  end type shooting_report_t

  !> y' = f(t, y) of the mechanism, optionally with the variational equations.
  type, extends(ode_system_t) :: flow_t
    class(periodic_system_t), pointer :: sys => null()
    integer :: n = 0
    logical :: variational = .false.
    real(dp), allocatable :: m(:, :), c(:, :), k(:, :), f(:), fn(:), kt(:, :)
    type(dense_lu_t) :: lu
    type(dense_lu_t) :: newton_lu          !< I - h el0 J of one block (BDF's Newton matrix)
  contains
    procedure :: rhs => flow_rhs
    procedure :: jacobian => flow_jacobian
    procedure :: has_newton_matrix => flow_has_newton_matrix
    procedure :: newton_factor => flow_newton_factor
    procedure :: newton_solve => flow_newton_solve
    procedure :: setup
  end type flow_t

  !> The flow with the parameter sensitivities S_j = dy/dp_j after the state
  !> (and the monodromy columns, when asked): S_j' = f_y S_j + f_p_j, with
  !> f_p_j the central difference (f(p + h_j) - f(p - h_j)) / (2 h_j) of the
  !> right-hand sides of the two perturbed systems.
  type, extends(flow_t) :: sensitivity_flow_t
    logical :: with_mono = .false.
    type(flow_t), allocatable :: plus(:), minus(:)
    real(dp), allocatable :: inv_step(:)          !< 1 / (p_j+ - p_j-)
  contains
    procedure :: rhs => sensitivity_rhs
  end type sensitivity_flow_t

contains

  subroutine setup(self, sys, variational)
    class(flow_t), intent(inout) :: self
    class(periodic_system_t), target, intent(inout) :: sys
    logical, intent(in) :: variational
    self%sys => sys
    self%n = sys%n
    self%variational = variational
    if (.not. allocated(self%m)) allocate(self%m(sys%n, sys%n), self%c(sys%n, sys%n), self%k(sys%n, sys%n), &
                                          self%f(sys%n), self%fn(sys%n), self%kt(sys%n, sys%n))
    call self%err%clear()
  end subroutine setup

  subroutine flow_rhs(self, t, y, ydot)
    class(flow_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    type(nonlinear_info_t) :: info
    integer :: n, j, n2
    real(dp) :: acc(self%n), col(self%n)
    logical :: ok
    n = self%n
    n2 = 2*n
    ydot = 0.0_dp
    call linear_terms_at(self, t, ok)
    if (.not. ok) return
    if (self%sys%is_nonlinear()) then
      if (self%variational) then
        call self%sys%nonlinear_terms(y(1:n), self%fn, info, tangent=self%kt)
      else
        call self%sys%nonlinear_terms(y(1:n), self%fn, info)
      end if
      if (info%beyond_peak) then
        call self%fail(t, 'strain '//str(info%max_abs_strain, 6)//' in element '//str(info%element)// &
                       ' is past the peak of the Ramberg-Osgood law: the material has no stable meaning beyond it')
        return
      end if
    else
      self%fn = 0.0_dp
      self%kt = 0.0_dp
    end if
    call factor_mass(self, t, ok)
    if (.not. ok) return
    acc = self%f - matmul(self%c, y(n + 1:n2)) - matmul(self%k, y(1:n)) - self%fn
    call self%lu%solve(acc)
    ydot(1:n) = y(n + 1:n2)
    ydot(n + 1:n2) = acc
    if (.not. self%variational) return
    if (self%sys%is_nonlinear()) self%k = self%k + self%kt
    ! Y = [Yq; Yv] (2n x 2n, column-major after the state): Yq' = Yv,
    ! Yv' = -M^-1 (K Yq + C Yv)
    do j = 1, n2
      associate (yq => y(n2 + (j - 1)*n2 + 1:n2 + (j - 1)*n2 + n), yv => y(n2 + (j - 1)*n2 + n + 1:n2 + j*n2))
        ydot(n2 + (j - 1)*n2 + 1:n2 + (j - 1)*n2 + n) = yv
        col = -(matmul(self%k, yq) + matmul(self%c, yv))
        call self%lu%solve(col)
        ydot(n2 + (j - 1)*n2 + n + 1:n2 + j*n2) = col
      end associate
    end do
  end subroutine flow_rhs

  !> M, C, K and f of the system at time t (the flow fails on an error).
  subroutine linear_terms_at(self, t, ok)
    class(flow_t), intent(inout) :: self
    real(dp), intent(in) :: t
    logical, intent(out) :: ok
    type(error_t) :: err
    call self%sys%set_time(t, err)
    ok = .not. err%failed()
    if (.not. ok) then
      call self%fail(t, err%text())
      return
    end if
    call self%sys%linear_terms(self%m, self%c, self%k, self%f, .true.)
  end subroutine linear_terms_at

  !> The LU factors of M for the solves of the right-hand side.
  subroutine factor_mass(self, t, ok)
    class(flow_t), intent(inout) :: self
    real(dp), intent(in) :: t
    logical, intent(out) :: ok
    type(error_t) :: err
    call self%lu%factor(self%m, err)
    ok = .not. err%failed()
    if (.not. ok) call self%fail(t, 'mass matrix: '//err%text())
  end subroutine factor_mass

  integer function method_flag(s)
    type(shooting_settings_t), intent(in) :: s
    method_flag = mf_adams
    if (s%bdf) method_flag = mf_bdf_band_user
  end function method_flag

  !> The lower blocks of J = [0 I; A B] at (t, y): A = -M^-1 K_t, B = -M^-1 C.
  subroutine jacobian_blocks(self, t, y, a, b, ok)
    class(flow_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: a(:, :), b(:, :)
    logical, intent(out) :: ok
    type(nonlinear_info_t) :: info
    real(dp) :: col(self%n)
    integer :: j
    call linear_terms_at(self, t, ok)
    if (.not. ok) return
    if (self%sys%is_nonlinear()) then
      call self%sys%nonlinear_terms(y(1:self%n), self%fn, info, tangent=self%kt)
      self%k = self%k + self%kt
    end if
    call factor_mass(self, t, ok)
    if (.not. ok) return
    do j = 1, self%n
      col = -self%k(:, j)
      call self%lu%solve(col)
      a(:, j) = col
      col = -self%c(:, j)
      call self%lu%solve(col)
      b(:, j) = col
    end do
  end subroutine jacobian_blocks

  !> The BDF flow factors its own Newton matrix (one block; see the header).
  logical function flow_has_newton_matrix(self)
    class(flow_t), intent(in) :: self
    flow_has_newton_matrix = self%n > 0
  end function flow_has_newton_matrix

  !> P = I - hl0 J of one 2n block at (t, y), factored.
  subroutine flow_newton_factor(self, t, y, hl0, ok)
    class(flow_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:), hl0
    logical, intent(out) :: ok
    real(dp) :: a(self%n, self%n), b(self%n, self%n), p(2*self%n, 2*self%n)
    type(error_t) :: err
    integer :: n, i
    n = self%n
    call jacobian_blocks(self, t, y, a, b, ok)
    if (.not. ok) return
    p = 0.0_dp
    do i = 1, n
      p(i, i) = 1.0_dp
      p(i, n + i) = -hl0
    end do
    p(n + 1:, 1:n) = -hl0*a
    p(n + 1:, n + 1:) = -hl0*b
    do i = n + 1, 2*n
      p(i, i) = p(i, i) + 1.0_dp
    end do
    call self%newton_lu%factor(p, err)
    ok = .not. err%failed()
  end subroutine flow_newton_factor

  !> x := P^-1 x, block by block.
  subroutine flow_newton_solve(self, x)
    class(flow_t), intent(inout) :: self
    real(dp), intent(inout) :: x(:)
    real(dp) :: block(2*self%n)
    integer :: n2, o
    n2 = 2*self%n
    do o = 0, size(x) - n2, n2
      block = x(o + 1:o + n2)
      call self%newton_lu%solve(block)
      x(o + 1:o + n2) = block
    end do
  end subroutine flow_newton_solve

  !> Block-diagonal Jacobian in DLSODE's band storage, pd(i - j + mu + 1, j).
  subroutine flow_jacobian(self, t, y, ml, mu, pd)
    class(flow_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    integer, intent(in) :: ml, mu
    real(dp), intent(inout) :: pd(:, :)
    real(dp) :: a(self%n, self%n), b(self%n, self%n)
    integer :: n, n2, nb, blk, i, j, o
    logical :: ok
    n = self%n
    n2 = 2*self%n
    if (ml < n2 - 1 .or. mu < n2 - 1) then
      call self%fail(t, 'the band (ml = '//str(ml)//', mu = '//str(mu)//') does not hold a '//str(n2)//' x '// &
                     str(n2)//' block of the flow''s Jacobian')
      return
    end if
    call jacobian_blocks(self, t, y, a, b, ok)
    if (.not. ok) return
    nb = size(y)/n2
    do blk = 0, nb - 1
      o = blk*n2
      do j = 1, n
        pd(o + j - (o + n + j) + mu + 1, o + n + j) = 1.0_dp
        do i = 1, n
          pd(o + n + i - (o + j) + mu + 1, o + j) = a(i, j)
          pd(o + n + i - (o + n + j) + mu + 1, o + n + j) = b(i, j)
        end do
      end do
    end do
  end subroutine flow_jacobian

  !> One revolution from y0 (state only, or with the monodromy matrix).
  subroutine revolution(sys, s, y0, variational, yt, mono, rep, err)
    class(periodic_system_t), target, intent(inout) :: sys
    type(shooting_settings_t), intent(in) :: s
    real(dp), intent(in) :: y0(:)
    logical, intent(in) :: variational
    real(dp), intent(out) :: yt(:)
    real(dp), intent(out) :: mono(:, :)
    type(shooting_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    type(flow_t), target :: flow
    type(lsode_t) :: ode
    type(lsode_counters_t) :: cnt
    real(dp), allocatable :: y(:)
    integer :: n2, neq, j
    n2 = 2*sys%n
    neq = n2
    if (variational) neq = n2 + n2*n2
    allocate(y(neq))
    y(1:n2) = y0
    if (variational) then
      y(n2 + 1:) = 0.0_dp
      do j = 1, n2
        y(n2 + (j - 1)*n2 + j) = 1.0_dp
      end do
    end if
    call flow%setup(sys, variational)
    call ode%init(neq, 0.0_dp, method_flag(s), s%rtol, [s%atol], err, max_steps=s%max_steps, ml=n2 - 1, mu=n2 - 1)
    if (err%failed()) return
    call integrate_revolution(ode, flow, y, sys%period(), s, err)
    cnt = ode%counters()
    rep%steps = rep%steps + cnt%steps
    rep%rhs_evaluations = rep%rhs_evaluations + cnt%rhs_evals
    rep%revolutions = rep%revolutions + 1
    if (err%failed()) return
    yt = y(1:n2)
    if (variational) mono = reshape(y(n2 + 1:), [n2, n2])
  end subroutine revolution

  !> y from 0 to the period in legs_per_revolution legs.  DLSODE steps past
  !> each leg's end and interpolates, so the legs leave the step sequence
  !> alone; after each, a step count that extrapolates past max_steps for the
  !> revolution stops the run there, instead of after minutes of the tiny
  !> steps of a problem too stiff for its method (fuzz seed 11, case 20129:
  !> 42 s of Adams steps before the limit; now 0.7 s).
  subroutine integrate_revolution(ode, flow, y, period, s, err)
    type(lsode_t), intent(inout) :: ode
    type(flow_t), intent(inout) :: flow
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: period
    type(shooting_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    integer, parameter :: legs_per_revolution = 64
    type(lsode_counters_t) :: cnt
    real(dp) :: projected
    integer :: leg
    do leg = 1, legs_per_revolution
      call ode%integrate_to(flow, y, period*leg/legs_per_revolution, err)
      if (err%failed()) return
      cnt = ode%counters()
      projected = real(cnt%steps, dp)*legs_per_revolution/leg
      if (leg < legs_per_revolution .and. past_limit(cnt%steps, projected, leg)) then
        call err%set('DLSODE', str(cnt%steps)//' steps for '//str(leg)//'/'//str(legs_per_revolution)// &
          ' of a revolution: at this rate the revolution needs '//str(nint(projected))//' > max_steps = '// &
          str(s%max_steps)//trim(stiff_advice(s)), code=-1)
        return
      end if
    end do
  contains
    !> The first legs hold the start-up of the step sequence (the Whitworth
    !> deck at 60 rad/s: its first 1/64 extrapolates to 230,000 steps, its
    !> revolution takes 50,000), so before 1/8 of the revolution only a count
    !> that extrapolates far past the limit stops the run.
    logical function past_limit(steps, projected, leg)
      integer, intent(in) :: steps, leg
      real(dp), intent(in) :: projected
      integer, parameter :: sampled_legs = legs_per_revolution/8, early_margin = 4
      past_limit = steps > s%max_steps .or. projected > real(early_margin, dp)*s%max_steps .or. &
                   (leg >= sampled_legs .and. projected > s%max_steps)
    end function past_limit
  end subroutine integrate_revolution

  function stiff_advice(s) result(advice)
    type(shooting_settings_t), intent(in) :: s
    character(len=:), allocatable :: advice
    if (s%bdf) then
      advice = '; the step size is far below the period: check the mechanism''s proportions and the tolerances, '// &
        'or raise max_steps (&steady)'
    else
      advice = '; the problem is probably stiff for the Adams method: use integrator = ''bdf'' (&steady), '// &
        'or raise max_steps'
    end if
  end function stiff_advice

  !> Newton on Phi_T(y0) = y0 from the guess y0; on return y0 is the initial
  !> state of the periodic solution.  monodromy, when present, receives the
  !> last monodromy matrix Y(T): at the returned y0 itself for a nonlinear
  !> system (the converged iteration integrates it there and takes no step),
  !> and for a linear one, whose Y(T) does not depend on y0, the first
  !> iteration's (orbit_sensitivity can then skip its monodromy columns).
  subroutine shooting_solve(sys, s, y0, rep, err, monodromy)
    class(periodic_system_t), target, intent(inout) :: sys
    type(shooting_settings_t), intent(in) :: s
    real(dp), intent(inout) :: y0(:)
    type(shooting_report_t), intent(out) :: rep
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: monodromy(:, :)
    real(dp), allocatable :: yt(:), mono(:, :), jac(:, :), r(:), wr(:), wi(:), d(:), m(:, :), c(:, :), k(:, :), f(:)
    integer, allocatable :: ipiv(:)
    integer :: n, n2, it, j, i
    real(dp) :: res, sq, rc, jnorm
    logical :: have_mono, linear
    type(progress_t) :: bar
    n = sys%n
    n2 = 2*n
    allocate(yt(n2), mono(n2, n2), jac(n2, n2), r(n2), ipiv(n2), wr(n2), wi(n2), d(n2), m(n, n), c(n, n), &
             k(n, n), f(n))
    linear = .not. sys%is_nonlinear()
    ! energy scaling of the state, D = diag(sqrt(K_ii), sqrt(M_ii)) at t = 0:
    ! (Q, Q_d) differ in size by the natural frequencies, and Y(T) - I is only
    ! meaningfully conditioned in units where both carry energy
    call sys%set_time(0.0_dp, err)
    if (err%failed()) return
    call sys%linear_terms(m, c, k, f, .true.)
    do i = 1, n
      d(i) = sqrt(max(abs(k(i, i)), tiny(1.0_dp)))
      d(n + i) = sqrt(max(abs(m(i, i)), tiny(1.0_dp)))
    end do
    have_mono = .false.
    call bar%start('shooting Newton iterations', 0.0_dp, real(s%max_newton, dp), counts=.true.)
    do it = 0, s%max_newton
      call bar%update(real(it, dp), str(rep%revolutions)//' revolutions integrated')
      if (linear .and. have_mono) then
        call revolution(sys, s, y0, .false., yt, jac, rep, err)
      else
        call revolution(sys, s, y0, .true., yt, mono, rep, err)
        have_mono = .true.
      end if
      if (err%failed()) then
        call bar%finish()
        call err%add_context('shooting, Newton iteration '//str(it))
        return
      end if
      ! residual in energy units, relative to the state
      r = yt - y0
      sq = max(maxval(abs(d*y0)), maxval(abs(d*yt)), tiny(1.0_dp))
      res = maxval(abs(d*r))/sq
      rep%residual(it) = res
      rep%newton_iterations = it
      if (res <= s%newton_tol .and. it > 0) then
        rep%converged = .true.
        exit
      end if
      if (it == s%max_newton) exit
      ! Newton step: (Y(T) - I) dy = -(Phi(y0) - y0), in energy units D
      do j = 1, n2
        jac(:, j) = d*mono(:, j)/d(j)
        jac(j, j) = jac(j, j) - 1.0_dp
      end do
      ! in energy units |Y(T)| ~ 1: rcond |J| estimates the smallest singular
      ! value of J, i.e. how far the nearest multiplier is from 1
      jnorm = maxval(sum(abs(jac), dim=1))
      call lu_factor(jac, ipiv, err, rc)
      rc = rc*jnorm
      rep%rcond_newton = min(rep%rcond_newton, rc)
      if (err%failed() .or. rc < s%singular_rcond) then
        rep%near_resonance = .true.
        if (err%failed()) call err%clear()
        call err%set('shooting', 'the one-revolution map minus identity is nearly singular (smallest singular '// &
          'value about '//str(rc, 3)//' in energy units): a Floquet multiplier is at 1, a harmonic of the crank '// &
          'speed sits on a natural frequency; no isolated periodic solution')
        exit
      end if
      r = -d*r
      call lu_solve(jac, ipiv, r, err)
      y0 = y0 + r/d
    end do
    call bar%finish()
    ! Floquet multipliers of the (last) monodromy matrix
    call eigenvalues_general(mono, wr, wi, err)
    if (err%failed()) return
    rep%mult_re = wr
    rep%mult_im = wi
    rep%max_multiplier = maxval(sqrt(wr**2 + wi**2))
    rep%stable = rep%max_multiplier <= 1.0_dp + s%unit_circle_tol
    if (present(monodromy)) monodromy = mono
  end subroutine shooting_solve

  !> Q (and Q_d) along the periodic orbit from y0 at increasing times in [0, T].
  subroutine periodic_orbit(sys, s, y0, times, q, qd, rep, err)
    class(periodic_system_t), target, intent(inout) :: sys
    type(shooting_settings_t), intent(in) :: s
    real(dp), intent(in) :: y0(:), times(:)
    real(dp), intent(out) :: q(:, :), qd(:, :)
    type(shooting_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    type(flow_t), target :: flow
    type(lsode_t) :: ode
    type(lsode_counters_t) :: cnt
    real(dp) :: y(size(y0))
    integer :: j, n
    n = sys%n
    y = y0
    call flow%setup(sys, .false.)
    call ode%init(2*n, 0.0_dp, method_flag(s), s%rtol, [s%atol], err, max_steps=s%max_steps, ml=2*n - 1, mu=2*n - 1)
    if (err%failed()) return
    do j = 1, size(times)
      if (times(j) > ode%t) call ode%integrate_to(flow, y, times(j), err)
      if (err%failed()) return
      q(:, j) = y(1:n)
      qd(:, j) = y(n + 1:2*n)
    end do
    cnt = ode%counters()
    rep%steps = rep%steps + cnt%steps
    rep%rhs_evaluations = rep%rhs_evaluations + cnt%rhs_evals
  end subroutine periodic_orbit

  !> An exact periodic solution that must not be printed, as an error: Newton
  !> did not converge, or the orbit is unstable (parametric resonance).
  subroutine shooting_diagnosis(ss, rep, omega, allow_resonance, err)
    type(shooting_settings_t), intent(in) :: ss
    type(shooting_report_t), intent(in) :: rep
    real(dp), intent(in) :: omega
    logical, intent(in) :: allow_resonance
    type(error_t), intent(inout) :: err
    if (.not. rep%converged) then
      call err%set('exact periodic solution', 'Newton on the one-revolution map did not converge in '// &
                   str(ss%max_newton)//' iterations (residual '// &
                   str(rep%residual(rep%newton_iterations), 3)//') at crank speed '//str(omega, 6)//' rad/s')
    else if (.not. rep%stable .and. .not. allow_resonance) then
      call err%set('exact periodic solution', 'the periodic solution at crank speed '//str(omega, 6)// &
                   ' rad/s is UNSTABLE: a Floquet multiplier has modulus '//str(rep%max_multiplier, 8)// &
                   ' > 1 (parametric resonance); the steady state is not printed (allow_resonance = .true. '// &
                   'prints it anyway)')
    end if
  end subroutine shooting_diagnosis

  !> Right-hand side of [y, (Y), S_1 .. S_np]: the flow's own (state and
  !> monodromy columns), then each sensitivity column.
  subroutine sensitivity_rhs(self, t, y, ydot)
    class(sensitivity_flow_t), intent(inout) :: self
    real(dp), intent(in) :: t, y(:)
    real(dp), intent(out) :: ydot(:)
    type(nonlinear_info_t) :: info
    real(dp) :: fp(2*self%n), fm(2*self%n), col(self%n)
    integer :: n, n2, nm, j, o
    n = self%n
    n2 = 2*n
    nm = n2
    if (self%with_mono) nm = n2 + n2*n2
    ydot = 0.0_dp
    self%variational = self%with_mono
    call flow_rhs(self, t, y(1:nm), ydot(1:nm))
    if (self%err%failed()) return
    ! flow_rhs put the tangent into K only with the monodromy columns
    if (.not. self%with_mono) then
      if (self%sys%is_nonlinear()) then
        call self%sys%nonlinear_terms(y(1:n), self%fn, info, tangent=self%kt)
        self%k = self%k + self%kt
      end if
    end if
    do j = 1, size(self%plus)
      call self%plus(j)%rhs(t, y(1:n2), fp)
      call self%minus(j)%rhs(t, y(1:n2), fm)
      if (self%plus(j)%err%failed() .or. self%minus(j)%err%failed()) then
        call self%fail(t, 'sensitivity to parameter '//str(j)//': '//perturbed_failure(self%plus(j), self%minus(j)))
        return
      end if
      fp = (fp - fm)*self%inv_step(j)
      o = nm + (j - 1)*n2
      associate (sq => y(o + 1:o + n), sv => y(o + n + 1:o + n2))
        ydot(o + 1:o + n) = sv + fp(1:n)
        col = -(matmul(self%k, sq) + matmul(self%c, sv))
        call self%lu%solve(col)
        ydot(o + n + 1:o + n2) = col + fp(n + 1:n2)
      end associate
    end do
  end subroutine sensitivity_rhs

  function perturbed_failure(plus, minus) result(text)
    type(flow_t), intent(in) :: plus, minus
    character(len=:), allocatable :: text
    if (plus%err%failed()) then
      text = plus%err%text()
    else
      text = minus%err%text()
    end if
  end function perturbed_failure

  !> Sensitivities of the periodic orbit y0 = Phi_T(y0, p) to parameters p_j,
  !> from the variational equations (no differences of whole analyses):
  !> plus(j) and minus(j) are the system at p_j + h_j and p_j - h_j
  !> (step(j) = 2 h_j), which give f_p by a central difference of the
  !> right-hand side (RHS evaluations only).  One revolution of
  !> [y, Y, S] from (y0, I, 0) gives the monodromy Y(T) = Phi_y and
  !> S(T) = dPhi_T/dp; the orbit's start moves by
  !> dy0/dp = (I - Phi_y)^-1 dPhi_T/dp; a second pass of [y, S] from
  !> (y0, dy0/dp) gives q and dq/dp at the times (increasing, in [0, T]).
  !> y0 must be the periodic state (shooting_solve).  With monodromy (Y(T)
  !> at y0, from shooting_solve) the first pass integrates [y, S] only: the
  !> 2n monodromy columns are most of its unknowns.
  subroutine orbit_sensitivity(sys, plus, minus, step, s, y0, times, q, dq, rep, err, monodromy)
    class(periodic_system_t), target, intent(inout) :: sys
    class(periodic_system_t), target, intent(inout) :: plus(:), minus(:)
    real(dp), intent(in) :: step(:)
    type(shooting_settings_t), intent(in) :: s
    real(dp), intent(in) :: y0(:), times(:)
    real(dp), intent(out) :: q(:, :), dq(:, :, :)
    type(shooting_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    real(dp), intent(in), optional :: monodromy(:, :)
    type(sensitivity_flow_t), target :: flow
    real(dp), allocatable :: y(:), a(:, :), z(:, :)
    integer, allocatable :: ipiv(:)
    integer :: n, n2, np, j
    n = sys%n
    n2 = 2*n
    np = size(step)
    call flow%setup(sys, .true.)
    allocate(flow%plus(np), flow%minus(np))
    do j = 1, np
      call flow%plus(j)%setup(plus(j), .false.)
      call flow%minus(j)%setup(minus(j), .false.)
    end do
    flow%inv_step = 1.0_dp/step
    ! one revolution with the monodromy columns (unless given): Phi_y and dPhi_T/dp
    flow%with_mono = .not. present(monodromy)
    if (present(monodromy)) then
      allocate(y(n2*(1 + np)))
      y = 0.0_dp
      y(1:n2) = y0
      call sensitivity_pass(flow, s, y, [sys%period()], rep, err)
      if (err%failed()) return
      a = -monodromy
      z = reshape(y(n2 + 1:), [n2, np])
    else
      allocate(y(n2*(1 + n2 + np)))
      y = 0.0_dp
      y(1:n2) = y0
      do j = 1, n2
        y(n2 + (j - 1)*n2 + j) = 1.0_dp
      end do
      call sensitivity_pass(flow, s, y, [sys%period()], rep, err)
      if (err%failed()) return
      a = -reshape(y(n2 + 1:n2 + n2*n2), [n2, n2])
      z = reshape(y(n2 + n2*n2 + 1:), [n2, np])
    end if
    do j = 1, n2
      a(j, j) = a(j, j) + 1.0_dp
    end do
    allocate(ipiv(n2))
    call lu_factor(a, ipiv, err)
    if (.not. err%failed()) call lu_solve(a, ipiv, z, err)
    if (err%failed()) then
      call err%add_context('sensitivity of the periodic orbit: I - monodromy')
      return
    end if
    ! the orbit and its sensitivities from (y0, dy0/dp)
    flow%with_mono = .false.
    deallocate(y)
    allocate(y(n2*(1 + np)))
    y(1:n2) = y0
    y(n2 + 1:) = reshape(z, [n2*np])
    call sensitivity_pass(flow, s, y, times, rep, err, q, dq)
  end subroutine orbit_sensitivity

  !> Integrate the sensitivity flow from 0 through the times; with q and dq,
  !> record the displacements and their sensitivities there.
  subroutine sensitivity_pass(flow, s, y, times, rep, err, q, dq)
    type(sensitivity_flow_t), target, intent(inout) :: flow
    type(shooting_settings_t), intent(in) :: s
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: times(:)
    type(shooting_report_t), intent(inout) :: rep
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: q(:, :), dq(:, :, :)
    type(lsode_t) :: ode
    type(lsode_counters_t) :: cnt
    integer :: n, n2, nm, k, j
    n = flow%n
    n2 = 2*n
    nm = size(y) - n2*size(flow%plus)
    call ode%init(size(y), 0.0_dp, method_flag(s), s%rtol, [s%atol], err, max_steps=s%max_steps, ml=n2 - 1, &
                  mu=n2 - 1)
    if (err%failed()) return
    do k = 1, size(times)
      if (times(k) > ode%t) call ode%integrate_to(flow, y, times(k), err)
      if (err%failed()) exit
      if (present(q)) q(:, k) = y(1:n)
      if (present(dq)) then
        do j = 1, size(flow%plus)
          dq(:, k, j) = y(nm + (j - 1)*n2 + 1:nm + (j - 1)*n2 + n)
        end do
      end if
    end do
    cnt = ode%counters()
    rep%steps = rep%steps + cnt%steps
    rep%rhs_evaluations = rep%rhs_evaluations + cnt%rhs_evals
    rep%revolutions = rep%revolutions + 1
  end subroutine sensitivity_pass
end module periodic_shooting
