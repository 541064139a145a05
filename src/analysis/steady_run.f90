!> The steady-state analysis of a deck (Tennant 1985), shared by the `steady`
!> driver (module steady_analysis) and the `design` driver, which analyses its
!> initial and final designs with it: the steady-state vibration of a
!> flexible linkage driven at constant crank speed, by the paper's
!> harmonic-series method (T26-T28) with the outer iteration on the nonlinear
!> stiffness, by the exact periodic solution (shooting, Floquet multipliers),
!> or both side by side.  Output rows over one crank revolution: elastic
!> displacements of the joints, local deformations of each link's end 2, the
!> maximum |stress| of every element, and with shape_points = k the local
!> displacements of k + 1 points per element of every link (drawn shapes).  Near resonance the analysis stops
!> with the diagnosis instead of printing a meaningless steady state.
module steady_run
  use kinds, only: dp, pi, two_pi
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t, invalid_value, input_error_in
  use table_output, only: table_t
  use mechanism_report, only: write_mechanism_header, joint_moves, joint_carrier, response_column_names, &
                              response_columns_text, link_point_name
  use linkage, only: mechanism_t, profile_constant
  use linkage_deck, only: read_mechanism, check_section_rules, echo_mechanism
  use tennant_element, only: tennant_stress_t
  use steady_model, only: steady_model_t
  use plausibility, only: warn_materials, warn_strength
  use steady_settings, only: steady_settings_t, read_steady_settings, echo_steady_settings
  use run_settings, only: read_run_settings, write_run_header
  use harmonic_solver, only: harmonic_report_t, harmonic_solve, harmonic_diagnosis
  use periodic_shooting, only: shooting_report_t, shooting_solve, periodic_orbit, shooting_diagnosis
  implicit none
  private
  public :: analyse_steady, analyse_steady_deck

  integer, parameter :: n_freq_reported = 5

