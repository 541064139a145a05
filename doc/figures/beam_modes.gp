# Beams released from their first and second mode shapes (inputs/beam_*_mode*.nml):
# |sigma| of the element next to the left end against t/T (T: Euler-Bernoulli
# period), with the undamped theory |cos(2 pi t/T)| scaled to the first value.
# Run from the repository root: gnuplot doc/figures/beam_modes.gp
set terminal pngcairo size 1000,700 font ',10'
set output 'doc/figures/beam_modes.png'
set multiplot layout 2,2 title 'Beams with immovable ends released from a mode shape (4 elements, all effects on)'
E = 10.87e6; rho = 2.536e-4; A = 0.25; I = 0.25/12.0; L = 20.0
w(bl) = (bl/L)**2*sqrt(E*I/(rho*A))
set xlabel 't / T_{EB}'
set ylabel '|{/Symbol s}| element 1 (psi)'
set key outside bottom center horizontal
set samples 2000
set xrange [0:5]
do for [c in 'pinned_mode1:3.141592653589793 pinned_mode2:6.283185307179586 clamped_mode1:4.730040744862704 clamped_mode2:7.853204624095838'] {
  name = word(system('echo '.c.' | tr ":" " "'), 1)
  bl = real(word(system('echo '.c.' | tr ":" " "'), 2))
  f = 'reference_outputs/beam_'.name.'.out'
  T = 2*pi/w(bl)
  s0 = real(system("awk '!/^#/{print $5; exit}' ".f))
  set title name noenhanced
  plot f using ($1/T):5 with points pt 7 ps 0.4 title 'flexmech', \
       s0*abs(cos(2*pi*x)) with lines lw 1 title 'Euler-Bernoulli period'
}
unset multiplot
