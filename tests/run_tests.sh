#!/bin/sh
# Runs the flexmech tests and ends with "N passed, M failed".
#  1. unit suites (debug build: -fcheck=all, FP traps), one executable per module;
#  2. deck-error tests: every tests/decks/*.nml must fail as its header says
#     (! expect-status: N, ! expect-message: TEXT, ! expect-no-message: TEXT);
#  3. scenario tests: tests/scenarios/*.sh;
#  4. regression tests: every inputs/X.nml with reference_outputs/X.out is run
#     and compared column by column within the tolerances of
#     reference_outputs/X.tol.
# Steps 2-4 run with the release binary and again with the debug binary
# (-fcheck=all, FP traps): every deck must reach the same exit status and
# messages in both, without a trap or runtime error.  The debug build's
# regression outputs are compared too with DEBUG_COMPARE=1 (make check-opt
# compares every optimization level).
# The tests are independent and run JOBS at a time (default: the number of
# cores), the slowest first (their times from the last run are kept in
# BUILD_DIR/test_times.txt); each prints one line when it ends.
# usage: run_tests.sh BUILD_DIR [filter] [flavours]
#   flavours: "release debug" (default), or one of them
#   SKIP_UNITS=1 in the environment skips step 1; UNIT_FLAVOUR=release runs
#   the unit tests of the release build (make check-opt)
#   SELECTION=FILE runs, besides every unit suite and deck-error test, only
#   the regression decks and scenarios FILE names (make check: tests/check.txt)
set -u

# what a deck run must never print: a gfortran runtime error or warning, a trap
crash_marks='Fortran runtime|Program received signal|Backtrace|Segmentation fault'

# ---------------------------------------------------------------- one test
# run_tests.sh --job SEQ KIND FLAVOUR NAME (environment: RT_BUILD, RT_WORK,
# RT_LIMIT): the test's result goes to RT_WORK/results/SEQ: "PASSED FAILED",
# the line printed, then what failed.
if [ "${1:-}" = "--job" ]; then
  seq=$2; kind=$3; flavour=$4; name=$5
  build=$RT_BUILD; work=$RT_WORK; limit=$RT_LIMIT
  start=$(date +%s%N)
  p=0; f=0; detail=""
  case $flavour in
    release) flexmech="$build/bin/flexmech" ;;
    *) flexmech="$build/$flavour/bin/flexmech" ;;
  esac
  dir="$work/$flavour"
  case $kind in
  unit)
    t="$build/$flavour/tests/$name"
    log="$work/$name.log"
    $limit "$t" > "$log" 2>&1
    status=$?
    line=$(grep -E '^[a-z_0-9]+: [0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
    p=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed.*/\1/')
    f=$(echo "$line" | sed -E 's/.* ([0-9]+) failed$/\1/')
    [ -n "$line" ] || { p=0; f=1; }
    if [ $status -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi   # crashed after its summary
    if [ "$f" -ne 0 ] || [ $status -ne 0 ]; then
      detail="$name (exit $status):
$(grep -E 'FAIL|assertion failed|Error|error' "$log" | head -n 20 | sed 's/^/      /')"
      shown="unit $name: FAILED ($p passed, $f failed; log $log)"
    else
      shown="unit $name: $p passed"
    fi ;;
  deck)
    deck="tests/decks/$name.nml"
    want_status=$(sed -n 's/^! *expect-status: *//p' "$deck" | head -n 1)
    [ -n "$want_status" ] || want_status=2
    out="$dir/$name.out"
    $limit "$flexmech" "$deck" -o "$out" > "$dir/$name.stdout" 2> "$dir/$name.stderr"
    status=$?
    ok=1; why=""
    [ "$status" -eq "$want_status" ] || { ok=0; why="exit status $status, expected $want_status"; }
    if grep -qE "$crash_marks" "$dir/$name.stderr"; then
      ok=0; why="$why; runtime error or warning: $(grep -E "$crash_marks" "$dir/$name.stderr" | head -n 1)"
    fi
    if [ "$want_status" -eq 2 ] && { [ -e "$out" ] || ls "$out".tmp* >/dev/null 2>&1; }; then
      ok=0; why="$why; output file left behind"
    fi
    # each expected fragment must appear in stderr, and no forbidden fragment may
    sed -n 's/^! *expect-message: *//p' "$deck" | while IFS= read -r m; do
      [ -z "$m" ] && continue
      grep -qF -- "$m" "$dir/$name.stderr" || echo "missing: $m"
    done > "$dir/$name.missing"
    sed -n 's/^! *expect-no-message: *//p' "$deck" | while IFS= read -r m; do
      [ -z "$m" ] && continue
      grep -qF -- "$m" "$dir/$name.stderr" && echo "unwanted: $m"
    done >> "$dir/$name.missing"
    if [ -s "$dir/$name.missing" ]; then ok=0; why="$why; message wrong: $(tr '\n' ';' < "$dir/$name.missing")"; fi
    if [ $ok -eq 1 ]; then
      p=1; shown="deck error test $name [$flavour]: ok"
    else
      f=1; shown="deck error test $name [$flavour]: FAILED ($why)"
      detail="deck error test $name [$flavour]: $why
        stderr: $(head -c 400 "$dir/$name.stderr")"
    fi ;;
  scenario)
    if sh "tests/scenarios/$name.sh" "$flexmech" "$build/release/tools/compare_tables" "$dir/$name" \
         > "$dir/$name.log" 2>&1; then
      p=1; shown="scenario $name [$flavour]: ok"
    else
      f=1; shown="scenario $name [$flavour]: FAILED (see $dir/$name.log)"
      detail="scenario $name [$flavour]:
