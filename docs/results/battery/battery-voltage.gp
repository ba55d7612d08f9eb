# made by `maptr experiment battery --out docs/results/battery`; run in this folder: gnuplot battery-voltage.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'battery-voltage.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Battery voltage, NO vs EC (34.4 kg, 15 m/s)'
set xlabel 'time (s)'
set ylabel 'battery voltage (V, mean of L and R)'
plot 'series/no.csv' using "t_s":"battery_V" with lines lw 2 title 'NO', \
     'series/ec.csv' using "t_s":"battery_V" with lines lw 2 title 'EC'
