# made by `maptr experiment wear --out docs/results/wear`; run in this folder: gnuplot wear-idle.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'wear-idle.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Average idle time per agent vs number of agents (EC, 13.2 kg, 1800 s)'
set xlabel 'agents N'
set ylabel 'idle time per agent (steps of T_ON = 100 s)'
set logscale x 2
set xrange [6:40]
set yrange [0:*]
plot 'wear.csv' using "agents":"idle_mean_steps":"idle_min_steps":"idle_max_steps" with yerrorlines lw 2 pt 7 title 'mean (bars: min and max agent)'
