#!/bin/sh
# Planar limit of the spatial analysis: Tennant's four-bar at 100 rad/s,
# linear, two elements per link, one revolution, built in the spatial code
# (inputs/spatial_fourbar_planar_100.nml, revolute joints about Z) and in the
# planar code (inputs/fourbar_100_linear.nml with the same tolerances, span,
# output step and mesh).  The physics and the mesh are the same (doc/spatial.md,
# "Planar limit"); the runs differ only in DLSODE's step choices (other
# unknowns, other error norm), rtol = 1e-9: B and C displacements agree to
# 1e-6 relative (+1e-8 in near zero crossings), element stresses to 1e-6
# (+0.05 psi = 1.6e-6 of the crank's peak 31700 psi, near small values); out-of-plane
# columns are exactly zero.
# usage: spatial_planar_limit.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
sed -e "s/rtol = .*/rtol = 1.0e-9/" -e "s/atol = .*/atol = 1.0e-13/" -e "s/revolutions = .*/revolutions = 1/" \
    -e "s/output_step_deg = .*/output_step_deg = 5.0/" -e "s/link_n_elements = .*/link_n_elements = 3*2/" \
    inputs/fourbar_100_linear.nml > "$work/planar.nml"
"$flexmech" "$work/planar.nml" -o "$work/planar.out" > /dev/null
"$flexmech" inputs/spatial_fourbar_planar_100.nml -o "$work/spatial.out" > /dev/null
# pick columns by name into a common layout: t crank_deg BX BY CX CY s1 s2 s3
pick() {  # file, then the 9 column names in order
  f=$1; shift
  awk -v want="$*" '
    BEGIN { n = split(want, w, " ") }
    /^#/ { hdr = $0; next }
    !done { split(substr(hdr, 2), h, " "); for (i in h) idx[h[i]] = i;
            printf "#"; for (k = 1; k <= n; k++) printf " c%d", k; printf "\n"; done = 1 }
    { for (k = 1; k <= n; k++) printf " %s", $(idx[w[k]]); printf "\n" }' "$f"
}
pick "$work/planar.out" t crank_deg B_U B_W C_U C_W sigma_max_e1 sigma_max_e2 sigma_max_e3 > "$work/planar.cols"
pick "$work/spatial.out" t crank_deg B_UX B_UY C_UX C_UY sigma_max_e1 sigma_max_e2 sigma_max_e3 > "$work/spatial.cols"
printf 'default 1e-6 1e-8\nc7 1e-6 0.05\nc8 1e-6 0.05\nc9 1e-6 0.05\n' > "$work/tol"
"$compare" "$work/planar.cols" "$work/spatial.cols" "$work/tol"
# out of the plane: B_UZ, C_UZ exactly zero
awk '/^#/ {hdr = $0; next} {split(substr(hdr, 2), h, " "); for (i in h) if (h[i] == "B_UZ" || h[i] == "C_UZ") if ($i != 0) bad = 1}
     END {if (bad) {print "out-of-plane displacement not zero"; exit 1}}' "$work/spatial.out"
