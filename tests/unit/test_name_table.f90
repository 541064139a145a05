!> The code <-> name tables (module name_table) and the families that use
!> them: every name read back to its code, the spellings the decks and
!> outputs have always used, and what lies outside a table.
module test_name_table_suite
  use name_table, only: name_of, code_of
  use gauss_optimizer, only: method_from_name, method_name, hessian_from_name, hessian_name, method_gauss, &
                             method_gnlc_ns, method_auto, hessian_auto, hessian_exact, hessian_bfgs
  use optim_problem, only: con_kind_name, con_linear, con_general
  use sweep_run, only: status_meaning
  use lsode_solver, only: istate_sentence, mf_adams
  use strings, only: starts_with
  use assertions
  implicit none
  private
  public :: run_all

  character(len=*), parameter :: colours(4) = [character(len=6) :: 'red', '', 'green', 'blue']

contains

  subroutine run_all()
    call run_test('table_codes_and_names_round_trip', test_round_trip)
    call run_test('outside_a_table_and_on_a_gap_is_otherwise', test_outside)
    call run_test('optimizer_names_unchanged', test_optimizer_names)
    call run_test('status_and_istate_sentences_unchanged', test_sentences)
  end subroutine run_all

  !> Codes 5..8 (6 a gap): each name gives its code back, whatever its case
  !> and surrounding blanks.
  subroutine test_round_trip()
    integer :: code
    do code = 5, 8
      if (code == 6) cycle
      call assert_equal(code_of(colours, name_of(colours, code, 5, '?'), 5, -1), code, &
                        'code of the name of '//name_of(colours, code, 5, '?'))
    end do
    call assert_equal(code_of(colours, '  GrEeN ', 5, -1), 7, 'case and blanks ignored')
    call assert_equal(name_of(colours, 8, 5, '?'), 'blue', 'name trimmed')
  end subroutine test_round_trip

  subroutine test_outside()
    call assert_equal(name_of(colours, 4, 5, 'none'), 'none', 'code below the table')
    call assert_equal(name_of(colours, 9, 5, 'none'), 'none', 'code above the table')
    call assert_equal(name_of(colours, 6, 5, 'none'), 'none', 'a gap has no name')
    call assert_equal(code_of(colours, '', 5, -1), -1, 'a blank name does not match the gap')
    call assert_equal(code_of(colours, 'redd', 5, -1), -1, 'a longer name does not match')
    call assert_equal(code_of(colours, 're', 5, -1), -1, 'a prefix does not match')
  end subroutine test_outside

  !> The names the decks and output headers use (doc/optimization.md).
  subroutine test_optimizer_names()
    character(len=17), parameter :: methods(7) = [character(len=17) :: 'gauss', 'gauss_constrained', 'gnlc', &
      'gnlc_ns', 'gnlc_general', 'gnlc_general_ns', 'auto']
    integer :: k
    do k = 1, size(methods)
      call assert_equal(method_name(method_from_name(methods(k))), trim(methods(k)), 'method '//methods(k))
    end do
    call assert_equal(method_from_name('GNLC.NS'), method_gnlc_ns, "B's spelling gnlc.ns")
    call assert_equal(method_from_name('auto'), method_auto, 'auto')
    call assert_equal(method_from_name('newton'), 0, 'unknown method')
    call assert_equal(method_name(method_gauss - 1), 'unknown', 'name of no method')
    call assert_equal(hessian_from_name(' '), hessian_auto, 'blank hessian is auto')
    call assert_equal(hessian_from_name('Exact'), hessian_exact, 'hessian exact')
    call assert_equal(hessian_from_name('newton'), -1, 'unknown hessian')
    call assert_equal(hessian_from_name('BFGS'), hessian_bfgs, 'hessian bfgs')
    call assert_equal(hessian_name(hessian_exact), 'exact', 'name of exact')
    call assert_equal(hessian_name(7), 'auto', 'unknown hessian code reads as auto')
    call assert_equal(con_kind_name(con_linear), 'linear', 'linear constraint')
    call assert_equal(con_kind_name(con_general), 'general', 'general constraint')
    call assert_equal(con_kind_name(0), 'unset', 'unset constraint')
  end subroutine test_optimizer_names

  subroutine test_sentences()
    call assert_equal(status_meaning(-1), 'could not be started', 'status -1')
    call assert_equal(status_meaning(0), 'ok', 'status 0')
    call assert_equal(status_meaning(3), 'analysis stopped', 'status 3')
    call assert_equal(status_meaning(4), 'crashed', 'status 4')
    call assert_equal(status_meaning(-2), 'crashed', 'status -2')
    call assert_equal(istate_sentence(2, mf_adams), 'integration successful', 'ISTATE 2')
    call assert_equal(istate_sentence(-6, mf_adams), 'a component of the error weight vanished (pure relative ' &
                      //'error control, atol = 0, on a solution component that became zero)', 'ISTATE -6')
    call assert_equal(istate_sentence(0, mf_adams), 'unknown ISTATE 0', 'ISTATE 0 is not a DLSODE return')
    call assert_true(starts_with(istate_sentence(-1, mf_adams), 'excess work done: the step limit for one ' &
                     //'output interval was reached before TOUT; the problem is probably stiff'), 'ISTATE -1, Adams')
    call assert_equal(istate_sentence(-1, 22), 'excess work done: the step limit for one output interval was ' &
                      //'reached before TOUT; raise max_steps or shorten the output interval', 'ISTATE -1, BDF')
  end subroutine test_sentences
end module test_name_table_suite

program test_name_table
  use test_name_table_suite, only: run_all
  use assertions, only: finish_suite
  implicit none
  call run_all()
  call finish_suite('test_name_table')
end program test_name_table
