#!/bin/sh
# Runs every flexmech test and ends with "N passed, M failed".
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
# usage: run_tests.sh BUILD_DIR [filter] [flavours]
#   flavours: "release debug" (default), or one of them
#   SKIP_UNITS=1 in the environment skips step 1; UNIT_FLAVOUR=release runs
#   the unit tests of the release build (make check-opt)
set -u
build=${1:-build}
filter=${2:-}
flavours=${3:-release debug}
passed=0
failed=0
failures=""
work="$build/test_out"
rm -rf "$work"; mkdir -p "$work"

# a hung run fails its test instead of blocking the suite (the slowest deck
# takes about a minute in the debug build)
limit=""
command -v timeout >/dev/null 2>&1 && limit="timeout 900"

note_fail() { failed=$((failed + 1)); failures="$failures
  $1"; }

# 0. no merge-conflict markers in the tracked sources and pages (an earlier
#    merge left some in a doc page unnoticed)
if [ -z "$filter" ] && command -v git >/dev/null 2>&1 && git rev-parse --git-dir >/dev/null 2>&1; then
  echo "== merge-conflict markers in tracked files"
  marks=$(git grep -n -I -E '^(<<<<<<< |>>>>>>> |=======$)' -- . ':!*.out' 2>/dev/null)
  if [ -n "$marks" ]; then
    echo "$marks" | sed 's/^/   /'
    note_fail "merge-conflict markers (above)"
  else
    echo "   none"
    passed=$((passed + 1))
  fi
fi

unit_flavour=${UNIT_FLAVOUR:-debug}
echo "== unit tests ($unit_flavour build)"
[ "${SKIP_UNITS:-0}" = 1 ] && echo "   (skipped: SKIP_UNITS=1)"
for t in "$build"/$unit_flavour/tests/test_*; do
  [ "${SKIP_UNITS:-0}" = 1 ] && break
  [ -x "$t" ] || continue
  name=$(basename "$t")
  case "$name" in *"$filter"*) ;; *) continue ;; esac
  log="$work/$name.log"
  $limit "$t" > "$log" 2>&1
  status=$?
  line=$(grep -E '^[a-z_0-9]+: [0-9]+ passed, [0-9]+ failed$' "$log" | tail -n 1)
  p=$(echo "$line" | sed -E 's/.*: ([0-9]+) passed.*/\1/')
  f=$(echo "$line" | sed -E 's/.* ([0-9]+) failed$/\1/')
  [ -n "$line" ] || { p=0; f=1; }
  if [ $status -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi   # crashed after its summary
  passed=$((passed + p)); failed=$((failed + f))
  if [ "$f" -ne 0 ] || [ $status -ne 0 ]; then
    failures="$failures
  $name (exit $status):
$(grep -E 'FAIL|assertion failed|Error|error' "$log" | head -n 20 | sed 's/^/      /')"
    echo "   $name: FAILED ($p passed, $f failed; log $log)"
  else
    echo "   $name: $p passed"
  fi
done

# what a deck run must never print: a gfortran runtime error or warning, a trap
crash_marks='Fortran runtime|Program received signal|Backtrace|Segmentation fault'
for flavour in $flavours; do
  case $flavour in
    release) flexmech="$build/bin/flexmech" ;;
    debug) flexmech="$build/debug/bin/flexmech" ;;
    *) echo "unknown flavour $flavour"; exit 1 ;;
  esac
  mkdir -p "$work/$flavour"
  echo "== deck error tests, $flavour build (bad input must exit 2, name the problem, leave no output)"
  for deck in tests/decks/*.nml; do
    [ -f "$deck" ] || continue
    name=$(basename "$deck" .nml)
    case "$name" in *"$filter"*) ;; *) continue ;; esac
    want_status=$(sed -n 's/^! *expect-status: *//p' "$deck" | head -n 1)
    [ -n "$want_status" ] || want_status=2
    out="$work/$flavour/$name.out"
    $limit "$flexmech" "$deck" -o "$out" > "$work/$flavour/$name.stdout" 2> "$work/$flavour/$name.stderr"
    status=$?
    ok=1; why=""
    [ "$status" -eq "$want_status" ] || { ok=0; why="exit status $status, expected $want_status"; }
    if grep -qE "$crash_marks" "$work/$flavour/$name.stderr"; then
      ok=0; why="$why; runtime error or warning: $(grep -E "$crash_marks" "$work/$flavour/$name.stderr" | head -n 1)"
    fi
    if [ "$want_status" -eq 2 ] && { [ -e "$out" ] || ls "$out".tmp* >/dev/null 2>&1; }; then
      ok=0; why="$why; output file left behind"
    fi
    msgs=$(sed -n 's/^! *expect-message: *//p' "$deck")
    # each expected fragment must appear in stderr
    echo "$msgs" | while IFS= read -r m; do
      [ -z "$m" ] && continue
      grep -qF -- "$m" "$work/$flavour/$name.stderr" || echo "missing: $m"
    done > "$work/$flavour/$name.missing"
    # and no forbidden fragment may
    sed -n 's/^! *expect-no-message: *//p' "$deck" | while IFS= read -r m; do
      [ -z "$m" ] && continue
      grep -qF -- "$m" "$work/$flavour/$name.stderr" && echo "unwanted: $m"
    done >> "$work/$flavour/$name.missing"
    if [ -s "$work/$flavour/$name.missing" ]; then ok=0; why="$why; message wrong: $(tr '\n' ';' < "$work/$flavour/$name.missing")"; fi
    if [ $ok -eq 1 ]; then
      passed=$((passed + 1)); echo "   $name: ok"
    else
      note_fail "deck error test $name [$flavour]: $why
        stderr: $(head -c 400 "$work/$flavour/$name.stderr")"
      echo "   $name: FAILED ($why)"
    fi
  done

  echo "== scenario tests, $flavour build (tests/scenarios/*.sh: several runs of the program checked together)"
  for sc in tests/scenarios/*.sh; do
    [ -f "$sc" ] || continue
    name=$(basename "$sc" .sh)
    case "$name" in *"$filter"*) ;; *) continue ;; esac
    if sh "$sc" "$flexmech" "$build/release/tools/compare_tables" "$work/$flavour/$name" > "$work/$flavour/$name.log" 2>&1; then
      passed=$((passed + 1)); echo "   $name: ok"
    else
      note_fail "scenario $name [$flavour]:
  $(tail -n 15 "$work/$flavour/$name.log" | sed 's/^/      /')"
      echo "   $name: FAILED (see $work/$flavour/$name.log)"
    fi
  done

  echo "== regression tests, $flavour build (vs reference_outputs/)"
  for ref in reference_outputs/*.out; do
    [ -f "$ref" ] || continue
    name=$(basename "$ref" .out)
    case "$name" in *"$filter"*) ;; *) continue ;; esac
    deck="inputs/$name.nml"
    if [ ! -f "$deck" ]; then note_fail "regression $name: no deck $deck"; continue; fi
    out="$work/$flavour/$name.out"
    $limit "$flexmech" "$deck" -o "$out" > "$work/$flavour/$name.stdout" 2> "$work/$flavour/$name.stderr"
    status=$?
    want_status=$(sed -n 's/^! *expect-status: *//p' "$deck" | head -n 1)
    [ -n "$want_status" ] || want_status=0
    if grep -qE "$crash_marks" "$work/$flavour/$name.stderr"; then
      note_fail "regression $name [$flavour]: $(grep -E "$crash_marks" "$work/$flavour/$name.stderr" | head -n 1)"
      echo "   $name: FAILED (runtime error or warning)"; continue
    fi
    if [ $status -ne "$want_status" ]; then
      note_fail "regression $name [$flavour]: exit status $status, expected $want_status: $(head -c 400 "$work/$flavour/$name.stderr")"
      echo "   $name: FAILED (exit $status)"; continue
    fi
    if [ "$flavour" = debug ] && [ "${DEBUG_COMPARE:-0}" != 1 ]; then
      # the debug build (-O0) must run every deck to its exit status without a
      # trap or runtime error; its numbers are compared by make check-opt
      passed=$((passed + 1)); echo "   $name: exit $status as expected, no runtime error"; continue
    fi
    tol="reference_outputs/$name.tol"
    [ -f "$tol" ] || tol=""
    if "$build/release/tools/compare_tables" "$ref" "$out" $tol > "$work/$flavour/$name.cmp" 2>&1; then
      passed=$((passed + 1)); echo "   $name: $(tail -n 1 "$work/$flavour/$name.cmp")"
    else
      note_fail "regression $name [$flavour]:
  $(head -n 25 "$work/$flavour/$name.cmp" | sed 's/^/      /')"
      echo "   $name: FAILED (see $work/$flavour/$name.cmp)"
    fi
  done
done

if [ $failed -gt 0 ]; then
  echo "== failures:$failures"
fi
echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