$(tail -n 15 "$dir/$name.log" | sed 's/^/      /')"
    fi ;;
  regression)
    deck="inputs/$name.nml"
    out="$dir/$name.out"
    f=1
    if [ ! -f "$deck" ]; then
      shown="regression $name: FAILED (no deck $deck)"; detail="regression $name: no deck $deck"
    else
      $limit "$flexmech" "$deck" -o "$out" > "$dir/$name.stdout" 2> "$dir/$name.stderr"
      status=$?
      want_status=$(sed -n 's/^! *expect-status: *//p' "$deck" | head -n 1)
      [ -n "$want_status" ] || want_status=0
      tol="reference_outputs/$name.tol"
      [ -f "$tol" ] || tol=""
      if grep -qE "$crash_marks" "$dir/$name.stderr"; then
        shown="regression $name [$flavour]: FAILED (runtime error or warning)"
        detail="regression $name [$flavour]: $(grep -E "$crash_marks" "$dir/$name.stderr" | head -n 1)"
      elif [ $status -ne "$want_status" ]; then
        shown="regression $name [$flavour]: FAILED (exit $status)"
        detail="regression $name [$flavour]: exit status $status, expected $want_status: $(head -c 400 "$dir/$name.stderr")"
      elif [ "$flavour" = debug ] && [ "${DEBUG_COMPARE:-0}" != 1 ]; then
        # the debug build (-O0) must run every deck to its exit status without a
        # trap or runtime error; its numbers are compared by make check-opt
        f=0; p=1; shown="regression $name [$flavour]: exit $status as expected, no runtime error"
      elif "$build/release/tools/compare_tables" "$ref_dir/$name.out" "$out" $tol > "$dir/$name.cmp" 2>&1; then
        f=0; p=1; shown="regression $name [$flavour]: $(tail -n 1 "$dir/$name.cmp")"
      else
        shown="regression $name [$flavour]: FAILED (see $dir/$name.cmp)"
        detail="regression $name [$flavour]:
$(head -n 25 "$dir/$name.cmp" | sed 's/^/      /')"
      fi
    fi ;;
  esac
  end=$(date +%s%N)
  echo "$kind:$flavour:$name $(( (end - start) / 1000000 ))" >> "$work/times.new"
  { echo "$p $f"; echo "$shown"; [ -n "$detail" ] && echo "  $detail"; } > "$work/results/$seq"
  echo "   $shown"
  exit 0
fi

# ---------------------------------------------------------------- the suite
build=${1:-build}
filter=${2:-}
flavours=${3:-release debug}
selection=${SELECTION:-}
ref_dir=reference_outputs
jobs=${JOBS:-$(nproc 2>/dev/null || echo 1)}
work="$build/test_out"
rm -rf "$work"; mkdir -p "$work/results"
passed=0
failed=0
failures=""

