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
  eval (fmt eq "png" ? "set terminal pngcairo size 1000,640 font ',11' noenhanced" : "set terminal svg size 1000,640 dynamic font ',11' noenhanced")
  eval common
  set output base."_peaks.".fmt
  set title title."\nsummary peaks against the swept value"
  set multiplot layout 1,1 title title."\nsummary peaks against the swept value"
  unset title
  set key below
  set xlabel "omega (rad/s)"
  set ylabel "peak stress (log scale)"
  set logscale y
  plot data u 1:($11 > 0 ? $11 : NaN) w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "element_1_peak_stress_harmonic_series", \
       data u 1:($12 > 0 ? $12 : NaN) w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "element_2_peak_stress_harmonic_series", \
       data u 1:($13 > 0 ? $13 : NaN) w lp lw 2 ps 1.1 lc rgb "#00009e73" pt 9 dt 1 t "element_3_peak_stress_harmonic_series", \
       NaN notitle
  unset multiplot
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? "set terminal pngcairo size 1000,700 font ',11' noenhanced" : "set terminal svg size 1000,700 dynamic font ',11' noenhanced")
  eval common
  set output base."_cost.".fmt
  set title title."\ncost of each point"
  set multiplot layout 2,1 title title."\ncost of each point"
  unset title
  set key below
  set xlabel "omega (rad/s)"
  set ylabel "CPU seconds (log scale)"
  set logscale y
  plot data u 1:($10 > 0 ? $10 : NaN) w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "cost_cpu_seconds_harmonic", \
       data u 1:($15 > 0 ? $15 : NaN) w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "cost_total_cpu_seconds", \
       NaN notitle
  set ylabel "count"
  unset logscale y
  plot data u 1:4 w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "cost_harmonics_used", \
       data u 1:5 w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "cost_outer_iterations", \
       data u 1:6 w lp lw 2 ps 1.1 lc rgb "#00009e73" pt 9 dt 1 t "cost_factorizations", \
       data u 1:7 w lp lw 2 ps 1.1 lc rgb "#00cc79a7" pt 11 dt 1 t "cost_linear_assemblies", \
       data u 1:8 w lp lw 2 ps 1.1 lc rgb "#00e69f00" pt 13 dt 1 t "cost_nonlinear_assemblies", \
       data u 1:9 w lp lw 2 ps 1.1 lc rgb "#0056b4e9" pt 1 dt 1 t "cost_nonlinear_integrand_evaluations", \
       data u 1:14 w lp lw 2 ps 1.1 lc rgb "#00000000" pt 7 dt 1 t "cost_kinematics_solutions", \
       NaN notitle
  unset multiplot
  set output
}
