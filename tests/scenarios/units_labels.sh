#!/bin/sh
# &run units: the same spin-up beam run with units = 'SI', 'in-lbf-s' and
# 'none' gives the same rows (the units decide labels only, and the material
# is given); the labels of the column descriptions, the summary lines and the
# header follow the system; the plausibility check judges the SI material
# right in SI and wrong when the deck claims in-lbf-s (a warning on stderr and
# in the output, the result unchanged).
# usage: units_labels.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
sed -e "s/t_end = 20.0/t_end = 2.0/" inputs/spinup_beam_si.nml > "$work/si.nml"
sed -e "s/units = 'SI'/units = 'in-lbf-s'/" "$work/si.nml" > "$work/in.nml"
sed -e "s/units = 'SI'/units = 'none'/" "$work/si.nml" > "$work/none.nml"
for f in si in none; do "$flexmech" "$work/$f.nml" -o "$work/$f.out" > /dev/null 2> "$work/$f.err"; done
printf 'default 0 0\n' > "$work/tol"
"$compare" "$work/si.out" "$work/in.out" "$work/tol"
"$compare" "$work/si.out" "$work/none.out" "$work/tol"
has() { grep -qF -- "$2" "$1" || { echo "$1: no '$2'"; exit 1; }; }
hasnt() { ! grep -qF -- "$2" "$1" || { echo "$1: unexpected '$2'"; exit 1; }; }
has "$work/si.out" '# units: SI (lengths (m), forces (N), stresses (Pa)'
has "$work/si.out" 'along global X, Y (m)'
has "$work/si.out" 'over both outer fibres (Pa)'
has "$work/si.out" 'Pa at 1.74593 deg of revolution 1'
hasnt "$work/si.out" 'psi'
has "$work/in.out" 'over both outer fibres (psi)'
has "$work/in.out" 'psi at 1.74593 deg of revolution 1'
has "$work/none.out" 'whole run peak |stress| beam (element 1) = '
hasnt "$work/none.out" ' Pa at'
hasnt "$work/none.out" ' psi at'
hasnt "$work/none.out" '(in)'
hasnt "$work/si.err" 'wave speed'
has "$work/in.err" "link beam: its wave speed sqrt(link_e1/link_rho) = 4994.0 in/s is outside"
has "$work/in.out" "# warning: link beam: its wave speed"
hasnt "$work/none.err" 'wave speed'
echo "units: SI, in-lbf-s and none give the same rows with their own labels; the wave-speed warning only where the system is wrong"
