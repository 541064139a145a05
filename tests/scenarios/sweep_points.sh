#!/bin/sh
# Sweeps (&sweep): every point is the analysis of its own deck, a failing point
# is reported and does not stop the others, and an array section sets every
# element.
#  1. omega = 175, 100, 75 on Tennant's linear four-bar (deck written with
#     omega = 50, n_harmonics = 12): 175 rad/s puts harmonic 8 at 1400 rad/s
#     on a frozen natural frequency (the harmonic series stops: exit 3); the
#     sweep exits 3, its summary has rows for 100 and 75 and a comment line
#     with the diagnosis for 175 (tables hold finite numbers only) before the
#     column names (the failing point is the first: the names stay the last
#     '#' line before the rows), and the
#     omega = 100 point equals reference_outputs/tennant_fig3_linear.out (the
#     same analysis at 100 rad/s) within that reference's tolerances — so the
#     override replaced the deck's omega = 50.
#  2. link_n_elements(1:3) = 2 gives 6 elements (columns sigma_max_e1..e6).
#  3. several decks on one command line: one table of exit statuses, exit 3
#     when one of them fails.
#  4. a group of the general mechanism (&general_mechanism driver_rate).
# usage: sweep_points.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); compare=$2; work=$3
rm -rf "$work"; mkdir -p "$work"
fail=0
sed -e 's/omega = 100.0/omega = 50.0/' -e 's/n_harmonics = 12/n_harmonics = 8/' \
    inputs/tennant_fig3_linear.nml > "$work/speeds.nml"
cat >> "$work/speeds.nml" <<'EOD'
&sweep group = 'mechanism', variable = 'omega', values = 175, 100, 75 /
EOD
sed -i 's/n_harmonics = 8/n_harmonics = 12/' "$work/speeds.nml"
set +e; "$flexmech" "$work/speeds.nml" -o "$work/speeds.out" > "$work/speeds.log" 2>&1; st=$?; set -e
[ $st -eq 3 ] || { echo "FAIL: sweep with a failing point exited $st, expected 3"; cat "$work/speeds.log"; fail=1; }
rows=$(grep -v '^#' "$work/speeds.out" | awk '{printf "%g:%d ", $1, $2}')
[ "$rows" = "100:0 75:0 " ] || { echo "FAIL: rows (omega:exit) '$rows', expected '100:0 75:0 '"; fail=1; }
grep -q '^# point 1: omega = 175: exit 3 (analysis stopped), no row; flexmech: analysis stopped: harmonic series: near resonance' \
  "$work/speeds.out" || { echo "FAIL: point 1's diagnosis missing from the summary"; fail=1; }
"$compare" reference_outputs/tennant_fig3_linear.out "$work/speeds_points/speeds_002.out" \
  reference_outputs/tennant_fig3_linear.tol > "$work/cmp.log" 2>&1 \
  || { echo "FAIL: point omega = 100 differs from tennant_fig3_linear:"; head "$work/cmp.log"; fail=1; }
# the column names stay the last '#' line before the rows (the comparator reads them there)
"$compare" "$work/speeds.out" "$work/speeds.out" > "$work/self.log" 2>&1 \
  || { echo "FAIL: the summary is not a readable table:"; head -3 "$work/self.log"; fail=1; }
[ -s "$work/speeds_points/speeds_003.out" ] || { echo "FAIL: the point after the failing one did not run"; fail=1; }

cp inputs/tennant_fig3_linear.nml "$work/mesh.nml"
cat >> "$work/mesh.nml" <<'EOD'
&sweep group = 'mechanism', variable = 'link_n_elements(1:3)', values = 1, 2 /
EOD
"$flexmech" "$work/mesh.nml" -o "$work/mesh.out" > /dev/null 2>&1 || { echo "FAIL: mesh sweep failed"; fail=1; }
grep -q 'sigma_max_e6' "$work/mesh_points/mesh_002.out" || { echo "FAIL: link_n_elements(1:3) = 2 did not give 6 elements"; fail=1; }
grep -q 'sigma_max_e4' "$work/mesh_points/mesh_001.out" && { echo "FAIL: 1 element per link gave more than 3 elements"; fail=1; }

# 4. a group of the general mechanism: the crank rate of the rigid four-bar, each point's deck
#    carrying its value
cp inputs/kinematics_fourbar.nml "$work/rates.nml"
cat >> "$work/rates.nml" <<'EOD'
&sweep group = 'general_mechanism', variable = 'driver_rate', values = 100, 200 /
EOD
"$flexmech" "$work/rates.nml" -o "$work/rates.out" > /dev/null 2>&1 || { echo "FAIL: general_mechanism sweep failed"; fail=1; }
rows=$(grep -v '^#' "$work/rates.out" | awk '{printf "%g:%d ", $1, $2}')
[ "$rows" = "100:0 200:0 " ] || { echo "FAIL: general_mechanism sweep rows '$rows', expected '100:0 200:0 '"; fail=1; }
grep -q 'driver_rate = 200' "$work/rates_points/rates_002.nml" || { echo "FAIL: point 2's deck lacks driver_rate = 200"; fail=1; }

cp inputs/lsode_kinetics.nml "$work/good.nml"
sed 's/rtol = .*/rtol = -1.0/' inputs/lsode_kinetics.nml > "$work/bad.nml"
set +e; (cd "$work" && "$flexmech" good.nml bad.nml > batch.log 2>&1); st=$?; set -e
[ $st -eq 3 ] || { echo "FAIL: batch with a bad deck exited $st, expected 3"; fail=1; }
grep -qE '^ +0 +ok +good.nml -> good.out' "$work/batch.log" || { echo "FAIL: batch table lacks good.nml"; cat "$work/batch.log"; fail=1; }
grep -qE '^ +2 +input error +bad.nml -> bad.out' "$work/batch.log" || { echo "FAIL: batch table lacks bad.nml"; fail=1; }
[ $fail -eq 0 ] && echo "sweep points: all ok"
exit $fail
