# Four-bar transient results (reference outputs of inputs/fourbar_*.nml).
# Run from the repository root:  gnuplot doc/figures/fourbar_transient.gp
# Columns: 1 t, 2 crank_deg, 3 B_U, 4 B_W, 5 C_U, 6 C_W, 7-12 link end deformations,
#          13-15 sigma_max of elements 1 (crank), 2 (coupler), 3 (rocker).
set terminal pngcairo size 1000,620 font ",11"
set grid
set key top right
set xlabel 'crank angle (deg)'

do for [w in "100 150"] {
  lin = sprintf('reference_outputs/fourbar_%s_linear.out', w)
  non = (w eq "100") ? 'reference_outputs/fourbar_100_nonlinear.out' : 'reference_outputs/fourbar_150_geometric.out'
  lab = (w eq "100") ? 'all nonlinear effects' : 'geometric nonlinearities'
  set output sprintf('doc/figures/fourbar_%s_joint_B.png', w)
  set title sprintf('Four-bar at %s rad/s from the rigid-body state: elastic displacement of pin B', w)
  set ylabel 'displacement (in)'
  plot lin u 2:3 w l lw 1.5 t 'U_B linear', non u 2:3 w l lw 1.5 dt 2 t 'U_B '.lab, \
       lin u 2:4 w l lw 1.5 t 'W_B linear', non u 2:4 w l lw 1.5 dt 2 t 'W_B '.lab
  set output sprintf('doc/figures/fourbar_%s_joint_C.png', w)
  set title sprintf('Four-bar at %s rad/s from the rigid-body state: elastic displacement of pin C', w)
  plot lin u 2:5 w l lw 1.5 t 'U_C linear', non u 2:5 w l lw 1.5 dt 2 t 'U_C '.lab, \
       lin u 2:6 w l lw 1.5 t 'W_C linear', non u 2:6 w l lw 1.5 dt 2 t 'W_C '.lab
  set output sprintf('doc/figures/fourbar_%s_stress.png', w)
  set title sprintf('Four-bar at %s rad/s: maximum |stress| per element', w)
  set ylabel 'max |stress| (psi)'
  plot lin u 2:13 w l lw 1.5 t 'crank, linear', non u 2:13 w l lw 1.5 dt 2 t 'crank, '.lab, \
       lin u 2:14 w l lw 1.5 t 'coupler, linear', non u 2:14 w l lw 1.5 dt 2 t 'coupler, '.lab, \
       lin u 2:15 w l lw 1.5 t 'rocker, linear', non u 2:15 w l lw 1.5 dt 2 t 'rocker, '.lab
}
set output 'doc/figures/fourbar_150_damped_stress.png'
set title 'Four-bar at 150 rad/s, linear, beta = 1e-5 s: start-up and periodic steady state'
set ylabel 'max |stress| (psi)'
plot 'reference_outputs/fourbar_150_damped.out' u 2:13 w l lw 1.5 t 'crank', '' u 2:14 w l lw 1.5 t 'coupler', '' u 2:15 w l lw 1.5 t 'rocker'
