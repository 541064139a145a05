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
  use lsode_solver, only: lsode_t, lsode_counters_t, mf_bdf_full_user, mf_bdf_band_user, mf_bdf_band_fd, &
                          mf_bdf_full_fd
  use transient_settings, only: transient_settings_t
  implicit none
  private
  public :: start_integrator, write_start_frequencies, write_integration_cost

  integer, parameter :: n_modes_reported = 5

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
      ode%max_order = s%max_order           ! DLSODE's MAXORD (optional input, IOPT = 1)
      ode%iwork(5) = s%max_order
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
