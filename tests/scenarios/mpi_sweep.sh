#!/bin/sh
# A sweep on 2 MPI ranks (build/mpi/bin/flexmech, `make MPI=1`) gives, point by
# point, the serial run's results: the summary rows agree exactly except the
# CPU-time columns, every point's output rows are byte-identical, and the
# failing point (175 rad/s, harmonic 8 on a natural frequency) is reported in
# both summaries while the others run.  A batch of two decks on 2 ranks prints
# one table of exit statuses; one plain deck under mpirun runs once.  Skipped
# when Open MPI or the MPI build is absent.
# usage: mpi_sweep.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
serial=$(cd "$(dirname "$1")" && pwd)/$(basename "$1"); compare=$2; work=$3
mpi=$(dirname "$(dirname "$serial")")/mpi/bin/flexmech
rm -rf "$work"; mkdir -p "$work"
if ! command -v mpirun >/dev/null 2>&1 || [ ! -x "$mpi" ]; then
  echo "skipped: no mpirun or no $mpi (make MPI=1)"; exit 0
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fail=0
sed -e 's/n_harmonics = 12/n_harmonics = 8/' inputs/tennant_fig3_linear.nml > "$work/speeds.nml"
cat >> "$work/speeds.nml" <<'EOD'
&sweep group = 'mechanism', variable = 'omega', values = 50, 100, 175, 125, 150 /
EOD
set +e
(cd "$work" && "$serial" speeds.nml -o serial.out > serial.log 2>&1); s1=$?
(cd "$work" && mpirun -n 2 "$mpi" speeds.nml -o mpi.out > mpi.log 2>&1); s2=$?
set -e
[ $s1 -eq 3 ] || { echo "FAIL: serial sweep exited $s1, expected 3"; fail=1; }
[ $s2 -ne 0 ] || { echo "FAIL: the MPI sweep with a failing point exited 0"; fail=1; }
grep -q 'processes = 2' "$work/mpi.out" || { echo "FAIL: the MPI summary does not say 2 processes"; cat "$work/mpi.log"; fail=1; }
printf 'default 0 0\ncost_cpu_* -1 0\ncost_total_cpu_seconds -1 0\n' > "$work/exact.tol"
"$compare" "$work/serial.out" "$work/mpi.out" "$work/exact.tol" > "$work/cmp.log" 2>&1 \
  || { echo "FAIL: MPI summary differs from the serial one:"; head "$work/cmp.log"; fail=1; }
for k in 1 2 4 5; do
  grep -v '^#' "$work/serial_points/serial_00$k.out" > "$work/s.rows"
  grep -v '^#' "$work/mpi_points/mpi_00$k.out" > "$work/m.rows"
  cmp -s "$work/s.rows" "$work/m.rows" || { echo "FAIL: point $k rows differ between serial and MPI"; fail=1; }
done
grep -q '^# point 3: omega = 175: exit 3 (analysis stopped), no row' "$work/mpi.out" \
  || { echo "FAIL: the MPI summary does not report the failing point"; fail=1; }
cp inputs/lsode_kinetics.nml "$work/good.nml"
sed 's/rtol = .*/rtol = -1.0/' inputs/lsode_kinetics.nml > "$work/bad.nml"
set +e; (cd "$work" && mpirun -n 2 "$mpi" good.nml bad.nml > batch.log 2>&1); set -e
[ "$(grep -c 'batch of 2 decks' "$work/batch.log")" -eq 1 ] || { echo "FAIL: MPI batch table missing or repeated"; cat "$work/batch.log"; fail=1; }
grep -qE '^ +2 +input error +bad.nml' "$work/batch.log" || { echo "FAIL: MPI batch lacks bad.nml's status"; fail=1; }
# one plain deck under mpirun -n 2 runs once (not once per rank)
set +e; (cd "$work" && mpirun -n 2 "$mpi" good.nml -o single.out > single.log 2>&1); st=$?; set -e
[ $st -eq 0 ] || { echo "FAIL: single deck under mpirun exited $st"; cat "$work/single.log"; fail=1; }
[ "$(grep -c 'wrote single.out' "$work/single.log")" -eq 1 ] || { echo "FAIL: the single deck did not run exactly once"; cat "$work/single.log"; fail=1; }
[ $fail -eq 0 ] && echo "mpi sweep: all ok"
exit $fail
