#!/usr/bin/env bash
# A full disk (simulated with a file size limit) stops the run when it happens: exit 74, a
# message naming the output, and no truncated file under the final or the partial name.
set -euo pipefail
simbob=$1
repo=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
fail() { echo "FAIL: $*"; exit 1; }
set +e
# SIGXFSZ ignored (inherited across exec) turns the limit into a failing write(), like ENOSPC.
(trap '' XFSZ; ulimit -f 16; exec "$simbob" run "$repo/scenes/box_stack.xml" --duration 1000 --out full.csv) 2> err.txt
status=$?
set -e
[ $status -eq 74 ] || fail "expected exit 74, got $status: $(cat err.txt)"
grep -q "^full.csv: error: writing the trajectory failed at t=" err.txt || fail "message: $(cat err.txt)"
grep -q "^full.csv: error: write failed: File too large" err.txt || fail "cause not named: $(cat err.txt)"
# Stopped early: 16 KiB of CSV is far less than 1000 s of simulation.
t=$(sed -n 's/.*failed at t=\([0-9.]*\) s.*/\1/p' err.txt)
python3 -c "import sys; sys.exit(0 if float('$t') < 100 else 1)" || fail "the run went on after the failure (t=$t)"
# What is left is the failed run's summary, whole (it fits under the limit), and nothing else.
[ "$(ls | tr '\n' ' ')" = "err.txt full.partial.json " ] || fail "files left behind: $(ls)"
/usr/bin/python3 - full.partial.json <<'EOF' || fail "partial summary: $(cat full.partial.json)"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["status"] == "failed", s["status"]
assert s["error"]["file"] == "full.csv", s["error"]
assert s["error"]["text"].startswith("full.csv: error: writing the trajectory failed at t="), s["error"]["text"]
assert "partial_trajectory" not in s, s
EOF
echo PASS
