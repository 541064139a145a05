!> A link sliding through a sleeve (joint 'slider_link') in the transient
!> model: its active length Delta(t) between the pinned end and the sleeve
!> varies with time (T24), so the link is one Tennant element with the
!> moving integration limit (module tennant_element, doc/steady_state.md
!> §2.4) -- the same element and the same sleeve map as the steady model's,
!> so that the two models agree term for term on that link.
!>
!> The element's end 2 is in the sleeve; its DOFs follow from the global
!> unknowns through the angle-dependent map of the correlation table,
!> q_e = C(phi) Q (correlation_table%element_map), assembled by virtual work:
!>     M += C^T M_e C,
!>     F += C^T [F_e - C_e q_e_d - K_e q_e - f_n(q_e) - M_e (2 C_d Q_d + C_dd Q)]
!> with q_e_d = C Q_d + C_d Q.  Delta and its rates come from the rigid
!> states: the sleeve point P (the carrier's pin, or a ground pivot) lies on
!> the link's line through its pinned end R1 in direction u(phi), so
!>     Delta = (P - R1).u,  Delta_d = (P_d - R1_d).u,
!>     Delta_dd = (P_dd - R1_dd).u + phi_d (P_d - R1_d).n
!> (the terms in (P - R1).n vanish), which also holds for the tabulated motion.
module sliding_link
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use linkage, only: mechanism_t, joint_slider_link
  use correlation_table, only: correlation_table_t, link_end_t, end_pin => joint_pin, end_sleeve => joint_sleeve
  use element_effects, only: element_effects_t
  use planar_element, only: rigid_state_t, stress_report_t
  use material_law, only: ramberg_osgood_t
  use tennant_element, only: tennant_element_t, tennant_options_t, tennant_section_t, frame_state_t, tennant_info_t, &
                             tennant_stress_t, tennant_element_init, tennant_linear_terms, tennant_nonlinear_terms, &
                             tennant_stress_recovery, tennant_kinetic_energy, tennant_strain_energy
  implicit none
  private
  public :: sliding_link_t, mechanism_link_ends, sliding_link_init, sliding_link_set_state, sliding_link_add, &
            sliding_link_matrices, sliding_link_element_q, sliding_link_stress, sliding_link_energies

  integer, parameter :: nd = 8            !< Kear's and Tennant's slender element DOFs
  integer, parameter :: mx = nd + 2       !< globals of a sleeve element: its own and the sleeve's U_s, W_s

  type :: sliding_link_t
    integer :: element = 0                !< the link's one element
    integer :: carrier_element = 0        !< element whose node carries the sleeve (0: sleeve on the ground)
    integer :: carrier_node = 0
    real(dp) :: carrier_length = 0.0_dp
    real(dp) :: ground_point(2) = 0.0_dp  !< a ground sleeve's pivot
    type(tennant_element_t) :: el
    type(frame_state_t) :: fs             !< current frame state with Delta(t)
    integer :: ng = 0
    integer :: glob(mx) = 0
    real(dp) :: c0(nd, mx) = 0.0_dp, c1(nd, mx) = 0.0_dp, c2(nd, mx) = 0.0_dp   !< map and its rates
  end type sliding_link_t

contains

  !> The correlation table's description of every link end: joint kinds
  !> map one to one, except at a slider_link joint, where the sliding link's
  !> end is the sleeve (carried when another link meets there) and the
  !> carriers are pinned to it.
  pure subroutine mechanism_link_ends(mech, ends)
    type(mechanism_t), intent(in) :: mech
    type(link_end_t), intent(out) :: ends(:, :)   !< (2, n_links)
    integer :: k, side, j
    do k = 1, mech%n_links
      do side = 1, 2
        j = mech%links(k)%joint(side)
        ends(side, k) = link_end_t(mech%joints(j)%kind, j, atan2(mech%joints(j)%guide(2), mech%joints(j)%guide(1)))
        if (mech%joints(j)%kind /= joint_slider_link) cycle
        if (mech%joints(j)%sliding_link == k) then
          ends(side, k) = link_end_t(end_sleeve, j, 0.0_dp, mech%joints(j)%n_links > 1)
        else
          ends(side, k) = link_end_t(end_pin, j, 0.0_dp, .false.)
        end if
      end do
    end do
  end subroutine mechanism_link_ends

  !> Set up the sliding link k: Tennant's slender element with the transient
  !> deck's effects (stretching -> D_g, curvature -> D_b, material -> D_k:
  !> Tennant's forms of those terms, doc/transient.md §slider), and where its
  !> sleeve is.  Needs Kear's 8-DOF table and the coupling terms on.
  subroutine sliding_link_init(sl, mech, k, length, effects, beta, node_dofs, err)
    type(sliding_link_t), intent(out) :: sl
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: k, node_dofs
    real(dp), intent(in) :: length, beta
    type(element_effects_t), intent(in) :: effects
    type(error_t), intent(inout) :: err
    type(tennant_options_t) :: opt
    integer :: j, i, link
    associate (lk => mech%links(k))
      if (node_dofs /= nd/2) then
        call err%set('sliding link', 'link '''//trim(lk%name)//''' slides through a sleeve: that needs Kear''s '// &
                     '8-DOF element (formulation ''exact'' or ''kear1987''; ''default'' with stretching = T is the '// &
                     'consistent element)')
        return
      end if
      if (.not. effects%coupling) then
        call err%set('sliding link', 'link '''//trim(lk%name)//''' slides through a sleeve: its element (Tennant''s, '// &
                     'T24) always has the Coriolis and Euler terms; set coupling = T')
        return
      end if
      opt%d_k = merge(1.0_dp, 0.0_dp, effects%material)
      opt%d_b = merge(1.0_dp, 0.0_dp, effects%curvature)
      opt%d_g = merge(1.0_dp, 0.0_dp, effects%stretching)
      opt%rotary_inertia = effects%rotary_inertia
      opt%damping_beta = beta
      call tennant_element_init(sl%el, length, [tennant_section_t(0.0_dp, 1.0_dp, lk%b, lk%h)], &
                                ramberg_osgood_t(lk%e1, lk%e2, lk%m, lk%rho), opt, err, sliding=.true., &
                                fibre_ratio=lk%fibre/(0.5_dp*lk%h))
      if (err%failed()) then
        call err%add_context('link '''//trim(lk%name)//''' (sliding)')
        return
      end if
      sl%element = lk%first_element
      j = lk%joint(2)
    end associate
    sl%ground_point = [mech%joints(j)%x, mech%joints(j)%y]
    do i = 1, mech%joints(j)%n_links
      link = mech%joints(j)%link(i)
      if (link == k) cycle
      sl%carrier_node = mech%joints(j)%link_end(i)
      sl%carrier_element = mech%links(link)%first_element
      if (sl%carrier_node == 2) sl%carrier_element = sl%carrier_element + mech%links(link)%n_elements - 1
      exit
    end do
  end subroutine sliding_link_init

  !> Frame state (with Delta and its rates) and the sleeve map at the current
  !> rigid states rb; carrier_length is the carrier element's length.
  pure subroutine sliding_link_set_state(sl, table, rb, carrier_length)
    type(sliding_link_t), intent(inout) :: sl
    type(correlation_table_t), intent(in) :: table
    type(rigid_state_t), intent(in) :: rb(:)
    real(dp), intent(in) :: carrier_length
    real(dp) :: p(2), pd(2), pdd(2), u(2), n(2), c, s, d(2), dd(2), ddd(2)
    p = sl%ground_point
    pd = 0.0_dp
    pdd = 0.0_dp
    if (sl%carrier_element > 0) then
      associate (r => rb(sl%carrier_element))
        p = [r%x1, r%y1]
        pd = [r%x1_d, r%y1_d]
        pdd = [r%x1_dd, r%y1_dd]
        if (sl%carrier_node == 2) then
          c = cos(r%phi)
          s = sin(r%phi)
          p = p + carrier_length*[c, s]
          pd = pd + carrier_length*r%phi_d*[-s, c]
          pdd = pdd + carrier_length*[-r%phi_dd*s - r%phi_d**2*c, r%phi_dd*c - r%phi_d**2*s]
        end if
      end associate
    end if
    associate (r => rb(sl%element))
      u = [cos(r%phi), sin(r%phi)]
      n = [-u(2), u(1)]
      d = p - [r%x1, r%y1]
      dd = pd - [r%x1_d, r%y1_d]
      ddd = pdd - [r%x1_dd, r%y1_dd]
      sl%fs = frame_state_t(r%x1, r%y1, r%phi, r%x1_d, r%y1_d, r%phi_d, r%x1_dd, r%y1_dd, r%phi_dd, &
                            dot_product(d, u), dot_product(dd, u), dot_product(ddd, u) + r%phi_d*dot_product(dd, n))
      call table%element_map(sl%element, r%phi, r%phi_d, r%phi_dd, sl%ng, sl%c0, sl%c1, sl%c2)
    end associate
    sl%glob(1:sl%ng) = table%globals_of(sl%element)
  end subroutine sliding_link_set_state

  !> Element DOFs from the global displacements (current map).
  pure function sliding_link_element_q(sl, q) result(qe)
    type(sliding_link_t), intent(in) :: sl
    real(dp), intent(in) :: q(:)
    real(dp) :: qe(nd), qg(mx)
    qg = globals(sl, q)
    qe = matmul(sl%c0, qg)
  end function sliding_link_element_q

  !> The globals the element uses, padded with zeros to mx (the map's
  !> columns beyond ng are zero).
  pure function globals(sl, q) result(qg)
    type(sliding_link_t), intent(in) :: sl
    real(dp), intent(in) :: q(:)
    real(dp) :: qg(mx)
    integer :: i
    qg = 0.0_dp
    do i = 1, sl%ng
      qg(i) = q(sl%glob(i))
    end do
  end function globals

  !> mass_band (lower band, kd+1 rows) += C^T M_e C and force += the
  !> generalized force of the element (module comment); gravity acts like a
  !> frame acceleration -g.  n_points counts nonlinear integrand evaluations.
  pure subroutine sliding_link_add(sl, q, qd, gravity, kd, mass_band, force, n_points, info)
    type(sliding_link_t), intent(in) :: sl
    real(dp), intent(in) :: q(:), qd(:), gravity(2)
    integer, intent(in) :: kd
    real(dp), intent(inout) :: mass_band(:, :), force(:)
    integer, intent(inout) :: n_points
    type(tennant_info_t), intent(out) :: info
    real(dp) :: me(nd, nd), ce(nd, nd), ke(nd, nd), fe(nd), fn(nd), qg(mx), qdg(mx), qe(nd), qde(nd), mg(mx, mx)
    type(frame_state_t) :: fl
    integer :: i, j, gi, gj, ng
    ng = sl%ng
    qg = globals(sl, q)
    qdg = globals(sl, qd)
    qe = matmul(sl%c0, qg)
    qde = matmul(sl%c0, qdg) + matmul(sl%c1, qg)
    fl = sl%fs
    fl%x1_dd = fl%x1_dd - gravity(1)
    fl%y1_dd = fl%y1_dd - gravity(2)
    call tennant_linear_terms(sl%el, fl, me, ce, ke, fe, .true.)
    fe = fe - matmul(ce, qde) - matmul(ke, qe) - matmul(me, 2.0_dp*matmul(sl%c1, qdg) + matmul(sl%c2, qg))
    if (sl%el%nonlinear) then
      call tennant_nonlinear_terms(sl%el, qe, sl%fs, fn, info)
      n_points = n_points + info%n_points
      fe = fe - fn
    end if
    mg = matmul(transpose(sl%c0), matmul(me, sl%c0))
    qg = matmul(transpose(sl%c0), fe)
    do j = 1, ng
      gj = sl%glob(j)
      force(gj) = force(gj) + qg(j)
      do i = 1, ng
        gi = sl%glob(i)
        if (gi < gj .or. gi - gj > kd) cycle
        mass_band(1 + gi - gj, gj) = mass_band(1 + gi - gj, gj) + mg(i, j)
      end do
    end do
  end subroutine sliding_link_add

  !> The element's mass C^T M_e C and elastic tangent stiffness C^T K_t C
  !> (K_lin plus the tangent of f_n: like Kear's elements, the inertial
  !> stiffness and the map's rates are left out of the Newton matrix) at q,
  !> as dense blocks over glob(1:ng).
  pure subroutine sliding_link_matrices(sl, q, mg, kg)
    type(sliding_link_t), intent(in) :: sl
    real(dp), intent(in) :: q(:)
    real(dp), intent(out) :: mg(mx, mx), kg(mx, mx)
    real(dp) :: me(nd, nd), ce(nd, nd), ke(nd, nd), fe(nd), fn(nd), kt(nd, nd)
    type(frame_state_t) :: still
    type(tennant_info_t) :: info
    ! at rest in the same position: K_e is then the rotated K_lin
    still = frame_state_t(sl%fs%x1, sl%fs%y1, sl%fs%phi, length=sl%fs%length)
    call tennant_linear_terms(sl%el, still, me, ce, ke, fe, .false.)
    if (sl%el%nonlinear) then
      call tennant_nonlinear_terms(sl%el, sliding_link_element_q(sl, q), sl%fs, fn, info, tangent=kt)
      ke = ke + kt
    end if
    mg = matmul(transpose(sl%c0), matmul(me, sl%c0))
    kg = matmul(transpose(sl%c0), matmul(ke, sl%c0))
  end subroutine sliding_link_matrices

  !> Largest stress over the sliding element (Tennant's recovery, T §3.9).
  pure function sliding_link_stress(sl, q) result(rep)
    type(sliding_link_t), intent(in) :: sl
    real(dp), intent(in) :: q(:)
    type(stress_report_t) :: rep
    type(tennant_stress_t) :: ts
    ts = tennant_stress_recovery(sl%el, sliding_link_element_q(sl, q), sl%fs)
    rep%max_abs_stress = ts%max_abs_stress
    rep%stress = ts%stress
    rep%stress_x_over_l = ts%x_over_l
    rep%stress_fibre = ts%fibre
    rep%max_abs_strain = ts%max_abs_strain
    rep%eps_star = sl%el%eps_star
    rep%beyond_peak = ts%beyond_peak
  end function sliding_link_stress

  !> Kinetic and strain energy of the sliding element.
  pure subroutine sliding_link_energies(sl, q, qd, kinetic, strain)
    type(sliding_link_t), intent(in) :: sl
    real(dp), intent(in) :: q(:), qd(:)
    real(dp), intent(out) :: kinetic, strain
    real(dp) :: qe(nd), qde(nd), qg(mx), qdg(mx)
    qg = globals(sl, q)
    qdg = globals(sl, qd)
    qe = matmul(sl%c0, qg)
    qde = matmul(sl%c0, qdg) + matmul(sl%c1, qg)
    kinetic = tennant_kinetic_energy(sl%el, qe, qde, sl%fs)
    strain = tennant_strain_energy(sl%el, qe, sl%fs)
  end subroutine sliding_link_energies
end module sliding_link
