# Comparison figures written by `flexmech plot --compare`; rerun with gnuplot
# from the directory it ran in.
data1 = "reference_outputs/fourbar_100_linear.out"
data2 = "reference_outputs/fourbar_100_nonlinear.out"
base = "doc/figures/standard/fourbar_100_linear_vs_nonlinear"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key below; set datafile missing 'NaN'"
title = "Four-bar at 100 rad/s from the rigid-body state"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_stress.".fmt
  set title title."\nlargest |stress| per element; line pattern: run, colour: column"
  set xlabel "crank angle (deg)"
  set ylabel "stress (psi)"
  set autoscale xfix
  set xtics 360
  plot data1 u 2:13 w l lw 2 dt 1 lc rgb "#000072b2" t "crank, linear", \
       data2 u 2:13 w l lw 2 dt 2 lc rgb "#000072b2" t "crank, all nonlinear effects", \
       data1 u 2:14 w l lw 2 dt 1 lc rgb "#00d55e00" t "coupler, linear", \
       data2 u 2:14 w l lw 2 dt 2 lc rgb "#00d55e00" t "coupler, all nonlinear effects", \
       data1 u 2:15 w l lw 2 dt 1 lc rgb "#00009e73" t "rocker, linear", \
       data2 u 2:15 w l lw 2 dt 2 lc rgb "#00009e73" t "rocker, all nonlinear effects"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_joints.".fmt
  set title title."\njoint elastic displacement (global axes); line pattern: run, colour: column"
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  set autoscale xfix
  set xtics 360
  plot data1 u 2:3 w l lw 2 dt 1 lc rgb "#000072b2" t "B_U, linear", \
       data2 u 2:3 w l lw 2 dt 2 lc rgb "#000072b2" t "B_U, all nonlinear effects", \
       data1 u 2:4 w l lw 2 dt 1 lc rgb "#00d55e00" t "B_W, linear", \
       data2 u 2:4 w l lw 2 dt 2 lc rgb "#00d55e00" t "B_W, all nonlinear effects"
  set output
}
