#!/usr/bin/env bash
# Regenerates docs/component-types.md from the registry (`simbob types --markdown`); ctest
# cli.docs_types fails while the committed file differs. Usage: scripts/update-docs.sh
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/simbob ] || bash scripts/build.sh
tmp=$(mktemp docs/.component-types.md.XXXXXX)
trap 'rm -f "$tmp"' EXIT
build/simbob types --markdown >"$tmp"
if cmp -s "$tmp" docs/component-types.md; then
  echo "update-docs: docs/component-types.md is up to date"
else
  chmod 644 "$tmp"
  mv "$tmp" docs/component-types.md
  echo "update-docs: wrote docs/component-types.md; review it (git diff docs/) and commit it"
fi
