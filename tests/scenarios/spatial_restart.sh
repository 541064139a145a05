#!/bin/sh
# Restart and start from a mode in the spatial analysis.
# 1. The undamped RSSR (inputs/spatial_rssr_100.nml) over one revolution in
#    one run, and as two half revolutions, the second started from the first
#    one's restart file: the second run starts at the first one's end time
#    and crank angle (to the 1e-9 of the printed digits) and ends where the
#    single run ends: joint translations B_U*, C_U* within 1e-4 of their
#    largest value over the revolution (the deck's static start replaced by
#    the restart file in the second run; measured about 1e-7: DLSODE restarts
#    at order 1 with fresh step sizes, an rtol = 1e-7 difference; a lost rate
#    or time offset gives O(1)).
# 2. initial = 'mode' (mode 1, amplitude 0.01 in): the first row holds the
#    mode at rest, no link-end transverse deflection above the amplitude and
#    some above a tenth of it.
# usage: spatial_restart.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; work=$3
mkdir -p "$work"
deck=inputs/spatial_rssr_100.nml
sed 's/revolutions = 1/revolutions = 1.0/' "$deck" > "$work/full.nml"
sed "s/revolutions = 1/revolutions = 0.5, restart_out = '$(echo "$work" | sed 's/[\/&]/\\&/g')\/half.dat'/" "$deck" > "$work/first.nml"
sed "s/revolutions = 1/revolutions = 0.5, initial = 'restart', restart_in = '$(echo "$work" | sed 's/[\/&]/\\&/g')\/half.dat'/; s/initial_static = T/initial_static = F/" "$deck" > "$work/second.nml"
"$flexmech" "$work/full.nml" -o "$work/full.out" > /dev/null
"$flexmech" "$work/first.nml" -o "$work/first.out" > /dev/null
"$flexmech" "$work/second.nml" -o "$work/second.out" > /dev/null
grep -q 'initial state: restart file' "$work/second.out"
# first row of the second run = last row of the first; last rows of full and second
last1=$(grep -v '^#' "$work/first.out" | tail -n 1)
first2=$(grep -v '^#' "$work/second.out" | head -n 1)
lastf=$(grep -v '^#' "$work/full.out" | tail -n 1)
last2=$(grep -v '^#' "$work/second.out" | tail -n 1)
scale=$(grep -v '^#' "$work/full.out" | awk '{ for (i = 3; i <= 8; i++) { a = $i < 0 ? -$i : $i; if (a > m) m = a } } END { print m }')
echo "joint translation scale $scale"
echo "$last1
$first2" | awk '
  NR == 1 { for (i = 1; i <= NF; i++) a[i] = $i; next }
  { for (i = 1; i <= NF; i++) { d = $i - a[i]; if (d < 0) d = -d; s = a[i] < 0 ? -a[i] : a[i]
      if (d > 1e-9 * (s + 1e-30) && d > 1e-30) { print "restart row differs in column " i ": " a[i] " vs " $i; exit 1 } } }'
echo "$lastf
$last2" | awk -v sc="$scale" '
  NR == 1 { for (i = 1; i <= NF; i++) a[i] = $i; next }
  { if ($1 - a[1] > 1e-12 || a[1] - $1 > 1e-12) { print "end times differ: " a[1] " " $1; exit 1 }
    m = 0; for (i = 3; i <= 8; i++) { d = $i - a[i]; if (d < 0) d = -d; if (d > m) m = d }
    print "largest joint translation difference " m " (relative " m / sc ")"
    if (m > 1e-4 * sc) exit 1 }'
# start from mode 1
sed "s/revolutions = 1/revolutions = 0.02, initial = 'mode', mode_number = 1, mode_amplitude = 0.01/; s/initial_static = T/initial_static = F/" "$deck" > "$work/mode.nml"
"$flexmech" "$work/mode.nml" -o "$work/mode.out" > /dev/null
grep -q 'initial state: mode 1' "$work/mode.out"
grep -v '^#' "$work/mode.out" | head -n 1 | awk '{ m = 0
  # link-end v, w: columns 10, 11 (crank), 16, 17 (coupler), 22, 23 (rocker)
  split("10 11 16 17 22 23", c, " "); for (k in c) { a = $(c[k]); if (a < 0) a = -a; if (a > m) m = a }
  print "largest link-end transverse deflection in the first row " m
  if (m > 0.01 * (1 + 1e-9) || m < 0.001) exit 1 }'
# 3. The periodicity defect after a restart counts its samples from the
#    restart (spatial_fourbar_planar_100: 5 deg steps, 72 a revolution): a
#    run over 2.5 revolutions and its continuation over the last 2 from a
#    0.5-revolution run's restart file judge the same samples (revolution
#    1.5-2.5 against 0.5-1.5), so they print the same defect to the
#    restart's difference (measured below 1e-6 relative; the defect is about
#    1e-1).  Counted from t = 0 instead, the continuation judged samples of
#    its first revolution against ring slots never written.
pdeck=inputs/spatial_fourbar_planar_100.nml
sed "s/revolutions = 1/revolutions = 2.5/" "$pdeck" > "$work/p_full.nml"
sed "s/revolutions = 1/revolutions = 0.5, restart_out = '$(echo "$work" | sed 's/[\/&]/\\&/g')\/p_half.dat'/" "$pdeck" > "$work/p_first.nml"
sed "s/revolutions = 1/revolutions = 2, initial = 'restart', restart_in = '$(echo "$work" | sed 's/[\/&]/\\&/g')\/p_half.dat'/" "$pdeck" > "$work/p_second.nml"
for r in p_full p_first p_second; do "$flexmech" "$work/$r.nml" -o "$work/$r.out" > /dev/null; done
d_full=$(sed -n 's/^# summary: periodicity defect over the last revolution = \([^ ]*\) .*/\1/p' "$work/p_full.out")
d_second=$(sed -n 's/^# summary: periodicity defect over the last revolution = \([^ ]*\) .*/\1/p' "$work/p_second.out")
echo "periodicity defect: one run $d_full, continued after a restart $d_second"
awk -v a="$d_full" -v b="$d_second" 'BEGIN { d = a - b; if (d < 0) d = -d
  if (a == "" || b == "" || !(a > 1e-3) || d > 1e-4 * a) exit 1 }'
