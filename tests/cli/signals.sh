#!/usr/bin/env bash
# SIGINT and SIGTERM stop a run at the next step: exit 130 / 143, the samples so far kept in
# NAME.partial.csv, NAME.csv never created. Also (issue #10, items 5-8): a step that does not
# end is abandoned within about a second; --check-determinism interrupted in its second run is
# an interrupt; a signal while loading says so; batch forwards the signal to its workers and a
# killed batch leaves no workers behind.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# interrupt SIGNAL EXPECTED_STATUS NAME
interrupt() {
  local sig=$1 want=$2 name=$3 pid status=0 i
  check "SIG$sig: a 100000 s run of box_stack, interrupted after a second, exits $want"
  "$SIMBOB" run "$SCENES/box_stack.xml" --duration 100000 --out "$name.csv" >"$name.out" 2>"$name.err" &
  pid=$!
  # Wait until the run has started (its temporary trajectory exists), then let it run a while.
  for ((i = 0; i < 100; i++)); do
    compgen -G "$name.csv.tmp*" >/dev/null && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  sleep 1
  kill -0 "$pid" 2>/dev/null || fail "the run ended before it was signalled: $(cat "$name.err")"
  kill -"$sig" "$pid"
  # It must stop promptly; never leave it running.
  for ((i = 0; i < 100; i++)); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    kill -KILL "$pid"
    wait "$pid" || true
    fail "SIG$sig did not stop the run within 10 s"
  fi
  wait "$pid" || status=$?
  expect_eq "exit status after SIG$sig" "$status" "$want"
  expect_match "the error says it was interrupted" "$name.err" "error: interrupted at t="
  expect_match "stderr names the partial trajectory" "$name.err" "$name.partial.csv"

  check "SIG$sig: $name.partial.csv holds whole samples from t = 0; no $name.csv, no .json"
  expect_no_file "$name.csv"
  expect_no_file "$name.json"
  expect_file "$name.partial.csv"
  local summary samples bodies rows first last
  summary=$(csv_summary "$name.partial.csv")
  read -r samples bodies rows first last <<<"$summary"
  expect_eq "bodies in the partial trajectory" "$bodies" 6
  expect_eq "first time" "$first" "0.0"
  expect_eq "rows = samples * bodies" "$rows" "$((samples * bodies))"
  [[ $samples -ge 2 ]] || fail "only $samples samples after running a second"
  local leftovers
  leftovers=$(find . -name "$name.*tmp*")
  expect_eq "temporary files" "$leftovers" ""
}

interrupt INT 130 int
interrupt TERM 143 term

# wait_for GLOB PID: until a file matching GLOB exists (the run has started), at most 20 s.
wait_for() {
  local i
  for ((i = 0; i < 200; i++)); do
    compgen -G "$1" >/dev/null && return 0
    kill -0 "$2" 2>/dev/null || fail "process $2 ended before $1 appeared"
    sleep 0.1
  done
  fail "$1 did not appear within 20 s"
}
# stops_within SECONDS PID: the process ends within SECONDS (else it is killed and we fail).
stops_within() {
  local i
  for ((i = 0; i < $1 * 10; i++)); do
    kill -0 "$2" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -KILL "$2" 2>/dev/null || true
  fail "process $2 still running $1 s after the signal"
}

# ---------------------------------------------------------------- 6: a step that does not end
check "SIGTERM in the middle of a step that takes seconds: exit 143 within about a second"
# 450 coincident boxes in a Simple space with 64 contacts a pair: one step takes several
# seconds (about 6 s here) while loading takes a fraction of one.
python3 - <<'PY'
body = ('<RCMobileRigidBody Key="B%d"><Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/>'
        '</RCGlobalCoordinates></Pose><Geom><RCCuboidGeom/></Geom></RCMobileRigidBody>\n')
with open("slow.xml", "w") as f:
    f.write('<Simulation><SceneSettings><Space Value="Simple"/><MaxContacts Value="64"/></SceneSettings>\n'
            '<ComponentList>\n' + "".join(body % i for i in range(450)) + '</ComponentList></Simulation>\n')
PY
"$SIMBOB" run slow.xml --duration 10 --out slow.csv >slow.out 2>slow.err &
pid=$!
wait_for "slow.csv.tmp*" $pid
sleep 1
kill -TERM $pid
stops_within 3 $pid
status=0
wait $pid || status=$?
expect_eq "exit status" "$status" 143
expect_match "message" slow.err "^simbob: error: interrupted at t=0 s \(the last whole sample; the step under way was abandoned\)$"
expect_match "partial named" slow.err "^simbob: kept the trajectory so far in slow.partial.csv$"
summary=$(csv_summary slow.partial.csv)
expect_eq "the partial holds the t=0 sample of every box" "$summary" "1 450 450 0.0 0.0"
expect_no_file slow.csv
expect_no_file slow.json
expect_eq "temporary files" "$(find . -name 'slow.*tmp*')" ""

