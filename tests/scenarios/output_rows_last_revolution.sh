#!/bin/sh
# &transient output_rows: 'last_revolution' writes exactly the rows of the
# last crank turn of the full run, 'none' writes no rows, and both print the
# same summary (peaks over every output time) as 'all'.  Same integration in
# all three runs (the output times are the same), so rows and summaries agree
# to the last printed digit: compared exactly (tolerance 0).
# usage: output_rows_last_revolution.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
base=inputs/fourbar_150_damped.nml
sed -e "s/revolutions = 5/revolutions = 2/" -e "s/output_step_deg = 2.0/output_step_deg = 10.0/" "$base" > "$work/all.nml"
sed -e "s/damping_beta = 1.0e-5/damping_beta = 1.0e-5, output_rows = 'last_revolution'/" "$work/all.nml" > "$work/last.nml"
sed -e "s/damping_beta = 1.0e-5/damping_beta = 1.0e-5, output_rows = 'none'/" "$work/all.nml" > "$work/none.nml"
for f in all last none; do "$flexmech" "$work/$f.nml" -o "$work/$f.out" > /dev/null; done
rows() { grep -v '^#' "$1" | grep -c . || true; }
[ "$(rows "$work/all.out")" -eq 73 ] || { echo "all: $(rows "$work/all.out") rows, expected 73 (2 turns every 10 deg)"; exit 1; }
[ "$(rows "$work/last.out")" -eq 37 ] || { echo "last: $(rows "$work/last.out") rows, expected 37 (360 to 720 deg)"; exit 1; }
[ "$(rows "$work/none.out")" -eq 0 ] || { echo "none: $(rows "$work/none.out") rows, expected 0"; exit 1; }
# the last revolution's rows are the tail of the full table
{ awk '!/^#/ {exit} {print}' "$work/all.out"; grep -v '^#' "$work/all.out" | tail -n 37; } > "$work/all.tail"
printf 'default 0 0\n' > "$work/tol"
"$compare" "$work/all.tail" "$work/last.out" "$work/tol"
grep '^# summary' "$work/all.out" > "$work/all.sum"
for f in last none; do
  grep '^# summary' "$work/$f.out" > "$work/$f.sum"
  cmp -s "$work/all.sum" "$work/$f.sum" || { echo "$f: summary differs from all"; diff "$work/all.sum" "$work/$f.sum"; exit 1; }
done
echo "output_rows: all 73 rows, last_revolution 37 (the tail), none 0; same summary"
