#!/usr/bin/env bash
# RCLocalSocketCommunicator end to end (docs/socket-protocol.md): scenes/socket_robot.xml driven
# by scripts/simbob_client.py matches its golden byte for byte, twice, and moves as the client's
# law says; the same run with simbob as the client gives the same bytes; a peer that
# disconnects, stalls, breaks the protocol or never comes, and a client with no server, stop the
# run with one line naming the scene line and exit 69 (76 for the protocol); "done" lets the run
# finish; --port-offset moves the port so two runs go side by side. Only 127.0.0.1.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
# Background peers and listeners never outlive the test.
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

# The scene names its peer program (Controller); these tests start their peers by hand instead.
sed '/<Controller Value=/d' "$SCENES/socket_robot.xml" >by_hand.xml
SCENE="$WORK/by_hand.xml"
CLIENT="$REPO/scripts/simbob_client.py"
FAULT="$CLI_DIR/socket_fault_peer.py"
BASE_PORT=47311 # the scene's Port
LINE=$(grep -n '<RCLocalSocketCommunicator' "$SCENE" | cut -d: -f1)

# A port nobody listens on now (the kernel's choice of a free ephemeral port).
free_port() {
  python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()'
}
# Starts the client (or fault peer) in the background: PEER_PID.
start_peer() {
  "$@" >peer.out 2>peer.err &
  PEER_PID=$!
}
# Starts the fault peer in the background and waits until it is ready to connect, so that a short
# --peer-timeout measures the peer's answers, not Python's start-up.
start_fault_peer() {
  start_peer python3 "$FAULT" "$@"
  for _ in $(seq 300); do grep -q ready peer.err && return 0; sleep 0.1; done
  fail "the fault peer did not start: $(cat peer.err)"
}
# Waits for the background peer; fails unless it exits with status $1.
expect_peer_status() {
  local got=0
  wait "$PEER_PID" || got=$?
  [[ "$got" == "$1" ]] || fail "peer exited $got, expected $1: $(cat peer.out peer.err)"
}

check "socket_robot: simbob check is clean (the communicator is not 'without effect')"
expect_status 0 "$SIMBOB" check "$SCENE"
if grep -q "no effect" "$LAST_ERR"; then fail "check still warns: $(cat "$LAST_ERR")"; fi

check "socket_robot driven by simbob_client.py equals golden/socket_robot.csv byte for byte, twice"
for i in 1 2; do
  port=$(free_port)
  start_peer python3 "$CLIENT" --port "$port"
  expect_status 0 "$SIMBOB" run "$SCENE" --duration 10 --port-offset $((port - BASE_PORT)) --out "run$i.csv"
  expect_peer_status 0
  expect_match "client saw the end of the run" peer.err "the run ended at t=10 s after 201 exchanges"
  expect_same_file "run$i.csv" "$REPO/golden/socket_robot.csv"
done
python3 "$CLI_DIR/scene_expectations.py" socket_robot run1.csv || fail "socket_robot: physical expectations"

check "simbob as the client (IsServer false) of simbob_client.py --listen gives the same bytes"
sed 's|<IsServer Value="true"/>|<IsServer Value="false"/>|' "$SCENE" >client_mode.xml
port=$(free_port)
start_peer python3 "$CLIENT" --listen --port "$port"
for _ in $(seq 100); do grep -q listening peer.err && break; sleep 0.1; done
expect_status 0 "$SIMBOB" run client_mode.xml --duration 10 --port-offset $((port - BASE_PORT)) --out client.csv
expect_peer_status 0
expect_same_file client.csv "$REPO/golden/socket_robot.csv"

check "client mode with no server: exit 69 at once, naming the scene line and the port"
port=$(free_port)
expect_status 69 "$SIMBOB" run client_mode.xml --duration 1 --port-offset $((port - BASE_PORT)) --out none.csv -q
expect_eq "no-server message" "$(cat "$LAST_ERR")" \
  "client_mode.xml:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' (127.0.0.1:$port): cannot connect to a server: Connection refused (IsServer is false: start the peer's server first; simbob does not retry)"
expect_no_file none.csv

check "no peer ever connects: exit 69 after --peer-timeout"
port=$(free_port)
expect_status 69 "$SIMBOB" run "$SCENE" --duration 1 --peer-timeout 0.5 --port-offset $((port - BASE_PORT)) \
  --out nopeer.csv -q
