#!/usr/bin/env bash
# Plug-ins (docs/plugins.md): the example square_driver.so (C++ through simbob/plugin.hpp over
# the C ABI) adds the controller type SquareDriver to the registry (types, check, run), given by
# --plugin or found in the global setting ExtensionFolder; examples/plugins/square_robot.xml
# moves as its law says, the same bytes twice. A wrong ABI version, a plug-in of the old C++ ABI
# (simbob_plugin_v1), a type name that is taken, a library without the entry point, an
# incomplete type and a missing file are one-line errors naming the file (65, 65, 65, 65, 65,
# 66); plug-in code that fails (create, act, a ref out of range, a sensor's read, a C++
# exception) stops the run with one line at the scene element (2, a controller failed; the
# partial kept).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

PLUGINS="$(dirname "$SIMBOB")/plugins"
SQUARE="$PLUGINS/square_driver.so"
SCENE="$REPO/examples/plugins/square_robot.xml"
if [[ ! -f "$SQUARE" || ! -f "$PLUGINS/bad_bad_abi.so" ]]; then
  say "SKIP: the plug-ins are not built in $PLUGINS (cmake --build builds them with simbob)"
  exit 77
fi

check "without the plug-in the type is unknown; with it, types lists it and check is clean"
expect_status 65 "$SIMBOB" check "$SCENE"
expect_match "unknown type" "$LAST_ERR" "unknown component type 'SquareDriver'|'SquareDriver'.*unknown"
expect_status 0 "$SIMBOB" types --plugin "$SQUARE"
expect_match "types lists SquareDriver" "$LAST_OUT" "SquareDriver"
expect_match "with its parameters" "$LAST_OUT" "WheelSpeed"
expect_status 0 "$SIMBOB" check "$SCENE" --plugin "$SQUARE"

check "the square robot moves as SquareDriver's law says, the same bytes twice"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 6 --plugin "$SQUARE" --out sq1.csv -q
expect_status 0 "$SIMBOB" run "$SCENE" --duration 6 --plugin "$SQUARE" --out sq2.csv -q
expect_same_file sq1.csv sq2.csv

check "batch hands its --plugin to its workers: the same bytes as run"
expect_status 0 "$SIMBOB" batch "$SCENE" --duration 6 --plugin "$SQUARE" --out-dir sqb -q
expect_same_file sq1.csv sqb/square_robot.csv
python3 - sq1.csv <<'PY' || fail "square robot motion"
import csv, math, sys
rows = {}
for r in csv.DictReader(open(sys.argv[1])):
    if r["body"] == "Bot.Cart.Chassis":
        rows[round(float(r["time"]), 6)] = [float(r[k]) for k in ("x", "y", "z", "qw", "qx", "qy", "qz")]
def heading(p):
    w, x, y, z = p[3:7]
    return math.atan2(-2 * (x * z - w * y), 1 - 2 * (y * y + z * z))
def near(what, got, want, tol):
    ok = abs(got - want) <= tol
    print(f"check: {what} = {got:.6f} (expected {want:.6f} +- {tol})")
    if not ok:
        sys.exit(f"FAIL: {what}")
def dist(a, b):
    return math.hypot(b[0] - a[0], b[2] - a[2])
# Side 1 (0-2 s): r * WheelSpeed = 0.1 * 2 = 0.2 m/s along +X once up to speed (the wheels
# start at rest): x(2) - x(1) = 0.2 m, straight ahead.
near("x gained over [1 s, 2 s] (m)", rows[2.0][0] - rows[1.0][0], 0.2, 1e-3)
near("heading on the first side (rad)", heading(rows[2.0]), 0.0, 1e-6)
# Corner (2-3.49 s): turning left at 2 r WheelSpeed / track = 0.4 / 0.38 rad/s; over
# [2.5 s, 3.3 s] that is 0.842 rad. The round tyres touch the ground on the wheels' mid-planes,
# 0.38 m apart, so only the wheels' spin-up after 2 s (over by 2.5 s) and the caster's drag
# stand between the law and the run: 1e-4 rad, as in tests/robot/two_wheel_test.cpp.
want = 0.8 * 0.4 / 0.38
near("heading gained over [2.5 s, 3.3 s] (rad)", heading(rows[3.3]) - heading(rows[2.5]), want, 1e-4)
# Side 2 (3.49-5.49 s): straight again at 0.2 m/s, now to the left of the first side (-Z):
# 0.28 m over [4 s, 5.4 s] with the heading held.
near("distance over [4 s, 5.4 s] (m)", dist(rows[4.0], rows[5.4]), 0.28, 2e-3)
near("heading held on the second side (rad)", heading(rows[5.4]) - heading(rows[4.0]), 0.0, 1e-6)
near("the second side runs towards -Z (m)", rows[5.4][2] - rows[4.0][2], -0.28, 0.02)
PY

