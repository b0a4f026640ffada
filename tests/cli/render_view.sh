#!/usr/bin/env bash
# What `render` draws and writes (issue 18 point 4): --out must be a .png; scenes whose bodies
# have no models draw their collision shapes (--draw), framed where the bodies are at --at.
# The extension checks need no GL; the pictures skip (77) when this machine has no GL back end.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
BASIC="$REPO/tests/data/render/basic.xml"
PENDULUM="$SCENES/pendulum.xml"
pixels() { /usr/bin/python3 "$CLI_DIR/png_pixels.py" "$@"; }

check "render --out with another extension than .png is a usage error (64) naming it; nothing is written"
expect_status 64 "$SIMBOB" render "$BASIC" --out still.jpg
expect_match "--out x.jpg" "$LAST_ERR" "^simbob: error: --out still.jpg: a still is a .png, not .jpg$"
expect_no_file still.jpg
expect_status 64 "$SIMBOB" render "$BASIC" --out still
expect_match "--out without extension" "$LAST_ERR" "a still is a .png, not a name without extension"
expect_no_file still
expect_status 64 "$SIMBOB" render "$BASIC" --out still.bmp
expect_match "--out x.bmp" "$LAST_ERR" "not .bmp$"

check "--draw takes models, geoms or both; anything else is a usage error (64)"
expect_status 64 "$SIMBOB" render "$BASIC" --out x.png --draw meshes
expect_match "--draw" "$LAST_ERR" "--draw must be models, geoms, sensors or a list of them \\(models,sensors\\), got 'meshes'"
expect_no_file x.png

info_status=0
"$SIMBOB" info >info.txt 2>&1 || info_status=$?
if [ "$info_status" -eq 66 ] && ! grep -q ': EGL \|: OSMesa' info.txt; then
  say "skipped: no GL back end: $(tr '\n' ' ' <info.txt)"
  exit 77
fi
[ "$info_status" -eq 0 ] || fail "simbob info exited $info_status: $(cat info.txt)"

check "an upper-case .PNG is a PNG"
expect_status 0 "$SIMBOB" render "$BASIC" --out STILL.PNG --size 32x24
expect_file STILL.PNG

# The pendulum has no models: its bob is a 5 cm sphere geom. The default background is
# ClearColor 0.3 0.3 0.5.
BG="77 77 128"
check "a scene without models draws its collision shapes, says so once, and the default view frames the bob"
expect_status 0 "$SIMBOB" render "$PENDULUM" --out bob0.png --size 160x120
expect_match "notice" "$LAST_ERR" "^simbob: no body has a model: drawing the collision shapes \(--draw geoms"
expect_eq "notice lines" "$(grep -c 'no body has a model' "$LAST_ERR")" 1
centre=$(pixels bob0.png 80 60)
[ "$centre" != "$BG" ] || fail "the bob is not at the centre of the default view at t = 0: $centre"
n=$(pixels bob0.png --differing $BG)
[ "$n" -gt 30 ] || fail "only $n pixels differ from the background at t = 0"

check "--at 1: the default view frames the bob where it has swung to"
expect_status 0 "$SIMBOB" render "$PENDULUM" --at 1 --out bob1.png --size 160x120
centre=$(pixels bob1.png 80 60)
[ "$centre" != "$BG" ] || fail "the bob is not at the centre of the default view at t = 1: $centre"

check "--draw models draws the models alone, without a notice: an empty picture here"
expect_status 0 "$SIMBOB" render "$PENDULUM" --out models.png --size 160x120 --draw models
if grep -q 'no body has a model' "$LAST_ERR"; then fail "a notice with --draw models"; fi
expect_eq "pixels off the background" "$(pixels models.png --differing $BG)" 0

check "--draw models,geoms on a scene with models adds the collision shapes as wire frames"
expect_status 0 "$SIMBOB" render "$BASIC" --out m.png --size 160x120 --camera Front
expect_status 0 "$SIMBOB" render "$BASIC" --out mg.png --size 160x120 --camera Front --draw models,geoms
if grep -q 'no body has a model' "$LAST_ERR"; then fail "a notice on a scene with models"; fi
cmp -s m.png mg.png && fail "--draw models,geoms drew the same picture as the models alone"

check "run --record takes --draw too and falls back the same way"
expect_status 0 "$SIMBOB" run "$PENDULUM" --duration 0.2 --out p.csv --record frames --fps 10 --size 80x60
expect_eq "notice lines" "$(grep -c 'no body has a model' "$LAST_ERR")" 1
n=$(pixels frames/frame_000002.png --differing $BG)
[ "$n" -gt 5 ] || fail "frame 2 of the pendulum is empty"
expect_status 0 "$SIMBOB" run "$PENDULUM" --duration 0.2 --out p.csv --record frames2 --fps 10 --size 80x60 \
  --draw models
expect_eq "pixels off the background with --draw models" "$(pixels frames2/frame_000002.png --differing $BG)" 0

# A range sensor on a box at (0.25, 0.5, 0) looks along -Z at a wall whose face is at z = -1.9;
# camera Top at (0, 10, -1) looks straight down (image top = -Z), 160x120, 60 degrees: the ray
# is column 80 + f 0.25 / 9.5 = 83 (f = 80 / tan 30 deg), rows 60 + f (z + 1) / 9.5, so pixel
# (83, 60) is the ray at z = -1 (tests/render/sensor_rays_test.cpp checks every ray pixel).
cat >ray.xml <<'XML'
<Simulation>
  <CameraList>
    <RCStaticCamera Key="Top">
      <Pose><RCGlobalCoordinates><Pose Value="0 10 -1 -90 0 0"/></RCGlobalCoordinates></Pose>
    </RCStaticCamera>
  </CameraList>
  <ComponentList>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 -2 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="6"/><Height Value="1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Pose><RCGlobalCoordinates><Pose Value="0.25 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Geom><RCCuboidGeom><Width Value="0.1"/><Height Value="0.1"/><Depth Value="0.1"/></RCCuboidGeom></Geom>
      </RCMobileRigidBody></Body>
      <ChildList><RCRangeSensor Key="Front"><MaxRange Value="5"/></RCRangeSensor></ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>
XML
check "--draw geoms,sensors draws the range sensor's ray (red) where the projection puts it; --draw geoms does not"
expect_status 0 "$SIMBOB" render ray.xml --out plain.png --size 160x120 --camera Top --draw geoms
expect_status 0 "$SIMBOB" render ray.xml --out ray.png --size 160x120 --camera Top --draw geoms,sensors
bg=$(pixels plain.png 90 60)
expect_eq "pixel on the ray without sensors" "$(pixels plain.png 83 60)" "$bg"
expect_eq "pixel on the ray" "$(pixels ray.png 83 60)" "255 0 0"
expect_eq "pixel beside the ray" "$(pixels ray.png 90 60)" "$bg"

check "run --record --draw sensors draws the rays on the render thread's frames too"
expect_status 0 "$SIMBOB" run ray.xml --duration 0.1 --out r.csv --record rayframes --fps 10 --size 160x120 \
  --camera Top --draw sensors
expect_eq "frame 0 pixel on the ray" "$(pixels rayframes/frame_000000.png 83 60)" "255 0 0"