expect_eq "no-peer message" "$(cat "$LAST_ERR")" \
  "$SCENE:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' (127.0.0.1:$port): no peer connected within 0.5 s (--peer-timeout)"
expect_no_file nopeer.csv

check "a peer that disconnects at t=1 s: exit 69, the trajectory so far kept as partial"
port=$(free_port)
start_fault_peer --port "$port" --mode disconnect --at 1
expect_status 69 "$SIMBOB" run "$SCENE" --duration 10 --port-offset $((port - BASE_PORT)) --out gone.csv
expect_peer_status 0
expect_match "disconnect message" "$LAST_ERR" \
  "^.*by_hand.xml:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' \(127.0.0.1:$port\): the peer disconnected at t=1 s without 'done'$"
expect_no_file gone.csv
expect_file gone.partial.csv
last=$(tail -n 1 gone.partial.csv | cut -d, -f1)
expect_eq "partial ends with the sample at the failure" "$last" "1"

check "a peer that stops answering at t=1 s: exit 69 after MaxAccessTime (2 s, below --peer-timeout 30 s); the peer is told why"
port=$(free_port)
start_fault_peer --port "$port" --mode stall --at 1
expect_status 69 "$SIMBOB" run "$SCENE" --duration 10 --peer-timeout 30 --set SceneSettings.MaxAccessTime=2 --port-offset $((port - BASE_PORT)) \
  --out stall.csv -q
expect_peer_status 0
expect_eq "stall message" "$(cat "$LAST_ERR")" \
  "$SCENE:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' (127.0.0.1:$port): the peer sent no 'step' within 2 s at t=1 s (MaxAccessTime)"
expect_eq "the peer got an error line" "$(cat peer.out)" \
  "error the peer sent no 'step' within 2 s at t=1 s (MaxAccessTime)"

check "a peer that breaks the protocol: exit 76 quoting its line"
port=$(free_port)
start_fault_peer --port "$port" --mode garbage --at 0.5
expect_status 76 "$SIMBOB" run "$SCENE" --duration 10 --port-offset $((port - BASE_PORT)) --out bad.csv -q
expect_peer_status 0
expect_eq "protocol message" "$(cat "$LAST_ERR")" \
  "$SCENE:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' (127.0.0.1:$port): the peer sent 'jump Bot.Motion 3' at t=0.5 s: expected 'set KEY VALUE...', 'step' or 'done'"

check "a peer that says 'done' at t=1 s: the run completes without it"
port=$(free_port)
start_fault_peer --port "$port" --mode done --at 1
expect_status 0 "$SIMBOB" run "$SCENE" --duration 3 --port-offset $((port - BASE_PORT)) --out done.csv -q
expect_peer_status 0
last=$(tail -n 1 done.csv | cut -d, -f1)
expect_eq "the run reached its end" "$last" "3"

check "--port-offset: two runs side by side on different ports both succeed with the same bytes"
p1=$(free_port)
start_peer python3 "$CLIENT" --port "$p1"
pid1=$PEER_PID
mv peer.err peer1.err
p2=$(free_port)
[[ "$p2" != "$p1" ]] || p2=$((p1 + 1))
start_peer python3 "$CLIENT" --port "$p2"
pid2=$PEER_PID
s1=0 s2=0
"$SIMBOB" run "$SCENE" --duration 10 --port-offset $((p1 - BASE_PORT)) --out par1.csv -q 2>par1.err &
run1=$!
"$SIMBOB" run "$SCENE" --duration 10 --port-offset $((p2 - BASE_PORT)) --out par2.csv -q 2>par2.err &
run2=$!
wait $run1 || s1=$?
wait $run2 || s2=$?
wait $pid1 || fail "client 1 failed: $(cat peer1.err)"
wait $pid2 || fail "client 2 failed: $(cat peer.err)"
expect_eq "run 1 status ($(cat par1.err))" "$s1" 0
expect_eq "run 2 status ($(cat par2.err))" "$s2" 0
expect_same_file par1.csv "$REPO/golden/socket_robot.csv"
expect_same_file par2.csv "$REPO/golden/socket_robot.csv"

check "a port another program listens on: the run cannot listen (exit 69)"
port=$(free_port)
python3 -c "import socket,time; s=socket.socket(); s.bind(('127.0.0.1', $port)); s.listen(1); print('up', flush=True); time.sleep(60)" >holder.out &
holder=$!
for _ in $(seq 100); do grep -q up holder.out && break; sleep 0.05; done
expect_status 69 "$SIMBOB" run "$SCENE" --duration 1 --port-offset $((port - BASE_PORT)) --out clash.csv -q
kill "$holder"
expect_eq "clash message" "$(cat "$LAST_ERR")" \
  "$SCENE:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' (127.0.0.1:$port): cannot listen: Address already in use (another run on this port? --port-offset moves every port)"

