#!/usr/bin/env bash
# A diverging run exits 1, names the body and the time, keeps NAME.partial.csv with the rows
# computed so far and never creates (or touches) NAME.csv.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# rocket_scene SPEED: a 1 kg ball thrown up at SPEED m/s beside a resting one. simbob calls a
# run diverged once a position or velocity exceeds 1e6 (m, m/s).
rocket_scene() {
  cat <<XML
<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCMobileRigidBody Key="Resting">
      <Pose><RCGlobalCoordinates><Pose Value="2 0.1 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
      <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
    </RCMobileRigidBody>
    <RCMobileRigidBody Key="Rocket">
      <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Motion><RCGlobalMotion><LinVelocity Value="0 $1 0"/></RCGlobalMotion></Motion>
      <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
      <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
    </RCMobileRigidBody>
  </ComponentList>
</Simulation>
XML
}

check "1e7 m/s along Y: diverges in the first step"
rocket_scene 1e7 >fast.xml
expect_status 1 "$SIMBOB" run fast.xml --duration 10 --out fast.csv
# check's tunnelling warning first (run shows it before it starts), then the error and the
# partial trajectory.
expect_lines "stderr" "$LAST_ERR" 3
expect_match "check's warning first" <(head -n 1 "$LAST_ERR") "^fast.xml:[0-9]+: warning: body 'Rocket' is 0.2 m thin"
expect_match "error names the body, the time and the scene line" "$LAST_ERR" \
  "^fast.xml:[0-9]+: error: body 'Rocket' diverged at t=0.001 s"
expect_match "stderr points to the partial trajectory" "$LAST_ERR" "fast.partial.csv"
expect_no_file fast.csv
expect_no_file fast.json
expect_file fast.partial.csv
summary=$(csv_summary fast.partial.csv)
read -r samples bodies rows first last <<<"$summary"
expect_eq "partial samples (only t=0)" "$samples" 1
expect_eq "partial bodies" "$bodies" 2
expect_eq "partial first time" "$first" "0.0"

check "1e5 m/s along Y: passes 1e6 m just after t = 10 s; the partial CSV holds every sample before"
rocket_scene 1e5 >slow.xml
expect_status 1 "$SIMBOB" run slow.xml --duration 20 --out slow.csv --json
expect_match "error names the body" "$LAST_ERR" "error: body 'Rocket' diverged at t=[0-9.]+ s"
t=$(sed -nE "s/.*diverged at t=([0-9.]+) s.*/\1/p" "$LAST_ERR")
# y = 1 + 1e5 t - 4.905 t^2 reaches 1e6 m at t = 10.0049 s; the 1 ms step that crosses it
# ends at 10.005 s.
float_between "divergence time" "$t" 10.004 10.006
expect_no_file slow.csv
expect_no_file slow.json
expect_file slow.partial.csv
summary=$(csv_summary slow.partial.csv)
read -r samples bodies rows first last <<<"$summary"
expect_eq "partial samples: t = 0, 0.01, ..., 10" "$samples" 1001
expect_eq "partial rows: samples * 2 bodies" "$rows" 2002
expect_eq "partial last time" "$last" "10.0"
check "--json prints the diverged summary on stdout"
vals=$(json_fields "$LAST_OUT" status samples partial_trajectory)
mapfile -t j <<<"$vals"
expect_eq "summary status" "${j[0]}" diverged
expect_eq "summary samples" "${j[1]}" 1001
expect_eq "summary partial_trajectory" "${j[2]}" slow.partial.csv
check "the failed run keeps its summary beside the partial trajectory: slow.partial.json, with the error line"
expect_no_file slow.json
expect_file slow.partial.json
vals=$(json_fields slow.partial.json status samples partial_trajectory)
mapfile -t j <<<"$vals"
expect_eq "partial summary status" "${j[0]}" diverged
expect_eq "partial summary samples" "${j[1]}" 1001
expect_eq "partial summary partial_trajectory" "${j[2]}" slow.partial.csv
error_text=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["error"]["text"])' slow.partial.json)
expect_eq "partial summary error line = the line on stderr" "$error_text" "$(grep ': error: ' "$LAST_ERR" | head -n 1)"

check "batch reports a failed worker by the error line of its run summary"
expect_status 1 "$SIMBOB" batch slow.xml --duration 20 --out-dir b
error_text=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["error"]["text"])' b/slow.partial.json)
grep -qF -- "diverged  slow.xml" "$LAST_OUT" || fail "batch line: $(cat "$LAST_OUT")"
grep -qF -- " -- $error_text" "$LAST_OUT" || fail "batch line lacks the summary's error line: $(cat "$LAST_OUT")"

check "a diverging run leaves an existing NAME.csv untouched and replaces an old partial"
printf 'old trajectory\n' >fast.csv
cp fast.csv fast.csv.orig
touch -d '2001-02-03 04:05:06' fast.csv
before=$(stat -c '%y %s' fast.csv)
printf 'stale partial\n' >fast.partial.csv
expect_status 1 "$SIMBOB" run fast.xml --duration 10 --out fast.csv
expect_same_file fast.csv fast.csv.orig
expect_eq "mtime and size of fast.csv" "$(stat -c '%y %s' fast.csv)" "$before"
expect_eq "partial header" "$(head -n 1 fast.partial.csv)" "time,body,x,y,z,qw,qx,qy,qz"

check "a huge (upward) gravity diverges too"
sed 's|<ComponentList>|<SceneSettings><Gravity Value="0 1e9 0"/></SceneSettings>\n  <ComponentList>|' \
  <(rocket_scene 0) >heavy.xml
expect_status 1 "$SIMBOB" run heavy.xml --duration 1 --out heavy.csv
expect_match "error names a body" "$LAST_ERR" "error: body '(Resting|Rocket)' diverged at t="
expect_no_file heavy.csv
expect_file heavy.partial.csv

leftovers=$(find . -name '*tmp*')
expect_eq "temporary files" "$leftovers" ""
say "ok"
