!> The one door to LAPACK: explicit interfaces to the F77 routines flexmech
!> uses, and thin assumed-shape wrappers that turn INFO into a sentence and can
!> report a reciprocal condition number (1-norm).
!>
!> Dense and banded LU (general), dense and banded Cholesky (mass matrices,
!> the transient Newton matrix), symmetric
!> generalized eigenproblem (natural frequencies), nonsymmetric eigenvalues
!> (Floquet multipliers).
module linalg
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  implicit none
  private
  public :: lu_factor, lu_solve, solve_linear
  public :: cholesky_factor, cholesky_solve
  public :: band_cholesky_factor, band_cholesky_solve
  public :: band_lu_factor, band_lu_solve
  public :: sym_generalized_eig, band_generalized_eig, band_eigenvector, symmetric_eigenvalues, identity, eigenvalues_general
  public :: dense_to_lower_band, outer, cross

  interface
    subroutine dgetrf(m, n, a, lda, ipiv, info)
      import :: dp
      integer, intent(in) :: m, n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgetrf
    subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
      import :: dp
      character(len=1), intent(in) :: trans
      integer, intent(in) :: n, nrhs, lda, ldb, ipiv(*)
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgetrs
    subroutine dgecon(norm, n, a, lda, anorm, rcond, work, iwork, info)
      import :: dp
      character(len=1), intent(in) :: norm
      integer, intent(in) :: n, lda
      real(dp), intent(in) :: a(lda, *), anorm
      real(dp), intent(out) :: rcond, work(*)
      integer, intent(out) :: iwork(*), info
    end subroutine dgecon
    subroutine dpotrf(uplo, n, a, lda, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(inout) :: a(lda, *)
      integer, intent(out) :: info
    end subroutine dpotrf
    subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, nrhs, lda, ldb
      real(dp), intent(in) :: a(lda, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpotrs
    subroutine dpocon(uplo, n, a, lda, anorm, rcond, work, iwork, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, lda
      real(dp), intent(in) :: a(lda, *), anorm
      real(dp), intent(out) :: rcond, work(*)
      integer, intent(out) :: iwork(*), info
    end subroutine dpocon
    subroutine dpbtrf(uplo, n, kd, ab, ldab, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, kd, ldab
      real(dp), intent(inout) :: ab(ldab, *)
      integer, intent(out) :: info
    end subroutine dpbtrf
    subroutine dpbtrs(uplo, n, kd, nrhs, ab, ldab, b, ldb, info)
      import :: dp
      character(len=1), intent(in) :: uplo
      integer, intent(in) :: n, kd, nrhs, ldab, ldb
      real(dp), intent(in) :: ab(ldab, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dpbtrs
    subroutine dgbtrf(m, n, kl, ku, ab, ldab, ipiv, info)
      import :: dp
      integer, intent(in) :: m, n, kl, ku, ldab
      real(dp), intent(inout) :: ab(ldab, *)
      integer, intent(out) :: ipiv(*), info
    end subroutine dgbtrf
    subroutine dgbtrs(trans, n, kl, ku, nrhs, ab, ldab, ipiv, b, ldb, info)
      import :: dp
      character(len=1), intent(in) :: trans
      integer, intent(in) :: n, kl, ku, nrhs, ldab, ldb, ipiv(*)
      real(dp), intent(in) :: ab(ldab, *)
      real(dp), intent(inout) :: b(ldb, *)
      integer, intent(out) :: info
    end subroutine dgbtrs
    subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
      import :: dp
      integer, intent(in) :: itype, n, lda, ldb, lwork
      character(len=1), intent(in) :: jobz, uplo
      real(dp), intent(inout) :: a(lda, *), b(ldb, *)
      real(dp), intent(out) :: w(*), work(*)
      integer, intent(out) :: info
    end subroutine dsygv
    subroutine dsbgv(jobz, uplo, n, ka, kb, ab, ldab, bb, ldbb, w, z, ldz, work, info)
      import :: dp
      character(len=1), intent(in) :: jobz, uplo
      integer, intent(in) :: n, ka, kb, ldab, ldbb, ldz
      real(dp), intent(inout) :: ab(ldab, *), bb(ldbb, *)
      real(dp), intent(out) :: w(*), z(ldz, *), work(*)
      integer, intent(out) :: info
    end subroutine dsbgv
    subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
      import :: dp
      character(len=1), intent(in) :: jobvl, jobvr
      integer, intent(in) :: n, lda, ldvl, ldvr, lwork
      real(dp), intent(inout) :: a(lda, *)
      real(dp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
      integer, intent(out) :: info
    end subroutine dgeev
  end interface

  interface lu_solve
    module procedure lu_solve_vec, lu_solve_mat
  end interface lu_solve

contains

  !> LU factorization with partial pivoting (DGETRF), in place.  With `rcond`
  !> present, also estimates the reciprocal 1-norm condition number (DGECON).
  subroutine lu_factor(a, ipiv, err, rcond)
    real(dp), intent(inout) :: a(:, :)
    integer, intent(out) :: ipiv(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: rcond
    integer :: n, info
    real(dp) :: anorm
    real(dp), allocatable :: work(:)
    integer, allocatable :: iwork(:)
    n = size(a, 1)
    if (size(a, 2) /= n .or. size(ipiv) < n) then
      call err%set('lu_factor', 'matrix must be square and ipiv at least n long')
      return
    end if
    anorm = maxval(sum(abs(a), dim=1))
    call dgetrf(n, n, a, n, ipiv, info)
    if (info < 0) then
      call err%set('lu_factor', 'DGETRF: argument '//str(-info)//' has an illegal value')
      return
    else if (info > 0) then
      if (present(rcond)) rcond = 0.0_dp
      call err%set('lu_factor', 'DGETRF: matrix is exactly singular (U('//str(info)//','//str(info)//') = 0)')
      return
    end if
    if (present(rcond)) then
      allocate(work(4*n), iwork(n))
      call dgecon('1', n, a, n, anorm, rcond, work, iwork, info)
      if (info /= 0) call err%set('lu_factor', 'DGECON: argument '//str(-info)//' has an illegal value')
    end if
  end subroutine lu_factor

  subroutine lu_solve_vec(a, ipiv, b, err)
    real(dp), intent(in) :: a(:, :)
    integer, intent(in) :: ipiv(:)
    real(dp), intent(inout), target, contiguous :: b(:)
    type(error_t), intent(inout) :: err
    real(dp), pointer :: b2(:, :)
    b2(1:size(b), 1:1) => b
    call lu_solve_mat(a, ipiv, b2, err)
  end subroutine lu_solve_vec

  subroutine lu_solve_mat(a, ipiv, b, err)
    real(dp), intent(in) :: a(:, :)
    integer, intent(in) :: ipiv(:)
    real(dp), intent(inout) :: b(:, :)
    type(error_t), intent(inout) :: err
    integer :: n, info
    n = size(a, 1)
    call dgetrs('N', n, size(b, 2), a, n, ipiv, b, size(b, 1), info)
    if (info /= 0) call err%set('lu_solve', 'DGETRS: argument '//str(-info)//' has an illegal value')
  end subroutine lu_solve_mat

  !> Solve A x = b (A is not modified); optional reciprocal condition number.
  subroutine solve_linear(a, b, err, rcond)
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(inout), contiguous :: b(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: rcond
    real(dp), allocatable :: lu(:, :)
    integer, allocatable :: ipiv(:)
    allocate(lu(size(a, 1), size(a, 2)), ipiv(size(a, 1)))
    lu = a
    call lu_factor(lu, ipiv, err, rcond)
    if (err%failed()) return
    call lu_solve(lu, ipiv, b, err)
  end subroutine solve_linear

  !> Cholesky factorization A = L L^T (DPOTRF, lower triangle used and
  !> overwritten).  A matrix that is not positive definite is an error that
  !> names the failing leading minor.
  subroutine cholesky_factor(a, err, rcond)
    real(dp), intent(inout) :: a(:, :)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: rcond
    integer :: n, info, j
    real(dp) :: anorm
    real(dp), allocatable :: work(:)
    integer, allocatable :: iwork(:)
    n = size(a, 1)
    anorm = 0.0_dp
    if (present(rcond)) then
      ! 1-norm of the symmetric matrix from its lower triangle
      do j = 1, n
        anorm = max(anorm, sum(abs(a(j:n, j))) + sum(abs(a(j, 1:j - 1))))
      end do
    end if
    call dpotrf('L', n, a, n, info)
    if (info < 0) then
      call err%set('cholesky_factor', 'DPOTRF: argument '//str(-info)//' has an illegal value')
      return
    else if (info > 0) then
      call err%set('cholesky_factor', 'DPOTRF: matrix is not positive definite (leading minor of order ' &
                   //str(info)//' is not positive)')
      return
    end if
    if (present(rcond)) then
      allocate(work(3*n), iwork(n))
      call dpocon('L', n, a, n, anorm, rcond, work, iwork, info)
      if (info /= 0) call err%set('cholesky_factor', 'DPOCON: argument '//str(-info)//' has an illegal value')
    end if
  end subroutine cholesky_factor

  subroutine cholesky_solve(l, b, err)
    real(dp), intent(in) :: l(:, :)
    real(dp), intent(inout), contiguous :: b(:)
    type(error_t), intent(inout) :: err
    integer :: info
    call dpotrs('L', size(l, 1), 1, l, size(l, 1), b, size(b), info)
    if (info /= 0) call err%set('cholesky_solve', 'DPOTRS: argument '//str(-info)//' has an illegal value')
  end subroutine cholesky_solve

  !> Banded Cholesky (DPBTRF) of a symmetric positive definite band matrix in
  !> LAPACK lower band storage ab(1+i-j, j) = A(i, j), j <= i <= j + kd.
  !> Cost O(n kd^2): linear in the number of elements of a beam chain.
  subroutine band_cholesky_factor(ab, kd, err)
    real(dp), intent(inout) :: ab(:, :)
    integer, intent(in) :: kd
    type(error_t), intent(inout) :: err
    integer :: info
    call dpbtrf('L', size(ab, 2), kd, ab, size(ab, 1), info)
    if (info < 0) then
      call err%set('band_cholesky_factor', 'DPBTRF: argument '//str(-info)//' has an illegal value')
    else if (info > 0) then
      call err%set('band_cholesky_factor', 'DPBTRF: matrix is not positive definite (leading minor of order ' &
                   //str(info)//' is not positive)')
    end if
  end subroutine band_cholesky_factor

  subroutine band_cholesky_solve(ab, kd, b, err)
    real(dp), intent(in) :: ab(:, :)
    integer, intent(in) :: kd
    real(dp), intent(inout), contiguous :: b(:)
    type(error_t), intent(inout) :: err
    integer :: info
    call dpbtrs('L', size(ab, 2), kd, 1, ab, size(ab, 1), b, size(b), info)
    if (info /= 0) call err%set('band_cholesky_solve', 'DPBTRS: argument '//str(-info)//' has an illegal value')
  end subroutine band_cholesky_solve

  !> Banded LU with partial pivoting (DGBTRF) of an n x n matrix with kl
  !> sub- and ku super-diagonals in LAPACK general band storage:
  !> ab(kl + ku + 1 + i - j, j) = A(i, j); ab has 2 kl + ku + 1 rows, the first
  !> kl hold the fill-in of the pivoting.  Cost O(n kl (kl + ku)).
  subroutine band_lu_factor(ab, kl, ku, ipiv, err)
    real(dp), intent(inout) :: ab(:, :)
    integer, intent(in) :: kl, ku
    integer, intent(out) :: ipiv(:)
    type(error_t), intent(inout) :: err
    integer :: info, n
    n = size(ab, 2)
    if (size(ab, 1) < 2*kl + ku + 1 .or. size(ipiv) < n) then
      call err%set('band_lu_factor', 'band storage needs 2 kl + ku + 1 = '//str(2*kl + ku + 1)// &
                   ' rows and ipiv n entries')
      return
    end if
    call dgbtrf(n, n, kl, ku, ab, size(ab, 1), ipiv, info)
    if (info < 0) then
      call err%set('band_lu_factor', 'DGBTRF: argument '//str(-info)//' has an illegal value')
    else if (info > 0) then
      call err%set('band_lu_factor', 'DGBTRF: matrix is exactly singular (U('//str(info)//','//str(info)//') = 0)')
    end if
  end subroutine band_lu_factor

  subroutine band_lu_solve(ab, kl, ku, ipiv, b, err)
    real(dp), intent(in) :: ab(:, :)
    integer, intent(in) :: kl, ku, ipiv(:)
    real(dp), intent(inout), contiguous :: b(:)
    type(error_t), intent(inout) :: err
    integer :: info
    call dgbtrs('N', size(ab, 2), kl, ku, 1, ab, size(ab, 1), ipiv, b, size(b), info)
    if (info /= 0) call err%set('band_lu_solve', 'DGBTRS: argument '//str(-info)//' has an illegal value')
  end subroutine band_lu_solve

  !> Copy the lower band (half-bandwidth kd) of a dense symmetric matrix into
  !> LAPACK lower band storage.
  pure subroutine dense_to_lower_band(a, kd, ab)
    real(dp), intent(in) :: a(:, :)
    integer, intent(in) :: kd
    real(dp), intent(out) :: ab(:, :)
    integer :: i, j, n
    n = size(a, 1)
    ab = 0.0_dp
    do j = 1, n
      do i = j, min(n, j + kd)
        ab(1 + i - j, j) = a(i, j)
      end do
    end do
  end subroutine dense_to_lower_band

  !> Generalized symmetric-definite eigenproblem K x = w M x (DSYGV).
  !> Eigenvalues ascending in `w`; with `vectors` present, M-orthonormal
  !> eigenvectors in its columns.
  subroutine sym_generalized_eig(k, m, w, err, vectors)
    real(dp), intent(in) :: k(:, :), m(:, :)
    real(dp), intent(out) :: w(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: vectors(:, :)
    real(dp), allocatable :: a(:, :), b(:, :), work(:)
    integer :: n, info, lwork
    character(len=1) :: jobz
    n = size(k, 1)
    allocate(a(n, n), b(n, n))
    a = k
    b = m
    jobz = 'N'
    if (present(vectors)) jobz = 'V'
    lwork = max(1, 66*n)
    allocate(work(lwork))
    call dsygv(1, jobz, 'L', n, a, n, b, n, w, work, lwork, info)
    if (info < 0) then
      call err%set('sym_generalized_eig', 'DSYGV: argument '//str(-info)//' has an illegal value')
    else if (info > 0 .and. info <= n) then
      call err%set('sym_generalized_eig', 'DSYGV: '//str(info)//' off-diagonal elements failed to converge')
    else if (info > n) then
      call err%set('sym_generalized_eig', 'DSYGV: mass matrix is not positive definite (leading minor of order ' &
                   //str(info - n)//')')
    end if
    if (present(vectors) .and. .not. err%failed()) vectors = a
  end subroutine sym_generalized_eig

  !> The generalized eigenproblem K x = w M x of a banded K and M (half-
  !> bandwidth kd, given dense): eigenvalues ascending in `w` by LAPACK's
  !> banded reduction (DSBGV without vectors, about 12 n^2 kd operations
  !> instead of DSYGV's 9 n^3 or more); with `vectors`, M-orthonormal
  !> eigenvectors by inverse iteration (band_eigenvector).  Same results as
  !> sym_generalized_eig (eigenvectors up to sign, and up to a rotation
  !> inside a cluster of equal eigenvalues).
  subroutine band_generalized_eig(k, m, kd, w, err, vectors)
    real(dp), intent(in) :: k(:, :), m(:, :)
    integer, intent(in) :: kd
    real(dp), intent(out) :: w(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: vectors(:, :)
    real(dp) :: kb(kd + 1, size(k, 1)), mb(kd + 1, size(k, 1)), z(1, 1), work(3*size(k, 1))
    integer :: n, info, mode
    n = size(k, 1)
    call dense_to_lower_band(k, kd, kb)
    call dense_to_lower_band(m, kd, mb)
    call dsbgv('N', 'L', n, kd, kd, kb, kd + 1, mb, kd + 1, w, z, 1, work, info)
    if (info < 0) then
      call err%set('band_generalized_eig', 'DSBGV: argument '//str(-info)//' has an illegal value')
    else if (info > 0 .and. info <= n) then
      call err%set('band_generalized_eig', 'DSBGV: '//str(info)//' off-diagonal elements failed to converge')
    else if (info > n) then
      call err%set('band_generalized_eig', 'DSBGV: mass matrix is not positive definite (leading minor of order ' &
                   //str(info - n)//')')
    end if
    if (err%failed() .or. .not. present(vectors)) return
    do mode = 1, n
      call band_eigenvector(k, m, kd, w, mode, vectors, err)
      if (err%failed()) return
    end do
  end subroutine band_generalized_eig

  !> Column `mode` of `vectors`: the M-normalised eigenvector of eigenvalue
  !> w(mode) (w: all eigenvalues, ascending, from band_generalized_eig) by
  !> inverse iteration on the banded K - sigma M (two O(n kd^2) solves from
  !> sigma just below the eigenvalue), M-orthogonalized against the earlier
  !> modes of its cluster (columns found before, in ascending order).
  subroutine band_eigenvector(k, m, kd, w, mode, vectors, err)
    real(dp), intent(in) :: k(:, :), m(:, :), w(:)
    integer, intent(in) :: kd, mode
    real(dp), intent(inout) :: vectors(:, :)
    type(error_t), intent(inout) :: err
    real(dp), parameter :: cluster = 1.0e-8_dp    !< relative gap below which two eigenvalues are one cluster
    real(dp) :: shifted(3*kd + 1, size(k, 1)), x(size(k, 1)), mx(size(k, 1)), sigma, scale, norm
    integer :: ipiv(size(k, 1)), n, i, j, it, first
    n = size(k, 1)
    ! Gaps and the shift are measured on the eigenvalue's own scale: on the
    ! largest one's (1e16 against 1e6 with the curvature DOFs), the shift of
    ! a low mode would sit nearer the mode below it than its own.  Not below
    ! 1e-4 of the largest: a free mode (zero to round-off) keeps K - sigma M
    ! away from exact singularity.
    scale = 1.0e-4_dp*maxval(abs(w))
    first = 1                           ! the cluster's first mode: a gap from it starts the next
    do i = 2, mode
      if (w(i) - w(first) > cluster*max(abs(w(i)), scale)) first = i
    end do
    sigma = w(mode) - cluster*max(abs(w(mode)), scale)
    shifted = 0.0_dp
    do j = 1, n
      do i = max(1, j - kd), min(n, j + kd)
        shifted(2*kd + 1 + i - j, j) = k(i, j) - sigma*m(i, j)
      end do
    end do
    call band_lu_factor(shifted, kd, kd, ipiv, err)
    if (err%failed()) return
    x = [(1.0_dp + 0.01_dp*modulo(37*i + 11*mode, 101), i = 1, n)]   ! a start of its own: one a cluster's earlier modes lack
    mx = band_m(x)
    do it = 1, 2
      x = mx
      call band_lu_solve(shifted, kd, kd, ipiv, x, err)
      if (err%failed()) return
      if (first < mode) call m_orthogonalize(x, first, mode)
      mx = band_m(x)
      norm = sqrt(max(dot_product(x, mx), tiny(1.0_dp)))
      x = x/norm
      mx = mx/norm
    end do
    vectors(:, mode) = x
  contains
    !> x M-orthogonal to the cluster's modes found before this one
    subroutine m_orthogonalize(x, first, mode)
      real(dp), intent(inout) :: x(:)
      integer, intent(in) :: first, mode
      integer :: p
      do p = first, mode - 1
        x = x - dot_product(vectors(:, p), band_m(x))*vectors(:, p)
      end do
    end subroutine m_orthogonalize
    !> M x within the band: O(n kd)
    pure function band_m(x) result(y)
      real(dp), intent(in) :: x(:)
      real(dp) :: y(size(x))
      integer :: r, c
      y = 0.0_dp
      do c = 1, n
        do r = max(1, c - kd), min(n, c + kd)
          y(r) = y(r) + m(r, c)*x(c)
        end do
      end do
    end function band_m
  end subroutine band_eigenvector

  !> Eigenvalues (ascending) of a symmetric matrix: the generalized
  !> eigensolver with M = I (the inertia and convexity tests of the models,
  !> the design sequence's quadratic model); with `vectors`, orthonormal
  !> eigenvectors in its columns.
  subroutine symmetric_eigenvalues(a, ev, err, vectors)
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(out) :: ev(:)
    type(error_t), intent(inout) :: err
    real(dp), intent(out), optional :: vectors(:, :)
    call sym_generalized_eig(a, identity(size(a, 1)), ev, err, vectors)
  end subroutine symmetric_eigenvalues

  pure function identity(n) result(eye)
    integer, intent(in) :: n
    real(dp) :: eye(n, n)
    integer :: i
    eye = 0.0_dp
    do i = 1, n
      eye(i, i) = 1.0_dp
    end do
  end function identity

  !> Eigenvalues (wr + i wi) of a general square matrix (DGEEV, no vectors).
  subroutine eigenvalues_general(a, wr, wi, err)
    real(dp), intent(in) :: a(:, :)
    real(dp), intent(out) :: wr(:), wi(:)
    type(error_t), intent(inout) :: err
    real(dp), allocatable :: c(:, :), work(:)
    real(dp) :: dummy_left(1, 1), dummy_right(1, 1)
    integer :: n, info, lwork
    n = size(a, 1)
    allocate(c(n, n))
    c = a
    lwork = max(1, 8*n)
    allocate(work(lwork))
    call dgeev('N', 'N', n, c, n, wr, wi, dummy_left, 1, dummy_right, 1, work, lwork, info)
    if (info < 0) then
      call err%set('eigenvalues_general', 'DGEEV: argument '//str(-info)//' has an illegal value')
    else if (info > 0) then
      call err%set('eigenvalues_general', 'DGEEV: QR algorithm failed; eigenvalues '//str(info + 1)// &
                   ' onward not computed')
    end if
  end subroutine eigenvalues_general
  !> The outer product x y^T (the element routines' rank-one terms).
  pure function outer(x, y) result(m)
    real(dp), intent(in) :: x(:), y(:)
    real(dp) :: m(size(x), size(y))
    integer :: j
    do j = 1, size(y)
      m(:, j) = x*y(j)
    end do
  end function outer

  !> The vector product a x b of two 3-vectors (the spatial element and kinematics).
  pure function cross(a, b) result(c)
    real(dp), intent(in) :: a(3), b(3)
    real(dp) :: c(3)
    c = [a(2)*b(3) - a(3)*b(2), a(3)*b(1) - a(1)*b(3), a(1)*b(2) - a(2)*b(1)]
  end function cross
end module linalg
