!> The second part of the Hock-Schittkowski collection (module
!> hs_collection): 25 further problems of W. Hock and K. Schittkowski, Test
!> Examples for Nonlinear Programming Codes, LNEMS 187, Springer (1981),
!> with their standard starts and optima, all in the collection's second
!> hold-out (never used to choose a rule or a constant of the method).
!> Posed as printed (inequalities c(x) >= 0, equalities h(x) = 0, bounds;
!> a ranged constraint a <= c(x) <= b as the two inequalities c - a >= 0,
!> b - c >= 0).  Where the printed optimum disagrees with the printed
!> problem, the value the problem gives at the printed x* is stored and the
!> difference is listed in doc/optimization.md §8 (HS 58, 106, 112).
!> Also home of the data HS 86 (Colville's first problem) shares with its
!> dual HS 117, and of pos(), the continuation the functions of both
!> modules use outside their domains.
module hs_collection_added
  use kinds, only: dp
  implicit none
  private
  public :: added_numbers, added_data, added_f, added_c, pos, colville_quadratic, colville_a, colville_b, &
            colville_d, colville_e, xstar_digits

  !> The problems defined here.
  integer, parameter :: added_numbers(25) = [13, 25, 47, 54, 58, 68, 69, 84, 95, 96, 97, 98, 101, 102, 103, &
                                             106, 107, 108, 109, 111, 112, 114, 116, 117, 118]
  real(dp), parameter :: none = 1.0e30_dp      !< no bound
  real(dp), parameter :: colville_d(5) = [4.0_dp, 8.0_dp, 10.0_dp, 6.0_dp, 2.0_dp]
  real(dp), parameter :: colville_e(5) = [-15.0_dp, -27.0_dp, -36.0_dp, -18.0_dp, -12.0_dp]
  real(dp), parameter :: colville_quadratic(5, 5) = reshape([30, -20, -10, 32, -10, -20, 39, -6, -31, 32, -10, -6, &
                                                            10, -6, -10, 32, -31, -6, 39, -20, -10, 32, -10, -20, 30], [5, 5])
  !> HS 114's constants
  real(dp), parameter :: a114 = 0.99_dp, b114 = 0.9_dp
  !> HS 107 and 109's network constants
  real(dp), parameter :: c107 = 48.4_dp/50.176_dp*0.24740395925452294_dp, d107 = 48.4_dp/50.176_dp*0.96891242171064473_dp
  real(dp), parameter :: a109 = 50.176_dp, sin025 = 0.24740395925452294_dp, cos025 = 0.96891242171064473_dp
  !> HS 84's coefficients a_1..a_21
  real(dp), parameter :: a84(21) = [-24345.0_dp, -8720288.849_dp, 150512.5253_dp, -156.6950325_dp, 476470.3222_dp, &
    729482.8271_dp, -145421.402_dp, 2931.1506_dp, -40.427932_dp, 5106.192_dp, 15711.36_dp, -155011.1084_dp, &
    4360.53352_dp, 12.9492344_dp, 10236.884_dp, 13176.786_dp, -326669.5104_dp, 7390.68412_dp, -27.8986976_dp, &
    16643.076_dp, 30988.146_dp]
  !> HS 118's lower limits of the five periods' totals
  real(dp), parameter :: totals118(5) = [60.0_dp, 50.0_dp, 70.0_dp, 85.0_dp, 100.0_dp]

contains

  !> max(v, 1e-150): trial points of the multiplier equations and of the
  !> step may leave the bounds that keep a division, a logarithm or a power
  !> defined (HS 25, 62, 64, 72, 101-104, 110, 112, 114); outside them the
  !> functions are continued with finite values (1/1e-150 = 1e150 does not
  !> overflow when summed), never NaN.
  elemental real(dp) function pos(v)
    real(dp), intent(in) :: v
    pos = max(v, 1.0e-150_dp)
  end function pos

  !> Significant digits to which x* is stored: 7 (HS print 7 to 10) unless
  !> the public statement of the optimum used here gives fewer (the test of
  !> the published optima allows the corresponding first-order error in f
  !> and in the constraints).
  pure integer function xstar_digits(number)
    integer, intent(in) :: number
    xstar_digits = 7
    if (any(number == [101, 102, 103, 107, 108, 109, 111, 112, 114])) xstar_digits = 6
    if (number == 116) xstar_digits = 5     ! x11* = 20.233
  end function xstar_digits

  !> Sizes, bounds, standard start and optimum of each added problem.
  !> Length: data, one short case per problem.
  subroutine added_data(number, n, mg, me, lo, hi, x0, xs, fs)
    integer, intent(in) :: number
    integer, intent(out) :: n, mg, me
    real(dp), allocatable, intent(out) :: lo(:), hi(:), x0(:), xs(:)
    real(dp), intent(out) :: fs
    real(dp) :: t
    integer :: i
    mg = 0
    me = 0
    fs = 0.0_dp
    select case (number)
    case (13)
      call dims(2); mg = 1; lo = 0.0_dp
      x0 = [-2.0_dp, -2.0_dp]; xs = [1.0_dp, 0.0_dp]; fs = 1.0_dp
    case (25)
      call dims(3); lo = [0.1_dp, 0.0_dp, 0.0_dp]; hi = [100.0_dp, 25.6_dp, 5.0_dp]
      x0 = [100.0_dp, 12.5_dp, 3.0_dp]; xs = [50.0_dp, 25.0_dp, 1.5_dp]; fs = 0.0_dp
    case (47)
      call dims(5); me = 3
      x0 = [2.0_dp, sqrt(2.0_dp), -1.0_dp, 2.0_dp - sqrt(2.0_dp), 0.5_dp]; xs = spread(1.0_dp, 1, 5); fs = 0.0_dp
    case (54)
      call dims(6); me = 1; lo = [0.0_dp, -10.0_dp, 0.0_dp, 0.0_dp, -1.0_dp, 0.0_dp]
      hi = [2.0e4_dp, 10.0_dp, 1.0e7_dp, 20.0_dp, 1.0_dp, 2.0e8_dp]
      x0 = [6.0e3_dp, 1.5_dp, 4.0e6_dp, 2.0_dp, 3.0e-3_dp, 5.0e7_dp]
      xs = [91600.0_dp/7.0_dp, 79.0_dp/70.0_dp, 2.0e6_dp, 10.0_dp, 1.0e-3_dp, 1.0e8_dp]; fs = -exp(-27.0_dp/280.0_dp)
    case (58)
      ! x* = the intersection of x2 = x1^2 and x1^2 + x2^2 = 1 with x1 < 0
      call dims(2); mg = 3; lo(1) = -2.0_dp; hi(1) = 0.5_dp
      t = 0.5_dp*(sqrt(5.0_dp) - 1.0_dp)
      x0 = [-2.0_dp, 1.0_dp]; xs = [-sqrt(t), t]; fs = (1.0_dp + sqrt(t))**2
    case (68, 69)
      ! x3*, x4* from x2* through the two equalities (exact on them)
      call dims(4); me = 2; lo = [1.0e-4_dp, 0.0_dp, 0.0_dp, 0.0_dp]; hi = [100.0_dp, 100.0_dp, 2.0_dp, 2.0_dp]
      x0 = spread(1.0_dp, 1, 4)
      if (number == 68) then
        xs = [0.06785874_dp, 3.6461717_dp, 0.0_dp, 0.0_dp]; fs = -0.920425026_dp
      else
        xs = [0.0293714_dp, 1.19025_dp, 0.0_dp, 0.0_dp]; fs = -956.71288_dp
      end if
      xs(3) = 2.0_dp*phi(-xs(2))
      xs(4) = phi(-xs(2) + sqrt(hs68_n(number))) + phi(-xs(2) - sqrt(hs68_n(number)))
    case (84)
      call dims(5); mg = 6; lo = [0.0_dp, 1.2_dp, 20.0_dp, 9.0_dp, 6.5_dp]; hi = [1000.0_dp, 2.4_dp, 60.0_dp, 9.3_dp, 7.0_dp]
      x0 = [2.52_dp, 2.0_dp, 37.5_dp, 9.25_dp, 6.8_dp]; xs = [4.53743097_dp, 2.4_dp, 60.0_dp, 9.3_dp, 7.0_dp]
      fs = -5280335.133_dp
    case (95, 96, 97, 98)
      call dims(6); mg = 4; lo = 0.0_dp; hi = [0.31_dp, 0.046_dp, 0.068_dp, 0.042_dp, 0.028_dp, 0.0134_dp]
      x0 = spread(0.0_dp, 1, 6)
      if (number <= 96) then
        xs = [0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 4.97_dp/1495.5_dp]; fs = 0.015619514_dp
      else
        ! x5, x6 at their upper bounds, x1 on the first constraint
        xs = [(32.97_dp - 623.4_dp*0.028_dp - 1495.5_dp*0.0134_dp + 24300.0_dp*0.028_dp*0.0134_dp)/17.1_dp, &
              0.0_dp, 0.0_dp, 0.0_dp, 0.028_dp, 0.0134_dp]; fs = 3.1358091_dp
      end if
    case (101, 102, 103)
      call dims(7); mg = 6; lo = 0.1_dp; lo(7) = 0.01_dp; hi = 10.0_dp
      x0 = spread(6.0_dp, 1, 7)
      select case (number)
      case (101)
        xs = [2.85616_dp, 0.610823_dp, 2.15081_dp, 4.71287_dp, 0.999488_dp, 1.34751_dp, 0.0316528_dp]; fs = 1809.76476_dp
      case (102)
        xs = [3.89625_dp, 0.809359_dp, 2.66439_dp, 4.30091_dp, 0.853555_dp, 1.09529_dp, 0.0273105_dp]; fs = 911.880571_dp
      case default
        xs = [4.3941_dp, 0.854469_dp, 2.84323_dp, 3.39998_dp, 0.722926_dp, 0.870406_dp, 0.0246388_dp]; fs = 543.667958_dp
      end select
    case (106)
      call dims(8); mg = 6; lo = [100.0_dp, 1000.0_dp, 1000.0_dp, 10.0_dp, 10.0_dp, 10.0_dp, 10.0_dp, 10.0_dp]
      hi = [1.0e4_dp, 1.0e4_dp, 1.0e4_dp, 1000.0_dp, 1000.0_dp, 1000.0_dp, 1000.0_dp, 1000.0_dp]
      x0 = [5000.0_dp, 5000.0_dp, 5000.0_dp, 200.0_dp, 350.0_dp, 150.0_dp, 225.0_dp, 425.0_dp]
      xs = [579.306685017979589_dp, 1359.97067807935605_dp, 5109.97065743133317_dp, 182.01769963061534_dp, &
            295.601173702746792_dp, 217.982300369384632_dp, 286.41652592786852_dp, 395.601173702746735_dp]
      fs = 7049.24802052867_dp
    case (107)
      call dims(9); me = 6; lo(1:2) = 0.0_dp; lo(5:7) = 0.90909_dp; hi(5:7) = 1.0909_dp
      x0 = [0.8_dp, 0.8_dp, 0.2_dp, 0.2_dp, 1.0454_dp, 1.0454_dp, 1.0454_dp, 0.0_dp, 0.0_dp]
      xs = [0.667013_dp, 1.02238_dp, 0.228287_dp, 0.184822_dp, 1.0909_dp, 1.0909_dp, 1.06904_dp, 0.106611_dp, -0.338788_dp]
      fs = 5055.011803_dp
    case (108)
      call dims(9); mg = 13; lo(9) = 0.0_dp
      x0 = spread(1.0_dp, 1, 9)
      xs = [-0.554603_dp, -0.831898_dp, 0.44323_dp, -0.896408_dp, -0.554697_dp, -0.832052_dp, 0.443331_dp, -0.896141_dp, &
            0.0002167_dp]; fs = -0.8660254038_dp
    case (109)
      call dims(9); mg = 4; me = 6
      lo = [0.0_dp, 0.0_dp, -0.55_dp, -0.55_dp, 196.0_dp, 196.0_dp, 196.0_dp, -400.0_dp, -400.0_dp]
      hi = [none, none, 0.55_dp, 0.55_dp, 252.0_dp, 252.0_dp, 252.0_dp, 800.0_dp, 800.0_dp]
      x0 = spread(0.0_dp, 1, 9)
      xs = [675.025_dp, 1134.02_dp, 0.133485_dp, -0.37119_dp, 252.0_dp, 252.0_dp, 201.466_dp, 426.619_dp, 368.488_dp]
      fs = 5362.06928_dp
    case (111, 112)
      call dims(10); me = 3
      xs = [0.0406681_dp, 0.14773_dp, 0.783153_dp, 0.00141422_dp, 0.485247_dp, 0.000693175_dp, 0.0273993_dp, &
            0.0179473_dp, 0.0373144_dp, 0.0968713_dp]; fs = -47.76109026_dp
      if (number == 111) then
        lo = -100.0_dp; hi = 100.0_dp
        x0 = spread(-2.3_dp, 1, 10); xs = log(xs)
      else
        lo = 1.0e-6_dp
        x0 = spread(0.1_dp, 1, 10)
      end if
    case (114)
      call dims(10); mg = 8; me = 3
      lo = [1.0e-5_dp, 1.0e-5_dp, 1.0e-5_dp, 1.0e-5_dp, 1.0e-5_dp, 85.0_dp, 90.0_dp, 3.0_dp, 1.2_dp, 145.0_dp]
      hi = [2000.0_dp, 16000.0_dp, 120.0_dp, 5000.0_dp, 2000.0_dp, 93.0_dp, 95.0_dp, 12.0_dp, 4.0_dp, 162.0_dp]
      x0 = [1745.0_dp, 12000.0_dp, 110.0_dp, 3048.0_dp, 1974.0_dp, 89.2_dp, 92.8_dp, 8.0_dp, 3.6_dp, 145.0_dp]
      xs = [1698.09_dp, 15818.6_dp, 54.1027_dp, 3031.23_dp, 2000.0_dp, 90.1154_dp, 95.0_dp, 10.4933_dp, 1.56164_dp, &
            153.535_dp]; fs = -1768.80696_dp
    case (116)
      call dims(13); mg = 15
      lo = [0.1_dp, 0.1_dp, 0.1_dp, 1.0e-4_dp, 0.1_dp, 0.1_dp, 0.1_dp, 0.1_dp, 500.0_dp, 0.1_dp, 1.0_dp, 1.0e-4_dp, 1.0e-4_dp]
      hi = [1.0_dp, 1.0_dp, 1.0_dp, 0.1_dp, 0.9_dp, 0.9_dp, 1000.0_dp, 1000.0_dp, 1000.0_dp, 500.0_dp, 150.0_dp, 150.0_dp, &
            150.0_dp]
      x0 = [0.5_dp, 0.8_dp, 0.9_dp, 0.1_dp, 0.14_dp, 0.5_dp, 489.0_dp, 80.0_dp, 650.0_dp, 450.0_dp, 150.0_dp, 150.0_dp, &
            150.0_dp]
      xs = [0.803773_dp, 0.899986_dp, 0.970982_dp, 0.1_dp, 0.190813_dp, 0.460655_dp, 574.077_dp, 74.0775_dp, 500.016_dp, &
            0.1_dp, 20.233_dp, 77.3477_dp, 0.00672893_dp]; fs = 97.588409_dp
    case (117)
      call dims(15); mg = 5; lo = 0.0_dp
      x0 = spread(0.001_dp, 1, 15); x0(7) = 60.0_dp
      xs = [0.0_dp, 0.0_dp, 5.174136_dp, 0.0_dp, 3.061093_dp, 11.83968_dp, 0.0_dp, 0.0_dp, 0.1039071_dp, 0.0_dp, &
            0.2999929_dp, 0.3334709_dp, 0.3999910_dp, 0.4283145_dp, 0.2239607_dp]; fs = 32.348679_dp
    case (118)
      call dims(15); mg = 29
      lo = [8.0_dp, 43.0_dp, 3.0_dp, (0.0_dp, i = 1, 12)]
      hi = [21.0_dp, 57.0_dp, 16.0_dp, (90.0_dp, 120.0_dp, 60.0_dp, i = 1, 4)]
      x0 = [20.0_dp, 55.0_dp, 15.0_dp, (20.0_dp, 60.0_dp, 20.0_dp, i = 1, 4)]
      xs = [8.0_dp, 49.0_dp, 3.0_dp, 1.0_dp, 56.0_dp, 0.0_dp, 1.0_dp, 63.0_dp, 6.0_dp, 3.0_dp, 70.0_dp, 12.0_dp, 5.0_dp, &
            77.0_dp, 18.0_dp]; fs = 664.82045_dp
    end select
  contains
    subroutine dims(nn)
      integer, intent(in) :: nn
      n = nn
      allocate(lo(n), hi(n))
      lo = -none
      hi = none
    end subroutine dims
  end subroutine added_data

  !> The standard normal distribution function (HS 68, 69).
  elemental real(dp) function phi(z)
    real(dp), intent(in) :: z
    phi = 0.5_dp*erfc(-z/sqrt(2.0_dp))
  end function phi

  !> HS 68 and 69 differ in the constants a, b, n (d = 1).
  pure real(dp) function hs68_n(number)
    integer, intent(in) :: number
    hs68_n = merge(24.0_dp, 4.0_dp, number == 68)
  end function hs68_n

  !> f(x) as printed by Hock and Schittkowski.
  real(dp) function added_f(number, x) result(f)
    integer, intent(in) :: number
    real(dp), intent(in) :: x(:)
    real(dp) :: a, b, ex
    integer :: i
    select case (number)
    case (13)
      f = (x(1) - 2.0_dp)**2 + x(2)**2
    case (25)
      f = 0.0_dp
      do i = 1, 99
        a = 25.0_dp + (-50.0_dp*log(0.01_dp*i))**(2.0_dp/3.0_dp)
        f = f + (-0.01_dp*i + exp(-pos(a - x(2))**x(3)/pos(x(1))))**2
      end do
    case (47)
      f = (x(1) - x(2))**2 + (x(2) - x(3))**3 + (x(3) - x(4))**4 + (x(4) - x(5))**4
    case (54)
      f = -exp(-0.5_dp*hs54_h(x))
    case (58)
      f = 100.0_dp*(x(2) - x(1)**2)**2 + (1.0_dp - x(1))**2
    case (68, 69)
      a = merge(1.0e-4_dp, 0.1_dp, number == 68)
      b = merge(1.0_dp, 1000.0_dp, number == 68)
      ex = exp(min(x(1), 700.0_dp)) - 1.0_dp
      f = (a*hs68_n(number) - (b*ex - x(3))*x(4)/(ex + x(4)))/pos(x(1))
    case (84)
      f = -a84(1) - a84(2)*x(1) - x(1)*dot_product(a84(3:6), [x(2), x(3), x(4), x(5)])
    case (95, 96, 97, 98)
      f = dot_product([4.3_dp, 31.8_dp, 63.3_dp, 15.8_dp, 68.5_dp, 4.7_dp], x(1:6))
    case (101, 102, 103)
      f = hs101_f(number, x)
    case (106)
      f = x(1) + x(2) + x(3)
    case (107)
      f = 3000.0_dp*x(1) + 1000.0_dp*x(1)**3 + 2000.0_dp*x(2) + 666.667_dp*x(2)**3
    case (108)
      f = -0.5_dp*(x(1)*x(4) - x(2)*x(3) + x(3)*x(9) - x(5)*x(9) + x(5)*x(8) - x(6)*x(7))
    case (109)
      f = 3.0_dp*x(1) + 1.0e-6_dp*x(1)**3 + 2.0_dp*x(2) + 0.522074e-6_dp*x(2)**3
    case (111)
      f = hs112_f(exp(min(x(1:10), 700.0_dp)))
    case (112)
      f = hs112_f(x(1:10))
    case (114)
      f = 5.04_dp*x(1) + 0.035_dp*x(2) + 10.0_dp*x(3) + 3.36_dp*x(5) - 0.063_dp*x(4)*x(7)
    case (116)
      f = x(11) + x(12) + x(13)
    case (117)
      f = -dot_product([(colville_b(i), i = 1, 10)], x(1:10)) &
          + dot_product(x(11:15), matmul(colville_quadratic, x(11:15))) + 2.0_dp*dot_product(colville_d, x(11:15)**3)
    case (118)
      f = 0.0_dp
      do i = 0, 4
        f = f + 2.3_dp*x(3*i + 1) + 1.0e-4_dp*x(3*i + 1)**2 + 1.7_dp*x(3*i + 2) + 1.0e-4_dp*x(3*i + 2)**2 &
            + 2.2_dp*x(3*i + 3) + 1.5e-4_dp*x(3*i + 3)**2
      end do
    case default
      f = 0.0_dp
    end select
  end function added_f

  !> HS inequality c_j(x) >= 0 (kind 1) or equality h_j(x) = 0 (kind 2).
  !> Length (about 150 lines): a flat data table, one case per constraint
  !> (number*100 + j) holding its printed formula, as hs_collection's.
  real(dp) function added_c(number, kind, j, x) result(c)
    integer, intent(in) :: number, kind, j
    real(dp), intent(in) :: x(:)
    real(dp) :: s
    integer :: k, r, i
    c = 0.0_dp
    if (kind == 1) then
      select case (number*100 + j)
      case (1301)
        c = (1.0_dp - x(1))**3 - x(2)
      case (5801)
        c = x(2)**2 - x(1)
      case (5802)
        c = x(1)**2 - x(2)
      case (5803)
        c = x(1)**2 + x(2)**2 - 1.0_dp
      case (8401:8406)
        k = (j - 1)/2
        s = x(1)*dot_product(a84(7 + 5*k:11 + 5*k), [1.0_dp, x(2), x(3), x(4), x(5)])
        c = merge(s, merge(294000.0_dp, 277200.0_dp, k < 2) - s, mod(j, 2) == 1)
      case (9501:9504, 9601:9604, 9701:9704, 9801:9804)
        c = hs95_c(j, x) - hs95_b(number, j)
      case (10101:10104, 10201:10204, 10301:10304)
        c = hs101_c(j, x)
      case (10105, 10205, 10305)
        c = hs101_f(number, x) - 100.0_dp
      case (10106, 10206, 10306)
        c = 3000.0_dp - hs101_f(number, x)
      case (10601)
        c = 1.0_dp - 0.0025_dp*(x(4) + x(6))
      case (10602)
        c = 1.0_dp - 0.0025_dp*(x(5) + x(7) - x(4))
      case (10603)
        c = 1.0_dp - 0.01_dp*(x(8) - x(5))
      case (10604)
        c = x(1)*x(6) - 833.33252_dp*x(4) - 100.0_dp*x(1) + 83333.333_dp
      case (10605)
        c = x(2)*x(7) - 1250.0_dp*x(5) - x(2)*x(4) + 1250.0_dp*x(4)
      case (10606)
        c = x(3)*x(8) - 1250000.0_dp - x(3)*x(5) + 2500.0_dp*x(5)
      case (10801:10813)
        c = hs108_c(j, x)
      case (10901)
        c = x(4) - x(3) + 0.55_dp
      case (10902)
        c = x(3) - x(4) + 0.55_dp
      case (10903)
        c = 2250000.0_dp - x(1)**2 - x(8)**2
      case (10904)
        c = 2250000.0_dp - x(2)**2 - x(9)**2
      case (11401:11408)
        c = hs114_c(j, x)
      case (11601:11615)
        c = hs116_c(j, x)
      case (11701:11705)
        c = 2.0_dp*dot_product(colville_quadratic(:, j), x(11:15)) + 3.0_dp*colville_d(j)*x(10 + j)**2 + colville_e(j) &
            - dot_product([(colville_a(k, j), k = 1, 10)], x(1:10))
      case (11801:11824)
        ! rows j = 1..4 of the stages, per variable of the stage: 0 <= x_{3j+i} - x_{3j-3+i} + 7 <= 13 (14 for i = 2)
        k = (j - 1)/6 + 1
        r = mod(j - 1, 6)
        i = r/2 + 1
        s = x(3*k + i) - x(3*k - 3 + i) + 7.0_dp
        c = merge(s, merge(14.0_dp, 13.0_dp, i == 2) - s, mod(r, 2) == 0)
      case (11825:11829)
        k = j - 24
        c = sum(x(3*k - 2:3*k)) - totals118(k)
      end select
    else
      select case (number*100 + j)
      case (4701)
        c = x(1) + x(2)**2 + x(3)**3 - 3.0_dp
      case (4702)
        c = x(2) - x(3)**2 + x(4) - 1.0_dp
      case (4703)
        c = x(1)*x(5) - 1.0_dp
      case (5401)
        c = x(1) + 4000.0_dp*x(2) - 17600.0_dp
      case (6801, 6901)
        c = x(3) - 2.0_dp*phi(-x(2))
      case (6802, 6902)
        c = x(4) - phi(-x(2) + sqrt(hs68_n(number))) - phi(-x(2) - sqrt(hs68_n(number)))
      case (10701:10706)
        c = hs107_h(j, x)
      case (10901:10906)
        c = hs109_h(j, x)
      case (11101:11103)
        c = hs112_h(j, exp(min(x(1:10), 700.0_dp)))
      case (11201:11203)
        c = hs112_h(j, x(1:10))
      case (11401)
        c = 1.22_dp*x(4) - x(1) - x(5)
      case (11402)
        c = 98000.0_dp*x(3)/pos(x(4)*x(9) + 1000.0_dp*x(3)) - x(6)
      case (11403)
        c = (x(2) + x(5))/pos(x(1)) - x(8)
      end select
    end if
  end function added_c

  !> HS 54's quadratic form h (f = -exp(-h/2)) in the scaled variables.
  pure real(dp) function hs54_h(x) result(h)
    real(dp), intent(in) :: x(:)
    real(dp) :: y(6)
    y = (x(1:6) - [1.0e4_dp, 1.0_dp, 2.0e6_dp, 10.0_dp, 1.0e-3_dp, 1.0e8_dp]) &
        /[8.0e3_dp, 1.0_dp, 7.0e6_dp, 50.0_dp, 0.05_dp, 5.0e8_dp]
    h = (y(1)**2 + 0.4_dp*y(1)*y(2) + y(2)**2)/0.96_dp + sum(y(3:6)**2)
  end function hs54_h

  !> HS 95-98: the four constraint functions (before the constant b_j).
  pure real(dp) function hs95_c(j, x) result(c)
    integer, intent(in) :: j
    real(dp), intent(in) :: x(:)
    select case (j)
    case (1)
      c = 17.1_dp*x(1) + 38.2_dp*x(2) + 204.2_dp*x(3) + 212.3_dp*x(4) + 623.4_dp*x(5) + 1495.5_dp*x(6) &
          - 169.0_dp*x(1)*x(3) - 3580.0_dp*x(3)*x(5) - 3810.0_dp*x(4)*x(5) - 18500.0_dp*x(4)*x(6) - 24300.0_dp*x(5)*x(6)
    case (2)
      c = 17.9_dp*x(1) + 36.8_dp*x(2) + 113.9_dp*x(3) + 169.7_dp*x(4) + 337.8_dp*x(5) + 1385.2_dp*x(6) &
          - 139.0_dp*x(1)*x(3) - 2450.0_dp*x(4)*x(5) - 16600.0_dp*x(4)*x(6) - 17200.0_dp*x(5)*x(6)
    case (3)
      c = -273.0_dp*x(2) - 70.0_dp*x(4) - 819.0_dp*x(5) + 26000.0_dp*x(4)*x(5)
    case default
      c = 159.9_dp*x(1) - 311.0_dp*x(2) + 587.0_dp*x(4) + 391.0_dp*x(5) + 2198.0_dp*x(6) - 14000.0_dp*x(1)*x(6)
    end select
  end function hs95_c

  !> The right-hand sides b_j, the only difference between HS 95, 96, 97, 98.
  pure real(dp) function hs95_b(number, j) result(b)
    integer, intent(in) :: number, j
    real(dp), parameter :: bs(4, 95:98) = reshape([4.97_dp, -1.88_dp, -29.08_dp, -78.02_dp, &
      4.97_dp, -1.88_dp, -69.08_dp, -118.02_dp, 32.97_dp, 25.12_dp, -29.08_dp, -78.02_dp, &
      32.97_dp, 25.12_dp, -124.08_dp, -173.02_dp], [4, 4])
    b = bs(j, number)
  end function hs95_b

  !> HS 101-103's variables continued outside [1e-6, 1e6] (the box is [0.01,
  !> 10]): trial points of B11 may leave it, and a posynomial of up to ten
  !> factors with powers to 3 of a variable near 0 overflows (pos's 1e-150
  !> is too small here).
  elemental real(dp) function clamp101(v)
    real(dp), intent(in) :: v
    clamp101 = min(max(v, 1.0e-6_dp), 1.0e6_dp)
  end function clamp101

  !> HS 101-103's posynomial objective (they differ in the exponent a of x7).
  pure real(dp) function hs101_f(number, xx) result(f)
    integer, intent(in) :: number
    real(dp), intent(in) :: xx(:)
    real(dp) :: x(7), a
    x = clamp101(xx(1:7))
    a = merge(-0.25_dp, merge(0.125_dp, 0.5_dp, number == 102), number == 101)
    f = 10.0_dp*x(1)*x(4)**2*x(7)**a/(x(2)*x(6)**3) + 15.0_dp*x(3)*x(4)/(x(1)*x(2)**2*x(5)*x(7)**0.5_dp) &
        + 20.0_dp*x(2)*x(6)/(x(1)**2*x(4)*x(5)**2) + 25.0_dp*x(1)**2*x(2)**2*x(5)**0.5_dp*x(7)/(x(3)*x(6)**2)
  end function hs101_f

  !> HS 101-103's four posynomial constraints 1 - Sum t_k >= 0.
  pure real(dp) function hs101_c(j, xx) result(c)
    integer, intent(in) :: j
    real(dp), intent(in) :: xx(:)
    real(dp) :: x(7)
    real(dp), parameter :: third = 1.0_dp/3.0_dp
    x = clamp101(xx(1:7))
    select case (j)
    case (1)
      c = 1.0_dp - 0.5_dp*x(1)**0.5_dp*x(7)/(x(3)*x(6)**2) - 0.7_dp*x(1)**3*x(2)*x(6)*x(7)**0.5_dp/x(3)**2 &
          - 0.2_dp*x(3)*x(6)**(2*third)*x(7)**0.25_dp/(x(2)*x(4)**0.5_dp)
    case (2)
      c = 1.0_dp - 1.3_dp*x(2)*x(6)/(x(1)**0.5_dp*x(3)*x(5)) - 0.8_dp*x(3)*x(6)**2/(x(4)*x(5)) &
          - 3.1_dp*x(2)**0.5_dp*x(6)**third/(x(1)*x(4)**2*x(5))
    case (3)
      c = 1.0_dp - 2.0_dp*x(1)*x(5)*x(7)**third/(x(3)**1.5_dp*x(6)) - 0.1_dp*x(2)*x(5)/(x(3)**0.5_dp*x(6)*x(7)**0.5_dp) &
          - x(2)*x(3)**0.5_dp*x(5)/x(1) - 0.65_dp*x(3)*x(5)*x(7)/(x(2)**2*x(6))
    case default
      c = 1.0_dp - 0.2_dp*x(2)*x(5)**0.5_dp*x(7)**third/(x(1)**2*x(4)) &
          - 0.3_dp*x(1)**0.5_dp*x(2)**2*x(3)*x(4)**third*x(7)**0.25_dp/x(5)**(2*third) &
          - 0.4_dp*x(3)*x(5)*x(7)**0.75_dp/(x(1)**3*x(2)**2) - 0.5_dp*x(4)*x(7)**0.5_dp/x(3)**2
    end select
  end function hs101_c

  !> HS 107's six power-flow equalities.
  pure real(dp) function hs107_h(j, x) result(h)
    integer, intent(in) :: j
    real(dp), intent(in) :: x(:)
    real(dp) :: y1, y2, y3, y4, y5, y6
    real(dp), parameter :: c = c107, d = d107
    y1 = sin(x(8)); y2 = cos(x(8)); y3 = sin(x(9)); y4 = cos(x(9)); y5 = sin(x(8) - x(9)); y6 = cos(x(8) - x(9))
    select case (j)
    case (1)
      h = 0.4_dp - x(1) + 2.0_dp*c*x(5)**2 - x(5)*x(6)*(d*y1 + c*y2) - x(5)*x(7)*(d*y3 + c*y4)
    case (2)
      h = 0.4_dp - x(2) + 2.0_dp*c*x(6)**2 + x(5)*x(6)*(d*y1 - c*y2) + x(6)*x(7)*(d*y5 - c*y6)
    case (3)
      h = 0.8_dp + 2.0_dp*c*x(7)**2 + x(5)*x(7)*(d*y3 - c*y4) - x(6)*x(7)*(d*y5 + c*y6)
    case (4)
      h = 0.2_dp - x(3) + 2.0_dp*d*x(5)**2 + x(5)*x(6)*(c*y1 - d*y2) + x(5)*x(7)*(c*y3 - d*y4)
    case (5)
      h = 0.2_dp - x(4) + 2.0_dp*d*x(6)**2 - x(5)*x(6)*(c*y1 + d*y2) - x(6)*x(7)*(c*y5 + d*y6)
    case default
      h = -0.337_dp + 2.0_dp*d*x(7)**2 - x(5)*x(7)*(c*y3 + d*y4) + x(6)*x(7)*(c*y5 - d*y6)
    end select
  end function hs107_h

  !> HS 108's thirteen inequalities (the hexagon of largest area).
  pure real(dp) function hs108_c(j, x) result(c)
    integer, intent(in) :: j
    real(dp), intent(in) :: x(:)
    select case (j)
    case (1)
      c = 1.0_dp - x(3)**2 - x(4)**2
    case (2)
      c = 1.0_dp - x(9)**2
    case (3)
      c = 1.0_dp - x(5)**2 - x(6)**2
    case (4)
      c = 1.0_dp - x(1)**2 - (x(2) - x(9))**2
    case (5)
      c = 1.0_dp - (x(1) - x(5))**2 - (x(2) - x(6))**2
    case (6)
      c = 1.0_dp - (x(1) - x(7))**2 - (x(2) - x(8))**2
    case (7)
      c = 1.0_dp - (x(3) - x(5))**2 - (x(4) - x(6))**2
    case (8)
      c = 1.0_dp - (x(3) - x(7))**2 - (x(4) - x(8))**2
    case (9)
      c = 1.0_dp - x(7)**2 - (x(8) - x(9))**2
    case (10)
      c = x(1)*x(4) - x(2)*x(3)
    case (11)
      c = x(3)*x(9)
    case (12)
      c = -x(5)*x(9)
    case default
      c = x(5)*x(8) - x(6)*x(7)
    end select
  end function hs108_c

  !> HS 109's six equalities.
  pure real(dp) function hs109_h(j, x) result(h)
    integer, intent(in) :: j
    real(dp), intent(in) :: x(:)
    real(dp), parameter :: a = a109, b = sin025, c = cos025
    select case (j)
    case (1)
      h = x(5)*x(6)*sin(-x(3) - 0.25_dp) + x(5)*x(7)*sin(-x(4) - 0.25_dp) + 2.0_dp*b*x(5)**2 - a*x(1) + 400.0_dp*a
    case (2)
      h = x(5)*x(6)*sin(x(3) - 0.25_dp) + x(6)*x(7)*sin(x(3) - x(4) - 0.25_dp) + 2.0_dp*b*x(6)**2 - a*x(2) + 400.0_dp*a
    case (3)
      h = x(5)*x(7)*sin(x(4) - 0.25_dp) + x(6)*x(7)*sin(x(4) - x(3) - 0.25_dp) + 2.0_dp*b*x(7)**2 + 881.779_dp*a
    case (4)
      h = a*x(8) + x(5)*x(6)*cos(-x(3) - 0.25_dp) + x(5)*x(7)*cos(-x(4) - 0.25_dp) - 200.0_dp*a - 2.0_dp*c*x(5)**2 &
          + 0.7533e-3_dp*a*x(5)**2
    case (5)
      h = a*x(9) + x(5)*x(6)*cos(x(3) - 0.25_dp) + x(6)*x(7)*cos(x(3) - x(4) - 0.25_dp) - 2.0_dp*c*x(6)**2 &
          + 0.7533e-3_dp*a*x(6)**2 - 200.0_dp*a
    case default
      h = x(5)*x(7)*cos(x(4) - 0.25_dp) + x(6)*x(7)*cos(x(4) - x(3) - 0.25_dp) - 2.0_dp*c*x(7)**2 - 22.938_dp*a &
          + 0.7533e-3_dp*a*x(7)**2
    end select
  end function hs109_h

  !> HS 111 and 112: Gibbs free energy of the ten species (HS 111 in x = ln of HS 112's amounts).
  pure real(dp) function hs112_f(y) result(f)
    real(dp), intent(in) :: y(:)
    real(dp), parameter :: cj(10) = [-6.089_dp, -17.164_dp, -34.054_dp, -5.914_dp, -24.721_dp, -14.986_dp, -24.1_dp, &
                                     -10.708_dp, -26.662_dp, -22.179_dp]
    f = sum(y*(cj + log(pos(y)/pos(sum(y)))))
  end function hs112_f

  !> HS 111 and 112: the three element balances.
  pure real(dp) function hs112_h(j, y) result(h)
    integer, intent(in) :: j
    real(dp), intent(in) :: y(:)
    select case (j)
    case (1)
      h = y(1) + 2.0_dp*y(2) + 2.0_dp*y(3) + y(6) + y(10) - 2.0_dp
    case (2)
      h = y(4) + 2.0_dp*y(5) + y(6) + y(7) - 1.0_dp
    case default
      h = y(3) + y(7) + y(8) + 2.0_dp*y(9) + y(10) - 1.0_dp
    end select
  end function hs112_h

  !> HS 114 (alkylation process): the eight inequalities.
  pure real(dp) function hs114_c(j, x) result(c)
    integer, intent(in) :: j
    real(dp), intent(in) :: x(:)
    real(dp) :: g1, g2, g5, g6
    g1 = 35.82_dp - 0.222_dp*x(10) - b114*x(9)
    g2 = -133.0_dp + 3.0_dp*x(7) - a114*x(10)
    g5 = 1.12_dp*x(1) + 0.13167_dp*x(1)*x(8) - 0.00667_dp*x(1)*x(8)**2 - a114*x(4)
    g6 = 57.425_dp + 1.098_dp*x(8) - 0.038_dp*x(8)**2 + 0.325_dp*x(6) - a114*x(7)
    select case (j)
    case (1)
      c = g1
    case (2)
      c = g2
    case (3)
      c = -g1 + x(9)*(1.0_dp/b114 - b114)
    case (4)
      c = -g2 + (1.0_dp/a114 - a114)*x(10)
    case (5)
      c = g5
    case (6)
      c = g6
    case (7)
      c = -g5 + (1.0_dp/a114 - a114)*x(4)
    case default
      c = -g6 + (1.0_dp/a114 - a114)*x(7)
    end select
  end function hs114_c

  !> HS 116 (three-stage membrane separation): the fifteen inequalities.
  pure real(dp) function hs116_c(j, x) result(c)
    integer, intent(in) :: j
    real(dp), intent(in) :: x(:)
    real(dp), parameter :: a = 0.002_dp, b = 1.262626_dp, cc = 1.231059_dp, d = 0.03475_dp, e = 0.975_dp, f = 0.00975_dp
    select case (j)
    case (1)
      c = x(3) - x(2)
    case (2)
      c = x(2) - x(1)
    case (3)
      c = 1.0_dp - a*x(7) + a*x(8)
    case (4)
      c = x(11) + x(12) + x(13) - 50.0_dp
    case (5)
      c = x(13) - b*x(10) + cc*x(3)*x(10)
    case (6)
      c = x(5) - d*x(2) - e*x(2)*x(5) + f*x(2)**2
    case (7)
      c = x(6) - d*x(3) - e*x(3)*x(6) + f*x(3)**2
    case (8)
      c = x(4) - d*x(1) - e*x(1)*x(4) + f*x(1)**2
    case (9)
      c = x(12) - b*x(9) + cc*x(2)*x(9)
    case (10)
      c = x(11) - b*x(8) + cc*x(1)*x(8)
    case (11)
      c = x(5)*x(7) - x(1)*x(8) - x(4)*x(7) + x(4)*x(8)
    case (12)
      c = 1.0_dp - a*(x(2)*x(9) + x(5)*x(8) - x(1)*x(8) - x(6)*x(9)) - x(5) - x(6)
    case (13)
      c = x(2)*x(9) - x(3)*x(10) - x(6)*x(9) - 500.0_dp*x(2) + 500.0_dp*x(6) + x(2)*x(10)
    case (14)
      c = x(2) - 0.9_dp - a*(x(2)*x(10) - x(3)*x(10))
    case default
      c = 250.0_dp - x(11) - x(12) - x(13)
    end select
  end function hs116_c

  !> Colville's constraint rows a_k (HS 86: a_k^T x >= b_k; HS 117: the
  !> columns of the same matrix), element (k, j).
  pure real(dp) function colville_a(k, j) result(a)
    integer, intent(in) :: k, j
    real(dp), parameter :: rows(5, 10) = reshape([-16.0_dp, 2.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, &
      0.0_dp, -2.0_dp, 0.0_dp, 4.0_dp, 2.0_dp, -3.5_dp, 0.0_dp, 2.0_dp, 0.0_dp, 0.0_dp, &
      0.0_dp, -2.0_dp, 0.0_dp, -4.0_dp, -1.0_dp, 0.0_dp, -9.0_dp, -2.0_dp, 1.0_dp, -2.8_dp, &
      2.0_dp, 0.0_dp, -4.0_dp, 0.0_dp, 0.0_dp, -1.0_dp, -1.0_dp, -1.0_dp, -1.0_dp, -1.0_dp, &
      -1.0_dp, -2.0_dp, -3.0_dp, -2.0_dp, -1.0_dp, 1.0_dp, 2.0_dp, 3.0_dp, 4.0_dp, 5.0_dp, &
      1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp, 1.0_dp], [5, 10])
    a = rows(j, k)
  end function colville_a

  pure real(dp) function colville_b(k) result(b)
    integer, intent(in) :: k
    real(dp), parameter :: bs(10) = [-40.0_dp, -2.0_dp, -0.25_dp, -4.0_dp, -4.0_dp, -1.0_dp, -40.0_dp, -60.0_dp, &
                                     5.0_dp, 1.0_dp]
    b = bs(k)
  end function colville_b
end module hs_collection_added
