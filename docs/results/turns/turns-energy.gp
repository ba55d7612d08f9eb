# made by `maptr experiment turns --out docs/results/turns`; run in this folder: gnuplot turns-energy.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'turns-energy.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Energy drawn on the warehouse loop, NO vs EC (30 kg, 1 m/s)'
set xlabel 'time (s)'
set ylabel 'energy (kJ)'
set key inside left top
plot 'series/loop-no.csv' using "t_s":"energy_kJ" with lines lw 2 title 'loop NO', \
     'series/loop-ec.csv' using "t_s":"energy_kJ" with lines lw 2 title 'loop EC'
