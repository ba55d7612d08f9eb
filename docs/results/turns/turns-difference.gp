# made by `maptr experiment turns --out docs/results/turns`; run in this folder: gnuplot turns-difference.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'turns-difference.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'EC minus NO on the warehouse loop: energy drawn and active agents'
set xlabel 'time (s)'
set ylabel 'E_EC - E_NO (J)'
set y2label 'active agents (L + R)'
set y2range [0:17]
set ytics nomirror
set y2tics
set key inside right bottom
plot 'series/loop-difference.csv' using "t_s":"dE_J" with lines lw 2 lc rgb '#c0392b' title 'E_EC - E_NO', \
     '' using "t_s":"active_EC" with steps lw 1 lc rgb '#008837' axes x1y2 title 'active EC (right axis)', \
     '' using "t_s":"active_NO" with steps lw 1 dt 2 lc rgb 'black' axes x1y2 title 'active NO (right axis)'
