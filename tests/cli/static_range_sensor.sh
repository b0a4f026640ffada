#!/usr/bin/env bash
# Range sensors on a static mount (docs/sensors.md): a ray skips only the geoms of the sensor's
# own body and of the bodies joined to it, for a sensor on a fixed post as on a mobile mast. In a
# room of four static walls, a post (a static body whose own box encloses the sensors' origin)
# carries an RCRangeSensor, a 4-ray 360-degree RCLaserScanner and the example plug-in's
# BeamSensor (cast_ray). Each ray reads the analytic distance from the post's axis to the inner
# face of the wall it points at, or to the face of a free crate in its way; the post's own box
# and a flag hinged to the post (in the way of the -X ray) are not seen. Before, a static mount
# skipped every static geom and read MaxRange everywhere.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# wall KEY X Z WIDTH DEPTH: a static box 2 m high centred at (X, 1, Z).
wall() {
  cat <<EOF
    <RCStaticRigidBody Key="$1">
      <Pose><RCGlobalCoordinates><Pose Value="$2 1 $3 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="$4"/><Height Value="2"/><Depth Value="$5"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
EOF
}
# The room's inner faces: x = 3 (East), x = -2 (West), z = -1.5 (North), z = 2.5 (South).
{
  cat <<'EOF'
<Simulation>
  <SceneSettings><Gravity Value="0 0 0"/><MaxTimeStep Value="0.01"/></SceneSettings>
  <ComponentList>
EOF
  wall East 3.1 0.5 0.2 5
  wall West -2.1 0.5 0.2 5
  wall North 0.5 -1.6 6 0.2
  wall South 0.5 2.6 6 0.2
  cat <<'EOF'
    <RCMobileRigidBody Key="Crate">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 1.1 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="0.4"/><Height Value="0.4"/><Depth Value="0.4"/></RCCuboidGeom></Geom>
    </RCMobileRigidBody>
    <RCRobot Key="Fixed">
      <Construction>
        <RCConstruction Key="Mount">
          <Body>
            <RCStaticRigidBody Key="Post">
              <Pose><RCGlobalCoordinates><Pose Value="0 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
              <Geom><RCCuboidGeom><Width Value="0.3"/><Height Value="1"/><Depth Value="0.3"/></RCCuboidGeom></Geom>
            </RCStaticRigidBody>
          </Body>
          <ChildList>
            <RCHingeJoint Key="FlagHinge">
              <Pose><RCLocalCoordinates><Pose Value="-1 0 0 0 0 0"/></RCLocalCoordinates></Pose>
              <Body>
                <RCMobileRigidBody Key="Flag">
                  <Pose Macro="Origin"/>
                  <Geom><RCCuboidGeom><Width Value="0.1"/><Height Value="0.4"/><Depth Value="0.4"/></RCCuboidGeom></Geom>
                </RCMobileRigidBody>
              </Body>
            </RCHingeJoint>
            <RCRangeSensor Key="Range"><MaxRange Value="10"/></RCRangeSensor>
            <RCLaserScanner Key="Scan">
              <Rays Value="4"/><FieldOfView Value="360"/><MaxRange Value="10"/>
            </RCLaserScanner>
            BEAM
          </ChildList>
        </RCConstruction>
      </Construction>
    </RCRobot>
  </ComponentList>
</Simulation>
EOF
} >room.in
sed 's|BEAM||' room.in >room.xml

# expect_readings LOG KEY=VALUE...: at t = 0, each "component/quantity" of the sensor log reads
# VALUE within 1e-9 m (ODE's ray against a box is exact to rounding; no noise or resolution).
expect_readings() {
  python3 - "$@" <<'PY' || fail "readings"
import csv, sys
got = {f"{r['component']}/{r['quantity']}": float(r["value"]) for r in csv.DictReader(open(sys.argv[1]))
       if float(r["time"]) == 0}
for item in sys.argv[2:]:
    key, want = item.split("=")
    print(f"check: {key} = {got.get(key)} (expected {want} m)")
    if key not in got or abs(got[key] - float(want)) > 1e-9:
        sys.exit(f"FAIL: {key}: got {got.get(key)}, expected {want}")
PY
}

check "a fixed range sensor and scanner read the static walls, the crate, not their post or the flag hinged to it"
expect_status 0 "$SIMBOB" run room.xml --duration 0.02 --out room.csv --log sensors -q
# The range sensor looks along -Z: the North wall, 1.5 m. Scanner ray k at a_k = -180 + 90 k deg
# looks along (-sin a_k, 0, -cos a_k): +Z (the crate's face at z = 0.9), +X (East, 3 m), -Z
# (North, 1.5 m), -X (the flag at x = -1 is joined to the post: West, 2 m).
expect_readings room.log.csv Fixed.Mount.Range/distance=1.5 \
  Fixed.Mount.Scan/range0=0.9 Fixed.Mount.Scan/range1=3 Fixed.Mount.Scan/range2=1.5 Fixed.Mount.Scan/range3=2

check "the same readings when the sensors are read on 3 threads (lib/physics/rays.cpp's parallel path)"
expect_status 0 "$SIMBOB" run room.xml --duration 0.02 --threads 3 --out room3.csv --log sensors -q
expect_same_file room.log.csv room3.log.csv
expect_same_file room.csv room3.csv

if command -v cc >/dev/null; then
  check "a plug-in sensor's cast_ray from the same post reads the same wall"
  cc -std=c99 -shared -fPIC -I "$REPO/include" "$REPO/examples/plugins/beam_sensor.c" -o beam.so
  sed 's|BEAM|<BeamSensor Key="Beam"><MaxRange Value="10"/></BeamSensor>|' room.in >beam.xml
  expect_status 0 "$SIMBOB" run beam.xml --duration 0.02 --plugin ./beam.so --out beam.csv --log sensors -q
  expect_readings beam.log.csv Fixed.Mount.Beam/distance=1.5 Fixed.Mount.Range/distance=1.5
else
  say "note: no C compiler (cc): the plug-in's cast_ray is not checked here"
fi
say "ok: static_range_sensor"
