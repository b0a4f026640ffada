#!/usr/bin/env bash
# simbob run --check-determinism: two runs in one process agree, the summary says so, and the
# reproducibility facts are recorded.
set -euo pipefail
simbob=$1
repo=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
for s in box_stack chain; do
  "$simbob" run "$repo/scenes/$s.xml" --duration 2 --out "$tmp/$s.csv" --check-determinism --json > "$tmp/$s.out"
  python3 - "$tmp/$s.out" <<'PY' || fail "$s: summary lacks the determinism check or reproducibility facts"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["determinism_check"] == "identical", s.get("determinism_check")
r = s["reproducibility"]
assert "ODE_double_precision" in r["physics"], r
assert r["precision"] == "double" and r["fp_contract"] == "off", r
assert isinstance(r["cpu_features"], list) and r["compiler"], r
import re
assert re.fullmatch(r"0\.16\.\d+", r["ode_version"]), r
assert re.fullmatch(r"(gcc|clang) \d.*", r["compiler"]), r
assert re.fullmatch(r"glibc \d+\.\d+", r["libc"]), r
PY
  # The checked run writes the same bytes as a plain run.
  "$simbob" run "$repo/scenes/$s.xml" --duration 2 --out "$tmp/$s.plain.csv" --quiet
  cmp "$tmp/$s.csv" "$tmp/$s.plain.csv" || fail "$s: --check-determinism changed the output"
done
echo PASS
