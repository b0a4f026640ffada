#!/usr/bin/env bash
# Sampling and stepping options: --sample-interval, --duration, --dt, --json.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
BOUNCE="$SCENES/bounce.xml"  # 3 mobile bodies, MaxTimeStep 0.001

check "--sample-interval 0.1 --duration 1: exactly 11 samples per body, at 0, 0.1, ..., 1"
expect_status 0 "$SIMBOB" run "$BOUNCE" --duration 1 --sample-interval 0.1 --out s.csv
summary=$(csv_summary s.csv)
read -r samples bodies rows first last <<<"$summary"
expect_eq "samples" "$samples" 11
expect_eq "bodies" "$bodies" 3
expect_eq "rows" "$rows" 33
expect_eq "first time" "$first" "0.0"
expect_eq "last time" "$last" "1.0"
times=$(cut -d, -f1 s.csv | tail -n +2 | uniq | tr '\n' ' ')
expect_eq "sample times" "$times" "0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9 1 "
for b in Dull Medium Lively; do
  expect_eq "rows of $b" "$(grep -c ",$b," s.csv)" 11
done

check "the default interval is 0.01 s: 101 samples in 1 s"
expect_status 0 "$SIMBOB" run "$BOUNCE" --duration 1 --out d.csv
summary=$(csv_summary d.csv)
read -r samples bodies rows first last <<<"$summary"
expect_eq "samples" "$samples" 101

check "a duration that is not a multiple of the interval still records the final state"
expect_status 0 "$SIMBOB" run "$BOUNCE" --duration 0.25 --sample-interval 0.1 --out odd.csv
times=$(cut -d, -f1 odd.csv | tail -n +2 | uniq | tr '\n' ' ')
expect_eq "sample times" "$times" "0 0.1 0.2 0.25 "

check "--json prints the summary on stdout, the same as the .json file"
expect_status 0 "$SIMBOB" run "$BOUNCE" --duration 1 --json --out j.csv
python3 - "$LAST_OUT" j.json <<'PY' || fail "--json summary"
import json, sys
printed, saved = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert printed == saved, f"stdout summary differs from j.json:\n{printed}\n{saved}"
for k, v in {"status": "completed", "dt": 0.001, "duration": 1.0, "sim_time": 1.0, "steps": 1000,
             "samples": 101, "bodies": 3, "sample_interval": 0.01, "trajectory": "j.csv"}.items():
    assert printed[k] == v, f"{k} = {printed[k]!r}, expected {v!r}"
PY

check "--dt sets the step: 1 s takes 1000 steps at the scene's 1 ms, 500 at 2 ms, 4000 at 0.25 ms"
for pair in "0.002 500" "0.00025 4000" "0.001 1000"; do
  read -r dt steps <<<"$pair"
  expect_status 0 "$SIMBOB" run "$BOUNCE" --duration 1 --dt "$dt" --json --out "dt$dt.csv"
  vals=$(json_fields "$LAST_OUT" dt steps samples sim_time)
  mapfile -t j <<<"$vals"
  float_between "dt in the summary" "${j[0]}" "$dt" "$dt"
  expect_eq "steps with --dt $dt" "${j[1]}" "$steps"
  expect_eq "samples with --dt $dt (independent of the step)" "${j[2]}" 101
  expect_eq "sim_time with --dt $dt" "${j[3]}" "1.0"
done
check "--dt equal to the scene's MaxTimeStep changes nothing"
expect_status 0 "$SIMBOB" run "$BOUNCE" --duration 1 --out nodt.csv
expect_same_file nodt.csv dt0.001.csv
check "a different --dt gives a different trajectory"
if cmp -s dt0.002.csv dt0.001.csv; then fail "--dt 0.002 and 0.001 gave the same trajectory"; fi

check "--dt too small and --sample-interval 0 are usage errors"
expect_status 64 "$SIMBOB" run "$BOUNCE" --duration 1 --dt 1e-12 --out tiny.csv
expect_status 64 "$SIMBOB" run "$BOUNCE" --duration 1 --sample-interval 0 --out zero.csv
expect_no_file tiny.csv
expect_no_file zero.csv
say "ok"
