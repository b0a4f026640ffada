#!/usr/bin/env bash
# Controllers started by simbob (docs/socket-protocol.md#controllers-started-by-simbob): the
# communicator's Controller (or run --controller KEY=COMMAND) runs in a process group of its own,
# in the scene's folder, with SIMBOB_PORT, SIMBOB_KEY and SIMBOB_SEED, its output in
# <trajectory>.controller.log; socket_robot.xml runs unattended to its golden in run, batch -j 2,
# --check-determinism and sweep run; a controller that cannot start, exits before connecting or
# never connects fails the run with one line naming it; nothing of its group outlives the run,
# whether it completes, fails or is stopped by SIGINT or SIGTERM.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

SCENE="$SCENES/socket_robot.xml"
GOLDEN="$REPO/golden/socket_robot.csv"
KEY=Bot.Cart.Link
LINE=$(grep -n '<RCLocalSocketCommunicator' "$SCENE" | cut -d: -f1)

# no_group PGID_FILE: fails if any process of the group whose id the file holds is still alive.
no_group() {
  local pgid
  pgid=$(tr -dc 0-9 <"$1")
  [[ -n "$pgid" ]] || fail "the controller did not write its process group ($1 is empty)"
  local left
  left=$(ps -eo pid=,pgid=,stat=,args= | awk -v g="$pgid" '$2 == g && $3 !~ /^Z/')
  [[ -z "$left" ]] || fail "processes of the controller's group $pgid outlived the run: $left"
}

# A controller that leaves a child behind (sleep, in its process group), notes its group and
# environment, then is the example client.
cat >leaves_child.sh <<SH
#!/bin/sh
sleep 300 &
echo \$\$ >"$WORK/pgid"
echo "env SIMBOB_PORT=\$SIMBOB_PORT SIMBOB_KEY=\$SIMBOB_KEY SIMBOB_SEED=\$SIMBOB_SEED cwd=\$(pwd)"
exec /usr/bin/python3 "$REPO/scripts/simbob_client.py"
SH
chmod +x leaves_child.sh

check "socket_robot.xml starts its own client: the trajectory equals its golden byte for byte"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 10 --out own.csv -q
expect_same_file own.csv "$GOLDEN"
expect_match "the client's output is in own.controller.log" own.controller.log \
  "the run ended at t=10 s after 201 exchanges"

check "--controller KEY=COMMAND: environment, folder, log; the client's leftover child is ended"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 10 --seed 7 --out env.csv -q \
  --controller "$KEY=./leaves_child.sh"
expect_same_file env.csv "$GOLDEN"
expect_match "environment" env.controller.log \
  "^env SIMBOB_PORT=[0-9]+ SIMBOB_KEY=$KEY SIMBOB_SEED=7 cwd=$WORK\$"
no_group pgid

check "a quoted command line: words split without a shell"
mkdir "dir with space"
cp leaves_child.sh "dir with space/it's here.sh"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 0.2 --out quoted.csv -q \
  --controller "$KEY=\"dir with space/it's here.sh\" --wait '3'"
no_group pgid

check "IsServer false: simbob connects to the controller's server on Port + --port-offset, retrying while it starts"
sed 's|<IsServer Value="true"/>|<IsServer Value="false"/>|' "$SCENE" >client_mode.xml
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()')
expect_status 0 "$SIMBOB" run client_mode.xml --duration 10 --out client.csv -q --port-offset $((port - 47311)) \
  --controller "$KEY=/bin/sh -c 'sleep 0.5; exec /usr/bin/python3 $REPO/scripts/simbob_client.py --listen'"
expect_same_file client.csv "$GOLDEN"

