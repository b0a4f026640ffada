#!/usr/bin/env bash
# Documented limits hold at the command line (issue #10, items 9 and 16): every time option has
# a range checked before the run (64); batch -j, manifests, trajectories and far-away bodies are
# refused with the documented status and a message that names the problem.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
P="$SCENES/pendulum.xml"

# ---------------------------------------------------------------- 9: time options
# expect_time_refused OPTION VALUE MESSAGE-VALUE
expect_time_refused() {
  check "64: $1 $2"
  expect_status 64 "$SIMBOB" run "$P" --duration 1 --out t.csv "$1" "$2"
  expect_eq "$1 $2: stderr" "$(cat "$LAST_ERR")" "simbob: error: $1 must be between 1e-9 and 1e9 s, got $3"
  expect_no_file t.csv
}
expect_time_refused --dt 9.3e9 9.3e+09
expect_time_refused --dt 1e300 1e+300
expect_time_refused --dt 1e-10 1e-10
expect_time_refused --sample-interval 1e10 1e+10
expect_time_refused --sample-interval 0 0
expect_time_refused --duration 1e-10 1e-10
expect_time_refused --duration 2e9 2e+09
check "the bounds themselves are accepted, and the summary reports what was run"
expect_status 0 "$SIMBOB" run "$P" --duration 1e-4 --dt 1e-9 --sample-interval 1e9 --out b.csv
expect_eq "dt and status" "$(json_get b.json '(j["dt"], j["status"], j["steps"] > 90000)')" "(1e-09, 'completed', True)"
check "batch checks its time options the same way"
expect_status 64 "$SIMBOB" batch "$P" --dt 1e300 --out-dir bo
expect_eq "stderr" "$(cat "$LAST_ERR")" "simbob: error: --dt must be between 1e-9 and 1e9 s, got 1e+300"
check "a scene whose MaxTimeStep does not fit the clock is 65"
sed 's|<MaxTimeStep Value="0.001"/>|<MaxTimeStep Value="1e-12"/><MinTimeStep Value="1e-13"/>|' "$P" >tiny_step.xml
grep -q 'MaxTimeStep Value="1e-12"' tiny_step.xml || fail "could not make tiny_step.xml"
expect_status 65 "$SIMBOB" run tiny_step.xml --duration 1 --out ts.csv
expect_match "message" "$LAST_ERR" "^tiny_step.xml: error: SceneSettings MaxTimeStep 1e-12 s is outside 1e-9 to 1e9 s \(give --dt\)$"

# ---------------------------------------------------------------- 16: batch
check "64: batch -j 0 and -j -1"
expect_status 64 "$SIMBOB" batch "$P" -j 0 --out-dir bo
expect_match "message" "$LAST_ERR" "jobs"
expect_status 64 "$SIMBOB" batch "$P" -j -1 --out-dir bo
expect_no_file bo
check "66: batch --manifest naming a directory"
mkdir mdir
expect_status 66 "$SIMBOB" batch --manifest mdir --out-dir bo
expect_eq "stderr" "$(cat "$LAST_ERR")" "mdir: error: cannot read manifest: is a directory"
check "65: a bad manifest line is named with its problem"
printf '# scenes\n%s --duration 1\n%s --bogus 3\n' "$P" "$P" >bad.manifest
expect_status 65 "$SIMBOB" batch --manifest bad.manifest --out-dir bo
expect_eq "stderr" "$(cat "$LAST_ERR")" \
  "bad.manifest:3: error: run options: The following arguments were not expected: 3 --bogus"
printf '%s --dt 1e300\n' "$P" >range.manifest
expect_status 65 "$SIMBOB" batch --manifest range.manifest --out-dir bo
expect_eq "stderr" "$(cat "$LAST_ERR")" "range.manifest:1: error: --dt must be between 1e-9 and 1e9 s, got 1e+300"
expect_no_file bo

# ---------------------------------------------------------------- 16: compare inputs
check "65: compare refuses a zero quaternion and a NUL in a body key"
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A,0,1,0,1,0,0,0\n' >good.csv
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A,0,1,0,0,0,0,0\n' >zero.csv
expect_status 65 "$SIMBOB" compare zero.csv good.csv
expect_eq "stderr" "$(cat "$LAST_ERR")" "zero.csv:2: error: quaternion qw qx qy qz is zero: not a rotation"
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,A\0B,0,1,0,1,0,0,0\n' >nul.csv
expect_status 65 "$SIMBOB" compare good.csv nul.csv
expect_eq "stderr" "$(cat "$LAST_ERR")" "nul.csv:2: error: body key contains a NUL byte"

# ---------------------------------------------------------------- 16: far-away bodies
check "65: a body 1e8 m away fails check and run, before any step"
cat >far.xml <<'XML'
<Simulation><ComponentList>
<RCMobileRigidBody Key="Far">
<Pose><RCGlobalCoordinates><Pose Value="1e8 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
<Geom><RCSphereGeom/></Geom></RCMobileRigidBody>
</ComponentList></Simulation>
XML
want="far.xml:2: error: body 'Far' starts 1e+08 m from the origin, beyond the 1e+06 m at which a run stops as diverged; move the scene nearer the origin"
expect_status 65 "$SIMBOB" check far.xml
expect_eq "check: stderr" "$(cat "$LAST_ERR")" "$want"
expect_status 65 "$SIMBOB" run far.xml --duration 1 --out far.csv
expect_eq "run: stderr" "$(cat "$LAST_ERR")" "$want"
expect_no_file far.csv
expect_no_file far.partial.csv

# ---------------------------------------------------------------- 11, 15: size and FIFO scenes
check "65: a scene over 64 MiB (an input limit), with the file named"
truncate -s 65M huge.xml
expect_status 65 "$SIMBOB" check huge.xml
expect_eq "stderr" "$(cat "$LAST_ERR")" "huge.xml: error: cannot read scene: larger than 64 MiB"
rm huge.xml
check "66: a FIFO with no writer as the scene is refused at once"
mkfifo fifo.xml
expect_status 66 timeout 10 "$SIMBOB" check fifo.xml
expect_eq "stderr" "$(cat "$LAST_ERR")" "fifo.xml: error: cannot read scene: not a regular file"
say "ok"
