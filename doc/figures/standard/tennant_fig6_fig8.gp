# Comparison figures written by `flexmech plot --compare`; rerun with gnuplot
# from the directory it ran in.
data1 = "reference_outputs/tennant_fig5_linear.out"
data2 = "reference_outputs/tennant_fig6_material.out"
base = "doc/figures/standard/tennant_fig6_fig8"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key below; set datafile missing 'NaN'"
title = "T Figs. 6 and 8: 150 rad/sec, material nonlinearity"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_stress.".fmt
  set title title."\nlargest |stress| per element; line pattern: run, colour: column"
  set xlabel "crank angle (deg)"
  set ylabel "stress (psi)"
  set autoscale xfix
  set xtics 45
  plot data1 u 1:14 w l lw 2 dt 1 lc rgb "#000072b2" t "coupler, linear", \
       data2 u 1:14 w l lw 2 dt 2 lc rgb "#000072b2" t "coupler, nonlinear (D_k = 1)"
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
  set xtics 45
  plot data1 u 1:5 w l lw 2 dt 1 lc rgb "#000072b2" t "C_U, linear", \
       data2 u 1:5 w l lw 2 dt 2 lc rgb "#000072b2" t "C_U, nonlinear (D_k = 1)"
  set output
}
