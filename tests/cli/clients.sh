#!/usr/bin/env bash
# The client libraries' conformance test (docs/socket-protocol.md#client-libraries): every client
# -- python/simbob_client.py and examples/clients/simbob_client.c, each through its
# drive_two_wheel example, started by simbob as the Controller -- (1) drives socket_robot.xml
# to golden/socket_robot.csv byte for byte with the same commands, and (2) negotiates version 3,
# reads keys with a space, a comma and UTF-8, subscribes to one body and no joints, and reads
# that body's pose and velocities: the same printout, line for line, for every client; (3) each
# client's maze follower (examples/clients/maze_follower.py and .c, the same law with the same
# float64 operations), started by simbob, drives scenes/maze_socket.xml to golden/maze_socket.csv
# byte for byte, reading the laser scanner over version 3, and, with a 360-ray scanner (a state
# line of about 7 kB; the C client built with -DSB_VALUES=360), to the same bytes as each other.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

KEY=Bot.Cart.Link
EX="$REPO/examples/clients"
check "the C client builds as C99 without warnings"
${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -ffp-contract=off -o drive_two_wheel \
  "$EX/drive_two_wheel.c" -lm || fail "examples/clients/drive_two_wheel.c does not build"

CLIENTS=(python c)
declare -A COMMAND=(
  [python]="/usr/bin/python3 $EX/drive_two_wheel.py"
  [c]="$WORK/drive_two_wheel"
)
sed -e 's|<RCTwoWheelMotionControl Key="Motion">|<RCTwoWheelMotionControl Key="Mo tion">|' \
  -e 's|<RCMobileRigidBody Key="Chassis">|<RCMobileRigidBody Key="Châssis, 1">|' \
  "$SCENES/socket_robot.xml" >keys.xml
cat >probe.expected <<'TXT'
version 3
key Bot.Cart.Link
motion Bot.Mo tion
body Bot.Cart.Châssis, 1
body Bot.Cart.LeftAxle.LeftWheel
body Bot.Cart.RightAxle.RightWheel
body Bot.Cart.CasterSocket.CasterBall
t 0.050
state body Bot.Cart.Châssis, 1 13 moving 1
end
TXT

for client in "${CLIENTS[@]}"; do
  check "$client client: socket_robot.xml to its golden byte for byte"
  expect_status 0 "$SIMBOB" run "$SCENES/socket_robot.xml" --duration 10 --out "drive_$client.csv" -q \
    --controller "$KEY=${COMMAND[$client]}"
  expect_same_file "drive_$client.csv" "$REPO/golden/socket_robot.csv"
  expect_match "$client: the run ended" "drive_$client.controller.log" "the run ended at t=10 s after 201 exchanges"

  check "$client client: version 3, escaped keys, a subscription, velocities"
  expect_status 0 "$SIMBOB" run keys.xml --duration 1 --out "probe_$client.csv" -q \
    --controller "$KEY=${COMMAND[$client]} probe"
  diff probe.expected "probe_$client.controller.log" >probe.diff ||
    fail "$client: the probe's printout differs: $(cat probe.diff)"
done

check "the C maze follower builds as C99 without warnings"
${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -ffp-contract=off -o maze_follower \
  "$EX/maze_follower.c" -lm || fail "examples/clients/maze_follower.c does not build"
declare -A FOLLOWER=(
  [python]="/usr/bin/python3 $EX/maze_follower.py"
  [c]="$WORK/maze_follower"
)
for client in "${CLIENTS[@]}"; do
  check "$client client: maze_socket.xml to its golden byte for byte"
  expect_status 0 "$SIMBOB" run "$SCENES/maze_socket.xml" --duration 10 --out "maze_$client.csv" -q \
    --controller "$KEY=${FOLLOWER[$client]}"
  expect_same_file "maze_$client.csv" "$REPO/golden/maze_socket.csv"
  expect_match "$client: the follower ran to the end" "maze_$client.controller.log" \
    "the run ended at t=10 s after 201 exchanges"
done

check "a 360-ray scanner (one line of about 7 kB): both followers give the same trajectory bytes"
sed 's|<Rays Value="36"/>|<Rays Value="360"/>|' "$SCENES/maze_socket.xml" >maze360.xml
grep -q '<Rays Value="360"/>' maze360.xml || fail "maze360.xml has no 360-ray scanner"
${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -ffp-contract=off -DSB_VALUES=360 -o maze_follower360 \
  "$EX/maze_follower.c" -lm || fail "maze_follower.c does not build with -DSB_VALUES=360"
expect_status 0 "$SIMBOB" run maze360.xml --duration 10 --out maze360_python.csv -q \
  --controller "$KEY=${FOLLOWER[python]}"
expect_status 0 "$SIMBOB" run maze360.xml --duration 10 --out maze360_c.csv -q --controller "$KEY=$WORK/maze_follower360"
expect_match "c: the follower ran to the end" maze360_c.controller.log "the run ended at t=10 s after 201 exchanges"
expect_same_file maze360_c.csv maze360_python.csv
cmp -s maze360_c.csv "$REPO/golden/maze_socket.csv" && fail "360 rays drove the robot as 36 do: the scanner was not read"
say "ok"
