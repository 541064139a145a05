# Comparison figures written by `flexmech plot --compare`; rerun with gnuplot
# from the directory it ran in.
data1 = "reference_outputs/tennant_fig4_linear.out"
data2 = "reference_outputs/tennant_fig4_shear_d0.out"
data3 = "reference_outputs/tennant_fig4_shear_d1.out"
base = "doc/figures/standard/tennant_fig4"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key below; set datafile missing 'NaN'"
title = "T Fig. 4: deformation U~1 (B_U) of the crank end at 200 rad/sec"

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
  plot data1 u 1:3 w l lw 2 dt 1 lc rgb "#000072b2" t "B_U, linear, no shear angle (Bahgat-Willmert stand-in)", \
       data2 u 1:3 w l lw 2 dt 2 lc rgb "#000072b2" t "B_U, shear angle, tracing constants 0", \
       data3 u 1:3 w l lw 2 dt 3 lc rgb "#000072b2" t "B_U, shear angle, tracing constants 1 (crank past the R-O peak)"
  set output
}