check "ExtensionFolder in the global settings loads every .so in it (relative to the settings file)"
mkdir -p conf/ext
cp "$SQUARE" conf/ext/
printf 'ExtensionFolder = ext\n' >conf/settings.ini
expect_status 0 "$SIMBOB" check "$SCENE" --settings conf/settings.ini
printf 'ExtensionFolder = missing\n' >conf/missing.ini
expect_status 66 "$SIMBOB" check "$SCENE" --settings conf/missing.ini
expect_match "missing folder" "$LAST_ERR" "^conf/missing: error: cannot read ExtensionFolder: "

check "the same plug-in twice: its type name is taken (65)"
expect_status 65 "$SIMBOB" check "$SCENE" --plugin "$SQUARE" --settings conf/settings.ini
expect_eq "duplicate message" "$(cat "$LAST_ERR")" \
  "conf/ext/square_driver.so: error: plug-in 'square_driver' could not register its types: component type 'SquareDriver': the name 'SquareDriver' is already registered"

check "a plug-in that redefines a built-in type (65)"
expect_status 65 "$SIMBOB" types --plugin "$PLUGINS/bad_duplicate.so"
expect_eq "built-in duplicate message" "$(cat "$LAST_ERR")" \
  "$PLUGINS/bad_duplicate.so: error: plug-in 'duplicate' could not register its types: component type 'RCDriveTest': the name 'RCDriveTest' is already registered"

check "a wrong ABI version (65)"
expect_status 65 "$SIMBOB" run "$SCENE" --duration 1 --plugin "$PLUGINS/bad_bad_abi.so" --out x.csv
expect_eq "ABI message" "$(cat "$LAST_ERR")" \
  "$PLUGINS/bad_bad_abi.so: error: plug-in ABI version 999, but this simbob loads version 3 (rebuild it against this simbob's simbob/plugin_c.h)"
expect_no_file x.csv

check "a plug-in of the old C++ ABI, entry point simbob_plugin_v1 (65)"
expect_status 65 "$SIMBOB" check "$SCENE" --plugin "$PLUGINS/bad_v1.so"
expect_eq "v1 message" "$(cat "$LAST_ERR")" \
  "$PLUGINS/bad_v1.so: error: built for plug-in ABI 1 (the C++ ABI, entry point simbob_plugin_v1), which this simbob no longer loads: rebuild it against simbob/plugin_c.h or simbob/plugin.hpp (docs/plugins.md)"

check "a library without the entry point (65)"
expect_status 65 "$SIMBOB" check "$SCENE" --plugin "$PLUGINS/bad_no_entry.so"
expect_eq "no entry message" "$(cat "$LAST_ERR")" \
  "$PLUGINS/bad_no_entry.so: error: not a simbob plug-in: it has no entry point simbob_plugin_v2 (see simbob/plugin_c.h)"

check "an incomplete type: a sensor without read (65)"
expect_status 65 "$SIMBOB" types --plugin "$PLUGINS/bad_no_read.so"
expect_eq "no read message" "$(cat "$LAST_ERR")" \
  "$PLUGINS/bad_no_read.so: error: plug-in 'bad' could not register its types: type 'BadSensor': a sensor needs read"

