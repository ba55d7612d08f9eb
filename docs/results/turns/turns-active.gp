# made by `maptr experiment turns --out docs/results/turns`; run in this folder: gnuplot turns-active.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'turns-active.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Active agents (L + R) on the warehouse loop'
set xlabel 'time (s)'
set ylabel 'active agents'
set yrange [0:17]
plot 'series/loop-no.csv' using "t_s":"n_active" with steps lw 2 title 'loop NO', \
     'series/loop-ec.csv' using "t_s":"n_active" with steps lw 2 title 'loop EC'
