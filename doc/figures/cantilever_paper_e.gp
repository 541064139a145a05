# Paper E section 8.3, Figs 2-7 (captions lost in the OCR; subject read from the text, "Rotating
# cantilever beam (see Figures 2-7)" at 100, 300, 500 rad/s, and from Kear's pair of figures for the
# same experiment, "Response of a rotating cantilever beam" and "Transverse response"): for each
# speed the tip's axial response u_L and its transverse response, from the decks
# inputs/cantilever_rotating_paper_e_{100,300,500}.nml (E = 10.6e6, the modulus the printed u_L fixes;
# started at the full speed from rest, beta = 2e-3 s), with the printed u_L.  Run from the
# repository root.
set terminal pngcairo size 1200,1000 font ',9'
set output 'doc/figures/cantilever_paper_e.png'
d = 'reference_outputs/cantilever_rotating_paper_e_'
set multiplot layout 3,2 title "Paper E's rotating cantilever (L = 20 in, r = 0.2 in, E = 10.6e6 psi), started at full speed (Figs 2-7, captions lost: reconstructed)"
set xlabel 't (s)'
set key bottom right
set format y '%.2te%+03T'
do for [i = 1:3] {
  w = word('100 300 500', i)
  up = word('6.3799e-4 5.7419e-3 1.5949e-2', i)
  f = d.w.'.out'
  set title sprintf('Fig %d (reconstructed): axial response of the tip at %s rad/s', 2*i, w)
  set ylabel 'u_L (in)'
  set yrange [0:1.2*real(up)]
  set key bottom right
  plot f using 1:5 with lines lw 1.5 title 'flexmech beam\_u\_end', \
       real(up) with lines dt 2 lw 1.5 title sprintf('paper E table: u_L = %s', up)
  set title sprintf('Fig %d (reconstructed): transverse response of the tip at %s rad/s', 2*i + 1, w)
  set ylabel 'v_L (in), in the rotation plane'
  set autoscale y
  set key top right
  plot f using 1:6 with lines lw 1.5 title 'flexmech beam\_w\_end'
}
unset multiplot
