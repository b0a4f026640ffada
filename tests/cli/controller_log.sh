#!/usr/bin/env bash
# The controller's log is bounded and never overwrites an input (issue 31, item 4;
# docs/socket-protocol.md, "Output"): OUT.controller.log keeps the first and the last 4 MiB of
# what the controller prints and says how much it cut between them, for a controller that
# prints without end and for one that never connects; a controller program or a file it is
# given that happens to be named OUT.controller.log is an input: the run is refused (64) and
# the file keeps its bytes.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

SCENE="$SCENES/socket_robot.xml"
KEY=Bot.Cart.Link
CAP=$((8 * 1024 * 1024))

# log_shape LOG: the log holds the head, one line naming the cut, and the tail; at most the cap
# and that line.
log_shape() {
  /usr/bin/python3 - "$1" "$CAP" <<'PY'
import re, sys
path, cap = sys.argv[1], int(sys.argv[2])
data = open(path, 'rb').read()
marks = list(re.finditer(rb'\n\[simbob: ([0-9]+) bytes of the controller\'s output cut here; this log keeps the first 4 MiB and the last 4 MiB\]\n', data))
if len(marks) != 1:
    sys.exit(f'FAIL: {path}: {len(marks)} lines naming the cut ({len(data)} bytes): {data[:80]!r} ... {data[-200:]!r}')
m = marks[0]
head, tail = data[:m.start()], data[m.end():]
if len(head) + len(tail) > cap or len(data) > cap + 200:
    sys.exit(f'FAIL: {path}: {len(data)} bytes ({len(head)} head, {len(tail)} tail), the cap is {cap}')
if not head.startswith(b'y\ny\n'):
    sys.exit(f'FAIL: {path}: the head is not the first output: {head[:20]!r}')
print(len(data), int(m.group(1)), tail[-120:].decode(errors='replace'))
PY
}

check "a controller that prints without end, then connects: the log keeps head and tail, the run completes"
cat >chatty.sh <<SH
#!/bin/sh
timeout 2 yes
exec /usr/bin/python3 "$REPO/scripts/simbob_client.py"
SH
chmod +x chatty.sh
expect_status 0 "$SIMBOB" run "$SCENE" --duration 2 --out chatty.csv -q --controller "$KEY=./chatty.sh" --peer-timeout 60
shape=$(log_shape chatty.controller.log)
say "  $shape" | head -c 300; echo
expect_match "the tail is the client's last words" chatty.controller.log "the run ended at t=2 s"

check "a controller that prints and never connects: the log is bounded when --peer-timeout ends it"
cat >silent.sh <<SH
#!/bin/sh
exec yes
SH
chmod +x silent.sh
expect_status 69 "$SIMBOB" run "$SCENE" --duration 2 --out silent.csv -q --controller "$KEY=./silent.sh" --peer-timeout 2
log_shape silent.controller.log >/dev/null

check "a controller program named like the log is an input: refused (64), its bytes kept"
cat >run.controller.log <<SH
#!/bin/sh
exec /usr/bin/python3 "$REPO/scripts/simbob_client.py"
SH
chmod +x run.controller.log
cp run.controller.log program.bak
expect_status 64 "$SIMBOB" run "$SCENE" --duration 2 --out run.csv -q --controller "$KEY=./run.controller.log"
expect_same_file run.controller.log program.bak
expect_match "names the clash" "$LAST_ERR" "run.controller.log"

check "a file the controller is given, named like the log, is an input too"
cp "$REPO/scripts/simbob_client.py" arg.controller.log
cp arg.controller.log arg.bak
expect_status 64 "$SIMBOB" run "$SCENE" --duration 2 --out arg.csv -q --controller "$KEY=/usr/bin/python3 arg.controller.log"
expect_same_file arg.controller.log arg.bak

check "the scene's own Controller, run from the scene's folder, given the log's name: refused too"
mkdir scene
sed 's|<Controller Value="[^"]*"/>|<Controller Value="/usr/bin/python3 own.controller.log"/>|' "$SCENE" >scene/own.xml
cp "$REPO/scripts/simbob_client.py" scene/own.controller.log
cp scene/own.controller.log own.bak
expect_status 64 "$SIMBOB" run scene/own.xml --duration 2 --out scene/own.csv -q
expect_same_file scene/own.controller.log own.bak
say "ok"
