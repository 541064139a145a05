#!/bin/sh
# Regenerates doc/figures/standard/: the standard figures of a set of reference
# outputs, drawn by `flexmech plot` itself, so the figures in doc/ are exactly
# what users get from their own runs (tests/scenarios/plot_figures.sh checks
# that the committed scripts are what `flexmech plot` writes today).
# Run from the repository root after `make`:  sh tools/doc_figures.sh
# usage: doc_figures.sh [FLEXMECH [DIR [--script-only]]]   (the drift test writes the scripts elsewhere)
set -eu
bin=${1:-build/bin/flexmech}
dir=${2:-doc/figures/standard}
mode=${3:---png}
mkdir -p "$dir"
for name in fourbar_150_damped fourbar_100_nonlinear slidercrank_150_nonlinear \
            tennant_fig3_linear tennant_fig5_exact tennant_fig6_material \
            opt_rosen_suzuki_gnlc_x0_0000 opt_fourbar_path lsode_kinetics; do
  "$bin" plot "reference_outputs/$name.out" -d "$dir" "$mode"
done
# comparisons: the paper's figures (T Figs. 3-8) and linear against nonlinear transients
r=reference_outputs
cmp() { "$bin" plot "$@" --compare -d "$dir" "$mode"; }
cmp $r/tennant_fig3_linear.out $r/tennant_fig3_shear_d0.out $r/tennant_fig3_shear_d1.out -n tennant_fig3 \
    --columns B_U -t 'T Fig. 3: deformation U~1 (B_U) of the crank end at 100 rad/sec' \
    --labels 'linear, no shear angle (Bahgat-Willmert stand-in);shear angle, tracing constants 0;shear angle, tracing constants 1'
cmp $r/tennant_fig4_linear.out $r/tennant_fig4_shear_d0.out $r/tennant_fig4_shear_d1.out -n tennant_fig4 \
    --columns B_U -t 'T Fig. 4: deformation U~1 (B_U) of the crank end at 200 rad/sec' \
    --labels 'linear, no shear angle (Bahgat-Willmert stand-in);shear angle, tracing constants 0;shear angle, tracing constants 1 (crank past the R-O peak)'
cmp $r/tennant_fig5_linear.out $r/tennant_fig5_geometric.out -n tennant_fig5_fig7 --columns C_U,sigma_max_e2 \
    -t 'T Figs. 5 and 7: 150 rad/sec, geometric nonlinearity' \
    --labels 'linear;nonlinear (D_b = D_g = 1)'
cmp $r/tennant_fig5_linear.out $r/tennant_fig6_material.out -n tennant_fig6_fig8 --columns C_U,sigma_max_e2 \
    -t 'T Figs. 6 and 8: 150 rad/sec, material nonlinearity' \
    --labels 'linear;nonlinear (D_k = 1)'
cmp $r/fourbar_150_linear.out $r/fourbar_150_geometric.out -n fourbar_150_linear_vs_geometric \
    --columns B_U,B_W,sigma_max_e1,sigma_max_e2,sigma_max_e3 \
    -t 'Four-bar at 150 rad/s from the rigid-body state' \
    --labels 'linear;geometric nonlinearities'
cmp $r/fourbar_100_linear.out $r/fourbar_100_nonlinear.out -n fourbar_100_linear_vs_nonlinear \
    --columns B_U,B_W,sigma_max_e1,sigma_max_e2,sigma_max_e3 \
    -t 'Four-bar at 100 rad/s from the rigid-body state' \
    --labels 'linear;all nonlinear effects'
for out in doc/figures/data/*.out; do   # outputs too costly for the regression tests
  [ -f "$out" ] && "$bin" plot "$out" -d "$dir" "$mode"
done
for deck in inputs/sweep_*.nml; do
  [ -f "$deck" ] || continue
  name=$(basename "$deck" .nml)
  [ -f "reference_outputs/$name.out" ] || continue
  "$bin" plot "reference_outputs/$name.out" -d "$dir" "$mode"
done
