!> The spatial design with the analysis in the loop (doc/design.md, "Spatial
!> mechanisms"): a spatial_design deck's problem through GNLC (as the
!> spatial_design analysis runs it) and through NLopt's SLSQP (gradient-based
!> SQP) and COBYLA (derivative-free), from the same start, with the same
!> analyses, bounds and constraints, and for SLSQP the same forward-difference
!> derivatives (the problem's fd_rel_step; every neighbour one analysis,
!> shared by every constraint through the problem's record of analysed
!> designs).
!>
!> Printed per optimizer: NF (spatial analyses of distinct designs,
!> derivatives included), failed analyses, revolutions integrated, CPU of the
!> analyses, the final F (mass / initial mass), the largest constraint
!> (ln ratio) and the final design.  A benchmark: figures, not pass/fail.
!> Deck: the argument, or inputs/design_rssr_100.nml.
module spatial_design_nlopt_glue
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp, i8
  use nlopt_api
  use error_status, only: error_t
  use spatial_design_problem, only: spatial_design_problem_t
  implicit none
  private
  public :: nlopt_spatial_design, alg_slsqp, alg_cobyla

  !> what a failed analysis returns to NLopt: a violation of e^10 (NLopt has
  !> no notion of a failed trial)
  real(dp), parameter :: failed_constraint = 10.0_dp

  ! NLopt's callbacks carry only an integer: the problem is module state for
  ! the duration of one nlopt_spatial_design
  type(spatial_design_problem_t), pointer :: current => null()
  integer, target, save :: ids(0:20) = 0

contains

  !> Minimise from x with NLopt's `alg`: the variables' bounds as NLopt
  !> bounds, each analysis constraint an inequality; stops at |dx| < xtol or
  !> a relative change of F below ftol.
  subroutine nlopt_spatial_design(prob, alg, x, xtol, ftol, f, ires)
    type(spatial_design_problem_t), intent(inout), target :: prob
    integer, intent(in) :: alg
    real(dp), intent(inout) :: x(:)
    real(dp), intent(in) :: xtol, ftol
    real(dp), intent(out) :: f
    integer, intent(out) :: ires
    integer(i8) :: opt
    integer :: i, r
    current => prob
    do i = 0, size(ids) - 1
      ids(i) = i
    end do
    call nlo_create(opt, alg, size(x))
    call nlo_set_min_objective(r, opt, objective_cb, ids(0))
    call nlo_set_lower_bounds(r, opt, prob%xl)
    call nlo_set_upper_bounds(r, opt, prob%xu)
    do i = 1, prob%n_analysis_constraints()
      call nlo_add_inequality_constraint(r, opt, constraint_cb, ids(i), 0.0_dp)
    end do
    call nlo_set_xtol_abs1(r, opt, xtol)
    call nlo_set_ftol_rel(r, opt, ftol)
    call nlo_set_maxeval(r, opt, 500)
    call nlo_optimize(ires, opt, x, f)
    call nlo_destroy(opt)
    current => null()
  end subroutine nlopt_spatial_design

  !> F = mass / initial mass and its gradient (explicit: no analysis).
  subroutine objective_cb(val, n, x, grad, need_gradient, f_data)
    real(dp), intent(out) :: val
    integer, intent(in) :: n
    real(dp), intent(in) :: x(n)
    real(dp), intent(inout) :: grad(n)
    integer, intent(in) :: need_gradient
    integer, intent(in) :: f_data
    type(error_t) :: err
    call current%objective(x, val, err)
    if (need_gradient == 0 .or. f_data /= 0) return
    call current%gradient(x, val, grad, err)
  end subroutine objective_cb

  !> Constraint f_data and its forward-difference gradient (the problem's own,
  !> as GNLC takes it).
  subroutine constraint_cb(val, n, x, grad, need_gradient, f_data)
    real(dp), intent(out) :: val
    integer, intent(in) :: n
    real(dp), intent(in) :: x(n)
    real(dp), intent(inout) :: grad(n)
    integer, intent(in) :: need_gradient
    integer, intent(in) :: f_data
    type(error_t) :: err
    call current%general_constraint(f_data, x, val, err)
    if (.not. ieee_is_finite(val)) then
      val = failed_constraint
      if (need_gradient /= 0) grad = 0.0_dp
      return
    end if
    if (need_gradient == 0) return
    call current%general_constraint_gradient(f_data, x, val, grad, err)
    if (.not. all(ieee_is_finite(grad))) grad = 0.0_dp
  end subroutine constraint_cb
