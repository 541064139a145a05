# Spin-up beam of Kane, Ryan & Banerjee (1987): tip transverse deflection in the
# rotating frame (column beam_w_end) for Ws = 4 and 10 rad/s, 8 elements, the
# consistent element (default with stretching on) beside Kear's element with
# exact stretching, which locks.  Decks inputs/spinup_ws*.nml; run from the
# repository root.
set terminal pngcairo size 900,460 font ',10'
set output 'doc/figures/spinup.png'
set xlabel 't (s)'
set ylabel 'tip deflection in the rotating frame (m)'
set key bottom right
set grid
set title 'Spin-up beam, L = 8 m, Ts = 15 s, 8 elements (consistent: 4-32 elements agree to 1e-4 at Ws = 4)'
plot 'reference_outputs/spinup_ws4.out' using 1:6 with lines lw 2 lc rgb '#1f77b4' title 'Ws = 4, consistent', \
     'reference_outputs/spinup_ws4_kear.out' using 1:6 with lines lw 2 dt 2 lc rgb '#1f77b4' title 'Ws = 4, Kear (locks)', \
     'reference_outputs/spinup_ws10.out' using 1:6 with lines lw 2 lc rgb '#d62728' title 'Ws = 10, consistent', \
     'reference_outputs/spinup_ws10_kear.out' using 1:6 with lines lw 2 dt 2 lc rgb '#d62728' title 'Ws = 10, Kear (locks)'
