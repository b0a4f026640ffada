#!/usr/bin/env bash
# Plug-in parameter lists (docs/plugins.md "Limits"): plug-ins built here with cc from
# tests/plugins/param_plugins.c. A number or ref whose name is taken -- by Pose or Period, the
# parameters simbob gives every plug-in periphery or controller, by another number, by a ref,
# or by a name that differs only in case -- is refused when the plug-in registers (65, one line
# naming the plug-in, the type and the parameter), by `types`, `check` and `run` alike, never
# a failure of every scene using the type (70 before). A type with more numbers than the
# documented bound is refused at once; one with as many as the bound loads, and a scene using
# it runs with every number reaching create() in order (the plug-in checks them).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

command -v cc >/dev/null || {
  say "SKIP: no C compiler (cc) to build the test plug-ins"
  exit 77
}
SRC="$REPO/tests/plugins/param_plugins.c"
build() {  # build NAME DEFINITION...: NAME.so from param_plugins.c with -DDEFINITION...
  local name=$1
  shift
  cc -std=c99 -O1 -shared -fPIC -I "$REPO/include" "${@/#/-D}" "$SRC" -o "$name.so" || fail "cc $*"
}

# A robot whose controller list holds $1 (its type's parameters left at their defaults).
scene_with() {
  cat <<EOF
<Simulation>
  <SceneSettings><Gravity Value="0 0 0"/></SceneSettings>
  <ComponentList>
    <RCRobot Key="Bot">
      <Construction>
        <RCConstruction Key="Cart">
          <Body>
            <RCMobileRigidBody Key="Box">
              <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.2"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
            </RCMobileRigidBody>
          </Body>
          <ChildList>$2</ChildList>
        </RCConstruction>
      </Construction>
      <ControllerList>$1</ControllerList>
    </RCRobot>
  </ComponentList>
</Simulation>
EOF
}

# refused DEFINITION TYPE WHY: every command refuses the plug-in with the one line
#   ./DEF.so: error: plug-in 'params' could not register its types: type 'TYPE': WHY
refused() {
  local def=$1 type=$2 why=$3
  build "$def" "$def"
  local want="./$def.so: error: plug-in 'params' could not register its types: type '$type': $why"
  expect_status 65 "$SIMBOB" types --plugin "./$def.so"
  expect_eq "types: $def" "$(cat "$LAST_ERR")" "$want"
  expect_status 65 "$SIMBOB" check scene.xml --plugin "./$def.so"
  expect_eq "check: $def" "$(cat "$LAST_ERR")" "$want"
  expect_status 65 "$SIMBOB" run scene.xml --duration 0.1 --plugin "./$def.so" --out "$def.csv" -q
  expect_eq "run: $def" "$(cat "$LAST_ERR")" "$want"
  expect_no_file "$def.csv"
}

check "names taken by simbob's own parameters, by another parameter, or in another case: 65 at registration"
scene_with "" "" >scene.xml
refused SENSOR_POSE PoseSensor \
  "the number 'Pose' clashes with simbob's own parameter 'Pose' (every plug-in sensor has it): rename it"
refused SENSOR_PERIOD PeriodSensor \
  "the number 'Period' clashes with simbob's own parameter 'Period' (every plug-in sensor has it): rename it"
refused ACTUATOR_POSE PoseActuator \
  "the number 'Pose' clashes with simbob's own parameter 'Pose' (every plug-in actuator has it): rename it"
refused CONTROLLER_PERIOD PeriodController \
  "the number 'Period' clashes with simbob's own parameter 'Period' (every plug-in controller has it): rename it"
refused REF_PERIOD RefPeriodController \
  "the ref 'Period' clashes with simbob's own parameter 'Period' (every plug-in controller has it): rename it"
refused TWO_GAINS TwoGains \
  "the number 'Gain' clashes with the number 'Gain' (parameter names must differ, also in case: INI keys ignore it)"
refused GAIN_CASE GainCase \
  "the number 'gain' clashes with the number 'Gain' (parameter names must differ, also in case: INI keys ignore it)"
refused NUMBER_IS_REF NumberIsRef \
  "the number 'Drive' clashes with the ref 'Drive' (parameter names must differ, also in case: INI keys ignore it)"

check "an actuator may have a number named Period (only sensors and controllers have simbob's)"
build ACTUATOR_PERIOD_OK ACTUATOR_POSE POSE_NAME=\"Period\"
expect_status 0 "$SIMBOB" types --plugin ./ACTUATOR_PERIOD_OK.so
expect_match "the actuator's Period" "$LAST_OUT" "^  Period : Number"

check "more numbers than the bound (10000): refused at once, naming the bound"
build many_10001 NUMBERS=10001
expect_status 65 "$SIMBOB" types --plugin ./many_10001.so
expect_eq "bound message" "$(cat "$LAST_ERR")" \
  "./many_10001.so: error: plug-in 'params' could not register its types: type 'ManyNumbers': more than 10000 numbers and refs (10001 numbers, 0 refs)"

check "as many numbers as the bound: the plug-in loads and a scene using it runs, every number reaching create()"
build many_10000 NUMBERS=10000
scene_with '<ManyNumbers Key="C"><N9999 Value="9999"/></ManyNumbers>' "" >many.xml
expect_status 0 "$SIMBOB" check many.xml --plugin ./many_10000.so
expect_status 0 "$SIMBOB" run many.xml --duration 0.05 --plugin ./many_10000.so --out many.csv -q
expect_file many.csv
# create() fails with "number k is ..." unless number k is k: a wrong value set in the scene shows it reaches it.
scene_with '<ManyNumbers Key="C"><N9999 Value="1"/></ManyNumbers>' "" >wrong.xml
expect_status 2 "$SIMBOB" run wrong.xml --duration 0.05 --plugin ./many_10000.so --out wrong.csv -q
expect_match "the scene's value reached create()" "$LAST_ERR" "create\(\) failed: number 9999 is 1, not 9999$"

check "more quantities than the bound (100000): refused; as many as the bound: loads"
build quantities_100001 QUANTITIES=100001
expect_status 65 "$SIMBOB" types --plugin ./quantities_100001.so
expect_eq "quantity bound message" "$(cat "$LAST_ERR")" \
  "./quantities_100001.so: error: plug-in 'params' could not register its types: type 'ManyQuantities': more than 100000 quantities (100001)"
build quantities_100000 QUANTITIES=100000
expect_status 0 "$SIMBOB" types --plugin ./quantities_100000.so
say "ok: plugins_params"
