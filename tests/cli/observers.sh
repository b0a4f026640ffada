#!/usr/bin/env bash
# Observing a run never changes it (the fixed step grid): every shipped scene, run for 2 s and
# watched every way simbob can watch it -- sample intervals h, 0.01, 0.0125 and 0.03 s; PNG
# frames and videos at 10, 24, 25, 30 and 60 fps; the run log; --check-determinism -- writes at
# each of its sample times exactly the row (byte for byte) that a run sampled every step writes
# at that grid instant. And the socket scene's peer, exchanging every 0.01 s or every 1/30 s,
# sends the same commands (they change every 0.1 s) and gives the same trajectory bytes.
# Before the fixed grid, a 30 fps recording split steps and moved the chain 0.43 m.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
trap 'kill $(jobs -p) 2>/dev/null || true; rm -rf "$WORK"' EXIT

PY=/usr/bin/python3
[[ -x $PY ]] || PY=python3
DURATION=2
VIDEO_FPS=(10 24 25 30 60)
RECORD_FPS=(30 60)
# The sanitizer build (scripts/sanitize.sh) runs a lighter set: the same observers on every
# scene, 1 s, with the frame rates that split the step grid differently (10 divides it, 30 does
# not); this build runs them all.
if [[ -n "${SIMBOB_SANITIZED:-}" ]]; then
  DURATION=1
  VIDEO_FPS=(10 30)
  RECORD_FPS=(30)
fi
VIEW=(--size 32x24 --gl "${SIMBOB_GL:-osmesa}")
have_gl=1
"$SIMBOB" info >info.txt 2>&1 || true
grep -qi "osmesa.*ok\|OSMesa" info.txt || have_gl=0

step_of() { $PY -c 'import json,sys; print(repr(json.load(open(sys.argv[1]))["dt"]))' "$1"; }

for scene in $(shipped_scenes); do
  name=$(basename "$scene" .xml)
  check "$name: rows at shared grid times equal the run sampled every step"
  expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --out "$name.default.csv" -q
  h=$(step_of "$name.default.json")
  expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --sample-interval "$h" --out "$name.every.csv" -q
  outs=("$name.default.csv")
  for si in 0.01 0.0125 0.03; do
    expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --sample-interval $si --out "$name.si$si.csv" -q
    outs+=("$name.si$si.csv")
  done
  expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --log joints,sensors,commands --out "$name.log.csv" -q
  outs+=("$name.log.csv")
  expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --check-determinism --out "$name.det.csv" -q
  outs+=("$name.det.csv")
  if [[ $have_gl == 1 ]]; then
    for fps in "${VIDEO_FPS[@]}"; do
      expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --fps $fps --video "$name.$fps.avi" "${VIEW[@]}" \
        --out "$name.video$fps.csv" -q
      outs+=("$name.video$fps.csv")
      frames=$($PY -c 'import json,sys; print(json.load(open(sys.argv[1]))["frames"])' "$name.video$fps.json")
      # Frame n shows the first grid instant at or after n/fps: one frame per 1/fps, t = 0 included.
      [[ $frames == $((DURATION * fps + 1)) ]] || fail "$name at $fps fps: $frames frames, expected $((DURATION * fps + 1))"
    done
    for fps in "${RECORD_FPS[@]}"; do
      expect_status 0 "$SIMBOB" run "$scene" --duration $DURATION --fps $fps --record "frames$fps.$name" "${VIEW[@]}" \
        --out "$name.record$fps.csv" -q
      outs+=("$name.record$fps.csv")
    done
  fi
  $PY "$CLI_DIR/grid_rows.py" "$name.every.csv" "${outs[@]}" || fail "$name: an observer changed the trajectory"
done
[[ $have_gl == 1 ]] || say "note: no GL back end here, so the --video and --record runs were left out"

check "socket_robot: a peer exchanging every 0.01 s and one every 1/30 s give the same bytes"
# The scene names its peer program (Controller); this peer is started by hand instead.
sed '/<Controller Value=/d' "$SCENES/socket_robot.xml" >by_hand.xml
SCENE="$WORK/by_hand.xml"
BASE_PORT=47311
free_port() {
  $PY -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()'
}
for period in 0.01 0.0333333333333333; do
  port=$(free_port)
  $PY "$CLI_DIR/grid_peer.py" "$port" >peer.out 2>peer.err &
  peer=$!
  expect_status 0 "$SIMBOB" run "$SCENE" --duration $DURATION --set "Bot.Cart.Link.Period=$period" \
    --port-offset $((port - BASE_PORT)) --out "socket$period.csv" -q
  wait $peer || fail "the peer failed: $(cat peer.err)"
done
expect_same_file socket0.01.csv socket0.0333333333333333.csv
say "ok"
