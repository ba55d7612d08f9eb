#!/bin/sh
# A stalled run ends (ctest label `soak`): the plant of a running fleet is stopped (SIGSTOP)
# for good; with --stall-timeout 10 the launcher must end the run by itself with the status
# "aborted: stalled: ..." and leave no process of the fleet. The plant is stopped, so no tick
# can come: the test does not depend on the machine's speed.
# Usage: stall_plant.sh BIN_DIR SOURCE_DIR. Exit 0 when the run ended as stalled.
set -u
bin="$1"
src="$2"
dir=$(mktemp -d "${TMPDIR:-/tmp}/maptr-stall-XXXXXX")
out="$dir/run"
domain=$((100 + $$ % 120))
"$bin/maptr" run "$src/deploy/scenarios/soak.yaml" --realtime --duration 600 --stall-timeout 10 \
  --out "$out" --domain "$domain" --quiet > "$dir/run.log" 2>&1 &
launcher=$!
# json FILE EXPR: prints EXPR of the JSON document FILE, one value a line ("null" for a missing
# value), with python3 (installed by deploy/maptr); the document is bound to `j`.
json() {
  python3 -c 'import json, sys
j = json.load(open(sys.argv[1]))
v = eval(sys.argv[2], {"j": j})
for x in (v if isinstance(v, list) else [v]):
    print("null" if x is None else x)' "$1" "$2" 2>/dev/null
}
fail() {
  echo "stall_plant: $*"
  [ -f "$out/fleet.json" ] && for p in $(json "$out/fleet.json" '[p["pid"] for p in j["processes"]] + [j.get("discovery_server_pid")]'); do
    [ "$p" != null ] && kill -CONT "$p" 2>/dev/null && kill -KILL "$p" 2>/dev/null
  done
  kill -KILL "$launcher" 2>/dev/null
  cat "$dir/run.log"
  tail -20 "$out/logs/launcher.log" 2>/dev/null
  rm -rf "$dir"
  exit 1
}
# The run has started once the plant has matched every process and published ticks.
i=0
until [ -f "$out/fleet.json" ] && grep -q "matched" "$out/logs/plant.log" 2>/dev/null; do
  i=$((i + 1)); [ "$i" -gt 600 ] && fail "the fleet did not start within 60 s"
  sleep 0.1
done
sleep 2
plant=$(json "$out/fleet.json" '[p["pid"] for p in j["processes"] if p["name"] == "plant"]')
kill -STOP "$plant" || fail "no plant to stop"
# The launcher must end on its own: 10 s of stall, then the end of every process.
i=0
while kill -0 "$launcher" 2>/dev/null; do
  i=$((i + 1)); [ "$i" -gt 1200 ] && fail "the launcher did not end within 120 s of the stall"
  sleep 0.1
done
# A stalled run exits 1 (README); then its summary says why.
wait "$launcher"
code=$?
[ "$code" -eq 1 ] || fail "the launcher exited $code, not 1"
status=$(json "$out/summary.json" 'j["status"]')
case "$status" in
  "aborted: stalled: "*) ;;
  *) fail "status '$status', not 'aborted: stalled: ...'" ;;
esac
for p in $(json "$out/fleet.json" '[p["pid"] for p in j["processes"]]'); do
  kill -0 "$p" 2>/dev/null && fail "process $p of the fleet is still there"
done
echo "stall_plant: $status"
rm -rf "$dir"
exit 0
