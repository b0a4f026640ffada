#!/usr/bin/env bash
# Memory before any limit (issue 31, item 14): a replay page embeds each texture file once, as
# the renderer reads it (decoded, trailing bytes never read, within a budget), and says why a
# texture cannot be used instead of "not found"; `check` names the limits of camera sensors
# (their images together) and of pages (their textures together) before anything is run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

# bmp FILE W H: a W x H 24-bit BMP of noise (incompressible: a PNG of it is not much smaller).
bmp() {
  /usr/bin/python3 - "$@" <<'PY'
import os, struct, sys
path, w, h = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
row = (w * 24 + 31) // 32 * 4
pixels = os.urandom(row * h)
head = b"BM" + struct.pack("<IHHI", 54 + len(pixels), 0, 0, 54)
head += struct.pack("<IiiHHIIiiII", 40, w, h, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
open(path, "wb").write(head + pixels)
PY
}
# scene TEXTURE N: N boards, each with a skin of its own naming TEXTURE.
scene() {
  printf '<Simulation><ComponentList>\n'
  for i in $(seq "$2"); do
    printf '  <RCTexturedSkin Key="S%s"><Texture Value="%s"/></RCTexturedSkin>\n' "$i" "$1"
    printf '  <RCMobileRigidBody Key="Board%s"><Pose><RCGlobalCoordinates><Pose Value="%s 0 0 0 0 0"/></RCGlobalCoordinates></Pose>\n' "$i" "$i"
    printf '    <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>\n'
    printf '    <Model><RCPlaneModel><Skin Ref="S%s"/><ExtensionX Value="1"/><ExtensionY Value="1"/></RCPlaneModel></Model></RCMobileRigidBody>\n' "$i"
  done
  printf '</ComponentList></Simulation>\n'
}
size() { stat -c %s "$1"; }

check "ten skins naming one 512 x 512 texture: the page holds it once"
bmp noise.bmp 512 512
scene noise.bmp 1 >one.xml
scene noise.bmp 10 >ten.xml
printf 'time,body,x,y,z,qw,qx,qy,qz\n0,Board1,0,0,0,1,0,0,0\n' >t.csv
expect_status 0 "$SIMBOB" view t.csv --scene one.xml -o one.html
expect_status 0 "$SIMBOB" view t.csv --scene ten.xml -o ten.html
one=$(size one.html)
ten=$(size ten.html)
say "  one skin: $one bytes, ten skins: $ten bytes"
[[ $ten -lt $((one + 100000)) ]] || fail "ten skins of one texture make a page of $ten bytes, one skin $one"

check "a 16 x 16 BMP with 1 GiB after its pixels: the page is as small as without, and view is quick"
bmp small.bmp 16 16
bmp padded.bmp 16 16
truncate -s +1G padded.bmp
scene small.bmp 1 >small.xml
scene padded.bmp 1 >padded.xml
expect_status 0 "$SIMBOB" view t.csv --scene small.xml -o small.html
expect_status 0 "$SIMBOB" view t.csv --scene padded.xml -o padded.html
[[ $(size padded.html) -lt $(($(size small.html) + 2000)) ]] ||
  fail "the padded BMP makes a page of $(size padded.html) bytes, the plain one $(size small.html)"

check "a texture that cannot be read says why (65 naming the file), not 'not found'"
head -c 100 small.bmp >short.bmp
scene short.bmp 1 >short.xml
expect_status 65 "$SIMBOB" view t.csv --scene short.xml -o short.html
expect_match "the reason" "$LAST_ERR" '^(\./)?short\.bmp: error: BMP: file is shorter than its pixels$'
expect_no_file short.html

check "textures past the page's 256 MiB: view refuses naming the limit; check says so first"
bmp big.bmp 16384 8192  # 384 MiB decoded, header only: sparse
truncate -s $((54 + 16384 * 3 * 8192)) big.bmp
scene big.bmp 1 >big.xml
expect_status 0 "$SIMBOB" check big.xml
expect_match "check names the page limit" "$LAST_ERR" \
  "^big\.xml:2: warning: RCTexturedSkin 'S1': its texture big\.bmp takes 384 MiB decoded: the scene's textures come to 384 MiB, more than the 256 MiB a replay page embeds \(view and --html will refuse\)$"
expect_status 65 "$SIMBOB" view t.csv --scene big.xml -o big.html
expect_match "view names the limit" "$LAST_ERR" "texture memory: .* past 256 MiB"
expect_no_file big.html

check "four 8192 x 8192 camera sensors: check refuses them (65), naming the limit"
{
  printf '<Simulation><ComponentList>\n<RCConstruction Key="Bot"><Body><RCMobileRigidBody Key="Base">\n'
  printf '  <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom></RCMobileRigidBody></Body><ChildList>\n'
  for i in 1 2 3 4; do
    printf '  <RCCameraSensor Key="Eye%s"><Width Value="8192"/><Height Value="8192"/></RCCameraSensor>\n' "$i"
  done
  printf '</ChildList></RCConstruction>\n</ComponentList></Simulation>\n'
} >eyes.xml
expect_status 65 "$SIMBOB" check eyes.xml
expect_lines "one error a sensor past the limit" "$LAST_ERR" 3
expect_match "the second sensor's line names the limit" "$LAST_ERR" \
  "^eyes\.xml:5: error: RCCameraSensor 'Bot\.Eye2': the camera sensors' images together would be 134217728 pixels, more than 67108864 \(one 8192 x 8192 image\)$"
say "ok"
