#!/usr/bin/env bash
# `simbob types` lists every component type with its parameters; --markdown prints tables.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

check "types exits 0 and prints to stdout only"
expect_status 0 "$SIMBOB" types
cp "$LAST_OUT" types.txt
expect_lines "types stderr" "$LAST_ERR" 0

check "RCHingeJoint is listed as a JointComponent with its Hinge parameter"
# The block of a type: its header line up to the next line that does not start with a space.
hinge=$(awk '/^RCHingeJoint \(/ {on = 1; print; next} on && /^[^ ]/ {on = 0} on {print}' types.txt)
[[ -n "$hinge" ]] || fail "no RCHingeJoint entry in simbob types"
printf '%s\n' "$hinge" >hinge.txt
expect_match "RCHingeJoint header" hinge.txt "^RCHingeJoint \(JointComponent"
expect_match "Hinge parameter" hinge.txt "^  Hinge : PoseComponent"
expect_match "Body parameter" hinge.txt "^  Body : BodyComponent"
expect_match "Pose parameter" hinge.txt "^  Pose : PoseComponent"

check "every type used by the shipped scenes is listed"
for t in RCGround RCSandBox RCSky RCMobileRigidBody RCStaticRigidBody RCRodBody RCConstruction \
  RCImportBody RigidBodyClone RCImportRefList RCRobot RCBallSocketJoint RCSliderJoint RCFixJoint \
  RCGenericMaterial RCColoredSkin RCCylinderModel RCModelMatchGeom RCTransformGeom \
  RCGenericVelControlledDrive RCTwoWheelMotionControl RCInertiaByGeom RCGenericInertia; do
  expect_match "$t listed" types.txt "^$t \("
done
check "parameters show their defaults and units"
expect_match "RCSphereGeom Radius default and unit" types.txt "^  Radius : Number = 0.5 \[m\]"
expect_match "the Origin macro" types.txt "^  Origin -> RCLocalCoordinates"

check "--markdown prints a table for RCHingeJoint"
expect_status 0 "$SIMBOB" types --markdown
cp "$LAST_OUT" types.md
expect_match "title" types.md "^# simbob component types"
section=$(awk '/^## RCHingeJoint / {on = 1; print; next} on && /^## / {on = 0} on {print}' types.md)
[[ -n "$section" ]] || fail "no '## RCHingeJoint' section in simbob types --markdown"
printf '%s\n' "$section" >hinge.md
expect_match "section header" hinge.md "^## RCHingeJoint \(JointComponent\)"
expect_match "table header" hinge.md "^\| Parameter \| Type \| Default \| Unit \| Meaning \|$"
expect_match "table rule" hinge.md "^\|---\|---\|---\|---\|---\|$"
expect_match "Hinge row" hinge.md "^\| Hinge \| PoseComponent \| "
check "every markdown table row has as many cells as its header (a '|' in a cell is escaped)"
python3 - types.md <<'PY' || fail "malformed markdown table rows"
import re, sys
width, bad = None, []
for n, line in enumerate(open(sys.argv[1]), start=1):
    line = line.rstrip("\n")
    if not line.startswith("|"):
        width = None
        continue
    cells = re.split(r"(?<!\\)\|", line)[1:-1]  # split on '|' not preceded by a backslash
    if width is None:
        width = len(cells)
    elif len(cells) != width:
        bad.append(f"line {n}: {len(cells)} cells, the table has {width}: {line}")
if bad:
    sys.exit("\n".join(bad[:5]))
PY
say "ok"

check "types takes the options every command takes: --settings, -q, -v, --log-file (README)"
printf 'LogFile = from-settings.log\n' >settings.ini
expect_status 0 "$SIMBOB" types --settings settings.ini -q
expect_same_file "$LAST_OUT" types.txt
expect_file from-settings.log
expect_status 0 "$SIMBOB" types -v --log-file types.log
expect_same_file "$LAST_OUT" types.txt
expect_file types.log
say "ok"