check "a file that is not there or not a library (66)"
expect_status 66 "$SIMBOB" check "$SCENE" --plugin nowhere.so
expect_match "dlopen message" "$LAST_ERR" "^nowhere.so: error: cannot load the plug-in: .*nowhere.so: cannot open shared object file"
printf 'not an ELF file\n' >fake.so
expect_status 66 "$SIMBOB" check "$SCENE" --plugin fake.so
expect_match "not ELF message" "$LAST_ERR" "^fake.so: error: cannot load the plug-in: "
check "plug-in code that fails: an error naming the plug-in, never a crash (2, a controller failed, during a run with the partial kept)"
sed '/<SquareDriver/,/<\/SquareDriver>/c\        <BadController Key="Bad"/>' "$SCENE" >bad_robot.xml
grep -q BadController bad_robot.xml || fail "the controller was not replaced"
BLINE=$(grep -n '<BadController' bad_robot.xml | cut -d: -f1)
WHO="bad_robot.xml:$BLINE: error: controller 'Bot.Bad' (plug-in 'bad', type 'BadController')"
# bad_run NAME STATUS: runs bad_robot.xml for 1 s with bad_NAME.so into NAME.csv.
bad_run() {
  expect_status "$2" "$SIMBOB" run bad_robot.xml --duration 1 --plugin "$PLUGINS/bad_$1.so" --out "$1.csv" -q
  expect_no_file "$1.csv"
  expect_no_file "$1.json"
  expect_eq "no temporary files after $1" "$(ls -a | grep -c '\.tmp\.' || true)" 0
}
bad_run create_fails 2
expect_eq "create message" "$(cat "$LAST_ERR")" "$WHO: create() failed: create failed on purpose"
expect_file create_fails.partial.csv
bad_run throw_create 2
expect_eq "C++ constructor message" "$(cat "$LAST_ERR")" "$WHO: create() failed: constructor failed on purpose"
for name in act_fails throw_act bad_index neg_index; do
  bad_run $name 2
  expect_file $name.partial.csv
  last=$(tail -n 1 $name.partial.csv | cut -d, -f1)
  expect_eq "$name: the partial ends at the failure" "$last" "0.5"
done
expect_eq "set_command(-1) message" "$(cat "$LAST_ERR")" \
  "$WHO: set_command(-1): there is no ref -1 (the type has 0)"
bad_run bad_index 2
expect_eq "set_command(99999) message" "$(cat "$LAST_ERR")" \
  "$WHO: set_command(99999): there is no ref 99999 (the type has 0)"
bad_run act_fails 2
expect_eq "act message" "$(cat "$LAST_ERR")" "$WHO: act() failed: act failed on purpose at t=0.5"
bad_run throw_act 2
expect_eq "C++ act message" "$(cat "$LAST_ERR")" "$WHO: act() failed: act failed on purpose"
bad_run controller_ray 2
expect_eq "cast_ray from a controller" "$(cat "$LAST_ERR")" \
  "$WHO: cast_ray() is for sensors and actuators, not controllers"

check "a plug-in sensor whose read fails stops the run at its scene element (2)"
sed 's|<RCGenericVelControlledDrive Key="LeftDrive">|<BadSensor Key="Bad"><Period Value="0.1"/></BadSensor>\n&|' "$SCENE" >bad_sensor.xml
SLINE=$(grep -n '<BadSensor' bad_sensor.xml | cut -d: -f1)
expect_status 2 "$SIMBOB" run bad_sensor.xml --duration 1 --plugin "$SQUARE" --plugin "$PLUGINS/bad_sensor_fails.so" --out s.csv -q
expect_eq "read message" "$(cat "$LAST_ERR")" \
  "bad_sensor.xml:$SLINE: error: sensor 'Bot.Cart.Bad' (plug-in 'bad', type 'BadSensor'): read() failed: read failed on purpose at t=0.5"
# Nothing acts on the failed reading: the run stops before the instant's grants (and samples).
expect_eq "the partial ends before the failure" "$(tail -n 1 s.partial.csv | cut -d, -f1)" "0.49"

check "a plug-in actuator whose force is not finite stops the run at its scene element (2)"
sed 's|<RCGenericVelControlledDrive Key="LeftDrive">|<BadActuator Key="Bad"/>\n&|' "$SCENE" >bad_actuator.xml
ALINE=$(grep -n '<BadActuator' bad_actuator.xml | cut -d: -f1)
expect_status 2 "$SIMBOB" run bad_actuator.xml --duration 1 --plugin "$SQUARE" --plugin "$PLUGINS/bad_actuator_nan.so" --out a.csv -q
expect_eq "apply message" "$(cat "$LAST_ERR")" \
  "bad_actuator.xml:$ALINE: error: actuator 'Bot.Cart.Bad' (plug-in 'bad', type 'BadActuator'): apply() gave a force or torque that is not finite"
say "ok: plugins"
