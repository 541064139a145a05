!> Problems a user adds without editing flexmech (issue 11).  This default
!> defines none.  `make PROBLEM=path/to/file.f90` compiles that file, which
!> must define a module `user_problems` with exactly these two public
!> procedures, and links it in place of this one into build/user/flexmech; a
!> deck then names the problem in `&optimize problem = '...'`.  The template
!> is examples/user_problem/hs71_problem.f90 (doc/optimization.md §10).
module user_problems
  use error_status, only: error_t
  use optim_problem, only: opt_problem_t
  use problem_library, only: problem_info_t
  implicit none
  private
  public :: create_user_problem, user_problem_names

contains

  !> If `name` is one of the user's problems, allocate and set it up, fill
  !> info (title, source, start x0, known optimum if any) and set found.
  subroutine create_user_problem(name, prob, info, found, err)
    character(len=*), intent(in) :: name
    class(opt_problem_t), allocatable, intent(out) :: prob
    type(problem_info_t), intent(out) :: info
    logical, intent(out) :: found
    type(error_t), intent(inout) :: err
    class(opt_problem_t), allocatable :: none
    found = .false.
    if (.false.) call move_alloc(none, prob)
    if (.false.) info%name = name
    if (.false.) call err%clear()
  end subroutine create_user_problem

  !> The user's problem names, quoted and comma-separated ('' for none).
  function user_problem_names() result(names)
    character(len=:), allocatable :: names
    names = ''
  end function user_problem_names
end module user_problems
