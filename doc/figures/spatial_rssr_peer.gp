# RSSR four-bar at 100 rad/s, linear material, one revolution from the rigid-body
# state: flexmech (consistent element, 1, 4, 2 elements; Kear's element, one a
# link) against Exudyn (geometrically exact 3D beams, 64 elements a link).
# The data come from bench/peers/spatial_rssr.py (make bench-peers); then run
# gnuplot doc/figures/spatial_rssr_peer.gp from the repository root
# (doc/spatial.md, "Cross-check against Exudyn").
set terminal pngcairo size 1100,750 font ',10'
set output 'doc/figures/spatial_rssr_peer.png'
f = 'build/peers/spatial_rssr/overlay.dat'
set multiplot layout 2,2 title 'RSSR, 100 rad/s, from the rigid state: flexmech (consistent, solid; Kear''s, dotted) and Exudyn (dashed)'
set xlabel 'crank angle (deg)'
set xrange [0:360]
set key top left
set ylabel 'B_{UZ} (in)'
plot f using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'flexmech', \
     f using 1:3 with lines lw 2 dt 2 lc rgb '#d62728' title 'Exudyn', \
     f using 1:4 with lines dt 3 lc rgb '#7f7f7f' title 'Kear''s element'
set ylabel 'C_{UX} (in)'
plot f using 1:5 with lines lw 2 lc rgb '#1f77b4' title 'flexmech', \
     f using 1:6 with lines lw 2 dt 2 lc rgb '#d62728' title 'Exudyn', \
     f using 1:7 with lines dt 3 lc rgb '#7f7f7f' title 'Kear''s element'
set ylabel 'root bending moment (lb in)'
plot f using 1:14 with lines lw 2 lc rgb '#1f77b4' title 'crank, flexmech', \
     f using 1:15 with lines lw 2 dt 2 lc rgb '#d62728' title 'crank, Exudyn', \
     f using 1:17 with lines lw 2 lc rgb '#2ca02c' title 'rocker, flexmech', \
     f using 1:18 with lines lw 2 dt 2 lc rgb '#ff7f0e' title 'rocker, Exudyn'
set ylabel 'largest coupler stress (psi)'
plot f using 1:20 with lines lw 2 lc rgb '#1f77b4' title 'flexmech', \
     f using 1:21 with lines lw 2 dt 2 lc rgb '#d62728' title 'Exudyn', \
     f using 1:22 with lines dt 3 lc rgb '#7f7f7f' title 'Kear''s element'
unset multiplot
