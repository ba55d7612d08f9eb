# made by `maptr experiment failures --out docs/results/failures`; run in this folder: gnuplot failures-speed.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'failures-speed.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Speed tracking vs killed agents per side (EC, 16 agents, 23.2 kg, 10 m/s)'
set xlabel 'agents killed per side at t = 20 s'
set ylabel 'max speed error after the kill (%)'
set y2label 'final speed (m/s)'
set ytics nomirror
set y2tics
set xtics 1
set yrange [0:*]
set y2range [0:12.0]
set arrow from 4, graph 0 to 4, graph 1 nohead dt 2
set label 'tolerance' at 4, graph 0.95 offset 0.5,0
plot 'failures.csv' using "killed_per_side":"max_speed_error_pct" with linespoints lw 2 pt 7 axes x1y1 title 'max speed error', \
     '' using "killed_per_side":"final_speed_mps" with linespoints lw 2 pt 5 axes x1y2 title 'final speed'
