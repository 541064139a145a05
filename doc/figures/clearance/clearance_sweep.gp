# Drawn by tools/clearance_sweep.sh from doc/figures/clearance/sweep.dat:
# last-revolution (5th) peaks against the radial clearance at pin C.
set terminal pngcairo size 900,420 font ',10'
set output 'doc/figures/clearance/clearance_sweep.png'
set multiplot layout 1,2 title 'Four-bar at 150 rad/s, clearance at pin C: peaks in the 5th revolution (c = 1e-5 in: the pinned limit)'
set logscale x
set xrange [5e-6:0.02]
set xlabel 'radial clearance c (in)'
set grid
set key top left
set ylabel 'peak |stress| (psi)'
plot 'doc/figures/clearance/sweep.dat' every 5::4 using 1:4 with linespoints pt 7 title 'coupler', \
     '' every 5::4 using 1:5 with linespoints pt 5 title 'rocker'
set ylabel 'peak contact force at C (lb)'
plot 'doc/figures/clearance/sweep.dat' every 5::4 using 1:8 with linespoints pt 7 title 'every step, 5 revolutions', \
     '' every 5::4 using 1:6 with linespoints pt 5 title '5th revolution, rows every 2 deg'
unset multiplot
