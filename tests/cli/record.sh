#!/usr/bin/env bash
# Recording (issue #12): run --record writes frame n at t = n / fps as PNGs, leaves the
# trajectory byte for byte as it is without recording, never overwrites a recording; render
# draws one still. Skips (77) when this machine has no GL back end.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
BASIC="$REPO/tests/data/render/basic.xml"
ROBOT="$SCENES/two_wheel_robot.xml"

# Skip only when info says that neither back end is there (exit 66, EX_NOINPUT); any other
# failure of info (a crash, a sanitizer report) fails the test.
info_status=0
"$SIMBOB" info >info.txt 2>&1 || info_status=$?
if [ "$info_status" -eq 66 ] && ! grep -q ': EGL \|: OSMesa' info.txt; then
  say "skipped: no GL back end: $(tr '\n' ' ' <info.txt)"
  exit 77
fi
if [ "$info_status" -ne 0 ]; then
  cat info.txt >&2
  fail "simbob info exited $info_status"
fi
check "info names a back end and its GL_RENDERER"
expect_match "info" info.txt '^gl (egl|osmesa): (EGL \((surfaceless|device)\)|OSMesa), GL_RENDERER .+'

check "a run with --record writes the same trajectory bytes as one without (robot with controllers)"
expect_status 0 "$SIMBOB" run "$ROBOT" --duration 2 --out plain.csv
expect_status 0 "$SIMBOB" run "$ROBOT" --duration 2 --out rec.csv --record frames --fps 10 --size 64x48
expect_same_file rec.csv plain.csv

check "2 s at 10 fps: frames 0 to 20 (t = 0, 0.1, ..., 2), each a 64x48 PNG; the summary counts them"
n=$(find frames -name 'frame_*.png' | wc -l)
expect_eq "frames" "$n" 21
expect_file frames/frame_000000.png
expect_file frames/frame_000020.png
expect_no_file frames/frame_000021.png
python3 - frames/frame_000020.png <<'PY'
import struct, sys
b = open(sys.argv[1], 'rb').read(32)
assert b[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
w, h = struct.unpack('>II', b[16:24])
assert (w, h) == (64, 48), (w, h)
PY
expect_eq "frames in the summary" "$(json_get rec.json "j['frames']")" 21

check "a directory that already holds a recording is refused (73), nothing overwritten"
cp frames/frame_000000.png keep.png
expect_status 73 "$SIMBOB" run "$ROBOT" --duration 1 --out again.csv --record frames --fps 10 --size 64x48
expect_match "message" "$LAST_ERR" 'already holds a recording'
expect_same_file frames/frame_000000.png keep.png

check "each back end this machine has records through --gl (the references are compared per back end in render.egl, render.osmesa)"
for gl in egl osmesa; do
  if "$SIMBOB" info --gl "$gl" >/dev/null 2>&1; then
    expect_status 0 "$SIMBOB" run "$BASIC" --duration 0.1 --out "$gl.csv" --record "rec-$gl" --fps 10 --size 160x120 \
      --gl "$gl" --camera Front
  fi
done

check "render --at 0 draws the same picture as frame 0 of a recording"
expect_status 0 "$SIMBOB" render "$BASIC" --out still.png --size 160x120 --camera Front
[[ -d rec-egl ]] && expect_same_file still.png rec-egl/frame_000000.png

check "render --at T follows the frames of a recording at --fps: the tracking camera's still is frame T*fps"
GALLERY="$SCENES/gallery.xml"
expect_status 0 "$SIMBOB" run "$GALLERY" --duration 1 --out chase.csv --record chase --fps 10 --size 96x72 --camera Chase
expect_status 0 "$SIMBOB" render "$GALLERY" --at 1 --fps 10 --out chase-still.png --size 96x72 --camera Chase
expect_same_file chase-still.png chase/frame_000010.png
# The camera did move: the still from frame 0's place differs (else the check proves nothing).
cmp -s chase/frame_000000.png chase/frame_000010.png && fail "Chase frames 0 and 10 are the same picture"
expect_status 64 "$SIMBOB" render "$GALLERY" --at 1 --fps 0 --out x.png
expect_match "--fps" "$LAST_ERR" "--fps must be above 0 and at most 1000, got 0"

check "DocumentIni: camera Front given Top's pose in basic.ini draws Top's picture (the same bytes)"
mkdir docini
cp "$BASIC" docini/basic.xml
printf '[Front]\nPose.Pose = 0 8 0 -90 0 0\n' >docini/basic.ini
printf 'DocumentIni = True\n' >docini/settings.ini
expect_status 0 "$SIMBOB" render docini/basic.xml --out top.png --size 160x120 --camera Top
expect_status 0 "$SIMBOB" render docini/basic.xml --out front-ini.png --size 160x120 --camera Front \
  --settings docini/settings.ini
expect_same_file front-ini.png top.png
cmp -s still.png top.png && fail "Front and Top draw the same picture: the check above proves nothing"

check "bad view options are usage errors (64) naming the option"
expect_status 64 "$SIMBOB" render "$BASIC" --out x.png --size 0x10
expect_match "--size" "$LAST_ERR" "--size must be WIDTHxHEIGHT"
expect_status 64 "$SIMBOB" render "$BASIC" --out x.png --quality shiny
expect_match "--quality" "$LAST_ERR" "--quality must be frame, wire"
expect_status 64 "$SIMBOB" render "$BASIC" --out x.png --gl vulkan
expect_match "--gl" "$LAST_ERR" "--gl must be egl or osmesa, got 'vulkan'"
expect_status 65 "$SIMBOB" render "$BASIC" --out x.png --camera Side
expect_match "--camera" "$LAST_ERR" "no camera 'Side' in the scene \(cameras: Front, Top\)"
expect_no_file x.png

check "a run without --record never touches GL: a bad SIMBOB_GL does not matter to it"
SIMBOB_GL=vulkan expect_status 0 "$SIMBOB" run "$BASIC" --duration 0.1 --out nogl.csv
SIMBOB_GL=vulkan expect_status 64 "$SIMBOB" run "$BASIC" --duration 0.1 --out nogl.csv --record r2
expect_match "SIMBOB_GL" "$LAST_ERR" "SIMBOB_GL must be egl or osmesa, got 'vulkan'"

check "--video: the same frames as one MP4 (H.264) and one AVI (MJPEG): 1 s at 10 fps = 11 frames"
for ext in mp4 avi; do
  expect_status 0 "$SIMBOB" run "$BASIC" --duration 1 --out "v-$ext.csv" --video "clip.$ext" --fps 10 --size 64x48
  expect_file "clip.$ext"
  if command -v ffprobe >/dev/null; then
    frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,width,height \
      -of csv=p=0 "clip.$ext")
    expect_eq "ffprobe width,height,frames of clip.$ext" "$frames" "64,48,11"
  fi
done
check "--video with an odd size for H.264 is a usage error before anything runs"
expect_status 64 "$SIMBOB" run "$BASIC" --duration 1 --out odd.csv --video odd.mp4 --size 65x48
expect_match "odd size" "$LAST_ERR" "must be even"
expect_no_file odd.mp4
say "ok"
