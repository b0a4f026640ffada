#!/usr/bin/env bash
# From a fresh Debian 12 machine: install what is missing, build, and run an example scene.
# Only what building and running needs is installed, and the tests are not built (test.sh
# installs and builds those).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh -DSIMBOB_TESTS=OFF
mkdir -p out
build/simbob run scenes/pendulum.xml --duration 10 --out out/pendulum.csv
echo
echo "Trajectory: out/pendulum.csv (summary: out/pendulum.json). First rows:"
head -n 4 out/pendulum.csv
