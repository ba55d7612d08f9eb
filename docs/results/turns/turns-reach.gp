# made by `maptr experiment turns --out docs/results/turns`; run in this folder: gnuplot turns-reach.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'turns-reach.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Tightest steady turn against speed (16 agents, Type I, full battery)'
set xlabel 'speed (m/s)'
set ylabel 'tightest radius (m), log scale'
set logscale y
set key outside right top
set samples 200
plot 'turns-reach.csv' using "speed_mps":"R_uni_13.2kg_m" with linespoints lw 2 pt 7 lc rgb '#7b3294' dt 2 title 'unidirectional, 13.2 kg', \
     '' using "speed_mps":"R_uni_30kg_m" with linespoints lw 2 pt 5 lc rgb '#008837' dt 2 title 'unidirectional, 30 kg', \
     '' using "speed_mps":"R_uni_38.2kg_m" with linespoints lw 2 pt 9 lc rgb '#2166ac' dt 2 title 'unidirectional, 38.2 kg', \
     '' using "speed_mps":"R_bi_13.2kg_m" with linespoints lw 2 pt 7 lc rgb '#7b3294' title 'bidirectional, 13.2 kg', \
     '' using "speed_mps":"R_bi_30kg_m" with linespoints lw 2 pt 5 lc rgb '#008837' title 'bidirectional, 30 kg', \
     '' using "speed_mps":"R_bi_38.2kg_m" with linespoints lw 2 pt 9 lc rgb '#2166ac' title 'bidirectional, 38.2 kg', \
     x**2/0.9810 with lines lw 1 dt 3 lc rgb 'black' title 'v^2/(mu_l g)'
