#!/usr/bin/env bash
# Prints the CMake arguments that compile through ccache, or nothing when ccache is missing or
# cannot write its cache (a read-only home, a full disk): then builds compile as they would
# without it. scripts/build.sh and scripts/sanitize.sh use it; scripts/deps.sh test installs it.
# The caller exports CCACHE_BASEDIR (the checkout) so that any checkout of the project hits.
set -euo pipefail
command -v ccache >/dev/null || exit 0
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'int simbob_ccache_probe;\n' >"$tmp/probe.c"
if ccache cc -c "$tmp/probe.c" -o "$tmp/probe.o" >/dev/null 2>&1; then
  echo "-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
else
  echo "ccache-args: ccache cannot compile here (its cache is not writable?); building without it" >&2
fi
