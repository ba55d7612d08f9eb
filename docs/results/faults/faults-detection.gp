# made by `maptr experiment faults --out docs/results/faults`; run in this folder: gnuplot faults-detection.gp
set terminal pngcairo size 900,600 font ',11' noenhanced
set output 'faults-detection.png'
set datafile separator ','
set datafile columnheaders
set grid
set key outside right top
set title 'One broken agent: detection and isolation (EC, 16 agents, 30 kg)'
set ylabel 'simulated s after the fault'
set yrange [0:*]
set xtics rotate by -25 ('open' 0, 'short' 1, 'torque=0.5' 2, 'resistance=3' 3, 'stuck=12' 4, 'sensor=5' 5, 'erratic=2' 6, 'liar' 7, 'kill' 8)
set xrange [-0.5:9-0.5]
set key inside top left
set grid ytics
plot 'faults.csv' using (((column('agents')==1 && column('mass_kg')==30.0 && strcol('detection') eq 'on') || (column('agents')==1 && column('mass_kg')==30.0 && strcol('detection') eq 'plant')) ? column('mode_index') : NaN):'detect_s_max' with points pt 7 ps 1.5 title 'detected', \
     '' using (((column('agents')==1 && column('mass_kg')==30.0 && strcol('detection') eq 'on') || (column('agents')==1 && column('mass_kg')==30.0 && strcol('detection') eq 'plant')) ? column('mode_index') : NaN):'isolate_s_max' with points pt 6 ps 2 title 'isolated'
