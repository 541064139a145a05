# Tennant's four-bar built in 3D at 100 rad/s, linear material, one revolution from the rigid-body
# state: flexmech's spatial analysis (consistent element, two elements a link, undamped) against Exudyn
# (geometrically exact 3D beams, 64 elements a link).  The data come from
# bench/peers/spatial_fourbar.py (make bench-peers); then run gnuplot doc/figures/spatial_fourbar_peer.gp
# from the repository root (doc/spatial.md, "Cross-check against Exudyn").
set terminal pngcairo size 1100,750 font ',10'
set output 'doc/figures/spatial_fourbar_peer.png'
f = 'build/peers/spatial_fourbar/overlay.dat'
set multiplot layout 2,2 title 'Four-bar in 3D, 100 rad/s, from the rigid state: flexmech (solid) and Exudyn (dashed)'
set xlabel 'crank angle (deg)'
set xrange [0:360]
set key top left
set ylabel 'elastic displacement of B (in)'
plot f using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'B_{UX}, flexmech', \
     f using 1:3 with lines lw 2 dt 2 lc rgb '#d62728' title 'B_{UX}, Exudyn', \
     f using 1:4 with lines lw 2 lc rgb '#2ca02c' title 'B_{UY}, flexmech', \
     f using 1:5 with lines lw 2 dt 2 lc rgb '#ff7f0e' title 'B_{UY}, Exudyn'
set ylabel 'elastic displacement of C (in)'
plot f using 1:6 with lines lw 2 lc rgb '#1f77b4' title 'C_{UX}, flexmech', \
     f using 1:7 with lines lw 2 dt 2 lc rgb '#d62728' title 'C_{UX}, Exudyn', \
     f using 1:8 with lines lw 2 lc rgb '#2ca02c' title 'C_{UY}, flexmech', \
     f using 1:9 with lines lw 2 dt 2 lc rgb '#ff7f0e' title 'C_{UY}, Exudyn'
set ylabel 'crank root bending moment (lb in)'
plot f using 1:10 with lines lw 2 lc rgb '#1f77b4' title 'flexmech', \
     f using 1:11 with lines lw 2 dt 2 lc rgb '#d62728' title 'Exudyn'
set ylabel 'largest stress (psi)'
plot f using 1:12 with lines lw 2 lc rgb '#1f77b4' title 'coupler, flexmech', \
     f using 1:13 with lines lw 2 dt 2 lc rgb '#d62728' title 'coupler, Exudyn', \
     f using 1:14 with lines lw 2 lc rgb '#2ca02c' title 'rocker, flexmech', \
     f using 1:15 with lines lw 2 dt 2 lc rgb '#ff7f0e' title 'rocker, Exudyn'
unset multiplot
