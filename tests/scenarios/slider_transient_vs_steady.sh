#!/bin/sh
# Links sliding through a sleeve (slider_link, T24) in the transient analysis
# agree with the steady analysis's exact periodic solution (doc/transient.md,
# "Links sliding through a sleeve").  Two decks: inputs/whitworth_60_damped.nml
# (the lever slides through a sleeve on the crank pin) and
# inputs/inverted_slidercrank_80_damped.nml (the rod slides through a sleeve
# pivoting on the ground); both linear with rotatory inertia and the
# Coriolis/Euler terms, beta = 1e-5 s, damped over three revolutions into
# their periodic state.  Against each: shooting on the deck's own &mechanism
# with the same physics (&tennant D_k = D_b = D_g = 0, rotatory inertia on,
# the deck's damping_beta).  Compared over the last revolution, every 5 deg of
# crank: every output column (the moving joints' global displacements, every
# link's end displacements -- a sliding link's are its slide s and the
# displacement across it at the sleeve -- and every element's largest stress).
# The start-up transient has decayed to about e^-24 of its size; what remains
# is DLSODE's error (rtol 1e-9 and 1e-10): measured up to 5e-9 of a column's
# peak.  Tolerance 1e-6 relative (the issue asks 1e-4) with an absolute floor
# of 1e-6 of each column's peak (+1e-15) where a column crosses zero.
# Measured on the Whitworth deck: dropping the sleeve map's rate terms
# (2 M_e C_d Q_d + M_e C_dd Q) moves the columns by up to 5e-5 of their peaks
# (324 of 648 values fail), dropping the moving-length terms of T24
# (Delta_d = Delta_dd = 0) by up to 0.74.
# usage: slider_transient_vs_steady.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"

# the data rows of an output but the one closing the revolution (360 deg = 0
# deg), as: crank angle within the revolution, then the columns named
pick() {  # file, then the column names in order
  f=$1; shift
  awk '/^#/ {print; next} {if (have) print prev; prev = $0; have = 1}' "$f" |
  awk -v want="$*" '
    BEGIN { n = split(want, w, " ") }
    /^#/ { hdr = $0; next }
    !done { split(substr(hdr, 2), h, " "); for (i in h) idx[h[i]] = i;
            printf "# deg"; for (k = 1; k <= n; k++) printf " %s", w[k]; printf "\n"; done = 1 }
    { d = $(idx["crank_deg"]) % 360; if (d < 0) d += 360; printf " %.6f", d
      for (k = 1; k <= n; k++) printf " %s", $(idx[w[k]]); printf "\n" }' | sort -n -k1 -s
}

for name in whitworth_60_damped inverted_slidercrank_80_damped; do
  deck=inputs/$name.nml
  "$flexmech" "$deck" -o "$work/$name.transient.out" > /dev/null
  beta=$(awk -F= '/^ *damping_beta *=/ {gsub(/ /, "", $2); print $2}' "$deck")
  {
    printf "&run\n  analysis = 'steady'\n  title = '%s: exact periodic solution'\n/\n" "$name"
    awk '/^&mechanism/ {on = 1} on {print} on && /^\// {exit}' "$deck"
    printf "&steady\n  method = 'shooting'\n  output_step_deg = 5.0\n  damping_beta = %s\n" "$beta"
    printf "  rtol = 1.0e-10\n  atol = 1.0e-14\n/\n"
    printf "&tennant\n  d_k = 0, d_b = 0, d_g = 0\n  rotary_inertia = T\n/\n"
  } > "$work/$name.steady.nml"
  "$flexmech" "$work/$name.steady.nml" -o "$work/$name.steady.out" > /dev/null
  # every column of the transient output but t and crank_deg
  cols=$(awk '/^#/ {hdr = $0; next} {print substr(hdr, 2); exit}' "$work/$name.transient.out" |
         tr -s ' ' '\n' | grep -v -x -e '' -e t -e crank_deg | tr '\n' ' ')
  pick "$work/$name.steady.out" $cols > "$work/$name.steady.cols"
  pick "$work/$name.transient.out" $cols > "$work/$name.transient.cols"
  rows=$(grep -vc '^#' "$work/$name.transient.cols")
  [ "$rows" -eq 72 ] || { echo "$name: expected 72 rows of the last revolution, got $rows"; exit 1; }
  # tolerances: 1e-6 relative, floor 1e-6 of the column's peak (+1e-15)
  awk -v want="$cols" 'BEGIN { n = split(want, w, " ") } /^#/ {next}
       { for (k = 1; k <= n; k++) { v = $(k + 1); if (v < 0) v = -v; if (v > pk[k]) pk[k] = v } }
       END { print "deg 0 1e-6"; for (k = 1; k <= n; k++) printf "%s 1e-6 %.3e\n", w[k], 1e-6*pk[k] + 1e-15 }' \
      "$work/$name.steady.cols" > "$work/$name.tol"
  echo "$name: $(echo $cols | wc -w) columns"
  "$compare" "$work/$name.steady.cols" "$work/$name.transient.cols" "$work/$name.tol"
done
