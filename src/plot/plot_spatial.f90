!> The deformed spatial four-bar in 3D (gnuplot splot), from a spatial output:
!>   every plot of such a run: the still <base>_shape (PNG, SVG) at the
!>     output time of the largest stress of the last revolution;
!>   `--animate`: <base>_anim.gif over the last revolution (at most 90 frames).
!>
!> The rigid-body positions of the joints A (crank pivot), B, C and D (rocker
!> pivot) are recomputed from the &spatial_mechanism group echoed in the
!> output's header (the run's own kinematics, at each row's crank angle); the
!> output holds the elastic translations of B and C (B_UX ... C_UZ, global),
!> so each link is drawn straight between its displaced ends (the output has
!> a link's end-2 rotations but not its end-1 slopes, which a bent shape
!> would need).  Each link is coloured by the largest sigma_max_e<k> of its
!> elements, the joint axes of the crank and the rocker are drawn dashed
!> through A and D, the rigid position faint beneath.
module plot_spatial
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use deck_reader, only: deck_t
  use spatial_kinematics, only: spatial_fourbar_t, spatial_pose_t, spatial_fourbar_solve
  use spatial_settings, only: spatial_input_t, read_spatial_mechanism, build_spatial
  use spatial_model, only: spatial_link_t
  use run_output, only: run_output_t, column_index, column_unit
  use plot_script, only: esc, begin_figure, end_figure, number_text
  use plot_animation, only: last_revolution_rows, header_group_file, open_animation_script, frame_text, &
                            factor_text, unit_text, nice_factor
  implicit none
  private
  public :: write_spatial_animation, append_spatial_shape

  integer, parameter :: max_frames = 90
  real(dp), parameter :: pi = acos(-1.0_dp)

  !> The drawing of a spatial run at the rows `rows`.
  type :: drawing_3d_t
    type(spatial_input_t) :: input
    integer, allocatable :: rows(:)
    real(dp), allocatable :: joints(:, :, :)   !< rigid positions (xyz, A B C D, frame)
    real(dp), allocatable :: disp(:, :, :)     !< elastic translations (xyz, A B C D, frame)
    real(dp), allocatable :: sigma(:, :)       !< |stress| of each link (link, frame)
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
    write(u, '(a)') '  set title "'//esc(out%title)//'\nlinks straight between their displaced joints; '// &
      'elastic displacements x '//factor_text(d%factor)//'\n".when[i + 1]'
    call splot_frame(u, d, 'data', 'i', '  ')
    write(u, '(a)') '}'
    write(u, '(a)') 'set output'
    close(u)
    n_frames = size(d%rows)
  end subroutine write_spatial_animation

  !> The still at the largest stress of the last revolution, appended to the
  !> open standard script (unit u); nothing when the output cannot be drawn.
  subroutine append_spatial_shape(u, out, base, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    character(len=64), allocatable, intent(inout) :: figures(:)
    type(drawing_3d_t) :: d
    type(error_t) :: err
    integer :: peak(2)
    character(len=:), allocatable :: what
    character(len=*), parameter :: names(3) = [character(len=7) :: 'crank', 'coupler', 'rocker']
    call last_revolution_rows(out, d%rows, huge(1))
    call build_3d(out, base//'_shape.nml', d, 0.0_dp, err)
    if (err%failed()) return
    peak = maxloc(d%sigma)
    what = 'the largest |stress| of the last revolution, '//number_text(d%sigma(peak(1), peak(2)))
    if (len(column_unit(out, 'sigma_max_e')) > 0) what = what//' '//column_unit(out, 'sigma_max_e')
    what = what//' in the '//trim(names(peak(1)))
    d%rows = [d%rows(peak(2))]
    d%joints = d%joints(:, :, peak(2):peak(2))
    d%disp = d%disp(:, :, peak(2):peak(2))
    d%sigma = d%sigma(:, peak(2):peak(2))
    call write_frames_3d(base//'_shape.dat', d)
    call begin_figure(u, 'shape', 'deformed shape at '//what, figures, height=760)
    write(u, '(a)') '  set title title."\n'//esc('deformed shape at '//what)//'\n'// &
      esc(frame_text(out, d%rows(1), column_index(out, 'crank_deg'), column_index(out, 't')))// &
      '; elastic displacements x '//factor_text(d%factor)//'"'
    write(u, '(a)') '  sdata = "'//esc(base)//'_shape.dat"'
    call settings_3d(u, out, d, '  ')
    call splot_frame(u, d, 'sdata', '0', '  ')
    call end_figure(u)
  end subroutine append_spatial_shape

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
    integer :: jb, jc, ic, f, k, e, first, row, u, j
    character(len=1), parameter :: axis(3) = ['X', 'Y', 'Z']
    integer :: cols(3, 2)
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
    do k = 1, 3
      cols(k, 1) = column_index(out, 'B_U'//axis(k))
      cols(k, 2) = column_index(out, 'C_U'//axis(k))
    end do
    if (all(cols == 0)) then
      call err%set('animate', out%path//' has no joint translation columns (B_UX ... C_UZ)', 3)
      return
    end if
    allocate(d%joints(3, 4, size(d%rows)), d%disp(3, 4, size(d%rows)), d%sigma(3, size(d%rows)))
    d%disp = 0.0_dp
    d%sigma = 0.0_dp
    d%scale = (norm2(d%input%crank_pin - d%input%crank_pivot) + d%input%coupler_length + d%input%rocker_length)/3.0_dp
    do f = 1, size(d%rows)
      row = d%rows(f)
      call spatial_fourbar_solve(kin, out%data(row, ic)*pi/180.0_dp, d%input%omega, 0.0_dp, pose, err)
      if (err%failed()) return
      d%joints(:, :, f) = reshape([d%input%crank_pivot, pose%b, pose%c, d%input%rocker_pivot], [3, 4])
      do k = 1, 3
        if (cols(k, 1) > 0) d%disp(k, 2, f) = out%data(row, cols(k, 1))
        if (cols(k, 2) > 0) d%disp(k, 3, f) = out%data(row, cols(k, 2))
      end do
      first = 0
      do k = 1, 3                        ! a link's largest stress over its elements
        do e = 1, links(k)%n_elements
          j = column_index(out, 'sigma_max_e'//str(first + e))
          if (j > 0) d%sigma(k, f) = max(d%sigma(k, f), abs(out%data(row, j)))
        end do
        first = first + links(k)%n_elements
      end do
    end do
    d%factor = magnify
    if (d%factor <= 0.0_dp) then
      d%factor = 1.0_dp
      if (maxval(norm2(d%disp, dim=1)) > 0.0_dp) d%factor = nice_factor(0.25_dp*d%scale/maxval(norm2(d%disp, dim=1)))
    end if
  end subroutine build_3d

  !> Block 0: the joint axes through A and D (segments: x y z of both ends);
  !> per frame, block 1 + 2f: the links (x y z of both rigid ends, of both
  !> deformed ends, |stress|; one line each, drawn as vectors), block 2 + 2f:
  !> the joints (x y z rigid, x y z deformed).
  subroutine write_frames_3d(path, d)
    character(len=*), intent(in) :: path
    type(drawing_3d_t), intent(in) :: d
    integer :: u, f, k, j
    real(dp) :: half
    real(dp) :: def(3, 4)
    half = 0.35_dp*d%scale
    open(newunit=u, file=path, status='replace', action='write')
    write(u, '(a)') '# block 0: joint axes; per frame: links (rigid end 1, end 2, deformed end 1, end 2, |stress|),'// &
      ' then joints (rigid, deformed); elastic displacements x '//factor_text(d%factor)
    write(u, '(6es16.7)') d%input%crank_pivot - half*unit(d%input%crank_axis), &
                          d%input%crank_pivot + half*unit(d%input%crank_axis)
    write(u, '(6es16.7)') d%input%rocker_pivot - half*unit(d%input%rocker_axis), &
                          d%input%rocker_pivot + half*unit(d%input%rocker_axis)
    write(u, '(a)') ''
    write(u, '(a)') ''
    do f = 1, size(d%rows)
      def = d%joints(:, :, f) + d%factor*d%disp(:, :, f)
      do k = 1, 3
        write(u, '(13es16.7)') d%joints(:, link_ends(1, k), f), d%joints(:, link_ends(2, k), f), &
                               def(:, link_ends(1, k)), def(:, link_ends(2, k)), d%sigma(k, f)
      end do
      write(u, '(a)') ''
      write(u, '(a)') ''
      do j = 1, 4
        write(u, '(6es16.7)') d%joints(:, j, f), def(:, j)
      end do
      write(u, '(a)') ''
      write(u, '(a)') ''
    end do
    close(u)
  contains
    pure function unit(v) result(w)
      real(dp), intent(in) :: v(3)
      real(dp) :: w(3)
      w = v/norm2(v)
    end function unit
  end subroutine write_frames_3d

  subroutine settings_3d(u, out, d, indent)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    type(drawing_3d_t), intent(in) :: d
    character(len=*), intent(in) :: indent
    real(dp) :: smax
    character(len=:), allocatable :: lunit
    smax = maxval(d%sigma)
    if (.not. smax > 0.0_dp) smax = 1.0_dp
    lunit = unit_text(out, '_U')
    write(u, '(a)') indent//'set view equal xyz'
    write(u, '(a)') indent//'set view 62, 32'
    write(u, '(a)') indent//'set xyplane 0'
    write(u, '(a)') indent//'set key at screen 0.02, 0.86 left top vertical Left reverse'
    write(u, '(a)') indent//'set xlabel "X '//lunit//'"'
    write(u, '(a)') indent//'set ylabel "Y '//lunit//'"'
    write(u, '(a)') indent//'set zlabel "Z '//lunit//'" rotate parallel'
    write(u, '(a)') indent//'set palette defined (0 "#2c7bb6", 0.25 "#00a6ca", 0.5 "#90d743", 0.75 "#f98e09", 1 "#d7191c")'
    write(u, '(a)') indent//'set cbrange [0:'//str(smax, 4)//']'
    write(u, '(a)') indent//'set cblabel "largest |stress| of the link '//unit_text(out, 'sigma_max_e')//'"'
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
    write(u, '(a)') indent//'      '//links//' u 7:8:9:($10-$7):($11-$8):($12-$9):13 w vectors nohead lw 4 lc palette '// &
      't "deformed, elastic displacements x '//factor_text(d%factor)//'", \'
    write(u, '(a)') indent//'      '//joints//' u 4:5:6 w p pt 7 ps 1.2 lc rgb "#202020" notitle'
  end subroutine splot_frame
end module plot_spatial
