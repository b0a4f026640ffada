#!/usr/bin/env bash
# `simbob run --log joints,sensors,commands`: the run log beside the trajectory, sampled at the
# trajectory's times, with analytic commands, joint angles that agree with the trajectory, a
# proximity sensor that switches once, readings of every sensor kind by name, usage errors, and a partial log kept by a failed run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

check "flywheel: commands are sin(2 pi Variation t / 60), the joint angle is the trajectory's"
cp "$SCENES/flywheel.xml" fly.xml
expect_status 0 "$SIMBOB" run fly.xml --duration 3 --sample-interval 0.05 --out fly.csv --log commands,joints --json
expect_file fly.log.csv
python3 - fly.xml fly.csv fly.log.csv fly.json <<'PY'
import csv, json, math, re, sys
scene, traj, log, summ = sys.argv[1:]
V = float(re.search(r'<Variation Value="([^"]+)"', open(scene).read()).group(1))
rows = list(csv.reader(open(log)))
assert rows[0] == ["time", "component", "quantity", "value"], rows[0]
cmd, pos = {}, {}
for t, comp, q, v in rows[1:]:
    if (comp, q) == ("Bot.Base.Motor", "command"): cmd[t] = float(v)
    elif (comp, q) == ("Bot.Base.Axle", "pos"): pos[t] = float(v)
    elif (comp, q) == ("Bot.Base.Axle", "vel"): pass
    else: sys.exit(f"unexpected row {comp},{q}")
tr = list(csv.reader(open(traj)))[1:]
times = [r[0] for r in tr]
# Same sample times, as the same text.
assert list(cmd) == times == list(pos), (list(cmd)[:5], times[:5])
assert len(times) == 61, len(times)
# The controller runs every 1 ms, so at every sample time (a multiple of 1 ms) it has just set
# sin(2 pi V t / 60). Both sides compute a sine of the same double t; only the order of the
# multiplications differs (a few ulp), so 1e-9 is far above rounding and far below any wrong
# time (one Period off changes the value by up to 2 pi V / 60 * 1e-3 = 3e-3).
worst = max(abs(cmd[t] - math.sin(2 * math.pi * V * float(t) / 60)) for t in times)
assert worst < 1e-9, worst
# The flywheel turns about +Y from its start pose: angle = 2 atan2(qrel_y, qrel_w) of
# q(t) * conj(q(0)), compared modulo 2 pi (the joint's position is the total angle). Both come from the
# same body orientation, so they agree to rounding (1e-9).
def mul(a, b):
    aw, ax, ay, az = a; bw, bx, by, bz = b
    return (aw*bw - ax*bx - ay*by - az*bz, aw*bx + ax*bw + ay*bz - az*by,
            aw*by - ax*bz + ay*bw + az*bx, aw*bz + ax*by - ay*bx + az*bw)
q0 = tuple(float(x) for x in tr[0][5:9]); c0 = (q0[0], -q0[1], -q0[2], -q0[3])
worst_angle = 0.0
for r in tr:
    qr = mul(tuple(float(x) for x in r[5:9]), c0)
    a = 2 * math.atan2(qr[2], qr[0])
    a = math.atan2(math.sin(a), math.cos(a))
    d = abs(a - pos[r[0]]); d = min(d, 2 * math.pi - d)
    worst_angle = max(worst_angle, d)
assert worst_angle < 1e-9, worst_angle
# And the angle is the analytic one, (t - sin(pi t)/pi)/2, to the scene's 1 ms Euler step.
t = 3.0
assert abs(pos["3"] - (t - math.sin(math.pi * t) / math.pi) / 2) < 5e-3, pos["3"]
assert json.load(open(summ))["run_log"] == "fly.log.csv"
print(f"flywheel: {len(times)} samples, command error {worst:.1e}, angle error {worst_angle:.1e}")
PY

check "the same run gives the same log bytes"
expect_status 0 "$SIMBOB" run fly.xml --duration 3 --sample-interval 0.05 --out fly2.csv --log commands,joints --log-out again.csv
expect_same_file fly.log.csv again.csv

check "wall stop: the proximity sensor goes from 0 to 1 once and stays 1"
cp "$SCENES/wall_stop_robot.xml" wall.xml
expect_status 0 "$SIMBOB" run wall.xml --duration 10 --out wall.csv --log sensors
python3 - wall.log.csv <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))[1:]
keys = {r[1] for r in rows}
assert keys == {"Bot.Cart.Front"}, keys
seq = [r[3] for r in rows]
assert set(seq) <= {"0", "1"}, set(seq)
assert seq[0] == "0" and seq[-1] == "1", (seq[0], seq[-1])
changes = sum(1 for a, b in zip(seq, seq[1:]) if a != b)
assert changes == 1, changes
print(f"wall stop: touching from t={rows[seq.index('1')][0]} s")
PY

