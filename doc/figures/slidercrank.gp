# Slider-crank at 150 rad/s (inputs/slidercrank_150_*.nml): largest |sigma| in
# the crank and in the coupler during the third turn, one and four elements
# per link, linear and nonlinear.  Run from the repository root.
set terminal pngcairo size 1000,420 font ',10'
set output 'doc/figures/slidercrank_150.png'
set multiplot layout 1,2 title 'Slider-crank (crank 5, coupler 11 in, block 3.5e-4 lb s^2/in) at 150 rad/s, beta = 1e-5 s: third turn'
set xlabel 'crank angle (deg, third turn)'
set xrange [0:360]
set xtics 60
set key top right
lin = 'reference_outputs/slidercrank_150_linear.out'
ref = 'reference_outputs/slidercrank_150_refined.out'
non = 'reference_outputs/slidercrank_150_nonlinear.out'
set ylabel 'crank: max |{/Symbol s}| (psi)'
plot lin using ($2-720):($2>=720 ? $11 : 1/0) with lines lw 2 title '1 element/link', \
     ref using ($2-720):($2>=720 ? ($11>$12 ? ($11>$13 ? ($11>$14?$11:$14) : ($13>$14?$13:$14)) : ($12>$13 ? ($12>$14?$12:$14) : ($13>$14?$13:$14))) : 1/0) with lines dt 2 lw 2 title '4 elements/link', \
     non using ($2-720):($2>=720 ? $11 : 1/0) with lines lw 1 title '1 element, all effects'
set ylabel 'coupler: max |{/Symbol s}| (psi)'
plot lin using ($2-720):($2>=720 ? $12 : 1/0) with lines lw 2 title '1 element/link', \
     ref using ($2-720):($2>=720 ? ($15>$16 ? ($15>$17 ? ($15>$18?$15:$18) : ($17>$18?$17:$18)) : ($16>$17 ? ($16>$18?$16:$18) : ($17>$18?$17:$18))) : 1/0) with lines dt 2 lw 2 title '4 elements/link', \
     non using ($2-720):($2>=720 ? $12 : 1/0) with lines lw 1 title '1 element, all effects'
unset multiplot
