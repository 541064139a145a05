# Standard figures of doc/figures/data/sweep_parametric_tongue.out (analysis: sweep).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "doc/figures/data/sweep_parametric_tongue.out"
base = "doc/figures/standard/sweep_parametric_tongue"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "Parametric-resonance tongue near 295 rad/s: largest Floquet multiplier against crank speed (undamped linear four-bar)"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_peaks.".fmt
  set title title."\nsummary peaks against the swept value"
  set xlabel "omega"
  set key inside left top
  plot data u 1:15 w lp lw 2 pt 7 ps 0.8 lc rgb "#000072b2" t "element_1_peak_stress_exact_periodic", \
       data u 1:16 w lp lw 2 pt 7 ps 0.8 lc rgb "#00d55e00" t "element_2_peak_stress_exact_periodic", \
       data u 1:17 w lp lw 2 pt 7 ps 0.8 lc rgb "#00009e73" t "element_3_peak_stress_exact_periodic"
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
  plot data u 1:14 w lp lw 2 pt 7 ps 0.8 lc rgb "#000072b2" t "cost_cpu_seconds_shooting", \
       data u 1:19 w lp lw 2 pt 7 ps 0.8 lc rgb "#00d55e00" t "cost_total_cpu_seconds"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_multipliers.".fmt
  set title title."\nlargest Floquet multiplier moduli (above 1: parametric resonance)"
  set xlabel "omega"
  set key inside left top
  plot data u 1:5 w lp lw 2 pt 7 ps 0.8 lc rgb "#000072b2" t "floquet_multipliers_largest_moduli_1", \
       data u 1:6 w lp lw 2 pt 7 ps 0.8 lc rgb "#00d55e00" t "floquet_multipliers_largest_moduli_2", \
       data u 1:7 w lp lw 2 pt 7 ps 0.8 lc rgb "#00009e73" t "floquet_multipliers_largest_moduli_3", \
       data u 1:8 w lp lw 2 pt 7 ps 0.8 lc rgb "#00cc79a7" t "floquet_multipliers_largest_moduli_4", \
       data u 1:9 w lp lw 2 pt 7 ps 0.8 lc rgb "#00e69f00" t "floquet_multipliers_largest_moduli_5", \
       data u 1:10 w lp lw 2 pt 7 ps 0.8 lc rgb "#0056b4e9" t "floquet_multipliers_largest_moduli_6"
  set output
}