# ---------------------------------------------------------------- 7: --check-determinism
check "SIGINT in the second run of --check-determinism is an interrupt, not a difference"
"$SIMBOB" run "$SCENES/box_stack.xml" --duration 100 --check-determinism --verbose --out det.csv \
  >det.out 2>det.err &
pid=$!
for ((i = 0; i < 600; i++)); do
  grep -q "running the scene a second time" det.err && break
  kill -0 $pid 2>/dev/null || fail "the run ended before its second run: $(cat det.err)"
  sleep 0.1
done
grep -q "running the scene a second time" det.err || fail "no second run within 60 s"
kill -INT $pid
stops_within 3 $pid
status=0
wait $pid || status=$?
expect_eq "exit status" "$status" 130
expect_match "message" det.err "error: interrupted at t=.* \(second run of --check-determinism\)$"
if grep -q "differ" det.err; then fail "an interrupt reported as a difference: $(cat det.err)"; fi
expect_eq "the partial holds the whole first run" "$(csv_summary det.partial.csv | cut -d' ' -f1,2,5)" "10001 6 100.0"
expect_no_file det.csv

# ---------------------------------------------------------------- 8: while loading
check "a signal while loading says so: exit 130/143 with one line"
python3 - <<'PY'
body = ('<RCMobileRigidBody Key="B%d"><Pose><RCGlobalCoordinates><Pose Value="%d 1 0 0 0 0"/>'
        '</RCGlobalCoordinates></Pose><Geom><RCSphereGeom/></Geom></RCMobileRigidBody>\n')
with open("big.xml", "w") as f:
    f.write('<Simulation><ComponentList>\n' + "".join(body % (i, i) for i in range(40000)) +
            '</ComponentList></Simulation>\n')
PY
# The signal goes as soon as simbob catches SIGTERM (its mask in /proc/PID/status), which it
# starts to do as it starts loading: loading these 40,000 bodies takes a few tenths of a second,
# a fixed delay could land after it on a fast machine (it did: check had printed "ok").
caught_term() {
  local mask
  # simbob itself, not the shell that forks it (which catches SIGTERM too until it execs)
  [ "$(cat "/proc/$1/comm" 2>/dev/null)" = simbob ] || return 1
  mask=$(awk '/^SigCgt:/ {print $2}' "/proc/$1/status" 2>/dev/null) || return 1
  [ -n "$mask" ] && (((16#$mask >> 14) & 1))  # SIGTERM is signal 15: bit 14
}
for cmd in "run big.xml --duration 1 --out big.csv" "check big.xml"; do
  # shellcheck disable=SC2086
  "$SIMBOB" $cmd >load.out 2>load.err &
  pid=$!
  for _ in $(seq 1 2000); do
    caught_term $pid && break
    sleep 0.002
  done
  kill -TERM $pid
  status=0
  wait $pid || status=$?
  expect_eq "$cmd: exit status" "$status" 143
  expect_eq "$cmd: stderr" "$(cat load.err)" "big.xml: error: interrupted while loading (SIGTERM)"
done
expect_no_file big.csv
expect_eq "temporary files" "$(find . -name 'big.*tmp*')" ""

# ---------------------------------------------------------------- 5: batch
check "SIGTERM to batch: forwarded to the workers, partials kept, reported interrupted, exit 143"
mkdir -p bs
cp "$SCENES/box_stack.xml" bs/a.xml
cp "$SCENES/box_stack.xml" bs/b.xml
"$SIMBOB" batch bs/a.xml bs/b.xml -j 2 --duration 100000 --out-dir bout --report bout/report.json \
  >batch.out 2>batch.err &
pid=$!
wait_for "bout/a.csv.tmp*" $pid
wait_for "bout/b.csv.tmp*" $pid
workers=$(pgrep -P $pid | tr '\n' ' ')
[[ -n "$workers" ]] || fail "no worker processes found"
sleep 0.5
kill -TERM $pid
stops_within 5 $pid
status=0
wait $pid || status=$?
expect_eq "exit status" "$status" 143
for w in $workers; do
  if kill -0 "$w" 2>/dev/null; then fail "worker $w still running after batch ended"; fi
done
expect_match "a reported interrupted" batch.out "\] interrupted  bs/a.xml"
expect_match "b reported interrupted" batch.out "\] interrupted  bs/b.xml"
expect_eq "statuses in the report" "$(json_get bout/report.json '[r["status"] for r in j["results"]]')" \
  "['interrupted', 'interrupted']"
expect_file bout/a.partial.csv
expect_file bout/b.partial.csv
expect_no_file bout/a.csv

check "SIGKILL to batch: its workers do not outlive it"
rm -rf bout
"$SIMBOB" batch bs/a.xml bs/b.xml -j 2 --duration 100000 --out-dir bout >batch.out 2>batch.err &
pid=$!
wait_for "bout/a.csv.tmp*" $pid
wait_for "bout/b.csv.tmp*" $pid
workers=$(pgrep -P $pid | tr '\n' ' ')
kill -KILL $pid
wait $pid 2>/dev/null || true
for w in $workers; do stops_within 5 "$w"; done
expect_file bout/a.partial.csv
expect_file bout/b.partial.csv
say "ok"
