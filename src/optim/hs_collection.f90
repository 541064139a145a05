!> A Hock-Schittkowski test collection for the Gauss family (issue 11):
!> W. Hock and K. Schittkowski, Test Examples for Nonlinear Programming
!> Codes, Lecture Notes in Economics and Mathematical Systems 187, Springer
!> (1981), with their standard starts and published optima.
!>
!> Each problem is posed as printed: a general objective f (Rosenbrock's
!> HS 1 and HS 2 as the sum of squares they are, see n_residuals), general
!> inequalities (HS write c(x) >= 0; stored as g = -c <= 0), general
!> equalities h(x) = 0 and simple bounds (linear constraints, numbered after
!> the general inequalities).  Derivatives are central differences (error
!> ~eps^(2/3) for gradients, counted as finite-difference evaluations, not
!> in NF), Hessians central second differences.  The problems already in
!> problem_library (HS 15, 21, 28, 35, 43 = Rosen-Suzuki, 65) keep their
!> own formulations there.
module hs_collection
  use kinds, only: dp, pi
  use error_status, only: error_t
  use strings, only: str
  use optim_problem, only: opt_problem_t
  use hs_collection_added, only: added_numbers, added_data, added_f, added_c, pos, colville_quadratic, colville_a, &
                                 colville_b, colville_d, colville_e
  implicit none
  private
  public :: hs_problem_t, hs_numbers, hs_holdout, hs_holdout2, create_hs

  !> The numbers of the problems defined here.
  integer, parameter :: hs_numbers(97) = [1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 14, 16, 17, 18, 20, 22, 23, 24, 27, &
                                          29, 30, 31, 32, 34, 36, 37, 38, 39, 40, 42, 48, 50, 51, 52, 53, 60, 71, 76, &
                                          77, 78, 79, 44, 46, 57, 63, 64, 83, &
                                          8, 19, 26, 33, 41, 45, 55, 61, 62, 66, 72, 100, 110, 113, &
                                          49, 56, 73, 74, 75, 80, 81, 86, 93, 104, added_numbers]
  !> The hold-out: problems added after the globalization and the first-order
  !> test were designed, never used to choose a rule or a constant of the
  !> method; their results are reported apart (doc/optimization.md).
  integer, parameter :: hs_holdout(24) = [8, 19, 26, 33, 41, 45, 55, 61, 62, 66, 72, 100, 110, 113, &
                                          49, 56, 73, 74, 75, 80, 81, 86, 93, 104]
  !> The second hold-out: the 25 problems of hs_collection_added, added
  !> after the method's rules were last changed and never used to change them.
  integer, parameter :: hs_holdout2(25) = added_numbers
  real(dp), parameter :: none = 1.0e30_dp      !< no bound
  real(dp), parameter :: s2 = 1.4142135623730951_dp, s3 = 1.7320508075688772_dp

  type, extends(opt_problem_t) :: hs_problem_t
    integer :: number = 0
    integer :: mg = 0                     !< general inequalities (constraints 1..mg); bounds mg+1..m
  contains
    procedure :: objective => hs_objective
    procedure :: residuals => hs_residuals
    procedure :: jacobian => hs_jacobian
    procedure :: gradient => hs_gradient
    procedure :: general_constraint => hs_constraint
    procedure :: general_constraint_gradient => hs_constraint_gradient
  end type hs_problem_t

