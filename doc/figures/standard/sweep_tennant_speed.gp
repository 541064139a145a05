# Standard figures of reference_outputs/sweep_tennant_speed.out (analysis: sweep).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "reference_outputs/sweep_tennant_speed.out"
base = "doc/figures/standard/sweep_tennant_speed"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "Sweep: linear four-bar, harmonic series, peak stress against crank speed"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_peaks.".fmt
  set title title."\nsummary peaks against the swept value"
  set xlabel "omega"
  set key inside left top
  plot data u 1:11 w lp lw 2 pt 7 ps 0.8 lc rgb "#000072b2" t "element_1_peak_stress_harmonic_series", \
       data u 1:12 w lp lw 2 pt 7 ps 0.8 lc rgb "#00d55e00" t "element_2_peak_stress_harmonic_series", \
       data u 1:13 w lp lw 2 pt 7 ps 0.8 lc rgb "#00009e73" t "element_3_peak_stress_harmonic_series"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_cost.".fmt
  set title title."\ncost of each point (log scale)"
  set xlabel "omega"
  set key inside left top
  set logscale y
  set ylabel "CPU seconds"
  plot data u 1:10 w lp lw 2 pt 7 ps 0.8 lc rgb "#000072b2" t "cost_cpu_seconds_harmonic", \
       data u 1:15 w lp lw 2 pt 7 ps 0.8 lc rgb "#00d55e00" t "cost_total_cpu_seconds"
  set output
}
