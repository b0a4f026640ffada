#!/usr/bin/env bash
# MaxAccessTime end to end: a scene whose MaxAccessTime no grant can meet (1 ns) stops at the
# first grant with exit 69 (EX_UNAVAILABLE) and a one-line error naming the party and the limit,
# keeps the partial trajectory and writes no trajectory; the default (1 s) runs the same robot.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

sed 's|<Simulation>|<Simulation><SceneSettings><MaxAccessTime Value="1e-9"/></SceneSettings>|' \
  "$SCENES/flywheel.xml" >tight.xml
check "69: a grant longer than MaxAccessTime stops the run"
expect_status 69 "$SIMBOB" run tight.xml --duration 1 --out tight.csv
expect_match "stderr names the party and the limit" "$LAST_ERR" \
  "error: the trajectory sampler held the simulation for [0-9.e+-]+ s of wall-clock time at t=0 s, longer than MaxAccessTime \(1e-09 s\)"
expect_eq "one error line" "$(grep -c 'error:' "$LAST_ERR")" 1
expect_no_file tight.csv
expect_no_file tight.json
expect_file tight.partial.csv

check "the same robot under the default MaxAccessTime completes"
expect_status 0 "$SIMBOB" run "$SCENES/flywheel.xml" --duration 1 --out ok.csv
expect_file ok.csv
say "ok"
