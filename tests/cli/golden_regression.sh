#!/usr/bin/env bash
# Every scene with a golden file (lib.sh's golden_scenes: each golden/NAME.csv and its scene, and
# every scenes/*.xml, which must have one), run for 10 s by `simbob batch`, matches its golden
# trajectory. A changed physics result fails here with the batch report in the log.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
cd "$REPO"
# A scene with a socket communicator starts its peer program itself (its Controller).
list=$(golden_scenes)
mapfile -t scenes <<<"$list"
"$SIMBOB" batch "${scenes[@]}" --duration 10 --out-dir "$WORK" --golden golden -j 2
echo "PASS: every scene matches golden/"
