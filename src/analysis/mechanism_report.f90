!> What every analysis of a flexible mechanism reports the same way: the
!> mechanism summary and the correlation table in the output header, which
!> joints move elastically, where a joint's displacement is read, and the
!> names of the response columns (joints, link ends, element stresses).
module mechanism_report
  use kinds, only: dp
  use strings, only: str
  use table_output, only: table_t
  use linkage, only: mechanism_t, joint_pin, joint_slider_fixed, joint_free, joint_slider_link
  use linkage_report, only: mechanism_summary
  use correlation_table, only: correlation_table_t
  implicit none
  private
  public :: write_mechanism_header, joint_moves, joint_carrier, response_column_names, response_columns_text
  public :: link_point_name

  !> Meaning of the response columns, for the '# columns:' line.
  character(len=*), parameter :: response_columns_text = &
    '<joint>_U, <joint>_W = elastic displacement of the joint along global X, Y (in); <link>_u_end, <link>_w_end '// &
    '= axial and transverse elastic displacement of the link''s end 2 in the link''s rigid-body axes (in); '// &
    'sigma_max_e<k> = largest |stress| in element k over both outer fibres (psi)'

contains

  !> The mechanism summary (its non-blank lines), then the model's
  !> correlation table.
  subroutine write_mechanism_header(out, mech, table)
    type(table_t), intent(inout) :: out
    type(mechanism_t), intent(in) :: mech
    type(correlation_table_t), intent(in) :: table
    character(len=160), allocatable :: table_lines(:)
    associate (lines => mechanism_summary(mech))
      call out%comments(pack(lines, len_trim(lines) > 0))
    end associate
    call table%describe(table_lines)
    call out%comments(table_lines)
  end subroutine write_mechanism_header

  !> Joints whose elastic translation is a model unknown: pins, slider blocks,
  !> free ends and sleeves carried by a link, unless grounded.
  logical function joint_moves(mech, j)
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: j
    integer :: i
    joint_moves = .false.
    if (mech%joints(j)%grounded) return
    if (any(mech%joints(j)%kind == [joint_pin, joint_slider_fixed, joint_free])) then
      joint_moves = .true.
    else if (mech%joints(j)%kind == joint_slider_link) then
      do i = 1, mech%joints(j)%n_links
        if (mech%joints(j)%link(i) /= mech%joints(j)%sliding_link) joint_moves = .true.
      end do
    end if
  end function joint_moves

  !> The element and its node (1 or 2) at which joint j's displacement is
  !> read: the first link end there that does not slide through the joint's
  !> sleeve.  element = 0 if none.
  subroutine joint_carrier(mech, j, element, node)
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: j
    integer, intent(out) :: element, node
    integer :: i, link
    element = 0
    node = 0
    do i = 1, mech%joints(j)%n_links
      link = mech%joints(j)%link(i)
      if (mech%joints(j)%kind == joint_slider_link .and. link == mech%joints(j)%sliding_link) cycle
      node = mech%joints(j)%link_end(i)
      element = mech%links(link)%first_element
      if (node == 2) element = element + mech%links(link)%n_elements - 1
      return
    end do
  end subroutine joint_carrier

  !> Response column names: moving joints' U, W; links' end-2 u, w; the
  !> largest stress of each element; every name with the suffix.
  function response_column_names(mech, n_elements, suffix) result(names)
    type(mechanism_t), intent(in) :: mech
    integer, intent(in) :: n_elements
    character(len=*), intent(in) :: suffix
    character(len=32), allocatable :: names(:)
    integer :: j, i, e
    allocate(names(0))
    do j = 1, mech%n_joints
      if (.not. joint_moves(mech, j)) cycle
      names = [character(len=32) :: names, trim(mech%joints(j)%name)//'_U'//suffix, &
               trim(mech%joints(j)%name)//'_W'//suffix]
    end do
    do i = 1, mech%n_links
      names = [character(len=32) :: names, trim(mech%links(i)%name)//'_u_end'//suffix, &
               trim(mech%links(i)%name)//'_w_end'//suffix]
    end do
    do e = 1, n_elements
      names = [character(len=32) :: names, 'sigma_max_e'//str(e)//suffix]
    end do
  end function response_column_names

  !> '<link>_s<position>': the name of the point at `s` times a link's length
  !> (at most 4 decimals, no trailing zeros), the stem of its columns.
  function link_point_name(link, s) result(label)
    character(len=*), intent(in) :: link
    real(dp), intent(in) :: s
    character(len=:), allocatable :: label
    character(len=16) :: num
    integer :: i
    write(num, '(f6.4)') s
    i = len_trim(num)
    do while (num(i:i) == '0')
      i = i - 1
    end do
    if (num(i:i) == '.') i = i - 1
    label = trim(link)//'_s'//trim(adjustl(num(1:i)))
  end function link_point_name
end module mechanism_report
