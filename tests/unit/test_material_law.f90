!> Tests of the Ramberg-Osgood law and its through-thickness integration
!> (module material_law).
module test_material_law_suite
  use kinds, only: dp
  use error_status, only: error_t
  use material_law
  use assertions
  implicit none
  private
  public :: run_all

  !> Tennant's example material, FORMULATION.md section 8.1 ("approximating aluminum").
  type(ramberg_osgood_t), parameter :: alu = ramberg_osgood_t(e1=10.87e6_dp, e2=0.8387e11_dp, m=3.0_dp, &
                                                              rho=0.0002536_dp)
  real(dp), parameter :: b = 0.25_dp, t = 1.0_dp, area = b*t    !< section of section 8.1

contains

  subroutine run_all()
    call run_test('peak_of_example_material_at_6p573e-3_and_47631_psi', test_peak)
    call run_test('softening_ratios_of_example_material', test_softening)
    call run_test('law_is_odd_and_energy_even_for_integer_and_real_m', test_symmetry)
    call run_test('energy_density_derivative_is_stress_and_stress_derivative_is_tangent', test_derivatives)
    call run_test('closed_form_section_equals_thickness_quadrature_odd_m', test_closed_form_vs_quadrature)
    call run_test('kear_k16_k17_printed_form_equals_polynomial_form', test_k16_k17)
    call run_test('non_odd_m_closed_form_equals_antiderivative_and_quadrature', test_non_odd_m)
    call run_test('section_resultants_are_derivatives_of_section_energy', test_section_derivatives)
    call run_test('linear_material_gives_EA_and_EI', test_linear_section)
    call run_test('invalid_constants_are_rejected_by_name', test_validation)
  end subroutine run_all

  !> Section 3.2 [derived]: eps* = sqrt(A/(3B)) = 6.573e-3 and sigma_max =
  !> 47,631 psi, quoted to 4 and 5 digits: tolerances half a unit of the last
  !> quoted digit.  d sigma/d eps changes sign there.
  subroutine test_peak()
    real(dp) :: es
    es = peak_strain(alu)
    call assert_close(es, 6.573e-3_dp, 0.5e-6_dp, 'eps* (4 digits)')
    call assert_rel_close(es, sqrt(alu%e1/(3.0_dp*alu%e2)), 1.0e-15_dp, 'eps* = sqrt(E1/(3 E2)) for m = 3')
    call assert_close(peak_stress(alu), 47631.0_dp, 0.5_dp, 'sigma_max (psi)')
    call assert_close(ro_tangent(alu, es)/alu%e1, 0.0_dp, 1.0e-14_dp, 'tangent vanishes at eps*')
    call assert_true(ro_tangent(alu, 0.99_dp*es) > 0.0_dp, 'rising below eps*')
    call assert_true(ro_tangent(alu, 1.01_dp*es) < 0.0_dp, 'falling beyond eps*')
    call assert_true(ro_stress(alu, 1.01_dp*es) < peak_stress(alu), 'stress below the peak past eps*')
    call assert_true(peak_strain(ramberg_osgood_t(e1=1.0_dp, e2=0.0_dp, m=3.0_dp)) > 1.0e300_dp, &
                     'no peak when E2 = 0')
    ! E1/(m E2) overflows for a subnormal E2 (fuzz seed 9): logarithms then;
    ! m = 3: eps* = sqrt(1e7/(3 E2)) = 5.8e157 for E2 = 1e-300, huge() for 4.9e-324
    call assert_rel_close(peak_strain(ramberg_osgood_t(e1=1.0e7_dp, e2=1.0e-300_dp, m=3.0_dp)), &
                          sqrt(1.0e7_dp/3.0_dp)*1.0e150_dp, 1.0e-13_dp, 'eps* for E2 = 1e-300 (ratio 3e306)')
    call assert_rel_close(peak_strain(ramberg_osgood_t(e1=1.0e7_dp, e2=1.0e-310_dp, m=3.0_dp)), &
                          sqrt(1.0e7_dp/3.0_dp)*1.0e155_dp, 1.0e-12_dp, 'eps* for E2 = 1e-310 (ratio overflows)')
    call assert_true(peak_strain(ramberg_osgood_t(e1=1.0e7_dp, e2=1.0e-310_dp, m=1.5_dp)) >= huge(1.0_dp), &
                     'no peak within reach when eps* itself overflows')
  end subroutine test_peak

  !> Section 3.2 [derived]: sigma/(A eps) = 0.9923 at 1e-3 and 0.807 at 5e-3.
  subroutine test_softening()
    call assert_close(ro_stress(alu, 1.0e-3_dp)/(alu%e1*1.0e-3_dp), 0.9923_dp, 0.5e-4_dp, 'ratio at 1e-3')
    call assert_close(ro_stress(alu, 5.0e-3_dp)/(alu%e1*5.0e-3_dp), 0.807_dp, 0.5e-3_dp, 'ratio at 5e-3')
  end subroutine test_softening

  !> (T6)/(T7) and (K12): sigma(-eps) = -sigma(eps), W(-eps) = W(eps), also
  !> for non-integer m where the |eps|^(m-1) form matters.
  subroutine test_symmetry()
    type(ramberg_osgood_t) :: mat
    real(dp) :: eps
    integer :: k, im
    real(dp), parameter :: ms(3) = [3.0_dp, 2.5_dp, 5.0_dp]
    do im = 1, 3
      mat = alu
      mat%m = ms(im)
      do k = 1, 9
        eps = real(k, dp)*1.0e-3_dp
        call assert_close(ro_stress(mat, -eps), -ro_stress(mat, eps), 1.0e-12_dp*abs(ro_stress(mat, eps)), 'odd')
        call assert_close(ro_energy_density(mat, -eps), ro_energy_density(mat, eps), &
                          1.0e-12_dp*abs(ro_energy_density(mat, eps)), 'even')
      end do
    end do
    ! the T6 branch for eps >= 0 by hand: A eps - B eps^m
    call assert_rel_close(ro_stress(alu, 4.0e-3_dp), alu%e1*4.0e-3_dp - alu%e2*(4.0e-3_dp)**3, 1.0e-15_dp, &
                          'T6 branch')
    call assert_rel_close(ro_stress(alu, -4.0e-3_dp), -alu%e1*4.0e-3_dp + alu%e2*(4.0e-3_dp)**3, 1.0e-15_dp, &
                          'T7 branch')
  end subroutine test_symmetry

  !> dW/deps = sigma and dsigma/deps = E_t by central differences (h = 1e-7,
  !> truncation ~ h^2 W''' ~ 1e-4 psi on sigma ~ 1e4 psi: 1e-7 relative).
  subroutine test_derivatives()
    real(dp), parameter :: h = 1.0e-7_dp
    type(ramberg_osgood_t) :: mat
    real(dp) :: eps
    integer :: k, im
    real(dp), parameter :: ms(2) = [3.0_dp, 2.5_dp]
    do im = 1, 2
      mat = alu
      mat%m = ms(im)
      do k = -4, 4
        eps = real(k, dp)*1.7e-3_dp + 0.3e-3_dp
        call assert_rel_close((ro_energy_density(mat, eps + h) - ro_energy_density(mat, eps - h))/(2.0_dp*h), &
                              ro_stress(mat, eps), 1.0e-7_dp, 'dW/deps = sigma')
        call assert_rel_close((ro_stress(mat, eps + h) - ro_stress(mat, eps - h))/(2.0_dp*h), &
                              ro_tangent(mat, eps), 1.0e-6_dp, 'dsigma/deps = E_t')
      end do
    end do
  end subroutine test_derivatives

  !> For odd m the pointwise law is a polynomial of degree m+1 in y, so an
  !> n-point Gauss rule through the depth with 2n-1 >= m+1 is exact: the
  !> closed form must agree to round-off (1e-12 relative, entries scaled by
  !> the largest term of each resultant), for m = 3, 5, 7, at kappa = 0, at
  !> eps_n = 0 and with both signs.
  subroutine test_closed_form_vs_quadrature()
    type(ramberg_osgood_t) :: mat
    type(section_resultants_t) :: cf, gq
    real(dp), parameter :: cases(2, 6) = reshape([ 2.0e-3_dp, 0.0_dp, 0.0_dp, 3.0e-3_dp, 1.0e-3_dp, 4.0e-3_dp, &
                                                  -1.5e-3_dp, 2.5e-3_dp, 3.0e-3_dp, -1.0e-3_dp, -2.0e-3_dp, -6.0e-3_dp], &
                                                 [2, 6])
    integer :: im, k
    real(dp) :: en, ka
    do im = 3, 7, 2
      mat = alu
      mat%m = real(im, dp)
      mat%e2 = alu%e2*(100.0_dp)**(im - 3)       ! keep the E2 term visible for higher m
      do k = 1, 6
        en = cases(1, k)
        ka = cases(2, k)/(0.5_dp*t)                ! second entry is the outer-fibre bending strain
        cf = section_response(mat, area, t, en, ka, .true.)
        gq = section_response_quadrature(mat, area, t, en, ka, .true., 8)
        call compare(cf, gq, 1.0e-12_dp, 'closed form vs 8-point depth rule, m = '//achar(48 + im))
      end do
    end do
  end subroutine test_closed_form_vs_quadrature

  !> (K16) and (K17) exactly as printed (with the 0/0 form, kappa /= 0)
  !> against the polynomial form used in the code; 1e-9 relative allows the
  !> cancellation in the printed difference of fifth powers.
  subroutine test_k16_k17()
    type(section_resultants_t) :: cf
    real(dp) :: en, ka, se, tk, dn, dm
    en = 1.2e-3_dp
    ka = -2.0e-3_dp
    cf = section_response(alu, area, t, en, ka, .true.)
    tk = t*ka
    se = area*(0.5_dp*alu%e1*(en**2 + tk**2/12.0_dp) &
               - alu%e2/(20.0_dp*tk)*((en + 0.5_dp*tk)**5 - (en - 0.5_dp*tk)**5))
    call assert_rel_close(cf%energy, se, 1.0e-9_dp, '(K16)')
    dn = area*(alu%e1*en - alu%e2*(en**3 + en*(0.5_dp*tk)**2))
    dm = area*(alu%e1*tk/6.0_dp - alu%e2*(en**2*(0.5_dp*tk) + (0.5_dp*tk)**3/5.0_dp))*(0.5_dp*t)
    call assert_rel_close(cf%axial_force, dn, 1.0e-13_dp, '(K17) axial factor')
    call assert_rel_close(cf%moment, dm, 1.0e-13_dp, '(K17) bending factor')
  end subroutine test_k16_k17

  !> m = 2.5: the depth integral of |eps|^(m+1) has the antiderivative
  !> z|z|^(m+1)/(m+2) (the (K16) form), exact for kappa /= 0.  The code's
  !> resultants must match it to 1e-13 relative with and without a
  !> zero-strain fibre inside the section, and also at small curvature where
  !> the code switches to Gauss (there the reference is a 64-point rule on
  !> the smooth integrand).  A 2000-point plain rule across the kink agrees
  !> to its own accuracy (~1e-7 for the |eps|^1.5 of the tangent).
  subroutine test_non_odd_m()
    type(ramberg_osgood_t) :: mat
    type(section_resultants_t) :: cf, gq
    real(dp) :: en, ka, s, p, ref, zp, zm
    integer :: k
    ! k = 1: zero-strain fibre inside; 2: one sign, closed form; 3: small curvature, Gauss
    real(dp), parameter :: ens(3) = [0.4e-3_dp, 3.0e-3_dp, 1.5e-3_dp], bends(3) = [2.0e-3_dp, 2.0e-3_dp, 0.2e-3_dp]
    mat = alu
    mat%m = 2.5_dp
    mat%e2 = 3.0e9_dp
    p = mat%m + 1.0_dp
    do k = 1, 3
      en = ens(k)
      ka = bends(k)/(0.5_dp*t)
      s = 0.5_dp*t*ka
      zp = en + s
      zm = en - s
      ref = area*(0.5_dp*mat%e1*(en**2 + s**2/3.0_dp) &
                  - mat%e2/p*0.5_dp/s*(zp*abs(zp)**p - zm*abs(zm)**p)/(p + 1.0_dp))
      cf = section_response(mat, area, t, en, ka, .true.)
      call assert_rel_close(cf%energy, ref, 1.0e-13_dp, 'closed form vs antiderivative')
      if (k == 3) then
        gq = section_response_quadrature(mat, area, t, en, ka, .true., 64)
        call compare(cf, gq, 1.0e-13_dp, 'small curvature vs 64-point rule')
      else
        gq = section_response_quadrature(mat, area, t, en, ka, .true., 2000)
        call compare(cf, gq, 1.0e-7_dp, 'vs 2000-point plain rule')
      end if
    end do
  end subroutine test_non_odd_m

  !> N = dE/deps_n, M = dE/dkappa and D = d(N, M)/d(eps_n, kappa) by central
  !> differences (steps 1e-8 of strain; truncation ~1e-10 relative).
  subroutine test_section_derivatives()
    type(ramberg_osgood_t) :: mat
    type(section_resultants_t) :: r0, rp, rm
    real(dp), parameter :: he = 1.0e-8_dp
    real(dp) :: en, ka, hk
    integer :: im
    real(dp), parameter :: ms(2) = [3.0_dp, 2.5_dp]
    en = 1.1e-3_dp
    ka = 3.0e-3_dp
    hk = he/(0.5_dp*t)
    do im = 1, 2
      mat = alu
      mat%m = ms(im)
      r0 = section_response(mat, area, t, en, ka, .true.)
      rp = section_response(mat, area, t, en + he, ka, .true.)
      rm = section_response(mat, area, t, en - he, ka, .true.)
      call assert_rel_close((rp%energy - rm%energy)/(2.0_dp*he), r0%axial_force, 1.0e-6_dp, 'N = dE/deps_n')
      call assert_rel_close((rp%axial_force - rm%axial_force)/(2.0_dp*he), r0%tangent(1, 1), 1.0e-6_dp, 'D11')
      call assert_rel_close((rp%moment - rm%moment)/(2.0_dp*he), r0%tangent(2, 1), 1.0e-5_dp, 'D21')
      rp = section_response(mat, area, t, en, ka + hk, .true.)
      rm = section_response(mat, area, t, en, ka - hk, .true.)
      call assert_rel_close((rp%energy - rm%energy)/(2.0_dp*hk), r0%moment, 1.0e-6_dp, 'M = dE/dkappa')
      call assert_rel_close((rp%moment - rm%moment)/(2.0_dp*hk), r0%tangent(2, 2), 1.0e-6_dp, 'D22')
      call assert_rel_close((rp%axial_force - rm%axial_force)/(2.0_dp*hk), r0%tangent(1, 2), 1.0e-5_dp, 'D12')
    end do
  end subroutine test_section_derivatives

  !> Material switch off (or E2 = 0): N = E A eps_n, M = E I kappa, energy
  !> (EA eps_n^2 + EI kappa^2)/2, I = b t^3/12.
  subroutine test_linear_section()
    type(section_resultants_t) :: r
    real(dp) :: en, ka, ei
    en = 2.0e-3_dp
    ka = -5.0e-3_dp
    ei = alu%e1*b*t**3/12.0_dp
    r = section_response(alu, area, t, en, ka, .false.)
    call assert_rel_close(r%axial_force, alu%e1*area*en, 1.0e-15_dp, 'N')
    call assert_rel_close(r%moment, ei*ka, 1.0e-15_dp, 'M')
    call assert_rel_close(r%energy, 0.5_dp*(alu%e1*area*en**2 + ei*ka**2), 1.0e-15_dp, 'energy')
    call assert_all_close(reshape(r%tangent, [4]), [alu%e1*area, 0.0_dp, 0.0_dp, ei], 1.0e-15_dp, 0.0_dp, 'D')
    ! kappa = 0, nonlinear: uniform fibre strain, N = A sigma(eps_n)
    r = section_response(alu, area, t, en, 0.0_dp, .true.)
    call assert_rel_close(r%axial_force, area*ro_stress(alu, en), 1.0e-15_dp, 'N = A sigma at kappa = 0')
    call assert_close(r%moment, 0.0_dp, 0.0_dp, 'M = 0 at kappa = 0')
  end subroutine test_linear_section

  subroutine test_validation()
    type(error_t) :: err
    call validate_material(alu, err)
    call assert_true(.not. err%failed(), 'example material accepted')
    call validate_material(ramberg_osgood_t(e1=-1.0_dp, e2=0.0_dp, m=3.0_dp), err)
    call assert_true(err%failed() .and. index(err%text(), 'E1') > 0, 'negative E1 named: '//err%text())
    call err%clear()
    call validate_material(ramberg_osgood_t(e1=1.0_dp, e2=1.0_dp, m=1.0_dp), err)
    call assert_true(err%failed() .and. index(err%text(), 'exponent m') > 0, 'm = 1 named: '//err%text())
    call err%clear()
    call validate_material(ramberg_osgood_t(e1=1.0_dp, e2=-1.0_dp, m=3.0_dp), err)
    call assert_true(err%failed() .and. index(err%text(), 'E2') > 0, 'negative E2 named: '//err%text())
    call assert_true(has_odd_integer_exponent(alu), 'm = 3 is odd')
    call assert_true(.not. has_odd_integer_exponent(ramberg_osgood_t(e1=1.0_dp, e2=1.0_dp, m=4.0_dp)), 'm = 4 not odd')
    call assert_true(.not. has_odd_integer_exponent(ramberg_osgood_t(e1=1.0_dp, e2=1.0_dp, m=2.9_dp)), &
                     'm = 2.9 not odd')
  end subroutine test_validation

  subroutine compare(x, y, rtol, msg)
    type(section_resultants_t), intent(in) :: x, y
    real(dp), intent(in) :: rtol
    character(len=*), intent(in) :: msg
    call assert_close(x%energy, y%energy, rtol*abs(y%energy), msg//': energy')
    call assert_close(x%axial_force, y%axial_force, rtol*(abs(y%axial_force) + abs(y%moment)/t), msg//': N')
    call assert_close(x%moment, y%moment, rtol*(abs(y%moment) + abs(y%axial_force)*t), msg//': M')
    call assert_all_close(reshape(x%tangent, [4]), reshape(y%tangent, [4]), 0.0_dp, &
                          rtol*maxval(abs(y%tangent)), msg//': D')
  end subroutine compare
end module test_material_law_suite

program test_material_law
  use test_material_law_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_material_law')
end program test_material_law
