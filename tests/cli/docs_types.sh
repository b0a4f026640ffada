#!/usr/bin/env bash
# docs/component-types.md is exactly what `simbob types --markdown` prints, so the reference
# of every type's parameters, defaults and units stays in step with the registry.
# After changing a type: scripts/update-docs.sh.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

check "docs/component-types.md equals simbob types --markdown (else run scripts/update-docs.sh)"
expect_status 0 "$SIMBOB" types --markdown
expect_file "$REPO/docs/component-types.md"
if ! cmp -s "$LAST_OUT" "$REPO/docs/component-types.md"; then
  diff -u "$REPO/docs/component-types.md" "$LAST_OUT" | head -n 40 >&2 || true
  fail "docs/component-types.md is out of date: run scripts/update-docs.sh and commit it"
fi
say "ok"
