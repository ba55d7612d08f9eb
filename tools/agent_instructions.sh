#!/usr/bin/env bash
# Instructions of one agent's tick path, counted by callgrind: repeatable for the same build and
# scenario whatever else the machine does (a benchmark of the code, not of the machine).
#
#   tools/agent_instructions.sh [--agents N] [--mode ec|all] [--duration S] [--bin DIR] [--out DIR]
#                               [--cold-cache]
#
# Runs `maptr run` with agent L3 started by this script under
# `valgrind --tool=callgrind`, collecting only inside Fast DDS's receive callback
# (ReceiverResource::OnDataReceived: the tick's reception, the agent's core, its answer's
# write), and prints the instructions per tick of that path and of its main parts. Compare two
# builds with --bin. --cold-cache also simulates a cache of 64 KiB (L1 32 KiB), so small that
# nothing stays from one tick to the next, and prints the 64-byte lines of code and data one
# tick touches: what a tick fetches from memory when the other processes have evicted the
# agent's caches. Needs valgrind (Debian: valgrind).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
AGENTS=16 MODE=all DURATION=10 BIN="$ROOT/build/bin" OUT="" CACHE=()
while [ $# -gt 0 ]; do
  case "$1" in
    --agents) AGENTS="$2"; shift 2 ;;
    --mode) MODE="$2"; shift 2 ;;
    --duration) DURATION="$2"; shift 2 ;;
    --bin) BIN="$2"; shift 2 ;;
    --out) OUT="$2"; shift 2 ;;
    --cold-cache) CACHE=(--cache-sim=yes --I1=32768,8,64 --D1=32768,8,64 --LL=65536,8,64); shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "agent_instructions: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
command -v valgrind >/dev/null || { echo "agent_instructions: needs valgrind" >&2; exit 2; }
[ -x "$BIN/maptr" ] || { echo "agent_instructions: no $BIN/maptr (build first: deploy/maptr build)" >&2; exit 2; }
TMP=""
if [ -z "$OUT" ]; then TMP="$(mktemp -d)"; OUT="$TMP/run"; fi
LAUNCHER=""
cleanup() {
  if [ -n "$LAUNCHER" ] && kill -0 "$LAUNCHER" 2>/dev/null; then kill -INT "$LAUNCHER"; wait "$LAUNCHER" || true; fi
  if [ -n "$TMP" ]; then rm -rf "$TMP"; fi
}
trap cleanup EXIT

"$BIN/maptr" run --agents "$AGENTS" --mode "$MODE" --duration "$DURATION" --external L3 --out "$OUT" --quiet \
  > "$OUT.launcher.txt" 2>&1 &
LAUNCHER=$!
# The launcher logs the command that starts L3 (its environment, then the binary and arguments).
CMD=""
for _ in $(seq 1 300); do
  CMD="$(grep -h 'external L3:' "$OUT"/logs/*.log 2>/dev/null | sed 's/.*external L3: //' || true)"
  [ -n "$CMD" ] && break
  kill -0 "$LAUNCHER" 2>/dev/null || { cat "$OUT.launcher.txt" >&2; exit 1; }
  sleep 0.2
done
[ -n "$CMD" ] || { echo "agent_instructions: the launcher printed no command for L3" >&2; exit 1; }
ENVS="${CMD%% /*}"
PROG="/${CMD#* /}"
CG="$OUT.callgrind.out"
# shellcheck disable=SC2086  # the environment and the arguments are words
env $ENVS valgrind --tool=callgrind --collect-atstart=no "${CACHE[@]}" \
  --toggle-collect='eprosima::fastrtps::rtps::ReceiverResource::OnDataReceived*' \
  --callgrind-out-file="$CG" $PROG > "$OUT.valgrind.txt" 2>&1
wait "$LAUNCHER" && LAUNCHER="" || { LAUNCHER=""; echo "agent_instructions: the run did not end ok" >&2; cat "$OUT.launcher.txt" >&2; exit 1; }
TICKS=$(($(wc -l < "$OUT/trace.csv") - 1))
echo "agent L3 of $AGENTS agents, mode $MODE, $TICKS ticks ($(grep -o 'sha256 .*' "$OUT.launcher.txt" | cut -c1-20)...)"
callgrind_annotate --inclusive=yes "$CG" 2>/dev/null | awk -v ticks="$TICKS" '
  function part(label, pattern) {
    if ($0 ~ pattern && !(label in seen)) { gsub(",", "", $1); seen[label] = $1 }
  }
  { part("receive path (the whole callback)", "ReceiverResource::OnDataReceived");
    part("  take: DataReader::take_next_sample", "DataReader::take_next_sample");
    part("    deserialize the tick", "PlantTickPubSubType::deserialize");
    part("  answer: DataWriter::write", "DataWriterImpl::write\\(");
    part("    shared-memory send", "SharedMemTransport::send\\(unsigned char");
    part("  core: AgentCore::step", "AgentCore::step") }
  END {
    n = split("receive path (the whole callback)|  take: DataReader::take_next_sample|    deserialize the tick|  answer: DataWriter::write|    shared-memory send|  core: AgentCore::step", order, "|")
    for (i = 1; i <= n; ++i) if (order[i] in seen) printf "%-40s %9.0f instructions / tick\n", order[i], seen[order[i]] / ticks
  }'
if [ ${#CACHE[@]} -gt 0 ]; then
  # PROGRAM TOTALS of the collected path: Ir Dr Dw I1mr D1mr D1mw ILmr DLmr DLmw.
  callgrind_annotate "$CG" 2>/dev/null | awk -v ticks="$TICKS" '/PROGRAM TOTALS/ {
      for (i = 1; i <= NF; ++i) gsub(",", "", $i)
      printf "%-40s %9.0f lines / tick (%.0f KiB)\n", "code lines fetched (64-KiB cache)", $7 / ticks, $7 / ticks / 16
      printf "%-40s %9.0f lines / tick (%.0f KiB)\n", "data lines fetched (64-KiB cache)", ($8 + $9) / ticks, ($8 + $9) / ticks / 16
    }'
fi
