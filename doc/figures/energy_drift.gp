# Energy drift of the four-bar with the driver stopped (all effects on, 100
# periods undamped) against rtol: doc/verification_transient.md §4, numbers from
# bench/bench_transient_verification.f90 (table 5).  Run from the repository root.
set terminal pngcairo size 700,480 font ',10'
set output 'doc/figures/energy_drift.png'
$d << EOD
1e-4  4.637e-3
1e-5  2.968e-3
1e-6  5.233e-5
1e-7  2.782e-6
1e-8  7.748e-8
1e-9  2.193e-8
1e-10 2.440e-9
EOD
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'rtol (Adams, atol = 1e-5 rtol)'
set ylabel 'max |E(t) - E(0)| / E(0) over 100 periods'
set title 'Four-bar, driver stopped, all effects on, released from mode 1 (0.02 in)'
set key top left
set xrange [3e-11:3e-4]
plot $d using 1:2 with linespoints pt 7 lw 2 title 'flexmech', \
     10*x with lines dt 2 title '10 rtol', 100*x with lines dt 3 title '100 rtol'
