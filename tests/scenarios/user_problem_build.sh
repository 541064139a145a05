#!/bin/sh
# A problem of the user's own, without editing flexmech: `make
# PROBLEM=examples/user_problem/hs71_problem.f90` builds build/user/flexmech,
# whose deck names the problem; HS 71 from its standard start with default
# settings must reach Hock & Schittkowski's f* = 17.0140173 (printed to 8
# digits: |F - F*| <= 1e-6 (1 + |f*|)) and x* to 1e-6.  The plain flexmech
# does not know the name and says how to add it (exit 2).  A second, older
# problem file then replaces the first (the build follows PROBLEM).
# usage: user_problem_build.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; work=$3
mkdir -p "$work"
# the build the binary belongs to: BUILD_DIR/bin/flexmech (release) or
# BUILD_DIR/debug/bin/flexmech, whose objects the user build reuses
build=$(dirname "$(dirname "$flexmech")"); flavour=release
[ "$(basename "$build")" = debug ] && { flavour=debug; build=$(dirname "$build"); }
user="$work/user"     # not build/user: the release and debug runs of this test may overlap
make --no-print-directory -s BUILD_DIR="$build" BUILD=$flavour USER_DIR="$user" PROBLEM=examples/user_problem/hs71_problem.f90 \
  "$user/flexmech" > "$work/make.log" 2>&1 || { cat "$work/make.log"; exit 1; }
"$user/flexmech" examples/user_problem/hs71.nml -o "$work/hs71.out" > /dev/null
grep -q '^# summary: status = converged' "$work/hs71.out" || { echo "HS 71 not converged"; exit 1; }
awk '/^# summary: \|F - F\*\| =/ {if ($NF + 0 > 1.8e-5) bad = 1; sf = 1}
     /^# summary: \|x - x\*\|_inf =/ {if ($NF + 0 > 1e-6) bad = 1; sx = 1}
     END {exit (sf && sx && !bad) ? 0 : 1}' "$work/hs71.out" || { grep summary "$work/hs71.out"; exit 1; }
status=0
"$flexmech" examples/user_problem/hs71.nml -o "$work/plain.out" 2> "$work/plain.err" || status=$?
[ "$status" -eq 2 ] || { echo "plain flexmech: exit $status, expected 2"; exit 1; }
grep -q 'make PROBLEM=' "$work/plain.err" || { echo "plain flexmech does not say how to add a problem"; exit 1; }
# Another problem file, older than the binary just built: the build must follow
# PROBLEM, not the timestamps (it used to keep the previous binary, and the deck
# then failed with "must be one of").
sed 's/my_hs71/my_hs71_older/g' examples/user_problem/hs71_problem.f90 > "$work/older_problem.f90"
sed 's/my_hs71/my_hs71_older/g' examples/user_problem/hs71.nml > "$work/older.nml"
touch -d '2000-01-01 00:00' "$work/older_problem.f90"
make --no-print-directory -s BUILD_DIR="$build" BUILD=$flavour USER_DIR="$user" PROBLEM="$work/older_problem.f90" \
  "$user/flexmech" > "$work/make_older.log" 2>&1 || { cat "$work/make_older.log"; exit 1; }
"$user/flexmech" "$work/older.nml" -o "$work/older.out" > /dev/null 2> "$work/older.err" ||
  { echo "the older problem file was not built in:"; cat "$work/older.err"; exit 1; }
grep -q '^# summary: status = converged' "$work/older.out" || { echo "my_hs71_older not converged"; exit 1; }
echo "HS 71 as a user problem: converged, $(grep 'summary: NF' "$work/hs71.out")"
