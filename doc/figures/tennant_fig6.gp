# Fig. 6  Comparison of deformations Ũ2 at 150 rad/sec for material nonlinearity
# Run from the repository root: gnuplot doc/figures/tennant_fig6.gp
# Data: the reference outputs of the decks in inputs/ (regenerate them with
# build/bin/flexmech inputs/<deck>.nml -o reference_outputs/<deck>.out).
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'doc/figures/tennant_fig6.png'
set title "Fig. 6  Comparison of deformations Ũ2 at 150 rad/sec for material nonlinearity"
set xlabel 'crank position (deg)'
set ylabel "Ũ2 = C_U (in)"
set xrange [0:360]
set xtics 45
set grid
set key bottom center
plot 'reference_outputs/tennant_fig5_linear.out' using 1:5 with lines lw 2 title 'linear', 'reference_outputs/tennant_fig6_material.out' using 1:5 with lines lw 2 dt 2 title 'nonlinear (D_k = 1)'
