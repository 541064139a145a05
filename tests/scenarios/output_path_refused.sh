#!/bin/sh
# The output path is checked before the analysis (issue 8, item 7): an empty
# name, an existing directory, a symbolic link, a FIFO, a device node (when
# mknod is permitted) and the deck itself are refused with exit 2, a message
# naming the output and why, no temporary file left, and the target
# untouched (the link still a link, the FIFO still a FIFO, the deck intact).
# A missing directory is refused the same way.
# usage: output_path_refused.sh FLEXMECH COMPARE_TABLES WORKDIR
set -u
flexmech=$1; work=$3
rm -rf "$work"; mkdir -p "$work/dir"
cp inputs/lsode_kinetics.nml "$work/deck.nml"
ln -s deck.nml "$work/link"
mkfifo "$work/fifo"
fails=0
refuse() {   # refuse TARGET FRAGMENT
  "$flexmech" "$work/deck.nml" -o "$1" > "$work/stdout" 2> "$work/stderr"
  st=$?
  if [ $st -ne 2 ]; then echo "FAIL -o '$1': exit $st, expected 2"; fails=$((fails + 1)); fi
  if ! grep -qF -- "$2" "$work/stderr"; then
    echo "FAIL -o '$1': message lacks '$2': $(cat "$work/stderr")"; fails=$((fails + 1))
  fi
  if ls "$work"/*.tmp* "$work"/.tmp* "$work"/dir/*.tmp* ./*.tmp* ./.tmp* >/dev/null 2>&1; then
    echo "FAIL -o '$1': temporary file left"; fails=$((fails + 1)); rm -f "$work"/*.tmp* "$work"/.tmp* ./.tmp*
  fi
}
refuse "" "output file name is empty"
refuse "$work/dir" "is a directory"
refuse "$work/link" "is a symbolic link"
refuse "$work/fifo" "not a regular file"
refuse "$work/deck.nml" "is the deck itself"
refuse "$work/dir/../deck.nml" "is the deck itself"
refuse "$work/no_such_dir/x.out" "cannot create"
if mknod "$work/null" c 1 3 2>/dev/null; then
  refuse "$work/null" "not a regular file"
  [ -c "$work/null" ] || { echo "FAIL device node replaced"; fails=$((fails + 1)); }
else
  echo "(mknod not permitted here: device node case skipped)"
fi
[ -L "$work/link" ] || { echo "FAIL symbolic link replaced"; fails=$((fails + 1)); }
[ -p "$work/fifo" ] || { echo "FAIL FIFO replaced"; fails=$((fails + 1)); }
cmp -s inputs/lsode_kinetics.nml "$work/deck.nml" || { echo "FAIL deck overwritten"; fails=$((fails + 1)); }
# a regular file is replaced as before
: > "$work/old.out"
"$flexmech" "$work/deck.nml" -o "$work/old.out" > /dev/null 2>&1 || { echo "FAIL regular output refused"; fails=$((fails + 1)); }
grep -q '^# summary' "$work/old.out" || { echo "FAIL regular output not written"; fails=$((fails + 1)); }
echo "$fails failures"
[ $fails -eq 0 ]