# a hung run fails its test instead of blocking the suite (the slowest deck
# takes about a minute in the debug build)
limit=""
command -v timeout >/dev/null 2>&1 && limit="timeout 900"

# 0. no merge-conflict markers in the tracked sources and pages (an earlier
#    merge left some in a doc page unnoticed)
if [ -z "$filter" ] && command -v git >/dev/null 2>&1 && git rev-parse --git-dir >/dev/null 2>&1; then
  marks=$(git grep -n -I -E '^(<<<<<<< |>>>>>>> |=======$)' -- . ':!*.out' 2>/dev/null)
  if [ -n "$marks" ]; then
    echo "== merge-conflict markers in tracked files"
    echo "$marks" | sed 's/^/   /'
    failed=$((failed + 1)); failures="
  merge-conflict markers (above)"
  else
    passed=$((passed + 1))
  fi
fi

selected() {   # selected KIND NAME: in the filter and, with SELECTION, in the file
  case "$2" in *"$filter"*) ;; *) return 1 ;; esac
  [ -z "$selection" ] && return 0
  grep -qE "^$1[[:space:]]+$2[[:space:]]*$" "$selection"
}

for flavour in $flavours; do
  case $flavour in release|debug) ;; *) echo "unknown flavour $flavour"; exit 1 ;; esac
done

# the list of tests: KIND FLAVOUR NAME
unit_flavour=${UNIT_FLAVOUR:-debug}
{
  if [ "${SKIP_UNITS:-0}" != 1 ]; then
    for t in "$build"/$unit_flavour/tests/test_*; do
      [ -x "$t" ] || continue
      name=$(basename "$t")
      case "$name" in *"$filter"*) echo "unit $unit_flavour $name" ;; esac
    done
  fi
  for flavour in $flavours; do
    mkdir -p "$work/$flavour"
    for deck in tests/decks/*.nml; do
      [ -f "$deck" ] || continue
      name=$(basename "$deck" .nml)
      case "$name" in *"$filter"*) echo "deck $flavour $name" ;; esac
    done
    for sc in tests/scenarios/*.sh; do
      [ -f "$sc" ] || continue
      name=$(basename "$sc" .sh)
      selected scenario "$name" && echo "scenario $flavour $name"
    done
    for ref in "$ref_dir"/*.out; do
      [ -f "$ref" ] || continue
      name=$(basename "$ref" .out)
      selected regression "$name" && echo "regression $flavour $name"
    done
  done
  true
} > "$work/list"

# the slowest first (times of the last run; a test not timed yet counts as slow)
times="$build/test_times.txt"
[ -f "$times" ] || : > "$times"
awk 'FILENAME == ARGV[1] { ms[$1] = $2; next }
     { key = $1 ":" $2 ":" $3; print ((key in ms) ? ms[key] : 1e9), $0 }' "$times" "$work/list" |
  sort -s -k1,1 -g -r | awk '{ print NR, $2, $3, $4 }' > "$work/jobs"
total=$(wc -l < "$work/jobs")
echo "== $total tests, $jobs at a time (unit suites: $unit_flavour build; decks: $flavours)"
: > "$work/times.new"
RT_BUILD=$build RT_WORK=$work RT_LIMIT=$limit ref_dir=$ref_dir
export RT_BUILD RT_WORK RT_LIMIT ref_dir
xargs -r -P "$jobs" -n 4 sh "$0" --job < "$work/jobs"

# keep the times of this run (and those of tests it did not run)
awk 'FILENAME == ARGV[1] { ms[$1] = $2; next } { if (!($1 in ms)) ms[$1] = $2 }
     END { for (k in ms) print k, ms[k] }' "$work/times.new" "$times" | sort > "$times.tmp" && mv "$times.tmp" "$times"

# the results in the order of the list
seq=1
while [ $seq -le "$total" ]; do
  r="$work/results/$seq"
  if [ -f "$r" ]; then
    read -r p f < "$r"
    passed=$((passed + p)); failed=$((failed + f))
    [ "$f" -ne 0 ] && failures="$failures
$(sed 1,2d "$r")"
  else
    failed=$((failed + 1)); failures="$failures
  test $(sed -n "${seq}p" "$work/jobs"): no result (the job did not finish)"
  fi
  seq=$((seq + 1))
done

if [ $failed -gt 0 ]; then
  echo "== failures:$failures"
fi
echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
