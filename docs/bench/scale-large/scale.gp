# made by `maptr bench scale`; redraw with `maptr bench scale --replot --out DIR`
set terminal pngcairo size 1100,800 noenhanced
set output 'scale.png'
set datafile separator ','
set key autotitle columnhead
set multiplot layout 2,2 title 'MAPTR scale-up on this machine (lock-step, EC mode)'
set logscale x 2
set grid
set xlabel 'agent processes N'
set ylabel 'seconds'
set title 'launch to all matched'
plot 'scale.csv' using 1:3 with linespoints title 'all processes matched'
set ylabel 'simulated s per wall s'
set title 'real-time factor at 100 Hz (log scale)'
set logscale y
plot 'scale.csv' using 1:5 with linespoints title 'RTF', 1 with lines dt 2 title 'real time'
set ylabel 'CPU s per simulated s'
set title 'CPU cost (log scale)'
plot 'scale.csv' using 1:6 with linespoints title 'all processes'
unset logscale y
set ylabel 'MB'
set title 'proportional memory (PSS) per agent process'
set yrange [0:14]
plot 'scale.csv' using 1:($7/1024) with linespoints title 'median', '' using 1:($8/1024) with linespoints title 'max', 12 with lines dt 2 title 'target 12 MB'
unset multiplot
