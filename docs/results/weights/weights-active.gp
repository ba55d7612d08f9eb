# made by `maptr experiment weights --out docs/results/weights`; run in this folder: gnuplot weights-active.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'weights-active.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Active agents (L + R), EC, gross masses at 10 m/s'
set xlabel 'time (s)'
set ylabel 'active agents'
set yrange [0:*]
plot 'series/13.2kg.csv' using "t_s":"n_active" with lines lw 2 title '13.2 kg', \
     'series/23.2kg.csv' using "t_s":"n_active" with lines lw 2 title '23.2 kg', \
     'series/33.2kg.csv' using "t_s":"n_active" with lines lw 2 title '33.2 kg'
