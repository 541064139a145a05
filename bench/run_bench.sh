#!/bin/sh
# Runs every benchmark program (bench/bench_*.f90, built in build/release/bench/)
# and keeps each one's report in build/bench/<name>.txt.  Benchmarks print
# figures (error against cost, cost per evaluation against problem size);
# they never pass or fail.  Copy a report into doc/ when it documents a result.
# usage: run_bench.sh BUILD_DIR
set -u
build=${1:-build}
mkdir -p "$build/bench"
export BENCH_DIR="$build/bench"     # where bench_optimizers writes its data files
for b in "$build"/release/bench/bench_*; do
  [ -x "$b" ] || continue
  name=$(basename "$b")
  echo "== $name"
  "$b" | tee "$build/bench/$name.txt"
done
# the optimizer collection's performance profile (doc/optimization.md)
if [ -f "$build/bench/hs_profile.dat" ] && command -v gnuplot > /dev/null; then
  gnuplot -e "dat='$build/bench/hs_profile.dat'; out='$build/bench/hs_profile.png'" bench/hs_profile.gp &&
    echo "figure $build/bench/hs_profile.png (copy to doc/figures/optimization_hs_profile.png)"
fi
echo "reports in $build/bench/"
