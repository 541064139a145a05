# Standard figures of /tmp/dex/design_fourbar_mass_150.out (analysis: design).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "/tmp/dex/design_fourbar_mass_150.out"
base = "doc/figures/design/design_fourbar_mass_150"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "Minimum mass of Tennant's four-bar at 150 rad/s: stress <= 20 ksi, frequency >= 5 omega"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_history.".fmt
  set title title."\ndesign history   "
  set multiplot layout 2,3 title title
  set xlabel "iteration k"
  unset key
  set title "mass of the links"
  plot data u 1:4 w lp lw 2 pt 7 lc rgb "#000072b2"
  set title "max constraint violation (log scale)"
  set logscale y
  set format y "%.0e"
  plot data u 1:($5 > 0 ? $5 : NaN) w lp lw 2 pt 7 lc rgb "#000072b2"
  unset logscale y
  set format y "% h"
  set title "move limit (log scale)"
  set logscale y
  set format y "%.0e"
  plot data u 1:($6 > 0 ? $6 : NaN) w lp lw 2 pt 7 lc rgb "#000072b2"
  unset logscale y
  set format y "% h"
  set title "analysis constraints g (feasible: g <= 0)"
  set key on inside right top
  plot data u 1:10 w lp lw 2 pt 7 ps 0.6 lc rgb "#000072b2" t "g1", \
       data u 1:11 w lp lw 2 pt 7 ps 0.6 lc rgb "#00d55e00" t "g2", \
       data u 1:12 w lp lw 2 pt 7 ps 0.6 lc rgb "#00009e73" t "g3", \
       data u 1:13 w lp lw 2 pt 7 ps 0.6 lc rgb "#00cc79a7" t "g4"
  unset key
  set title "design variables"
  set key on inside right top
  unset logscale y
  plot data u 1:7 w lp lw 2 pt 7 ps 0.6 lc rgb "#000072b2" t "link_h(1)", \
       data u 1:8 w lp lw 2 pt 7 ps 0.6 lc rgb "#00d55e00" t "link_h(2)", \
       data u 1:9 w lp lw 2 pt 7 ps 0.6 lc rgb "#00009e73" t "link_h(3)"
  unset multiplot
  set output
}
