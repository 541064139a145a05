# Fig. 4  Deformation Ũ1 of the free end of the crank at 200 rad/sec
# Run from the repository root: gnuplot doc/figures/tennant_fig4.gp
# Data: the reference outputs of the decks in inputs/ (regenerate them with
# build/bin/flexmech inputs/<deck>.nml -o reference_outputs/<deck>.out).
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'doc/figures/tennant_fig4.png'
set title "Fig. 4  Deformation Ũ1 of the free end of the crank at 200 rad/sec"
set xlabel 'crank position (deg)'
set ylabel "Ũ1 = B_U (in)"
set xrange [0:360]
set xtics 45
set grid
set key bottom center
plot 'reference_outputs/tennant_fig4_linear.out' using 1:3 with lines lw 2 title 'linear, no shear angle (Bahgat-Willmert stand-in)', 'reference_outputs/tennant_fig4_shear_d0.out' using 1:3 with lines lw 2 dt 2 title 'shear angle, tracing constants 0', 'reference_outputs/tennant_fig4_shear_d1.out' using 1:3 with lines lw 2 dt 4 title 'shear angle, tracing constants 1 (crank past the R-O peak)'
