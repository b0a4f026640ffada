#!/usr/bin/env bash
# DocumentIni (guide 3.3.1): with the global setting on, the camera settings in <scene>.ini
# beside the scene override the scene file's; --set wins over both; the INI sets cameras only,
# and its errors name its file and line. (That a render uses them: tests/cli/record.sh.)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
cp "$REPO/tests/data/render/basic.xml" scene.xml
printf 'DocumentIni = True\n' >on.ini

check "without the setting <scene>.ini is not read"
printf '; the view we last liked\n[Front]\nViewAngle = 40\nPose.Pose = 0 2 7 -15 0 0\n' >scene.ini
expect_status 0 "$SIMBOB" dump scene.xml
expect_match "file's angle" "$LAST_OUT" '<ViewAngle Value="60" />'
expect_status 0 "$SIMBOB" dump scene.xml --settings on.ini
cp "$LAST_OUT" on.xml

check "with DocumentIni the INI's camera settings replace the file's (a camera's own and inside its pose)"
python3 - on.xml <<'PY'
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
cams = {c.get("Key"): c for c in root.find("CameraList")}
front, top = cams["Front"], cams["Top"]
assert front.find("ViewAngle").get("Value") == "40", front.find("ViewAngle").get("Value")
assert front.find("Pose/RCGlobalCoordinates/Pose").get("Value") == "0 2 7 -15 0 0"
assert top.find("ViewAngle").get("Value") == "60", "the other camera keeps its settings"
PY

check "--set wins over the INI (command line last)"
expect_status 0 "$SIMBOB" dump scene.xml --settings on.ini --set Front.ViewAngle=25
expect_match "--set" "$LAST_OUT" '<ViewAngle Value="25" />'

check "a run with DocumentIni moves no body: the trajectory is the same bytes"
expect_status 0 "$SIMBOB" run scene.xml --duration 0.2 --out plain.csv
expect_status 0 "$SIMBOB" run scene.xml --duration 0.2 --out ini.csv --settings on.ini
expect_same_file ini.csv plain.csv
expect_eq "overrides in the summary" "$(json_get ini.json "','.join(j['overrides'])")" \
  "Front.ViewAngle=40,Front.Pose.Pose=0 2 7 -15 0 0"

check "the INI is an input: --out never overwrites it (64, as for the scene)"
cp scene.ini keep.ini
expect_status 64 "$SIMBOB" run scene.xml --duration 0.1 --out scene.ini --settings on.ini
expect_match "message" "$LAST_ERR" "--out scene.ini is the DocumentIni scene.ini: an output must not overwrite an input"
expect_same_file scene.ini keep.ini

check "a body is no camera: the INI's file and line, 65"
printf '[Front]\nViewAngle = 40\n[Ball]\nPose.Pose = 0 3 0 0 0 0\n' >scene.ini
expect_status 65 "$SIMBOB" run scene.xml --duration 0.1 --out no.csv --settings on.ini
expect_lines "one line" "$LAST_ERR" 1
expect_match "message" "$LAST_ERR" \
  "^scene.ini:4: error: RCGlobalCoordinates 'Ball.Pose' is no camera: a DocumentIni sets camera parameters only \(guide 3.3.1\)$"
expect_no_file no.csv

check "an unknown parameter gets a did-you-mean at its line; a malformed line is named"
printf '[Front]\nViewAngel = 40\n' >scene.ini
expect_status 65 "$SIMBOB" check scene.xml --settings on.ini
expect_match "message" "$LAST_ERR" \
  "^scene.ini:2: error: RCStaticCamera 'Front': parameter 'ViewAngel' unknown \(did you mean 'ViewAngle'\?\)$"
printf '[Front]\nViewAngle 40\n' >scene.ini
expect_status 65 "$SIMBOB" check scene.xml --settings on.ini
expect_match "message" "$LAST_ERR" "^scene.ini:2: error: expected 'key = value', got 'ViewAngle 40'$"
printf 'ViewAngle = 40\n' >scene.ini
expect_status 65 "$SIMBOB" check scene.xml --settings on.ini
expect_match "message" "$LAST_ERR" \
  "^scene.ini:1: error: expected 'CAMERA.PARAM = VALUE' or 'PARAM = VALUE' under \[CAMERA\], got 'ViewAngle'$"
printf '[Front]\nViewAngle = wide\n' >scene.ini
expect_status 65 "$SIMBOB" check scene.xml --settings on.ini
expect_match "message" "$LAST_ERR" "^scene.ini:2: error: RCStaticCamera 'Front': "

check "no INI beside the scene is no error; an INI scene has no DocumentIni"
rm scene.ini
expect_status 0 "$SIMBOB" check scene.xml --settings on.ini
expect_status 0 "$SIMBOB" dump scene.xml --format ini
cp "$LAST_OUT" inis.ini
expect_status 0 "$SIMBOB" check inis.ini --settings on.ini
say "PASS"
