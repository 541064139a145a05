!> Clearance joints in a transient run (doc/clearance.md): reads &clearance,
!> gives the model its clearance joints, integrates step by step so that the
!> start of every contact is located and the integration restarted there, and
!> reports the journal's motion, the contact forces and the impact counts.
!>
!> Events.  DLSODE is driven one step at a time (ITASK = 5, never past the
!> output time).  After each step the penetration delta = |e| - c of every
!> journal that was free is examined; where it became positive, the onset is
!> bracketed on DLSODE's interpolant (DINTDY) by bisection to 1e-12 of the
!> step, the state is set to the interpolated state just inside the contact,
!> the contact's reference speed v_impact (the damping term's delta'(-)) is
!> the approach speed there, and DLSODE restarts from that point (its history
!> holds the free flight's smooth solution, not the contact's).  Approach
!> speeds below impact_speed are gentle contacts: no restart when the last
!> restart was fewer than 5 steps ago, so a journal rolling on the wall with
!> micro-separations cannot make the integrator restart at every step
!> (chattering).  Separations (delta < 0 after contact) need no restart: the
!> force goes to zero with zero slope.
module clearance_run
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use lsode_solver, only: lsode_t, mf_adams
  use linkage, only: mechanism_t, joint_pin, driver_angle
  use contact_law, only: contact_law_init, normal_force
  use joint_clearance, only: clearance_joint_t, contact_state
  use mechanism_model, only: mechanism_model_t
  use clearance_settings, only: clearance_settings_t, read_clearance_settings, echo_clearance_settings
  implicit none
  private
  public :: clearance_monitor_t

  integer, parameter :: mode_free = 0, mode_contact = 1, mode_impact = 2
  integer, parameter :: min_steps_between_gentle_restarts = 5

  type :: clearance_monitor_t
    logical :: active = .false.
    type(clearance_settings_t) :: s
    integer :: n = 0                                  !< clearance joints
    character(len=16), allocatable :: name(:)
    logical, allocatable :: in_contact(:), impact_since_row(:)
    integer, allocatable :: n_impacts(:), n_gentle(:), n_separations(:)
    real(dp), allocatable :: peak_force(:), peak_angle(:), peak_approach(:)
    integer :: n_restarts = 0
    integer :: n_steps = 0                            !< steps taken through the monitor
    integer :: last_restart = -1000000                !< step count at the last restart
  contains
    procedure :: read => monitor_read
    procedure :: echo => monitor_echo
    procedure :: joints
    procedure :: attach
    procedure :: integrate_to
    procedure :: column_names
    procedure :: row_values
    procedure :: report
  end type clearance_monitor_t

