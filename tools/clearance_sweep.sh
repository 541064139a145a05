#!/bin/sh
# The clearance sweep of doc/clearance.md: Tennant's four-bar at 150 rad/s
# (inputs/fourbar_150_clearance.nml) over 5 revolutions with radial clearance
# c = 1e-5 (the pinned limit), 0.001, 0.005, 0.01 in at pin C, the contact
# stiffness from Lankarani and Nikravesh's Hertz formula for a 1/4 in steel
# pin in an aluminium bearing, K = 4/(3 (s_steel + s_alu)) sqrt(R (R + c)/c)
# (c = 1e-5: 1e10, the stiff pinned limit of test_clearance_run).  Writes
# per-revolution peaks to doc/figures/clearance/sweep.dat and draws
# clearance_sweep.png with gnuplot.
# Run from the repository root after `make`:  sh tools/clearance_sweep.sh
set -eu
bin=${1:-build/bin/flexmech}
dir=doc/figures/clearance
work=${TMPDIR:-/tmp}/flexmech_clearance_sweep_$$
mkdir -p "$dir" "$work"
dat="$dir/sweep.dat"
printf '# c_in K revolution peak_coupler_psi peak_rocker_psi peak_contact_rows_lb impact_rows peak_contact_run_lb\n' > "$dat"
# stresses and the rows' contact force are sampled every 2 deg of crank (per revolution); the
# run's peak contact force (last column) is over every integration step of the 5 revolutions
for ck in 1e-5:1.0e10 0.001:8.85e7 0.005:3.99e7 0.01:2.85e7; do
  c=${ck%%:*}; k=${ck#*:}
  deck="$work/c$c.nml"
  sed -e 's/revolutions = 1$/revolutions = 5/' -e "s/joint_clearance(3) = 0.005/joint_clearance(3) = $c/" \
      -e "s/joint_stiffness(3) = 4.0e7/joint_stiffness(3) = $k/" inputs/fourbar_150_clearance.nml > "$deck"
  "$bin" "$deck" -o "$work/c$c.out" > /dev/null
  grep -E 'summary: joint C (peak|impacts)|cost: (cpu_seconds_integration|steps|clearance_restarts)' "$work/c$c.out" | \
    sed "s/^/c = $c: /"
  # per revolution: peak coupler and rocker stress, peak contact force, rows with an impact
  fmax=$(sed -n 's/^# summary: joint C peak contact force = \([^ ]*\) lb.*/\1/p' "$work/c$c.out")
  awk -v c="$c" -v k="$k" -v fmax="$fmax" '
    /^#/ && $2 == "t" && $3 == "crank_deg" { for (i = 2; i <= NF; i++) { if ($i == "sigma_max_e2") e2 = i - 1
        if ($i == "sigma_max_e3") e3 = i - 1; if ($i == "C_Fn") fn = i - 1; if ($i == "C_mode") md = i - 1 } }
    /^#/ { next }
    { r = int(($2 - 1e-9) / 360) + 1; if ($2 == 0) r = 1
      if ($e2 > p2[r]) p2[r] = $e2; if ($e3 > p3[r]) p3[r] = $e3; if ($fn > pf[r]) pf[r] = $fn; if ($md == 2) ni[r]++ }
    END { for (r = 1; r <= 5; r++) printf "%s %s %d %.1f %.1f %.1f %d %s\n", c, k, r, p2[r], p3[r], pf[r], ni[r], fmax }
  ' "$work/c$c.out" >> "$dat"
done
rm -rf "$work"
cat "$dat"
command -v gnuplot > /dev/null && gnuplot "$dir/clearance_sweep.gp"
