!> flexmech DECK.nml [-o OUT]
!>
!> Reads a namelist deck, runs the analysis named in its &run group and writes
!> a tabular output file.  Exit status: 0 success; 1 usage error or an output
!> file that could not be renamed into place at the end; 2 bad input (deck or
!> output path; no output file is left); 3 the analysis stopped with a
!> diagnosis (the output written so far is kept, with the diagnosis in its
!> footer).  See doc/failure_modes.md.
program flexmech
  use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
  use kinds, only: dp
  use error_status, only: error_t
  use strings, only: str
  use version, only: program_name
  use deck_reader, only: deck_t, invalid_value, input_error_code
  use table_output, only: table_t
  use run_settings, only: read_run_settings, write_run_header, analysis_driver, check_deck_groups
  use command_line, only: parse_arguments, quit, output_path_problem
  use lsode_check_analysis, only: run_lsode_check
  use kinematics_analysis, only: run_kinematics
  use general_transient_analysis, only: run_general_transient
  use transient_analysis, only: run_transient
  use optimize_analysis, only: run_optimize
  use steady_analysis, only: run_steady
  use spatial_analysis, only: run_spatial
  use design_analysis, only: run_design
  use spatial_design_analysis, only: run_spatial_design
  use plot_command, only: dispatch_plot
  use subcommands, only: dispatch_subcommands
  implicit none

  !> An analysis a deck can name in &run: its name and its driver.
  type :: analysis_t
    character(len=24) :: name
    procedure(analysis_driver), pointer, nopass :: run
  end type analysis_t

  type(analysis_t), allocatable :: analyses(:)
  character(len=:), allocatable :: deck_path, out_path
  type(deck_t) :: deck
  type(table_t) :: out
  type(error_t) :: err
  real(dp) :: cpu0, cpu1
  character(len=32) :: analysis
  character(len=256) :: title
  integer :: k

  call cpu_time(cpu0)
  call dispatch_plot()          ! flexmech plot ... (src/plot); returns for any other command line
  call dispatch_subcommands()   ! sweeps, batches (src/batch); returns for a single deck
  call parse_arguments(deck_path, out_path)

  call deck%open(deck_path, err)
  if (err%failed()) call fail_input(err)
  ! the output path is checked before any work: a run never ends in an
  ! unwritable or dangerous output
  if (len(output_path_problem(out_path, deck_path)) > 0) then
    call err%set('output '''//out_path//'''', output_path_problem(out_path, deck_path), input_error_code)
    call fail_input(err)
  end if
  call read_run_settings(deck, analysis, title, err)
  if (err%failed()) call fail_input(err)
  call check_deck_groups(deck, analysis, .false., err)
  if (err%failed()) call fail_input(err)

  call out%open(out_path, err)
  if (err%failed()) then
    err%code = input_error_code
    call fail_input(err)
  end if
  call write_run_header(out, deck_path, title)

  ! the analyses, in the order the message of an unknown name lists them
  analyses = [analysis_t('transient', run_transient), analysis_t('steady', run_steady), &
              analysis_t('optimize', run_optimize), analysis_t('design', run_design), &
              analysis_t('spatial', run_spatial), analysis_t('spatial_design', run_spatial_design), &
              analysis_t('lsode_check', run_lsode_check), &
              analysis_t('kinematics', run_kinematics), analysis_t('general_transient', run_general_transient)]
  k = position(analyses, analysis)
  if (k > 0) then
    call analyses(k)%run(deck, out, err)
  else
    call invalid_value(deck, 'run', 'analysis', ''''//trim(analysis)//'''', 'must be one of '//names(analyses), err)
  end if
  call deck%close()
  if (.not. err%failed()) then
    if (out%bad_row > 0) call err%set('output', out%non_finite_text(), 3)
  end if

  if (err%failed()) then
    if (err%code == input_error_code) then
      call out%discard()
      call fail_input(err)
    end if
    call out%comment('stopped: '//err%text())
  end if
  call cpu_time(cpu1)
  call out%cost('total_cpu_seconds', str(cpu1 - cpu0, 4))
  block
    type(error_t) :: commit_err
    call out%commit(commit_err)
    if (commit_err%failed()) then
      write(error_unit, '(a)') program_name//': error: '//commit_err%text()
      call quit(1)
    end if
  end block
  if (err%failed()) then
    write(error_unit, '(a)') program_name//': analysis stopped: '//err%text()
    write(error_unit, '(a)') program_name//': partial output kept in '//out_path
    call quit(3)
  end if
  write(output_unit, '(a)') program_name//': wrote '//out_path

contains

  !> The index of the analysis called `name` in `list`, 0 if none.
  integer function position(list, name)
    type(analysis_t), intent(in) :: list(:)
    character(len=*), intent(in) :: name
    integer :: i
    position = 0
    do i = 1, size(list)
      if (list(i)%name == name) position = i
    end do
  end function position

  !> 'a', 'b', ... : the analyses' names for a message.
  function names(list) result(text)
    type(analysis_t), intent(in) :: list(:)
    character(len=:), allocatable :: text
    integer :: i
    text = ''''//trim(list(1)%name)//''''
    do i = 2, size(list)
      text = text//', '''//trim(list(i)%name)//''''
    end do
  end function names

  subroutine fail_input(err)
    type(error_t), intent(in) :: err
    write(error_unit, '(a)') program_name//': input error: '//err%text()
    call quit(input_error_code)
  end subroutine fail_input

end program flexmech
