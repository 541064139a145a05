# Spinning cantilever (inputs/cantilever_rotating_300.nml): axial tip displacement
# in the beam's rotating axes against the closed-form steady stretch of a bar
# spinning about its root, tan(kL)/k - L.  Run from the repository root.
set terminal pngcairo size 800,420 font ',10'
set output 'doc/figures/cantilever_stretch.png'
E = 10.87e6; rho = 2.536e-4; L = 20.0; W = 300.0
k = W*sqrt(rho/E)
u_exact = tan(k*L)/k - L
u_lead = rho*W**2*L**3/(3*E)
set xlabel 'crank angle (deg)'
set ylabel 'tip axial displacement (in)'
set key bottom right
set title 'Cantilever started at 300 rad/s, beta = 4e-3 s, 2 elements, stretching on'
plot 'reference_outputs/cantilever_rotating_300.out' using 2:5 with linespoints pt 7 ps 0.5 title 'flexmech u(L)', \
     u_exact with lines lw 2 title sprintf('tan(kL)/k - L = %.5e', u_exact), \
     u_lead with lines dt 2 title sprintf('{/Symbol r}{/Symbol W}^2L^3/(3E) = %.5e', u_lead)
