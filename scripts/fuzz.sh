#!/usr/bin/env bash
# Runs every libFuzzer target (fuzz/*_fuzzer.cpp) for SECONDS each (default 60) in build-fuzz,
# the clang ASan+UBSan build that scripts/sanitize.sh makes: ctest -L fuzz.
#
# Usage: scripts/fuzz.sh [SECONDS]
# A fuzzer that crashes, hangs (-timeout=10) or exceeds 2 GB (-rss_limit_mb=2048) fails its
# test and leaves the input in build-fuzz/fuzz/artifacts/<target>/. Fix the bug and copy the
# input to tests/data/fuzz/<target>/: the normal test suite replays every file there.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-60}
case "$seconds" in
  '' | *[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS]" >&2; exit 2 ;;
esac

bash scripts/sanitize.sh --build-only -DSIMBOB_FUZZ_SECONDS="$seconds"

# Without the fuzz targets (top-level CMakeLists.txt lacks add_subdirectory(fuzz)) ctest would
# find no tests and pass.
if [ ! -x build-fuzz/fuzz/values_fuzzer ]; then
  echo "fuzz: no fuzz targets in build-fuzz (is fuzz/ added to CMakeLists.txt under SIMBOB_FUZZ?)" >&2
  exit 1
fi

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}"
cd build-fuzz
status=0
ctest -L fuzz --output-on-failure -j"$(nproc)" || status=$?
if [ "$status" -ne 0 ]; then
  echo "fuzz: findings (reproducers):" >&2
  find fuzz/artifacts -type f -newer CMakeCache.txt -printf '  build-fuzz/%p\n' >&2 || true
fi
exit "$status"
