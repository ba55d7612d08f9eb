# made by `maptr experiment battery --out docs/results/battery`; run in this folder: gnuplot battery-active.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'battery-active.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Active agents (L + R), NO vs EC'
set xlabel 'time (s)'
set ylabel 'active agents'
set yrange [0:17]
plot 'series/no.csv' using "t_s":"n_active" with lines lw 2 title 'NO', \
     'series/ec.csv' using "t_s":"n_active" with lines lw 2 title 'EC'
