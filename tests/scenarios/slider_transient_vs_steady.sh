#!/bin/sh
# A link sliding through a sleeve (slider_link, T24) in the transient analysis
# agrees with the steady analysis's exact periodic solution: the Whitworth
# deck inputs/whitworth_60_damped.nml (linear, rotatory inertia, Coriolis and
# Euler terms, beta = 1e-5 s) damped over three revolutions into its periodic
# state, against shooting on the same mechanism and the same physics (&tennant
# D_k = D_b = D_g = 0, rotatory inertia on, the same beta; doc/transient.md
# §13).  Compared over the last revolution, every 5 deg of crank: B's global
# displacements, the links' end displacements (the lever's at the sleeve:
# its slide s and the crank's displacement across it) and both elements'
# largest stress.  The start-up transient has decayed to e^-24 of its size;
# what remains is DLSODE's error (rtol 1e-9 and 1e-10): measured 1e-8 relative.
# Tolerance 1e-6 relative (the issue asks 1e-4), with absolute floors of 1e-6
# of each column's peak where a column crosses zero.  Measured: dropping the
# sleeve map's rate terms (2 M_e C_d Q_d + M_e C_dd Q) moves the columns by up
# to 5e-5 of their peaks (324 of 648 values fail), dropping the moving-length
# terms of T24 (Delta_d = Delta_dd = 0) by up to 0.74.
# usage: slider_transient_vs_steady.sh FLEXMECH COMPARE_TABLES WORKDIR
set -eu
flexmech=$1; compare=$2; work=$3
mkdir -p "$work"
deck=inputs/whitworth_60_damped.nml
"$flexmech" "$deck" -o "$work/transient.out" > /dev/null
# the steady deck: the transient deck's &mechanism group, exact periodic solution
{
  printf "&run\n  analysis = 'steady'\n  title = 'Whitworth at 60 rad/s, exact periodic solution'\n/\n"
  awk '/^&mechanism/ {on = 1} on {print} on && /^\// {exit}' "$deck"
  printf "&steady\n  method = 'shooting'\n  output_step_deg = 5.0\n  damping_beta = 1.0e-5\n"
  printf "  rtol = 1.0e-10\n  atol = 1.0e-14\n/\n"
  printf "&tennant\n  d_k = 0, d_b = 0, d_g = 0\n  rotary_inertia = T\n/\n"
} > "$work/steady.nml"
"$flexmech" "$work/steady.nml" -o "$work/steady.out" > /dev/null
# common layout: crank angle within the revolution (the row closing the
# revolution, 360 deg = 0 deg, left out), then the compared columns
pick() {  # file, then the column names in order
  f=$1; shift
  awk '/^#/ {print; next} {if (have) print prev; prev = $0; have = 1}' "$f" > "$f.open"
  awk -v want="$*" '
    BEGIN { n = split(want, w, " ") }
    /^#/ { hdr = $0; next }
    !done { split(substr(hdr, 2), h, " "); for (i in h) idx[h[i]] = i;
            printf "# deg"; for (k = 1; k <= n; k++) printf " %s", w[k]; printf "\n"; done = 1 }
    { d = $(idx["crank_deg"]) % 360; if (d < 0) d += 360; printf " %.6f", d
      for (k = 1; k <= n; k++) printf " %s", $(idx[w[k]]); printf "\n" }' "$f.open" | sort -n -k1 -s
}
cols="B_U B_W crank_u_end crank_w_end lever_u_end lever_w_end sigma_max_e1 sigma_max_e2"
pick "$work/steady.out" $cols > "$work/steady.cols"
pick "$work/transient.out" $cols > "$work/transient.cols"
rows=$(grep -vc '^#' "$work/transient.cols")
[ "$rows" -eq 72 ] || { echo "expected 72 rows of the last revolution, got $rows"; exit 1; }
cat > "$work/tol" <<'TOL'
default      1e-6  5e-11
deg          0     1e-6
lever_u_end  1e-6  3e-12
sigma_max_*  1e-6  1.5e-4
TOL
"$compare" "$work/steady.cols" "$work/transient.cols" "$work/tol"
