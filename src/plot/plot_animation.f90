!> The deformed mechanism drawn from a transient or steady output:
!>   `flexmech plot RUN.out --animate [--magnify F]`: an animated GIF of the
!>     last revolution (at most 90 frames), <base>_anim.gif, .gp, .dat;
!>   every plot of such a run: the still <base>_shape (PNG, SVG), the
!>     deformed mechanism at the output time of the largest stress of the last
!>     revolution, a figure of the standard script.
!>
!> The rigid-body positions are not in the output; they are recomputed from
!> the &mechanism group echoed in its header (the same kinematics as the run,
!> at each row's time t).  A link is drawn bent when the output has its shape
!> columns <link>_s<x>_u, _w (elastic displacement of the link point at x
!> times its length, in the link's rigid-body axes, evaluated by the run from
!> the element's own shape functions: deck `shape_points = k` writes k + 1
!> points per element); otherwise straight between its displaced joints
!> (<joint>_U, <joint>_W, global X, Y), and the frame says so.  Each link is
!> coloured by the stress of its elements (|sigma_b_e<k>|, the bending
!> stress, when the output has it; else sigma_max_e<k>, the outer-fibre
!> stress), on a colour bar fixed over the frames.  Displacements are
!> multiplied by F (default: 1, 2 or 5 times a power of ten that makes the
!> largest one at most a quarter of the mean link length), stated on the frame.
module plot_animation
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, lower, starts_with
  use deck_reader, only: deck_t
  use linkage, only: mechanism_t
  use linkage_deck, only: read_mechanism
  use kinematics, only: kinematics_t
  use run_output, only: run_output_t, column_index, column_unit
  use plot_script, only: esc, begin_figure, end_figure, number_text
  implicit none
  private
  public :: write_animation, append_shape_figure, nice_factor, link_shapes, link_shape_t, drawn_frame
  public :: last_revolution_rows, header_group_file, open_animation_script, frame_text, factor_text, unit_text, &
            sorted   ! shared with plot_spatial

  integer, parameter :: max_frames = 90

  !> How one link is drawn: its points (fractions s of its length), the
  !> columns of their displacements and the stress column of each point's element.
  type :: link_shape_t
    logical :: bent = .false.                      !< from shape columns (local u, w); else joints (global U, W)
    real(dp), allocatable :: s(:)
    integer, allocatable :: ju(:), jw(:), jsig(:)  !< 0: no column (held at zero)
  end type link_shape_t

  !> The drawing of a run: the mechanism, its links' shapes, the frames' rows.
  type :: drawing_t
    type(mechanism_t) :: mech
    type(link_shape_t), allocatable :: shapes(:)
    integer, allocatable :: rows(:)
    real(dp), allocatable :: rigid(:, :, :, :)     !< (xy, point, link, frame)
    real(dp), allocatable :: disp(:, :, :, :)      !< elastic displacement, global (xy, point, link, frame)
    real(dp), allocatable :: sigma(:, :, :)        !< |stress| (point, link, frame)
    real(dp), allocatable :: joints(:, :, :)       !< rigid joint positions (xy, joint, frame)
    real(dp) :: factor = 1.0_dp
    integer :: n_points = 0                        !< the most points of a link
    character(len=:), allocatable :: stress_label
  end type drawing_t

contains

  !> Writes base_anim.dat and base_anim.gp (which draws base_anim.gif).
  !> magnify <= 0: automatic.  n_frames: frames written.
  subroutine write_animation(out, base, magnify, n_frames, err)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    real(dp), intent(in) :: magnify
    integer, intent(out) :: n_frames
    type(error_t), intent(inout) :: err
    type(drawing_t) :: d
    n_frames = 0
    call mechanism_from_header(out, base//'_anim.nml', d%mech, err)
    if (err%failed()) return
    call last_revolution_rows(out, d%rows, max_frames)
    call build_drawing(out, d, magnify, err)
    if (err%failed()) return
    call write_frames(base//'_anim.dat', out, d)
    call write_anim_script(base, out, d)
    n_frames = size(d%rows)
  end subroutine write_animation

  !> The still: appends the figure `shape` to the open standard script (unit
  !> u) and writes its data, base_shape.dat.  Nothing when the output has no
  !> mechanism to draw (no &mechanism group, no joint columns).
  subroutine append_shape_figure(u, out, base, figures, magnify)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    character(len=64), allocatable, intent(inout) :: figures(:)
    real(dp), intent(in) :: magnify      !< <= 0: automatic
    type(drawing_t) :: d
    type(error_t) :: err
    integer, allocatable :: rows(:)
    integer :: peak, f, c, j, i, at
    real(dp) :: smax
    character(len=:), allocatable :: what, how
    if (column_index(out, 't') == 0) return
    call mechanism_from_header(out, base//'_shape.nml', d%mech, err)
    if (err%failed()) return
    call last_revolution_rows(out, rows, huge(1))
    d%rows = rows
    call build_drawing(out, d, magnify, err)
    if (err%failed()) return
    peak = 1                                      ! the frame and link of the largest stress
    at = 1
    smax = -1.0_dp
    do f = 1, size(d%rows)
      do i = 1, d%mech%n_links
        if (maxval(d%sigma(:, i, f)) > smax) then
          smax = maxval(d%sigma(:, i, f))
          peak = f
          at = i
        end if
      end do
    end do
    what = 'the largest '//d%stress_label//' of the '//trim(merge('steady', 'last  ', out%analysis == 'steady'))// &
           ' revolution, '//number_text(smax)
    if (len(unit_text(out, 'sigma_max_e')) > 0) what = what//' '//column_unit(out, 'sigma_max_e')
    what = what//' in '//trim(d%mech%links(at)%name)
    c = column_index(out, 'crank_deg')
    j = column_index(out, 't')
    d%rows = [d%rows(peak)]
    d%rigid = d%rigid(:, :, :, peak:peak)
    d%disp = d%disp(:, :, :, peak:peak)
    d%sigma = d%sigma(:, :, peak:peak)
    d%joints = d%joints(:, :, peak:peak)
    call write_frames(base//'_shape.dat', out, d)
    how = ''                                      ! (straight links: the legend says so)
    if (all(d%shapes(:)%bent)) how = '; links bent by their elements'' shape functions'
    call begin_figure(u, 'shape', 'deformed shape at '//what, figures)
    write(u, '(a)') '  set title title."\n'//esc('deformed shape at '//what)//'\n'// &
      esc(frame_text(out, d%rows(1), c, j))//how//'; elastic displacements x '//factor_text(d%factor)// &
      solution_text(out)//'"'
    write(u, '(a)') '  sdata = "'//esc(base)//'_shape.dat"'
    call frame_settings(u, out, d, '  ')
    call plot_frame(u, d, 'sdata', '0', '  ')
    call end_figure(u)
  end subroutine append_shape_figure

  !> The drawn links of output row `row` (x y, point, link; a link's last
  !> point repeated up to the longest link's count): rigid + magnify x elastic.
  subroutine drawn_frame(out, row, magnify, drawn, err)
    type(run_output_t), intent(in) :: out
    integer, intent(in) :: row
    real(dp), intent(in) :: magnify
    real(dp), allocatable, intent(out) :: drawn(:, :, :)
    type(error_t), intent(inout) :: err
    type(drawing_t) :: d
    call mechanism_from_header(out, 'drawn_frame.nml', d%mech, err)
    if (err%failed()) return
    d%rows = [row]
    call build_drawing(out, d, magnify, err)
    if (err%failed()) return
    drawn = d%rigid(:, :, :, 1) + d%factor*d%disp(:, :, :, 1)
  end subroutine drawn_frame

  !> Shapes, rigid positions, displacements, stresses and the factor of the
  !> rows d%rows.
  subroutine build_drawing(out, d, magnify, err)
    type(run_output_t), intent(in) :: out
    type(drawing_t), intent(inout) :: d
    real(dp), intent(in) :: magnify
    type(error_t), intent(inout) :: err
    type(kinematics_t) :: kin
    integer :: it, f, i, k, j1, j2, row, n
    real(dp) :: p1(2), p2(2), ex(2), ey(2), uw(2), dmax
    it = column_index(out, 't')
    if (it == 0 .or. size(out%data, 1) < 1) then
      call err%set('animate', out%path//' has no t column or no rows: nothing to draw', 3)
      return
    end if
    call link_shapes(out, d%mech, d%shapes, d%stress_label)
    if (.not. any([(any(d%shapes(i)%ju > 0) .or. any(d%shapes(i)%jw > 0), i = 1, size(d%shapes))])) then
      call err%set('animate', out%path//' has no joint displacement columns (<joint>_U, <joint>_W)', 3)
      return
    end if
    d%n_points = maxval([(size(d%shapes(i)%s), i = 1, size(d%shapes))])
    n = size(d%rows)
    allocate(d%rigid(2, d%n_points, d%mech%n_links, n), d%disp(2, d%n_points, d%mech%n_links, n), &
             d%sigma(d%n_points, d%mech%n_links, n), d%joints(2, d%mech%n_joints, n))
    d%rigid = 0.0_dp
    d%disp = 0.0_dp
    d%sigma = 0.0_dp
    call kin%init(d%mech, err)
    if (err%failed()) return
    do f = 1, n
      row = d%rows(f)
      call kin%solve(out%data(row, it), err)
      if (err%failed()) return
      do i = 1, d%mech%n_joints
        d%joints(:, i, f) = kin%joint_position(i)
      end do
      do i = 1, d%mech%n_links
        j1 = d%mech%links(i)%joint(1)
        j2 = d%mech%links(i)%joint(2)
        p1 = kin%joint_position(j1)
        p2 = kin%joint_position(j2)
        ex = (p2 - p1)/max(norm2(p2 - p1), tiny(1.0_dp))
        ey = [-ex(2), ex(1)]
        associate (sh => d%shapes(i))
          do k = 1, size(sh%s)
            d%rigid(:, k, i, f) = p1 + sh%s(k)*(p2 - p1)
            uw = [value_of(sh%ju(k)), value_of(sh%jw(k))]
            if (sh%bent) then
              d%disp(:, k, i, f) = uw(1)*ex + uw(2)*ey
            else
              d%disp(:, k, i, f) = uw
            end if
            d%sigma(k, i, f) = abs(value_of(sh%jsig(k)))
          end do
          do k = size(sh%s) + 1, d%n_points      ! padding: repeats the last point
            d%rigid(:, k, i, f) = d%rigid(:, size(sh%s), i, f)
            d%disp(:, k, i, f) = d%disp(:, size(sh%s), i, f)
            d%sigma(k, i, f) = d%sigma(size(sh%s), i, f)
          end do
        end associate
      end do
    end do
    dmax = maxval(norm2(d%disp, dim=1))
    d%factor = magnify
    if (d%factor <= 0.0_dp) then
      d%factor = 1.0_dp
      if (dmax > 0.0_dp) d%factor = nice_factor(0.25_dp*d%mech%length_scale/dmax)
    end if
  contains
    real(dp) function value_of(j)
      integer, intent(in) :: j
      value_of = 0.0_dp
      if (j > 0) value_of = out%data(row, j)
    end function value_of
  end subroutine build_drawing

  !> How each link of mech is drawn from the columns of out: bent from its
  !> shape columns <link>_s<x>_u, _w (sorted by x, both ends present), or
  !> straight between the displacements of its joints.  stress_label: what the
  !> colours are.
  subroutine link_shapes(out, mech, shapes, stress_label)
    type(run_output_t), intent(in) :: out
    type(mechanism_t), intent(in) :: mech
    type(link_shape_t), allocatable, intent(out) :: shapes(:)
    character(len=:), allocatable, intent(out) :: stress_label
    integer :: i, j, k, n, ne, first, ios, jw
    real(dp) :: x
    character(len=:), allocatable :: nm, prefix, sig
    real(dp), allocatable :: s(:)
    integer, allocatable :: ju(:)
    sig = 'sigma_max_e'
    stress_label = '|stress| (outer fibre)'
    if (column_index(out, 'sigma_b_e1') > 0) then
      sig = 'sigma_b_e'
      stress_label = '|bending stress|'
    end if
    allocate(shapes(mech%n_links))
    do i = 1, mech%n_links
      prefix = trim(mech%links(i)%name)//'_s'
      allocate(s(0), ju(0))
      do j = 1, out%n_columns()
        nm = out%names(j)%s
        if (.not. starts_with(nm, prefix) .or. len(nm) < len(prefix) + 3) cycle
        if (nm(len(nm) - 1:) /= '_u') cycle
        read(nm(len(prefix) + 1:len(nm) - 2), *, iostat=ios) x
        if (ios /= 0) cycle
        if (column_index(out, nm(1:len(nm) - 2)//'_w') == 0) cycle
        s = [s, x]
        ju = [ju, j]
      end do
      first = mech%links(i)%first_element
      ne = mech%links(i)%n_elements
      if (size(s) >= 2) then
        ju = ju(sorted(s))
        s = s(sorted(s))
        if (s(1) <= 1.0e-4_dp .and. s(size(s)) >= 1.0_dp - 1.0e-4_dp) then
          shapes(i)%bent = .true.
          shapes(i)%s = s
          shapes(i)%ju = ju
          allocate(shapes(i)%jw(size(s)))
          do k = 1, size(s)
            nm = out%names(shapes(i)%ju(k))%s
            shapes(i)%jw(k) = column_index(out, nm(1:len(nm) - 2)//'_w')
          end do
        end if
      end if
      if (.not. shapes(i)%bent) then
        shapes(i)%s = [0.0_dp, 1.0_dp]
        shapes(i)%ju = [(column_index(out, trim(mech%joints(mech%links(i)%joint(k))%name)//'_U'), k = 1, 2)]
        shapes(i)%jw = [(column_index(out, trim(mech%joints(mech%links(i)%joint(k))%name)//'_W'), k = 1, 2)]
      end if
      n = size(shapes(i)%s)
      allocate(shapes(i)%jsig(n))
      do k = 1, n             ! the element of each point (an interior element end: the one before)
        jw = first + min(ne - 1, max(0, ceiling(shapes(i)%s(k)*ne - 1.0e-9_dp) - 1))
        shapes(i)%jsig(k) = column_index(out, sig//str(jw))
      end do
      deallocate(s, ju)
    end do
  end subroutine link_shapes

  !> The permutation that sorts x (insertion sort: a link has few points).
  pure function sorted(x) result(p)
    real(dp), intent(in) :: x(:)
    integer :: p(size(x))
    integer :: i, j, t
    p = [(i, i = 1, size(x))]
    do i = 2, size(x)
      j = i
      do while (j > 1)
        if (x(p(j - 1)) <= x(p(j))) exit
        t = p(j)
        p(j) = p(j - 1)
        p(j - 1) = t
        j = j - 1
      end do
    end do
  end function sorted

  !> The rows of the last revolution (all rows when the run is shorter or the
  !> driver does not turn), at most `most` of them, evenly picked.
  subroutine last_revolution_rows(out, rows, most)
    type(run_output_t), intent(in) :: out
    integer, allocatable, intent(out) :: rows(:)
    integer, intent(in) :: most
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
    step = max(1, (n - first)/most + 1)
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
    integer :: u
    call header_group_file(out, 'mechanism', path, err)
    if (err%failed()) return
    call deck%open(path, err)
    if (.not. err%failed()) call read_mechanism(deck, mech, err)
    call deck%close()
    open(newunit=u, file=path, status='old')
    close(u, status='delete')
    if (err%failed()) call err%add_context('animate: the mechanism echoed in '//out%path)
  end subroutine mechanism_from_header

  !> Writes the group &<group> of the output's echoed input to `path` (a deck
  !> of that one group); an error (status 3) when the header has none.
  subroutine header_group_file(out, group, path, err)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: group, path
    type(error_t), intent(inout) :: err
    integer :: u, i, first
    first = 0
    do i = 1, size(out%header)
      if (lower(trim(out%header(i)%s)) == '&'//group) then
        first = i
        exit
      end if
    end do
    if (first == 0) then
      call err%set('animate', out%path//' has no &'//group//' group in its header: not a mechanism analysis', 3)
      return
    end if
    open(newunit=u, file=path, status='replace', action='write')
    do i = first, size(out%header)
      write(u, '(a)') out%header(i)%s
      if (out%header(i)%s == '/') exit
    end do
    close(u)
  end subroutine header_group_file

  !> Two gnuplot data blocks per frame: the links (x_rigid y_rigid x_deformed
  !> y_deformed |stress|, a blank line after each link), then the joints
  !> (x_rigid y_rigid x_deformed y_deformed).
  subroutine write_frames(path, out, d)
    character(len=*), intent(in) :: path
    type(run_output_t), intent(in) :: out
    type(drawing_t), intent(in) :: d
    integer :: u, f, i, k, ic, e, j
    real(dp) :: dj(2)
    ic = column_index(out, 'crank_deg')
    open(newunit=u, file=path, status='replace', action='write')
    write(u, '(a)') '# per frame: the links (x_rigid y_rigid x_deformed y_deformed |stress|), then the joints'// &
      ' (x_rigid y_rigid x_deformed y_deformed); elastic displacements x '//factor_text(d%factor)
    do f = 1, size(d%rows)
      if (ic > 0) write(u, '(a,es16.8)') '# crank_deg ', out%data(d%rows(f), ic)
      do i = 1, d%mech%n_links
        do k = 1, size(d%shapes(i)%s)
          write(u, '(5es16.7)') d%rigid(:, k, i, f), d%rigid(:, k, i, f) + d%factor*d%disp(:, k, i, f), d%sigma(k, i, f)
        end do
        write(u, '(a)') ''
      end do
      write(u, '(a)') ''
      write(u, '(a)') ''
      do j = 1, d%mech%n_joints
        dj = 0.0_dp
        do i = 1, d%mech%n_links             ! the displaced joint: an end of a link that holds it
          do e = 1, 2
            if (d%mech%links(i)%joint(e) /= j) cycle
            dj = d%disp(:, merge(1, size(d%shapes(i)%s), e == 1), i, f)
          end do
        end do
        write(u, '(4es16.7)') d%joints(:, j, f), d%joints(:, j, f) + d%factor*dj
      end do
      write(u, '(a)') ''
      write(u, '(a)') ''
    end do
    close(u)
  end subroutine write_frames

  !> Axes, ranges, colour bar and key shared by the animation and the still.
  subroutine frame_settings(u, out, d, indent)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    type(drawing_t), intent(in) :: d
    character(len=*), intent(in) :: indent
    real(dp) :: lo(2), hi(2), pad, smax
    integer :: k
    character(len=:), allocatable :: lunit
    do k = 1, 2
      lo(k) = min(minval(d%rigid(k, :, :, :)), minval(d%rigid(k, :, :, :) + d%factor*d%disp(k, :, :, :)))
      hi(k) = max(maxval(d%rigid(k, :, :, :)), maxval(d%rigid(k, :, :, :) + d%factor*d%disp(k, :, :, :)))
    end do
    pad = 0.06_dp*max(hi(1) - lo(1), hi(2) - lo(2), d%mech%length_scale)
    smax = maxval(d%sigma)
    if (.not. smax > 0.0_dp) smax = 1.0_dp
    lunit = unit_text(out, '_U')
    write(u, '(a)') indent//'set size ratio -1'
    write(u, '(a)') indent//'set grid lc rgb "#e0e0e0"'
    write(u, '(a)') indent//'set key outside below horizontal'
    write(u, '(a)') indent//'set xrange ['//str(lo(1) - pad, 6)//':'//str(hi(1) + pad, 6)//']'
    write(u, '(a)') indent//'set yrange ['//str(lo(2) - pad, 6)//':'//str(hi(2) + pad, 6)//']'
    write(u, '(a)') indent//'set xlabel "X '//lunit//'"'
    write(u, '(a)') indent//'set ylabel "Y '//lunit//'"'
    write(u, '(a)') indent//'set palette defined (0 "#2c7bb6", 0.25 "#00a6ca", 0.5 "#90d743", 0.75 "#f98e09", 1 "#d7191c")'
    write(u, '(a)') indent//'set cbrange [0:'//str(smax, 4)//']'
    write(u, '(a)') indent//'set cblabel "'//esc(d%stress_label)//' '//unit_text(out, 'sigma_max_e')//'"'
  end subroutine frame_settings

  !> The plot command of frame `index` of the data file named by `var`.
  subroutine plot_frame(u, d, var, index, indent)
    integer, intent(in) :: u
    type(drawing_t), intent(in) :: d
    character(len=*), intent(in) :: var, index, indent
    character(len=:), allocatable :: links, joints, note
    links = var//' index 2*('//index//')'
    joints = var//' index 2*('//index//')+1'
    write(u, '(a)') indent//'plot '//links//' u 1:2 w l lw 7 lc rgb "#d8d8d8" t "rigid-body position", \'
    write(u, '(a)') indent//'     '//joints//' u 1:2 w p pt 6 ps 1.2 lc rgb "#b0b0b0" notitle, \'
    note = ''
    if (.not. all(d%shapes(:)%bent)) note = ' (links straight: no shape columns)'
    write(u, '(a)') indent//'     '//links//' u 3:4:5 w l lw 4 lc palette t "deformed, elastic displacements x '// &
      factor_text(d%factor)//note//'", \'
    write(u, '(a)') indent//'     '//joints//' u 3:4 w p pt 7 ps 1.2 lc rgb "#202020" notitle'
  end subroutine plot_frame

  subroutine write_anim_script(base, out, d)
    character(len=*), intent(in) :: base
    type(run_output_t), intent(in) :: out
    type(drawing_t), intent(in) :: d
    integer :: u
    character(len=:), allocatable :: how
    how = 'bent by their elements'' shape functions'
    if (.not. all(d%shapes(:)%bent)) how = 'links straight between their displaced joints (the output has no '// &
                                           'shape columns: deck shape_points)'
    call open_animation_script(base, out, d%rows, u)
    call frame_settings(u, out, d, '')
    write(u, '(a)') 'do for [i = 0:'//str(size(d%rows) - 1)//'] {'
    write(u, '(a)') '  set title "'//esc(out%title)//'\n'//esc(how)//'; elastic displacements x '// &
      factor_text(d%factor)//'\n".when[i + 1]."'//solution_text(out)//'"'
    call plot_frame(u, d, 'data', 'i', '  ')
    write(u, '(a)') '}'
    write(u, '(a)') 'set output'
    close(u)
  end subroutine write_anim_script

  !> Opens `base`_anim.gp and writes what every animation script starts with:
  !> the GIF terminal, its data file and each frame's crank angle and time
  !> (gnuplot array `when`, one entry per row of `rows`).
  subroutine open_animation_script(base, out, rows, u)
    character(len=*), intent(in) :: base
    type(run_output_t), intent(in) :: out
    integer, intent(in) :: rows(:)
    integer, intent(out) :: u
    integer :: f, ic, it
    ic = column_index(out, 'crank_deg')
    it = column_index(out, 't')
    open(newunit=u, file=base//'_anim.gp', status='replace', action='write')
    write(u, '(a)') '# Animation of '//out%path//', written by `flexmech plot --animate`.'
    write(u, '(a)') '# Rerun with gnuplot from the directory it ran in.'
    write(u, '(a)') 'set terminal gif animate delay 8 loop 0 size 960,760 font ",11" noenhanced'
    write(u, '(a)') 'set output "'//esc(base)//'_anim.gif"'
    write(u, '(a)') 'data = "'//esc(base)//'_anim.dat"'
    write(u, '(a)') 'array when['//str(size(rows))//']'
    do f = 1, size(rows)
      write(u, '(a)') 'when['//str(f)//'] = "'//frame_text(out, rows(f), ic, it)//'"'
    end do
  end subroutine open_animation_script

  !> 'crank angle 290.0 deg of turn 5, t = 1.23E-01 s' of a row: the angle
  !> within its turn (0-360 deg), the turn counted from 1 at crank angle 0.
  function frame_text(out, row, ic, it) result(s)
    type(run_output_t), intent(in) :: out
    integer, intent(in) :: row, ic, it
    character(len=:), allocatable :: s
    character(len=64) :: buf
    real(dp) :: angle, within
    integer :: turn
    s = ''
    if (ic > 0) then
      angle = out%data(row, ic)
      within = modulo(angle, 360.0_dp)
      if (within > 359.95_dp) within = 0.0_dp    ! 359.96 prints as 360.0: the next turn's 0.0
      turn = nint((angle - within)/360.0_dp) + 1
      write(buf, '(f10.1)') within
      s = 'crank angle '//trim(adjustl(buf))//' deg'
      if (turn /= 1) s = s//' of turn '//str(turn)
      s = s//', '
    end if
    write(buf, '(es12.5)') out%data(row, it)
    s = s//'t = '//trim(adjustl(buf))//' s'
  end function frame_text

  !> Which solution a steady run's drawing shows when its output holds two
  !> (method = 'both': the columns without a suffix are the harmonic series').
  function solution_text(out) result(s)
    type(run_output_t), intent(in) :: out
    character(len=:), allocatable :: s
    s = ''
    if (column_index(out, 'sigma_max_e1_exact') > 0) s = '\ndrawn: the harmonic series (columns _exact: the exact '// &
                                                         'periodic solution)'
  end function solution_text

  !> '(unit)' of the columns whose description names `key`, '' when unknown.
  function unit_text(out, key) result(s)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: key
    character(len=:), allocatable :: s
    s = column_unit(out, key)
    if (len(s) > 0) s = '('//s//')'
  end function unit_text

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
