#!/usr/bin/env bash
# Camera images on socket protocol version 3 (docs/socket-protocol.md#camera-images): a peer that
# subscribes to an RCCameraSensor gets `image KEY W H N` and N bytes of RGB in each state block,
# and they are, byte for byte, `simbob render --camera KEY --size WxH --at T` at the camera's
# Period instants (held in between); a peer that does not subscribe gets none. The Python client
# (python/simbob_client.py) and the C client (examples/clients/simbob_client.c) receive the same
# bytes and print the same lines; an unknown camera in `subscribe` is a protocol error (76).
# Skips (77) when this machine has no GL back end (as the other camera and render tests).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

info_status=0
"$SIMBOB" info >info.txt 2>&1 || info_status=$?
if [ "$info_status" -eq 66 ] && ! grep -q ': EGL \|: OSMesa' info.txt; then
  say "skipped: no GL back end: $(tr '\n' ' ' <info.txt)"
  exit 77
fi
[ "$info_status" -eq 0 ] || { cat info.txt >&2; fail "simbob info exited $info_status"; }

# A box with a camera on it falls towards the ground, looking at two walls (the scene of
# tests/render/camera_sensor_test.cpp); with $1 = socket, a communicator every 0.05 s as well.
scene() {
  local link=""
  [[ "${1:-}" == socket ]] && link='<RCLocalSocketCommunicator Key="Link"><IsServer Value="true"/>
          <Port Value="47391"/><Period Value="0.05"/></RCLocalSocketCommunicator>'
  cat <<XML
<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/></SceneSettings>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 -3 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="2"/><Height Value="1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCStaticRigidBody Key="Post">
      <Pose><RCGlobalCoordinates><Pose Value="0.8 1 -2 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="2"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
      </RCMobileRigidBody></Body>
      <ChildList>
        <RCCameraSensor Key="Eye">
          <Pose><RCLocalCoordinates><Pose Value="0 0.1 0 -10 0 0"/></RCLocalCoordinates></Pose>
          <Width Value="64"/><Height Value="48"/><Period Value="0.1"/>
        </RCCameraSensor>
        $link
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>
XML
}
scene socket >eye_socket.xml
scene >eye.xml
KEY=Bot.Link

# same_pixels PNG RGB: true if the PNG's pixels are the raw RGB file's bytes.
same_pixels() {
  /usr/bin/python3 - "$CLI_DIR" "$1" "$2" <<'PY'
import sys
sys.path.insert(0, sys.argv[1])
from png_pixels import read_png
w, h, channels, rows = read_png(sys.argv[2])
rgb = b"".join(bytes(b for i, b in enumerate(row) if i % channels < 3) for row in rows)
raw = open(sys.argv[3], "rb").read()
sys.exit(0 if (w, h) == (64, 48) and rgb == raw else 1)
PY
}

check "the Python client: images from t = 0.05 on (subscribed after the first state), none before"
expect_status 0 "$SIMBOB" run eye_socket.xml --duration 0.4 --out py.csv -q \
  --controller "$KEY=/usr/bin/python3 $CLI_DIR/socket_camera_peer.py py"
cat >expected.txt <<'TXT'
version 3
camera Bot.Eye 64 48 0.1
t 0.00 images 0
t 0.05 image Bot.Eye 64 48 9216
t 0.10 image Bot.Eye 64 48 9216
t 0.15 image Bot.Eye 64 48 9216
t 0.20 image Bot.Eye 64 48 9216
t 0.25 image Bot.Eye 64 48 9216
t 0.30 image Bot.Eye 64 48 9216
t 0.35 image Bot.Eye 64 48 9216
t 0.40 image Bot.Eye 64 48 9216
bye 0.4
TXT
diff expected.txt py.controller.log >py.diff || fail "the Python peer's printout: $(cat py.diff)"

check "the peer changes nothing: the same trajectory as the scene without the communicator"
expect_status 0 "$SIMBOB" run eye.xml --duration 0.4 --out plain.csv -q
expect_same_file py.csv plain.csv

check "the image at T is simbob render --camera Bot.Eye --size 64x48 --at T0, T0 the Period instant at or before T"
for pair in 0.00:0.05 0.10:0.10 0.10:0.15 0.30:0.30 0.30:0.35 0.40:0.40; do
  t0=${pair%:*} t=${pair#*:}
  [[ -f "render_$t0.png" ]] ||
    expect_status 0 "$SIMBOB" render eye.xml --at "$t0" --camera Bot.Eye --size 64x48 --out "render_$t0.png" --quiet
  same_pixels "render_$t0.png" "py_$t.rgb" || fail "the image at t=$t is not the render at $t0"
done
check "the check can fail: the pictures of 0.30 and 0.40 differ (the box fell)"
same_pixels render_0.30.png py_0.40.rgb && fail "the image at 0.40 is the render at 0.30"
cmp -s py_0.30.rgb py_0.40.rgb && fail "the images at 0.30 and 0.40 are the same"

check "the C client: the same printout and the same bytes"
${CC:-cc} -std=c99 -Wall -Wextra -Wpedantic -Werror -O2 -I "$REPO/examples/clients" -o camera_peer \
  "$CLI_DIR/socket_camera_peer.c" || fail "tests/cli/socket_camera_peer.c does not build"
expect_status 0 "$SIMBOB" run eye_socket.xml --duration 0.4 --out c.csv -q --controller "$KEY=$WORK/camera_peer c"
diff expected.txt c.controller.log >c.diff || fail "the C peer's printout: $(cat c.diff)"
for f in py_*.rgb; do
  expect_same_file "c_${f#py_}" "$f"
done

check "subscribe cameras with an unknown key: 'error' to the peer, exit 76"
for peer in "/usr/bin/python3 $CLI_DIR/socket_camera_peer.py" "$WORK/camera_peer"; do
  expect_status 76 "$SIMBOB" run eye_socket.xml --duration 0.4 --out bad.csv -q --controller "$KEY=$peer x bad"
  expect_match "the peer read the error" bad.controller.log \
    "^error 'subscribe cameras': no camera sensor has the key 'Bot.Nose' at t=0 s$"
  expect_match "the same on stderr" "$LAST_ERR" "'subscribe cameras': no camera sensor has the key 'Bot.Nose'"
done
say "ok"
