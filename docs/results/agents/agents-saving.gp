# made by `maptr experiment agents --out docs/results/agents`; run in this folder: gnuplot agents-saving.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'agents-saving.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Energy advantage of EC over NO vs number of agents (10 m/s, 120 s)'
set xlabel 'agents N'
set ylabel 'saving (%)'
set logscale x 2
set xrange [6:160]
set yrange [0:*]
plot 'agents.csv' using "agents":(strcol("series") eq '0.8 kg/agent' ? column("saving_pct") : NaN) with linespoints lw 2 pt 5 title '0.8 kg/agent', \
     'agents.csv' using "agents":(strcol("series") eq '1.5 kg/agent' ? column("saving_pct") : NaN) with linespoints lw 2 pt 7 title '1.5 kg/agent', \
     'agents.csv' using "agents":(strcol("series") eq '2.2 kg/agent' ? column("saving_pct") : NaN) with linespoints lw 2 pt 9 title '2.2 kg/agent', \
     'agents.csv' using "agents":(strcol("series") eq '13.2 kg for every N' ? column("saving_pct") : NaN) with linespoints lw 2 pt 11 title '13.2 kg for every N'
