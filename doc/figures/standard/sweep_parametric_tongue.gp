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
  eval (fmt eq "png" ? "set terminal pngcairo size 1000,640 font ',11' noenhanced" : "set terminal svg size 1000,640 dynamic font ',11' noenhanced")
  eval common
  set output base."_peaks.".fmt
  set title title."\nsummary peaks against the swept value"
  set multiplot layout 1,1 title title."\nsummary peaks against the swept value"
  unset title
  set key below
  set xlabel "omega (rad/s)"
  set ylabel "peak stress"
  unset logscale y
  plot data u 1:15 w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "element_1_peak_stress_exact_periodic", \
       data u 1:16 w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "element_2_peak_stress_exact_periodic", \
       data u 1:17 w lp lw 2 ps 1.1 lc rgb "#00009e73" pt 9 dt 1 t "element_3_peak_stress_exact_periodic", \
       data u 1:($5 > 1.000001 ? $15 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" t "unbounded (Floquet multiplier > 1)", \
       data u 1:($5 > 1.000001 ? $16 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" notitle, \
       data u 1:($5 > 1.000001 ? $17 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" notitle, \
       data u 1:($4 < 1.0000000000E-02 ? $15 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" t "near a forced resonance (rcond of the shooting matrix < 0.01)", \
       data u 1:($4 < 1.0000000000E-02 ? $16 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" notitle, \
       data u 1:($4 < 1.0000000000E-02 ? $17 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" notitle, \
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
  plot data u 1:($14 > 0 ? $14 : NaN) w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "cost_cpu_seconds_shooting", \
       data u 1:($19 > 0 ? $19 : NaN) w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "cost_total_cpu_seconds", \
       data u 1:($5 > 1.000001 ? $14 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" t "unbounded (Floquet multiplier > 1)", \
       data u 1:($5 > 1.000001 ? $19 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" notitle, \
       data u 1:($4 < 1.0000000000E-02 ? $14 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" t "near a forced resonance (rcond of the shooting matrix < 0.01)", \
       data u 1:($4 < 1.0000000000E-02 ? $19 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" notitle, \
       NaN notitle
  set ylabel "count (log scale)"
  set logscale y
  plot data u 1:($11 > 0 ? $11 : NaN) w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "cost_shooting_revolutions_integrated", \
       data u 1:($12 > 0 ? $12 : NaN) w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "cost_shooting_steps", \
       data u 1:($13 > 0 ? $13 : NaN) w lp lw 2 ps 1.1 lc rgb "#00009e73" pt 9 dt 1 t "cost_shooting_rhs_evaluations", \
       data u 1:($18 > 0 ? $18 : NaN) w lp lw 2 ps 1.1 lc rgb "#00cc79a7" pt 11 dt 1 t "cost_kinematics_solutions", \
       data u 1:($5 > 1.000001 ? $11 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" t "unbounded (Floquet multiplier > 1)", \
       data u 1:($5 > 1.000001 ? $12 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" notitle, \
       data u 1:($5 > 1.000001 ? $13 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" notitle, \
       data u 1:($5 > 1.000001 ? $18 : NaN) w p pt 2 ps 2.5 lw 2 lc rgb "#d00000" notitle, \
       data u 1:($4 < 1.0000000000E-02 ? $11 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" t "near a forced resonance (rcond of the shooting matrix < 0.01)", \
       data u 1:($4 < 1.0000000000E-02 ? $12 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" notitle, \
       data u 1:($4 < 1.0000000000E-02 ? $13 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" notitle, \
       data u 1:($4 < 1.0000000000E-02 ? $18 : NaN) w p pt 6 ps 2.5 lw 2 lc rgb "#e07000" notitle, \
       NaN notitle
  unset multiplot
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? "set terminal pngcairo size 1000,640 font ',11' noenhanced" : "set terminal svg size 1000,640 dynamic font ',11' noenhanced")
  eval common
  set output base."_multipliers.".fmt
  set title title."\nlargest Floquet multiplier moduli (above 1: unbounded, parametric resonance)"
  set multiplot layout 1,1 title title."\nlargest Floquet multiplier moduli (above 1: unbounded, parametric resonance)"
  unset title
  set key below
  set xlabel "omega (rad/s)"
  set ylabel "modulus"
  unset logscale y
  plot data u 1:5 w lp lw 2 ps 1.1 lc rgb "#000072b2" pt 7 dt 1 t "floquet_multipliers_largest_moduli_1", \
       data u 1:6 w lp lw 2 ps 1.1 lc rgb "#00d55e00" pt 5 dt 1 t "floquet_multipliers_largest_moduli_2", \
       data u 1:7 w lp lw 2 ps 1.1 lc rgb "#00009e73" pt 9 dt 1 t "floquet_multipliers_largest_moduli_3", \
       data u 1:8 w lp lw 2 ps 1.1 lc rgb "#00cc79a7" pt 11 dt 1 t "floquet_multipliers_largest_moduli_4", \
       data u 1:9 w lp lw 2 ps 1.1 lc rgb "#00e69f00" pt 13 dt 1 t "floquet_multipliers_largest_moduli_5", \
       data u 1:10 w lp lw 2 ps 1.1 lc rgb "#0056b4e9" pt 1 dt 1 t "floquet_multipliers_largest_moduli_6", \
       NaN notitle
  unset multiplot
  set output
}
