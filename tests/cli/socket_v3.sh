#!/usr/bin/env bash
# Socket protocol version 3 (docs/socket-protocol.md): a peer that says `version 2 3` gets
# `version 3`, the version 3 hello (sensor kinds) and state (body velocities); keys with spaces
# and UTF-8 travel %-escaped both ways; `subscribe` narrows the state blocks; a version 2 peer
# (scripts/simbob_client.py, which never sends `version`) still drives the robot to its golden;
# every protocol error sends `error MESSAGE` before simbob closes (exit 76).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

PEER="/usr/bin/python3 $CLI_DIR/socket_v3_peer.py"
KEY=Bot.Cart.Link
# The robot with a space in its motion control's key and UTF-8 in its chassis' key.
sed -e 's|<RCTwoWheelMotionControl Key="Motion">|<RCTwoWheelMotionControl Key="Mo tion">|' \
  -e 's|<RCMobileRigidBody Key="Chassis">|<RCMobileRigidBody Key="Châssis">|' \
  "$SCENES/socket_robot.xml" >keys.xml

check "a version 2 peer (scripts/simbob_client.py) still drives socket_robot.xml to its golden"
expect_status 0 "$SIMBOB" run "$SCENES/socket_robot.xml" --duration 10 --out v2.csv -q
expect_same_file v2.csv "$REPO/golden/socket_robot.csv"

check "simbob check accepts keys with spaces and UTF-8 in a scene with a communicator"
expect_status 0 "$SIMBOB" check keys.xml

check "version 3: negotiation, escaped keys, sensor kinds, velocities, subscriptions"
expect_status 0 "$SIMBOB" run keys.xml --duration 1 --out v3.csv -q \
  --controller "$KEY=$PEER v3 Bot.Cart.Ch%c3%a2ssis Bot.Mo%20tion"
log=v3.controller.log
expect_match "the version 2 hello offers 2 and 3" $log "^hello2: simbob 2 Bot.Cart.Link 0.05 \| versions 2 3 \|"
expect_match "the version 2 hello escapes the space" $log "\| motion Bot.Mo%20tion \|"
expect_match "'version 3' comes first in simbob's answer" $log "^skipped 0 lines before 'version 3'$"
expect_match "version 3 hello" $log "^hello3: simbob 3 Bot.Cart.Link 0.05$"
expect_match "escaped space" $log "^hello3: motion Bot.Mo%20tion$"
expect_match "escaped UTF-8" $log "^hello3: body Bot.Cart.Ch%C3%A2ssis$"
grep -q "versions" <(grep '^hello3:' $log) && fail "the version 3 hello repeats 'versions'"
# Before subscribing: every joint and body, bodies with 13 numbers (pose + velocities).
n=$(grep -c '^state0: body ' $log)
expect_eq "bodies in the first version 3 state" "$n" 4
n=$(grep -c '^state0: joint ' $log)
expect_eq "joints in the first version 3 state" "$n" 3
bad=$(grep '^state0: body ' $log | awk 'NF != 2 + 1 + 13' | head -1)
[[ -z "$bad" ]] || fail "a version 3 body line without 13 numbers: $bad"
# After subscribing to one body and no joints: exactly that.
for i in 1 2; do
  expect_eq "state$i bodies" "$(grep -c "^state$i: body " $log)" 1
  expect_eq "state$i joints" "$(grep -c "^state$i: joint " $log || true)" 0
  expect_match "state$i: the subscribed body" $log "^state$i: body Bot.Cart.Ch%C3%A2ssis( -?[0-9.e+-]+){13}$"
done
# The escaped 'set Bot.Mo%20tion 0.5 0' drove the robot: the chassis moves along +X after it.
x2=$(grep '^state2: body ' $log | awk '{print $4}')
vx2=$(grep '^state2: body ' $log | awk '{print $11}')
float_between "chassis vx at the second exchange" "$vx2" 0.05 1
float_between "chassis x at the second exchange" "$x2" 0.0001 0.2
expect_match "done: simbob closes without bye" $log "^EOF$"

# expect_error NAME MESSAGE-ERE LINE...: the peer sends the lines after the first state; the run
# fails with 76 and the peer's last line before EOF is 'error ...' matching MESSAGE-ERE.
expect_error() {
  local name=$1 message=$2
  shift 2
  check "protocol error ($name): 'error' before simbob closes, exit 76"
  expect_status 76 "$SIMBOB" run keys.xml --duration 1 --out "err_$name.csv" -q \
    --controller "$KEY=$PEER send $(printf "'%s' " "$@")"
  local last
  last=$(grep -v '^EOF$' "err_$name.controller.log" | tail -n 1)
  [[ "$last" =~ ^error\  ]] || fail "$name: the peer's last line is not 'error': $(cat "err_$name.controller.log")"
  [[ "$last" =~ $message ]] || fail "$name: '$last' does not match /$message/"
  tail -n 1 "err_$name.controller.log" | grep -qx EOF || fail "$name: simbob did not close"
  expect_match "$name: the same message on stderr" "$LAST_ERR" "$message"
}
expect_error no_common_version "no protocol version in common: simbob speaks 2 and 3" "version 4 5"
expect_error version_not_first "the peer sent 'version 3'" "set Bot.Mo%20tion 0 0" "version 3"
expect_error bad_version "'version': 'x' is not a version number" "version x"
expect_error subscribe_in_v2 "the peer sent 'subscribe bodies \*'" "subscribe bodies *"
expect_error subscribe_kind "'subscribe' takes bodies, joints, sensors or cameras" "version 3" "subscribe wheels"
expect_error subscribe_key "'subscribe bodies': no body has the key 'Bot.Cart.Chassis'" \
  "version 3" "subscribe bodies Bot.Cart.Chassis"
expect_error unescaped_key "'set Bot.Mo': 'tion' is not a finite number" "set Bot.Mo tion 0 0"
expect_error unknown_key "'set Bot.Motion': no actuator or motion control has that key" "set Bot.Motion 0 0"
expect_error bad_escape "'set Bot.Mo%2': a '%' not followed by two hex digits" "set Bot.Mo%2 1 2"
# Issue 31: a bad escape in 'subscribe' is named as such, not as an unknown key.
expect_error subscribe_bad_escape "'subscribe bodies Bot%2': a '%' not followed by two hex digits" \
  "version 3" "subscribe bodies Bot%2"
expect_error bad_number "'set Bot.Mo%20tion': 'fast' is not a finite number" "set Bot.Mo%20tion fast 0"
expect_error unknown_line "the peer sent 'jump'" "jump"
expect_error long_line "a line longer than 4096 bytes" "$(head -c 5000 /dev/zero | tr '\0' x)"
say "ok"
