# Comparison figures written by `flexmech plot --compare`; rerun with gnuplot
# from the directory it ran in.
data1 = "/tmp/dex/design_fourbar_mass_150.initial.out"
data2 = "/tmp/dex/design_fourbar_mass_150.final.out"
base = "doc/figures/design/design_fourbar_mass_150_stress"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key below; set datafile missing 'NaN'"
title = "Tennant four-bar at 150 rad/s: peak stresses, initial (h = 1 in) and minimum-mass design"

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
  plot data1 u 1:13 w l lw 2 dt 1 lc rgb "#000072b2" t "sigma_max_e1, initial", \
       data2 u 1:13 w l lw 2 dt 2 lc rgb "#000072b2" t "sigma_max_e1, final", \
       data1 u 1:14 w l lw 2 dt 1 lc rgb "#00d55e00" t "sigma_max_e2, initial", \
       data2 u 1:14 w l lw 2 dt 2 lc rgb "#00d55e00" t "sigma_max_e2, final", \
       data1 u 1:15 w l lw 2 dt 1 lc rgb "#00009e73" t "sigma_max_e3, initial", \
       data2 u 1:15 w l lw 2 dt 2 lc rgb "#00009e73" t "sigma_max_e3, final"
  set output
}
