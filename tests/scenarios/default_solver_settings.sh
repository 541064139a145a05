#!/bin/sh
# The solver settings a deck leaves out are chosen from its model
# (doc/transient.md, "Default solver settings"): four shipped decks with their
# solver lines (method, rtol, atol, atol_rate, max_order) deleted must print
# what was chosen and reach every peak of their reference output within 1 %:
#  - fourbar_100_linear: undamped four-bar, Kear's element (tuned: Adams);
#  - spinup_ws4: the Kane-Ryan-Banerjee spin-up beam, consistent element,
#    undamped stiff axial modes (tuned: BDF order 2, hand-set atol_rate);
#  - beam_clamped_mode1: free vibration from the first mode, no crank;
#  - spatial_fourbar_planar_100: the spatial analysis' settings.
# A column's peak difference is taken relative to the larger of its peak and
# 1 % of the largest peak among the columns of its kind (the name without its
# first word and digits), as tools/default_settings.py does for the table of
# doc/benchmarks.md; round-off columns (kind below 1e-10 of the table's
# largest peak) are not compared.  No CPU assertion (tests never time).
# usage: default_solver_settings.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; work=$3
mkdir -p "$work"
fail=0

# peaks FILE: "name peak" lines (largest |value| of every data column)
peaks() {
  awk '/^#/ { hdr = $0; next }
       NF > 0 { if (!n) { n = split(substr(hdr, 2), name, " ") }
                for (i = 1; i <= NF; i++) { v = $i < 0 ? -$i : $i; if (v > p[i]) p[i] = v } }
       END { for (i = 1; i <= n; i++) printf "%s %.17g\n", name[i], p[i] + 0 }' "$1"
}

# worst REF_PEAKS NEW_PEAKS: "worst_relative_difference column"
worst() {
  awk 'function kind(s,   w, k, i, r) { gsub(/[0-9]+/, "", s); k = split(s, w, "_"); if (k == 1) return s
                                       r = w[2]; for (i = 3; i <= k; i++) r = r "_" w[i]; return r }
       FNR == NR { if ($1 == "t" || $1 == "crank_deg") next; ref[$1] = $2; kd = kind($1)
                   if ($2 > big[kd]) big[kd] = $2; if ($2 > top) top = $2; next }
       ($1 in ref) { s = ref[$1]; if (0.01 * big[kind($1)] > s) s = 0.01 * big[kind($1)]
                     if (s <= 1e-10 * top) next
                     d = ($2 - ref[$1]) / s; if (d < 0) d = -d; seen[$1] = 1
                     if (d > w) { w = d; where = $1 } }
       END { for (c in ref) if (!(c in seen) && ref[c] > 1e-10 * top) { w = 1e30; where = c " missing" }
             printf "%.6g %s\n", w, where }' "$1" "$2"
}

for deck in fourbar_100_linear spinup_ws4 spinup_ws4_kear beam_clamped_mode1 spatial_fourbar_planar_100; do
  # the solver lines of &transient, each on its own line in these decks
  awk '/^&/ { g = $1 } /^\// { g = "" }
       g == "&transient" && $0 ~ /^[ \t]*(method|rtol|atol|atol_rate|max_order)[ \t]*=/ { next } { print }' \
    "inputs/$deck.nml" > "$work/$deck.nml"
  if grep -qE '^[[:space:]]*(method|rtol|atol|atol_rate|max_order)[[:space:]]*=' "$work/$deck.nml"; then
    echo "FAIL $deck: solver lines left in the scratch deck"; fail=1; continue
  fi
  if ! "$flexmech" "$work/$deck.nml" -o "$work/$deck.out" > "$work/$deck.log" 2>&1; then
    echo "FAIL $deck: the run with default settings failed:"; cat "$work/$deck.log"; fail=1; continue
  fi
  for what in method atol atol_rate; do
    grep -q "^# $what = .* (chosen): " "$work/$deck.out" || { echo "FAIL $deck: no header line for the chosen $what"; fail=1; }
  done
  peaks "reference_outputs/$deck.out" > "$work/$deck.ref.peaks"
  peaks "$work/$deck.out" > "$work/$deck.new.peaks"
  set -- $(worst "$work/$deck.ref.peaks" "$work/$deck.new.peaks")
  if awk -v w="$1" 'BEGIN { exit !(w <= 0.01) }'; then
    echo "$deck: worst peak difference $1 ($2), $(sed -n "s/^# \(method = '[a-z]*'\) (chosen).*/\1/p" "$work/$deck.out")"
  else
    echo "FAIL $deck: a peak differs from the reference by $1 of its scale (column $2; 1 % allowed)"; fail=1
  fi
done
# the spin-up beam: the rule limits BDF to order 2 (its undamped axial modes)
grep -q "^# max_order = 2 (chosen)" "$work/spinup_ws4.out" || { echo "FAIL spinup_ws4: max_order 2 not chosen"; fail=1; }
exit $fail
