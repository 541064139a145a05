#!/bin/sh
# One quiet build step: run a command with its output appended to the build
# log; on failure print that step's own output and the log's path, and
# print any warning a successful step gave.
# The first step of a make invocation (BUILD_ID) starts the log afresh and
# prints BANNER; the others print nothing.
# usage: build_step.sh LOG BANNER command [argument ...]
log=$1; banner=$2; shift 2
dir=$(dirname "$log")
mkdir -p "$dir"
mark="$dir/.started-${BUILD_ID:-0}"
if (set -C; : > "$mark") 2>/dev/null; then
  find "$dir" -maxdepth 1 -name '.started-*' ! -name ".started-${BUILD_ID:-0}" -exec rm -f {} + 2>/dev/null
  echo "$banner" > "$log"
  echo "$banner (full log: $log; V=1 prints every command)"
fi
step=$(mktemp "${TMPDIR:-/tmp}/flexmech-step.XXXXXX")
echo "$*" > "$step"
"$@" >> "$step" 2>&1
status=$?
cat "$step" >> "$log"
if [ $status -ne 0 ]; then
  echo "flexmech build: this step failed (exit $status):" >&2
  tail -n 40 "$step" | sed 's/^/  /' >&2
  echo "flexmech build: full log $log" >&2
elif [ "$(wc -l < "$step")" -gt 1 ]; then
  # a warning: the sources are meant to build warning-free, so show it
  sed 1d "$step" >&2
fi
rm -f "$step"
exit $status
