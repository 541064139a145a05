#!/bin/sh
# Two independent routes to the force at a clearance joint agree: the joint
# reaction on the coupler's end at C (src/model/joint_reactions: the element's
# own equation of motion, r = M qdd - F) and the contact law's normal force
# (src/element/contact_law, frictionless, journal massless) have the same
# magnitude in every row where the journal touches.  Asked: 1e-6 relative
# (both are printed to 8 digits; measured agreement is at the last digit).
# usage: clearance_joint_force.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; work=$3
mkdir -p "$work"
sed "s/  damping_beta = 1.0e-5/  damping_beta = 1.0e-5, reactions = T, output_digits = 8/" \
    inputs/fourbar_150_clearance.nml > "$work/deck.nml"
"$flexmech" "$work/deck.nml" -o "$work/deck.out" > /dev/null
awk '
  /^#.* t +crank_deg/ { for (i = 2; i <= NF; i++) { if ($i == "C_coupler_Fx") fx = i - 1; if ($i == "C_coupler_Fy") fy = i - 1
                        if ($i == "C_Fn") fn = i - 1; if ($i == "C_mode") md = i - 1 } }
  !/^#/ && fx && $md == 1 {
    n++; r = sqrt($fx * $fx + $fy * $fy); d = r - $fn; if (d < 0) d = -d
    if (d > 1.0e-6 * $fn + 1.0e-9) { bad++; print "crank " $2 " deg: |F_C| = " r ", F_n = " $fn }
  }
  END { if (!fx || n < 5) { print "too few contact rows (" n ")"; exit 1 }
        if (bad) exit 1; print n " contact rows: |F_C| = F_n" }' "$work/deck.out"
