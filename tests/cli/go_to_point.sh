#!/usr/bin/env bash
# RCSimGoToPoint (a sim controller): the robot ends within Tolerance + Speed * Period of its
# target, wherever the target lies (ahead-left, straight behind); its references are checked
# with errors that name the file and line of the offending parameter.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

SCENE="$SCENES/go_to_point_robot.xml"

# ends_near CSV X Z TOL: the chassis' last sample is within TOL m of (X, Z) on the ground, and
# it was not there at the start.
ends_near() {
  python3 - "$@" <<'PY'
import csv, math, sys
path, x, z, tol = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
rows = [r for r in csv.reader(open(path)) if r[1] == "Bot.Cart.Chassis"]
d0 = math.hypot(float(rows[0][2]) - x, float(rows[0][4]) - z)
d = math.hypot(float(rows[-1][2]) - x, float(rows[-1][4]) - z)
print(f"check: start {d0:.4f} m from ({x}, {z}), end {d:.4f} m (at most {tol})")
assert d0 > 0.5 and d <= tol, (d0, d)
PY
}

check "the example reaches (1, -1) within Tolerance + Speed * Period = 0.05 + 0.3 * 0.01 m"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 10 --out ahead.csv --log commands
ends_near ahead.csv 1 -1 0.053
# Stopped for good: the last commands are (0, 0), so both wheels are commanded 0.
expect_eq "last wheel commands" "$(tail -n 2 ahead.log.csv | cut -d, -f4 | tr '\n' ' ')" "0 0 "

check "a target straight behind: it turns on the spot first (v = Speed max(0, cos e)), then drives"
sed 's|<Target Value="1 -1"/>|<Target Value="-1 0"/>|' "$SCENE" >behind.xml
expect_status 0 "$SIMBOB" run behind.xml --duration 10 --out behind.csv
ends_near behind.csv -1 0 0.053

# bad_scene SED_EXPR OUT: the example with one line changed; LINE gets that line's number.
bad_scene() {
  sed "$1" "$SCENE" >"$2"
  LINE=$(grep -n "$3" "$2" | head -n 1 | cut -d: -f1)
  [[ -n "$LINE" ]] || fail "no line matching $3 in $2"
}

check "Motion must be an RC2DMotionControl"
bad_scene 's|<Motion Ref="Bot.Motion"/>|<Motion Ref="Bot.Pilot"/>|' m.xml '<Motion Ref='
expect_status 65 "$SIMBOB" check m.xml
expect_eq "error" "$(cat "$LAST_ERR")" "m.xml:$LINE: error: RCSimGoToPoint 'Bot.Pilot': parameter 'Motion' must refer to a component implementing RC2DMotionControl, but RCSimGoToPoint 'Bot.Pilot' does not"

check "Body must be a mobile body"
bad_scene 's|<Body Ref="Bot.Cart.Chassis"/>|<Body Ref="Post"/>|; s|<RCGround Key="Ground"/>|<RCGround Key="Ground"/><RCStaticRigidBody Key="Post"/>|' \
  b.xml '<Body Ref="Post"'
expect_status 65 "$SIMBOB" check b.xml
expect_eq "error" "$(cat "$LAST_ERR")" "b.xml:$LINE: error: RCSimGoToPoint 'Bot.Pilot': parameter 'Body' must refer to a mobile body built before this controller, but RCStaticRigidBody 'Post' is not one"

check "Body must be a body at all"
bad_scene 's|<Body Ref="Bot.Cart.Chassis"/>|<Body Ref="Bot.Cart.LeftDrive"/>|' d.xml '<Body Ref='
expect_status 65 "$SIMBOB" check d.xml
expect_eq "error" "$(cat "$LAST_ERR")" "d.xml:$LINE: error: RCSimGoToPoint 'Bot.Pilot': Ref 'Bot.Cart.LeftDrive' names a RCGenericVelControlledDrive, parameter 'Body' needs a BodyComponent"

check "Target must be two numbers"
bad_scene 's|<Target Value="1 -1"/>|<Target Value="1 0 -1"/>|' t.xml '<Target Value='
expect_status 65 "$SIMBOB" check t.xml
expect_eq "error" "$(cat "$LAST_ERR")" "t.xml:$LINE: error: RCSimGoToPoint 'Bot.Pilot': parameter 'Target' must be a point 'x z' on the ground plane (2 numbers, m), got 3 numbers"
say "ok"
