!> The &run group every deck starts with: which analysis to run and a title.
module run_settings
  use error_status, only: error_t
  use deck_reader, only: deck_t, group_read_t
  use table_output, only: table_t
  use version, only: program_name, program_version
  implicit none
  private
  public :: read_run_settings, write_run_header, analysis_driver

  abstract interface
    !> An analysis driver (run_transient, run_steady, ...): the deck in, the
    !> output table filled, an error value out.
    subroutine analysis_driver(deck, out, err)
      import :: deck_t, table_t, error_t
      type(deck_t), intent(inout) :: deck
      type(table_t), intent(inout) :: out
      type(error_t), intent(inout) :: err
    end subroutine analysis_driver
  end interface

  character(len=32) :: analysis
  character(len=256) :: title
  namelist /run/ analysis, title

contains

  subroutine read_run_settings(deck, analysis_out, title_out, err)
    type(deck_t), intent(inout) :: deck
    character(len=*), intent(out) :: analysis_out, title_out
    type(error_t), intent(inout) :: err
    logical :: found
    analysis = ''
    title = ''
    call deck%read_group('run', run_group, .true., found, err)
    analysis_out = analysis
    title_out = title
  end subroutine read_run_settings

  !> The first lines of every output: program, deck, title, and the &run
  !> group as read (after read_run_settings).
  subroutine write_run_header(out, deck_path, title_text)
    type(table_t), intent(inout) :: out
    character(len=*), intent(in) :: deck_path, title_text
    call out%comment(program_name//' '//program_version)
    call out%comment('deck: '//deck_path)
    if (len_trim(title_text) > 0) call out%comment('title: '//trim(title_text))
    call out%comment('effective input (every value, defaults included):')
    call out%echo_group(run_group)
  end subroutine write_run_header

  !> The &run group's namelist read and write (deck_reader, table_t%echo_group).
  subroutine run_group(r)
    type(group_read_t), intent(inout) :: r
    if (r%writing) then
      write(r%unit, nml=run, delim='apostrophe')
    else
      read(r%unit, nml=run, iostat=r%ios, iomsg=r%iomsg)
    end if
  end subroutine run_group
end module run_settings
