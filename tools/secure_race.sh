#!/usr/bin/env bash
# The secure-discovery abort, measured: RUNS secure fleets with an uncertified participant on
# their domain and RUNS without, alternating, each under BURNERS busy loops, every process with
# the preload library that counts overlapping SecurityManager::match_builtin_endpoints calls
# (tools/secure_race/match_shim.cpp). Prints one line per fleet and a table per condition:
# fleets, ok, processes that ended during discovery, of them on the matched_reader_add
# assertion, processes started again before the run, median discovery time, overlapping calls.
#
#   tools/secure_race.sh [--runs N] [--burners K] [--serialise] [--keep DIR] [-- RUN OPTIONS]
#
# Defaults: 5 runs each, 2 burners, deploy/scenarios/paper.yaml --secure --duration 10.
# --serialise locks each call (what the upstream fix does). Needs a build (deploy/maptr build).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${MAPTR_BUILD_DIR:-$ROOT/build}"
runs=5
burners=2
serialise=0
keep=""
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --burners) burners="$2"; shift 2 ;;
    --serialise) serialise=1; shift ;;
    --keep) keep="$2"; shift 2 ;;
    --) shift; break ;;
    *) echo "secure_race: unknown option $1 (see the header of $0)" >&2; exit 2 ;;
  esac
done
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "secure_race: --runs $runs: a positive integer" >&2; exit 2; }
[[ "$burners" =~ ^[0-9]+$ ]] || { echo "secure_race: --burners $burners: an integer >= 0" >&2; exit 2; }
maptr="$BUILD/bin/maptr"
intruder="$BUILD/bin/maptr_secure_intruder"
shim="$BUILD/lib/libmaptr_match_shim.so"
for f in "$maptr" "$intruder" "$shim"; do
  [ -e "$f" ] || { echo "secure_race: $f missing: build first (deploy/maptr build)" >&2; exit 2; }
done
extra=("$@")
[ ${#extra[@]} -gt 0 ] || extra=(--duration 10)

work="${keep:-$(mktemp -d "${TMPDIR:-/tmp}/maptr-secure-race-XXXXXX")}"
mkdir -p "$work"
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  [ -n "$keep" ] || rm -rf "$work"
}
trap cleanup EXIT
for ((b = 0; b < burners; b++)); do
  sh -c 'while :; do :; done' &
  pids+=($!)
done

# run_one CONDITION DIR: one secure fleet, with the intruder when CONDITION is intruder.
run_one() {
  local cond="$1" dir="$2" launcher ipid=""
  env LD_PRELOAD="$shim" MATCH_SHIM_SERIALISE="$serialise" \
    "$maptr" run "$ROOT/deploy/scenarios/paper.yaml" --secure "${extra[@]}" --out "$dir" --quiet \
    >"$dir.out" 2>&1 &
  launcher=$!
  if [ "$cond" = intruder ]; then
    # It joins as soon as the domain is known: during the start storm.
    while kill -0 "$launcher" 2>/dev/null && [ ! -s "$dir/fleet.json" ]; do sleep 0.2; done
    if [ -s "$dir/fleet.json" ]; then
      read -r domain lease < <(python3 -c 'import json,sys; f=json.load(open(sys.argv[1])); print(f["domain"], f["lease_s"])' "$dir/fleet.json")
      "$intruder" --domain "$domain" --lease "$lease" >"$dir.intruder" 2>&1 &
      ipid=$!
    fi
  fi
  local rc=0
  wait "$launcher" || rc=$?
  if [ -n "$ipid" ]; then kill "$ipid" 2>/dev/null || true; wait "$ipid" 2>/dev/null || true; fi
  python3 - "$cond" "$dir" "$rc" <<'PY'
import glob, json, os, re, sys
cond, d, rc = sys.argv[1], sys.argv[2], int(sys.argv[3])
try:
    s = json.load(open(os.path.join(d, "summary.json")))
except Exception:
    s = {}
launcher = open(os.path.join(d, "logs", "launcher.log"), errors="replace").read() if os.path.exists(os.path.join(d, "logs", "launcher.log")) else ""
ended = len(re.findall(r"ended during discovery", launcher))
asserts = 0
calls = overlapping = 0
for log in glob.glob(os.path.join(d, "logs", "*.log")) + glob.glob(os.path.join(d, "logs", "*.stderr")):
    text = open(log, errors="replace").read()
    asserts += text.count("matched_reader_add")
    for m in re.finditer(r"match_shim: pid \d+ calls (\d+) overlapping (\d+)", text):
        calls += int(m.group(1)); overlapping += int(m.group(2))
row = {"condition": cond, "exit": rc, "status": s.get("status", "no summary"),
       "ended_in_discovery": ended, "assertion": asserts,
       "rematched": len(s.get("discovery_rematched", [])), "discovery_s": s.get("discovery_s"),
       "match_calls": calls, "overlapping": overlapping}
print(json.dumps(row))
PY
}

rows="$work/rows.jsonl"
: >"$rows"
echo "secure_race: $runs fleets each, $burners burners, serialise $serialise, run options: ${extra[*]}" >&2
for ((i = 1; i <= runs; i++)); do
  # Alternate which condition goes first, so that drift in the machine's load hits both.
  if ((i % 2)); then order=(plain intruder); else order=(intruder plain); fi
  for cond in "${order[@]}"; do
    line="$(run_one "$cond" "$work/$cond-$i")"
    echo "$line" >>"$rows"
    echo "secure_race: $i/$runs $line" >&2
  done
done
python3 - "$rows" <<'PY'
import json, statistics, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
print(f"{'condition':<10} {'fleets':>6} {'ok':>4} {'ended in discovery':>19} {'on the assertion':>17} "
      f"{'started again':>14} {'discovery median s':>19} {'match calls':>12} {'overlapping':>12}")
for cond in ("plain", "intruder"):
    r = [x for x in rows if x["condition"] == cond]
    if not r:
        continue
    disc = [x["discovery_s"] for x in r if x["discovery_s"] is not None]
    print(f"{cond:<10} {len(r):>6} {sum(x['status'] == 'ok' for x in r):>4} "
          f"{sum(x['ended_in_discovery'] for x in r):>19} {sum(x['assertion'] > 0 for x in r):>17} "
          f"{sum(x['rematched'] for x in r):>14} {statistics.median(disc) if disc else float('nan'):>19.1f} "
          f"{sum(x['match_calls'] for x in r):>12} {sum(x['overlapping'] for x in r):>12}")
PY
