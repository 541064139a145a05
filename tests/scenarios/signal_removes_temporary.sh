#!/bin/sh
# SIGTERM, SIGINT or SIGHUP during a run remove the temporary output file
# (issue 8, item 7) and the program still dies of the signal (status 128+n):
# a four-bar run of 2000 revolutions is started, the signal is sent as soon
# as its temporary file exists (no timing assumption: the run lasts far
# longer than the wait), then the directory must hold neither the output nor
# a temporary file.
# usage: signal_removes_temporary.sh FLEXMECH COMPARE_TABLES WORKDIR
set -u
flexmech=$1; work=$3
rm -rf "$work"; mkdir -p "$work"
sed -e 's/revolutions = 5/revolutions = 2000/' inputs/fourbar_150_damped.nml > "$work/long.nml"
fails=0
# a non-interactive shell starts background jobs with SIGINT ignored, and a
# suite started under nohup ignores SIGHUP (the program leaves an ignored
# signal ignored): coreutils' env restores both
sigs="TERM HUP"; start=""
if env --default-signal=INT,HUP true 2>/dev/null; then sigs="TERM INT HUP"; start="env --default-signal=INT,HUP"; fi
for sig in $sigs; do
  case $sig in TERM) want=143 ;; INT) want=130 ;; HUP) want=129 ;; esac
  $start "$flexmech" "$work/long.nml" -o "$work/long.out" > /dev/null 2>&1 &
  pid=$!
  i=0
  while ! ls "$work"/long.out.tmp* >/dev/null 2>&1; do
    i=$((i + 1)); [ $i -gt 600 ] && break; sleep 0.1
  done
  kill -s $sig $pid
  wait $pid; st=$?
  [ $st -eq $want ] || { echo "FAIL SIG$sig: exit status $st, expected $want"; fails=$((fails + 1)); }
  if ls "$work"/long.out* >/dev/null 2>&1; then
    echo "FAIL SIG$sig: left $(ls "$work"/long.out*)"; fails=$((fails + 1)); rm -f "$work"/long.out*
  fi
done
echo "$fails failures"
[ $fails -eq 0 ]
