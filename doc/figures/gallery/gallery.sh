#!/bin/sh
# The paper gallery (doc/gallery.md): runs the shipped decks that reproduce
# the papers' figures and tables and draws each figure with `flexmech plot`
# into doc/figures/gallery/ (PNG), or with its own script doc/figures/NAME.gp
# into doc/figures/; prints the reproduced table rows.
# Run from the repository root after `make`:  make figures
# usage: gallery.sh [FLEXMECH [RUN_DIR]]
set -eu
bin=${1:-build/bin/flexmech}
run=${2:-build/gallery}
fig=doc/figures/gallery
mkdir -p "$run" "$fig"
rm -f "$fig"/*.png
command -v gnuplot >/dev/null 2>&1 || { echo "gallery: gnuplot not installed (make deps)" >&2; exit 1; }

deck() {  # run inputs/NAME.nml into RUN/NAME.out (quietly)
  "$bin" "inputs/$1.nml" -o "$run/$1.out" > "$run/$1.log" 2>&1 || {
    st=$?; [ $st -eq 3 ] || { echo "gallery: $1 failed (exit $st), see $run/$1.log" >&2; exit 1; }; }
}
cmp() {  # flexmech plot --compare into the gallery, PNG only
  "$bin" plot "$@" --compare -d "$fig" --png > /dev/null
}
one() {  # standard figures of one output into the gallery
  "$bin" plot "$@" -d "$fig" --png > /dev/null
}

# Tennant (T), the four-bar in the steady state, Figs. 3-8
for d in tennant_fig3_linear tennant_fig3_shear_d0 tennant_fig3_shear_d1 \
         tennant_fig4_linear tennant_fig4_shear_d0 tennant_fig4_shear_d1 \
         tennant_fig5_linear tennant_fig5_geometric tennant_fig6_material; do
  deck $d
done
r=$run
cmp $r/tennant_fig3_linear.out $r/tennant_fig3_shear_d0.out $r/tennant_fig3_shear_d1.out -n T_fig3 --columns B_U \
    -t 'T Fig. 3: deformation U~1 of the crank end B at 100 rad/sec' \
    --labels '(i) linear, no shear angle;(ii) shear angle, all D = 0;(iii) shear angle, all D = 1'
cmp $r/tennant_fig4_linear.out $r/tennant_fig4_shear_d0.out $r/tennant_fig4_shear_d1.out -n T_fig4 --columns B_U \
    -t 'T Fig. 4: deformation U~1 of the crank end B at 200 rad/sec' \
    --labels '(i) linear, no shear angle;(ii) shear angle, all D = 0;(iii) shear angle, all D = 1'
cmp $r/tennant_fig5_linear.out $r/tennant_fig5_geometric.out -n T_fig5_fig7 --columns C_U,sigma_max_e2 \
    -t 'T Figs. 5 and 7: U~2 and the maximum stress of element 2 at 150 rad/sec, geometric nonlinearity' \
    --labels 'linear;nonlinear (D_b = D_g = 1)'
cmp $r/tennant_fig5_linear.out $r/tennant_fig6_material.out -n T_fig6_fig8 --columns C_U,sigma_max_e2 \
    -t 'T Figs. 6 and 8: U~2 and the maximum stress of element 2 at 150 rad/sec, material nonlinearity' \
    --labels 'linear;nonlinear (D_k = 1)'

# Kear (K), the verification beams (Figs. 1-4) and the rotating cantilever (Figs. 6-7): the
# paper gives no data, so these are the same cases on the section and material of T
# (the decks with link points at the quarter and mid span: deck variables point_link, point_at)
for d in beam_pinned_mode1 beam_pinned_mode2 beam_clamped_mode1 beam_clamped_mode2; do
  sed "s/^&transient/\&transient point_link = 'beam', 'beam', point_at = 0.25, 0.5,/" inputs/$d.nml > "$run/$d.nml"
  "$bin" "$run/$d.nml" -o "$run/$d.out" > "$run/$d.log"
done
cmp $r/beam_pinned_mode1.out -n K_fig1 --columns beam_s0.25_w,beam_s0.5_w \
    -t 'K Fig. 1: response of a pinned-pinned beam - 1st mode (stand-in data)' --labels 'flexmech'
cmp $r/beam_pinned_mode2.out -n K_fig2 --columns beam_s0.25_w,beam_s0.5_w \
    -t 'K Fig. 2: response of a pinned-pinned beam - 2nd mode (stand-in data)' --labels 'flexmech'
cmp $r/beam_clamped_mode1.out -n K_fig3 --columns beam_s0.25_w,beam_s0.5_w \
    -t 'K Fig. 3: response of a clamped-clamped beam - 1st mode (stand-in data)' --labels 'flexmech'
cmp $r/beam_clamped_mode2.out -n K_fig4 --columns beam_s0.25_w,beam_s0.5_w \
    -t 'K Fig. 4: response of a clamped-clamped beam - 2nd mode (stand-in data)' --labels 'flexmech'
deck cantilever_rotating_300
cmp $r/cantilever_rotating_300.out -n K_fig6_fig7 --columns beam_u_end,beam_w_end \
    -t 'K Figs. 6 and 7: response of a rotating cantilever beam (stand-in data: 300 rad/s, damped)' --labels 'flexmech'

# Ertas-Willmert (E), the four-bar by the spatial code at 100 rad/s, Figs. 8-14
deck spatial_fourbar_100
cmp $r/spatial_fourbar_100.out -n E_fig8_fig9_fig11 --columns B_UX,B_UY,C_UX \
    -t 'E Figs. 8, 9, 11: axial and vertical displacements of node 2 (B), axial of node 3 (C), 100 rad/s' \
    --labels 'flexmech'
cmp $r/spatial_fourbar_100.out -n E_fig10 --columns crank_tz_end \
    -t 'E Fig. 10: angle of rotation of node 2 (crank end), 100 rad/s' --labels 'flexmech'
cmp $r/spatial_fourbar_100.out -n E_fig12_fig14 --columns sigma_max_e1,sigma_max_e3,sigma_max_e5 \
    -t 'E Figs. 12-14: maximum absolute stress of crank, coupler, rocker (elements 1, 3, 5: the first of each link), 100 rad/s' --labels 'flexmech'

# The deformed mechanism (what the project's graphics work showed): the default four-bar with
# its links' shapes written (shape_points), at the largest stress of its last revolution
sed 's/^  shape_points = 4$/  shape_points = 8/' inputs/fourbar_150_damped.nml \
  > "$run/fourbar_150_shapes.nml"
"$bin" "$run/fourbar_150_shapes.nml" -o "$run/fourbar_150_shapes.out" > /dev/null
one "$run/fourbar_150_shapes.out"
rm -f "$fig"/fourbar_150_shapes_joints.png "$fig"/fourbar_150_shapes_links.png "$fig"/fourbar_150_shapes_stress.png
# the steady revolution of T Figs. 5-8 (harmonic series and exact periodic solution) and the spatial
# four-bar of E and the RSSR four-bar, their links' shapes written, in 2D and in 3D
shapes() {  # shapes NAME SED: run inputs/NAME.nml edited by SED into RUN/NAME_shapes.out, draw its still
  sed "$2" "inputs/$1.nml" > "$run/$1_shapes.nml"
  "$bin" "$run/$1_shapes.nml" -o "$run/$1_shapes.out" > /dev/null
  one "$run/$1_shapes.out"
  rm -f "$fig/$1_shapes_joints.png" "$fig/$1_shapes_links.png" "$fig/$1_shapes_stress.png"
}
shapes tennant_fig5_exact 's/^  output_step_deg = 2.0$/  output_step_deg = 2.0, shape_points = 8/'
shapes spatial_fourbar_100 's/^  damping_beta = 1.0e-6$/  damping_beta = 1.0e-6, shape_points = 8/'
shapes spatial_rssr_100 's/^  output_step_deg = 5.0$/  output_step_deg = 5.0, shape_points = 8/'

# Path synthesis (B, P): the Table 3 design recovered from its own coupler path
deck opt_fourbar_path
one "$run/opt_fourbar_path.out"

# P Table I: Rosen-Suzuki, iterations NI and function evaluations NF
echo "P Table I (Rosen-Suzuki): deck, NI, NF"
for d in opt_rosen_suzuki_gnlc_ns_x0_0000 opt_rosen_suzuki_gnlc_ns_x0_1111 opt_rosen_suzuki_gnlc_ns_x0_2222 \
         opt_rosen_suzuki_gnlc_ns_x0_00r50 opt_rosen_suzuki_gnlc_x0_00r50 opt_rosen_suzuki_gnlc_x0_0000 \
         opt_rosen_suzuki_gnlc_x0_1111; do
  deck $d
  echo "  $d $(sed -n 's/^# summary: NI = //p' "$run/$d.out") $(sed -n 's/^# summary: NF = //p' "$run/$d.out")"
done
# Paper figures drawn by their own gnuplot scripts (doc/figures/NAME.gp read the reference
# outputs; here they read fresh runs of the same decks)
paper_gp() {  # NAME DECK...: run the decks into RUN, then doc/figures/NAME.gp on those outputs
  s=$1; shift
  for d in "$@"; do deck "$d"; done
  sed "s|reference_outputs/|$run/|g" "doc/figures/$s.gp" | gnuplot
}
paper_gp cantilever_paper_e cantilever_rotating_paper_e_100 cantilever_rotating_paper_e_300 \
    cantilever_rotating_paper_e_500                                 # E Figs. 2-7
paper_gp spatial_fourbar_100 spatial_fourbar_100                    # E Figs. 8-14 (overview)
paper_gp spatial_fourbar_150 spatial_fourbar_150 spatial_fourbar_150_damped   # E Figs. 15-21
rm -f "$fig"/*.gp "$fig"/*.dat
echo "gallery: figures in $fig"
