# Paper E section 8.4, Figs 15-18 (captions as in the OCR; Figs 19-21 read as the stresses, as
# Figs 12-14 at 100 rad/s, FORMULATION.md §8.4): the four-bar analysed by the spatial code at
# 150 rad/s, every effect on, the consistent element at two elements a link.  Two readings of the
# paper's unstated start and damping, under both of which the crank stays below the peak of the
# Ramberg-Osgood law (sigma* = 47631 psi): the first turn from the static state with light damping
# on the axial modes (inputs/spatial_fourbar_150.nml, beta = 1e-6 s), and the periodic state with
# beta = 3e-4 s (inputs/spatial_fourbar_150_damped.nml: its fourth turn, crank angle taken modulo
# 360).  Node 2 = joint B, node 3 = joint C; a link's stress is the larger of its two elements'
# (columns 39-44).  Run from the repository root.
set terminal pngcairo size 1200,1100 font ',9'
set output 'doc/figures/spatial_fourbar_150.png'
f = 'reference_outputs/spatial_fourbar_150.out'
g = 'reference_outputs/spatial_fourbar_150_damped.out'
max(a, b) = a > b ? a : b
last(x) = x >= 1080.0 - 1e-6 ? x - 1080.0 : NaN
a1 = 'first turn from the static state, {/Symbol b} = 1e-6 s'
a2 = 'periodic state, {/Symbol b} = 3e-4 s (4th turn)'
set multiplot layout 4,2 title 'Spatial code, four-bar at 150 rad/s, all effects (paper E Figs 15-21): two readings of the unstated start and damping'
set xlabel 'crank angle (deg)'
set xrange [0:360]
set key top right font ',8'
set title 'Fig 15: axial displacements of node 2 (global X)'
set ylabel 'B_{UX} (in)'
plot f using 2:3 with lines lw 1.5 title a1, g using (last($2)):3 with lines lw 1.5 title a2
set key off
set title 'Fig 16: vertical displacements of node 2 (global Y)'
set ylabel 'B_{UY} (in)'
plot f using 2:4 with lines lw 1.5, g using (last($2)):4 with lines lw 1.5
set title 'Fig 17: angle of rotation of node 2 (crank end, v_x)'
set ylabel 'rad'
plot f using 2:14 with lines lw 1.5, g using (last($2)):14 with lines lw 1.5
set title 'Fig 18: axial displacements of node 3 (global X)'
set ylabel 'C_{UX} (in)'
plot f using 2:6 with lines lw 1.5, g using (last($2)):6 with lines lw 1.5
set title 'Fig 19 (caption lost; as Fig 12): maximum absolute stress of the crank'
set ylabel 'psi'
set key center right font ',8'
plot f using 2:(max($39, $40)) with lines lw 1.5 notitle, g using (last($2)):(max($39, $40)) with lines lw 1.5 notitle, \
     47631 with lines dt 2 lc rgb 'black' title 'Ramberg-Osgood peak {/Symbol s}* = 47631 psi'
set key off
set title 'Fig 20 (caption lost; as Fig 13): maximum absolute stress of the coupler'
plot f using 2:(max($41, $42)) with lines lw 1.5, g using (last($2)):(max($41, $42)) with lines lw 1.5
set title 'Fig 21 (caption lost; as Fig 14): maximum absolute stress of the rocker'
plot f using 2:(max($43, $44)) with lines lw 1.5, g using (last($2)):(max($43, $44)) with lines lw 1.5
set title 'out of the plane: B_{UZ}, C_{UZ} (solver error level)'
set ylabel 'in'
plot f using 2:5 with lines lw 1.5, f using 2:8 with lines dt 2, g using (last($2)):5 with lines lw 1.5, g using (last($2)):8 with lines dt 2
unset multiplot
