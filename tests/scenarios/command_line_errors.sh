#!/bin/sh
# Usage errors exit 1 with a message and no runtime error (-o given twice
# used to fail inside the Fortran runtime: "already allocated"); a deck that
# is a directory exits 2 saying so.
# usage: command_line_errors.sh FLEXMECH COMPARE_TABLES WORKDIR
set -u
flexmech=$1; work=$3
rm -rf "$work"; mkdir -p "$work"
fails=0
expect() {   # expect STATUS FRAGMENT ARGS...
  want=$1; frag=$2; shift 2
  "$flexmech" "$@" > "$work/stdout" 2> "$work/stderr"; st=$?
  [ $st -eq "$want" ] || { echo "FAIL $*: exit $st, expected $want"; fails=$((fails + 1)); }
  grep -qF -- "$frag" "$work/stderr" || { echo "FAIL $*: message lacks '$frag': $(cat "$work/stderr")"; fails=$((fails + 1)); }
  if grep -qE 'Fortran runtime|Backtrace' "$work/stderr"; then echo "FAIL $*: runtime error"; fails=$((fails + 1)); fi
}
expect 1 "-o given twice" inputs/lsode_kinetics.nml -o "$work/a.out" -o "$work/b.out"
expect 1 "unknown option '-q'" -q inputs/lsode_kinetics.nml
expect 1 "-o needs a file name" inputs/lsode_kinetics.nml -o
expect 1 "unexpected argument" inputs/lsode_kinetics.nml inputs/lsode_kinetics.nml
expect 1 "usage:"
expect 2 "is a directory" "$work"
expect 2 "file not found" "$work/no_such_deck.nml"
ls "$work"/*.out* >/dev/null 2>&1 && { echo "FAIL output left: $(ls "$work"/*.out*)"; fails=$((fails + 1)); }
echo "$fails failures"
[ $fails -eq 0 ]
