# made by `maptr experiment table-pow --out docs/results/table-pow`; run in this folder: gnuplot table-pow-energy.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'table-pow-energy.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'Energy over the run, NO vs EC (16 agents, 20 m/s, 1800 s)'
set xlabel 'gross mass (kg)'
set ylabel 'energy drawn (kJ)'
plot 'table-pow.csv' using "gross_kg":"E_NO_kJ" with linespoints lw 2 pt 7 title 'NO (this model)', \
     '' using "gross_kg":"E_EC_kJ" with linespoints lw 2 pt 5 title 'EC (this model)', \
     '' using "gross_kg":"E_NO_paper_kJ" with points pt 6 ps 2 title 'NO (paper)', \
     '' using "gross_kg":"E_EC_paper_kJ" with points pt 4 ps 2 title 'EC (paper)'
