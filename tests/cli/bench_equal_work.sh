#!/usr/bin/env bash
# The benchmark compares equal work: simbob on the scene of bench/gen_scene.py and the bare-ODE
# loop of bench/bare_ode.cpp must produce the same trajectory (every pose within 1e-9; in practice
# the CSV files are byte-identical). Not a timing test.
# Usage: bash bench_equal_work.sh /path/to/simbob /path/to/repo   (bare_ode: <simbob dir>/bench/bare_ode)
set -euo pipefail
simbob=$1
repo=$2
bare="$(cd "$(dirname "$simbob")" && pwd)/bench/bare_ode"
if [ ! -x "$bare" ]; then
  echo "FAIL: $bare not built (bench/ is built by default; was SIMBOB_BENCH turned off?)"
  exit 1
fi
command -v python3 >/dev/null || { echo "FAIL: python3 is needed (scripts/deps.sh installs it)"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

status=0
for n in 10 100; do
  python3 "$repo/bench/gen_scene.py" "$n" "$tmp/boxes$n.xml"
  "$simbob" run "$tmp/boxes$n.xml" --duration 2 --out "$tmp/simbob$n.csv" -q
  "$bare" "$n" 2 "$tmp/bare$n.csv" >/dev/null
  # Same rows (time, body) in the same order; largest difference of any pose number.
  if python3 - "$tmp/simbob$n.csv" "$tmp/bare$n.csv" "$n" <<'EOF'; then :; else status=1; fi
import sys
a_path, b_path, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
with open(a_path) as fa, open(b_path) as fb:
    a, b = fa.read().splitlines(), fb.read().splitlines()
if a[0] != b[0]:
    print(f"FAIL n={n}: headers differ: {a[0]!r} vs {b[0]!r}")
    sys.exit(1)
if len(a) != len(b):
    print(f"FAIL n={n}: simbob wrote {len(a) - 1} rows, bare_ode {len(b) - 1}")
    sys.exit(1)
worst, where = 0.0, None
for i, (la, lb) in enumerate(zip(a[1:], b[1:]), start=2):
    fa_, fb_ = la.split(","), lb.split(",")
    if fa_[:2] != fb_[:2]:
        print(f"FAIL n={n}: line {i}: row (time, body) {fa_[:2]} vs {fb_[:2]}")
        sys.exit(1)
    for k in range(2, 9):
        d = abs(float(fa_[k]) - float(fb_[k]))
        if d > worst:
            worst, where = d, (fa_[0], fa_[1], ["x", "y", "z", "qw", "qx", "qy", "qz"][k - 2])
samples = len({l.split(",", 1)[0] for l in a[1:]})
identical = a == b
msg = (f"n={n}: {len(a) - 1} rows ({samples} samples), max |difference| {worst:.3g}"
       + (f" at t={where[0]} {where[1]}.{where[2]}" if where else "")
       + (" (byte-identical files)" if identical else ""))
if worst > 1e-9:
    print("FAIL " + msg + " > 1e-9")
    sys.exit(1)
print("ok   " + msg)
EOF
done
[ "$status" -eq 0 ] && echo "PASS: simbob and bare_ode do the same work"
exit "$status"