contains

  !> Read &clearance; active when some joint has c > 0.
  subroutine monitor_read(self, deck, mech, err)
    class(clearance_monitor_t), intent(inout) :: self
    type(deck_t), intent(inout) :: deck
    type(mechanism_t), intent(in) :: mech
    type(error_t), intent(inout) :: err
    call read_clearance_settings(deck, mech, self%s, err)
    if (err%failed()) return
    self%active = any(self%s%clearance > 0.0_dp)
  end subroutine monitor_read

  subroutine monitor_echo(self, out)
    class(clearance_monitor_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    call echo_clearance_settings(self%s, out)
  end subroutine monitor_echo

  !> The model's clearance joints (the journal: the end of the joint's
  !> second link, or of its only link at a ground pin); none when inactive.
  subroutine joints(self, mech, cj, err)
    class(clearance_monitor_t), intent(in) :: self
    type(mechanism_t), intent(in) :: mech
    type(clearance_joint_t), allocatable, intent(out) :: cj(:)
    type(error_t), intent(inout) :: err
    integer :: j, side
    allocate(cj(0))
    if (.not. self%active) return
    do j = 1, mech%n_joints
      if (.not. self%s%clearance(j) > 0.0_dp) cycle
      block
        type(clearance_joint_t) :: c
        c%joint = j
        c%name = mech%joints(j)%name
        c%clearance = self%s%clearance(j)
        c%journal_radius = self%s%journal_radius(j)
        c%v_impact = self%s%impact_speed
        call contact_law_init(c%law, self%s%law, self%s%stiffness(j), self%s%exponent, self%s%restitution(j), &
                              self%s%friction(j), self%s%friction_speed, err)
        if (err%failed()) return
        side = mech%joints(j)%n_links
        c%element_journal = end_element(mech, mech%joints(j)%link(side), mech%joints(j)%link_end(side))
        c%journal_node = mech%joints(j)%link_end(side)
        if (mech%joints(j)%kind == joint_pin) then
          c%element_bearing = end_element(mech, mech%joints(j)%link(1), mech%joints(j)%link_end(1))
          c%bearing_node = mech%joints(j)%link_end(1)
        end if
        cj = [cj, c]
      end block
    end do
  end subroutine joints

  !> Watch the model's clearance joints (the model was built with them,
  !> joints) and describe them.
  subroutine attach(self, model, mech, out)
    class(clearance_monitor_t), intent(inout) :: self
    type(mechanism_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    type(table_t), intent(inout) :: out
    integer :: k
    if (.not. self%active) return
    self%n = size(model%clearance)
    allocate(self%name(self%n), self%in_contact(self%n), self%impact_since_row(self%n), self%n_impacts(self%n), &
             self%n_gentle(self%n), self%n_separations(self%n), self%peak_force(self%n), self%peak_angle(self%n), &
             self%peak_approach(self%n))
    self%name = model%clearance%name
    self%in_contact = .false.
    self%impact_since_row = .false.
    self%n_impacts = 0
    self%n_gentle = 0
    self%n_separations = 0
    self%peak_force = 0.0_dp
    self%peak_angle = 0.0_dp
    self%peak_approach = 0.0_dp
    do k = 1, self%n
      associate (c => model%clearance(k))
        call out%comment('clearance at joint '//trim(c%name)//': c = '//str(c%clearance)//' in, law '// &
          trim(self%s%law)//', K = '//str(c%law%stiffness)//' lb/in^'//str(c%law%exponent)//', e = '// &
          str(c%law%restitution)//' (hysteresis factor chi = '//str(c%law%chi, 6)//'), friction mu = '// &
          str(c%law%friction)//'; journal = link '//trim(mech%links(mech%joints(c%joint)%link( &
          mech%joints(c%joint)%n_links))%name)//' end, its translations are unknowns '//str(c%journal(1))//', '// &
          str(c%journal(2)))
      end associate
    end do
    call out%comment('with clearance: '//str(model%n)//' global unknowns, half-bandwidth '//str(model%kd)// &
                     ' (the table and frequencies above are those of the pinned linkage)')
  end subroutine attach

  integer function end_element(mech, link, side) result(e)
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: link, side
    e = mech%links(link)%first_element
    if (side == 2) e = e + mech%links(link)%n_elements - 1
  end function end_element

  !> Advance to tout one DLSODE step at a time, locating and restarting at
  !> every contact onset (module header).
  subroutine integrate_to(self, ode, model, y, tout, err)
    class(clearance_monitor_t), intent(inout) :: self
    type(lsode_t), intent(inout) :: ode
    type(mechanism_model_t), intent(inout), target :: model
    real(dp), intent(inout), contiguous :: y(:)
    real(dp), intent(in) :: tout
    type(error_t), intent(inout) :: err
    integer :: steps_here
    real(dp) :: t_prev
    steps_here = 0
    do while (ode%t < tout)
      if (steps_here >= ode%max_steps) then
        call err%set('clearance joints', str(steps_here)//' steps in one output interval (max_steps) at t = '// &
                     str(ode%t)//stiff_hint(ode), code=4)
        return
      end if
      t_prev = ode%t
      call ode%integrate_to(model, y, tout, err, one_step=.true.)
      if (err%failed()) then
        if (ode%mf == mf_adams .and. ode%istate == -1) call err%add_context(trim(stiff_hint(ode)))
        return
      end if
      steps_here = steps_here + 1
      self%n_steps = self%n_steps + 1
      call after_step(self, ode, model, y, t_prev, err)
      if (err%failed()) return
    end do
  end subroutine integrate_to

  function stiff_hint(ode) result(s)
    type(lsode_t), intent(in) :: ode
    character(len=:), allocatable :: s
    s = ''
    if (ode%mf == mf_adams) s = '; the contact stiffness makes the equations stiff and Adams (functional iteration) '// &
      'crawls at the contact''s period: use method = ''bdf'''
  end function stiff_hint

  !> Events of the step just taken from t_prev to ode%t: separations, and the
  !> earliest contact onset (bracketed, restarted there); peak forces.
  subroutine after_step(self, ode, model, y, t_prev, err)
    type(clearance_monitor_t), intent(inout) :: self
    type(lsode_t), intent(inout) :: ode
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(inout) :: y(:)
    real(dp), intent(in) :: t_prev
    type(error_t), intent(inout) :: err
    integer :: k, first
    real(dp) :: delta, rate, t_on, t_hit, v
    real(dp) :: y_hit(size(y))
    first = 0
    t_hit = huge(1.0_dp)
    do k = 1, self%n
      if (self%in_contact(k)) cycle
      call penetration(model, k, y, delta, rate)
      if (delta > 0.0_dp) then
        t_on = onset_time(ode, model, k, t_prev, err)
        if (err%failed()) return
        if (t_on < t_hit) then
          t_hit = t_on
          first = k
        end if
      end if
    end do
    if (first > 0) then
      ! the earliest onset: state there, reference speed, restart (or not, when gentle)
      call ode%dense_output(t_hit, y_hit, err)
      if (err%failed()) return
      call penetration(model, first, y_hit, delta, rate)
      v = rate
      self%in_contact(first) = .true.
      self%peak_approach(first) = max(self%peak_approach(first), v)
      if (v >= self%s%impact_speed) then
        self%n_impacts(first) = self%n_impacts(first) + 1
        self%impact_since_row(first) = .true.
        model%clearance(first)%v_impact = v
      else
        self%n_gentle(first) = self%n_gentle(first) + 1
        model%clearance(first)%v_impact = self%s%impact_speed
      end if
      if (v >= self%s%impact_speed .or. self%n_steps - self%last_restart >= min_steps_between_gentle_restarts) then
        y = y_hit
        ode%t = t_hit
        call ode%restart()
        self%n_restarts = self%n_restarts + 1
        self%last_restart = self%n_steps
      end if
    end if
    ! separations, in the state the step ends with (or the restart's)
    do k = 1, self%n
      if (.not. self%in_contact(k) .or. k == first) cycle
      call penetration(model, k, y, delta, rate)
      if (.not. delta > 0.0_dp) then
        self%in_contact(k) = .false.
        self%n_separations(k) = self%n_separations(k) + 1
      end if
    end do
    call track_peaks(self, model, ode%t, y)
  end subroutine after_step

  !> Penetration |e| - c and its rate of clearance joint k in the state y.
  subroutine penetration(model, k, y, delta, rate)
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: k
    real(dp), intent(in) :: y(:)
    real(dp), intent(out) :: delta, rate
    real(dp) :: e(2), ed(2), n(2)
    call contact_state(model%clearance(k), y(1::2), y(2::2), e, ed, delta, rate, n)
  end subroutine penetration

  !> First time in (t_prev, ode%t] where joint k's penetration becomes
  !> positive on DLSODE's interpolant: bisection to 1e-12 of the step; the
  !> upper end (just inside the contact) is returned.
  real(dp) function onset_time(ode, model, k, t_prev, err) result(t_hi)
    type(lsode_t), intent(in) :: ode
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: k
    real(dp), intent(in) :: t_prev
    type(error_t), intent(inout) :: err
    real(dp) :: t_lo, t_mid, delta, rate, yy(ode%neq)
    integer :: it
    t_lo = t_prev
    t_hi = ode%t
    do it = 1, 60
      if (t_hi - t_lo <= 1.0e-12_dp*(ode%t - t_prev)) exit
      t_mid = 0.5_dp*(t_lo + t_hi)
      call ode%dense_output(t_mid, yy, err)
      if (err%failed()) return
      call penetration(model, k, yy, delta, rate)
      if (delta > 0.0_dp) then
        t_hi = t_mid
      else
        t_lo = t_mid
      end if
    end do
  end function onset_time

  !> Largest normal contact force of each joint over the accepted steps.
  subroutine track_peaks(self, model, t, y)
    type(clearance_monitor_t), intent(inout) :: self
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: t, y(:)
    integer :: k
    real(dp) :: fn, theta, theta_d, theta_dd
    do k = 1, self%n
      fn = contact_force(model, k, y)
      if (fn > self%peak_force(k)) then
        self%peak_force(k) = fn
        call driver_angle(model%kin%mech%driver, t, theta, theta_d, theta_dd)
        self%peak_angle(k) = theta*180.0_dp/pi
      end if
    end do
  end subroutine track_peaks

  real(dp) function contact_force(model, k, y) result(fn)
    type(mechanism_model_t), intent(in) :: model
    integer, intent(in) :: k
    real(dp), intent(in) :: y(:)
    real(dp) :: e(2), ed(2), n(2), delta, rate, d1, d2
    call contact_state(model%clearance(k), y(1::2), y(2::2), e, ed, delta, rate, n)
    call normal_force(model%clearance(k)%law, delta, rate, model%clearance(k)%v_impact, fn, d1, d2)
  end function contact_force

  !> Per clearance joint: journal position relative to the bearing (ex, ey,
  !> in), normal contact force (lb), mode (0 free, 1 contact, 2 an impact
  !> since the previous row).
  function column_names(self) result(names)
    class(clearance_monitor_t), intent(in) :: self
    character(len=32), allocatable :: names(:)
    integer :: k
    allocate(names(0))
    do k = 1, self%n
      names = [character(len=32) :: names, trim(self%name(k))//'_ex', trim(self%name(k))//'_ey', &
               trim(self%name(k))//'_Fn', trim(self%name(k))//'_mode']
    end do
  end function column_names

  function row_values(self, model, y) result(v)
    class(clearance_monitor_t), intent(inout) :: self
    type(mechanism_model_t), intent(in) :: model
    real(dp), intent(in) :: y(:)
    real(dp) :: v(4*self%n), e(2), ed(2), n(2), delta, rate
    integer :: k
    do k = 1, self%n
      call contact_state(model%clearance(k), y(1::2), y(2::2), e, ed, delta, rate, n)
      v(4*k - 3:4*k - 2) = e
      v(4*k - 1) = contact_force(model, k, y)
      v(4*k) = mode_free
      if (delta > 0.0_dp) v(4*k) = mode_contact
      if (self%impact_since_row(k)) v(4*k) = mode_impact
      self%impact_since_row(k) = .false.
    end do
  end function row_values

  !> Summary and cost lines.  The contact's frequency at the peak force,
  !> omega_c = sqrt(k_c/m) with k_c = n K^(1/n) F^((n-1)/n) the Hertz
  !> slope and m the journal's mass (the diagonal of M at its unknown), bounds
  !> Adams' step by stability (h omega_c ~ 1): with Adams the summary says so.
  subroutine report(self, out, revolutions, model, y, adams)
    class(clearance_monitor_t), intent(in) :: self
    type(table_t), intent(inout) :: out
    real(dp), intent(in) :: revolutions
    type(mechanism_model_t), intent(inout) :: model
    real(dp), intent(in) :: y(:)
    logical, intent(in) :: adams
    integer :: k
    character(len=:), allocatable :: per_rev
    real(dp) :: mass(model%n, model%n), stiff(model%n, model%n), kc, omega_c
    call model%assemble_dense(y(1::2), mass, stiff)
    do k = 1, self%n
      associate (law => model%clearance(k)%law, g => model%clearance(k)%journal(1))
        kc = law%exponent*law%stiffness**(1.0_dp/law%exponent)*self%peak_force(k)**(1.0_dp - 1.0_dp/law%exponent)
        omega_c = sqrt(kc/mass(g, g))
        call out%summary('joint '//trim(self%name(k))//' contact frequency at the peak force', str(omega_c, 6)// &
                         ' rad/s (Hertz slope '//str(kc, 6)//' lb/in, journal mass '//str(mass(g, g), 6)//')')
        if (adams .and. omega_c > 0.0_dp) call out%summary('warning', 'Adams (functional iteration) is stable only '// &
          'for steps below about 1/omega_c = '//str(1.0_dp/omega_c, 4)//' s at joint '//trim(self%name(k))// &
          ' while in contact: the contact makes the equations stiff; method = ''bdf'' is not bound by it')
      end associate
    end do
    do k = 1, self%n
      call out%summary('joint '//trim(self%name(k))//' peak contact force', str(self%peak_force(k), 8)// &
                       ' lb at crank angle '//str(self%peak_angle(k), 6)//' deg')
      per_rev = ''
      if (revolutions > 0.0_dp) per_rev = ' ('//str(self%n_separations(k)/revolutions, 6)//' per revolution)'
      call out%summary('joint '//trim(self%name(k))//' impacts', str(self%n_impacts(k))//' impacts, '// &
                       str(self%n_gentle(k))//' gentle contacts, '//str(self%n_separations(k))//' separations'// &
                       per_rev//'; largest approach speed '//str(self%peak_approach(k), 6)//' in/s')
    end do
    call out%cost('clearance_impacts', str(sum(self%n_impacts)))
    call out%cost('clearance_separations', str(sum(self%n_separations)))
    call out%cost('clearance_restarts', str(self%n_restarts))
    call out%cost('clearance_peak_contact_force', str(maxval(self%peak_force), 8))
  end subroutine report
end module clearance_run