check "batch 'scenes/*.xml' --golden golden -j 2: every scene, the socket scene's client started unattended"
(cd "$REPO" && "$SIMBOB" batch scenes/*.xml --duration 10 --out-dir "$WORK/batch" --golden golden -j 2 -q) \
  >batch.out 2>batch.err || fail "batch failed: $(cat batch.out batch.err)"
expect_same_file batch/socket_robot.csv "$GOLDEN"
expect_match "the batch run's controller log is beside its CSV" batch/socket_robot.controller.log \
  "the run ended at t=10 s after 201 exchanges"

check "--check-determinism runs the socket scene twice, each with its own client"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 3 --out det.csv -q --check-determinism

check "sweep run over the socket scene: 2 cases on 2 workers"
cat >socket.sweep.json <<JSON
{"scene": "$SCENE", "duration": 3,
 "vary": [{"param": "Bot.Cart.Link.Period", "values": [0.05, 0.025]}],
 "metrics": [{"name": "x", "body": "Bot.Cart.Chassis", "value": "x", "stat": "final"}]}
JSON
expect_status 0 "$SIMBOB" sweep plan socket.sweep.json -o socket.jsonl
expect_status 0 "$SIMBOB" sweep run socket.jsonl -j 2 -o sweep -q

check "a controller that exits before connecting: one line naming it and its status (69)"
expect_status 69 "$SIMBOB" run "$SCENE" --duration 1 --out exits.csv -q --controller "$KEY=/bin/sh -c 'exit 3'"
expect_lines "one line" "$LAST_ERR" 1
expect_match "names it and its status" "$LAST_ERR" \
  "^$SCENE:$LINE: error: RCLocalSocketCommunicator '$KEY' \(127.0.0.1:\\\$SIMBOB_PORT\): controller '/bin/sh -c 'exit 3'' exited with status 3 before connecting \(its output: exits.controller.log\)\$"

check "a controller that cannot be run (69)"
expect_status 69 "$SIMBOB" run "$SCENE" --duration 1 --out none.csv -q --controller "$KEY=./no-such-program x"
expect_lines "one line" "$LAST_ERR" 1
expect_match "names it and why" "$LAST_ERR" \
  "^$SCENE:$LINE: error: RCLocalSocketCommunicator '$KEY' \(127.0.0.1:\\\$SIMBOB_PORT\): cannot start controller './no-such-program x': cannot run ./no-such-program: No such file or directory\$"

check "a controller that never connects: --peer-timeout ends the run and the controller's group"
cat >silent.sh <<SH
#!/bin/sh
echo \$\$ >"$WORK/pgid"
sleep 300 &
sleep 300
SH
chmod +x silent.sh
expect_status 69 "$SIMBOB" run "$SCENE" --duration 1 --out silent.csv -q --peer-timeout 0.5 --controller "$KEY=./silent.sh"
expect_match "timeout message" "$LAST_ERR" \
  "no peer connected within 0.5 s \(--peer-timeout\); controller './silent.sh' is running but did not connect\$"
no_group pgid

for sig in INT TERM; do
  check "SIG$sig during a run: the controller's group is ended, the client hears 'error'"
  rm -f pgid
  "$SIMBOB" run "$SCENE" --duration 100000 --out sig.csv -q --controller "$KEY=./leaves_child.sh" 2>sig.err &
  run=$!
  for _ in $(seq 300); do [[ -s sig.controller.log && -s pgid ]] && break; sleep 0.1; done
  sleep 1
  kill -$sig $run
  status=0
  wait $run || status=$?
  want=130
  [[ $sig == INT ]] || want=143
  expect_eq "exit status after SIG$sig ($(cat sig.err))" "$status" $want
  expect_match "the client heard why" sig.controller.log "simbob says:"
  no_group pgid
done

check "unknown --controller key and a bad command line are usage errors (64); Controller is checked by check (65)"
expect_status 64 "$SIMBOB" run "$SCENE" --duration 1 --out x.csv -q --controller "Bot.Link=x"
expect_match "names the key" "$LAST_ERR" "no RCLocalSocketCommunicator has the key 'Bot.Link'"
expect_status 64 "$SIMBOB" run "$SCENE" --duration 1 --out x.csv -q --controller "$KEY=\"open"
sed 's|<Controller Value="[^"]*"/>|<Controller Value="python3 '"'"'x.py"/>|' "$SCENE" >bad_quote.xml
expect_status 65 "$SIMBOB" check bad_quote.xml
expect_match "check names the parameter" "$LAST_ERR" "bad_quote.xml:[0-9]+: .*parameter 'Controller': a quote \(') is not closed"
say "ok"
