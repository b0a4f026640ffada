#!/usr/bin/env bash
# Texture files cost what they describe, once (issue 19): a BMP padded far past its pixels is
# refused unread when it is over the cap (65 naming it), read as its header says when under it;
# three skins naming one texture draw as one. Sparse files: no disk or memory is spent on the
# padding. Skips (77) when this machine has no GL back end.
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

# A 16 x 16 grey 24-bit BMP (54-byte header, rows of 48 bytes).
bmp() {
  /usr/bin/python3 - "$1" <<'PY'
import struct, sys
w = h = 16
row = (w * 24 + 31) // 32 * 4
pixels = bytes([90]) * (row * h)
head = b"BM" + struct.pack("<IHHI", 54 + len(pixels), 0, 0, 54)
head += struct.pack("<IiiHHIIiiII", 40, w, h, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
open(sys.argv[1], "wb").write(head + pixels)
PY
}
# A scene whose three boards are drawn with skins naming the texture file $1.
scene() {
  cat <<XML
<Simulation>
  <CameraList><RCStaticCamera Key="Face">
    <Pose><RCGlobalCoordinates><Pose Value="0 0 4 0 0 0"/></RCGlobalCoordinates></Pose>
  </RCStaticCamera></CameraList>
  <ComponentList>
    <RCTexturedSkin Key="A"><Texture Value="$1"/></RCTexturedSkin>
    <RCTexturedSkin Key="B"><Texture Value="$1"/></RCTexturedSkin>
    <RCTexturedSkin Key="C"><Texture Value="./$1"/></RCTexturedSkin>
$(for k in A B C; do
    x=$([[ $k == A ]] && echo -1.2 || { [[ $k == B ]] && echo 0 || echo 1.2; })
    printf '    <RCStaticRigidBody Key="Board%s"><Pose><RCGlobalCoordinates><Pose Value="%s 0 0 0 0 0"/></RCGlobalCoordinates></Pose>\n' "$k" "$x"
    printf '      <Model><RCPlaneModel><Skin Ref="%s"/><ExtensionX Value="1"/><ExtensionY Value="1"/></RCPlaneModel></Model></RCStaticRigidBody>\n' "$k"
  done)
  </ComponentList>
</Simulation>
XML
}

check "a 16 x 16 BMP padded to 2 GiB is refused unread: 65 naming it, nothing written"
mkdir -p s
bmp s/huge.bmp
truncate -s 2G s/huge.bmp
scene huge.bmp >s/huge.xml
/usr/bin/python3 - "$SIMBOB" <<'PY' || fail "render of the padded BMP"
import resource, subprocess, sys, time
t0 = time.monotonic()
p = subprocess.run([sys.argv[1], "render", "s/huge.xml", "--out", "huge.png", "--size", "64x48", "--quality", "textures",
                    "--camera", "Face"], capture_output=True, text=True)
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(f"exit {p.returncode}, {time.monotonic() - t0:.2f} s, peak {peak:.0f} MiB: {p.stderr.strip()}")
assert p.returncode == 65, p.returncode
assert p.stderr.startswith("s/huge.bmp: error: texture file of 2147483648 bytes is larger than"), p.stderr
assert peak < 512, f"peak {peak:.0f} MiB"
PY
expect_no_file huge.png

check "the same BMP padded to 1 GiB (under the cap) draws as the unpadded one, without reading the padding"
bmp s/plain.bmp
bmp s/padded.bmp
truncate -s 1G s/padded.bmp
scene plain.bmp >s/plain.xml
scene padded.bmp >s/padded.xml
expect_status 0 "$SIMBOB" render s/plain.xml --out plain.png --size 64x48 --quality textures --camera Face
/usr/bin/python3 - "$SIMBOB" <<'PY' || fail "render of the padded BMP"
import resource, subprocess, sys
p = subprocess.run([sys.argv[1], "render", "s/padded.xml", "--out", "padded.png", "--size", "64x48", "--quality",
                    "textures", "--camera", "Face"], capture_output=True, text=True)
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(f"exit {p.returncode}, peak {peak:.0f} MiB")
assert p.returncode == 0, p.stderr
assert peak < 512, f"peak {peak:.0f} MiB"
PY
expect_same_file padded.png plain.png
say "ok"
