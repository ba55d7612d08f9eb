#!/bin/sh
# The real-time factor of a fleet with and without `maptr top` watching it (the full-screen view
# in a detached 80x24 tmux session), alternating off/on runs in one sitting; prints one line per
# run (mode, pair, real-time factor, trace sha256) and the median of each mode.
# usage: deploy/bench/top_watch.sh [PAIRS] [AGENTS] [DURATION_S] [DOMAIN] [OUT]
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
for i in $(seq 1 "$pairs"); do
  for mode in off on; do
    dir=$out/$mode-$i
    "$bin" run --agents "$agents" --duration "$duration" --out "$dir" --domain "$domain" --quiet >"$dir.log" 2>&1 &
    pid=$!
    if [ "$mode" = on ]; then
      while [ ! -f "$dir/fleet.json" ]; do sleep 0.1; done
      tmux -L "$server" new-session -d -x 80 -y 24 "$bin top --run $dir"
    fi
    wait "$pid" || true
    [ "$mode" = on ] && tmux -L "$server" kill-server 2>/dev/null || true
    echo "$mode $i $(jq -r '.real_time_factor' "$dir/summary.json") $(jq -r '.trace_sha256' "$dir/summary.json")" |
      tee -a "$out/rtf.txt"
  done
done
for mode in off on; do
  grep "^$mode " "$out/rtf.txt" | awk '{print $3}' | sort -g |
    awk -v m="$mode" '{v[NR]=$1} END {printf "%s: median real-time factor %.3f over %d runs\n", m, (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2), NR}'
done
# The ratio on/off of each pair (the runs of a pair ran back to back, under the same load).
awk '$1 == "off" {off[$2] = $3} $1 == "on" {print $3 / off[$2]}' "$out/rtf.txt" | sort -g |
  awk '{v[NR]=$1} END {printf "on/off per pair: median %.3f (min %.3f, max %.3f) over %d pairs\n", (NR%2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2), v[1], v[NR], NR}'
