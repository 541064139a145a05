#!/bin/sh
# Spatial-four-bar decks written as general mechanisms (analysis
# general_transient) against the spatial four-bar analysis' verified outputs,
# every common column (joint translations, link ends, root resultants,
# element stresses) within the spatial deck's tolerances:
#  - the RSSR (inputs/general_rssr_100.nml: spherical joints, a ground
#    revolute about X) against reference_outputs/spatial_rssr_100.out over
#    its revolution (measured 5e-7 relative at most, on the rocker's small Mz
#    at its root; 7e-9 on the joints' translations and the stresses);
#  - the planar four-bar (inputs/general_fourbar_150.nml: the plane's
#    revolute rule at B and C) against reference_outputs/spatial_fourbar_150.out
#    over the first quarter revolution, its rows from 0 to 90 deg (over the
#    whole revolution measured 5e-7 relative at most).
# usage: general_vs_spatial.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
pick() {  # file, rows, then the column names in order
  f=$1; rows=$2; shift 2
  awk -v want="$*" -v rows="$rows" '
    BEGIN { n = split(want, w, " ") }
    /^#/ { hdr = $0; next }
    !done { split(substr(hdr, 2), h, " "); for (i in h) idx[h[i]] = i;
            for (k = 1; k <= n; k++) if (!(w[k] in idx)) { print "no column " w[k] > "/dev/stderr"; exit 1 }
            printf "#"; for (k = 1; k <= n; k++) printf " %s", w[k]; printf "\n"; done = 1 }
    { if (++r > rows) exit; for (k = 1; k <= n; k++) printf " %s", $(idx[w[k]]); printf "\n" }' "$f"
}
check() {  # general deck, spatial name, rows compared
  ref=reference_outputs/$2.out
  "$flexmech" "$1" -o "$work/$2.general.out" > /dev/null
  # the spatial output's columns without crank_deg and the support forces, by name
  cols=$(awk '/^#/ {hdr = $0; next} {print substr(hdr, 2); exit}' "$ref" |
         tr ' ' '\n' | grep -v -e '^$' -e '^crank_deg$' -e '^A_F' -e '^D_F' | tr '\n' ' ')
  pick "$ref" "$3" $cols > "$work/$2.spatial.cols"
  pick "$work/$2.general.out" "$3" $cols > "$work/$2.general.cols"
  test "$(grep -vc '^#' "$work/$2.general.cols")" -eq "$3"
  "$compare" "$work/$2.spatial.cols" "$work/$2.general.cols" "reference_outputs/$2.tol"
}
check inputs/general_rssr_100.nml spatial_rssr_100 73
sed -e "s/revolutions = .*/revolutions = 0.25/" inputs/general_fourbar_150.nml > "$work/general_fourbar.nml"
check "$work/general_fourbar.nml" spatial_fourbar_150 46
