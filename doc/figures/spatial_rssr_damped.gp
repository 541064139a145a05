# RSSR four-bar at 100 rad/s, damped (inputs/spatial_rssr_100_damped.nml):
# elastic translation of the spherical joints B and C over eight turns from the
# rigid-body state into the periodic steady state, on the consistent element at
# 1, 4, 2 elements (doc/spatial.md, "RSSR").  Run from the repository root.
set terminal pngcairo size 1000,600 font ',10'
set output 'doc/figures/spatial_rssr_damped.png'
f = 'reference_outputs/spatial_rssr_100_damped.out'
set multiplot layout 2,1 title 'RSSR (crank about Z, rocker about X), 100 rad/s, beta = 5e-4 s, consistent element'
set xlabel 'crank angle (deg)'
set ylabel 'joint B (in)'
set key outside right
plot f using 2:3 with lines title 'B_{UX}', f using 2:4 with lines title 'B_{UY}', f using 2:5 with lines title 'B_{UZ}'
set ylabel 'joint C (in)'
plot f using 2:6 with lines title 'C_{UX}', f using 2:7 with lines title 'C_{UY}', f using 2:8 with lines title 'C_{UZ}'
unset multiplot
