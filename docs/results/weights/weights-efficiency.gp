# made by `maptr experiment weights --out docs/results/weights`; run in this folder: gnuplot weights-efficiency.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'weights-efficiency.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Per-agent efficiency, EC, gross masses at 10 m/s'
set xlabel 'time (s)'
set ylabel 'efficiency of an active agent (mean of L and R)'
set yrange [0:1]
plot 'series/13.2kg.csv' using "t_s":"eff_agent" with lines lw 2 title '13.2 kg', \
     'series/23.2kg.csv' using "t_s":"eff_agent" with lines lw 2 title '23.2 kg', \
     'series/33.2kg.csv' using "t_s":"eff_agent" with lines lw 2 title '33.2 kg'
