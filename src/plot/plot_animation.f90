!> `flexmech plot RUN.out --animate [--magnify F]`: the deformed mechanism over
!> its last revolution as an animated GIF (gnuplot's gif terminal), for
!> teaching.
!>
!> The rigid-body positions are not in the output; they are recomputed from
!> the &mechanism group echoed in its header (the same kinematics as the run,
!> at each row's time t).  The output holds the elastic displacement of every
!> joint whose translation is free (<joint>_U, <joint>_W, global X, Y) and
!> nothing of the links' interiors, so each link is drawn straight between its
!> displaced ends, over the rigid mechanism in grey.  Displacements are
!> multiplied by F (default: 1, 2 or 5 times a power of ten that makes the
!> largest one at most a quarter of the mean link length), stated in the title.
module plot_animation
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower, starts_with
  use deck_reader, only: deck_t
  use linkage, only: mechanism_t
  use linkage_deck, only: read_mechanism
  use kinematics, only: kinematics_t
  use run_output, only: run_output_t, column_index
  use plot_script, only: esc
  implicit none
  private
  public :: write_animation

  integer, parameter :: max_frames = 90

contains

  !> Writes base_anim.dat and base_anim.gp (which draws base_anim.gif).
  !> magnify <= 0: automatic.  n_frames: frames written.
  subroutine write_animation(out, base, magnify, n_frames, err)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    real(dp), intent(in) :: magnify
    integer, intent(out) :: n_frames
    type(error_t), intent(inout) :: err
    type(mechanism_t) :: mech
    type(kinematics_t) :: kin
    integer, allocatable :: rows(:), ju(:), jw(:)
    real(dp), allocatable :: p(:, :, :), d(:, :, :)     ! (xy, joint, frame): rigid position, displacement
    real(dp) :: factor, dmax
    integer :: f, j, it
    n_frames = 0
    call mechanism_from_header(out, base//'_anim.nml', mech, err)
    if (err%failed()) return
    it = column_index(out, 't')
    if (it == 0 .or. size(out%data, 1) < 2) then
      call err%set('animate', out%path//' has no t column or fewer than two rows: nothing to animate', 3)
      return
    end if
    call last_revolution_rows(out, rows)
    allocate(ju(mech%n_joints), jw(mech%n_joints))
    do j = 1, mech%n_joints
      ju(j) = column_index(out, trim(mech%joints(j)%name)//'_U')
      jw(j) = column_index(out, trim(mech%joints(j)%name)//'_W')
    end do
    if (all(ju == 0)) then
      call err%set('animate', out%path//' has no joint displacement columns (<joint>_U, <joint>_W)', 3)
      return
    end if
    call kin%init(mech, err)
    if (err%failed()) return
    allocate(p(2, mech%n_joints, size(rows)), d(2, mech%n_joints, size(rows)))
    d = 0.0_dp
    do f = 1, size(rows)
      call kin%solve(out%data(rows(f), it), err)
      if (err%failed()) return
      do j = 1, mech%n_joints
        p(:, j, f) = kin%joint_position(j)
        if (ju(j) > 0) d(1, j, f) = out%data(rows(f), ju(j))
        if (jw(j) > 0) d(2, j, f) = out%data(rows(f), jw(j))
      end do
    end do
    dmax = maxval(abs(d))
    factor = magnify
    if (factor <= 0.0_dp) then
      factor = 1.0_dp
      if (dmax > 0.0_dp) factor = nice_factor(0.25_dp*mech%length_scale/dmax)
    end if
    call write_frames(base//'_anim.dat', mech, out%data(rows, :), column_index(out, 'crank_deg'), p, d, factor)
    call write_script(base, out, mech, p, d, factor, size(rows))
    n_frames = size(rows)
  end subroutine write_animation

  !> The rows of the last revolution (all rows when the run is shorter or the
  !> driver does not turn), at most max_frames of them, evenly picked.
  subroutine last_revolution_rows(out, rows)
    type(run_output_t), intent(in) :: out
    integer, allocatable, intent(out) :: rows(:)
    integer :: ic, n, first, i, step
    ic = column_index(out, 'crank_deg')
    n = size(out%data, 1)
    first = 1
    if (ic > 0) then
      do i = n, 1, -1
        if (out%data(n, ic) - out%data(i, ic) >= 360.0_dp - 1.0e-9_dp) then
          first = i + 1
          exit
        end if
      end do
    end if
    step = max(1, (n - first + 1 + max_frames - 1)/max_frames)
    allocate(rows((n - first)/step + 1))
    do i = 1, size(rows)
      rows(i) = first + (i - 1)*step
    end do
  end subroutine last_revolution_rows

  !> 1, 2 or 5 times a power of ten, at most x.
  pure real(dp) function nice_factor(x) result(f)
    real(dp), intent(in) :: x
    real(dp) :: p
    p = 10.0_dp**floor(log10(x))
    f = p
    if (2.0_dp*p <= x) f = 2.0_dp*p
    if (5.0_dp*p <= x) f = 5.0_dp*p
  end function nice_factor

  !> The &mechanism group of the output's echoed input, read back as a deck.
  subroutine mechanism_from_header(out, path, mech, err)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: path
    type(mechanism_t), intent(out) :: mech
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    integer :: u, i, first
    first = 0
    do i = 1, size(out%header)
      if (starts_with(lower(out%header(i)%s), '&mechanism')) then
        first = i
        exit
      end if
    end do
    if (first == 0) then
      call err%set('animate', out%path//' has no &mechanism group in its header: not a mechanism analysis', 3)
      return
    end if
    open(newunit=u, file=path, status='replace', action='write')
    do i = first, size(out%header)
      write(u, '(a)') out%header(i)%s
      if (out%header(i)%s == '/') exit
    end do
    close(u)
    call deck%open(path, err)
    if (.not. err%failed()) call read_mechanism(deck, mech, err)
    call deck%close()
    open(newunit=u, file=path, status='old')
    close(u, status='delete')
    if (err%failed()) call err%add_context('animate: the mechanism echoed in '//out%path)
  end subroutine mechanism_from_header

  !> One gnuplot data block per frame: per link, its rigid ends (x, y) and
  !> displaced ends (x + F U, y + F W), a blank line after each link.
  subroutine write_frames(path, mech, data, ic, p, d, factor)
    character(len=*), intent(in) :: path
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: data(:, :), p(:, :, :), d(:, :, :), factor
    integer, intent(in) :: ic
    integer :: u, f, i, e, j
    open(newunit=u, file=path, status='replace', action='write')
    write(u, '(a)') '# x_rigid y_rigid x_deformed y_deformed, per link end; one block per frame'
    do f = 1, size(p, 3)
      if (ic > 0) write(u, '(a,es16.8)') '# crank_deg ', data(f, ic)
      do i = 1, mech%n_links
        do e = 1, 2
          j = mech%links(i)%joint(e)
          write(u, '(4es18.9)') p(:, j, f), p(:, j, f) + factor*d(:, j, f)
        end do
        write(u, '(a)') ''
      end do
      write(u, '(a)') ''
    end do
    close(u)
  end subroutine write_frames

  subroutine write_script(base, out, mech, p, d, factor, n)
    character(len=*), intent(in) :: base
    type(run_output_t), intent(in) :: out
    type(mechanism_t), intent(in) :: mech
    real(dp), intent(in) :: p(:, :, :), d(:, :, :), factor
    integer, intent(in) :: n
    integer :: u
    real(dp) :: lo(2), hi(2), pad
    lo = [minval(min(p(1, :, :), p(1, :, :) + factor*d(1, :, :))), minval(min(p(2, :, :), p(2, :, :) + factor*d(2, :, :)))]
    hi = [maxval(max(p(1, :, :), p(1, :, :) + factor*d(1, :, :))), maxval(max(p(2, :, :), p(2, :, :) + factor*d(2, :, :)))]
    pad = 0.05_dp*max(hi(1) - lo(1), hi(2) - lo(2), mech%length_scale)
    open(newunit=u, file=base//'_anim.gp', status='replace', action='write')
    write(u, '(a)') '# Animation of '//out%path//', written by `flexmech plot --animate`.'
    write(u, '(a)') '# Rerun with gnuplot from the directory it ran in.'
    write(u, '(a)') 'set terminal gif animate delay 8 loop 0 size 720,540 noenhanced'
    write(u, '(a)') 'set output "'//base//'_anim.gif"'
    write(u, '(a)') 'set size ratio -1'
    write(u, '(a)') 'set grid'
    write(u, '(a)') 'set key top right'
    write(u, '(a)') 'set xrange ['//str(lo(1) - pad, 8)//':'//str(hi(1) + pad, 8)//']'
    write(u, '(a)') 'set yrange ['//str(lo(2) - pad, 8)//':'//str(hi(2) + pad, 8)//']'
    write(u, '(a)') 'set xlabel "X (in)"'
    write(u, '(a)') 'set ylabel "Y (in)"'
    write(u, '(a)') 'data = "'//base//'_anim.dat"'
    write(u, '(a)') 'do for [i = 0:'//str(n - 1)//'] {'
    write(u, '(a)') '  set title "'//esc(out%title)//'\nelastic displacements x '//factor_text(factor)// &
      ' (links straight between their displaced ends); frame ".(i + 1)." of '//str(n)//'"'
    write(u, '(a)') '  plot data index i u 3:4 w lp lw 4 pt 7 ps 1.2 lc rgb "#0072b2" t "deformed x '// &
      factor_text(factor)//'", \'
    write(u, '(a)') '       data index i u 1:2 w lp lw 1.5 dt 2 pt 6 lc rgb "#404040" t "rigid-body position"'
    write(u, '(a)') '}'
    write(u, '(a)') 'set output'
    close(u)
  end subroutine write_script

  pure function factor_text(f) result(s)
    real(dp), intent(in) :: f
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if (f >= 1.0_dp .and. f < 1.0e9_dp .and. abs(f - anint(f)) <= 1.0e-9_dp*f) then
      write(buf, '(i0)') nint(f)
    else
      write(buf, '(g12.4)') f
    end if
    s = trim(adjustl(buf))
  end function factor_text
end module plot_animation
