!> The deformed spatial four-bar in 3D (gnuplot splot), from a spatial output:
!>   every plot of such a run: the still <base>_shape (PNG, SVG) at the
!>     output time of the largest stress of the last revolution;
!>   `--animate`: <base>_anim.gif over the last revolution (at most 90 frames).
!>
!> The rigid-body positions of the joints A (crank pivot), B, C and D (rocker
!> pivot) are recomputed from the &spatial_mechanism group echoed in the
!> output's header (the run's own kinematics, at each row's crank angle).  A
!> link is drawn bent when the output has its shape columns <link>_s<x>_UX,
!> _UY, _UZ (the elastic translation, global, of the link point at x times its
!> length from its end 1 (crank A-B, coupler B-C, rocker D-C), evaluated by the
!> run from the element's own shape functions: &transient shape_points = k
!> writes k + 1 points per element); otherwise straight between its displaced
!> joints (B_UX ... C_UZ), and the frame says so.  Each link is coloured by the
!> sigma_max_e<k> of its elements (a bent link point by point, a straight one
!> by the largest of its elements), the joint axes of the crank and the rocker
!> are drawn dashed through A and D, the rigid position faint beneath.
module plot_spatial
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, starts_with, lower
  use deck_reader, only: deck_t
  use spatial_kinematics, only: spatial_fourbar_t, spatial_pose_t, spatial_fourbar_solve
  use spatial_settings, only: spatial_input_t, read_spatial_mechanism, build_spatial
  use spatial_model, only: spatial_link_t
  use run_output, only: run_output_t, column_index, column_unit
  use plot_script, only: esc, begin_figure, end_figure, number_text
  use plot_animation, only: last_revolution_rows, header_group_file, open_animation_script, frame_text, &
                            factor_text, unit_text, nice_factor, sorted
  implicit none
  private
  public :: write_spatial_animation, append_spatial_shape, spatial_link_shapes, spatial_shape_3d_t, spatial_frame

  integer, parameter :: max_frames = 90
  real(dp), parameter :: pi = acos(-1.0_dp)
  character(len=*), parameter :: link_name(3) = [character(len=7) :: 'crank', 'coupler', 'rocker']
  character(len=1), parameter :: axis(3) = ['X', 'Y', 'Z']

  !> How one link is drawn: its points (fractions s of its length from end
  !> 1), the columns of their global translations and of their stresses.
  type :: spatial_shape_3d_t
    logical :: bent = .false.                  !< from shape columns; else straight between its joints
    real(dp), allocatable :: s(:)
    integer, allocatable :: cols(:, :)         !< (X Y Z, point); 0: no column (held at zero)
    integer, allocatable :: jsig(:, :)         !< (element, point): the stress columns coloured there (max)
  end type spatial_shape_3d_t

  !> The drawing of a spatial run at the rows `rows`.
  type :: drawing_3d_t
    type(spatial_input_t) :: input
    type(spatial_shape_3d_t) :: shapes(3)
    integer, allocatable :: rows(:)
    integer :: n_points = 2                    !< the most points of a link
    real(dp), allocatable :: joints(:, :, :)   !< rigid positions (xyz, A B C D, frame)
    real(dp), allocatable :: jdisp(:, :, :)    !< elastic translations of the joints (xyz, A B C D, frame)
    real(dp), allocatable :: rigid(:, :, :, :) !< rigid position of the link points (xyz, point, link, frame)
    real(dp), allocatable :: disp(:, :, :, :)  !< their elastic translations (xyz, point, link, frame)
    real(dp), allocatable :: sigma(:, :, :)    !< |stress| (point, link, frame)
    real(dp) :: factor = 1.0_dp, scale = 1.0_dp
  end type drawing_3d_t

  !> The links' joints: crank A-B, coupler B-C, rocker D-C.
  integer, parameter :: link_ends(2, 3) = reshape([1, 2, 2, 3, 4, 3], [2, 3])

