program flexmech
  implicit none
  print '(a)', 'flexmech placeholder'
end program flexmech
