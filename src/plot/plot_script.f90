!> The standard figures of a flexmech output as a gnuplot script.
!>
!> One script per output file, written beside the figures and kept, so that a
!> user can rerun or edit it (`gnuplot SCRIPT` from the directory the figures
!> were made in); doc/figures/standard/ is made by the same routine
!> (tools/doc_figures.sh).  Each figure is drawn as PNG (pngcairo) and SVG,
!> titled with the deck's title:
!>
!>   transient, steady  <base>_stress  largest |stress| per element against crank angle
!>                      <base>_joints  elastic joint displacements U, W
!>                      <base>_links   link-end deformations u_end, w_end
!>                      (transient: earlier revolutions faint, the last one bold;
!>                       steady with method = 'both': harmonic series solid, exact dashed)
!>   optimize           <base>_history objective, constraint violation, step and variables per iteration
!>   lsode_check        <base>_solution each component against t
!>   sweep              <base>_peaks, <base>_cost, <base>_multipliers (when the points report
!>                      Floquet multipliers)  summary values against the swept value
!>   anything else      <base>_columns the first column against the others
module plot_script
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str, starts_with, append_name, lower
  use run_output, only: run_output_t, column_index, column_unit, name_t, split_words, read_run_output
  implicit none
  private
  public :: write_plot_script
  public :: begin_figure, end_figure, colour, esc, selected   ! shared with plot_compare
  public :: number_text, element_links, legend, unit_of      ! shared with plot_animation, plot_compare

  character(len=6), parameter :: plot_palette(8) = [character(len=6) :: &
    '0072b2', 'd55e00', '009e73', 'cc79a7', 'e69f00', '56b4e9', '000000', 'f0e442']
  !> a sweep point whose shooting matrix Phi - I has a smaller rcond is marked near a forced resonance
  real(dp), parameter :: near_resonance_rcond = 0.01_dp
  character(len=*), parameter :: near_resonance_text = '0.01'

  type :: series_t
    integer :: y = 1
    character(len=:), allocatable :: x                 !< a column number or a gnuplot expression
    character(len=:), allocatable :: title, style, filter
  end type series_t

  !> A sweep summary's columns sorted for its figures (sweep_figures).
  type :: sweep_view_t
    character(len=16), allocatable :: kind(:)          !< per column: stress, displacement, ..., cpu, count, ''
    character(len=:), allocatable :: unit_stress, unit_length, unit_force, unit_moment   !< ' (psi)' or ''
    real(dp), allocatable :: failed(:)                 !< swept values of the failed points
    integer :: multiplier = 0                          !< column of the largest Floquet multiplier, 0: none
    integer :: rcond = 0                               !< column of rcond(Phi - I) of periodic shooting, 0: none
    logical :: work = .false.                          !< a tolerance or mesh sweep: the work-precision figure
    type(name_t), allocatable :: links(:)              !< the link of each element (none in a mesh sweep)
    logical :: logx = .false.
  end type sweep_view_t

  !> The x axis of the curve figures.
  type :: curve_axis_t
    integer :: ix = 1                                  !< its column
    character(len=:), allocatable :: label
    real(dp) :: split = -huge(1.0_dp)                  !< start of the last revolution (more than one drawn)
    logical :: last_only = .false.                     !< only the last revolution, shifted by offset
    real(dp) :: offset = 0.0_dp                        !< whole turns subtracted from the crank angle
  end type curve_axis_t

