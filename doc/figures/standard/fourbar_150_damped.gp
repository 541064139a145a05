# Standard figures of reference_outputs/fourbar_150_damped.out (analysis: transient).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "reference_outputs/fourbar_150_damped.out"
base = "doc/figures/standard/fourbar_150_damped"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "Four-bar at 150 rad/s, linear, light damping beta = 1e-5 s: start-up and periodic steady state"
split = 1440.000000

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_stress.".fmt
  set title title."\nlargest |stress| per element (outer fibre); last complete revolution (run's 1440-1800 deg)"
  set xrange [0:360]
  set xtics 45
  set xlabel "crank angle (deg)"
  set ylabel "stress (psi)"
  plot data u ($2 - 1440):($2 >= split ? $13 : NaN) w l lw 2 lc rgb "#000072b2" t "crank", \
       data u ($2 - 1440):($2 >= split ? $14 : NaN) w l lw 2 lc rgb "#00d55e00" t "coupler", \
       data u ($2 - 1440):($2 >= split ? $15 : NaN) w l lw 2 lc rgb "#00009e73" t "rocker"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_joints.".fmt
  set title title."\njoint elastic displacement (global axes); last complete revolution (run's 1440-1800 deg)"
  set xrange [0:360]
  set xtics 45
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  plot data u ($2 - 1440):($2 >= split ? $3 : NaN) w l lw 2 lc rgb "#000072b2" t "B_U", \
       data u ($2 - 1440):($2 >= split ? $4 : NaN) w l lw 2 lc rgb "#00d55e00" t "B_W", \
       data u ($2 - 1440):($2 >= split ? $5 : NaN) w l lw 2 lc rgb "#00009e73" t "C_U", \
       data u ($2 - 1440):($2 >= split ? $6 : NaN) w l lw 2 lc rgb "#00cc79a7" t "C_W"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_links.".fmt
  set title title."\nlink end 2 deformation in the link's rigid-body axes; last complete revolution (run's 1440-1800 deg)"
  set xrange [0:360]
  set xtics 45
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  plot data u ($2 - 1440):($2 >= split ? $7 : NaN) w l lw 2 lc rgb "#000072b2" t "crank_u_end", \
       data u ($2 - 1440):($2 >= split ? $8 : NaN) w l lw 2 lc rgb "#00d55e00" t "crank_w_end", \
       data u ($2 - 1440):($2 >= split ? $9 : NaN) w l lw 2 lc rgb "#00009e73" t "coupler_u_end", \
       data u ($2 - 1440):($2 >= split ? $10 : NaN) w l lw 2 lc rgb "#00cc79a7" t "coupler_w_end", \
       data u ($2 - 1440):($2 >= split ? $11 : NaN) w l lw 2 lc rgb "#00e69f00" t "rocker_u_end", \
       data u ($2 - 1440):($2 >= split ? $12 : NaN) w l lw 2 lc rgb "#0056b4e9" t "rocker_w_end"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_shape.".fmt
  set title title."\ndeformed shape at the largest |stress| (outer fibre) of the last revolution, 72007 psi in crank"
  set title title."\ndeformed shape at the largest |stress| (outer fibre) of the last revolution, 72007 psi in crank\ncrank angle 10.0 deg of turn 5, t = 1.68715E-01 s; links bent by their elements' shape functions; elastic displacements x 10"
  sdata = "doc/figures/standard/fourbar_150_damped_shape.dat"
  set size ratio -1
  set grid lc rgb "#e0e0e0"
  set key outside below horizontal
  set xrange [-0.728780:12.8751]
  set yrange [-0.728780:11.2260]
  set xlabel "X (in)"
  set ylabel "Y (in)"
  set palette defined (0 "#2c7bb6", 0.25 "#00a6ca", 0.5 "#90d743", 0.75 "#f98e09", 1 "#d7191c")
  set cbrange [0:0.7201E+05]
  set cblabel "|stress| (outer fibre) (psi)"
  plot sdata index 2*(0) u 1:2 w l lw 7 lc rgb "#d8d8d8" t "rigid-body position", \
       sdata index 2*(0)+1 u 1:2 w p pt 6 ps 1.2 lc rgb "#b0b0b0" notitle, \
       sdata index 2*(0) u 3:4:5 w l lw 4 lc palette t "deformed, elastic displacements x 10", \
       sdata index 2*(0)+1 u 3:4 w p pt 7 ps 1.2 lc rgb "#202020" notitle
  set output
}
