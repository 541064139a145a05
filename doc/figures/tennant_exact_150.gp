# Harmonic series (T26, N = 8) and exact periodic solution, linear four-bar at 150 rad/sec
# Run from the repository root: gnuplot doc/figures/tennant_exact_150.gp
# Data: the reference outputs of the decks in inputs/ (regenerate them with
# build/bin/flexmech inputs/<deck>.nml -o reference_outputs/<deck>.out).
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'doc/figures/tennant_exact_150.png'
set title "Harmonic series (T26, N = 8) and exact periodic solution, linear four-bar at 150 rad/sec"
set xlabel 'crank position (deg)'
set ylabel "Ũ2 = C_U (in)"
set xrange [0:360]
set xtics 45
set grid
set key bottom center
plot 'reference_outputs/tennant_fig5_exact.out' using 1:5 with lines lw 2 title 'harmonic series, N = 8 (the paper''s method)', 'reference_outputs/tennant_fig5_exact.out' using 1:18 with lines lw 2 dt 2 title 'exact periodic solution (shooting), beta = 1e-5 s'
