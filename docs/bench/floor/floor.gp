# made by `maptr bench floor`
set terminal pngcairo size 1400,600 noenhanced
set output 'floor.png'
set datafile separator ','
set multiplot layout 1,2 title 'IPC floor with a working set per process (pipes, no DDS)'
set logscale x 2
set grid
set xlabel 'processes W = N + 3'
set key top left
set ylabel 'CPU µs per worker and round'
set title 'CPU per worker and round'
plot 'floor.csv' using "workers":(column("touch_kb") == 0 ? column("cpu_us_per_worker_round") : NaN) with linespoints title '0 KiB', 'floor.csv' using "workers":(column("touch_kb") == 128 ? column("cpu_us_per_worker_round") : NaN) with linespoints title '128 KiB', 'floor.csv' using "workers":(column("touch_kb") == 512 ? column("cpu_us_per_worker_round") : NaN) with linespoints title '512 KiB'
set ylabel 'µs'
set title 'round median'
set logscale y
plot 'floor.csv' using "workers":(column("touch_kb") == 0 ? column("median_us") : NaN) with linespoints title '0 KiB', 'floor.csv' using "workers":(column("touch_kb") == 128 ? column("median_us") : NaN) with linespoints title '128 KiB', 'floor.csv' using "workers":(column("touch_kb") == 512 ? column("median_us") : NaN) with linespoints title '512 KiB'
unset multiplot
