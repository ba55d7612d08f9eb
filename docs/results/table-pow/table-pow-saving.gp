# made by `maptr experiment table-pow --out docs/results/table-pow`; run in this folder: gnuplot table-pow-saving.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'table-pow-saving.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Energy saving of EC over NO'
set xlabel 'gross mass (kg)'
set ylabel 'saving (%)'
plot 'table-pow.csv' using "gross_kg":"saving_pct" with linespoints lw 2 pt 7 title 'this model', \
     '' using "gross_kg":"saving_paper_pct" with points pt 6 ps 2 title 'paper'
