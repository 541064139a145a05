# Hinged beam with immovable ends, stretching on (doc/verification_transient.md §2):
# omega_NL/omega_L against a/r.  Left: the exact period of Woinowsky-Krieger's
# single-mode Duffing equation, its one-term form and flexmech (4, 8, 16
# elements; numbers from bench/bench_transient_verification.f90, table 2).
# Right: stress history next to mid-span in inputs/beam_pinned_large.nml
# (a = 2r) with |cos| at the linear and at the exact nonlinear period.  The
# release from the bending mode with no axial displacement is not in axial
# equilibrium (w_x^2/2 is not uniform), so undamped axial waves (3e4 rad/s,
# strain up to 2e-3) ring on top of the bending stress: the scattered points.
# Run from the repository root: gnuplot doc/figures/beam_large_amplitude.gp
set terminal pngcairo size 1000,420 font ',10'
set output 'doc/figures/beam_large_amplitude.png'
set multiplot layout 1,2
duffing(x) = pi*sqrt(1 + x**2/4)/(2*EllipticK(sqrt((x**2/4)/(2*(1 + x**2/4)))))
onemode(x) = sqrt(1 + 3.0/16*x**2)
$fe << EOD
# a/r  4el  8el  16el
0.5  1.02527 1.02369 1.02326
1.0  1.09696 1.09121 1.08964
1.5  1.20581 1.19429 1.19112
2.0  1.34223 1.32396 1.31892
EOD
set title 'Frequency ratio, hinged beam, immovable ends'
set xlabel 'a / r'
set ylabel '{/Symbol w}_{NL} / {/Symbol w}_L'
set xrange [0:2.1]
set key top left
set samples 200
plot duffing(x) with lines lw 2 title 'exact (elliptic) Duffing period', \
     onemode(x) with lines dt 2 title 'sqrt(1 + 3/16 (a/r)^2)', \
     $fe using 1:2 with points pt 4 ps 1.2 title '4 elements', \
     $fe using 1:3 with points pt 6 ps 1.2 title '8 elements', \
     $fe using 1:4 with points pt 7 ps 0.8 title '16 elements'
E = 10.87e6; rho = 2.536e-4; A = 0.25; I = 0.25/12.0; L = 20.0
w0 = (pi/L)**2*sqrt(E*I/(rho*A))
TL = 2*pi/w0
r = duffing(2.0)
f = 'reference_outputs/beam_pinned_large.out'
s0 = real(system("awk '!/^#/{print $8; exit}' ".f))
set title 'inputs/beam\_pinned\_large.nml: a = 2r, 8 elements (axial waves on top)'
set xlabel 't / T_L'
set ylabel '|{/Symbol s}| element 4 (psi)'
set xrange [0:3.2]
set yrange [0:*]
set samples 2000
set key outside bottom center horizontal
plot f using ($1/TL):8 with points pt 7 ps 0.4 title 'flexmech', \
     s0*abs(cos(2*pi*x*r)) with lines lw 1 title 'exact nonlinear period (shape: |cos|)', \
     s0*abs(cos(2*pi*x)) with lines dt 2 title 'linear period'
unset multiplot
