#!/usr/bin/env bash
# What a new user reads (issue 18): a mistyped option names the right one; an output in a
# missing folder is named by its own name; counts of one are singular; `types TYPE` prints one
# type; `info` names the git revision; `run` shows check's warnings once (not with -q); a
# command beyond an actuator's limit is reported once per actuator with both numbers; what ODE
# reports while stepping is one warning.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# One ball resting on the ground: one mobile body.
cat >one.xml <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCMobileRigidBody Key="Ball">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value="0.5"/></RCSphereGeom></Geom>
    </RCMobileRigidBody>
  </ComponentList>
</Simulation>
XML

check "a mistyped option names the one meant (64)"
expect_status 64 "$SIMBOB" run one.xml --duraton 1
expect_lines "one line" "$LAST_ERR" 1
expect_match "suggestion" "$LAST_ERR" \
  "^simbob run: error: unknown option '--duraton' \(did you mean '--duration'\?\); simbob run --help lists the options$"
expect_status 64 "$SIMBOB" sweep run m.jsonl --out x --jbos 2
expect_match "sweep run suggestion" "$LAST_ERR" "^simbob sweep run: error: unknown option '--jbos' \(did you mean '--jobs'\?\)"
expect_status 64 "$SIMBOB" check one.xml --zzzzzzzz
expect_match "no suggestion" "$LAST_ERR" "^simbob check: error: unknown option '--zzzzzzzz'; simbob check --help"

check "an output in a missing folder is named by its own name, never the temporary one (73)"
expect_status 73 "$SIMBOB" run one.xml --duration 0.01 --out nodir/one.csv
expect_match "own name" "$LAST_ERR" "^nodir/one.csv: error: cannot create: folder 'nodir' does not exist$"
if grep -q "tmp" "$LAST_ERR"; then fail "the temporary name shows: $(cat "$LAST_ERR")"; fi

check "counts of one are singular"
expect_status 0 "$SIMBOB" run one.xml --duration 0.01 --sample-interval 0.01 --dt 0.01 --out one.csv
expect_match "run summary" "$LAST_ERR" "^simbob: wrote one.csv \(2 samples of 1 body, 1 step in "
expect_status 0 "$SIMBOB" check one.xml
expect_match "check summary" "$LAST_ERR" "^simbob: one.xml: ok \(1 mobile body, 2 geoms, 0 joints\)$"
expect_status 0 "$SIMBOB" batch one.xml -j 1 --duration 0.01 --out-dir b
expect_match "batch summary" "$LAST_OUT" "1 of 1 scenes ok \(1 worker, "

check "types TYPE prints that type alone; an unknown one is a usage error naming the nearest"
expect_status 0 "$SIMBOB" types RCHingeJoint
expect_match "header" "$LAST_OUT" "^RCHingeJoint \(JointComponent"
expect_match "a parameter" "$LAST_OUT" "^  Hinge : PoseComponent"
[[ $(grep -c '^[A-Z]' "$LAST_OUT") -eq 1 ]] || fail "more than one type printed: $(head -n 5 "$LAST_OUT")"
expect_status 0 "$SIMBOB" types rcspheregeom --markdown
expect_match "markdown, any case" "$LAST_OUT" "^## RCSphereGeom \(GeomComponent\)"
expect_status 64 "$SIMBOB" types RCBoxGeom
expect_match "unknown type" "$LAST_ERR" \
  "^simbob: error: unknown component type 'RCBoxGeom' \(did you mean 'RCCuboidGeom' or 'RCMeshGeom'\?\); simbob types lists them all$"

check "info prints the version line of --version, git revision included"
expect_status 0 "$SIMBOB" --version
version=$(head -n 1 "$LAST_OUT")
[[ "$version" == *"(git "* ]] || fail "--version without a revision: $version"
"$SIMBOB" info >info.txt 2>/dev/null || true
expect_eq "info's first line" "$(head -n 1 info.txt)" "$version"

