#!/bin/sh
# A restarted process that cannot report ready (ctest label `soak`): the discovery server is
# paused at a fault gate before L1's restart, so the new L1 finds nobody. The restart's gate
# starts L1 once more after the gate's limit and then lets the plant go on; the later gate that
# resumes the discovery server is not held for L1, and the run ends. Everything acts at fault
# gates: no wall-clock race (whether L1 reports ready before the end is not checked).
# Usage: restart_unready.sh BIN_DIR SOURCE_DIR. Exit 0 on success.
set -u
bin="$1"
src="$2"
dir=$(mktemp -d "${TMPDIR:-/tmp}/maptr-unready-XXXXXX")
out="$dir/run"
domain=$((100 + $$ % 120))
timeout 280 "$bin/maptr" run "$src/deploy/scenarios/soak.yaml" --duration 20 --kill L1@5 --pause discovery@6 \
  --restart L1@8 --resume discovery@10 --out "$out" --domain "$domain" --quiet > "$dir/run.log" 2>&1
code=$?
fail() {
  echo "restart_unready: $*"
  cat "$dir/run.log"
  grep -v "info" "$out/logs/launcher.log" 2>/dev/null | tail -20
  rm -rf "$dir"
  exit 1
}
# The launcher's exit first: a run that failed may have no summary to read.
# (3: degraded. Killing L1 at 10 m/s leaves the left side weaker and the robot may leave its
# line, which the run reports; this test is about the restart of an unready process.)
[ "$code" -eq 0 ] || [ "$code" -eq 3 ] || fail "maptr run exited $code"
status=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["status"])' "$out/summary.json" 2>/dev/null)
case "$status" in
  ok | "degraded: "*) ;;
  *) fail "status '$status'" ;;
esac
log="$out/logs/launcher.log"
grep -q "restarted L1 (pid [0-9]*) did not report ready within .* started again" "$log" ||
  fail "L1 was not started again after the restart gate's limit"
# Only the restart's gate waited: one limit for the first start, one for the second.
[ "$(grep -c 'did not report ready within' "$log")" -eq 2 ] || fail "a gate other than the restart's waited"
echo "restart_unready: $status"
rm -rf "$dir"
exit 0
