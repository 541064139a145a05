#!/bin/sh
# A transient run split in two by a restart file ends where the unbroken run
# ends: 2 revolutions, then 1 more from the restart file, against 3 in one go
# (four-bar at 150 rad/s, damped, rtol 1e-9).  DLSODE restarts from scratch
# (order 1, small step) at the break, so the two agree to the integration
# error, not to the bit: 1e-5 relative on every column of the last row.
# usage: restart_continues_run.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
base=inputs/fourbar_150_damped.nml
sed -e "s/rtol = 1.0e-7/rtol = 1.0e-9/" -e "s/revolutions = 5/revolutions = 3/" \
    -e "s/output_step_deg = 2.0/output_step_deg = 90.0/" "$base" > "$work/whole.nml"
sed -e "s/revolutions = 3/revolutions = 2/" \
    -e "s|damping_beta = 1.0e-5|damping_beta = 1.0e-5, restart_out = '$work/state.rst'|" "$work/whole.nml" > "$work/first.nml"
sed -e "s/revolutions = 3/revolutions = 1/" \
    -e "s|damping_beta = 1.0e-5|damping_beta = 1.0e-5, initial = 'restart', restart_in = '$work/state.rst'|" \
    "$work/whole.nml" > "$work/second.nml"
"$flexmech" "$work/whole.nml" -o "$work/whole.out" > /dev/null
"$flexmech" "$work/first.nml" -o "$work/first.out" > /dev/null
"$flexmech" "$work/second.nml" -o "$work/second.out" > /dev/null
# keep the header and the last row of each
for f in whole second; do
  { awk '!/^#/ {exit} {print}' "$work/$f.out"; grep -v '^#' "$work/$f.out" | tail -n 1; } > "$work/$f.last"
done
printf 'default 1e-5 1e-9\nsigma_max_* 1e-5 1e-3\n' > "$work/tol"
"$compare" "$work/whole.last" "$work/second.last" "$work/tol"
