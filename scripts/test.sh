#!/usr/bin/env bash
# From a fresh Debian 12 machine: install what is missing, build, and run every test via ctest.
#   1. the normal build (build/): unit, physics, scene, CLI and golden-regression tests;
#   2. the ASan + UBSan build (build-fuzz/, clang): the same whole suite again;
#   3. every libFuzzer target for SIMBOB_FUZZ_SECONDS (default 60) each.
# SIMBOB_QUICK=1 runs stage 1 only (for a fast local check).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
if [ "${SIMBOB_QUICK:-0}" = 1 ]; then
  echo "test: SIMBOB_QUICK=1, skipped the sanitizer and fuzz stages"
  exit 0
fi
bash scripts/sanitize.sh
bash scripts/fuzz.sh "${SIMBOB_FUZZ_SECONDS:-60}"
