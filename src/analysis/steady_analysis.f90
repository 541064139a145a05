!> The `steady` analysis (Tennant 1985): the steady-state vibration of a
!> flexible linkage driven at constant crank speed (doc/steady_state.md).  The
!> analysis itself is module steady_run's, which the design analysis also runs
!> on its initial and final designs.
module steady_analysis
  use error_status, only: error_t
  use deck_reader, only: deck_t
  use table_output, only: table_t
  use steady_run, only: analyse_steady
  implicit none
  private
  public :: run_steady

contains

  !> Read, build, the harmonic series and/or the exact periodic solution over
  !> one revolution, then the table of both.
  subroutine run_steady(deck, out, err)
    type(deck_t), intent(inout) :: deck
    type(table_t), intent(inout) :: out
    type(error_t), intent(inout) :: err
    call analyse_steady(deck, out, err)
  end subroutine run_steady
end module steady_analysis