contains

  !> Read, build, the harmonic series and/or the exact periodic solution over
  !> one revolution, then the table of both.
  subroutine analyse_steady(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    type(mechanism_t) :: mech
    type(steady_settings_t) :: s
    type(steady_model_t), target :: model
    real(dp), allocatable :: times(:), qh(:, :), qs(:, :)
    integer :: n_out, k

    call read_mechanism(deck, mech, err)
    if (err%failed()) return
    call read_steady_settings(deck, mech%n_links, s, err)
    if (err%failed()) return         ! (a NaN d_k compared in check_steady_input traps: fuzz seed 12, case 20018)
    call check_steady_input(deck, mech, s, err)
    if (err%failed()) return
    call echo_mechanism(mech, out)
    call echo_steady_settings(out)
    call warn_materials(out, mech)

    call model%init_mechanism(mech, s%element, s%sections, err)
    if (err%failed()) then
      call input_error_in(deck, 'mechanism/&tennant', err)
      return
    end if
    call write_model_header(out, mech, s, model)
    call frequency_scan(out, model, s, err)
    if (err%failed()) return

    ! output grid: one revolution, both ends included
    n_out = max(1, nint(360.0_dp/s%output_step_deg))
    allocate(times(n_out + 1))
    do k = 0, n_out
      times(k + 1) = real(k, dp)*(two_pi/n_out)/model%omega
    end do

    if (s%method /= 'shooting') then
      call solve_harmonic(out, model, s, times, qh, err)
      if (err%failed()) return
    end if
    if (s%method /= 'harmonic') then
      call solve_shooting(out, model, s, times, qh, qs, err)
      if (err%failed()) return
    end if
    call write_table(out, mech, model, times, qh, qs, s%shape_points, err)
    if (err%failed()) return
    call out%cost('kinematics_solutions', str(model%n_kinematics))
  end subroutine analyse_steady

  !> The steady analysis of the deck file deck_path into the output file
  !> out_path: its &run title and header, the analysis, a 'stopped:' line if
  !> it stopped.  why: '' when the output was written, else why the deck or the
  !> output file could not be opened.
  subroutine analyse_steady_deck(deck_path, out_path, why)
    character(len=*), intent(in) :: deck_path, out_path
    character(len=:), allocatable, intent(out) :: why
    type(deck_t) :: deck
    type(table_t) :: out
    type(error_t) :: err
    character(len=32) :: analysis
    character(len=256) :: title
    why = ''
    call deck%open(deck_path, err)
    if (.not. err%failed()) call out%open(out_path, err)
    if (err%failed()) then
      why = err%text()
      return
    end if
    call read_run_settings(deck, analysis, title, err)
    call write_run_header(out, deck_path, title)
    if (.not. err%failed()) call analyse_steady(deck, out, err)
    call deck%close()
    if (err%failed()) call out%comment('stopped: '//err%text())
    call out%commit(err)
  end subroutine analyse_steady_deck

  !> Tennant's harmonic series (T26-T28) at the output times, qh(:, k) at
  !> times(k), with its report, cost and diagnosis.
  subroutine solve_harmonic(out, model, s, times, qh, err)
    type(table_t), intent(inout) :: out
    type(steady_model_t), target, intent(inout) :: model
    type(steady_settings_t), intent(in) :: s
    real(dp), intent(in) :: times(:)
    real(dp), allocatable, intent(out) :: qh(:, :)
    type(error_t), intent(inout) :: err
    type(harmonic_report_t) :: hrep
    real(dp) :: cpu0, cpu1
    allocate(qh(model%n, size(times)))
    call cpu_time(cpu0)
    call harmonic_solve(model, s%harmonic, times, qh, hrep, err)
    call cpu_time(cpu1)
    call report_harmonic(out, s, hrep, model%omega)
    call harmonic_cost(out, model, s, hrep, cpu1 - cpu0)
    if (err%failed()) then
      call err%add_context('harmonic series')
      return
    end if
    call harmonic_diagnosis(s%harmonic, hrep, model%omega, s%allow_resonance, s%allow_beyond_peak, err)
    if (err%failed()) return
    if (hrep%beyond_peak) call out%comment('WARNING: a strain passes the peak of the Ramberg-Osgood law ('// &
      str(hrep%max_abs_strain, 5)//' in element '//str(hrep%strain_element)//'); printed because '// &
      'allow_beyond_peak = .true.: the material law has no stable meaning there')
  end subroutine solve_harmonic

  !> The exact periodic solution by shooting (started from the harmonic
  !> series' state at t = 0 where there is one) at the output times, with its
  !> Floquet report, cost and diagnosis.
  subroutine solve_shooting(out, model, s, times, qh, qs, err)
    type(table_t), intent(inout) :: out
    type(steady_model_t), target, intent(inout) :: model
    type(steady_settings_t), intent(in) :: s
    real(dp), intent(in) :: times(:)
    real(dp), allocatable, intent(in) :: qh(:, :)
    real(dp), allocatable, intent(out) :: qs(:, :)
    type(error_t), intent(inout) :: err
    type(shooting_report_t) :: srep
    real(dp), allocatable :: qsd(:, :), y0(:)
    real(dp) :: cpu0, cpu1
    allocate(qs(model%n, size(times)), qsd(model%n, size(times)), y0(2*model%n))
    y0 = 0.0_dp
    if (allocated(qh)) y0(1:model%n) = qh(:, 1)
    call cpu_time(cpu0)
    call shooting_solve(model, s%shooting, y0, srep, err)
    if (.not. err%failed() .and. (srep%converged .and. (srep%stable .or. s%allow_resonance))) &
      call periodic_orbit(model, s%shooting, y0, times, qs, qsd, srep, err)
    call cpu_time(cpu1)
    call report_shooting(out, s, srep, model%omega)
    call out%cost('shooting_revolutions_integrated', str(srep%revolutions))
    call out%cost('shooting_steps', str(srep%steps))
    call out%cost('shooting_rhs_evaluations', str(srep%rhs_evaluations))
    call out%cost('cpu_seconds_shooting', str(cpu1 - cpu0, 4))
    if (err%failed()) then
      call err%add_context('exact periodic solution (shooting) at crank speed '//str(model%omega, 6)//' rad/s')
      return
    end if
    call shooting_diagnosis(s%shooting, srep, model%omega, s%allow_resonance, err)
  end subroutine solve_shooting

  !> The rows over the revolution of the solutions there are (qh: harmonic
  !> series, qs: exact periodic), each element's peak stress in each and
  !> how far apart the two are (shape_points: intervals per element of the
  !> links' shape columns, 0: none).
  subroutine write_table(out, mech, model, times, qh, qs, shape_points, err)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(steady_model_t), target, intent(inout) :: model
    real(dp), intent(in) :: times(:)
    real(dp), allocatable, intent(in) :: qh(:, :), qs(:, :)
    integer, intent(in) :: shape_points
    type(error_t), intent(inout) :: err
    character(len=32), allocatable :: names(:)
    real(dp), allocatable :: row(:)
    real(dp) :: peak(size(model%el), 2), peak_at(size(model%el), 2)
    integer :: k
    logical :: do_h, do_s
    do_h = allocated(qh)
    do_s = allocated(qs)
    call column_names(out, mech, model, do_h, do_s, shape_points, names)
    allocate(row(size(names)))
    peak = 0.0_dp
    peak_at = 0.0_dp
    do k = 1, size(times)
      call model%set_time(times(k), err)
      if (err%failed()) return
      row(1) = times(k)*model%omega*180.0_dp/pi + mech%driver%theta0*180.0_dp/pi
      row(2) = times(k)
      if (do_h) call fill_solution(mech, model, qh(:, k), shape_points, row, 2, peak(:, 1), peak_at(:, 1))
      if (do_s) call fill_solution(mech, model, qs(:, k), shape_points, row, merge(2 + (size(row) - 2)/2, 2, do_h), &
                                   peak(:, 2), peak_at(:, 2))
      call out%row(row)
    end do
    do k = 1, size(model%el)
      if (do_h) call out%summary('element '//str(k)//' peak |stress| (harmonic series)', str(peak(k, 1), 8)// &
                                 ' psi at crank angle '//str(peak_at(k, 1), 6)//' deg')
      if (do_s) call out%summary('element '//str(k)//' peak |stress| (exact periodic)', str(peak(k, 2), 8)// &
                                 ' psi at crank angle '//str(peak_at(k, 2), 6)//' deg')
    end do
    call warn_strength(out, mech, max(peak(:, 1), peak(:, 2)))
    if (do_h .and. do_s) then
      call out%summary('harmonic series vs exact periodic', 'max |Q_h - Q_exact| / max |Q_exact| = '// &
                       str(maxval(abs(qh - qs))/max(maxval(abs(qs)), tiny(1.0_dp)), 4))
    end if
  end subroutine write_table

  !> One solution's columns of a row, from row(c + 1) on: joints, link ends,
  !> element stresses (their peaks noted at the row's crank angle row(1)),
  !> the links' shape points.
  subroutine fill_solution(mech, model, q, shape_points, row, c, peak, peak_at)
    type(mechanism_t), intent(in) :: mech
    type(steady_model_t), intent(in) :: model
    real(dp), intent(in) :: q(:)
    integer, intent(in) :: shape_points
    real(dp), intent(inout) :: row(:)
    integer, intent(in) :: c
    real(dp), intent(inout) :: peak(:), peak_at(:)
    type(tennant_stress_t) :: st(size(model%el))
    real(dp) :: uwa(3)
    integer :: j, i, e, k, ne, p
    k = c
    do j = 1, mech%n_joints
      if (.not. joint_moves(mech, j)) cycle
      row(k + 1:k + 2) = joint_displacement(model, mech, j, q)
      k = k + 2
    end do
    do i = 1, mech%n_links
      e = mech%links(i)%first_element + mech%links(i)%n_elements - 1
      uwa = model%local_field(e, q, 1.0_dp)
      row(k + 1:k + 2) = uwa(1:2)
      k = k + 2
    end do
    call model%stresses(q, st)
    do e = 1, size(st)
      row(k + e) = st(e)%max_abs_stress
      if (st(e)%max_abs_stress > peak(e)) then
        peak(e) = st(e)%max_abs_stress
        peak_at(e) = row(1)
      end if
    end do
    k = k + size(st)
    do i = 1, merge(mech%n_links, 0, shape_points > 0)   ! the point at s = p/(shape_points ne) of the link
      ne = mech%links(i)%n_elements
      do p = 0, shape_points*ne
        e = min(ne - 1, max(0, (p - 1)/shape_points))   ! (an interior element end: the element before)
        uwa = model%local_field(mech%links(i)%first_element + e, q, real(p - e*shape_points, dp)/shape_points)
        row(k + 1:k + 2) = uwa(1:2)
        k = k + 2
      end do
    end do
  end subroutine fill_solution

  !> What the steady-state analysis needs of the mechanism and of &tennant:
  !> rectangular links where the material, shear or tapered sections need
  !> them, and a crank turning at a constant speed > 0.
  subroutine check_steady_input(deck, mech, s, err)
    type(deck_t), intent(in) :: deck
    type(mechanism_t), intent(in) :: mech
    type(steady_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    integer :: k
    call check_section_rules(deck, mech, s%element%d_k > 0.0_dp, s%element%shear, err)
    if (err%failed()) return
    do k = 1, mech%n_links
      if (s%sections(k)%n > 0 .and. mech%links(k)%section /= 'rectangle') then
        call invalid_value(deck, 'tennant', 'n_sections('//str(k)//')', str(s%sections(k)%n), 'tapered sections '// &
                           'are rectangles b x h; link '//str(k)//' has a '//trim(mech%links(k)%section)//' section', err)
        return
      end if
    end do
    if (.not. mech%driver%omega > 0.0_dp) then
      call invalid_value(deck, 'mechanism', 'omega', str(mech%driver%omega), &
                         'a steady-state analysis needs a crank turning at constant speed > 0', err)
    else if (mech%driver%profile /= profile_constant) then
      call invalid_value(deck, 'mechanism', 'profile', '''spinup''', &
                         'a steady-state analysis needs the constant crank speed profile', err)
    end if
  end subroutine check_steady_input

  ! ------------------------------------------------------------------ header

  subroutine write_model_header(out, mech, s, model)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(steady_settings_t), intent(in) :: s
    type(steady_model_t), intent(in) :: model
    call write_mechanism_header(out, mech, model%table)
    associate (o => s%element)
      if (o%shear .and. o%shear_modulus <= 0.0_dp) then
        call out%comment('element: Tennant (T17-T19), 14 DOFs with shear angle alpha; shear modulus G = '// &
                         str(model%el(1)%shear_modulus, 6)//' (default E1/(2(1 + nu)), nu = '//str(o%poisson, 3)// &
                         '), shear factor '//str(o%shear_factor, 4))
      else if (o%shear) then
        call out%comment('element: Tennant (T17-T19), 14 DOFs with shear angle alpha; shear modulus G = '// &
                         str(model%el(1)%shear_modulus, 6)//', shear factor '//str(o%shear_factor, 4))
      else
        call out%comment('element: Tennant (T17, T18, T29, T30), 8 DOFs, slender (no shear angle)')
      end if
      call out%comment('tracing constants: D_k = '//str(o%d_k, 3)//' (material), D_b = '//str(o%d_b, 3)// &
                       ' (curvature), D_g = '//str(o%d_g, 3)//' (stretching)')
      if (.not. (o%d_k > 0.0_dp .or. o%d_b > 0.0_dp .or. o%d_g > 0.0_dp)) &
        call out%comment('(all tracing constants zero: the linear analysis; no nonlinear term is computed)')
      call out%comment('kinetic energy: rotatory inertia '//str(o%rotary_inertia)//', shear-angle inertia (T4) '// &
                       str(o%shear .and. o%shear_inertia)//'; damping beta = '//str(o%damping_beta)//' s')
    end associate
    if (s%method /= 'shooting') then
      call out%comment('harmonic series (T26-T28): N = '//str(s%harmonic%n_harmonics)//' harmonics from '// &
                       str(2*s%harmonic%n_harmonics)//' samples per revolution, '// &
                       str(merge(s%harmonic%n_harmonics, s%harmonic%n_kept, s%harmonic%n_kept == 0))// &
                       ' kept; K(t), M(t) frozen at each output time; C Q_dot '// &
                       merge('kept     ', 'neglected', s%harmonic%velocity_terms)//' (T)')
    end if
  end subroutine write_model_header

  !> Natural frequencies of the structure frozen at the 2N sample times: their
  !> range over the revolution, and the harmonics of the crank speed inside it.
  subroutine frequency_scan(out, model, s, err)
    type(table_t), intent(inout) :: out
    type(steady_model_t), intent(inout) :: model
    type(steady_settings_t), intent(in) :: s
    type(error_t), intent(inout) :: err
    real(dp) :: wn(model%n), wmin(n_freq_reported), wmax(n_freq_reported), w
    integer :: k, ns, i, nf, h
    character(len=:), allocatable :: line
    nf = min(n_freq_reported, model%n)
    ns = max(2*s%harmonic%n_harmonics, 24)
    wmin = huge(1.0_dp)
    wmax = 0.0_dp
    do k = 0, ns - 1
      call model%set_time(k*model%period()/ns, err)
      if (err%failed()) return
      call model%frozen_frequencies(wn, err)
      if (err%failed()) return
      wmin(1:nf) = min(wmin(1:nf), wn(1:nf))
      wmax(1:nf) = max(wmax(1:nf), wn(1:nf))
    end do
    call model%set_time(0.0_dp, err)
    line = 'natural frequencies of the frozen structure over the revolution (rad/s, min-max):'
    do i = 1, nf
      line = line//' '//str(wmin(i), 5)//'-'//str(wmax(i), 5)
    end do
    call out%comment(line)
    w = model%omega
    call out%comment('crank speed '//str(w, 6)//' rad/s = '//str(w/wmin(1), 4)//' of the lowest natural frequency')
    do h = 1, s%harmonic%n_harmonics
      do i = 1, nf
        if (h*w >= 0.95_dp*wmin(i) .and. h*w <= 1.05_dp*wmax(i)) then
          call out%comment('warning: harmonic '//str(h)//' of the crank speed ('//str(h*w, 6)//' rad/s) meets '// &
                           'natural frequency '//str(i)//' of the frozen structure during the revolution')
        end if
      end do
    end do
  end subroutine frequency_scan

  ! ------------------------------------------------------------------ reports

  subroutine report_harmonic(out, s, rep, omega)
    type(table_t), intent(inout) :: out
    type(steady_settings_t), intent(in) :: s
    type(harmonic_report_t), intent(in) :: rep
    real(dp), intent(in) :: omega
    integer :: i
    if (s%harmonic%velocity_terms) then
      do i = 1, rep%velocity_iterations
        call out%summary('C Q_dot iteration '//str(i)//' on the samples', 'max relative change of Q = '// &
                         str(rep%velocity_change(i), 3))
      end do
    end if
    call out%summary('outer iterations (K_n updates after the linear solution)', str(rep%outer_iterations)// &
                     merge(' (converged)    ', ' (NOT converged)', rep%converged))
    do i = 1, rep%outer_iterations
      call out%summary('outer iteration '//str(i), 'max relative change of Q = '//str(rep%change(i), 3))
    end do
    call out%summary('worst conditioning of K - n^2 w^2 M', 'rcond/rcond(K) = '//str(rep%worst_ratio, 3)// &
                     ' for harmonic n = '//str(rep%worst_harmonic)//' ('//str(rep%worst_harmonic*omega, 6)// &
                     ' rad/s) at crank angle '//str(modulo(rep%worst_time*omega*180.0_dp/pi, 360.0_dp), 5)// &
                     ' deg; smallest rcond '//str(rep%min_rcond, 3))
    if (rep%max_abs_strain > 0.0_dp) call out%summary('largest strain (harmonic series)', &
      str(rep%max_abs_strain, 5)//' in element '//str(rep%strain_element)//' at crank angle '// &
      str(modulo(rep%strain_time*omega*180.0_dp/pi, 360.0_dp), 5)//' deg')
  end subroutine report_harmonic

  subroutine harmonic_cost(out, model, s, rep, cpu)
    type(table_t), intent(inout) :: out
    type(steady_model_t), intent(in) :: model
    type(steady_settings_t), intent(in) :: s
    type(harmonic_report_t), intent(in) :: rep
    real(dp), intent(in) :: cpu
    call out%cost('harmonics_used', str(rep%n_kept)//' of N = '//str(s%harmonic%n_harmonics)//' ('// &
                  str(rep%n_samples)//' samples per revolution)')
    call out%cost('outer_iterations', str(rep%outer_iterations))
    call out%cost('factorizations', str(rep%factorizations))
    call out%cost('linear_assemblies', str(model%n_linear_evaluations))
    call out%cost('nonlinear_assemblies', str(model%n_nonlinear_evaluations))
    call out%cost('nonlinear_integrand_evaluations', str(model%n_nonlinear_points))
    call out%cost('cpu_seconds_harmonic', str(cpu, 4))
  end subroutine harmonic_cost

  subroutine report_shooting(out, s, rep, omega)
    type(table_t), intent(inout) :: out
    type(steady_settings_t), intent(in) :: s
    type(shooting_report_t), intent(in) :: rep
    real(dp), intent(in) :: omega
    integer :: i, n, j
    real(dp), allocatable :: modulus(:)
    character(len=:), allocatable :: line
    call out%summary('shooting Newton iterations', str(rep%newton_iterations)// &
                     merge(' (converged)    ', ' (NOT converged)', rep%converged))
    do i = 0, rep%newton_iterations
      call out%summary('shooting iteration '//str(i), '|Phi(y0) - y0| / |y| = '//str(rep%residual(i), 3))
    end do
    call out%summary('rcond of the Newton matrix Y(T) - I (energy units)', str(rep%rcond_newton, 3))
    if (allocated(rep%mult_re)) then
      n = size(rep%mult_re)
      allocate(modulus(n))
      modulus = sqrt(rep%mult_re**2 + rep%mult_im**2)
      line = ''
      do i = 1, min(6, n)
        j = maxloc(modulus, dim=1)
        line = line//' '//str(modulus(j), 6)
        modulus(j) = -1.0_dp
      end do
      call out%summary('Floquet multipliers, largest moduli', trim(line))
      call out%summary('steady state', merge('stable  ', 'UNSTABLE', rep%stable)//' (largest |multiplier| '// &
                       str(rep%max_multiplier, 8)//', tolerance 1 + '//str(s%shooting%unit_circle_tol, 3)// &
                       ') at crank speed '//str(omega, 6)//' rad/s')
    end if
  end subroutine report_shooting



  ! ------------------------------------------------------------------ columns

  !> Global elastic (U, W) of joint j (mechanism_report%joint_carrier says where).
  function joint_displacement(model, mech, j, q) result(uw)
    type(steady_model_t), intent(in) :: model
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: j
    real(dp), intent(in) :: q(:)
    real(dp) :: uw(2)
    integer :: e, node, first
    real(dp), allocatable :: qe(:)
    uw = 0.0_dp
    call joint_carrier(mech, j, e, node)
    if (e == 0) return
    qe = model%element_q(e, q)
    first = 1
    if (node == 2) first = model%el(e)%nn + 1
    uw = qe(first:first + 1)
  end function joint_displacement

  subroutine column_names(out, mech, model, do_h, do_s, shape_points, names)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(steady_model_t), intent(in) :: model
    logical, intent(in) :: do_h, do_s
    integer, intent(in) :: shape_points
    character(len=32), allocatable, intent(out) :: names(:)
    names = [character(len=32) :: 'crank_deg', 't']
    if (do_h) names = [character(len=32) :: names, response_column_names(mech, size(model%el), ''), shape_names('')]
    if (do_s) names = [character(len=32) :: names, response_column_names(mech, size(model%el), &
                                                                          trim(merge('_exact', '      ', do_h))), &
                       shape_names(trim(merge('_exact', '      ', do_h)))]
    call out%comment('columns: crank_deg = crank angle (deg); t (s) from crank angle theta0; '// &
                     response_columns_text//'; T''s U~1 is B_U, U~2 is C_U for the four-bar; '// &
                     'suffix _exact: the exact periodic solution (shooting)')
    if (shape_points > 0) call out%comment('shape columns: <link>_s<x>_u, _w = axial and transverse elastic '// &
      'displacement of the link''s point at x times its length from its end 1, in the link''s rigid-body axes (in), '// &
      'by the element''s own shape functions; '//str(shape_points)//' intervals per element (shape_points)')
    call out%columns(names)
  contains
    function shape_names(suffix) result(list)
      character(len=*), intent(in) :: suffix
      character(len=32), allocatable :: list(:)
      integer :: i, p, n
      character(len=:), allocatable :: point
      allocate(list(0))
      do i = 1, merge(mech%n_links, 0, shape_points > 0)
        n = shape_points*mech%links(i)%n_elements
        do p = 0, n
          point = link_point_name(mech%links(i)%name, real(p, dp)/n)
          list = [character(len=32) :: list, point//'_u'//suffix, point//'_w'//suffix]
        end do
      end do
    end function shape_names
  end subroutine column_names
end module steady_run
