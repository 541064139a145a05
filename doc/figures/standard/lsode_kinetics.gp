# Standard figures of reference_outputs/lsode_kinetics.out (analysis: lsode_check).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "reference_outputs/lsode_kinetics.out"
base = "doc/figures/standard/lsode_kinetics"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "LSODE verification: stiff chemical kinetics"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_solution.".fmt
  set title title."\neach column against t"
  set multiplot layout 2,2 title title
  unset key
  set xlabel "t"
  set logscale x
  set title "y1"
  plot data u 1:2 w lp lw 2 pt 7 ps 0.5 lc rgb "#000072b2"
  set title "y2"
  plot data u 1:3 w lp lw 2 pt 7 ps 0.5 lc rgb "#00d55e00"
  set title "y3"
  plot data u 1:4 w lp lw 2 pt 7 ps 0.5 lc rgb "#00009e73"
  set title "y1+y2+y3-1"
  plot data u 1:5 w lp lw 2 pt 7 ps 0.5 lc rgb "#00cc79a7"
  unset multiplot
  set output
}
