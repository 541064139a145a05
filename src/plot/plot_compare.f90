!> `flexmech plot A.out B.out ... --compare [-n NAME] [--columns c1,c2]`:
!> several transient or steady runs in one set of figures (stress, joints,
!> links): one colour per column, one dash pattern per run, the legend naming
!> both.  --columns keeps only the columns named.  The doc's comparison
!> figures (linear against nonlinear, the paper's figures) are drawn this way.
module plot_compare
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use run_output, only: run_output_t, column_index, name_t, append_text
  use plot_script, only: begin_figure, end_figure, colour, esc, selected, element_links, legend, unit_of
  implicit none
  private
  public :: write_compare_script

contains

  !> only: comma-separated column names ('' = all); labels(i): legend label of
  !> run i; title: the figures' title ('' = the runs' names).
  subroutine write_compare_script(outs, labels, base, script_path, only, title, figures, err)
    type(run_output_t), intent(in) :: outs(:)
    character(len=*), intent(in) :: labels(:), base, script_path, only, title
    character(len=64), allocatable, intent(out) :: figures(:)
    type(error_t), intent(inout) :: err
    integer :: u, ios, i
    type(name_t), allocatable :: links(:)
    allocate(figures(0))
    do i = 1, size(outs)
      if (all(outs(i)%analysis /= [character(len=9) :: 'transient', 'steady', 'spatial'])) then
        call err%set('plot --compare', outs(i)%path//' is a '''//outs(i)%analysis// &
                     ''' output; --compare overlays transient, steady and spatial runs', 3)
        return
      end if
    end do
    open(newunit=u, file=script_path, status='replace', action='write', iostat=ios)
    if (ios /= 0) then
      call err%set('plot', 'cannot write the script '''//script_path//'''', 1)
      return
    end if
    write(u, '(a)') '# Comparison figures written by `flexmech plot --compare`; rerun with gnuplot'
    write(u, '(a)') '# from the directory it ran in.'
    do i = 1, size(outs)
      write(u, '(a)') 'data'//str(i)//' = "'//esc(outs(i)%path)//'"'
    end do
    write(u, '(a)') 'base = "'//esc(base)//'"'
    write(u, '(a)') 'if (!exists("formats")) formats = "png svg"'
    write(u, '(a)') 'term_png = "set terminal pngcairo size 1000,640 font '',11'' noenhanced"'
    write(u, '(a)') 'term_svg = "set terminal svg size 1000,640 dynamic font '',11'' noenhanced"'
    write(u, '(a)') 'common = "set grid; set key below; set datafile missing ''NaN''"'
    if (len_trim(title) > 0) then
      write(u, '(a)') 'title = "'//esc(title)//'"'
    else
      write(u, '(a)') 'title = "'//esc(compare_title(labels))//'"'
    end if
    links = element_links(outs(1))
    call compare_figure(u, outs, labels, links, only, 'stress', 'largest |stress| per element', &
                        'stress'//unit_of(outs(1), 'sigma_max_e'), 'sigma_max_e', '', figures)
    call compare_figure(u, outs, labels, links, only, 'joints', 'joint elastic displacement (global axes)', &
                        'displacement'//unit_of(outs(1), '_U'), '', '_U _W _UX _UY _UZ', figures)
    call compare_figure(u, outs, labels, links, only, 'links', 'link end 2 deformation in the link''s rigid-body axes', &
                        'displacement'//unit_of(outs(1), '_end'), '', '_u_end _w_end _v_end', figures)
    call compare_figure(u, outs, labels, links, only, 'points', 'transverse elastic displacement of link points '// &
                        'in the link''s rigid-body axes', 'displacement'//unit_of(outs(1), '_s<x>_u'), '', '_w', figures)
    call compare_figure(u, outs, labels, links, only, 'rotations', 'small rotation of link end 2 in the link''s '// &
                        'rigid-body axes', 'rotation'//unit_of(outs(1), '_tx'), '', '_tx_end _ty_end _tz_end', figures)
    close(u)
  end subroutine write_compare_script

  subroutine compare_figure(u, outs, labels, links, only, name, what, ylabel, prefix, suffixes, figures)
    integer, intent(in) :: u
    type(run_output_t), intent(in) :: outs(:)
    type(name_t), intent(in) :: links(:)
    character(len=*), intent(in) :: labels(:), only, name, what, ylabel, prefix, suffixes
    character(len=64), allocatable, intent(inout) :: figures(:)
    type(name_t), allocatable :: lines(:)
    integer :: i, j, k, ix
    character(len=:), allocatable :: nm
    allocate(lines(0))
    k = 0
    do j = 1, outs(1)%n_columns()
      nm = outs(1)%names(j)%s
      if (.not. selected(nm, prefix, suffixes) .or. .not. wanted(nm, only)) cycle
      k = k + 1
      do i = 1, size(outs)
        if (column_index(outs(i), nm) == 0) cycle
        ix = x_column(outs(i))
        call append_text(lines, 'data'//str(i)//' u '//str(ix)//':'//str(column_index(outs(i), nm))// &
          ' w l lw 2 dt '//str(mod(i - 1, 5) + 1)//' '//colour(k, '00')//' t "'//esc(legend(nm, links)//', '// &
          trim(labels(i)))//'"')
      end do
    end do
    if (size(lines) == 0) return
    call begin_figure(u, name, what//'; line pattern: run, colour: column', figures)
    write(u, '(a)') '  set xlabel "'//merge('crank angle (deg)', 't (s)            ', &
                    outs(1)%names(x_column(outs(1)))%s == 'crank_deg')//'"'
    write(u, '(a)') '  set ylabel "'//esc(ylabel)//'"'
    write(u, '(a)') '  set autoscale xfix'
    ix = x_column(outs(1))
    if (outs(1)%names(ix)%s == 'crank_deg') then
      if (maxval(outs(1)%data(:, ix)) - minval(outs(1)%data(:, ix)) > 720.0_dp) write(u, '(a)') '  set xtics 360'
      if (maxval(outs(1)%data(:, ix)) - minval(outs(1)%data(:, ix)) <= 360.0_dp + 1.0e-6_dp) write(u, '(a)') '  set xtics 45'
    end if
    do i = 1, size(lines)
      write(u, '(a)') merge('  plot ', '       ', i == 1)//lines(i)%s//trim(merge(', \', '   ', i < size(lines)))
    end do
    call end_figure(u)
  end subroutine compare_figure

  pure function compare_title(labels) result(s)
    character(len=*), intent(in) :: labels(:)
    character(len=:), allocatable :: s
    integer :: i
    s = 'Comparison: '//trim(labels(1))
    do i = 2, size(labels)
      s = s//' | '//trim(labels(i))
    end do
  end function compare_title

  !> crank_deg when the crank turns, else t.
  integer function x_column(out) result(ix)
    type(run_output_t), intent(in) :: out
    ix = column_index(out, 'crank_deg')
    if (ix > 0) then
      if (maxval(out%data(:, ix)) - minval(out%data(:, ix)) > 0.0_dp) return
    end if
    ix = max(1, column_index(out, 't'))
  end function x_column

  logical pure function wanted(name, only)
    character(len=*), intent(in) :: name, only
    wanted = len_trim(only) == 0
    if (.not. wanted) wanted = index(','//only//',', ','//name//',') > 0
  end function wanted
end module plot_compare
