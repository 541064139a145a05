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
  set title title."\nlargest |stress| per element; bold: the last revolution (crank angle >= 1440 deg)"
  set xtics 360
  set mxtics 4
  set autoscale xfix
  set xlabel "crank angle (deg)"
  set ylabel "stress (psi)"
  plot data u 2:($2 < split ? $13 : NaN) w l lw 1 lc rgb "#a00072b2" t "", \
       data u 2:($2 >= split ? $13 : NaN) w l lw 2 lc rgb "#000072b2" t "sigma_max_e1", \
       data u 2:($2 < split ? $14 : NaN) w l lw 1 lc rgb "#a0d55e00" t "", \
       data u 2:($2 >= split ? $14 : NaN) w l lw 2 lc rgb "#00d55e00" t "sigma_max_e2", \
       data u 2:($2 < split ? $15 : NaN) w l lw 1 lc rgb "#a0009e73" t "", \
       data u 2:($2 >= split ? $15 : NaN) w l lw 2 lc rgb "#00009e73" t "sigma_max_e3"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_joints.".fmt
  set title title."\njoint elastic displacement U (global X), W (global Y); bold: the last revolution (crank angle >= 1440 deg)"
  set xtics 360
  set mxtics 4
  set autoscale xfix
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  plot data u 2:($2 < split ? $3 : NaN) w l lw 1 lc rgb "#a00072b2" t "", \
       data u 2:($2 >= split ? $3 : NaN) w l lw 2 lc rgb "#000072b2" t "B_U", \
       data u 2:($2 < split ? $4 : NaN) w l lw 1 lc rgb "#a0d55e00" t "", \
       data u 2:($2 >= split ? $4 : NaN) w l lw 2 lc rgb "#00d55e00" t "B_W", \
       data u 2:($2 < split ? $5 : NaN) w l lw 1 lc rgb "#a0009e73" t "", \
       data u 2:($2 >= split ? $5 : NaN) w l lw 2 lc rgb "#00009e73" t "C_U", \
       data u 2:($2 < split ? $6 : NaN) w l lw 1 lc rgb "#a0cc79a7" t "", \
       data u 2:($2 >= split ? $6 : NaN) w l lw 2 lc rgb "#00cc79a7" t "C_W"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_links.".fmt
  set title title."\nlink end 2 deformation in the link's rigid-body axes; bold: the last revolution (crank angle >= 1440 deg)"
  set xtics 360
  set mxtics 4
  set autoscale xfix
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  plot data u 2:($2 < split ? $7 : NaN) w l lw 1 lc rgb "#a00072b2" t "", \
       data u 2:($2 >= split ? $7 : NaN) w l lw 2 lc rgb "#000072b2" t "crank_u_end", \
       data u 2:($2 < split ? $8 : NaN) w l lw 1 lc rgb "#a0d55e00" t "", \
       data u 2:($2 >= split ? $8 : NaN) w l lw 2 lc rgb "#00d55e00" t "crank_w_end", \
       data u 2:($2 < split ? $9 : NaN) w l lw 1 lc rgb "#a0009e73" t "", \
       data u 2:($2 >= split ? $9 : NaN) w l lw 2 lc rgb "#00009e73" t "coupler_u_end", \
       data u 2:($2 < split ? $10 : NaN) w l lw 1 lc rgb "#a0cc79a7" t "", \
       data u 2:($2 >= split ? $10 : NaN) w l lw 2 lc rgb "#00cc79a7" t "coupler_w_end", \
       data u 2:($2 < split ? $11 : NaN) w l lw 1 lc rgb "#a0e69f00" t "", \
       data u 2:($2 >= split ? $11 : NaN) w l lw 2 lc rgb "#00e69f00" t "rocker_u_end", \
       data u 2:($2 < split ? $12 : NaN) w l lw 1 lc rgb "#a056b4e9" t "", \
       data u 2:($2 >= split ? $12 : NaN) w l lw 2 lc rgb "#0056b4e9" t "rocker_w_end"
  set output
}
