#!/bin/sh
# A short soak (ctest label `soak`): a few fleets of 8 agents with about 20 seeded faults.
# Usage: soak_short.sh BIN_DIR. Exit status: maptr soak's (0 when every check passed).
set -u
bin="$1"
dir=$(mktemp -d "${TMPDIR:-/tmp}/maptr-soak-XXXXXX")
domain=$((100 + $$ % 120))
"$bin/maptr" soak --seed 1 --faults 20 --agents 8 --out "$dir/soak" --domain "$domain"
code=$?
if [ "$code" -ne 0 ]; then
  cat "$dir/soak/soak.json" 2>/dev/null | head -c 20000
fi
rm -rf "$dir"
exit "$code"
