# made by `maptr experiment battery --out docs/results/battery`; run in this folder: gnuplot battery-speed.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'battery-speed.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Speed, NO vs EC (34.4 kg, 15 m/s reference)'
set xlabel 'time (s)'
set ylabel 'speed (m/s)'
set yrange [0:*]
plot 'series/no.csv' using "t_s":"v_x_mps" with lines lw 2 title 'NO', \
     'series/ec.csv' using "t_s":"v_x_mps" with lines lw 2 title 'EC'
