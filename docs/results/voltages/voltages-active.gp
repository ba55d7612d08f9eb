# made by `maptr experiment voltages --out docs/results/voltages`; run in this folder: gnuplot voltages-active.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'voltages-active.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Active agents (L + R), EC, 14.4 kg at 8 m/s, several supply voltages'
set xlabel 'time (s)'
set ylabel 'active agents'
set yrange [0:*]
plot 'series/12V.csv' using "t_s":"n_active" with lines lw 2 title '12 V', \
     'series/16V.csv' using "t_s":"n_active" with lines lw 2 title '16 V', \
     'series/20V.csv' using "t_s":"n_active" with lines lw 2 title '20 V', \
     'series/23.4V.csv' using "t_s":"n_active" with lines lw 2 title '23.4 V'