end module spatial_design_nlopt_glue

program bench_spatial_design
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use spatial_settings, only: spatial_input_t
  use design_settings, only: design_settings_t
  use gauss_optimizer, only: gauss_optimizer_t
  use spatial_design_problem, only: spatial_design_problem_t, spatial_eval_t
  use spatial_design_analysis, only: load_spatial_design
  use spatial_design_nlopt_glue, only: nlopt_spatial_design, alg_slsqp, alg_cobyla
  implicit none
  character(len=256) :: path
  if (command_argument_count() >= 1) then
    call get_command_argument(1, path)
  else
    path = 'inputs/design_rssr_100.nml'
  end if
  write(*, '(a)') 'spatial design '//trim(path)//': GNLC (the spatial_design analysis) against NLopt SLSQP and '// &
    'COBYLA from the same start; NF = spatial analyses of distinct designs, derivatives included'
  write(*, '(a10, a6, a8, a8, a10, a14, a13, 2x, a)') 'method', 'NF', 'failed', 'revs', 'cpu_s', 'F', 'max_g', &
    'design (final sizes)'
  call run_one('gnlc')
  call run_one('slsqp')
  call run_one('cobyla')

contains

  subroutine run_one(method)
    character(len=*), intent(in) :: method
    type(deck_t) :: deck
    type(table_t) :: scratch
    type(spatial_design_problem_t), target :: prob
    type(gauss_optimizer_t) :: opt
    type(spatial_input_t) :: inp
    type(design_settings_t) :: ds
    type(spatial_eval_t) :: ev
    type(error_t) :: err
    real(dp), allocatable :: x(:)
    real(dp) :: f
    integer :: ires, i
    character(len=:), allocatable :: text
    call deck%open(trim(path), err)
    if (.not. err%failed()) call scratch%open('bench_spatial_design_scratch.out', err)
    if (.not. err%failed()) call load_spatial_design(deck, scratch, prob, x, opt, inp, ds, err)
    call deck%close()
    if (scratch%is_open()) call scratch%discard()
    if (err%failed()) then
      write(*, '(a)') method//': '//err%text()
      return
    end if
    select case (method)
    case ('gnlc')
      call opt%solve(prob, x, err)
      if (allocated(opt%x)) x = opt%x
      text = opt%message
    case ('slsqp')
      call nlopt_spatial_design(prob, alg_slsqp, x, ds%xtol, ds%xtol**2, f, ires)
      text = 'NLopt result '//str(ires)
    case default
      call nlopt_spatial_design(prob, alg_cobyla, x, ds%xtol, ds%xtol**2, f, ires)
      text = 'NLopt result '//str(ires)
    end select
    call prob%evaluate(x, ev)
    f = prob%mass_at(x)/prob%mass0
    write(*, '(a10, i6, i8, i8, f10.2, es14.6, es13.3)', advance='no') method, prob%n_analyses, prob%n_failed, &
      prob%n_revolutions, prob%cpu_analyses, f, merge(maxval(ev%g), huge(1.0_dp), ev%ok)
    do i = 1, size(x)
      write(*, '(2x, a, "=", f8.5)', advance='no') trim(prob%var(i)%name), prob%var(i)%value(x(i))
    end do
    write(*, '(2x, a)') '('//text//')'
  end subroutine run_one
end program bench_spatial_design
