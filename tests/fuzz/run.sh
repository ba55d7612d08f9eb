#!/usr/bin/env bash
# Builds the fuzz targets with clang into build/fuzz/ and runs each for SECONDS.
#   tests/fuzz/run.sh SECONDS [TARGET]      e.g. tests/fuzz/run.sh 60 fuzz_scenario
# Each target starts from its committed seed corpus (tests/fuzz/corpus/<name>/, read only); new
# inputs go to build/fuzz/corpus/<name>/, crashes to build/fuzz/crashes/<name>/.
# Prints, per target, the executions and the crashes; exits 1 if any target crashed.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
SECONDS_PER_TARGET="${1:?usage: tests/fuzz/run.sh SECONDS [TARGET]}"
ONLY="${2:-}"
BUILD="${MAPTR_FUZZ_BUILD_DIR:-$ROOT/build/fuzz}"
CXX_FUZZ="${MAPTR_FUZZ_CXX:-clang++-14}"
TARGETS=(fuzz_scenario)

cmake -S "$ROOT/tests/fuzz" -B "$BUILD" -DCMAKE_CXX_COMPILER="$CXX_FUZZ" -DCMAKE_BUILD_TYPE=None >/dev/null
cmake --build "$BUILD" -j2 ${ONLY:+--target "$ONLY"} >/dev/null

status=0
for t in "${TARGETS[@]}"; do
  [ -n "$ONLY" ] && [ "$t" != "$ONLY" ] && continue
  name="${t#fuzz_}"
  seeds="$ROOT/tests/fuzz/corpus/$name"
  work="$BUILD/corpus/$name"
  crashes="$BUILD/crashes/$name"
  log="$BUILD/$t.log"
  mkdir -p "$work" "$crashes"
  rc=0
  "$BUILD/bin/$t" "$work" "$seeds" -max_total_time="$SECONDS_PER_TARGET" -max_len=4096 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$crashes/" -print_final_stats=1 >"$log" 2>&1 || rc=$?
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  found="$(find "$crashes" -type f | wc -l)"
  echo "$t: ${execs:-?} executions in ${SECONDS_PER_TARGET} s, $found crash(es) in $crashes (log: $log)"
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then
    status=1
    grep -m1 -E "ERROR|SUMMARY|terminate" "$log" || true
  fi
done
exit "$status"
