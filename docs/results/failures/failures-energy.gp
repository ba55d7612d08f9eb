# made by `maptr experiment failures --out docs/results/failures`; run in this folder: gnuplot failures-energy.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'failures-energy.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Energy vs killed agents per side (EC, 60 s)'
set xlabel 'agents killed per side'
set ylabel 'energy drawn (kJ)'
set xtics 1
plot 'failures.csv' using "killed_per_side":"energy_kJ" with linespoints lw 2 pt 7 title 'energy'
