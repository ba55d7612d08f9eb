# made by `maptr experiment battery --out docs/results/battery`; run in this folder: gnuplot battery-efficiency.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'battery-efficiency.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Per-agent efficiency, NO vs EC'
set xlabel 'time (s)'
set ylabel 'efficiency of an active agent'
set yrange [0:1]
plot 'series/no.csv' using "t_s":"eff_agent" with lines lw 2 title 'NO', \
     'series/ec.csv' using "t_s":"eff_agent" with lines lw 2 title 'EC'
