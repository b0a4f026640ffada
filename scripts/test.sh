#!/usr/bin/env bash
# From a fresh Debian 12 machine: install what is missing, build, and run every test via ctest.
#   1. the normal build (build/): unit, physics, scene, CLI and golden-regression tests, then
#      the style checks (scripts/check-style.sh: clang-format, clang-tidy);
#   2. the ASan + UBSan build (build-fuzz/, clang): the same whole suite again;
#   3. every libFuzzer target for SIMBOB_FUZZ_SECONDS (default 60) each.
# SIMBOB_QUICK=1 runs stage 1 only (for a fast local check).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh test
bash scripts/build.sh -DSIMBOB_TESTS=ON
(cd build && ctest --output-on-failure --no-tests=error -j"$(nproc)")
bash scripts/check-style.sh
if [ "${SIMBOB_QUICK:-0}" = 1 ]; then
  echo "test: SIMBOB_QUICK=1, skipped the sanitizer and fuzz stages"
  exit 0
fi
bash scripts/sanitize.sh
bash scripts/fuzz.sh "${SIMBOB_FUZZ_SECONDS:-60}"
