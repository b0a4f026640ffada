#!/usr/bin/env bash
# Messages of issue 31: `batch -q` prints no line per scene (only the table it reports, and a
# failed scene's line); `batch` and `sweep run` (and `sweep sbatch`) take their output folder as
# both -o and --out-dir, the old spellings kept.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

BOX="$SCENES/sliding_box.xml"
CHAIN="$SCENES/chain.xml"

check "batch -q: no progress line per scene; the table stays"
expect_status 0 "$SIMBOB" batch "$BOX" "$CHAIN" --duration 0.1 --out-dir q -q
if grep -q '^\[[0-9]*/[0-9]*\]' "$LAST_OUT" "$LAST_ERR"; then fail "batch -q printed progress lines: $(cat "$LAST_OUT")"; fi
expect_match "the table" "$LAST_OUT" "^2 of 2 scenes ok"
[[ ! -s "$LAST_ERR" ]] || fail "batch -q wrote to stderr: $(cat "$LAST_ERR")"

check "batch without -q: a line per scene"
expect_status 0 "$SIMBOB" batch "$BOX" "$CHAIN" --duration 0.1 --out-dir loud
[[ $(grep -c '^\[[0-9]/2\] ok ' "$LAST_OUT") -eq 2 ]] || fail "no progress lines: $(cat "$LAST_OUT")"

check "batch -q: a failed scene still has its line"
printf '<Simulation><ComponentList><Nope/></ComponentList></Simulation>\n' >bad.xml
expect_status 1 "$SIMBOB" batch "$BOX" bad.xml --duration 0.1 --out-dir qf -q
[[ $(grep -c '^\[[0-9]/2\] ' "$LAST_OUT") -eq 1 ]] || fail "expected one line, for bad.xml: $(cat "$LAST_OUT")"
expect_match "the failed scene's line" "$LAST_OUT" '^\[[0-9]/2\] failed  bad\.xml'

check "batch -o DIR writes where --out-dir DIR does"
expect_status 0 "$SIMBOB" batch "$BOX" --duration 0.1 -o short -q
expect_status 0 "$SIMBOB" batch "$BOX" --duration 0.1 --out-dir long -q
expect_same_file short/sliding_box.csv long/sliding_box.csv

check "sweep run --out-dir DIR writes where -o DIR does"
cat >s.sweep.json <<JSON
{"scene": "$BOX", "duration": 0.1, "vary": [{"param": "Crate.Material.Friction", "values": [0.3]}],
 "metrics": [{"name": "x", "body": "Crate", "value": "x", "stat": "final"}]}
JSON
expect_status 0 "$SIMBOB" sweep plan s.sweep.json -o s.jsonl
expect_status 0 "$SIMBOB" sweep run s.jsonl -j 1 --out-dir sw_long -q
expect_status 0 "$SIMBOB" sweep run s.jsonl -j 1 -o sw_short -q
expect_same_file sw_long/case-0000/trajectory.csv sw_short/case-0000/trajectory.csv
expect_status 0 "$SIMBOB" sweep sbatch s.jsonl --out-dir sb -q
expect_file sb/sweep.sbatch
say "ok"
