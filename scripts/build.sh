#!/usr/bin/env bash
# Installs what building and running needs (scripts/deps.sh run), configures and builds simbob
# into build/ (binary: build/simbob). Extra arguments go to cmake. The test suite needs Catch2,
# which only scripts/deps.sh test installs: without it, and without an explicit
# -DSIMBOB_TESTS=..., the tests are left out (demo.sh asks for that; test.sh asks for them).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh run
args=("$@")
if [[ " $* " != *" -DSIMBOB_TESTS="* ]] &&
  ! dpkg-query -W -f='${Status}' catch2 2>/dev/null | grep -q "install ok installed"; then
  echo "build: Catch2 is not installed (scripts/deps.sh test), building without the tests" >&2
  args+=(-DSIMBOB_TESTS=OFF)
fi
# With ccache (scripts/deps.sh test installs it) a rebuild on this machine, from any checkout of
# the project (CCACHE_BASEDIR), compiles only what changed.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
read -r -a launcher <<<"$(bash scripts/ccache-args.sh)"
args=("${launcher[@]}" "${args[@]}")
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "${args[@]}" >/dev/null
cmake --build build -j"$(nproc)"
