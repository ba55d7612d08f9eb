#!/bin/sh
# A soak with a property made to break (ctest label `soak`): `--property max_dead_per_side:0`
# fails the first fleet that kills an agent; the fleet leaves repro.yaml, the JUnit file has a
# failing case for it, and `maptr run repro.yaml` runs the same fleet again (the same
# trace_sha256) which `maptr check` finds broken at the same tick. A bad --property is exit 2.
# Usage: soak_repro.sh BIN_DIR. Exit status 0 when all of that holds.
set -u
bin="$1"
dir=$(mktemp -d "${TMPDIR:-/tmp}/maptr-soak-repro-XXXXXX")
trap 'rm -rf "$dir"' EXIT
domain=$((100 + $$ % 120))
fail() { echo "soak_repro: $*"; exit 1; }

"$bin/maptr" soak --seed 3 --faults 4 --agents 8 --out "$dir/soak" --domain "$domain" --property nope:1 \
  > "$dir/bad.log" 2>&1
code=$?
[ "$code" -eq 2 ] || fail "a bad --property exited $code, not 2: $(cat "$dir/bad.log")"
grep -q -- "--property 'nope:1': no property 'nope'" "$dir/bad.log" || fail "no clear error: $(cat "$dir/bad.log")"

"$bin/maptr" soak --seed 3 --faults 4 --agents 8 --out "$dir/soak" --domain "$domain" \
  --property max_dead_per_side:0 --junit "$dir/soak.xml" > "$dir/soak.log" 2>&1
code=$?
cat "$dir/soak.log"
[ "$code" -eq 1 ] || fail "the soak exited $code, not 1"
repro="$dir/soak/fleet-0/repro.yaml"
[ -f "$repro" ] || fail "no $repro"
line=$(grep -o 'max_dead_per_side:0 at tick [0-9]*' "$dir/soak.log" | head -n 1)
[ -n "$line" ] || fail "the soak did not say where the property broke"
tick=${line##* }
python3 - "$dir/soak.xml" <<'PY' || fail "the JUnit file is not what it should be"
import sys, xml.etree.ElementTree as E
s = E.parse(sys.argv[1]).getroot()
c = s.findall('testcase')
assert s.tag == 'testsuite' and int(s.attrib['tests']) == len(c) >= 1, s.attrib
f = c[0].find('failure')
assert c[0].attrib['name'] == 'fleet-0' and f is not None and 'max_dead_per_side:0' in f.attrib['message']
PY

"$bin/maptr" run "$repro" --out "$dir/again" --domain "$domain" --quiet > "$dir/again.log" 2>&1
sha() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["trace_sha256"])' "$1"; }
first=$(sha "$dir/soak/fleet-0/summary.json")
again=$(sha "$dir/again/summary.json")
[ "$first" = "$again" ] || fail "repro.yaml ran another fleet: trace_sha256 $again, the soak's $first"
"$bin/maptr" check "$dir/again" --property max_dead_per_side:0 > "$dir/check.log" 2>&1
code=$?
cat "$dir/check.log"
[ "$code" -eq 1 ] || fail "maptr check of the reproduced run exited $code, not 1"
grep -q "BROKE  tick $tick " "$dir/check.log" || fail "the reproduced run did not break at tick $tick"
echo "soak_repro: fleet-0 breaks max_dead_per_side:0 at tick $tick again, trace_sha256 $first"
