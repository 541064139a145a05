!> The program's name and version, printed in every output header.
module version
  implicit none
  private
  public :: program_name, program_version

  character(len=*), parameter :: program_name = 'flexmech'
  character(len=*), parameter :: program_version = '0.1.0'
end module version
