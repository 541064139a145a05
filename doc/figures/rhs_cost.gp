# Cost of one right-hand side and of one BDF Jacobian against the number of
# elements (doc/benchmarks.md): data from bench/bench_transient.f90 ('cost'
# mode), copied to doc/figures/transient_rhs_cost.dat.  Run from the repository root.
set terminal pngcairo size 1000,420 font ',10'
set output 'doc/figures/rhs_cost.png'
set multiplot layout 1,2
f = 'doc/figures/transient_rhs_cost.dat'
set logscale xy
set xlabel 'elements (four-bar, 3n)'
set ylabel 'CPU microseconds per call'
set key bottom right font ",9"
set title 'One right-hand side'
set xrange [2:150]
plot f using 2:5 with linespoints pt 4 lw 2 title 'linear, rocker D->C as in the decks', \
     f using 2:7 with linespoints pt 7 lw 2 title 'linear, links end to end', \
     f using 2:8 with linespoints pt 5 lw 2 title 'all effects, links end to end', \
     0.8*x with lines dt 3 title '0.8 us x elements', 2.6*x with lines dt 3 title '2.6 us x elements'
set title 'One BDF Jacobian (dense M^{-1}K_t, model\_jacobian)'
plot f using 2:($9 > 0 ? $9 : 1/0) with linespoints pt 7 lw 2 title 'flexmech', \
     0.06*(x**3) with lines dt 3 title '0.06 us x elements^3'
unset multiplot
