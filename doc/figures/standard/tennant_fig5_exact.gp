# Standard figures of reference_outputs/tennant_fig5_exact.out (analysis: steady).
# Written by `flexmech plot`; rerun with gnuplot from the directory it ran in.
# Formats: gnuplot -e 'formats="png"' SCRIPT draws the PNG files only.
data = "reference_outputs/tennant_fig5_exact.out"
base = "doc/figures/standard/tennant_fig5_exact"
if (!exists("formats")) formats = "png svg"
term_png = "set terminal pngcairo size 1000,640 font ',11' noenhanced"
term_svg = "set terminal svg size 1000,640 dynamic font ',11' noenhanced"
common = "set grid; set key outside right top; set datafile missing 'NaN'"
title = "T Figs. 5-8 at 150 rad/sec, linear: harmonic series vs exact periodic solution"

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_stress.".fmt
  set title title."\nlargest |stress| per element (outer fibre); solid: harmonic series, dashed: exact"
  set xrange [0:360]
  set xtics 45
  set xlabel "crank angle (deg)"
  set ylabel "stress (psi)"
  plot data u 1:13 w l lw 2 lc rgb "#000072b2" t "crank (harmonic series)", \
       data u 1:26 w l lw 2 dt 2 lc rgb "#000072b2" t "crank (exact periodic)", \
       data u 1:14 w l lw 2 lc rgb "#00d55e00" t "coupler (harmonic series)", \
       data u 1:27 w l lw 2 dt 2 lc rgb "#00d55e00" t "coupler (exact periodic)", \
       data u 1:15 w l lw 2 lc rgb "#00009e73" t "rocker (harmonic series)", \
       data u 1:28 w l lw 2 dt 2 lc rgb "#00009e73" t "rocker (exact periodic)"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_joints.".fmt
  set title title."\njoint elastic displacement (global axes); solid: harmonic series, dashed: exact"
  set xrange [0:360]
  set xtics 45
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  plot data u 1:3 w l lw 2 lc rgb "#000072b2" t "B_U (harmonic series)", \
       data u 1:16 w l lw 2 dt 2 lc rgb "#000072b2" t "B_U (exact periodic)", \
       data u 1:4 w l lw 2 lc rgb "#00d55e00" t "B_W (harmonic series)", \
       data u 1:17 w l lw 2 dt 2 lc rgb "#00d55e00" t "B_W (exact periodic)", \
       data u 1:5 w l lw 2 lc rgb "#00009e73" t "C_U (harmonic series)", \
       data u 1:18 w l lw 2 dt 2 lc rgb "#00009e73" t "C_U (exact periodic)", \
       data u 1:6 w l lw 2 lc rgb "#00cc79a7" t "C_W (harmonic series)", \
       data u 1:19 w l lw 2 dt 2 lc rgb "#00cc79a7" t "C_W (exact periodic)"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_links.".fmt
  set title title."\nlink end 2 deformation in the link's rigid-body axes; solid: harmonic series, dashed: exact"
  set xrange [0:360]
  set xtics 45
  set xlabel "crank angle (deg)"
  set ylabel "displacement (in)"
  plot data u 1:7 w l lw 2 lc rgb "#000072b2" t "crank_u_end (harmonic series)", \
       data u 1:20 w l lw 2 dt 2 lc rgb "#000072b2" t "crank_u_end (exact periodic)", \
       data u 1:8 w l lw 2 lc rgb "#00d55e00" t "crank_w_end (harmonic series)", \
       data u 1:21 w l lw 2 dt 2 lc rgb "#00d55e00" t "crank_w_end (exact periodic)", \
       data u 1:9 w l lw 2 lc rgb "#00009e73" t "coupler_u_end (harmonic series)", \
       data u 1:22 w l lw 2 dt 2 lc rgb "#00009e73" t "coupler_u_end (exact periodic)", \
       data u 1:10 w l lw 2 lc rgb "#00cc79a7" t "coupler_w_end (harmonic series)", \
       data u 1:23 w l lw 2 dt 2 lc rgb "#00cc79a7" t "coupler_w_end (exact periodic)", \
       data u 1:11 w l lw 2 lc rgb "#00e69f00" t "rocker_u_end (harmonic series)", \
       data u 1:24 w l lw 2 dt 2 lc rgb "#00e69f00" t "rocker_u_end (exact periodic)", \
       data u 1:12 w l lw 2 lc rgb "#0056b4e9" t "rocker_w_end (harmonic series)", \
       data u 1:25 w l lw 2 dt 2 lc rgb "#0056b4e9" t "rocker_w_end (exact periodic)"
  set output
}

do for [fmt in formats] {
  reset
  eval (fmt eq "png" ? term_png : term_svg)
  eval common
  set output base."_shape.".fmt
  set title title."\ndeformed shape at the largest |stress| (outer fibre) of the steady revolution, 39275 psi in crank"
  set title title."\ndeformed shape at the largest |stress| (outer fibre) of the steady revolution, 39275 psi in crank\ncrank angle 8.0 deg, t = 9.30842E-04 s; elastic displacements x 10\ndrawn: the harmonic series (columns _exact: the exact periodic solution)"
  sdata = "doc/figures/standard/tennant_fig5_exact_shape.dat"
  set size ratio -1
  set grid lc rgb "#e0e0e0"
  set key outside below horizontal
  set xrange [-0.662356:11.7016]
  set yrange [-0.662356:11.1622]
  set xlabel "X (in)"
  set ylabel "Y (in)"
  set palette defined (0 "#2c7bb6", 0.25 "#00a6ca", 0.5 "#90d743", 0.75 "#f98e09", 1 "#d7191c")
  set cbrange [0:0.3928E+05]
  set cblabel "|stress| (outer fibre) (psi)"
  plot sdata index 2*(0) u 1:2 w l lw 7 lc rgb "#d8d8d8" t "rigid-body position", \
       sdata index 2*(0)+1 u 1:2 w p pt 6 ps 1.2 lc rgb "#b0b0b0" notitle, \
       sdata index 2*(0) u 3:4:5 w l lw 4 lc palette t "deformed, elastic displacements x 10 (links straight: no shape columns)", \
       sdata index 2*(0)+1 u 3:4 w p pt 7 ps 1.2 lc rgb "#202020" notitle
  set output
}
