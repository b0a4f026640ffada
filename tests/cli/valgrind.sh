#!/usr/bin/env bash
# Every example scene runs valgrind-clean (memcheck: no invalid access, no use of uninitialised
# values, no leak) for a short run through the whole pipeline: load, compile, ODE, CSV, summary.
set -euo pipefail
simbob=$1
repo=$2
if ! command -v valgrind >/dev/null; then
  echo "FAIL: valgrind is not installed (scripts/deps.sh installs it)"
  exit 1
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scene in "$repo"/scenes/*.xml; do
  name=$(basename "${scene%.xml}")
  if grep -q '<RCLocalSocketCommunicator' "$scene"; then
    echo "== $name: skipped (needs a socket peer; tests/cli/socket.sh runs it)"
    continue
  fi
  echo "== $name"
  valgrind --quiet --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect \
    "$simbob" run "$scene" --duration 0.05 --out "$tmp/$name.csv" --quiet || {
    echo "FAIL: valgrind reported errors for $name"
    exit 1
  }
done
echo PASS