check "--port-offset out of range and --peer-timeout out of range are usage errors"
expect_status 64 "$SIMBOB" run "$SCENE" --duration 1 --port-offset 20000 --out x.csv -q
expect_eq "port range message" "$(cat "$LAST_ERR")" \
  "$SCENE:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link': Port 47311 + --port-offset 20000 is outside 1 to 65535"
expect_status 64 "$SIMBOB" run "$SCENE" --duration 1 --peer-timeout 0 --out x.csv -q
expect_match "timeout range message" "$LAST_ERR" "--peer-timeout must be between 0.001 and 86400 s, got 0"
check "a peer reads the front sensor of wall_stop_robot: 0 at t=0, then 1 from the touch on, switching once"
# wall_stop_robot.xml with a communicator added; its RCWallStop still drives. The sensor reaches
# the wall after the chassis has gone 1.1 m at no more than 0.2 m/s: not before t=5.5 s.
port=$(free_port)
sed "s|<!-- Velocity-controlled wheel drives. -->|<RCLocalSocketCommunicator Key=\"Link\"><IsServer Value=\"true\"/><Port Value=\"$BASE_PORT\"/><Period Value=\"0.05\"/></RCLocalSocketCommunicator>|" \
  "$SCENES/wall_stop_robot.xml" >sensor_robot.xml
grep -q RCLocalSocketCommunicator sensor_robot.xml || fail "the communicator was not added"
start_peer python3 "$CLI_DIR/socket_sensor_peer.py" --port "$port"
expect_status 0 "$SIMBOB" run sensor_robot.xml --duration 8 --set SceneSettings.MaxAccessTime=30 --port-offset $((port - BASE_PORT)) --out sensor.csv -q
expect_peer_status 0
expect_eq "hello names the sensor" "$(grep '^hello' peer.out)" "hello sensor Bot.Cart.Front"
expect_eq "one reading per exchange (t = 0, 0.05, ..., 8)" "$(grep -vc '^hello' peer.out)" 161
expect_eq "reading at t=0" "$(sed -n 2p peer.out)" "0 Bot.Cart.Front 0"
expect_eq "reading at the end" "$(tail -n 1 peer.out)" "8 Bot.Cart.Front 1"
switches=$(grep -v '^hello' peer.out | awk '$3 != prev && NR > 1 {n++} {prev = $3} END {print n + 0}')
expect_eq "the reading switches once" "$switches" 1
first_touch=$(grep -v '^hello' peer.out | awk '$3 == 1 {print $1; exit}')
python3 -c "import sys; t = float('$first_touch'); sys.exit(0 if 5.5 <= t <= 6.5 else 1)" ||
  fail "the sensor switched at t=$first_touch s, expected 5.5 to 6.5 s"
check "a peer streaming valid 'set' lines without 'step' is stopped at --peer-timeout (2 s), not when it stops streaming (20 s)"
port=$(free_port)
start_fault_peer --port "$port" --mode stream --at 0.5 --stream 20
t0=$(date +%s.%N)
expect_status 69 "$SIMBOB" run "$SCENE" --duration 10 --peer-timeout 2 --port-offset $((port - BASE_PORT)) --out stream.csv -q
t1=$(date +%s.%N)
expect_peer_status 0
expect_eq "stream message" "$(cat "$LAST_ERR")" \
  "$SCENE:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' (127.0.0.1:$port): the peer sent no 'step' within 2 s at t=0.5 s (--peer-timeout)"
python3 -c "import sys; sys.exit(0 if $t1 - $t0 < 8 else 1)" || fail "the streaming peer held simbob for $(python3 -c "print($t1 - $t0)") s"

check "a peer that connects after 1.5 s with MaxAccessTime 1 s and --peer-timeout 10 s: the run completes; steps_per_second leaves the wait out"
port=$(free_port)
start_fault_peer --port "$port" --mode step --at 1e9 --delay 1.5
expect_status 0 "$SIMBOB" run "$SCENE" --duration 1 --peer-timeout 10 --set SceneSettings.MaxAccessTime=1 \
  --port-offset $((port - BASE_PORT)) --out late.csv --json -q
