#!/usr/bin/env bash
# Plug-ins that misuse the host or hand simbob what it refuses (docs/plugins.md, docs/testing.md
# "Plug-ins"): plug-ins built here with cc from tests/plugins/misuse_plugins.c, each doing one
# wrong thing at t = 0.5 s. NULL pointers and negative counts given to host calls, a NULL host,
# a non-finite command from a plug-in controller, a non-finite sensor reading, a sensor writing
# past the entries of its `out` and a force so large that the body runs away: each stops the run
# with one line at the scene element naming the plug-in and the call (exit 2, a controller failed), never a crash; the
# partial trajectory is kept, no temporary file is left, and no non-finite reading reaches
# `--log sensors`.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

command -v cc >/dev/null || {
  say "SKIP: no C compiler (cc) to build the test plug-ins"
  exit 77
}

# A free 1 kg box without gravity carrying the plug-in's sensor and actuator, driven by its controller.
cat >misuse.xml <<'EOF'
<Simulation>
  <SceneSettings><Gravity Value="0 0 0"/><MaxTimeStep Value="0.01"/></SceneSettings>
  <ComponentList>
    <RCRobot Key="Bot">
      <Construction>
        <RCConstruction Key="Cart">
          <Body>
            <RCMobileRigidBody Key="Box">
              <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.2"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
              <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
            </RCMobileRigidBody>
          </Body>
          <ChildList>
            <MisuseSensor Key="Sense"/>
            <MisuseActuator Key="Act"/>
          </ChildList>
        </RCConstruction>
      </Construction>
      <ControllerList>
        <MisuseController Key="Ctl">
          <Drive Ref="Bot.Cart.Act"/>
          <Sensor Ref="Bot.Cart.Sense"/>
        </MisuseController>
      </ControllerList>
    </RCRobot>
  </ComponentList>
</Simulation>
EOF
line_of() { grep -n "<$1" misuse.xml | head -n 1 | cut -d: -f1; }
CTL="misuse.xml:$(line_of MisuseController): error: controller 'Bot.Ctl' (plug-in 'misuse', type 'MisuseController')"
SENSE="misuse.xml:$(line_of MisuseSensor): error: sensor 'Bot.Cart.Sense' (plug-in 'misuse', type 'MisuseSensor')"
ACT="misuse.xml:$(line_of MisuseActuator): error: actuator 'Bot.Cart.Act' (plug-in 'misuse', type 'MisuseActuator')"

# misuse DEFINITION MESSAGE: the plug-in built with -DDEFINITION stops a 1 s run with MESSAGE (exit
# 2), the partial trajectory ends at 0.5 s or just before, no temporary file is left behind, and
# the sensor log holds only finite numbers.
misuse() {
  local def=$1 want=$2
  cc -std=c99 -O1 -shared -fPIC -I "$REPO/include" -D"$def" "$REPO/tests/plugins/misuse_plugins.c" -o "$def.so" -lm ||
    fail "cc -D$def"
  expect_status 2 "$SIMBOB" run misuse.xml --duration 1 --plugin "./$def.so" --out "$def.csv" --log sensors -q
  expect_eq "$def: the message" "$(cat "$LAST_ERR")" "$want"
  expect_no_file "$def.csv"
  expect_file "$def.partial.csv"
  local last
  last=$(tail -n 1 "$def.partial.csv" | cut -d, -f1)
  [[ "$last" == "0.49" || "$last" == "0.5" ]] || fail "$def: the partial ends at $last, not at the failure (0.5 s)"
  expect_eq "$def: no temporary files" "$(ls -a | grep -c '\.tmp\.' || true)" 0
  # The sensor log (--log sensors) of the partial run: every reading in it is a finite number.
  expect_file "$def.log.partial.csv"
  python3 - "$def.log.partial.csv" <<'PY' || fail "$def: a non-finite value reached the sensor log"
import csv, math, sys
rows = list(csv.reader(open(sys.argv[1])))
assert len(rows) > 1, "no readings logged"
for row in rows[1:]:
    for cell in row:
        try:
            v = float(cell)
        except ValueError:
            continue
        assert math.isfinite(v), f"{cell!r} in {row}"
PY
}

check "the plug-ins behave until 0.5 s: a clean run of the unmodified plug-in"
cc -std=c99 -O1 -shared -fPIC -I "$REPO/include" "$REPO/tests/plugins/misuse_plugins.c" -o fine.so -lm
expect_status 0 "$SIMBOB" run misuse.xml --duration 1 --plugin ./fine.so --out fine.csv --log sensors -q
expect_file fine.csv

check "NULL pointers and bad counts given to host calls: an error naming the call, never a crash"
misuse READ_NULL "$CTL: read_sensor(1): out is NULL but n is 8"
misuse READ_NEGATIVE "$CTL: read_sensor(1): n is -1: it is the number of entries out has room for"
misuse HOST_NULL "$CTL: read_sensor(): the host is NULL: pass the SimbobHost the callback got"
misuse MOUNT_NULL "$SENSE: mount_pose(): position or quaternion is NULL"
misuse VELOCITY_NULL "$SENSE: body_velocity(): linear or angular is NULL"
misuse RAY_NULL "$SENSE: cast_ray(): origin or direction is NULL"

check "non-finite values from plug-ins are refused, never logged, sent or turned into 0"
misuse COMMAND_NAN "$CTL: set_command(0): the command is not finite (nan)"
misuse COMMAND_INF "$CTL: set_command(0): the command is not finite (-inf)"
misuse READING_NAN "$SENSE: read() gave a reading that is not finite (value = nan)"
misuse READING_INF "$SENSE: read() gave a reading that is not finite (value = inf)"

check "a sensor that writes past the n entries of out: an error, not heap corruption"
misuse OVERFLOW "$SENSE: read() wrote past the end of out (it has room for n = 1 entries)"

check "a huge finite force: the actuator is named, not the body with advice on ERP and CFM"
# 1e300 N on 1 kg for 0.01 s: 1e298 m/s, beyond the runaway limit of 1e6 m/s.
misuse HUGE_FORCE "$ACT: apply() gave a force of 1e+300 N, which alone changes the velocity of its body by 1e+298 m/s in one step of 0.01 s, beyond the runaway limit (1e+06 m/s): the run would diverge"
say "ok: plugins_misuse"
