#!/bin/sh
# `flexmech plot` on one output of every analysis (transient, steady harmonic,
# steady harmonic + exact, optimize, lsode_check, sweep): runs headless, exits
# 0 and draws non-empty PNG files (PNG signature checked) and SVG files; the
# scripts committed in doc/figures/standard/ are what `flexmech plot` writes
# today (doc figures and user figures cannot drift apart); --animate draws
# a GIF of at least 30 frames for a transient and a steady run.
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
check reference_outputs/fourbar_150_damped.out stress joints links
check reference_outputs/beam_pinned_large.out stress links
check reference_outputs/tennant_fig3_linear.out stress joints links
check reference_outputs/tennant_fig5_exact.out stress joints links
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
for out in reference_outputs/fourbar_150_damped.out reference_outputs/tennant_fig3_linear.out; do
  stem=$(basename "$out" .out)
  if "$bin" plot "$out" -d "$work/anim" --png --animate > "$work/$stem.anim.log" 2>&1 &&
     [ "$(head -c 6 "$work/anim/${stem}_anim.gif")" = "GIF89a" ] &&
     [ "$(grep -c '^# crank_deg' "$work/anim/${stem}_anim.dat")" -gt 30 ]; then
    echo "ok: animation of $out"
  else
    echo "FAIL: no animation of $out"; cat "$work/$stem.anim.log"; fail=1
  fi
done
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
