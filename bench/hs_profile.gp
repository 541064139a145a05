# Dolan-More performance profile of all objective evaluations (NF + finite differences) on the Hock-Schittkowski
# collection, from build/bench/hs_profile.dat written by bench_optimizers.
# usage: gnuplot -e "dat='build/bench/hs_profile.dat'; out='build/bench/hs_profile.png'" bench/hs_profile.gp
set terminal pngcairo size 900,560 font ',11'
set output out
set logscale x 2
set xrange [1:4096]
set yrange [0:1.02]
set xlabel 'tau (objective evaluations within tau times the fewest of the four runs)'
set ylabel 'share of the 103 problems solved'
set key bottom right
set grid
set title 'Hock-Schittkowski collection, standard starts: all objective evaluations (NF + finite differences)'
plot dat using 1:2 with steps lw 2 title 'Gauss family (default settings: filter)', \
     dat using 1:3 with steps lw 2 title 'Gauss family, hessian = ''bfgs''', \
     dat using 1:4 with steps lw 2 title 'NLopt SLSQP', \
     dat using 1:5 with steps lw 2 title 'NLopt COBYLA'