expect_peer_status 0
python3 - "$LAST_OUT" <<'PY' || fail "steps_per_second counts the wait for the peer: $(cat "$LAST_OUT")"
import json, sys
s = json.load(open(sys.argv[1]))
busy = s["steps"] / s["steps_per_second"]
print(f"check: wall {s['wall_seconds']:.3f} s, simulating {busy:.3f} s")
sys.exit(0 if s["wall_seconds"] >= 1.0 and busy <= s["wall_seconds"] - 1.0 else 1)
PY

# stopped_run SIGNAL: a run under way with a peer that only steps, ended by SIGNAL; the peer's
# output in peer.out.
stopped_run() {
  port=$(free_port)
  start_fault_peer --port "$port" --mode step --at 0.2
  "$SIMBOB" run "$SCENE" --duration 100000 --port-offset $((port - BASE_PORT)) --out sig.csv -q 2>sig.err &
  local run=$!
  for _ in $(seq 300); do grep -q '^at ' peer.out && break; sleep 0.05; done
  grep -q '^at ' peer.out || fail "the run did not get under way: $(cat sig.err)"
  kill "-$1" "$run"
  RUN_STATUS=0
  wait "$run" || RUN_STATUS=$?
  expect_peer_status 0
}
check "SIGINT and SIGTERM: the peer gets an 'error' line before the connection closes, as README promises"
stopped_run INT
expect_eq "SIGINT exit" "$RUN_STATUS" 130
expect_match "SIGINT error line" peer.out "^error interrupted at t=[0-9.]+ s$"
stopped_run TERM
expect_eq "SIGTERM exit" "$RUN_STATUS" 143
expect_match "SIGTERM error line" peer.out "^error interrupted at t=[0-9.]+ s$"

check "a run that diverges: the peer gets an 'error' line naming the body"
port=$(free_port)
sed 's|<RCGround Key="Ground"/>|&<RCMobileRigidBody Key="Rocket"><Pose><RCGlobalCoordinates><Pose Value="5 1 5 0 0 0"/></RCGlobalCoordinates></Pose><Motion><RCGlobalMotion><LinVelocity Value="0 1e7 0"/></RCGlobalMotion></Motion><Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom><Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia></RCMobileRigidBody>|' \
  "$SCENE" >rocket_robot.xml
grep -q Rocket rocket_robot.xml || fail "the rocket was not added"
start_fault_peer --port "$port" --mode step --at 1e9
expect_status 1 "$SIMBOB" run rocket_robot.xml --duration 1 --port-offset $((port - BASE_PORT)) --out rocket.csv -q
expect_peer_status 0
expect_match "divergence error line" peer.out "^error body 'Rocket' diverged at t="

# Keys with a space or UTF-8 travel %-escaped (protocol version 3 and 2): tests/cli/socket_v3.sh.

check "simbob_client.py takes a later protocol version and ignores lines it does not know (README)"
port=$(free_port)
cat >fake_simbob.py <<'PY'
import socket, sys
srv = socket.socket()
srv.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
srv.bind(("127.0.0.1", int(sys.argv[1])))
srv.listen(1)
print("up", flush=True)
conn, _ = srv.accept()
conn.sendall(b"simbob 3 Bot.Cart.Link 0.05 extra\nnews\n\nactuator Bot.Cart.LeftDrive velocity\n"
             b"motion Bot.Motion\nbody Bot.Cart.Chassis\nend\n"
             b"t 0\nnews\n\nbody Bot.Cart.Chassis 0 0.1 0 1 0 0 0 more\nend\nnews 1 2\n")
got = b""
while b"step\n" not in got:
    chunk = conn.recv(4096)
    if not chunk:
        sys.exit("fake simbob: the client closed before 'step': " + got.decode())
    got += chunk
print(got.decode(), end="", flush=True)
conn.sendall(b"bye 0.05\n")
conn.close()
PY
python3 fake_simbob.py "$port" >fake.out 2>fake.err &
fake=$!
for _ in $(seq 100); do grep -q up fake.out && break; sleep 0.05; done
expect_status 0 python3 "$CLIENT" --port "$port" --wait 5
wait "$fake" || fail "the fake simbob failed: $(cat fake.err)"
expect_match "the client answered" fake.out "^set Bot.Motion 0.2 0.0$"
expect_match "the client saw bye" "$LAST_ERR" "the run ended at t=0.05 s after 1 exchanges"

say "ok: socket"
