#!/usr/bin/env bash
# Nothing a controller starts outlives simbob (issue 31, item 2; docs/socket-protocol.md,
# "Lifetime"): not a child that calls setsid, not the jobs of a shell with job control (each in a
# process group of its own), not Python's Popen(start_new_session=True) -- after a run that
# completes (0), fails (69), or is stopped by SIGTERM or SIGINT, and when simbob is SIGKILLed.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
trap 'kill $(jobs -p) 2>/dev/null || true; for f in "$WORK"/*.pid; do [[ -s $f ]] && kill -9 "$(cat "$f")" 2>/dev/null; done; rm -rf "$WORK"' EXIT

SCENE="$SCENES/socket_robot.xml"
KEY=Bot.Cart.Link

# The controller: three descendants that leave simbob's reach by the usual means, each writing
# its pid, then (MODE ok) the example client, (fail) exit 3 before connecting, (wait) the client
# of a long run.
cat >spawner.sh <<SH
#!/bin/bash
mode=\$1
setsid sh -c 'echo \$\$ >"$WORK/setsid.pid"; exec sleep 300' &
bash -c 'set -m; sleep 300 & echo \$! >"$WORK/jobctl.pid"; sleep 300' &
/usr/bin/python3 -c 'import subprocess; p = subprocess.Popen(["sleep", "300"], start_new_session=True); open("$WORK/popen.pid", "w").write(str(p.pid))' &
for f in setsid jobctl popen; do
  for _ in \$(seq 600); do [[ -s "$WORK/\$f.pid" ]] && break; sleep 0.05; done
done
[[ \$mode == fail ]] && exit 3
exec /usr/bin/python3 "$REPO/scripts/simbob_client.py"
SH
chmod +x spawner.sh

# none_left WHAT: each recorded descendant is gone (or a zombie waiting for PID 1 to reap it).
none_left() {
  local f pid state
  for f in setsid jobctl popen; do
    [[ -s $f.pid ]] || fail "$1: the controller did not start its $f descendant"
    pid=$(cat $f.pid)
    state=$(awk '{print $3}' /proc/$pid/stat 2>/dev/null || true)
    [[ -z "$state" || "$state" == Z ]] || fail "$1: the $f descendant ($pid, state $state) outlived simbob: $(ps -o pid,ppid,pgid,sid,args -p $pid | tail -n 1)"
  done
  rm -f setsid.pid jobctl.pid popen.pid
}

# wait_running NAME: until the controller has started its descendants and the run NAME steps (its
# trajectory's temporary file has rows: the peer connected and sent commands); fails after 60 s.
# (The controller's log stays empty while it runs: Python buffers the client's output.)
wait_running() {
  local _ tmp
  for _ in $(seq 1200); do
    for tmp in "$1".csv.tmp.*; do
      [[ -s popen.pid && -s $tmp ]] && return 0
    done
    sleep 0.05
  done
  fail "$1: the run did not start stepping with its controller within 60 s"
}

check "a run that completes (0): nothing the controller started is left"
expect_status 0 "$SIMBOB" run "$SCENE" --duration 2 --out ok.csv -q --controller "$KEY=./spawner.sh ok" --peer-timeout 60
none_left "exit 0"

check "a controller that exits 3 before connecting (69): nothing it started is left"
expect_status 69 "$SIMBOB" run "$SCENE" --duration 2 --out fail.csv -q --controller "$KEY=./spawner.sh fail" --peer-timeout 60
none_left "exit 69"

for sig in TERM INT; do
  check "SIG$sig during the run: nothing the controller started is left"
  "$SIMBOB" run "$SCENE" --duration 100000 --out sig.csv -q --controller "$KEY=./spawner.sh wait" --peer-timeout 60 2>sig.err &
  run=$!
  wait_running sig
  kill -$sig $run
  status=0
  wait $run || status=$?
  want=143
  [[ $sig == TERM ]] || want=130
  expect_eq "exit status after SIG$sig ($(cat sig.err))" "$status" $want
  none_left "SIG$sig"
done

check "simbob SIGKILLed: nothing the controller started is left within 10 s"
"$SIMBOB" run "$SCENE" --duration 100000 --out kill.csv -q --controller "$KEY=./spawner.sh wait" --peer-timeout 60 2>kill.err &
run=$!
wait_running kill
kill -KILL $run
wait $run || true
# The keeper gives them 1 s after simbob is gone, then SIGKILL: at most a few s on a busy machine.
for _ in $(seq 200); do
  left=0
  for f in setsid jobctl popen; do
    state=$(awk '{print $3}' /proc/$(cat $f.pid)/stat 2>/dev/null || true)
    [[ -z "$state" || "$state" == Z ]] || left=1
  done
  [[ $left == 0 ]] && break
  sleep 0.05
done
none_left "SIGKILL"
say "ok"