contains

  !> Set up HS problem `number`; found = .false. if it is not in hs_numbers.
  subroutine create_hs(number, prob, x0, x_star, f_star, found)
    integer, intent(in) :: number
    type(hs_problem_t), intent(out) :: prob
    real(dp), allocatable, intent(out) :: x0(:), x_star(:)
    real(dp), intent(out) :: f_star
    logical, intent(out) :: found
    real(dp), allocatable :: lo(:), hi(:)
    integer :: n, mg, me, i
    found = any(hs_numbers == number)
    f_star = 0.0_dp
    if (.not. found) return
    if (any(added_numbers == number)) then
      call added_data(number, n, mg, me, lo, hi, x0, x_star, f_star)
    else
      call hs_data(number, n, mg, me, lo, hi, x0, x_star, f_star)
    end if
    prob%number = number
    prob%mg = mg
    call prob%init_problem('hs'//str(number), n, n_residuals(number), mg, n_eq=me)
    do i = 1, mg
      call prob%set_general_constraint(i)
    end do
    do i = 1, me
      call prob%set_general_equality(i)
    end do
    call prob%set_bounds(lo, hi)                    ! constraints mg+1..m, after the general ones
  end subroutine create_hs

  !> Sizes, bounds, standard start and published optimum of each problem.
  !> Length: data, one short case per problem of the collection.
  subroutine hs_data(number, n, mg, me, lo, hi, x0, xs, fs)
    integer, intent(in) :: number
    integer, intent(out) :: n, mg, me
    real(dp), allocatable, intent(out) :: lo(:), hi(:), x0(:), xs(:)
    real(dp), intent(out) :: fs
    mg = 0
    me = 0
    select case (number)
    case (1)
      call dims(2); lo(2) = -1.5_dp
      x0 = [-2.0_dp, 1.0_dp]; xs = [1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (2)
      call dims(2); lo(2) = 1.5_dp
      x0 = [-2.0_dp, 1.0_dp]; xs = [1.224370748736353_dp, 1.5_dp]; fs = 0.0504261879_dp
    case (3)
      call dims(2); lo(2) = 0.0_dp
      x0 = [10.0_dp, 1.0_dp]; xs = [0.0_dp, 0.0_dp]; fs = 0.0_dp
    case (4)
      call dims(2); lo = [1.0_dp, 0.0_dp]
      x0 = [1.125_dp, 0.125_dp]; xs = [1.0_dp, 0.0_dp]; fs = 8.0_dp/3.0_dp
    case (5)
      call dims(2); lo = [-1.5_dp, -3.0_dp]; hi = [4.0_dp, 3.0_dp]
      x0 = [0.0_dp, 0.0_dp]; xs = [-pi/3.0_dp + 0.5_dp, -pi/3.0_dp - 0.5_dp]; fs = -0.5_dp*s3 - pi/3.0_dp
    case (6)
      call dims(2); me = 1
      x0 = [-1.2_dp, 1.0_dp]; xs = [1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (7)
      call dims(2); me = 1
      x0 = [2.0_dp, 2.0_dp]; xs = [0.0_dp, s3]; fs = -s3
    case (9)
      call dims(2); me = 1
      x0 = [0.0_dp, 0.0_dp]; xs = [-3.0_dp, -4.0_dp]; fs = -0.5_dp
    case (10)
      call dims(2); mg = 1
      x0 = [-10.0_dp, 10.0_dp]; xs = [0.0_dp, 1.0_dp]; fs = -1.0_dp
    case (11)
      call dims(2); mg = 1
      x0 = [4.9_dp, 0.1_dp]; xs = [1.234779016_dp, 1.524678871_dp]; fs = -8.498464223_dp
    case (12)
      call dims(2); mg = 1
      x0 = [0.0_dp, 0.0_dp]; xs = [2.0_dp, 3.0_dp]; fs = -30.0_dp
    case (14)
      call dims(2); mg = 1; me = 1
      x0 = [2.0_dp, 2.0_dp]; xs = [0.5_dp*(sqrt(7.0_dp) - 1.0_dp), 0.25_dp*(sqrt(7.0_dp) + 1.0_dp)]
      fs = 9.0_dp - 23.0_dp*sqrt(7.0_dp)/8.0_dp
    case (16)
      call dims(2); mg = 2; lo(1) = -2.0_dp; hi = [0.5_dp, 1.0_dp]
      x0 = [-2.0_dp, 1.0_dp]; xs = [0.5_dp, 0.25_dp]; fs = 0.25_dp
    case (17)
      call dims(2); mg = 2; lo(1) = -2.0_dp; hi = [0.5_dp, 1.0_dp]
      x0 = [-2.0_dp, 1.0_dp]; xs = [0.0_dp, 0.0_dp]; fs = 1.0_dp
    case (18)
      call dims(2); mg = 2; lo = [2.0_dp, 0.0_dp]; hi = [50.0_dp, 50.0_dp]
      x0 = [2.0_dp, 2.0_dp]; xs = [sqrt(250.0_dp), sqrt(2.5_dp)]; fs = 5.0_dp
    case (20)
      call dims(2); mg = 3; lo(1) = -0.5_dp; hi(1) = 0.5_dp
      x0 = [-2.0_dp, 1.0_dp]; xs = [0.5_dp, 0.5_dp*s3]; fs = 81.5_dp - 25.0_dp*s3
    case (22)
      call dims(2); mg = 2
      x0 = [2.0_dp, 2.0_dp]; xs = [1.0_dp, 1.0_dp]; fs = 1.0_dp
    case (23)
      call dims(2); mg = 5; lo = -50.0_dp; hi = 50.0_dp
      x0 = [3.0_dp, 1.0_dp]; xs = [1.0_dp, 1.0_dp]; fs = 2.0_dp
    case (24)
      call dims(2); mg = 3; lo = 0.0_dp
      x0 = [1.0_dp, 0.5_dp]; xs = [3.0_dp, s3]; fs = -1.0_dp
    case (27)
      call dims(3); me = 1
      x0 = [2.0_dp, 2.0_dp, 2.0_dp]; xs = [-1.0_dp, 1.0_dp, 0.0_dp]; fs = 0.04_dp
    case (29)
      call dims(3); mg = 1
      x0 = [1.0_dp, 1.0_dp, 1.0_dp]; xs = [4.0_dp, 2.0_dp*s2, 2.0_dp]; fs = -16.0_dp*s2
    case (30)
      call dims(3); mg = 1; lo = [1.0_dp, -10.0_dp, -10.0_dp]; hi = 10.0_dp
      x0 = [1.0_dp, 1.0_dp, 1.0_dp]; xs = [1.0_dp, 0.0_dp, 0.0_dp]; fs = 1.0_dp
    case (31)
      call dims(3); mg = 1; lo = [-10.0_dp, 1.0_dp, -10.0_dp]; hi = [10.0_dp, 10.0_dp, 1.0_dp]
      x0 = [1.0_dp, 1.0_dp, 1.0_dp]; xs = [1.0_dp/s3, s3, 0.0_dp]; fs = 6.0_dp
    case (32)
      call dims(3); mg = 1; me = 1; lo = 0.0_dp
      x0 = [0.1_dp, 0.7_dp, 0.2_dp]; xs = [0.0_dp, 0.0_dp, 1.0_dp]; fs = 1.0_dp
    case (34)
      call dims(3); mg = 2; lo = 0.0_dp; hi = [100.0_dp, 100.0_dp, 10.0_dp]
      x0 = [0.0_dp, 1.05_dp, 2.9_dp]; xs = [log(log(10.0_dp)), log(10.0_dp), 10.0_dp]; fs = -log(log(10.0_dp))
    case (36)
      call dims(3); mg = 1; lo = 0.0_dp; hi = [20.0_dp, 11.0_dp, 42.0_dp]
      x0 = [10.0_dp, 10.0_dp, 10.0_dp]; xs = [20.0_dp, 11.0_dp, 15.0_dp]; fs = -3300.0_dp
    case (37)
      call dims(3); mg = 2; lo = 0.0_dp; hi = 42.0_dp
      x0 = [10.0_dp, 10.0_dp, 10.0_dp]; xs = [24.0_dp, 12.0_dp, 12.0_dp]; fs = -3456.0_dp
    case (38)
      call dims(4); lo = -10.0_dp; hi = 10.0_dp
      x0 = [-3.0_dp, -1.0_dp, -3.0_dp, -1.0_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (39)
      call dims(4); me = 2
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]; xs = [1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp]; fs = -1.0_dp
    case (40)
      call dims(4); me = 3
      x0 = [0.8_dp, 0.8_dp, 0.8_dp, 0.8_dp]
      xs = [2.0_dp**(-1.0_dp/3.0_dp), 2.0_dp**(-0.5_dp), 2.0_dp**(-11.0_dp/12.0_dp), 2.0_dp**(-0.25_dp)]; fs = -0.25_dp
    case (42)
      call dims(4); me = 2
      x0 = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; xs = [2.0_dp, 2.0_dp, 0.6_dp*s2, 0.8_dp*s2]; fs = 28.0_dp - 10.0_dp*s2
    case (48)
      call dims(5); me = 2
      x0 = [3.0_dp, 5.0_dp, -3.0_dp, 2.0_dp, -2.0_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (50)
      call dims(5); me = 3
      x0 = [35.0_dp, -31.0_dp, 11.0_dp, 5.0_dp, -5.0_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (51)
      call dims(5); me = 3
      x0 = [2.5_dp, 0.5_dp, 2.0_dp, -1.0_dp, 0.5_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (52)
      call dims(5); me = 3
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]; xs = [-33.0_dp, 11.0_dp, 180.0_dp, -158.0_dp, 11.0_dp]/349.0_dp
      fs = 1859.0_dp/349.0_dp
    case (53)
      call dims(5); me = 3; lo = -10.0_dp; hi = 10.0_dp
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]; xs = [-33.0_dp, 11.0_dp, 27.0_dp, -5.0_dp, 11.0_dp]/43.0_dp
      fs = 176.0_dp/43.0_dp
    case (60)
      call dims(3); me = 1; lo = -10.0_dp; hi = 10.0_dp
      x0 = [2.0_dp, 2.0_dp, 2.0_dp]; xs = [1.104859024_dp, 1.196674194_dp, 1.535262257_dp]; fs = 0.03256820025_dp
    case (71)
      call dims(4); mg = 1; me = 1; lo = 1.0_dp; hi = 5.0_dp
      x0 = [1.0_dp, 5.0_dp, 5.0_dp, 1.0_dp]; xs = [1.0_dp, 4.742999643_dp, 3.821149981_dp, 1.379408293_dp]
      fs = 17.0140173_dp
    case (76)
      call dims(4); mg = 3; lo = 0.0_dp
      x0 = [0.5_dp, 0.5_dp, 0.5_dp, 0.5_dp]; xs = [3.0_dp, 23.0_dp, 0.0_dp, 6.0_dp]/11.0_dp
      fs = -4.681818181818182_dp
    case (77)
      call dims(5); me = 2
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]
      xs = [1.166172_dp, 1.182111_dp, 1.380257_dp, 1.506036_dp, 0.6109203_dp]; fs = 0.24150513_dp
    case (78)
      call dims(5); me = 3
      x0 = [-2.0_dp, 1.5_dp, 2.0_dp, -1.0_dp, -1.0_dp]
      xs = [-1.717143_dp, 1.595709_dp, 1.827247_dp, -0.7636413_dp, -0.7636450_dp]; fs = -2.91970041_dp
    case (79)
      call dims(5); me = 3
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]
      xs = [1.191127_dp, 1.362603_dp, 1.472818_dp, 1.635017_dp, 1.679081_dp]; fs = 0.0787768209_dp
    case (8)
      call dims(2); me = 2
      x0 = [2.0_dp, 1.0_dp]; xs = [sqrt(12.5_dp + 0.5_dp*sqrt(301.0_dp)), 9.0_dp/sqrt(12.5_dp + 0.5_dp*sqrt(301.0_dp))]
      fs = -1.0_dp
    case (19)
      call dims(2); mg = 2; lo = [13.0_dp, 0.0_dp]; hi = [100.0_dp, 100.0_dp]
      x0 = [20.1_dp, 5.84_dp]; xs = [14.095_dp, 0.84296079_dp]; fs = -6961.81381_dp
    case (26)
      call dims(3); me = 1
      x0 = [-2.6_dp, 2.0_dp, 2.0_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (33)
      call dims(3); mg = 2; lo = 0.0_dp; hi(3) = 5.0_dp
      x0 = [0.0_dp, 0.0_dp, 3.0_dp]; xs = [0.0_dp, s2, s2]; fs = s2 - 6.0_dp
    case (41)
      call dims(4); me = 1; lo = 0.0_dp; hi = [1.0_dp, 1.0_dp, 1.0_dp, 2.0_dp]
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]; xs = [2.0_dp/3.0_dp, 1.0_dp/3.0_dp, 1.0_dp/3.0_dp, 2.0_dp]
      fs = 52.0_dp/27.0_dp
    case (45)
      call dims(5); lo = 0.0_dp; hi = [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp]
      x0 = [2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp, 2.0_dp]; xs = [1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp]; fs = 1.0_dp
    case (55)
      call dims(6); me = 6; lo = 0.0_dp; hi(1) = 1.0_dp; hi(4) = 1.0_dp
      x0 = [1.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 2.0_dp]
      xs = [0.0_dp, 4.0_dp/3.0_dp, 5.0_dp/3.0_dp, 1.0_dp, 2.0_dp/3.0_dp, 1.0_dp/3.0_dp]; fs = 19.0_dp/3.0_dp
    case (61)
      call dims(3); me = 2
      x0 = [0.0_dp, 0.0_dp, 0.0_dp]; xs = [5.326770157_dp, -2.118998639_dp, 3.210464239_dp]; fs = -143.6461422_dp
    case (62)
      call dims(3); me = 1; lo = 0.0_dp; hi = 1.0_dp
      x0 = [0.7_dp, 0.2_dp, 0.1_dp]; xs = [0.6178126908_dp, 0.328202223_dp, 0.05398508606_dp]; fs = -26272.51448_dp
    case (66)
      call dims(3); mg = 2; lo = 0.0_dp; hi = [100.0_dp, 100.0_dp, 10.0_dp]
      x0 = [0.0_dp, 1.05_dp, 2.9_dp]; xs = [0.1841264879_dp, 1.202167873_dp, 3.327322322_dp]; fs = 0.5181632741_dp
    case (72)
      call dims(4); mg = 2; lo = 0.001_dp; hi = [4.0e5_dp, 3.0e5_dp, 2.0e5_dp, 1.0e5_dp]
      x0 = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; xs = [193.4071_dp, 179.5475_dp, 185.0186_dp, 168.7062_dp]; fs = 727.67937_dp
    case (100)
      call dims(7); mg = 4
      x0 = [1.0_dp, 2.0_dp, 0.0_dp, 4.0_dp, 0.0_dp, 1.0_dp, 1.0_dp]
      xs = [2.330499_dp, 1.951372_dp, -0.4775414_dp, 4.365726_dp, -0.6244870_dp, 1.038131_dp, 1.594227_dp]
      fs = 680.6300573_dp
    case (110)
      call dims(10); lo = 2.001_dp; hi = 9.999_dp
      x0 = spread(9.0_dp, 1, 10); xs = spread(9.35025655_dp, 1, 10); fs = -45.77846971_dp
    case (113)
      call dims(10); mg = 8
      x0 = [2.0_dp, 3.0_dp, 5.0_dp, 5.0_dp, 1.0_dp, 2.0_dp, 7.0_dp, 3.0_dp, 6.0_dp, 10.0_dp]
      xs = [2.171996_dp, 2.363683_dp, 8.773926_dp, 5.095984_dp, 0.9906548_dp, 1.430574_dp, 1.321644_dp, 9.828726_dp, &
            8.280092_dp, 8.375927_dp]; fs = 24.3062091_dp
    case (49)
      call dims(5); me = 2
      x0 = [10.0_dp, 7.0_dp, 2.0_dp, -3.0_dp, 0.8_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (56)
      call dims(7); me = 4
      x0 = [1.0_dp, 1.0_dp, 1.0_dp, asin(sqrt(1.0_dp/4.2_dp)), asin(sqrt(1.0_dp/4.2_dp)), asin(sqrt(1.0_dp/4.2_dp)), &
            asin(sqrt(5.0_dp/7.2_dp))]
      xs = [2.4_dp, 1.2_dp, 1.2_dp, asin(sqrt(4.0_dp/7.0_dp)), asin(sqrt(2.0_dp/7.0_dp)), asin(sqrt(2.0_dp/7.0_dp)), &
            0.5_dp*pi]; fs = -3.456_dp
    case (73)
      call dims(4); mg = 2; me = 1; lo = 0.0_dp
      x0 = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; xs = [0.6355216_dp, 0.0_dp, 0.3127019_dp, 0.05177655_dp]; fs = 29.894378_dp
    case (74, 75)
      call dims(4); mg = 2; me = 3; lo = [0.0_dp, 0.0_dp, -hs74_a(number), -hs74_a(number)]
      hi = [1200.0_dp, 1200.0_dp, hs74_a(number), hs74_a(number)]
      x0 = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]
      if (number == 74) then
        xs = [679.9453_dp, 1026.067_dp, 0.1188764_dp, -0.3962336_dp]; fs = 5126.4981_dp
      else
        xs = [776.1592_dp, 925.1949_dp, 0.05110879_dp, -0.4288911_dp]; fs = 5174.4129_dp
      end if
    case (80, 81)
      call dims(5); me = 3; lo = [-2.3_dp, -2.3_dp, -3.2_dp, -3.2_dp, -3.2_dp]; hi = -lo
      x0 = [-2.0_dp, 2.0_dp, 2.0_dp, -1.0_dp, -1.0_dp]
      xs = [-1.717143_dp, 1.595709_dp, 1.827247_dp, -0.7636413_dp, -0.7636450_dp]; fs = 0.0539498478_dp
    case (86)
      call dims(5); mg = 10; lo = 0.0_dp
      x0 = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp]
      xs = [0.3_dp, 0.33346761_dp, 0.4_dp, 0.42831010_dp, 0.22396487_dp]; fs = -32.34867897_dp
    case (93)
      call dims(6); mg = 2; lo = 0.0_dp
      x0 = [5.54_dp, 4.4_dp, 12.02_dp, 11.82_dp, 0.702_dp, 0.852_dp]
      xs = [5.332666_dp, 4.656744_dp, 10.43299_dp, 12.08230_dp, 0.7526074_dp, 0.87865084_dp]; fs = 135.075961_dp
    case (104)
      call dims(8); mg = 6; lo = 0.1_dp; hi = 10.0_dp
      x0 = [6.0_dp, 3.0_dp, 0.4_dp, 0.2_dp, 6.0_dp, 6.0_dp, 1.0_dp, 0.5_dp]
      xs = [6.465114_dp, 2.232709_dp, 0.6673975_dp, 0.5957564_dp, 5.932676_dp, 5.527235_dp, 1.013322_dp, 0.4006682_dp]
      fs = 3.9511634396_dp
    case (44)
      call dims(4); mg = 6; lo = 0.0_dp
      x0 = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp]; xs = [0.0_dp, 3.0_dp, 0.0_dp, 4.0_dp]; fs = -15.0_dp
    case (46)
      call dims(5); me = 2
      x0 = [0.5_dp*s2, 1.75_dp, 0.5_dp, 2.0_dp, 2.0_dp]; xs = [1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp]; fs = 0.0_dp
    case (57)
      call dims(2); mg = 1; lo = [0.4_dp, -4.0_dp]
      x0 = [0.42_dp, 5.0_dp]; xs = [0.419952675_dp, 1.284845629_dp]; fs = 0.02845966972_dp
    case (63)
      call dims(3); me = 2; lo = 0.0_dp
      x0 = [2.0_dp, 2.0_dp, 2.0_dp]; xs = [3.512118414_dp, 0.2169881741_dp, 3.552174034_dp]; fs = 961.7151721_dp
    case (64)
      call dims(3); mg = 1; lo = 1.0e-5_dp
      x0 = [1.0_dp, 1.0_dp, 1.0_dp]; xs = [108.7347175_dp, 85.12613942_dp, 204.3247078_dp]; fs = 6299.842428_dp
    case (83)
      call dims(5); mg = 6; lo = [78.0_dp, 33.0_dp, 27.0_dp, 27.0_dp, 27.0_dp]; hi = [102.0_dp, 45.0_dp, 45.0_dp, 45.0_dp, 45.0_dp]
      x0 = [78.0_dp, 33.0_dp, 27.0_dp, 27.0_dp, 27.0_dp]; xs = [78.0_dp, 33.0_dp, 29.99526_dp, 45.0_dp, 36.77581_dp]
      fs = -30665.53867_dp
    end select
  contains
    subroutine dims(nn)
      integer, intent(in) :: nn
      n = nn
      allocate(lo(n), hi(n))
      lo = -none
      hi = none
    end subroutine dims
  end subroutine hs_data

  !> f(x) as printed by Hock and Schittkowski.
  real(dp) function hs_f(number, x) result(f)
    integer, intent(in) :: number
    real(dp), intent(in) :: x(:)
    select case (number)
    case (1, 2, 16, 17, 20)
      f = 100.0_dp*(x(2) - x(1)**2)**2 + (1.0_dp - x(1))**2
    case (3)
      f = x(2) + 1.0e-5_dp*(x(2) - x(1))**2
    case (4)
      f = (x(1) + 1.0_dp)**3/3.0_dp + x(2)
    case (5)
      f = sin(x(1) + x(2)) + (x(1) - x(2))**2 - 1.5_dp*x(1) + 2.5_dp*x(2) + 1.0_dp
    case (6)
      f = (1.0_dp - x(1))**2
    case (7)
      f = log(1.0_dp + x(1)**2) - x(2)
    case (9)
      f = sin(pi*x(1)/12.0_dp)*cos(pi*x(2)/16.0_dp)
    case (10)
      f = x(1) - x(2)
    case (11)
      f = (x(1) - 5.0_dp)**2 + x(2)**2 - 25.0_dp
    case (12)
      f = 0.5_dp*x(1)**2 + x(2)**2 - x(1)*x(2) - 7.0_dp*x(1) - 7.0_dp*x(2)
    case (14, 22)
      f = (x(1) - 2.0_dp)**2 + (x(2) - 1.0_dp)**2
    case (18)
      f = 0.01_dp*x(1)**2 + x(2)**2
    case (23)
      f = x(1)**2 + x(2)**2
    case (24)
      f = ((x(1) - 3.0_dp)**2 - 9.0_dp)*x(2)**3/(27.0_dp*s3)
    case (27)
      f = 0.01_dp*(x(1) - 1.0_dp)**2 + (x(2) - x(1)**2)**2
    case (29, 36, 37)
      f = -x(1)*x(2)*x(3)
    case (30)
      f = x(1)**2 + x(2)**2 + x(3)**2
    case (31)
      f = 9.0_dp*x(1)**2 + x(2)**2 + 9.0_dp*x(3)**2
    case (32)
      f = (x(1) + 3.0_dp*x(2) + x(3))**2 + 4.0_dp*(x(1) - x(2))**2
    case (34)
      f = -x(1)
    case (38)
      f = 100.0_dp*(x(2) - x(1)**2)**2 + (1.0_dp - x(1))**2 + 90.0_dp*(x(4) - x(3)**2)**2 + (1.0_dp - x(3))**2 &
          + 10.1_dp*((x(2) - 1.0_dp)**2 + (x(4) - 1.0_dp)**2) + 19.8_dp*(x(2) - 1.0_dp)*(x(4) - 1.0_dp)
    case (39)
      f = -x(1)
    case (40)
      f = -x(1)*x(2)*x(3)*x(4)
    case (42)
      f = (x(1) - 1.0_dp)**2 + (x(2) - 2.0_dp)**2 + (x(3) - 3.0_dp)**2 + (x(4) - 4.0_dp)**2
    case (48)
      f = (x(1) - 1.0_dp)**2 + (x(2) - x(3))**2 + (x(4) - x(5))**2
    case (50)
      f = (x(1) - x(2))**2 + (x(2) - x(3))**2 + (x(3) - x(4))**4 + (x(4) - x(5))**2
    case (51, 53)
      f = (x(1) - x(2))**2 + (x(2) + x(3) - 2.0_dp)**2 + (x(4) - 1.0_dp)**2 + (x(5) - 1.0_dp)**2
    case (52)
      f = (4.0_dp*x(1) - x(2))**2 + (x(2) + x(3) - 2.0_dp)**2 + (x(4) - 1.0_dp)**2 + (x(5) - 1.0_dp)**2
    case (60)
      f = (x(1) - 1.0_dp)**2 + (x(1) - x(2))**2 + (x(2) - x(3))**4
    case (71)
      f = x(1)*x(4)*(x(1) + x(2) + x(3)) + x(3)
    case (76)
      f = x(1)**2 + 0.5_dp*x(2)**2 + x(3)**2 + 0.5_dp*x(4)**2 - x(1)*x(3) + x(3)*x(4) - x(1) - 3.0_dp*x(2) &
          + x(3) - x(4)
    case (77)
      f = (x(1) - 1.0_dp)**2 + (x(1) - x(2))**2 + (x(3) - 1.0_dp)**2 + (x(4) - 1.0_dp)**4 + (x(5) - 1.0_dp)**6
    case (78)
      f = x(1)*x(2)*x(3)*x(4)*x(5)
    case (79)
      f = (x(1) - 1.0_dp)**2 + (x(1) - x(2))**2 + (x(2) - x(3))**2 + (x(3) - x(4))**4 + (x(4) - x(5))**4
    case (8)
      f = -1.0_dp
    case (19)
      f = (x(1) - 10.0_dp)**3 + (x(2) - 20.0_dp)**3
    case (26)
      f = (x(1) - x(2))**2 + (x(2) - x(3))**4
    case (33)
      f = (x(1) - 1.0_dp)*(x(1) - 2.0_dp)*(x(1) - 3.0_dp) + x(3)
    case (41)
      f = 2.0_dp - x(1)*x(2)*x(3)
    case (45)
      f = 2.0_dp - product(x(1:5))/120.0_dp
    case (55)
      f = x(1) + 2.0_dp*x(2) + 4.0_dp*x(5) + exp(x(1)*x(4))
    case (61)
      f = 4.0_dp*x(1)**2 + 2.0_dp*x(2)**2 + 2.0_dp*x(3)**2 - 33.0_dp*x(1) + 16.0_dp*x(2) - 24.0_dp*x(3)
    case (62)
      f = -32.174_dp*(255.0_dp*log(pos(x(1) + x(2) + x(3) + 0.03_dp)/pos(0.09_dp*x(1) + x(2) + x(3) + 0.03_dp)) &
          + 280.0_dp*log(pos(x(2) + x(3) + 0.03_dp)/pos(0.07_dp*x(2) + x(3) + 0.03_dp)) &
          + 290.0_dp*log(pos(x(3) + 0.03_dp)/pos(0.13_dp*x(3) + 0.03_dp)))
    case (66)
      f = 0.2_dp*x(3) - 0.8_dp*x(1)
    case (72)
      f = 1.0_dp + sum(x(1:4))
    case (100)
      f = (x(1) - 10.0_dp)**2 + 5.0_dp*(x(2) - 12.0_dp)**2 + x(3)**4 + 3.0_dp*(x(4) - 11.0_dp)**2 + 10.0_dp*x(5)**6 &
          + 7.0_dp*x(6)**2 + x(7)**4 - 4.0_dp*x(6)*x(7) - 10.0_dp*x(6) - 8.0_dp*x(7)
    case (110)
      f = sum(log(pos(x - 2.0_dp))**2 + log(pos(10.0_dp - x))**2) - pos(product(x))**0.2_dp
    case (113)
      f = x(1)**2 + x(2)**2 + x(1)*x(2) - 14.0_dp*x(1) - 16.0_dp*x(2) + (x(3) - 10.0_dp)**2 + 4.0_dp*(x(4) - 5.0_dp)**2 &
          + (x(5) - 3.0_dp)**2 + 2.0_dp*(x(6) - 1.0_dp)**2 + 5.0_dp*x(7)**2 + 7.0_dp*(x(8) - 11.0_dp)**2 &
          + 2.0_dp*(x(9) - 10.0_dp)**2 + (x(10) - 7.0_dp)**2 + 45.0_dp
    case (49)
      f = (x(1) - x(2))**2 + (x(3) - 1.0_dp)**2 + (x(4) - 1.0_dp)**4 + (x(5) - 1.0_dp)**6
    case (56)
      f = -x(1)*x(2)*x(3)
    case (73)
      f = 24.55_dp*x(1) + 26.75_dp*x(2) + 39.0_dp*x(3) + 40.5_dp*x(4)
    case (74, 75)
      f = 3.0_dp*x(1) + 1.0e-6_dp*x(1)**3 + 2.0_dp*x(2) + 1.0e-6_dp*x(2)**3/1.5_dp
    case (80)
      f = exp(min(product(x(1:5)), 700.0_dp))
    case (81)
      f = exp(min(product(x(1:5)), 700.0_dp)) - 0.5_dp*(x(1)**3 + x(2)**3 + 1.0_dp)**2
    case (86)
      f = hs86(x)
    case (93)
      f = 0.0204_dp*x(1)*x(4)*(x(1) + x(2) + x(3)) + 0.0187_dp*x(2)*x(3)*(x(1) + 1.57_dp*x(2) + x(4)) &
          + 0.0607_dp*x(1)*x(4)*x(5)**2*(x(1) + x(2) + x(3)) + 0.0437_dp*x(2)*x(3)*x(6)**2*(x(1) + 1.57_dp*x(2) + x(4))
    case (104)
      f = hs104(x)
    case (44)
      f = x(1) - x(2) - x(3) - x(1)*x(3) + x(1)*x(4) + x(2)*x(3) - x(2)*x(4)
    case (46)
      f = (x(1) - x(2))**2 + (x(3) - 1.0_dp)**2 + (x(4) - 1.0_dp)**4 + (x(5) - 1.0_dp)**6
    case (57)
      f = hs57(x)
    case (63)
      f = 1000.0_dp - x(1)**2 - 2.0_dp*x(2)**2 - x(3)**2 - x(1)*x(2) - x(1)*x(3)
    case (64)
      f = 5.0_dp*x(1) + 50000.0_dp/pos(x(1)) + 20.0_dp*x(2) + 72000.0_dp/pos(x(2)) + 10.0_dp*x(3) &
          + 144000.0_dp/pos(x(3))
    case (83)
      f = 5.3578547_dp*x(3)**2 + 0.8356891_dp*x(1)*x(5) + 37.293239_dp*x(1) - 40792.141_dp
    case default
      f = added_f(number, x)
    end select
  end function hs_f

  !> HS inequality c_j(x) >= 0 (kind 1) or equality h_j(x) = 0 (kind 2).
  !> Length (about 140 lines): a flat data table, one case per constraint
  !> (number*10 + j) holding its printed formula and nothing else; the
  !> formulas share no step to fold, and a split (by kind or by problem)
  !> would only repeat the dispatch around the same table.
  real(dp) function hs_c(number, kind, j, x) result(c)
    integer, intent(in) :: number, kind, j
    real(dp), intent(in) :: x(:)
    integer :: i
    c = 0.0_dp
    if (any(added_numbers == number)) then
      c = added_c(number, kind, j, x)
    else if (kind == 1) then
      select case (number*10 + j)
      case (101)
        c = -3.0_dp*x(1)**2 + 2.0_dp*x(1)*x(2) - x(2)**2 + 1.0_dp
      case (111)
        c = -x(1)**2 + x(2)
      case (121)
        c = 25.0_dp - 4.0_dp*x(1)**2 - x(2)**2
      case (141)
        c = -0.25_dp*x(1)**2 - x(2)**2 + 1.0_dp
      case (161, 201)
        c = x(1) + x(2)**2
      case (162, 202)
        c = x(1)**2 + x(2)
      case (171)
        c = x(2)**2 - x(1)
      case (172)
        c = x(1)**2 - x(2)
      case (181)
        c = x(1)*x(2) - 25.0_dp
      case (182)
        c = x(1)**2 + x(2)**2 - 25.0_dp
      case (203)
        c = x(1)**2 + x(2)**2 - 1.0_dp
      case (221)
        c = -x(1) - x(2) + 2.0_dp
      case (222)
        c = -x(1)**2 + x(2)
      case (231)
        c = x(1) + x(2) - 1.0_dp
      case (232)
        c = x(1)**2 + x(2)**2 - 1.0_dp
      case (233)
        c = 9.0_dp*x(1)**2 + x(2)**2 - 9.0_dp
      case (234)
        c = x(1)**2 - x(2)
      case (235)
        c = x(2)**2 - x(1)
      case (241)
        c = x(1)/s3 - x(2)
      case (242)
        c = x(1) + s3*x(2)
      case (243)
        c = -x(1) - s3*x(2) + 6.0_dp
      case (291)
        c = -x(1)**2 - 2.0_dp*x(2)**2 - 4.0_dp*x(3)**2 + 48.0_dp
      case (301)
        c = x(1)**2 + x(2)**2 - 1.0_dp
      case (311)
        c = x(1)*x(2) - 1.0_dp
      case (321)
        c = 6.0_dp*x(2) + 4.0_dp*x(3) - x(1)**3 - 3.0_dp
      case (341)
        c = x(2) - exp(min(x(1), 700.0_dp))     ! guarded: trial points far out must not overflow
      case (342)
        c = x(3) - exp(min(x(2), 700.0_dp))
      case (361, 371)
        c = 72.0_dp - x(1) - 2.0_dp*x(2) - 2.0_dp*x(3)
      case (372)
        c = x(1) + 2.0_dp*x(2) + 2.0_dp*x(3)
      case (711)
        c = x(1)*x(2)*x(3)*x(4) - 25.0_dp
      case (761)
        c = -x(1) - 2.0_dp*x(2) - x(3) - x(4) + 5.0_dp
      case (762)
        c = -3.0_dp*x(1) - x(2) - 2.0_dp*x(3) + x(4) + 4.0_dp
      case (763)
        c = x(2) + 4.0_dp*x(3) - 1.5_dp
      case (191)
        c = (x(1) - 5.0_dp)**2 + (x(2) - 5.0_dp)**2 - 100.0_dp
      case (192)
        c = 82.81_dp - (x(2) - 5.0_dp)**2 - (x(1) - 6.0_dp)**2
      case (331)
        c = x(3)**2 - x(1)**2 - x(2)**2
      case (332)
        c = x(1)**2 + x(2)**2 + x(3)**2 - 4.0_dp
      case (661)
        c = x(2) - exp(min(x(1), 700.0_dp))
      case (662)
        c = x(3) - exp(min(x(2), 700.0_dp))
      case (721)
        c = 0.0401_dp - 4.0_dp/pos(x(1)) - 2.25_dp/pos(x(2)) - 1.0_dp/pos(x(3)) - 0.25_dp/pos(x(4))
      case (722)
        c = 0.010085_dp - 0.16_dp/pos(x(1)) - 0.36_dp/pos(x(2)) - 0.64_dp/pos(x(3)) - 0.64_dp/pos(x(4))
      case (1001)
        c = 127.0_dp - 2.0_dp*x(1)**2 - 3.0_dp*x(2)**4 - x(3) - 4.0_dp*x(4)**2 - 5.0_dp*x(5)
      case (1002)
        c = 282.0_dp - 7.0_dp*x(1) - 3.0_dp*x(2) - 10.0_dp*x(3)**2 - x(4) + x(5)
      case (1003)
        c = 196.0_dp - 23.0_dp*x(1) - x(2)**2 - 6.0_dp*x(6)**2 + 8.0_dp*x(7)
      case (1004)
        c = -4.0_dp*x(1)**2 - x(2)**2 + 3.0_dp*x(1)*x(2) - 2.0_dp*x(3)**2 - 5.0_dp*x(6) + 11.0_dp*x(7)
      case (1131)
        c = 105.0_dp - 4.0_dp*x(1) - 5.0_dp*x(2) + 3.0_dp*x(7) - 9.0_dp*x(8)
      case (1132)
        c = -10.0_dp*x(1) + 8.0_dp*x(2) + 17.0_dp*x(7) - 2.0_dp*x(8)
      case (1133)
        c = 8.0_dp*x(1) - 2.0_dp*x(2) - 5.0_dp*x(9) + 2.0_dp*x(10) + 12.0_dp
      case (1134)
        c = -3.0_dp*(x(1) - 2.0_dp)**2 - 4.0_dp*(x(2) - 3.0_dp)**2 - 2.0_dp*x(3)**2 + 7.0_dp*x(4) + 120.0_dp
      case (1135)
        c = -5.0_dp*x(1)**2 - 8.0_dp*x(2) - (x(3) - 6.0_dp)**2 + 2.0_dp*x(4) + 40.0_dp
      case (1136)
        c = -0.5_dp*(x(1) - 8.0_dp)**2 - 2.0_dp*(x(2) - 4.0_dp)**2 - 3.0_dp*x(5)**2 + x(6) + 30.0_dp
      case (1137)
        c = -x(1)**2 - 2.0_dp*(x(2) - 2.0_dp)**2 + 2.0_dp*x(1)*x(2) - 14.0_dp*x(5) + 6.0_dp*x(6)
      case (1138)
        c = 3.0_dp*x(1) - 6.0_dp*x(2) - 12.0_dp*(x(9) - 8.0_dp)**2 + 7.0_dp*x(10)
      case (731)
        c = 2.3_dp*x(1) + 5.6_dp*x(2) + 11.1_dp*x(3) + 1.3_dp*x(4) - 5.0_dp
      case (732)
        c = 12.0_dp*x(1) + 11.9_dp*x(2) + 41.8_dp*x(3) + 52.1_dp*x(4) - 21.0_dp &
            - 1.645_dp*sqrt(0.28_dp*x(1)**2 + 0.19_dp*x(2)**2 + 20.5_dp*x(3)**2 + 0.62_dp*x(4)**2)
      case (741, 751)
        c = x(4) - x(3) + hs74_a(number)
      case (742, 752)
        c = x(3) - x(4) + hs74_a(number)
      case (861:870)
        c = dot_product([(colville_a(j, i), i = 1, 5)], x(1:5)) - colville_b(j)
      case (931)
        c = 0.001_dp*product(x(1:6)) - 2.07_dp
      case (932)
        c = 1.0_dp - 0.00062_dp*x(1)*x(4)*x(5)**2*(x(1) + x(2) + x(3)) &
            - 0.00058_dp*x(2)*x(3)*x(6)**2*(x(1) + 1.57_dp*x(2) + x(4))
      case (1041)
        c = 1.0_dp - 0.0588_dp*x(5)*x(7) - 0.1_dp*x(1)
      case (1042)
        c = 1.0_dp - 0.0588_dp*x(6)*x(8) - 0.1_dp*x(1) - 0.1_dp*x(2)
      case (1043)
        c = 1.0_dp - 4.0_dp*x(3)/pos(x(5)) - 2.0_dp/(pos(x(3))**0.71_dp*pos(x(5))) - 0.0588_dp*x(7)/pos(x(3))**1.3_dp
      case (1044)
        c = 1.0_dp - 4.0_dp*x(4)/pos(x(6)) - 2.0_dp/(pos(x(4))**0.71_dp*pos(x(6))) - 0.0588_dp*x(8)/pos(x(4))**1.3_dp
      case (1045)
        c = hs104(x) - 1.0_dp
      case (1046)
        c = 4.2_dp - hs104(x)
      case (441)
        c = 8.0_dp - x(1) - 2.0_dp*x(2)
      case (442)
        c = 12.0_dp - 4.0_dp*x(1) - x(2)
      case (443)
        c = 12.0_dp - 3.0_dp*x(1) - 4.0_dp*x(2)
      case (444)
        c = 8.0_dp - 2.0_dp*x(3) - x(4)
      case (445)
        c = 8.0_dp - x(3) - 2.0_dp*x(4)
      case (446)
        c = 5.0_dp - x(3) - x(4)
      case (571)
        c = 0.49_dp*x(2) - x(1)*x(2) - 0.09_dp
      case (641)
        c = 1.0_dp - 4.0_dp/pos(x(1)) - 32.0_dp/pos(x(2)) - 120.0_dp/pos(x(3))
      case (831, 832)
        c = 85.334407_dp + 0.0056858_dp*x(2)*x(5) + 0.0006262_dp*x(1)*x(4) - 0.0022053_dp*x(3)*x(5)
        if (j == 1) c = 92.0_dp - c
      case (833, 834)
        c = 80.51249_dp + 0.0071317_dp*x(2)*x(5) + 0.0029955_dp*x(1)*x(2) + 0.0021813_dp*x(3)**2
        c = merge(110.0_dp - c, c - 90.0_dp, j == 3)
      case (835, 836)
        c = 9.300961_dp + 0.0047026_dp*x(3)*x(5) + 0.0012547_dp*x(1)*x(3) + 0.0019085_dp*x(3)*x(4)
        c = merge(25.0_dp - c, c - 20.0_dp, j == 5)
      end select
    else
      select case (number*10 + j)
      case (61)
        c = 10.0_dp*(x(2) - x(1)**2)
      case (71)
        c = (1.0_dp + x(1)**2)**2 + x(2)**2 - 4.0_dp
      case (91)
        c = 4.0_dp*x(1) - 3.0_dp*x(2)
      case (141)
        c = x(1) - 2.0_dp*x(2) + 1.0_dp
      case (271)
        c = x(1) + x(3)**2 + 1.0_dp
      case (321)
        c = 1.0_dp - x(1) - x(2) - x(3)
      case (391)
        c = x(2) - x(1)**3 - x(3)**2
      case (392)
        c = x(1)**2 - x(2) - x(4)**2
      case (401)
        c = x(1)**3 + x(2)**2 - 1.0_dp
      case (402)
        c = x(1)**2*x(4) - x(3)
      case (403)
        c = x(4)**2 - x(2)
      case (421)
        c = x(1) - 2.0_dp
      case (422)
        c = x(3)**2 + x(4)**2 - 2.0_dp
      case (481)
        c = sum(x(1:5)) - 5.0_dp
      case (482)
        c = x(3) - 2.0_dp*(x(4) + x(5)) + 3.0_dp
      case (501)
        c = x(1) + 2.0_dp*x(2) + 3.0_dp*x(3) - 6.0_dp
      case (502)
        c = x(2) + 2.0_dp*x(3) + 3.0_dp*x(4) - 6.0_dp
      case (503)
        c = x(3) + 2.0_dp*x(4) + 3.0_dp*x(5) - 6.0_dp
      case (511)
        c = x(1) + 3.0_dp*x(2) - 4.0_dp
      case (512, 522, 532)
        c = x(3) + x(4) - 2.0_dp*x(5)
      case (513, 523, 533)
        c = x(2) - x(5)
      case (521, 531)
        c = x(1) + 3.0_dp*x(2)
      case (601)
        c = x(1)*(1.0_dp + x(2)**2) + x(3)**4 - 4.0_dp - 3.0_dp*s2
      case (711)
        c = sum(x(1:4)**2) - 40.0_dp
      case (771)
        c = x(1)**2*x(4) + sin(x(4) - x(5)) - 2.0_dp*s2
      case (772)
        c = x(2) + x(3)**4*x(4)**2 - 8.0_dp - s2
      case (781)
        c = sum(x(1:5)**2) - 10.0_dp
      case (782)
        c = x(2)*x(3) - 5.0_dp*x(4)*x(5)
      case (783)
        c = x(1)**3 + x(2)**3 + 1.0_dp
      case (81)
        c = x(1)**2 + x(2)**2 - 25.0_dp
      case (82)
        c = x(1)*x(2) - 9.0_dp
      case (261)
        c = (1.0_dp + x(2)**2)*x(1) + x(3)**4 - 3.0_dp
      case (411)
        c = x(1) + 2.0_dp*x(2) + 2.0_dp*x(3) - x(4)
      case (551)
        c = x(1) + 2.0_dp*x(2) + 5.0_dp*x(5) - 6.0_dp
      case (552)
        c = x(1) + x(2) + x(3) - 3.0_dp
      case (553)
        c = x(4) + x(5) + x(6) - 2.0_dp
      case (554)
        c = x(1) + x(4) - 1.0_dp
      case (555)
        c = x(2) + x(5) - 2.0_dp
      case (556)
        c = x(3) + x(6) - 2.0_dp
      case (611)
        c = 3.0_dp*x(1) - 2.0_dp*x(2)**2 - 7.0_dp
      case (612)
        c = 4.0_dp*x(1) - x(3)**2 - 11.0_dp
      case (621)
        c = x(1) + x(2) + x(3) - 1.0_dp
      case (491)
        c = x(1) + x(2) + x(3) + 4.0_dp*x(4) - 7.0_dp
      case (492)
        c = x(3) + 5.0_dp*x(5) - 6.0_dp
      case (561, 562, 563)
        c = x(j) - 4.2_dp*sin(x(j + 3))**2
      case (564)
        c = x(1) + 2.0_dp*x(2) + 2.0_dp*x(3) - 7.2_dp*sin(x(7))**2
      case (731)
        c = x(1) + x(2) + x(3) + x(4) - 1.0_dp
      case (741, 751)
        c = 1000.0_dp*sin(-x(3) - 0.25_dp) + 1000.0_dp*sin(-x(4) - 0.25_dp) + 894.8_dp - x(1)
      case (742, 752)
        c = 1000.0_dp*sin(x(3) - 0.25_dp) + 1000.0_dp*sin(x(3) - x(4) - 0.25_dp) + 894.8_dp - x(2)
      case (743, 753)
        c = 1000.0_dp*sin(x(4) - 0.25_dp) + 1000.0_dp*sin(x(4) - x(3) - 0.25_dp) + 1294.8_dp
      case (801, 811)
        c = sum(x(1:5)**2) - 10.0_dp
      case (802, 812)
        c = x(2)*x(3) - 5.0_dp*x(4)*x(5)
      case (803, 813)
        c = x(1)**3 + x(2)**3 + 1.0_dp
      case (461)
        c = x(1)**2*x(4) + sin(x(4) - x(5)) - 1.0_dp
      case (462)
        c = x(2) + x(3)**4*x(4)**2 - 2.0_dp
      case (631)
        c = 8.0_dp*x(1) + 14.0_dp*x(2) + 7.0_dp*x(3) - 56.0_dp
      case (632)
        c = x(1)**2 + x(2)**2 + x(3)**2 - 25.0_dp
      case (791)
        c = x(1) + x(2)**2 + x(3)**3 - 2.0_dp - 3.0_dp*s2
      case (792)
        c = x(2) - x(3)**2 + x(4) + 2.0_dp - 2.0_dp*s2
      case (793)
        c = x(1)*x(5) - 2.0_dp
      end select
    end if
  end function hs_c

  !> HS 74 and 75 differ in the bound a on |x3 - x4| (and on x3, x4).
  pure real(dp) function hs74_a(number) result(a)
    integer, intent(in) :: number
    a = merge(0.55_dp, 0.48_dp, number == 74)
  end function hs74_a

  !> HS 86 (Colville's first problem): e^T x + x^T C x + d^T x^3 (the data
  !> it shares with its dual HS 117 are in hs_collection_added).
  pure real(dp) function hs86(x) result(f)
    real(dp), intent(in) :: x(:)
    f = dot_product(colville_e, x(1:5)) + dot_product(x(1:5), matmul(colville_quadratic, x(1:5))) &
        + dot_product(colville_d, x(1:5)**3)
  end function hs86

  !> HS 104's objective, also bounded in its constraints 5 and 6.
  pure real(dp) function hs104(x) result(f)
    real(dp), intent(in) :: x(:)
    f = 0.4_dp*(pos(x(1))/pos(x(7)))**0.67_dp + 0.4_dp*(pos(x(2))/pos(x(8)))**0.67_dp + 10.0_dp - x(1) - x(2)
  end function hs104

  !> HS 57: a fit of 44 observations b_i at a_i (Hock & Schittkowski's table).
  pure real(dp) function hs57(x) result(f)
    real(dp), intent(in) :: x(:)
    real(dp), parameter :: a(44) = [8, 8, 10, 10, 10, 10, 12, 12, 12, 12, 14, 14, 14, 16, 16, 16, 18, 18, 20, 20, 20, &
      22, 22, 22, 24, 24, 24, 26, 26, 26, 28, 28, 30, 30, 30, 32, 32, 34, 36, 36, 38, 38, 40, 42]
    real(dp), parameter :: b(44) = [0.49_dp, 0.49_dp, 0.48_dp, 0.47_dp, 0.48_dp, 0.47_dp, 0.46_dp, 0.46_dp, 0.45_dp, &
      0.43_dp, 0.45_dp, 0.43_dp, 0.43_dp, 0.44_dp, 0.43_dp, 0.43_dp, 0.46_dp, 0.45_dp, 0.42_dp, 0.42_dp, 0.43_dp, &
      0.41_dp, 0.41_dp, 0.40_dp, 0.42_dp, 0.40_dp, 0.40_dp, 0.41_dp, 0.40_dp, 0.41_dp, 0.41_dp, 0.40_dp, 0.40_dp, &
      0.40_dp, 0.38_dp, 0.41_dp, 0.40_dp, 0.40_dp, 0.41_dp, 0.38_dp, 0.40_dp, 0.40_dp, 0.39_dp, 0.39_dp]
    f = sum((b - x(1) - (0.49_dp - x(1))*exp(min(-x(2)*(a - 8.0_dp), 700.0_dp)))**2)
  end function hs57

  subroutine hs_objective(self, x, f, err)
    class(hs_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: f
    type(error_t), intent(inout) :: err
    f = hs_f(self%number, x)
    if (.false.) call err%clear()
  end subroutine hs_objective

  !> Residuals of the objectives posed as sums of squares, F = phi^T phi (the
  !> Gauss method's own form, G = 2 J J^T): HS 1 and HS 2 are Rosenbrock's
  !> function, phi = (10 (x2 - x1^2), 1 - x1), posed like HS 15 (the same
  !> objective) in problem_library.  0: a general objective.
  pure integer function n_residuals(number)
    integer, intent(in) :: number
    n_residuals = merge(2, 0, number == 1 .or. number == 2)
  end function n_residuals

  pure function hs_phi(x) result(phi)
    real(dp), intent(in) :: x(:)
    real(dp) :: phi(2)
    phi = [10.0_dp*(x(2) - x(1)**2), 1.0_dp - x(1)]
  end function hs_phi

  subroutine hs_residuals(self, x, phi, err)
    class(hs_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: phi(:)
    type(error_t), intent(inout) :: err
    phi = hs_phi(x)
    if (.false.) call err%set(self%name, '')
  end subroutine hs_residuals

  !> J (n, p) by central differences, as the collection's gradients.
  subroutine hs_jacobian(self, x, phi, jac, err)
    class(hs_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), phi(:)
    real(dp), intent(out) :: jac(:, :)
    type(error_t), intent(inout) :: err
    real(dp) :: xp(size(x)), xm(size(x))
    integer :: j
    do j = 1, size(x)
      call central_points(x, j, xp, xm)
      jac(j, :) = (hs_phi(xp) - hs_phi(xm))/(xp(j) - xm(j))
    end do
    self%count%fd_analyses = self%count%fd_analyses + 2*size(x)
    if (.false.) jac(1, 1) = phi(1)
    if (.false.) call err%clear()
  end subroutine hs_jacobian

  subroutine hs_gradient(self, x, f, grad, err)
    class(hs_problem_t), intent(inout) :: self
    real(dp), intent(in) :: x(:), f
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    call central_gradient(self, 0, x, grad)
    self%count%fd_analyses = self%count%fd_analyses + 2*size(x)
    if (.false.) grad(1) = f
    if (.false.) call err%clear()
  end subroutine hs_gradient

  !> Gradient of F (which = 0) or of constraint `which` by central differences.
  subroutine central_gradient(self, which, x, grad)
    class(hs_problem_t), intent(in) :: self
    integer, intent(in) :: which
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: grad(:)
    real(dp) :: xp(size(x)), xm(size(x))
    integer :: j
    do j = 1, size(x)
      call central_points(x, j, xp, xm)
      if (which == 0) then
        grad(j) = (hs_f(self%number, xp) - hs_f(self%number, xm))/(xp(j) - xm(j))
      else
        grad(j) = (constraint_of(self, which, xp) - constraint_of(self, which, xm))/(xp(j) - xm(j))
      end if
    end do
  end subroutine central_gradient

  !> The points x +- h e_j of the collection's central differences,
  !> h = eps^(1/3) max(|x_j|, 1): error ~1e-11 relative.
  pure subroutine central_points(x, j, xp, xm)
    real(dp), intent(in) :: x(:)
    integer, intent(in) :: j
    real(dp), intent(out) :: xp(:), xm(:)
    real(dp) :: h
    xp = x
    xm = x
    h = 6.0554544523933395e-6_dp*max(abs(x(j)), 1.0_dp)
    xp(j) = x(j) + h
    xm(j) = x(j) - h
  end subroutine central_points

  !> Constraint i: general inequality (i <= mg: g = -c), equality (i > mg).
  real(dp) function constraint_of(self, i, x) result(g)
    class(hs_problem_t), intent(in) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    if (i <= self%mg) then
      g = -hs_c(self%number, 1, i, x)
    else
      g = hs_c(self%number, 2, i - self%mg, x)       ! equality i - mg (user_index: bounds not counted)
    end if
  end function constraint_of

  subroutine hs_constraint(self, i, x, g, err)
    class(hs_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:)
    real(dp), intent(out) :: g
    type(error_t), intent(inout) :: err
    g = constraint_of(self, i, x)
    if (i > self%mg + self%n_eq) call err%set(self%name, 'no general constraint '//str(i))
  end subroutine hs_constraint

  subroutine hs_constraint_gradient(self, i, x, g, grad, err)
    class(hs_problem_t), intent(inout) :: self
    integer, intent(in) :: i
    real(dp), intent(in) :: x(:), g
    real(dp), intent(out) :: grad(:)
    type(error_t), intent(inout) :: err
    call central_gradient(self, i, x, grad)
    self%count%fd_constraint_evals = self%count%fd_constraint_evals + 2*size(x)
    if (.false.) grad(1) = g
    if (.false.) call err%clear()
  end subroutine hs_constraint_gradient
end module hs_collection