contains

  !> Writes the figure script for `out`; `figures` receives the figure names
  !> (suffixes after base_), empty when the output has nothing to draw.
  subroutine write_plot_script(out, base, script_path, figures, err, whole_run)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base, script_path
    character(len=64), allocatable, intent(out) :: figures(:)
    type(error_t), intent(inout) :: err
    logical, intent(in), optional :: whole_run   !< transient: every revolution (default: the last complete one)
    integer :: u, ios
    logical :: whole
    allocate(figures(0))
    open(newunit=u, file=script_path, status='replace', action='write', iostat=ios)
    if (ios /= 0) then
      call err%set('plot', 'cannot write the script '''//script_path//'''', 1)
      return
    end if
    whole = .false.
    if (present(whole_run)) whole = whole_run
    call preamble(u, out, base)
    if (size(out%data, 1) > 0) then
      select case (out%analysis)
      case ('transient', 'steady', 'spatial')
        call curve_figures(u, out, whole, figures)
      case ('optimize', 'design')
        call history_figure(u, out, figures)
      case ('sweep')
        call sweep_figures(u, out, figures)
      case default
        call columns_figure(u, out, figures)
      end select
    end if
    close(u)
  end subroutine write_plot_script

  subroutine preamble(u, out, base)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: base
    write(u, '(a)') '# Standard figures of '//out%path//' (analysis: '//out%analysis//').'
    write(u, '(a)') '# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.'
    write(u, '(a)') '# Formats: gnuplot -e ''formats="png"'' SCRIPT draws the PNG files only.'
    write(u, '(a)') 'data = "'//esc(out%path)//'"'
    write(u, '(a)') 'base = "'//esc(base)//'"'
    write(u, '(a)') 'if (!exists("formats")) formats = "png svg"'
    write(u, '(a)') 'term_png = "set terminal pngcairo size 1000,640 font '',11'' noenhanced"'
    write(u, '(a)') 'term_svg = "set terminal svg size 1000,640 dynamic font '',11'' noenhanced"'
    write(u, '(a)') 'common = "set grid; set key outside right top; set datafile missing ''NaN''"'
    write(u, '(a)') 'title = "'//esc(display_title(out))//'"'
  end subroutine preamble

  pure function display_title(out) result(s)
    type(run_output_t), intent(in) :: out
    character(len=:), allocatable :: s
    s = out%title
    if (len(s) == 0) s = out%deck
    if (len(s) == 0) s = out%path
  end function display_title

  !> Opens a figure block: a loop over the formats.
  subroutine begin_figure(u, name, subtitle, figures, height)
    integer, intent(in) :: u
    character(len=*), intent(in) :: name, subtitle
    character(len=64), allocatable, intent(inout) :: figures(:)
    integer, intent(in), optional :: height      !< pixels (default 640)
    call append_name(figures, name)
    write(u, '(a)') ''
    write(u, '(a)') 'do for [fmt in formats] {'
    write(u, '(a)') '  reset'
    if (present(height)) then
      write(u, '(a)') '  eval (fmt eq "png" ? "set terminal pngcairo size 1000,'//str(height)// &
        ' font '',11'' noenhanced" : "set terminal svg size 1000,'//str(height)//' dynamic font '',11'' noenhanced")'
    else
      write(u, '(a)') '  eval (fmt eq "png" ? term_png : term_svg)'
    end if
    write(u, '(a)') '  eval common'
    write(u, '(a)') '  set output base."_'//name//'.".fmt'
    write(u, '(a)') '  set title title."\n'//esc(subtitle)//'"'
  end subroutine begin_figure

  subroutine end_figure(u)
    integer, intent(in) :: u
    write(u, '(a)') '  set output'
    write(u, '(a)') '}'
  end subroutine end_figure

  !> One 'plot' command of the series given.
  subroutine plot_series(u, s)
    integer, intent(in) :: u
    type(series_t), intent(in) :: s(:)
    integer :: i
    character(len=:), allocatable :: y
    do i = 1, size(s)
      y = str(s(i)%y)
      if (len(s(i)%filter) > 0) y = '('//s(i)%filter//' ? $'//str(s(i)%y)//' : NaN)'
      write(u, '(a)', advance='no') merge('  plot ', '       ', i == 1)//'data u '//s(i)%x//':'//y// &
        ' '//s(i)%style//' t "'//esc(s(i)%title)//'"'
      if (i < size(s)) then
        write(u, '(a)') ', \'
      else
        write(u, '(a)') ''
      end if
    end do
  end subroutine plot_series

  !> A series_t built component by component (gfortran 12 mis-sizes a
  !> deferred-length component given another one in a structure constructor).
  function series(x, y, title, style, filter) result(item)
    character(len=*), intent(in) :: x
    integer, intent(in) :: y
    character(len=*), intent(in) :: title, style, filter
    type(series_t) :: item
    item%x = x
    item%y = y
    item%title = title
    item%style = style
    item%filter = filter
  end function series

  subroutine add_series(s, item)
    type(series_t), allocatable, intent(inout) :: s(:)
    type(series_t), intent(in) :: item
    type(series_t), allocatable :: longer(:)
    integer :: i
    allocate(longer(size(s) + 1))
    do i = 1, size(s)
      longer(i) = s(i)
    end do
    longer(size(longer)) = item
    call move_alloc(longer, s)
  end subroutine add_series

  pure function colour(i, alpha) result(s)
    integer, intent(in) :: i
    character(len=*), intent(in) :: alpha
    character(len=:), allocatable :: s
    s = 'lc rgb "#'//alpha//plot_palette(mod(i - 1, size(plot_palette)) + 1)//'"'
  end function colour

  !> Transient and steady runs: stress, joints, link ends against crank angle:
  !> the last complete revolution on a 360 deg axis, or with `whole` every
  !> revolution (the earlier ones faint).
  subroutine curve_figures(u, out, whole, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    logical, intent(in) :: whole
    character(len=64), allocatable, intent(inout) :: figures(:)
    type(curve_axis_t) :: ax
    logical :: exact
    integer :: j
    type(name_t), allocatable :: links(:)
    ax%ix = column_index(out, 'crank_deg')
    ax%label = 'crank angle (deg)'
    if (ax%ix > 0) then
      if (maxval(out%data(:, ax%ix)) - minval(out%data(:, ax%ix)) <= 0.0_dp) ax%ix = 0
    end if
    if (ax%ix == 0) then
      ax%ix = column_index(out, 't')
      ax%label = 't (s)'
    end if
    if (ax%ix == 0) ax%ix = 1
    if (ax%label(1:1) == 'c') then
      if (maxval(out%data(:, ax%ix)) - minval(out%data(:, ax%ix)) > 360.0_dp + 1.0e-9_dp) then
        ax%split = maxval(out%data(:, ax%ix)) - 360.0_dp
        ax%last_only = .not. whole
        ax%offset = 360.0_dp*floor(ax%split/360.0_dp + 1.0e-9_dp)
      else                                    ! one revolution (rows of the last only): shifted to 0-360
        ax%offset = 360.0_dp*floor(minval(out%data(:, ax%ix))/360.0_dp + 1.0e-9_dp)
      end if
    end if
    exact = any([(index(out%names(j)%s, '_exact') > 0, j = 1, out%n_columns())])
    links = element_links(out)
    if (ax%split > -huge(1.0_dp)) write(u, '(a)') 'split = '//str(ax%split, 10)
    call curve_figure(u, out, 'stress', 'largest |stress| per element (outer fibre)', &
                      'stress'//unit_of(out, 'sigma_max_e'), 'sigma_max_e', '', ax, exact, links, figures)
    call curve_figure(u, out, 'sections', 'bending and axial stress per element (signed, largest magnitude)', &
                      'stress'//unit_of(out, 'sigma_b_e'), 'sigma_b_e sigma_a_e', '', ax, exact, links, figures)
    call curve_figure(u, out, 'moments', 'bending moment per element; moment of the ground at a clamp', &
                      'moment'//unit_of(out, 'M_e'), 'M_e', '_Gm', ax, exact, links, figures)
    call curve_figure(u, out, 'forces', 'axial force per element; joint forces on link ends and ground forces '// &
                      '(global X, Y)', 'force'//unit_of(out, '_Fx'), 'N_e', '_Fx _Fy _Gx _Gy', ax, exact, links, figures)
    call curve_figure(u, out, 'joints', 'joint elastic displacement (global axes)', &
                      'displacement'//unit_of(out, '_U'), '', '_U _W _UX _UY _UZ', ax, exact, links, figures)
    call curve_figure(u, out, 'links', 'link end 2 deformation in the link''s rigid-body axes', &
                      'displacement'//unit_of(out, '_end'), '', '_u_end _w_end _v_end', ax, exact, links, figures)
  end subroutine curve_figures

  !> ' (unit)' of the columns described with `key`, '' when the header does not say.
  function unit_of(out, key) result(s)
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: key
    character(len=:), allocatable :: s
    s = column_unit(out, key)
    if (len(s) > 0) s = ' ('//s//')'
  end function unit_of

  !> The link of every element, as a legend names it: 'crank' (a link of one
  !> element) or 'coupler element 2' (the second of its elements), from the
  !> header's mechanism lines 'link NAME: A-B, length L, N element(s); ...'.
  function element_links(out) result(names)
    type(run_output_t), intent(in) :: out
    type(name_t), allocatable :: names(:)
    type(name_t), allocatable :: words(:), longer(:)
    integer :: i, n, k, ios, colon
    character(len=:), allocatable :: link
    allocate(names(0))
    do i = 1, size(out%header)
      associate (line => out%header(i)%s)
        if (.not. starts_with(line, 'link ') .or. index(line, ' element(s)') == 0) cycle
        colon = index(line, ':')
        if (colon < 7) cycle
        link = line(6:colon - 1)
        call split_words(line(colon + 1:index(line, ' element(s)') - 1), words)
        if (size(words) == 0) cycle
        read(words(size(words))%s, *, iostat=ios) n
        if (ios /= 0 .or. n < 1) cycle
        allocate(longer(size(names) + n))
        longer(1:size(names)) = names
        do k = 1, n
          longer(size(names) + k)%s = link
          if (n > 1) longer(size(names) + k)%s = link//' element '//str(k)
        end do
        call move_alloc(longer, names)
      end associate
    end do
  end function element_links

  !> A column's legend: an element's columns (sigma_max_e3) by its link.
  function legend(name, links) result(s)
    character(len=*), intent(in) :: name
    type(name_t), intent(in) :: links(:)
    character(len=:), allocatable :: s
    integer :: at, k, ios
    s = name
    at = index(name, '_e', back=.true.)
    if (at == 0 .or. at + 2 > len(name)) return
    if (verify(name(at + 2:), '0123456789') /= 0) return
    read(name(at + 2:), *, iostat=ios) k
    if (ios /= 0 .or. k < 1 .or. k > size(links)) return
    s = links(k)%s
    if (.not. starts_with(name, 'sigma_max_e')) s = name(1:at - 1)//' '//s     ! sigma_b crank, M coupler
  end function legend

  !> One curve figure: the columns whose name starts with `prefix` (when given)
  !> or ends with one of the words of `suffixes`, without the _exact twins.
  subroutine curve_figure(u, out, name, what, ylabel, prefix, suffixes, ax, exact, links, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: name, what, ylabel, prefix, suffixes
    type(curve_axis_t), intent(in) :: ax
    logical, intent(in) :: exact
    type(name_t), intent(in) :: links(:)
    character(len=64), allocatable, intent(inout) :: figures(:)
    type(series_t), allocatable :: s(:)
    integer :: j, k, je, ix
    character(len=:), allocatable :: sub, nm, x, label, style
    allocate(s(0))
    k = 0
    ix = ax%ix
    x = str(ix)
    if (ax%last_only .or. abs(ax%offset) > 0.0_dp) x = '($'//str(ix)//' - '//axis_number(ax%offset)//')'
    do j = 1, out%n_columns()
      nm = out%names(j)%s
      if (index(nm, '_exact') > 0) cycle
      if (.not. selected(nm, prefix, suffixes) .or. shape_column(nm)) cycle
      k = k + 1
      je = column_index(out, nm//'_exact')
      label = legend(nm, links)
      style = colour(k, '00')
      if (k > size(plot_palette)) style = style//' dt '//str(mod((k - 1)/size(plot_palette), 4) + 2)   ! past 8: dashed
      if (ax%last_only) then
        call add_series(s, series(x, j, label, 'w l lw 2 '//style, '$'//str(ix)//' >= split'))
      else if (ax%split > -huge(1.0_dp)) then
        call add_series(s, series(x, j, '', 'w l lw 1 '//colour(k, 'a0'), '$'//str(ix)//' < split'))
        call add_series(s, series(x, j, label, 'w l lw 2 '//style, '$'//str(ix)//' >= split'))
      else
        call add_series(s, series(x, j, label, 'w l lw 2 '//style, ''))
        if (je > 0) s(size(s))%title = label//' (harmonic series)'
      end if
      if (je > 0) call add_series(s, series(x, je, label//' (exact periodic)', 'w l lw 2 dt 2 '//colour(k, '00'), ''))
    end do
    if (k == 0) return
    sub = what
    if (ax%last_only) then
      sub = sub//'; last complete revolution (run''s '//str(nint(ax%split))//'-'// &
            str(nint(ax%split) + 360)//' deg)'
    else if (ax%split > -huge(1.0_dp)) then
      sub = sub//'; bold: the last revolution (crank angle >= '//str(nint(ax%split))//' deg)'
    end if
    if (exact) sub = sub//'; solid: harmonic series, dashed: exact'
    call begin_figure(u, name, sub, figures)
    if (ax%label(1:1) == 'c') then
      if (ax%last_only) then
        write(u, '(a)') '  set xrange ['//axis_number(ax%split - ax%offset)//':'// &
                        axis_number(ax%split - ax%offset + 360.0_dp)//']'
        write(u, '(a)') '  set xtics 45'
      else if (maxval(out%data(:, ix)) - minval(out%data(:, ix)) <= 360.0_dp + 1.0e-9_dp) then
        write(u, '(a)') '  set xrange [0:360]'
        write(u, '(a)') '  set xtics 45'
      else
        write(u, '(a)') '  set xtics 360'
        write(u, '(a)') '  set mxtics 4'
        write(u, '(a)') '  set autoscale xfix'
      end if
    end if
    write(u, '(a)') '  set xlabel "'//ax%label//'"'
    write(u, '(a)') '  set ylabel "'//esc(ylabel)//'"'
    call plot_series(u, s)
    call end_figure(u)
  end subroutine curve_figure

  !> A link shape column, <link>_s<x>_<component> (drawn in the shape
  !> figure, not among the joints or link ends).
  logical pure function shape_column(name)
    character(len=*), intent(in) :: name
    integer :: at
    shape_column = .false.
    at = index(name, '_s', back=.true.)
    if (at == 0 .or. at + 2 > len(name)) return
    shape_column = verify(name(at + 2:at + 2), '0123456789') == 0 .and. index(name(at + 2:), '_') > 0
  end function shape_column

  logical pure function selected(name, prefix, suffixes)
    character(len=*), intent(in) :: name, prefix, suffixes
    integer :: a, b, n
    selected = .false.
    a = 1
    do while (a <= len(prefix))            ! any of the prefixes (words)
      b = index(prefix(a:)//' ', ' ') + a - 1
      if (b > a) selected = selected .or. starts_with(name, prefix(a:b - 1))
      a = b + 1
    end do
    a = 1
    do while (a <= len(suffixes))
      b = index(suffixes(a:)//' ', ' ') + a - 1
      n = b - a
      if (n > 0 .and. len(name) > n) then
        if (name(len(name) - n + 1:) == suffixes(a:b - 1)) selected = .true.
      end if
      a = b + 1
    end do
  end function selected

  !> Optimizer history: F, violation, step and the variables per iteration.
  subroutine history_figure(u, out, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=64), allocatable, intent(inout) :: figures(:)
    integer :: k, j, n, jv
    type(series_t), allocatable :: s(:)
    logical :: design
    k = column_index(out, 'k')
    design = column_index(out, 'mass') > 0      ! the design analysis: mass, design values, g<i>
    if (k == 0 .or. (column_index(out, 'F') == 0 .and. .not. design)) then
      call columns_figure(u, out, figures)
      return
    end if
    call begin_figure(u, 'history', merge('design history   ', 'optimizer history', design), figures)
    write(u, '(a)') '  set multiplot layout '//merge('2,2', '2,3', n_panels() <= 4)//' title title'
    write(u, '(a)') '  set xlabel "iteration k"'
    if (maxval(out%data(:, k)) <= 20.0_dp) write(u, '(a)') '  set xtics 1'
    write(u, '(a)') '  unset key'
    call panel('objective F', 'F', .true.)
    call panel('mass of the links', 'mass', .false.)
    call panel('max constraint violation', 'max_violation', .true.)
    call panel('step |s|', 'step', .true.)
    call panel('move limit', 'move_limit', .true.)
    if (design) call constraint_panel()
    allocate(s(0))
    n = 0
    jv = max(column_index(out, 'max_violation'), column_index(out, 'move_limit'))
    do j = 1, out%n_columns()
      if (design) then           ! the design values: after the bookkeeping columns, before g1
        if (j <= jv .or. is_numbered(out%names(j)%s, 'g')) cycle
      else if (.not. is_numbered(out%names(j)%s, 'x')) then
        cycle
      end if
      n = n + 1
      call add_series(s, series(str(k), j, out%names(j)%s, 'w lp lw 2 pt 7 ps 0.6 '//colour(n, '00'), ''))
    end do
    if (n > 0) then
      write(u, '(a)') '  set title "design variables"'
      if (n <= 8) write(u, '(a)') '  set key on inside right top'
      write(u, '(a)') '  unset logscale y'
      call plot_series(u, s)
    end if
    write(u, '(a)') '  unset multiplot'
    call end_figure(u)
  contains
    !> The analysis constraints g<i> (feasible: <= 0).
    subroutine constraint_panel()
      integer :: j, m
      m = 0
      do j = 1, out%n_columns()
        if (.not. is_numbered(out%names(j)%s, 'g')) cycle
        m = m + 1
        if (m == 1) write(u, '(a)') '  set title "analysis constraints g (feasible: g <= 0)"'
        if (m == 1) write(u, '(a)') '  set key on inside right top'
        if (m > 1) write(u, '(a)') ', \'
        write(u, '(a)', advance='no') merge('  plot ', '       ', m == 1)// &
          'data u '//str(k)//':'//str(j)//' w lp lw 2 pt 7 ps 0.6 '//colour(m, '00')//' t "'//out%names(j)%s//'"'
      end do
      if (m == 0) return
      write(u, '(a)') ''
      write(u, '(a)') '  unset key'
    end subroutine constraint_panel

    integer function n_panels()
      integer :: j
      logical :: has_g, has_x
      n_panels = count([column_index(out, 'F') > 0, column_index(out, 'mass') > 0, &
                        column_index(out, 'max_violation') > 0, column_index(out, 'step') > 0, &
                        column_index(out, 'move_limit') > 0])
      has_g = .false.
      has_x = .false.
      do j = 1, out%n_columns()
        has_g = has_g .or. (design .and. is_numbered(out%names(j)%s, 'g'))
        has_x = has_x .or. is_numbered(out%names(j)%s, 'x') .or. design
      end do
      n_panels = n_panels + count([has_g, has_x])
    end function n_panels

    subroutine panel(label, name, logy)
      character(len=*), intent(in) :: label, name
      logical, intent(in) :: logy
      integer :: j
      logical :: positive
      j = column_index(out, name)
      if (j == 0) return
      positive = any(out%data(:, j) > 0.0_dp)
      if (name == 'F') positive = all(out%data(:, j) > 0.0_dp)
      if (positive .and. name == 'F') positive = maxval(out%data(:, j)) > 100.0_dp*minval(out%data(:, j))
      write(u, '(a)') '  set title "'//trim(label//merge(' (log scale)', '            ', &
                      logy .and. positive))//'"'
      if (name == 'F' .and. positive) write(u, '(a)') '  set title "objective F (log scale)"'
      if (logy .and. positive) then
        write(u, '(a)') '  set logscale y'
        write(u, '(a)') '  set format y "%.0e"'
        write(u, '(a)') '  plot data u '//str(k)//':($'//str(j)//' > 0 ? $'//str(j)//' : NaN) w lp lw 2 pt 7 '// &
                        colour(1, '00')
        write(u, '(a)') '  unset logscale y'
        write(u, '(a)') '  set format y "% h"'
      else if (maxval(out%data(:, j)) - minval(out%data(:, j)) <= 0.0_dp) then
        write(u, '(a)') '  set yrange [-1:1]'
        write(u, '(a)') '  plot data u '//str(k)//':'//str(j)//' w lp lw 2 pt 7 '//colour(1, '00')
        write(u, '(a)') '  set autoscale y'
      else
        write(u, '(a)') '  plot data u '//str(k)//':'//str(j)//' w lp lw 2 pt 7 '//colour(1, '00')
      end if
    end subroutine panel
  end subroutine history_figure

  !> name is prefix followed by digits only (x1, g12).
  logical pure function is_numbered(name, prefix)
    character(len=*), intent(in) :: name, prefix
    is_numbered = .false.
    if (len(name) <= len(prefix)) return
    if (name(1:len(prefix)) /= prefix) return
    is_numbered = verify(name(len(prefix) + 1:), '0123456789') == 0
  end function is_numbered

  !> Sweep summary against the swept value: `peaks` (one panel per kind of
  !> quantity: stresses, displacements, forces, moments, others, each with
  !> the unit its point outputs give), `cost` (CPU seconds; counts), the
  !> Floquet `multipliers` when the points report them, and `work` (the
  !> relative change of the largest peak stress from the most accurate
  !> point against CPU seconds) when the swept variable is a tolerance or a
  !> mesh.  Log axes where the values span more than two decades; points
  !> whose largest Floquet multiplier exceeds 1 (unbounded response) are
  !> marked, failed points (no row) drawn as dotted vertical lines.
  subroutine sweep_figures(u, out, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=64), allocatable, intent(inout) :: figures(:)
    type(sweep_view_t) :: v
    type(run_output_t) :: point
    call sweep_view(out, v, point)
    call panel_figure(u, out, v, 'peaks', 'summary peaks against the swept value', &
      [character(len=16) :: 'stress', 'displacement', 'force', 'moment', 'other peak'], figures)
    call panel_figure(u, out, v, 'cost', 'cost of each point', &
      [character(len=16) :: 'cpu', 'count'], figures)
    call panel_figure(u, out, v, 'multipliers', 'largest Floquet multiplier moduli (above 1: unbounded, '// &
      'parametric resonance)', [character(len=16) :: 'multiplier'], figures)
    if (v%work) call work_figure(u, out, v, figures)
  end subroutine sweep_figures

  !> What the sweep figures need beyond the table: each column's kind, the
  !> units (from the first point's output, when it is still there), the
  !> x axis, the unbounded test and the failed points' values.
  subroutine sweep_view(out, v, point)
    type(run_output_t), intent(in) :: out
    type(sweep_view_t), intent(out) :: v
    type(run_output_t), intent(out) :: point
    type(error_t) :: err
    integer :: j, i, a, b, ios
    real(dp) :: x
    logical :: found
    character(len=:), allocatable :: nm, line, path
    allocate(v%kind(out%n_columns()), v%failed(0), v%links(0))
    v%kind = ''
    v%unit_stress = ''
    v%unit_length = ''
    v%unit_force = ''
    v%unit_moment = ''
    path = ''
    do i = 1, size(out%header)                 ! 'sweep: ... logs in DIR/STEM_<k>.{nml,out,log}'
      line = out%header(i)%s
      a = index(line, 'logs in ')
      b = index(line, '<k>')
      if (starts_with(line, 'sweep: ') .and. a > 0 .and. b > a + 8) path = line(a + 8:b - 1)
      if (starts_with(line, 'point ') .and. index(line, ': exit ') > 0 .and. index(line, ' = ') > 0) then
        a = index(line, ' = ') + 3
        if (index(line(a:), '*') > 0 .and. index(line(a:), '*') < index(line(a:), ':')) a = a + index(line(a:), '*')
        read(line(a:a + index(line(a:), ':') - 2), *, iostat=ios) x
        if (ios == 0) v%failed = [v%failed, x]
      end if
    end do
    if (len(path) > 0) then               ! the first point's output, numbered 1, 01, 001 ...
      if (index(out%path, '/') > 0 .and. path(1:1) /= '/') path = out%path(1:index(out%path, '/', back=.true.))//path
      do i = 1, 5
        inquire(file=path//repeat('0', i - 1)//'1.out', exist=found)
        if (.not. found) cycle
        call read_run_output(path//repeat('0', i - 1)//'1.out', point, err)
        exit
      end do
      if (found .and. .not. err%failed()) then
        v%unit_stress = unit_of(point, 'sigma_max_e')
        v%unit_length = unit_of(point, '_U')
        v%unit_force = unit_of(point, '_Fx')
        v%unit_moment = unit_of(point, 'M_e')
        if (index(lower(out%names(1)%s), 'n_elements') == 0) v%links = element_links(point)
      end if
    end if
    v%multiplier = column_index(out, 'floquet_multipliers_largest_moduli_1')
    do j = 3, out%n_columns()
      if (starts_with(lower(out%names(j)%s), 'rcond_of_the_newton_matrix')) v%rcond = j
    end do
    do j = 3, out%n_columns()
      nm = lower(out%names(j)%s)
      if (.not. any(finite_positive(out%data(:, j), .false.))) cycle
      if (starts_with(nm, 'floquet_multipliers')) then
        v%kind(j) = 'multiplier'
      else if (starts_with(nm, 'cost_') .or. index(nm, 'cpu') > 0) then
        v%kind(j) = 'count'
        if (index(nm, 'cpu') > 0) v%kind(j) = 'cpu'
        if (nm == 'cost_last_method_order') v%kind(j) = ''
      else if (index(nm, 'peak') == 0) then
        cycle
      else if (index(nm, 'stress') > 0 .or. index(nm, 'sigma') > 0) then
        v%kind(j) = 'stress'
      else if (ends_with_any(nm, '_u _w _u_end _w_end _v_end _chord _ex _ey')) then
        v%kind(j) = 'displacement'
      else if (ends_with_any(nm, '_fx _fy _fz _gx _gy _gz')) then
        v%kind(j) = 'force'
      else if (ends_with_any(nm, '_gm') .or. index(nm, 'peak_m_e') > 0) then
        v%kind(j) = 'moment'
      else
        v%kind(j) = 'other peak'
      end if
    end do
    nm = lower(out%names(1)%s)
    v%work = index(nm, 'tol') > 0 .or. index(nm, 'n_elements') > 0 .or. index(nm, 'n_harmonics') > 0 .or. &
             index(nm, 'table_points') > 0
    v%logx = spans_decades(out%data(:, 1))
  end subroutine sweep_view

  !> A sweep column's legend with its element named by its link:
  !> element_2_peak_stress -> 'coupler: peak_stress', peak_sigma_max_e2 ->
  !> 'peak_sigma_max: coupler'.
  function sweep_legend(name, links) result(s)
    character(len=*), intent(in) :: name
    type(name_t), intent(in) :: links(:)
    character(len=:), allocatable :: s
    integer :: k, ios, b
    s = name
    if (starts_with(name, 'element_')) then
      b = index(name(9:), '_') + 7
      if (b <= 8) return
      read(name(9:b), *, iostat=ios) k
      if (ios /= 0 .or. k < 1 .or. k > size(links)) return
      s = links(k)%s//': '//name(b + 2:)
    else
      s = legend(name, links)
      if (s /= name) s = name(1:index(name, '_e', back=.true.) - 1)//': '//s(index(s, ' ', back=.true.) + 1:)
    end if
  end function sweep_legend

  !> All positive and max > 100 min.
  logical pure function spans_decades(x)
    real(dp), intent(in) :: x(:)
    spans_decades = .false.
    if (size(x) == 0) return
    if (minval(x) <= 0.0_dp) return
    spans_decades = maxval(x) > 100.0_dp*minval(x)
  end function spans_decades

  logical pure function ends_with_any(name, suffixes)
    character(len=*), intent(in) :: name, suffixes
    ends_with_any = selected(name, '', suffixes)
  end function ends_with_any

  !> A multiplot of one panel per kind of column present.
  subroutine panel_figure(u, out, v, name, what, kinds, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    type(sweep_view_t), intent(in) :: v
    character(len=*), intent(in) :: name, what
    character(len=16), intent(in) :: kinds(:)
    character(len=64), allocatable, intent(inout) :: figures(:)
    integer :: k, n, j, m
    logical :: logy, near
    character(len=:), allocatable :: mark, y
    n = count([(any(v%kind == kinds(k)), k = 1, size(kinds))])
    if (n == 0) return
    call begin_figure(u, name, what, figures, height=max(640, 40 + 330*n))
    write(u, '(a)') '  set multiplot layout '//str(n)//',1 title title."\n'//esc(what)//'"'
    write(u, '(a)') '  unset title'
    write(u, '(a)') '  set key below'
    write(u, '(a)') '  set xlabel "'//esc(out%names(1)%s//swept_unit(out%names(1)%s, v))//'"'
    if (v%logx) write(u, '(a)') '  set logscale x'
    do j = 1, size(v%failed)
      write(u, '(a)') '  set arrow '//str(j)//' from '//axis_number(v%failed(j))//', graph 0 to '// &
        axis_number(v%failed(j))//', graph 1 nohead dt 3 lw 2 lc rgb "#d00000"'
    end do
    do k = 1, size(kinds)
      if (.not. any(v%kind == kinds(k))) cycle
      logy = .true.
      do j = 1, out%n_columns()
        if (v%kind(j) /= kinds(k)) cycle
        if (any(out%data(:, j) <= 0.0_dp)) logy = .false.
      end do
      if (logy) logy = spans_decades(pack(out%data, spread(v%kind == kinds(k), 1, size(out%data, 1))))
      if (kinds(k) == 'cpu') logy = .true.
      y = axis_label(kinds(k), v)
      if (logy) y = y//' (log scale)'
      write(u, '(a)') '  set ylabel "'//esc(y)//'"'
      if (logy) then
        write(u, '(a)') '  set logscale y'
      else
        write(u, '(a)') '  unset logscale y'
      end if
      m = 0
      do j = 1, out%n_columns()
        if (v%kind(j) /= kinds(k)) cycle
        m = m + 1
        y = str(j)
        if (logy) y = '($'//str(j)//' > 0 ? $'//str(j)//' : NaN)'
        write(u, '(a)', advance='no') merge('  plot ', '       ', m == 1)//'data u 1:'//y// &
          ' w lp lw 2 ps 1.1 '//series_style(m)//' t "'//esc(sweep_legend(out%names(j)%s, v%links))//'"'
        write(u, '(a)') ', \'
      end do
      mark = ''
      if (v%multiplier > 0 .and. kinds(k) /= 'multiplier') then
        mark = '($'//str(v%multiplier)//' > 1.000001 ? $'
        m = 0
        do j = 1, out%n_columns()
          if (v%kind(j) /= kinds(k)) cycle
          m = m + 1
          write(u, '(a)') '       data u 1:'//mark//str(j)//' : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" '// &
            trim(merge('t "unbounded (Floquet multiplier > 1)"', 'notitle                               ', m == 1))//', \'
        end do
      end if
      ! a multiplier near +1 (Phi - I nearly singular): the periodic response to the crank's
      ! forcing is amplified about as 1/rcond, a forced resonance even where every |multiplier| = 1
      near = .false.
      if (v%rcond > 0) near = kinds(k) /= 'multiplier' .and. any(out%data(:, max(v%rcond, 1)) < near_resonance_rcond)
      if (near) then
        mark = '($'//str(v%rcond)//' < '//axis_number(near_resonance_rcond)//' ? $'
        m = 0
        do j = 1, out%n_columns()
          if (v%kind(j) /= kinds(k)) cycle
          m = m + 1
          y = 'notitle'
          if (m == 1) y = 't "near a forced resonance (rcond of the shooting matrix < '//near_resonance_text//')"'
          write(u, '(a)') '       data u 1:'//mark//str(j)//' : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" '//y//', \'
        end do
      end if
      if (size(v%failed) > 0) then
        write(u, '(a)') '       NaN w l dt 3 lw 2 lc rgb "#d00000" t "failed point (no row)"'
      else
        write(u, '(a)') '       NaN notitle'
      end if
    end do
    write(u, '(a)') '  unset multiplot'
    call end_figure(u)
  end subroutine panel_figure

  !> ' (rad/s)' for a sweep over the crank speed, the deck's length or stress
  !> unit for a length or modulus, '' for a count or a tolerance ratio.
  function swept_unit(name, v) result(s)
    character(len=*), intent(in) :: name
    type(sweep_view_t), intent(in) :: v
    character(len=:), allocatable :: s
    character(len=:), allocatable :: nm
    nm = lower(name)
    s = ''
    if (nm == 'omega') then
      s = ' (rad/s)'
    else if (nm == 'damping_beta' .or. nm == 'spinup_time' .or. nm == 't_end') then
      s = ' (s)'
    else if (any(nm == [character(len=12) :: 'link_length', 'joint_x', 'joint_y', 'link_c', 'link_depth', &
                        'link_width', 'link_radius', 'atol']) .and. allocated(v%unit_length)) then
      s = v%unit_length
    else if ((nm == 'link_e1' .or. nm == 'link_e2') .and. allocated(v%unit_stress)) then
      s = v%unit_stress
    end if
  end function swept_unit

  function axis_label(kind, v) result(s)
    character(len=*), intent(in) :: kind
    type(sweep_view_t), intent(in) :: v
    character(len=:), allocatable :: s
    select case (kind)
    case ('stress')
      s = 'peak stress'//v%unit_stress
    case ('displacement')
      s = 'peak displacement'//v%unit_length
    case ('force')
      s = 'peak force'//v%unit_force
    case ('moment')
      s = 'peak moment'//v%unit_moment
    case ('cpu')
      s = 'CPU seconds'
    case ('count')
      s = 'count'
    case ('multiplier')
      s = 'modulus'
    case default
      s = 'peak'
    end select
  end function axis_label

  !> Work-precision: the relative change of the largest peak stress of each
  !> point from the most accurate point's (the smallest tolerance, the
  !> largest mesh), against its CPU seconds, log-log.
  subroutine work_figure(u, out, v, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    type(sweep_view_t), intent(in) :: v
    character(len=64), allocatable, intent(inout) :: figures(:)
    integer :: jc, j, best, n
    real(dp), allocatable :: peak(:)
    character(len=:), allocatable :: nm
    jc = column_index(out, 'cost_total_cpu_seconds')
    n = size(out%data, 1)
    if (jc == 0 .or. n < 3 .or. .not. any(v%kind == 'stress')) return
    allocate(peak(n))
    peak = 0.0_dp
    do j = 1, out%n_columns()
      if (v%kind(j) == 'stress') peak = max(peak, abs(out%data(:, j)))
    end do
    nm = lower(out%names(1)%s)
    if (index(nm, 'tol') > 0) then
      best = minloc(out%data(:, 1), dim=1)
    else
      best = maxloc(out%data(:, 1), dim=1)
    end if
    if (.not. peak(best) > 0.0_dp) return
    write(u, '(a)') 'array werr['//str(n)//']'
    do j = 1, n
      write(u, '(a)') 'werr['//str(j)//'] = '//str(abs(peak(j) - peak(best))/peak(best), 6)
    end do
    call begin_figure(u, 'work', 'work-precision: change of the largest peak stress from the most accurate point ('// &
                      esc(out%names(1)%s)//' = '//number_text(out%data(best, 1))//'), against CPU', figures)
    write(u, '(a)') '  set logscale y'
    if (spans_decades(out%data(:, jc))) then
      write(u, '(a)') '  set logscale x'
    else
      write(u, '(a)') '  set offsets graph 0.05, graph 0.25, 0, 0'
    end if
    write(u, '(a)') '  set format y "%.0e"'
    write(u, '(a)') '  set xlabel "CPU seconds of the point"'
    write(u, '(a)') '  set ylabel "relative change of the largest peak stress (log scale)"'
    write(u, '(a)') '  set key inside right top'
    write(u, '(a)') '  plot data u '//str(jc)//':(werr[$0 + 1] > 0 ? werr[$0 + 1] : NaN) w lp lw 2 pt 7 ps 1.3 '// &
      colour(1, '00')//' t "largest peak stress", \'
    write(u, '(a)') '       data u '//str(jc)//':(werr[$0 + 1] > 0 ? werr[$0 + 1] : NaN):(sprintf("'// &
      esc(out%names(1)%s)//' = %g", $1)) w labels offset 1,0.8 left font ",9" notitle'
    call end_figure(u)
  end subroutine work_figure

  !> The style of series m: a colour, a point type and a dash pattern, so that
  !> no two of 48 series look alike.
  pure function series_style(m) result(s)
    integer, intent(in) :: m
    character(len=:), allocatable :: s
    integer, parameter :: points(6) = [7, 5, 9, 11, 13, 1]
    s = colour(m, '00')//' pt '//str(points(mod(m - 1, 6) + 1))//' dt '//str(mod((m - 1)/8, 6) + 1)
  end function series_style

  elemental logical function finite_positive(x, need_positive)
    real(dp), intent(in) :: x
    logical, intent(in) :: need_positive
    finite_positive = ieee_is_finite(x)
    if (finite_positive .and. need_positive) finite_positive = x > 0.0_dp
  end function finite_positive

  !> Any other table (lsode_check, unknown): the first column against the
  !> next ones (at most eight), one panel each; log x when it spans decades.
  subroutine columns_figure(u, out, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=64), allocatable, intent(inout) :: figures(:)
    integer :: j, n
    logical :: logx
    n = min(out%n_columns(), 9) - 1
    if (n < 1) return
    logx = minval(out%data(:, 1)) > 0.0_dp .and. maxval(out%data(:, 1)) > 100.0_dp*minval(out%data(:, 1))
    call begin_figure(u, merge('solution', 'columns ', out%analysis == 'lsode_check'), &
                      'each column against '//out%names(1)%s, figures)
    figures(size(figures)) = trim(figures(size(figures)))
    write(u, '(a)') '  set multiplot layout '//str((n + 1)/2)//','//str(min(n, 2))//' title title'
    write(u, '(a)') '  unset key'
    write(u, '(a)') '  set xlabel "'//esc(out%names(1)%s)//'"'
    if (logx) write(u, '(a)') '  set logscale x'
    do j = 2, n + 1
      write(u, '(a)') '  set title "'//esc(out%names(j)%s)//'"'
      write(u, '(a)') '  plot data u 1:'//str(j)//' w lp lw 2 pt 7 ps 0.5 '//colour(j - 1, '00')
    end do
    write(u, '(a)') '  unset multiplot'
    call end_figure(u)
  end subroutine columns_figure

  !> x with 5 significant digits, without exponent when 0.01 <= |x| < 1e7.
  function number_text(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if ((abs(x) >= 1.0e4_dp .and. abs(x) < 1.0e7_dp) .or. (abs(x) < 1.0e7_dp .and. abs(x - anint(x)) < 1.0e-9_dp)) then
      write(buf, '(i0)') nint(x)
    else if (abs(x) >= 0.01_dp .and. abs(x) < 1.0e4_dp) then
      write(buf, '(f0.' // str(4 - floor(log10(abs(x)))) // ')') x
    else
      write(buf, '(es11.4)') x
    end if
    s = trim(adjustl(buf))
    if (s(1:1) == '.') s = '0'//s
  end function number_text

  !> A coordinate for a gnuplot command: an integer as such, else 10 digits.
  function axis_number(x) result(s)
    real(dp), intent(in) :: x
    character(len=:), allocatable :: s
    character(len=32) :: buf
    if (abs(x) < 1.0e9_dp .and. abs(x - anint(x)) <= 1.0e-12_dp*max(1.0_dp, abs(x)) .and. &
        (abs(x) >= 0.5_dp .or. abs(x) < tiny(1.0_dp))) then
      write(buf, '(i0)') nint(x)
    else
      write(buf, '(es17.10)') x
    end if
    s = trim(adjustl(buf))
  end function axis_number

  !> Text inside a gnuplot double-quoted string.
  pure function esc(text) result(s)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: s
    integer :: i
    s = ''
    do i = 1, len(text)
      select case (text(i:i))
      case ('"', '\')
        s = s//'\'//text(i:i)
      case default
        s = s//text(i:i)
      end select
    end do
  end function esc
end module plot_script