check "run shows check's warnings once before the run; -q does not"
cat >overlap.xml <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCMobileRigidBody Key="A">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value="0.5"/></RCSphereGeom></Geom>
    </RCMobileRigidBody>
    <RCMobileRigidBody Key="B">
      <Pose><RCGlobalCoordinates><Pose Value="0.5 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value="0.5"/></RCSphereGeom></Geom>
    </RCMobileRigidBody>
  </ComponentList>
</Simulation>
XML
expect_status 0 "$SIMBOB" check overlap.xml
grep ': warning: ' "$LAST_ERR" >check_warnings.txt || fail "check gives no warning for overlap.xml"
expect_status 0 "$SIMBOB" run overlap.xml --duration 0.01 --out o.csv
grep ': warning: ' "$LAST_ERR" >run_warnings.txt || true
expect_same_file run_warnings.txt check_warnings.txt
expect_status 0 "$SIMBOB" run overlap.xml --duration 0.01 --out o.csv -q
expect_lines "-q: nothing on stderr" "$LAST_ERR" 0

check "a command beyond MaxVelocity is reported once per actuator with both numbers"
# Forward at 0.2 m/s on wheels of r = 0.1 m asks 2 rad/s of each wheel; at MaxVelocity 1 rad/s
# (the default) each is clamped once, when the schedule's first command comes.
expect_status 0 "$SIMBOB" run "$SCENES/two_wheel_robot.xml" --duration 1 --out robot.csv \
  --set Bot.Cart.LeftDrive.MaxVelocity=1 --set Bot.Cart.RightDrive.MaxVelocity=1
grep 'clamped' "$LAST_ERR" >clamps.txt || fail "no clamp notice: $(cat "$LAST_ERR")"
expect_lines "one notice per actuator" clamps.txt 2
expect_match "left" clamps.txt "two_wheel_robot.xml:85: warning: actuator 'Bot.Cart.LeftDrive': command velocity 2 rad/s is beyond MaxVelocity 1 rad/s, clamped \(1 command clamped in this run\)$"
expect_match "right" clamps.txt "two_wheel_robot.xml:90: warning: actuator 'Bot.Cart.RightDrive': command velocity 2 rad/s"
check "the scene as shipped (MaxVelocity 10) clamps nothing"
expect_status 0 "$SIMBOB" run "$SCENES/two_wheel_robot.xml" --duration 1 --out robot.csv
if grep -q 'clamped' "$LAST_ERR"; then fail "clamp notice without a clamp: $(cat "$LAST_ERR")"; fi

check "what ODE reports while stepping is one warning with its count, and a summary field"
# The box stack under Solver Step without constraint force mixing: ODE's LCP solver says
# "LCP internal error" many times; ODE alone would print each on lines of its own.
sed 's#<SceneSettings>#<SceneSettings><Solver Value="Step"/><CFM Value="0"/>#' "$SCENES/box_stack.xml" >step.xml
expect_status 0 "$SIMBOB" run step.xml --duration 1 --out step.csv
if grep -q 'ODE Message' "$LAST_ERR"; then fail "ODE's own lines on stderr: $(head -3 "$LAST_ERR")"; fi
grep 'ODE reported' "$LAST_ERR" >ode.txt || fail "no warning of ODE's messages: $(cat "$LAST_ERR")"
expect_lines "one warning" ode.txt 1
expect_match "count, first and advice" ode.txt \
  "^step.xml: warning: ODE reported [0-9]+ problems while stepping; the first, in the step to t = [0-9.e-]+ s: 'ODE message 3: LCP internal error, .*'\. Solver Step could not meet the constraints exactly there .* a CFM above 0 \(1e-5, say\) or Solver QuickStep avoids it$"
count=$(json_get step.json "j['physics_messages']['count']")
expect_match "the summary's count is the warning's" ode.txt "ODE reported $count problems"
check "the scene as shipped (QuickStep) gives ODE nothing to report"
expect_status 0 "$SIMBOB" run "$SCENES/box_stack.xml" --duration 1 --out stack.csv
if grep -q 'ODE' "$LAST_ERR"; then fail "a report without a message: $(cat "$LAST_ERR")"; fi
if grep -q physics_messages stack.json; then fail "stack.json has physics_messages"; fi

say "OK"
