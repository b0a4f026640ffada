#!/usr/bin/env bash
# Every shipped scene checks clean and runs 10 s into a well-formed trajectory and summary,
# and moves as its header comment says (tests/cli/scene_expectations.py).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# Mobile bodies of each documented scene (static bodies, ground and walls are not in the CSV).
# (scenes/socket_robot.xml, 4 mobile bodies, needs its peer: tests/cli/socket.sh runs and checks it.)
declare -A MOBILE=([pendulum]=1 [box_stack]=6 [chain]=5 [imported_bodies]=3 [mechanisms]=6 [bounce]=3 [robot]=4
  [two_wheel_robot]=4 [wall_stop_robot]=4 [flywheel]=1 [servo_arm]=1
  [sliding_box]=1 [gallery]=2 [go_to_point_robot]=4 [mesh_drop]=4 [kr5]=7 [drchubo]=52)

count=0
while read -r scene; do
  name=$(basename "$scene" .xml)
  count=$((count + 1))

  check "$name: simbob check exits 0"
  expect_status 0 "$SIMBOB" check "$scene"
  expect_match "$name: check reports ok" "$LAST_ERR" ": ok \([0-9]+ mobile bod(y|ies)"

  check "$name: simbob run --duration 10 exits 0"
  expect_status 0 "$SIMBOB" run "$scene" --duration 10 --out "$name.csv"
  expect_file "$name.csv"
  expect_file "$name.json"
  expect_no_file "$name.partial.csv"

  check "$name: header, finite numbers, one row per mobile body per sample"
  expect_eq "$name: header" "$(head -n 1 "$name.csv")" "time,body,x,y,z,qw,qx,qy,qz"
  summary=$(csv_summary "$name.csv")
  read -r samples bodies rows first last <<<"$summary"
  expect_eq "$name: first sample time" "$first" "0.0"
  expect_eq "$name: last sample time" "$last" "10.0"
  # 0, 0.01, ..., 10 s: 1001 samples at the default interval.
  expect_eq "$name: samples in the CSV" "$samples" 1001

  check "$name: the JSON summary names the scene and agrees with the CSV"
  vals=$(json_fields "$name.json" scene status samples bodies sim_time trajectory csv_bytes)
  mapfile -t j <<<"$vals"
  expect_eq "$name: summary scene" "${j[0]}" "$scene"
  expect_eq "$name: summary status" "${j[1]}" completed
  expect_eq "$name: summary samples" "${j[2]}" "$samples"
  expect_eq "$name: summary bodies (mobile bodies)" "$((j[3] + $(json_get "$name.json" "j.get('frames', 0)")))" "$bodies"
  frames=$(json_get "$name.json" "j.get('frames', 0)")  # rows of lumped URDF links, after the bodies'
  expect_eq "$name: rows = samples * (mobile bodies + frames)" "$rows" "$((j[2] * (j[3] + frames)))"
  expect_eq "$name: summary sim_time" "${j[4]}" "10.0"
  expect_eq "$name: summary trajectory" "${j[5]}" "$name.csv"
  expect_eq "$name: summary csv_bytes" "${j[6]}" "$(wc -c <"$name.csv")"
  if [[ -n "${MOBILE[$name]:-}" ]]; then
    expect_eq "$name: mobile bodies" "$bodies" "${MOBILE[$name]}"
  fi
  # `check` counts the same mobile bodies as the run.
  expect_status 0 "$SIMBOB" check "$scene"
  expect_match "$name: check counts ${j[3]} mobile bodies" "$LAST_ERR" ": ok \(${j[3]} mobile bod(y|ies)"

  check "$name: the motion is what the scene's comment promises"
  python3 "$CLI_DIR/scene_expectations.py" "$name" "$name.csv" || fail "$name: physical expectations"

  check "$name: no temporary files are left behind"
  leftovers=$(find . -name "$name.*tmp*" | head -n 5)
  expect_eq "$name: leftover temporary files" "$leftovers" ""
done < <(shipped_scenes)

check "the shipped scenes include the documented examples"
for want in "${!MOBILE[@]}"; do
  expect_file "$SCENES/$want.xml"
done
say "ok: $count scenes"