check "sensors of every kind: each quantity of each reading, by name, with analytic values"
cat >sensed.xml <<'XML'
<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/><Solver Value="Step"/></SceneSettings>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="2.5 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="1"/><Height Value="1"/><Depth Value="10"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Pose><RCGlobalCoordinates><Pose Value="0 0.05 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
      </RCMobileRigidBody></Body>
      <ChildList>
        <RCRangeSensor Key="Front">
          <Pose><RCLocalCoordinates><Pose Value="0 0 0 0 -90 0"/></RCLocalCoordinates></Pose>
          <MaxRange Value="3"/>
        </RCRangeSensor>
        <RCLaserScanner Key="Lidar"><Rays Value="3"/><FieldOfView Value="180"/><MaxRange Value="3"/></RCLaserScanner>
        <RCImuSensor Key="Imu"/>
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>
XML
expect_status 0 "$SIMBOB" run sensed.xml --duration 0.5 --sample-interval 0.1 --out sensed.csv --log sensors
python3 - sensed.log.csv <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))[1:]
names = []
for t, comp, q, v in rows:
    if t == "0": names.append((comp, q))
assert names == [("Bot.Front", "distance"), ("Bot.Lidar", "range0"), ("Bot.Lidar", "range1"),
                 ("Bot.Lidar", "range2"), ("Bot.Imu", "ax"), ("Bot.Imu", "ay"), ("Bot.Imu", "az"),
                 ("Bot.Imu", "gx"), ("Bot.Imu", "gy"), ("Bot.Imu", "gz")], names
last = {(c, q): float(v) for t, c, q, v in rows if t == "0.5"}
# The range sensor looks along +X (local -Z turned -90 degrees about Y) at the wall's face, x = 2.
assert abs(last[("Bot.Front", "distance")] - 2) < 1e-6, last
# The scanner looks along -Z: its rays point to +X (right, range0), -Z, -X (left): the wall, then
# nothing within 3 m.
assert abs(last[("Bot.Lidar", "range0")] - 2) < 1e-6, last
assert last[("Bot.Lidar", "range1")] == 3 and last[("Bot.Lidar", "range2")] == 3, last
# At rest on the ground: +g upwards.
assert abs(last[("Bot.Imu", "ay")] - 9.81) < 1e-3 and abs(last[("Bot.Imu", "ax")]) < 1e-3, last
print("sensors:", len(names), "quantities")
PY

check "usage errors: unknown word, --log-out without --log, --out - without --log-out"
expect_status 64 "$SIMBOB" run fly.xml --duration 1 --out x.csv --log joints,torques
expect_lines "stderr" "$LAST_ERR" 1
expect_match "names the word" "$LAST_ERR" \
  "^simbob: error: --log: unknown word 'torques' \\(give a comma list of joints, sensors, commands\\)$"
expect_status 64 "$SIMBOB" run fly.xml --duration 1 --out x.csv --log joints,
expect_match "empty word after a comma" "$LAST_ERR" "unknown word ''"
expect_status 64 "$SIMBOB" run fly.xml --duration 1 --out x.csv --log-out y.csv
expect_match "--log-out alone" "$LAST_ERR" "^simbob: error: --log-out needs --log \\(what to log\\)$"
expect_status 64 "$SIMBOB" run fly.xml --duration 1 --out - --log joints
expect_match "stream out" "$LAST_ERR" "needs --log-out FILE"
expect_no_file x.csv
expect_no_file x.log.csv

check "the log never overwrites the scene"
cp fly.xml keep.xml
expect_status 64 "$SIMBOB" run fly.xml --duration 1 --out z.csv --log joints --log-out fly.xml
expect_match "says why" "$LAST_ERR" \
  "^simbob: error: --log-out fly.xml is the scene fly.xml: an output must not overwrite an input$"
expect_same_file fly.xml keep.xml
expect_no_file z.csv

check "a failed run keeps the log so far in NAME.log.partial.csv and leaves NAME.log.csv alone"
# The flywheel scene plus a ball thrown at 1e7 m/s: the run diverges in the first step.
python3 - fly.xml >bad.xml <<'PY'
import sys
s = open(sys.argv[1]).read()
rocket = """    <RCMobileRigidBody Key="Rocket">
      <Pose><RCGlobalCoordinates><Pose Value="5 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Motion><RCGlobalMotion><LinVelocity Value="0 1e7 0"/></RCGlobalMotion></Motion>
      <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
      <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
    </RCMobileRigidBody>
"""
print(s.replace("  </ComponentList>", rocket + "  </ComponentList>"), end="")
PY
echo "old log" >bad.log.csv
expect_status 1 "$SIMBOB" run bad.xml --duration 1 --out bad.csv --log joints,commands
expect_match "diverged" "$LAST_ERR" "body 'Bot.Rocket' diverged|body 'Rocket' diverged"
expect_match "points to the partial log" "$LAST_ERR" "kept the run log so far in bad.log.partial.csv"
expect_file bad.log.partial.csv
expect_eq "untouched old log" "$(cat bad.log.csv)" "old log"
expect_eq "partial log" "$(cat bad.log.partial.csv)" "time,component,quantity,value
0,Bot.Base.Axle,pos,0
0,Bot.Base.Axle,vel,0
0,Bot.Base.Motor,command,0"
say "ok"
