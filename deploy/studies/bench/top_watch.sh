#!/bin/sh
# The real-time factor of a fleet with and without `maptr top` watching it (the full-screen view
# in a detached 80x24 tmux session), alternating off/on runs in one sitting. Prints one line per
# run (mode, pair, real-time factor, trace sha256, status, CPU seconds of `top`), then the median
# of each mode over the runs that ended ok and the median of the on/off ratio over complete pairs.
# usage: deploy/studies/bench/top_watch.sh [PAIRS] [AGENTS] [DURATION_S] [DOMAIN] [OUT]
set -eu
pairs=${1:-5}
agents=${2:-16}
duration=${3:-60}
domain=${4:-0}
out=${5:-/tmp/maptr-top-bench}
bin=$(dirname "$0")/../../build/bin/maptr
server=maptr-top-bench-$$
rm -rf "$out"
mkdir -p "$out"
median='{v[NR]=$1} END {if (NR) printf "%.3f", (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2); else printf "-"}'
for i in $(seq 1 "$pairs"); do
  for mode in off on; do
    dir=$out/$mode-$i
    "$bin" run --agents "$agents" --duration "$duration" --out "$dir" --domain "$domain" --quiet >"$dir.log" 2>&1 &
    pid=$!
    if [ "$mode" = on ]; then
      while [ ! -f "$dir/fleet.json" ]; do sleep 0.1; done
      tmux -L "$server" new-session -d -x 80 -y 24 "exec $bin top --run $dir"
    fi
    wait "$pid" || true
    cpu=-
    if [ "$mode" = on ]; then
      top_pid=$(tmux -L "$server" list-panes -F '#{pane_pid}' 2>/dev/null || true)
      [ -n "$top_pid" ] && cpu=$(awk -v hz="$(getconf CLK_TCK)" '{printf "%.2f", ($14 + $15) / hz}' "/proc/$top_pid/stat")
      tmux -L "$server" kill-server 2>/dev/null || true
    fi
    echo "$mode $i $(python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); print(s["real_time_factor"], s["trace_sha256"], s["status"].split(":")[0], sep="\t")' "$dir/summary.json") $cpu" |
      tee -a "$out/rtf.txt"
  done
done
for mode in off on; do
  echo "$mode: median real-time factor $(awk -v m="$mode" '$1 == m && $5 == "ok" {print $3}' "$out/rtf.txt" | sort -g | awk "$median")" \
    "over $(awk -v m="$mode" '$1 == m && $5 == "ok"' "$out/rtf.txt" | wc -l) runs that ended ok"
done
# The ratio on/off of each pair (its runs ran back to back, under the same load).
echo "on/off per pair: median $(awk '$5 != "ok" {bad[$2] = 1} $1 == "off" {off[$2] = $3} $1 == "on" {on[$2] = $3}
  END {for (p in on) if (!bad[p]) print on[p] / off[p]}' "$out/rtf.txt" | sort -g | awk "$median")"
