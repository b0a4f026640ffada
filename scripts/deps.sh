#!/usr/bin/env bash
# Installs simbob's build and test dependencies from Debian 12's packages (only what is missing).
# Sourced by demo.sh, test.sh and bench.sh; safe to run on its own.
set -euo pipefail

SIMBOB_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libode-dev            # physics
  libeigen3-dev         # linear algebra in the compile step
  libpugixml-dev        # XML scenes
  libcli11-dev          # command line
  nlohmann-json3-dev    # run summaries and reports
  libosmesa6-dev libpng-dev  # off-screen rendering (Record)
  libcairo2-dev         # trajectory plots (PNG, SVG)
  catch2                # unit tests
  python3               # test helpers
  valgrind              # memcheck of the example scenes (tests/cli/valgrind.sh)
  clang libclang-rt-14-dev  # sanitizer and fuzz builds (scripts/sanitize.sh, scripts/fuzz.sh)
)

missing=()
for p in "${SIMBOB_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "simbob: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
