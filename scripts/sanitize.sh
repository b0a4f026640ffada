#!/usr/bin/env bash
# The sanitizer stage: configures and builds build-fuzz with clang, AddressSanitizer +
# UndefinedBehaviorSanitizer and the libFuzzer targets, then runs the WHOLE normal test suite
# there (every ctest test except the fuzz runs: ctest -LE fuzz).
#
# Usage: scripts/sanitize.sh [--build-only] [extra cmake arguments]
#   --build-only   configure and build only (scripts/fuzz.sh uses this, then runs ctest -L fuzz)
set -euo pipefail
cd "$(dirname "$0")/.."

build_only=0
if [ "${1:-}" = "--build-only" ]; then
  build_only=1
  shift
fi

bash scripts/deps.sh test

# ASan's default leak check stays on; a failing check stops with a stack trace.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# Leaks of third-party libraries that simbob cannot free (each explained in the file).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}"

# Line tables are all a sanitizer's stack trace needs (file:line per frame): full debug info
# would double this build's compile and link time. ccache as in scripts/build.sh.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
read -r -a launcher <<<"$(bash scripts/ccache-args.sh)"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG" "${launcher[@]}" \
  -DSIMBOB_SANITIZE=ON -DSIMBOB_FUZZ=ON -DSIMBOB_WERROR=ON "$@" >/dev/null
if ! grep -q '^CMAKE_CXX_COMPILER_ID:INTERNAL=Clang\|^CMAKE_CXX_COMPILER:.*clang' build-fuzz/CMakeCache.txt; then
  echo "sanitize: build-fuzz was configured with another compiler; remove build-fuzz and rerun" >&2
  exit 1
fi
cmake --build build-fuzz -j"$(nproc)"
[ "$build_only" -eq 1 ] && exit 0

cd build-fuzz
ctest -LE fuzz --output-on-failure -j"$(nproc)"
