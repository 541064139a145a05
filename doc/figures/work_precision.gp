# Work-precision of the transient analysis (doc/benchmarks.md): relative error
# of the peak coupler stress in the fifth turn (four-bar, 150 rad/s, beta =
# 1e-5 s, linear) against DLSODE CPU ms per crank turn, for each method and
# mesh over rtol = 1e-3 ... 1e-10.  Data: bench/bench_transient.f90, copied to
# doc/figures/transient_work_precision.dat.  Run from the repository root.
set terminal pngcairo size 1000,560 font ',10'
set output 'doc/figures/work_precision.png'
f = 'doc/figures/transient_work_precision.dat'
set logscale xy
set xlabel 'CPU ms per crank turn (one core)'
set ylabel 'relative error, peak coupler stress (5th turn)'
set title 'Four-bar at 150 rad/s, {/Symbol b} = 1e-5 s: error against the 16-element, rtol 1e-9 run'
set key outside right top
set grid
set yrange [1e-4:0.1]
set xrange [5:1e5]
set arrow from 20,1e-4 to 20,0.1 nohead dt 3 lc rgb 'red'
set arrow from 5,0.01 to 1e5,0.01 nohead dt 3 lc rgb 'red'
set label 'target: 1 % in 20 ms' at 22,0.07 tc rgb 'red'
plot for [n in '1 2 4 8 16'] f using ((strcol(1) eq 'bdf' && $2 == n+0) ? $6 : 1/0):5 with linespoints pt 7 lw 2 title 'bdf, '.n.' el/link', \
     for [n in '1 2 4 8 16'] f using ((strcol(1) eq 'bdf_band' && $2 == n+0) ? $6 : 1/0):5 with linespoints pt 4 dt 2 title 'bdf\_band, '.n.' el/link', \
     for [n in '1 2'] f using ((strcol(1) eq 'adams' && $2 == n+0) ? $6 : 1/0):5 with linespoints pt 2 dt 3 title 'adams, '.n.' el/link'
