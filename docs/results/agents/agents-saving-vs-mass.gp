# made by `maptr experiment agents --out docs/results/agents`; run in this folder: gnuplot agents-saving-vs-mass.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'agents-saving-vs-mass.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Energy advantage of EC over NO vs gross mass, per number of agents (10 m/s, 120 s)'
set xlabel 'gross mass (kg)'
set ylabel 'saving (%)'
set logscale x 2
set yrange [0:*]
plot 'agents.csv' every 5::0 using "gross_kg":"saving_pct" smooth unique with linespoints lw 2 pt 5 title 'N = 8', \
     'agents.csv' every 5::1 using "gross_kg":"saving_pct" smooth unique with linespoints lw 2 pt 7 title 'N = 16', \
     'agents.csv' every 5::2 using "gross_kg":"saving_pct" smooth unique with linespoints lw 2 pt 9 title 'N = 32', \
     'agents.csv' every 5::3 using "gross_kg":"saving_pct" smooth unique with linespoints lw 2 pt 11 title 'N = 64', \
     'agents.csv' every 5::4 using "gross_kg":"saving_pct" smooth unique with linespoints lw 2 pt 13 title 'N = 128'
