#!/bin/sh
# `flexmech plot` on one output of every analysis (transient, steady harmonic,
# steady harmonic + exact, optimize, lsode_check, sweep): runs headless, exits
# 0 and draws non-empty PNG files (PNG signature checked) and SVG files; the
# scripts committed in doc/figures/standard/ are what `flexmech plot` writes
# today (doc figures and user figures cannot drift apart); --animate draws
# a GIF of at least 30 frames for a transient, a steady and a spatial run;
# with shape columns (shape_points) the links of all three are drawn bent.
# usage: plot_figures.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
bin=$1; work=$3
rm -rf "$work"; mkdir -p "$work"
command -v gnuplot >/dev/null 2>&1 || { echo "gnuplot not installed (make deps): skipped"; exit 0; }
fail=0
png_ok() {  # non-empty file that starts with the PNG signature
  [ -s "$1" ] && [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
}
check() {  # output, figures...
  out=$1; shift
  stem=$(basename "$out" .out)
  if ! "$bin" plot "$out" -d "$work" > "$work/$stem.log" 2>&1; then
    echo "FAIL: flexmech plot $out exited non-zero:"; cat "$work/$stem.log"; fail=1; return
  fi
  for fig in "$@"; do
    png_ok "$work/${stem}_$fig.png" || { echo "FAIL: $stem: no valid ${stem}_$fig.png"; fail=1; }
    [ -s "$work/${stem}_$fig.svg" ] || { echo "FAIL: $stem: no ${stem}_$fig.svg"; fail=1; }
  done
  echo "ok: $out -> $*"
}
check reference_outputs/fourbar_150_damped.out stress joints links shape
check reference_outputs/beam_pinned_large.out stress links
check reference_outputs/tennant_fig3_linear.out stress joints links shape
check reference_outputs/tennant_fig5_exact.out stress joints links shape
check reference_outputs/spatial_rssr_100.out stress joints links shape
# every optional column (stress_columns = 'all', link points, reactions) of a run written over its
# last revolution only (crank angle 1802-2160): its own axes and units, shifted onto 0-360 deg
check reference_outputs/fourbar_150_outputs.out stress sections moments forces joints links shape
grep -q 'ylabel "force (lb)"' "$work/fourbar_150_outputs.gp" && grep -q 'ylabel "moment (lb in)"' "$work/fourbar_150_outputs.gp" \
  && grep -q 'u (\$2 - 1800)' "$work/fourbar_150_outputs.gp" || { echo "FAIL: forces, moments or the shifted axis"; fail=1; }
grep -q '^  splot ' "$work/spatial_rssr_100.gp" || { echo "FAIL: the spatial run is not drawn in 3D"; fail=1; }
# the last complete revolution by default (crank angle 1440-1800 of five turns), all of it with --whole-run
grep -q 'set xrange \[0:360\]' "$work/fourbar_150_damped.gp" && grep -q 't "crank"' "$work/fourbar_150_damped.gp" \
  || { echo "FAIL: the default run's figures are not its last revolution on 0-360 deg with link names"; fail=1; }
"$bin" plot reference_outputs/fourbar_150_damped.out -d "$work/whole" --whole-run --script-only > /dev/null
grep -q 'set xtics 360' "$work/whole/fourbar_150_damped.gp" || { echo "FAIL: --whole-run does not draw every revolution"; fail=1; }
grep -q 'ylabel "stress (psi)"' "$work/fourbar_150_damped.gp" || { echo "FAIL: stress axis without its unit"; fail=1; }
check reference_outputs/opt_rosen_suzuki_gnlc_x0_0000.out history
check reference_outputs/lsode_kinetics.out solution
# a design history (the column layout of src/analysis/design_analysis.f90:
# k, analyses, cpu_s, mass, max_violation, move_limit, the design values,
# g<i>), synthetic: the design analysis has no reference output yet
cat > "$work/design_history.out" <<'EOD'
# title: design history layout
#  ANALYSIS='design',
#                      k                analyses                   cpu_s                    mass           max_violation              move_limit               link_h(1)               link_h(2)                      g1                      g2
  0 1 0.01 2.0 0.5 0.3 1.0 1.0 0.5 -0.2
  1 4 0.02 1.5 0.1 0.3 0.8 0.9 0.1 -0.1
  2 7 0.03 1.2 0.0 0.15 0.7 0.85 -0.01 -0.05
EOD
check "$work/design_history.out" history
grep -q 'analysis constraints g' "$work/design_history.gp" || { echo "FAIL: design history lacks the constraint panel"; fail=1; }
grep -q 't "link_h(1)"' "$work/design_history.gp" && ! grep -q 't "move_limit"' "$work/design_history.gp" \
  || { echo "FAIL: design values misidentified in the design history"; fail=1; }
for s in reference_outputs/sweep_*.out; do
  [ -f "$s" ] && check "$s" peaks cost
done
# the animation of a transient and of a steady run: GIF files (signature GIF89a)
for out in reference_outputs/fourbar_150_damped.out reference_outputs/tennant_fig3_linear.out \
           reference_outputs/spatial_rssr_100.out; do
  stem=$(basename "$out" .out)
  if "$bin" plot "$out" -d "$work/anim" --png --animate > "$work/$stem.anim.log" 2>&1 &&
     [ "$(head -c 6 "$work/anim/${stem}_anim.gif")" = "GIF89a" ] &&
     [ "$(grep -c '^when\[' "$work/anim/${stem}_anim.gp")" -gt 30 ]; then
    echo "ok: animation of $out"
  else
    echo "FAIL: no animation of $out"; cat "$work/$stem.anim.log"; fail=1
  fi
done
# a run with shape columns (shape_points): links drawn bent, no gnuplot chatter on the terminal
sed 's/^  damping_beta = 1.0e-5$/  damping_beta = 1.0e-5, shape_points = 6, revolutions = 1/' inputs/fourbar_150_damped.nml > "$work/shaped.nml"
"$bin" "$work/shaped.nml" -o "$work/shaped.out" > /dev/null
if "$bin" plot "$work/shaped.out" -d "$work/anim" --png --animate > "$work/shaped.log" 2>&1 &&
   grep -q "bent by their elements' shape functions" "$work/anim/shaped_anim.gp" &&
   ! grep -qi 'frames in animation' "$work/shaped.log" &&
   grep -q 'crank angle' "$work/anim/shaped_anim.gp"; then
  echo "ok: animation of bent links"
else
  echo "FAIL: animation of a run with shape columns"; cat "$work/shaped.log"; fail=1
fi
# the steady and the spatial analysis with shape columns: their links drawn bent too
sed 's/^  output_step_deg = 2.0$/  output_step_deg = 4.0, shape_points = 6/' inputs/tennant_fig3_linear.nml > "$work/steady_shaped.nml"
sed -e 's/^  revolutions = 1$/  revolutions = 0.5/' -e 's/^  output_step_deg = 5.0$/  output_step_deg = 10.0, shape_points = 4/' \
  inputs/spatial_rssr_100.nml > "$work/spatial_shaped.nml"
for stem in steady_shaped spatial_shaped; do
  "$bin" "$work/$stem.nml" -o "$work/$stem.out" > /dev/null
  if grep -q '_s0.5_' "$work/$stem.out" &&
     "$bin" plot "$work/$stem.out" -d "$work/anim" --png --animate > "$work/$stem.log" 2>&1 &&
     grep -q "bent by their elements' shape functions" "$work/anim/${stem}_anim.gp" &&
     grep -q "bent by their elements' shape functions" "$work/anim/$stem.gp" &&
     png_ok "$work/anim/${stem}_shape.png" && [ "$(head -c 6 "$work/anim/${stem}_anim.gif")" = "GIF89a" ]; then
    echo "ok: $stem drawn with bent links"
  else
    echo "FAIL: $stem not drawn with bent links"; cat "$work/$stem.log"; fail=1
  fi
done
# a tolerance sweep (synthetic summary): log x, the work-precision figure, a failed point marked
cat > "$work/sweep_rtol.out" <<'EOD'
# title: rtol sweep layout
# sweep: rtol of &transient over 4 values; point decks, outputs and logs in none/x_<k>.{nml,out,log}
# point 4: rtol = 1e-10: exit 3 (analysis stopped), no row
#  rtol exit_status element_1_peak_stress peak_b_u cost_steps cost_total_cpu_seconds
  1e-4 0 80034.9 0.0354 300 0.05
  1e-6 0 80031.97 0.03541 900 0.09
  1e-8 0 80031.973 0.035411 2900 0.2
EOD
check "$work/sweep_rtol.out" peaks cost work
grep -q 'set logscale x' "$work/sweep_rtol.gp" && grep -q 'set arrow 1 from 1.0000000000E-10' "$work/sweep_rtol.gp" \
  || { echo "FAIL: the rtol sweep lacks its log axis or its failed point"; fail=1; }
# a speed sweep of periodic shooting (synthetic summary): the x axis in rad/s, the point whose
# shooting matrix is nearly singular (rcond 1.6e-3) circled as near a forced resonance, the
# others (rcond 0.05, 0.13) not
cat > "$work/sweep_speed.out" <<'EOD'
# title: speed sweep layout
# sweep: omega of &mechanism over 3 values; point decks, outputs and logs in none/x_<k>.{nml,out,log}
#  omega exit_status rcond_of_the_newton_matrix_y_t_i_energy_units floquet_multipliers_largest_moduli_1 element_1_peak_stress_exact_periodic
  293 0 1.6e-3 1.0 1.38e7
  294 0 5.06e-2 1.0 3.88e5
  295 0 1.29e-1 1.0018 3.63e5
EOD
check "$work/sweep_speed.out" peaks
grep -q 'set xlabel "omega (rad/s)"' "$work/sweep_speed.gp" \
  && grep -q '(\$3 < 1.0000000000E-02 ? \$5 : NaN)' "$work/sweep_speed.gp" \
  && grep -q '(\$4 > 1.000001 ? \$5 : NaN)' "$work/sweep_speed.gp" \
  || { echo "FAIL: the speed sweep lacks its unit or its resonance marks"; fail=1; }
# an optimizer output has no mechanism: --animate is refused with exit 3
set +e; "$bin" plot reference_outputs/opt_hs15_gnlc_ns.out -d "$work/anim" --animate > /dev/null 2>&1; st=$?; set -e
[ $st -eq 3 ] || { echo "FAIL: --animate on an optimizer output exited $st, expected 3"; fail=1; }
# a file that is not an output: exit status 3, no crash
printf 'not a table\n' > "$work/bad.out"
set +e; "$bin" plot "$work/bad.out" -d "$work" > /dev/null 2>&1; st=$?; set -e
[ $st -eq 3 ] || { echo "FAIL: plot of a non-table exited $st, expected 3"; fail=1; }
# drift: every committed doc script is what tools/doc_figures.sh writes today
sh tools/doc_figures.sh "$bin" "$work/drift" --script-only > /dev/null
for gp in doc/figures/standard/*.gp; do
  [ -f "$gp" ] || continue
  new="$work/drift/$(basename "$gp")"
  [ -f "$new" ] || { echo "FAIL: $gp is no longer written by tools/doc_figures.sh"; fail=1; continue; }
  sed "s|$work/drift|doc/figures/standard|" "$new" | cmp -s - "$gp" || {
    echo "FAIL: $gp differs from what flexmech plot writes now (rerun sh tools/doc_figures.sh)"; fail=1; }
done
for new in "$work"/drift/*.gp; do
  [ -f "doc/figures/standard/$(basename "$new")" ] || { echo "FAIL: $(basename "$new") not committed in doc/figures/standard"; fail=1; }
done
[ $fail -eq 0 ] && echo "plot figures: all ok"
exit $fail
