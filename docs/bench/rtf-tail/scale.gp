# made by `maptr bench scale`; redraw with `maptr bench scale --replot --out DIR`
set terminal pngcairo size 1500,900 noenhanced
set output 'scale.png'
set datafile separator ','
set multiplot layout 2,3 title 'MAPTR scale-up on this machine (lock-step, one host)'
set logscale x 2
set grid
set xlabel 'agent processes N'
set key top left
set ylabel 'seconds'
set title 'launch to all matched'
plot 'scale.csv' using "agents":(strcol("mode") eq "ec" && column("hosts") == 1 ? column("discovery_s") : NaN) with linespoints title 'mode ec', 'scale.csv' using "agents":(strcol("mode") eq "all" && column("hosts") == 1 ? column("discovery_s") : NaN) with linespoints title 'mode all'
set ylabel 'simulated s per wall s'
set title 'real-time factor at 100 Hz (log scale)'
set logscale y
set key top right
plot 'scale.csv' using "agents":(strcol("mode") eq "ec" && column("hosts") == 1 ? column("real_time_factor") : NaN) with linespoints title 'mode ec', 'scale.csv' using "agents":(strcol("mode") eq "all" && column("hosts") == 1 ? column("real_time_factor") : NaN) with linespoints title 'mode all', 1 with lines dt 2 title 'real time'
set ylabel 'fleet tick / floor tick'
set title 'tick against the IPC floor (same run)'
unset logscale y
set key top left
plot 'scale.csv' using "agents":(strcol("mode") eq "ec" && column("hosts") == 1 ? column("x_floor") : NaN) with linespoints title 'mode ec', 'scale.csv' using "agents":(strcol("mode") eq "all" && column("hosts") == 1 ? column("x_floor") : NaN) with linespoints title 'mode all'
set ylabel 'CPU s per simulated s'
set title 'CPU cost (log scale)'
set logscale y
plot 'scale.csv' using "agents":(strcol("mode") eq "ec" && column("hosts") == 1 ? column("cpu_s_per_sim_s") : NaN) with linespoints title 'mode ec', 'scale.csv' using "agents":(strcol("mode") eq "all" && column("hosts") == 1 ? column("cpu_s_per_sim_s") : NaN) with linespoints title 'mode all'
unset logscale y
set ylabel 'ms'
set title 'plant tick, median'
plot 'scale.csv' using "agents":(strcol("mode") eq "ec" && column("hosts") == 1 ? column("tick_median_us")/1000 : NaN) with linespoints title 'mode ec', 'scale.csv' using "agents":(strcol("mode") eq "all" && column("hosts") == 1 ? column("tick_median_us")/1000 : NaN) with linespoints title 'mode all'
set ylabel 'MB'
set title 'PSS per agent process, median'
set yrange [0:*]
plot 'scale.csv' using "agents":(strcol("mode") eq "ec" && column("hosts") == 1 ? column("pss_agent_median_kB")/1024 : NaN) with linespoints title 'mode ec', 'scale.csv' using "agents":(strcol("mode") eq "all" && column("hosts") == 1 ? column("pss_agent_median_kB")/1024 : NaN) with linespoints title 'mode all', 8.000000 with lines dt 2 title 'target'
unset multiplot
