# made by `maptr experiment voltages --out docs/results/voltages`; run in this folder: gnuplot voltages-efficiency.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'voltages-efficiency.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Per-agent efficiency, EC, 14.4 kg at 8 m/s, several supply voltages'
set xlabel 'time (s)'
set ylabel 'efficiency of an active agent (mean of L and R)'
set yrange [0:1]
plot 'series/12V.csv' using "t_s":"eff_agent" with lines lw 2 title '12 V', \
     'series/16V.csv' using "t_s":"eff_agent" with lines lw 2 title '16 V', \
     'series/20V.csv' using "t_s":"eff_agent" with lines lw 2 title '20 V', \
     'series/23.4V.csv' using "t_s":"eff_agent" with lines lw 2 title '23.4 V'
