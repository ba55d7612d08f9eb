set terminal pngcairo size 1100,800
set output 'docs/bench/scale-30-128/scale.png'
set datafile separator ','
set key autotitle columnhead
set multiplot layout 2,2 title 'MAPTR scale-up on this machine (lock-step, EC mode)'
set logscale x 2
set grid
set xlabel 'agent processes N'
set ylabel 'seconds'
set title 'launch to all matched'
plot 'docs/bench/scale-30-128/scale.csv' using 1:3 with linespoints title 'discovery_s'
set ylabel 'simulated s per wall s'
set title 'real-time factor at 100 Hz'
plot 'docs/bench/scale-30-128/scale.csv' using 1:5 with linespoints title 'RTF', 1 with lines dt 2 title 'real time'
set ylabel 'CPU s per simulated s'
set title 'CPU cost'
plot 'docs/bench/scale-30-128/scale.csv' using 1:6 with linespoints title 'all processes'
set ylabel 'MB'
set title 'proportional memory (PSS) per agent process'
plot 'docs/bench/scale-30-128/scale.csv' using 1:($7/1024) with linespoints title 'median', '' using 1:($8/1024) with linespoints title 'max', 12 with lines dt 2 title 'target 12 MB'
unset multiplot
