# made by `maptr experiment table-pow --out docs/results/table-pow`; run in this folder: gnuplot table-pow-active.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'table-pow-active.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Active agents chosen by EC (L + R)'
set xlabel 'gross mass (kg)'
set ylabel 'active agents'
set yrange [0:17]
plot 'table-pow.csv' using "gross_kg":"active_EC_end" with linespoints lw 2 pt 7 title 'this model (end)', \
     '' using "gross_kg":"active_EC_mean" with linespoints lw 1 dt 2 pt 1 title 'this model (mean, 2nd half)', \
     '' using "gross_kg":"active_paper" with points pt 6 ps 2 title 'paper'
