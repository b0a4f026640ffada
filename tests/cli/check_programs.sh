#!/usr/bin/env bash
# Programs a scene starts are never started without a word (issue 31, item 3): `check` (and
# `check -v`) names each program a scene will start and the folder it runs in; --no-controllers
# makes check, run, batch, sweep run and render --at refuse such a scene (64) before anything
# starts, naming the communicator and the program.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

mkdir sent
sed 's|<Controller Value="[^"]*"/>|<Controller Value="./marker.sh --flag"/>|' "$SCENES/socket_robot.xml" >sent/scene.xml
LINE=$(grep -n '<RCLocalSocketCommunicator' sent/scene.xml | cut -d: -f1)
cat >sent/marker.sh <<SH
#!/bin/sh
touch "$WORK/started"
exec /usr/bin/python3 "$REPO/scripts/simbob_client.py"
SH
chmod +x sent/marker.sh
PROGRAM_LINE="^simbob: sent/scene.xml:$LINE: RCLocalSocketCommunicator 'Bot.Cart.Link' starts the program '\./marker\.sh --flag' in $WORK/sent when the scene runs \(run, batch, sweep run, render --at, Python's Simulation\)\$"

for v in "" -v; do
  check "check $v lists the program and its folder"
  expect_status 0 "$SIMBOB" check $v sent/scene.xml
  expect_match "the program line" "$LAST_ERR" "$PROGRAM_LINE"
  expect_match "the ok line counts it" "$LAST_ERR" '^simbob: sent/scene.xml: ok \(4 mobile bodies, 5 geoms, 3 joints; starts 1 program\)$'
done
expect_no_file started

check "a scene that starts nothing: no program line"
expect_status 0 "$SIMBOB" check "$SCENES/sliding_box.xml"
if grep -q "program" "$LAST_ERR"; then fail "check names a program of sliding_box.xml: $(cat "$LAST_ERR")"; fi

ERROR_LINE="^sent/scene.xml:$LINE: error: RCLocalSocketCommunicator 'Bot.Cart.Link' would start the program '\./marker\.sh --flag' in $WORK/sent: --no-controllers refuses it \(--controller Bot.Cart.Link= runs the scene with a peer of your own\)\$"

check "check --no-controllers: refused (64), one line"
expect_status 64 "$SIMBOB" check --no-controllers sent/scene.xml
expect_match "the refusal" "$LAST_ERR" "$ERROR_LINE"

check "run --no-controllers: refused (64) before anything starts or is written"
expect_status 64 "$SIMBOB" run --no-controllers sent/scene.xml --duration 1 --out run.csv
expect_lines "one line" "$LAST_ERR" 1
expect_match "the refusal" "$LAST_ERR" "$ERROR_LINE"
expect_no_file started
expect_no_file run.csv
expect_no_file run.controller.log

check "render --at --no-controllers: refused (64)"
expect_status 64 "$SIMBOB" render --no-controllers sent/scene.xml --at 0.5 --out r.png
expect_match "the refusal" "$LAST_ERR" "$ERROR_LINE"
expect_no_file r.png

check "batch --no-controllers: the scene fails, nothing started"
expect_status 1 "$SIMBOB" batch --no-controllers sent/scene.xml "$SCENES/sliding_box.xml" --duration 0.2 --out-dir b -q
expect_match "the refusal in the scene's partial summary" b/scene.partial.json "would start the program"
expect_file b/sliding_box.csv
expect_no_file started

check "sweep run --no-controllers: the case fails, nothing started"
cat >s.sweep.json <<JSON
{"scene": "sent/scene.xml", "duration": 0.2, "vary": [{"param": "Bot.Cart.Link.Period", "values": [0.05]}],
 "metrics": [{"name": "x", "body": "Bot.Cart.Chassis", "value": "x", "stat": "final"}]}
JSON
expect_status 0 "$SIMBOB" sweep plan s.sweep.json -o s.jsonl
expect_status 1 "$SIMBOB" sweep run --no-controllers s.jsonl -j 1 -o sw -q
expect_match "the case's refusal" sw/case-0000/case.json "would start the program"
expect_no_file started

check "without --no-controllers the program starts (the test can fail)"
expect_status 0 "$SIMBOB" run sent/scene.xml --duration 0.2 --out ok.csv -q --peer-timeout 60
expect_file started
say "ok"
