#!/bin/sh
# Regenerates doc/figures/standard/: the standard figures of a set of reference
# outputs, drawn by `flexmech plot` itself, so the figures in doc/ are exactly
# what users get from their own runs (tests/scenarios/plot_figures.sh checks
# that the committed scripts are what `flexmech plot` writes today).
# Run from the repository root after `make`:  sh tools/doc_figures.sh
set -eu
bin=${1:-build/bin/flexmech}
dir=doc/figures/standard
mkdir -p "$dir"
for name in fourbar_150_damped fourbar_100_nonlinear slidercrank_150_nonlinear \
            tennant_fig3_linear tennant_fig5_exact tennant_fig6_material \
            opt_rosen_suzuki_gnlc_x0_0000 opt_fourbar_path lsode_kinetics; do
  "$bin" plot "reference_outputs/$name.out" -d "$dir" --png
done
for out in doc/figures/data/*.out; do   # outputs too costly for the regression tests
  [ -f "$out" ] && "$bin" plot "$out" -d "$dir" --png
done
for deck in inputs/sweep_*.nml; do
  [ -f "$deck" ] || continue
  name=$(basename "$deck" .nml)
  [ -f "reference_outputs/$name.out" ] || continue
  "$bin" plot "reference_outputs/$name.out" -d "$dir" --png
done
