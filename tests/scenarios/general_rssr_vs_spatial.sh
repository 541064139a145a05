#!/bin/sh
# The RSSR four-bar written as a general mechanism (inputs/general_rssr_100.nml,
# analysis general_transient) against the spatial four-bar analysis' verified
# output (reference_outputs/spatial_rssr_100.out): the same links, elements,
# effects, start and integrator, so every common column (joints B and C, the
# links' ends, the roots' resultants, the element stresses) agrees within
# that deck's tolerances (reference_outputs/spatial_rssr_100.tol; measured
# 5e-7 relative at most, on the rocker's small Mz at its root).
# usage: general_rssr_vs_spatial.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
"$flexmech" inputs/general_rssr_100.nml -o "$work/general.out" > /dev/null
# the spatial output's columns without crank_deg and the support forces, by name
cols=$(awk '/^#/ {hdr = $0; next} {print substr(hdr, 2); exit}' reference_outputs/spatial_rssr_100.out |
       tr ' ' '\n' | grep -v -e '^$' -e '^crank_deg$' -e '^A_F' -e '^D_F' | tr '\n' ' ')
pick() {  # file, then the column names in order
  f=$1; shift
  awk -v want="$*" '
    BEGIN { n = split(want, w, " ") }
    /^#/ { hdr = $0; next }
    !done { split(substr(hdr, 2), h, " "); for (i in h) idx[h[i]] = i;
            for (k = 1; k <= n; k++) if (!(w[k] in idx)) { print "no column " w[k] > "/dev/stderr"; exit 1 }
            printf "#"; for (k = 1; k <= n; k++) printf " %s", w[k]; printf "\n"; done = 1 }
    { for (k = 1; k <= n; k++) printf " %s", $(idx[w[k]]); printf "\n" }' "$f"
}
pick reference_outputs/spatial_rssr_100.out $cols > "$work/spatial.cols"
pick "$work/general.out" $cols > "$work/general.cols"
"$compare" "$work/spatial.cols" "$work/general.cols" reference_outputs/spatial_rssr_100.tol
