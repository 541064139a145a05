#!/bin/sh
# Plausibility warnings never change a result, and each names its link:
# - link_strength below the peaks: one warning per link (crank, coupler,
#   rocker: each link's elements mapped to it), the rows the same as without;
# - link_rho = 0.283 (a weight density in lb/in^3), damping off: a
#   wave-speed warning per link naming link_rho, in the header and on stderr,
#   and the crank-speed warning (150 rad/s against a first frozen frequency
#   of 43.8 rad/s);
# - damping off with the right density (first frozen frequency 1462 rad/s):
#   no warning.
# usage: plausibility_warnings.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
sed -e "s/revolutions = 5/revolutions = 1/" -e "s/output_step_deg = 2.0/output_step_deg = 10.0/" \
  inputs/fourbar_150_damped.nml > "$work/plain.nml"
sed -e "s/link_h = 3\*1.0/link_h = 3*1.0, link_strength = 3*1000.0/" "$work/plain.nml" > "$work/strength.nml"
sed -e "s/damping_beta = 1.0e-5/damping_beta = 0.0/" "$work/plain.nml" > "$work/undamped.nml"
sed -e "s/link_h = 3\*1.0/link_h = 3*1.0, link_rho = 3*0.283/" "$work/undamped.nml" > "$work/rho.nml"
for f in plain strength rho undamped; do "$flexmech" "$work/$f.nml" -o "$work/$f.out" > /dev/null 2> "$work/$f.err"; done
printf 'default 0 0\n' > "$work/tol"
"$compare" "$work/plain.out" "$work/strength.out" "$work/tol"
count() { grep -c -- "$2" "$1" || true; }
for f in plain undamped; do
  [ "$(count "$work/$f.err" 'warning')" -eq 0 ] || { echo "$f: unexpected warning"; cat "$work/$f.err"; exit 1; }
done
[ "$(count "$work/plain.out" '# warning: link')" -eq 0 ] || { echo "plain: unexpected warning in the output"; exit 1; }
for link in crank coupler rocker; do
  grep -q "warning: link $link: peak |stress| .* psi is above its link_strength 1000.00 psi" "$work/strength.err" || \
    { echo "strength: no warning for $link"; cat "$work/strength.err"; exit 1; }
  grep -q "^# warning: link $link: its wave speed sqrt(link_e1/link_rho) = 6197.6 in/s" "$work/rho.out" || \
    { echo "rho: no wave-speed warning for $link in the output"; exit 1; }
done
[ "$(count "$work/strength.out" '# warning: link')" -eq 3 ] || { echo "strength: not 3 warnings in the output"; exit 1; }
[ "$(count "$work/rho.err" 'divided by g = 386.09')" -eq 3 ] || { echo "rho: not 3 warnings on stderr"; exit 1; }
grep -q "warning: the crank speed 150.000 rad/s is above the lowest natural frequency 43.77" "$work/rho.err" || \
  { echo "rho: no crank-speed warning"; cat "$work/rho.err"; exit 1; }
echo "warnings: strength (3 links, rows unchanged), weight density (3 links) and undamped crank speed; none on the plain decks"
