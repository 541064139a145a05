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
  use strings, only: str, starts_with, append_name
  use run_output, only: run_output_t, column_index, column_unit, name_t, split_words
  implicit none
  private
  public :: write_plot_script, plot_palette
  public :: begin_figure, end_figure, colour, esc, selected   ! shared with plot_compare

  character(len=6), parameter :: plot_palette(8) = [character(len=6) :: &
    '0072b2', 'd55e00', '009e73', 'cc79a7', 'e69f00', '56b4e9', '000000', 'f0e442']

  type :: series_t
    integer :: y = 1
    character(len=:), allocatable :: x                 !< a column number or a gnuplot expression
    character(len=:), allocatable :: title, style, filter
  end type series_t

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
      case ('transient', 'steady')
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
  subroutine begin_figure(u, name, subtitle, figures)
    integer, intent(in) :: u
    character(len=*), intent(in) :: name, subtitle
    character(len=64), allocatable, intent(inout) :: figures(:)
    call append_name(figures, name)
    write(u, '(a)') ''
    write(u, '(a)') 'do for [fmt in formats] {'
    write(u, '(a)') '  reset'
    write(u, '(a)') '  eval (fmt eq "png" ? term_png : term_svg)'
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
      end if
    end if
    exact = any([(index(out%names(j)%s, '_exact') > 0, j = 1, out%n_columns())])
    links = element_links(out)
    if (ax%split > -huge(1.0_dp)) write(u, '(a)') 'split = '//str(ax%split, 10)
    call curve_figure(u, out, 'stress', 'largest |stress| per element (outer fibre)', &
                      'stress'//unit_of(out, 'sigma_max_e'), 'sigma_max_e', '', ax, exact, links, figures)
    call curve_figure(u, out, 'joints', 'joint elastic displacement U (global X), W (global Y)', &
                      'displacement'//unit_of(out, '_U'), '', '_U _W', ax, exact, links, figures)
    call curve_figure(u, out, 'links', 'link end 2 deformation in the link''s rigid-body axes', &
                      'displacement'//unit_of(out, '_u_end'), '', '_u_end _w_end', ax, exact, links, figures)
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
    character(len=:), allocatable :: sub, nm, x, label
    allocate(s(0))
    k = 0
    ix = ax%ix
    x = str(ix)
    if (ax%last_only) x = '($'//str(ix)//' - '//str(ax%offset, 10)//')'
    do j = 1, out%n_columns()
      nm = out%names(j)%s
      if (index(nm, '_exact') > 0) cycle
      if (.not. selected(nm, prefix, suffixes)) cycle
      k = k + 1
      je = column_index(out, nm//'_exact')
      label = legend(nm, links)
      if (ax%last_only) then
        call add_series(s, series(x, j, label, 'w l lw 2 '//colour(k, '00'), '$'//str(ix)//' >= split'))
      else if (ax%split > -huge(1.0_dp)) then
        call add_series(s, series(x, j, '', 'w l lw 1 '//colour(k, 'a0'), '$'//str(ix)//' < split'))
        call add_series(s, series(x, j, label, 'w l lw 2 '//colour(k, '00'), '$'//str(ix)//' >= split'))
      else
        call add_series(s, series(x, j, label, 'w l lw 2 '//colour(k, '00'), ''))
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
        write(u, '(a)') '  set xrange ['//str(ax%split - ax%offset, 8)//':'//str(ax%split - ax%offset + 360.0_dp, 8)//']'
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

  logical pure function selected(name, prefix, suffixes)
    character(len=*), intent(in) :: name, prefix, suffixes
    integer :: a, b, n
    selected = .false.
    if (len(prefix) > 0) selected = starts_with(name, prefix)
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

  !> Sweep summary: peaks and cost against the swept value.
  subroutine sweep_figures(u, out, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=64), allocatable, intent(inout) :: figures(:)
    call sweep_figure(u, out, 'peaks', 'summary peaks against the swept value', 'peak', figures)
    call sweep_figure(u, out, 'cost', 'cost of each point (log scale)', 'cpu', figures)
    call sweep_figure(u, out, 'multipliers', 'largest Floquet multiplier moduli (above 1: parametric resonance)', &
                      'floquet_multipliers', figures)
  end subroutine sweep_figures

  subroutine sweep_figure(u, out, name, what, word, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: out
    character(len=*), intent(in) :: name, what, word
    character(len=64), allocatable, intent(inout) :: figures(:)
    type(series_t), allocatable :: s(:)
    integer :: j, n
    allocate(s(0))
    n = 0
    do j = 3, out%n_columns()
      if (index(out%names(j)%s, word) == 0) cycle
      if (.not. any(finite_positive(out%data(:, j), word == 'cpu'))) cycle
      n = n + 1
      call add_series(s, series('1', j, out%names(j)%s, 'w lp lw 2 pt 7 ps 0.8 '//colour(n, '00'), ''))
    end do
    if (n == 0) return
    call begin_figure(u, name, what, figures)
    write(u, '(a)') '  set xlabel "'//esc(out%names(1)%s)//'"'
    write(u, '(a)') '  set key inside left top'
    if (word == 'cpu') then
      write(u, '(a)') '  set logscale y'
      write(u, '(a)') '  set ylabel "CPU seconds"'
    end if
    call plot_series(u, s)
    call end_figure(u)
  end subroutine sweep_figure

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
