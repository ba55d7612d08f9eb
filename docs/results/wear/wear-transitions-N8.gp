# made by `maptr experiment wear --out docs/results/wear`; run in this folder: gnuplot wear-transitions-N8.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'wear-transitions-N8.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Which agents drive, EC, N = 8 (1 step = T_ON = 100 s)'
set xlabel 'step (T_ON = 100 s)'
set ylabel 'agent'
set ytics ("L0" 0, "L1" 1, "L2" 2, "L3" 3, "R0" 4, "R1" 5, "R2" 6, "R3" 7) font ',8'
set cblabel 'fraction of the step spent driving'
set cbrange [0:1]
set palette defined (0 'white', 1 'dark-blue')
set xrange [-0.5:17.5]
set yrange [-0.5:7.5]
unset grid
set key off
plot 'transitions-N8.csv' using 1:3:5 with image
