#!/usr/bin/env bash
# Fails on unformatted C++ (clang-format with .clang-format, over every tracked .cpp/.h) or on
# clang-tidy findings (.clang-tidy) in lib/ and cmd/. Needs build/compile_commands.json, which
# scripts/build.sh writes. scripts/test.sh runs it after the normal build and ctest.
# About 160 s of CPU, so about 80 s on 2 idle cores (clang-tidy is nearly all of it).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

sources() {  # NUL-separated C++ files under the given folders (tracked ones in a git checkout)
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -z -- "${@/%//*.cpp}" "${@/%//*.h}"
  else
    find "$@" \( -name '*.cpp' -o -name '*.h' \) -print0
  fi
}

echo "check-style: clang-format" >&2
sources bench cmd fuzz include lib python tests | xargs -0 clang-format --dry-run --Werror

echo "check-style: clang-tidy" >&2
if [ ! -f build/compile_commands.json ]; then
  echo "check-style: build/compile_commands.json is missing; run scripts/build.sh first" >&2
  exit 1
fi
log=build/clang-tidy.log
status=0
if command -v run-clang-tidy >/dev/null; then
  run-clang-tidy -quiet -p build -j "$jobs" "^$PWD/(lib|cmd)/" >"$log" 2>&1 || status=$?
else
  sources lib cmd | grep -z '\.cpp$' | xargs -0 -n 4 -P "$jobs" clang-tidy --quiet -p build >"$log" 2>&1 || status=$?
fi
if [ "$status" -ne 0 ]; then
  # One line per finding (a header's finding repeats once per file that includes it).
  sed 's/\x1b\[[0-9;]*m//g' "$log" | grep -E '(warning|error): ' | grep -v '^Error while processing' | sort -u >&2 ||
    cat "$log" >&2
  echo "check-style: clang-tidy found the problems above (whole output: $log)" >&2
  exit 1
fi
echo "check-style: ok" >&2
