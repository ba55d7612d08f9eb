#!/usr/bin/env bash
# Builds the fuzz targets with clang into build/fuzz/ and runs each for SECONDS.
#   tests/fuzz/run.sh SECONDS [TARGET]      e.g. tests/fuzz/run.sh 60 fuzz_scenario
#   tests/fuzz/run.sh --build               only build them (what `maptr fuzz` runs)
#   tests/fuzz/run.sh --seeds               rewrite the generated seed corpus (corpus/samples/)
# Each target starts from its committed seed corpus (tests/fuzz/corpus/<name>/, read only) with
# the options of tests/fuzz/<target>.flags; new inputs go to build/fuzz/corpus/<name>/, crashes
# to build/fuzz/crashes/<name>/. Prints, per target, the executions, exec/s and the crashes;
# exits 1 if any target crashed. `maptr fuzz` runs the same binaries for long runs.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="${MAPTR_FUZZ_BUILD_DIR:-$ROOT/build/fuzz}"
CXX_FUZZ="${MAPTR_FUZZ_CXX:-clang++-14}"
TARGETS=(fuzz_scenario fuzz_samples)

build() {
  cmake -S "$ROOT/tests/fuzz" -B "$BUILD" -DCMAKE_CXX_COMPILER="$CXX_FUZZ" -DCMAKE_BUILD_TYPE=None >/dev/null
  cmake --build "$BUILD" -j2 ${1:+--target "$1"} >/dev/null
}

case "${1:?usage: tests/fuzz/run.sh SECONDS [TARGET] | --build | --seeds}" in
  --build) build; exit 0 ;;
  --seeds)
    build make_sample_seeds
    rm -f "$ROOT"/tests/fuzz/corpus/samples/*
    mkdir -p "$ROOT/tests/fuzz/corpus/samples"
    "$BUILD/bin/make_sample_seeds" "$ROOT/tests/fuzz/corpus/samples"
    exit 0 ;;
esac
SECONDS_PER_TARGET="$1"
ONLY="${2:-}"
build "$ONLY"

status=0
for t in "${TARGETS[@]}"; do
  [ -n "$ONLY" ] && [ "$t" != "$ONLY" ] && continue
  name="${t#fuzz_}"
  seeds="$ROOT/tests/fuzz/corpus/$name"
  work="$BUILD/corpus/$name"
  crashes="$BUILD/crashes/$name"
  log="$BUILD/$t.log"
  mkdir -p "$work" "$crashes"
  read -r -a flags < "$ROOT/tests/fuzz/$t.flags"
  rc=0
  "$BUILD/bin/$t" "$work" "$seeds" -max_total_time="$SECONDS_PER_TARGET" "${flags[@]}" -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$crashes/" -print_final_stats=1 >"$log" 2>&1 || rc=$?
  execs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)"
  found="$(find "$crashes" -type f | wc -l)"
  echo "$t: ${execs:-?} executions in ${SECONDS_PER_TARGET} s (${rate:-?} exec/s), $found crash(es) in $crashes (log: $log)"
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then
    status=1
    grep -m1 -E "ERROR|SUMMARY|terminate" "$log" || true
  fi
done
exit "$status"
