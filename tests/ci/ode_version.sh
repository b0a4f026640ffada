#!/usr/bin/env bash
# CMake requires ODE 0.16.x (docs/ci.md: the broad phase reproduces 0.16.2's pair order and the
# golden files were made with it). A pkg-config that reports ODE 0.17.0 (a copy of Debian's
# ode.pc with another Version, first on PKG_CONFIG_PATH) stops the configure step with the reason,
# before any compiler work beyond CMake's own checks; Debian's own 0.16.2 configures (the build
# this test runs in).
#   bash ode_version.sh REPO
set -euo pipefail
repo=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pc=$(pkg-config --variable=pcfiledir ode)/ode.pc
mkdir "$work/pc"
sed 's/^Version: .*/Version: 0.17.0/' "$pc" >"$work/pc/ode.pc"
grep -q '^Version: 0.17.0$' "$work/pc/ode.pc" || { echo "FAIL: no Version line in $pc"; exit 1; }
status=0
PKG_CONFIG_PATH="$work/pc" cmake -S "$repo" -B "$work/build" -G Ninja -DSIMBOB_TESTS=OFF >"$work/out" 2>&1 || status=$?
if [[ $status -eq 0 ]]; then
  echo "FAIL: CMake configured simbob with ODE 0.17.0"
  exit 1
fi
# CMake wraps its messages: compare with the lines joined.
tr -s ' \n' '  ' <"$work/out" | grep -qF "simbob needs ODE 0.16.x (Debian 12's libode-dev 0.16.2); pkg-config found ODE 0.17.0" || {
  echo "FAIL: CMake stopped without naming the ODE version:"
  cat "$work/out"
  exit 1
}
echo "PASS: ODE 0.17.0 refused"
