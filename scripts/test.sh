#!/usr/bin/env bash
# From a fresh Debian 12 machine: install what is missing, build, and run every test via ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)"