contains

  subroutine write_spatial_animation(out, base, magnify, n_frames, err)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    real(dp), intent(in) :: magnify
    integer, intent(out) :: n_frames
    type(error_t), intent(inout) :: err
    type(drawing_3d_t) :: d
    integer :: u
    n_frames = 0
    call last_revolution_rows(out, d%rows, max_frames)
    call build_3d(out, base//'_anim.nml', d, magnify, err)
    if (err%failed()) return
    call write_frames_3d(base//'_anim.dat', d)
    call open_animation_script(base, out, d%rows, u)
    call settings_3d(u, out, d, '')
    write(u, '(a)') 'do for [i = 0:'//str(size(d%rows) - 1)//'] {'
    write(u, '(a)') '  set title "'//esc(out%title)//'\n'//esc(how_drawn(d))//'; elastic displacements x '// &
      factor_text(d%factor)//'\n".when[i + 1]'
    call splot_frame(u, d, 'data', 'i', '  ')
    write(u, '(a)') '}'
    write(u, '(a)') 'set output'
    close(u)
    n_frames = size(d%rows)
  end subroutine write_spatial_animation

  !> The still at the largest stress of the last revolution, appended to the
  !> open standard script (unit u); nothing when the output cannot be drawn.
  subroutine append_spatial_shape(u, out, base, figures, magnify)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    character(len=64), allocatable, intent(inout) :: figures(:)
    real(dp), intent(in) :: magnify
    type(drawing_3d_t) :: d
    type(error_t) :: err
    integer :: peak(2)
    character(len=:), allocatable :: what
    call last_revolution_rows(out, d%rows, huge(1))
    call build_3d(out, base//'_shape.nml', d, magnify, err)
    if (err%failed()) return
    peak = maxloc(maxval(d%sigma, dim=1))
    what = 'the largest |stress| of the last revolution, '//number_text(maxval(d%sigma(:, peak(1), peak(2))))
    if (len(column_unit(out, 'sigma_max_e')) > 0) what = what//' '//column_unit(out, 'sigma_max_e')
    what = what//' in the '//trim(link_name(peak(1)))
    d%rows = [d%rows(peak(2))]
    d%joints = d%joints(:, :, peak(2):peak(2))
    d%jdisp = d%jdisp(:, :, peak(2):peak(2))
    d%rigid = d%rigid(:, :, :, peak(2):peak(2))
    d%disp = d%disp(:, :, :, peak(2):peak(2))
    d%sigma = d%sigma(:, :, peak(2):peak(2))
    call write_frames_3d(base//'_shape.dat', d)
    call begin_figure(u, 'shape', 'deformed shape at '//what, figures, height=760)
    write(u, '(a)') '  set title title."\n'//esc('deformed shape at '//what)//'\n'// &
      esc(frame_text(out, d%rows(1), column_index(out, 'crank_deg'), column_index(out, 't')))// &
      '; '//esc(how_drawn(d))//'; elastic displacements x '//factor_text(d%factor)//'"'
    write(u, '(a)') '  sdata = "'//esc(base)//'_shape.dat"'
    call settings_3d(u, out, d, '  ')
    call splot_frame(u, d, 'sdata', '0', '  ')
    call end_figure(u)
  end subroutine append_spatial_shape

  !> How the links are drawn, for the titles.
  function how_drawn(d) result(s)
    type(drawing_3d_t), intent(in) :: d
    character(len=:), allocatable :: s
    s = 'links bent by their elements'' shape functions'
    if (.not. all(d%shapes(:)%bent)) s = 'links straight between their displaced joints (no shape columns: '// &
                                         '&transient shape_points)'
  end function how_drawn

  !> How each link (crank, coupler, rocker, of n_elements(k) elements) is
  !> drawn from the columns of out: bent from its shape columns <link>_s<x>_UX,
  !> _UY, _UZ (sorted by x, both ends present), or straight between the
  !> translations of its joints (A and D: none).
  subroutine spatial_link_shapes(out, n_elements, shapes)
    type(run_output_t), intent(in) :: out
    integer, intent(in) :: n_elements(3)
    type(spatial_shape_3d_t), intent(out) :: shapes(3)
    integer :: k, j, i, first, ios, n, e
    real(dp) :: x
    real(dp), allocatable :: s(:)
    integer, allocatable :: ju(:)
    character(len=:), allocatable :: nm, prefix
    character(len=1), parameter :: joint(4) = ['A', 'B', 'C', 'D']
    first = 0
    do k = 1, 3
      prefix = trim(link_name(k))//'_s'
      allocate(s(0), ju(0))
      do j = 1, out%n_columns()
        nm = out%names(j)%s
        if (.not. starts_with(nm, prefix) .or. len(nm) < len(prefix) + 4) cycle
        if (nm(len(nm) - 2:) /= '_UX') cycle
        read(nm(len(prefix) + 1:len(nm) - 3), *, iostat=ios) x
        if (ios /= 0) cycle
        if (column_index(out, nm(1:len(nm) - 1)//'Y') == 0 .or. column_index(out, nm(1:len(nm) - 1)//'Z') == 0) cycle
        s = [s, x]
        ju = [ju, j]
      end do
      if (size(s) >= 2) then
        ju = ju(sorted(s))
        s = s(sorted(s))
        shapes(k)%bent = s(1) <= 1.0e-4_dp .and. s(size(s)) >= 1.0_dp - 1.0e-4_dp
      end if
      if (shapes(k)%bent) then
        shapes(k)%s = s
        allocate(shapes(k)%cols(3, size(s)), shapes(k)%jsig(1, size(s)))
        do i = 1, size(s)
          nm = out%names(ju(i))%s
          shapes(k)%cols(:, i) = [ju(i), column_index(out, nm(1:len(nm) - 1)//'Y'), &
                                  column_index(out, nm(1:len(nm) - 1)//'Z')]
          e = first + min(n_elements(k) - 1, max(0, ceiling(s(i)*n_elements(k) - 1.0e-9_dp) - 1))
          shapes(k)%jsig(1, i) = column_index(out, 'sigma_max_e'//str(e + 1))
        end do
      else
        shapes(k)%s = [0.0_dp, 1.0_dp]
        allocate(shapes(k)%cols(3, 2), shapes(k)%jsig(n_elements(k), 2))
        do i = 1, 2
          shapes(k)%cols(:, i) = [(column_index(out, joint(link_ends(i, k))//'_U'//axis(j)), j = 1, 3)]
          shapes(k)%jsig(:, i) = [(column_index(out, 'sigma_max_e'//str(first + e)), e = 1, n_elements(k))]
        end do
      end if
      n = n_elements(k)
      first = first + n
      deallocate(s, ju)
    end do
  end subroutine spatial_link_shapes

  !> The drawn links of output row `row` (x y z, point, link; a link's last
  !> point repeated up to the longest link's count): rigid + magnify x elastic.
  subroutine spatial_frame(out, row, magnify, drawn, err)
    type(run_output_t), intent(in) :: out
    integer, intent(in) :: row
    real(dp), intent(in) :: magnify
    real(dp), allocatable, intent(out) :: drawn(:, :, :)
    type(error_t), intent(inout) :: err
    type(drawing_3d_t) :: d
    d%rows = [row]
    call build_3d(out, 'spatial_frame.nml', d, magnify, err)
    if (err%failed()) return
    drawn = d%rigid(:, :, :, 1) + d%factor*d%disp(:, :, :, 1)
  end subroutine spatial_frame

  !> Positions, displacements, stresses and the factor of the rows d%rows.
  subroutine build_3d(out, path, d, magnify, err)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: path
    type(drawing_3d_t), intent(inout) :: d
    real(dp), intent(in) :: magnify
    type(error_t), intent(inout) :: err
    type(deck_t) :: deck
    type(spatial_fourbar_t) :: kin
    type(spatial_link_t) :: links(3)
    type(spatial_pose_t) :: pose
    integer :: jb, jc, ic, f, k, i, row, u, n
    real(dp) :: p1(3), p2(3), dmax
    ic = column_index(out, 'crank_deg')
    if (ic == 0 .or. size(out%data, 1) < 1) then
      call err%set('animate', out%path//' has no crank_deg column or no rows: nothing to draw', 3)
      return
    end if
    call header_group_file(out, 'spatial_mechanism', path, err)
    if (err%failed()) return
    call deck%open(path, err)
    if (.not. err%failed()) call read_spatial_mechanism(deck, d%input, err)
    if (.not. err%failed()) call build_spatial(deck, d%input, kin, links, jb, jc, err)
    call deck%close()
    open(newunit=u, file=path, status='old')
    close(u, status='delete')
    if (err%failed()) then
      call err%add_context('animate: the spatial mechanism echoed in '//out%path)
      return
    end if
    call spatial_link_shapes(out, [(links(k)%n_elements, k = 1, 3)], d%shapes)
    if (all([(all(d%shapes(k)%cols == 0), k = 1, 3)])) then
      call err%set('animate', out%path//' has no joint translation columns (B_UX ... C_UZ)', 3)
      return
    end if
    d%n_points = maxval([(size(d%shapes(k)%s), k = 1, 3)])
    n = size(d%rows)
    allocate(d%joints(3, 4, n), d%jdisp(3, 4, n), d%rigid(3, d%n_points, 3, n), d%disp(3, d%n_points, 3, n), &
             d%sigma(d%n_points, 3, n))
    d%scale = (norm2(d%input%crank_pin - d%input%crank_pivot) + d%input%coupler_length + d%input%rocker_length)/3.0_dp
    do f = 1, n
      row = d%rows(f)
      call spatial_fourbar_solve(kin, out%data(row, ic)*pi/180.0_dp, d%input%omega, 0.0_dp, pose, err)
      if (err%failed()) return
      d%joints(:, :, f) = reshape([d%input%crank_pivot, pose%b, pose%c, d%input%rocker_pivot], [3, 4])
      d%jdisp(:, :, f) = 0.0_dp
      do k = 1, 3
        d%jdisp(k, 2, f) = value_of(column_index(out, 'B_U'//axis(k)))
        d%jdisp(k, 3, f) = value_of(column_index(out, 'C_U'//axis(k)))
      end do
      do k = 1, 3
        p1 = d%joints(:, link_ends(1, k), f)
        p2 = d%joints(:, link_ends(2, k), f)
        associate (sh => d%shapes(k))
          do i = 1, d%n_points
            associate (m => min(i, size(sh%s)))   ! padding: repeats the last point
              d%rigid(:, i, k, f) = p1 + sh%s(m)*(p2 - p1)
              d%disp(:, i, k, f) = [value_of(sh%cols(1, m)), value_of(sh%cols(2, m)), value_of(sh%cols(3, m))]
              d%sigma(i, k, f) = stress_of(sh%jsig(:, m))
            end associate
          end do
        end associate
      end do
    end do
    dmax = max(maxval(norm2(d%disp, dim=1)), maxval(norm2(d%jdisp, dim=1)))
    d%factor = magnify
    if (d%factor <= 0.0_dp) then
      d%factor = 1.0_dp
      if (dmax > 0.0_dp) d%factor = nice_factor(0.25_dp*d%scale/dmax)
    end if
  contains
    real(dp) function value_of(j)
      integer, intent(in) :: j
      value_of = 0.0_dp
      if (j > 0) value_of = out%data(row, j)
    end function value_of
    real(dp) function stress_of(js)
      integer, intent(in) :: js(:)
      integer :: q
      stress_of = 0.0_dp
      do q = 1, size(js)
        stress_of = max(stress_of, abs(value_of(js(q))))
      end do
    end function stress_of
  end subroutine build_3d

  !> Block 0: the joint axes through A and D (segments: x y z of both ends);
  !> per frame, block 1 + 2f: the links' segments between consecutive points
  !> (x y z rigid of both ends, x y z deformed of both ends, |stress| of the
  !> element of the segment; segments, not curves: gnuplot would join curves
  !> of equal length into a surface grid), block 2 + 2f: the joints (x y z
  !> rigid, x y z deformed).
  subroutine write_frames_3d(path, d)
    character(len=*), intent(in) :: path
    type(drawing_3d_t), intent(in) :: d
    integer :: u, f, k, j, i
    real(dp) :: half
    half = axis_half(d)
    open(newunit=u, file=path, status='replace', action='write')
    write(u, '(a)') '# block 0: joint axes; per frame: the links'' segments (rigid end 1, end 2, deformed end 1, '// &
      'end 2, |stress|), then joints (rigid, deformed); elastic displacements x '//factor_text(d%factor)
    write(u, '(6es16.7)') d%input%crank_pivot - half*unit_vector(d%input%crank_axis), &
                          d%input%crank_pivot + half*unit_vector(d%input%crank_axis)
    write(u, '(6es16.7)') d%input%rocker_pivot - half*unit_vector(d%input%rocker_axis), &
                          d%input%rocker_pivot + half*unit_vector(d%input%rocker_axis)
    write(u, '(a)') ''
    write(u, '(a)') ''
    do f = 1, size(d%rows)
      do k = 1, 3
        do i = 2, size(d%shapes(k)%s)
          write(u, '(13es16.7)') d%rigid(:, i - 1, k, f), d%rigid(:, i, k, f), &
            d%rigid(:, i - 1, k, f) + d%factor*d%disp(:, i - 1, k, f), d%rigid(:, i, k, f) + d%factor*d%disp(:, i, k, f), &
            d%sigma(i, k, f)
        end do
      end do
      write(u, '(a)') ''
      write(u, '(a)') ''
      do j = 1, 4
        write(u, '(6es16.7)') d%joints(:, j, f), d%joints(:, j, f) + d%factor*d%jdisp(:, j, f)
      end do
      write(u, '(a)') ''
      write(u, '(a)') ''
    end do
    close(u)
  end subroutine write_frames_3d

  !> Half the drawn length of a joint axis.
  pure real(dp) function axis_half(d)
    type(drawing_3d_t), intent(in) :: d
    axis_half = 0.35_dp*d%scale
  end function axis_half

  pure function unit_vector(v) result(w)
    real(dp), intent(in) :: v(3)
    real(dp) :: w(3)
    w = v/norm2(v)
  end function unit_vector

  subroutine settings_3d(u, out, d, indent)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    type(drawing_3d_t), intent(in) :: d
    character(len=*), intent(in) :: indent
    real(dp) :: smax, lo(3), hi(3), pad
    character(len=:), allocatable :: lunit, what
    integer :: k
    do k = 1, 3         ! ranges fixed over the frames: the animation does not jump
      lo(k) = min(minval(d%rigid(k, :, :, :)), minval(d%rigid(k, :, :, :) + d%factor*d%disp(k, :, :, :)))
      hi(k) = max(maxval(d%rigid(k, :, :, :)), maxval(d%rigid(k, :, :, :) + d%factor*d%disp(k, :, :, :)))
    end do
    associate (ends => reshape([d%input%crank_pivot - axis_half(d)*unit_vector(d%input%crank_axis), &
                                d%input%crank_pivot + axis_half(d)*unit_vector(d%input%crank_axis), &
                                d%input%rocker_pivot - axis_half(d)*unit_vector(d%input%rocker_axis), &
                                d%input%rocker_pivot + axis_half(d)*unit_vector(d%input%rocker_axis)], [3, 4]))
      lo = min(lo, minval(ends, dim=2))     ! the joint axes inside too
      hi = max(hi, maxval(ends, dim=2))
    end associate
    pad = 0.05_dp*maxval(hi - lo)
    smax = maxval(d%sigma)
    if (.not. smax > 0.0_dp) smax = 1.0_dp
    lunit = unit_text(out, '_U')
    what = 'largest |stress| of the link'
    if (all(d%shapes(:)%bent)) what = '|stress| (outer fibre) of the element'
    write(u, '(a)') indent//'set view equal xyz'
    write(u, '(a)') indent//'set view 62, 32'
    write(u, '(a)') indent//'set xyplane 0'
    write(u, '(a)') indent//'set key at screen 0.02, 0.86 left top vertical Left reverse'
    do k = 1, 3
      write(u, '(a)') indent//'set '//lower(axis(k))//'range ['//str(lo(k) - pad, 6)//':'//str(hi(k) + pad, 6)//']'
    end do
    write(u, '(a)') indent//'set xlabel "X '//lunit//'"'
    write(u, '(a)') indent//'set ylabel "Y '//lunit//'"'
    write(u, '(a)') indent//'set zlabel "Z '//lunit//'" rotate parallel'
    write(u, '(a)') indent//'set palette defined (0 "#2c7bb6", 0.25 "#00a6ca", 0.5 "#90d743", 0.75 "#f98e09", 1 "#d7191c")'
    write(u, '(a)') indent//'set cbrange [0:'//str(smax, 4)//']'
    write(u, '(a)') indent//'set cblabel "'//what//' '//unit_text(out, 'sigma_max_e')//'"'
  end subroutine settings_3d

  subroutine splot_frame(u, d, var, index, indent)
    integer, intent(in) :: u
    type(drawing_3d_t), intent(in) :: d
    character(len=*), intent(in) :: var, index, indent
    character(len=:), allocatable :: links, joints
    links = var//' index 1+2*('//index//')'
    joints = var//' index 2+2*('//index//')'
    write(u, '(a)') indent//'splot '//links//' u 1:2:3:($4-$1):($5-$2):($6-$3) w vectors nohead lw 7 '// &
      'lc rgb "#d8d8d8" t "rigid-body position", \'
    write(u, '(a)') indent//'      '//var//' index 0 u 1:2:3:($4-$1):($5-$2):($6-$3) w vectors nohead lw 2 dt 2 '// &
      'lc rgb "#606060" t "joint axes: crank (A), rocker (D)", \'
    write(u, '(a)') indent//'      '//joints//' u 1:2:3 w p pt 6 ps 1.2 lc rgb "#b0b0b0" notitle, \'
    write(u, '(a)') indent//'      '//links//' u 7:8:9:($10-$7):($11-$8):($12-$9):13 w vectors nohead lw 4 lc palette '// &
      't "deformed, elastic displacements x '//factor_text(d%factor)//'", \'
    write(u, '(a)') indent//'      '//joints//' u 4:5:6 w p pt 7 ps 1.2 lc rgb "#202020" notitle'
  end subroutine splot_frame
end module plot_spatial
