# The four-bar at 100 rad/s on flexible mounts at A and D (inputs/general_support_fourbar.nml,
# mount mass 0.2 lb s^2/in, 5 % damping): peaks over the last of three revolutions against the
# ratio of the mounts' own frequency sqrt(k/m) to the crank's (doc/general_mechanism.md, "Support
# structure").  The table is written by python3 tools/support_sweep.py, which then runs this
# script from the repository root.
set terminal pngcairo size 1000,700 font ',10'
set output 'doc/figures/general_support_sweep.png'
f = 'doc/figures/general_support_sweep.dat'
set multiplot layout 3,1 title 'Four-bar on flexible mounts at A and D, crank 100 rad/s: peaks over the last revolution'
set grid
set xtics 1
set key top right
set ylabel 'peak stress / rigid ground'
plot f using 1:5 with linespoints pt 7 ps 0.6 title 'largest element stress, relative to the rigidly grounded four-bar'
set ylabel 'mount displacement (in)'
set logscale y
plot f using 1:6 with linespoints pt 7 ps 0.6 title 'largest |(U_X, U_Y)| of mounts A and D'
unset logscale y
set ylabel 'mount force (lb)'
set xlabel 'mount frequency sqrt(k/m) / crank frequency'
plot f using 1:7 with linespoints pt 7 ps 0.6 title 'largest force a mount carries, |k u + c u''| in the plane'
unset multiplot
