# made by `maptr experiment wear --out docs/results/wear`; run in this folder: gnuplot wear-transitions-N32.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'wear-transitions-N32.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Which agents drive, EC, N = 32 (1 step = T_ON = 100 s)'
set xlabel 'step (T_ON = 100 s)'
set ylabel 'agent'
set ytics ("L0" 0, "L1" 1, "L2" 2, "L3" 3, "L4" 4, "L5" 5, "L6" 6, "L7" 7, "L8" 8, "L9" 9, "L10" 10, "L11" 11, "L12" 12, "L13" 13, "L14" 14, "L15" 15, "R0" 16, "R1" 17, "R2" 18, "R3" 19, "R4" 20, "R5" 21, "R6" 22, "R7" 23, "R8" 24, "R9" 25, "R10" 26, "R11" 27, "R12" 28, "R13" 29, "R14" 30, "R15" 31) font ',8'
set cblabel 'fraction of the step spent driving'
set cbrange [0:1]
set palette defined (0 'white', 1 'dark-blue')
set xrange [-0.5:17.5]
set yrange [-0.5:31.5]
unset grid
set key off
plot 'transitions-N32.csv' using 1:3:5 with image
