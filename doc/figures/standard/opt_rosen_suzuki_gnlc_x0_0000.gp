# Standard figures of reference_outputs/opt_rosen_suzuki_gnlc_x0_0000.out (analysis: optimize).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "reference_outputs/opt_rosen_suzuki_gnlc_x0_0000.out"
base = "doc/figures/standard/opt_rosen_suzuki_gnlc_x0_0000"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "Rosen-Suzuki, GNLC, x0 = [0, 0, 0, 0] (P Table I)"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_history.".fmt
  set title title."\noptimizer history"
  set multiplot layout 2,2 title title
  set xlabel "iteration k"
  set xtics 1
  unset key
  set title "objective F"
  plot data u 1:3 w lp lw 2 pt 7 lc rgb "#000072b2"
  set title "max constraint violation"
  set yrange [-1:1]
  plot data u 1:4 w lp lw 2 pt 7 lc rgb "#000072b2"
  set autoscale y
  set title "step |s| (log scale)"
  set logscale y
  set format y "%.0e"
  plot data u 1:($5 > 0 ? $5 : NaN) w lp lw 2 pt 7 lc rgb "#000072b2"
  unset logscale y
  set format y "% h"
  set title "design variables"
  set key on inside right top
  unset logscale y
  plot data u 1:7 w lp lw 2 pt 7 ps 0.6 lc rgb "#000072b2" t "x1", \
       data u 1:8 w lp lw 2 pt 7 ps 0.6 lc rgb "#00d55e00" t "x2", \
       data u 1:9 w lp lw 2 pt 7 ps 0.6 lc rgb "#00009e73" t "x3", \
       data u 1:10 w lp lw 2 pt 7 ps 0.6 lc rgb "#00cc79a7" t "x4"
  unset multiplot
  set output
}
