#!/bin/sh
# Progress goes to stderr only when stderr is a terminal.  Under a
# pseudo-terminal (util-linux `script`) a transient run shows its percentage
# and revolution and a sweep its points done (k/n); redirected to a file, the
# same runs write nothing to stderr.  Skipped without `script`.
# usage: progress_on_terminal.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); work=$3
rm -rf "$work"; mkdir -p "$work"
command -v script >/dev/null 2>&1 || { echo "skipped: no script(1)"; exit 0; }
fail=0
script -qec "'$bin' inputs/fourbar_150_damped.nml -o '$work/t.out'" "$work/t.tty" > /dev/null 2>&1 || true
grep -q 'transient 100%' "$work/t.tty" || { echo "FAIL: no 'transient 100%' on the terminal"; fail=1; }
grep -qE 'transient 100%  revolution 5, crank angle 1800 deg, [0-9]+ steps' "$work/t.tty" || { echo "FAIL: no revolution/crank angle on the terminal"; fail=1; }
"$bin" inputs/fourbar_150_damped.nml -o "$work/t2.out" > /dev/null 2> "$work/t2.err"
[ ! -s "$work/t2.err" ] || { echo "FAIL: progress written to a non-terminal stderr"; fail=1; }
script -qec "'$bin' inputs/sweep_tennant_speed.nml -o '$work/s.out'" "$work/s.tty" > /dev/null 2>&1 || true
grep -q 'sweep points done  6/6 100%' "$work/s.tty" || { echo "FAIL: no 'sweep points done  6/6 100%'"; fail=1; }
[ $fail -eq 0 ] && echo "progress: all ok"
exit $fail
