#!/usr/bin/env bash
# Regenerates golden/<scene>.csv for every scenes/*.xml (10 s each) and says what changed.
# Usage: scripts/update-golden.sh [scene.xml ...]   (default: every scene)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/simbob ] || bash scripts/build.sh
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/*.xml)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# A scene with an RCLocalSocketCommunicator starts its peer program itself (its Controller).
alone=("${scenes[@]}")
if [ ${#alone[@]} -gt 0 ]; then
  build/simbob batch "${alone[@]}" --duration 10 --out-dir "$tmp" --quiet >/dev/null || {
    echo "update-golden: some scenes failed; see the logs:" >&2
    build/simbob batch "${alone[@]}" --duration 10 --out-dir "$tmp" >&2 || true
    exit 1
  }
fi
mkdir -p golden
changed=0
for s in "${scenes[@]}"; do
  name=$(basename "${s%.xml}")
  new="$tmp/$name.csv"
  old="golden/$name.csv"
  if [ ! -f "$old" ]; then
    echo "new      $old"
    changed=1
  elif cmp -s "$new" "$old"; then
    echo "same     $old"
    continue
  else
    echo "changed  $old:"
    build/simbob compare "$new" "$old" --quiet | sed 's/^/    /' || true
    changed=1
  fi
  cp "$new" "$old"
done
[ $changed -eq 0 ] && echo "update-golden: nothing changed" || echo "update-golden: review and commit golden/"
