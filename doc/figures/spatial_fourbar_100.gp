# Paper E section 8.4, Figs 8-14 (captions as in the OCR, FORMULATION.md §8.4):
# the four-bar analysed by the spatial code at 100 rad/s, every effect on, the
# consistent element at two elements a link, from the static state
# (inputs/spatial_fourbar_100.nml).  Node 2 = joint B, node 3 = joint C; a
# link's stress is the larger of its two elements' (columns 39-44).  Run from
# the repository root.
set terminal pngcairo size 1200,1100 font ',9'
set output 'doc/figures/spatial_fourbar_100.png'
f = 'reference_outputs/spatial_fourbar_100.out'
max(a, b) = a > b ? a : b
set multiplot layout 4,2 title 'Spatial code, four-bar at 100 rad/s, all effects, from the static state (paper E Figs 8-14)'
set xlabel 'crank angle (deg)'
set key off
set title 'Fig 8: axial displacements of node 2 (global X)'
set ylabel 'B_{UX} (in)'
plot f using 2:3 with lines lw 1.5
set title 'Fig 9: vertical displacements of node 2 (global Y)'
set ylabel 'B_{UY} (in)'
plot f using 2:4 with lines lw 1.5
set title 'Fig 10: angle of rotation of node 2 (crank end, v_x)'
set ylabel 'rad'
plot f using 2:14 with lines lw 1.5
set title 'Fig 11: axial displacements of node 3 (global X)'
set ylabel 'C_{UX} (in)'
plot f using 2:6 with lines lw 1.5
set title 'Fig 12: maximum absolute stress of the crank'
set ylabel 'psi'
plot f using 2:(max($39, $40)) with lines lw 1.5
set title 'Fig 13: maximum absolute stress of the coupler'
plot f using 2:(max($41, $42)) with lines lw 1.5
set title 'Fig 14: maximum absolute stress of the rocker'
plot f using 2:(max($43, $44)) with lines lw 1.5
set title 'out of the plane: B_{UZ}, C_{UZ} (round-off)'
set ylabel 'in'
plot f using 2:5 with lines lw 1.5, f using 2:8 with lines dt 2
unset multiplot
