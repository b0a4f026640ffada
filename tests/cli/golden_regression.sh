#!/usr/bin/env bash
# Every shipped scene, run for 10 s by `simbob batch`, matches its golden trajectory.
# A changed physics result fails here with the batch report in the log.
set -euo pipefail
simbob=$1
repo=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$repo"
# A scene with a socket communicator starts its peer program itself (its Controller).
scenes=()
for s in scenes/*.xml; do
  name=$(basename "${s%.xml}")
  [ -f "golden/$name.csv" ] || { echo "FAIL: no golden/$name.csv for $s (run scripts/update-golden.sh)"; exit 1; }
  scenes+=("$s")
done
"$simbob" batch "${scenes[@]}" --duration 10 --out-dir "$tmp" --golden golden -j 2
echo "PASS: every scene matches golden/"
