#!/usr/bin/env bash
# README "Your first scene" works as written:
#   - the XML block between <!-- first-scene:begin --> and <!-- first-scene:end --> is
#     examples/first_scene.xml, byte for byte;
#   - every `build/simbob ...` line of the command block between <!-- first-scene-commands:begin
#     --> and <!-- first-scene-commands:end --> runs and exits 0 (from a folder where
#     examples/ is the repository's), writing what README says: box.csv with box.json,
#     box-plot.png, box-at-1s.png;
#   - the trajectory is what README says happens: free fall, landing at sqrt(2 * 0.9 m / g),
#     no bounce, and the box at rest with its centre half its size (0.1 m) above the ground.
# Skips (77) only when this machine has no GL back end for the render line, after every other
# check has passed.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"
README="$REPO/README.md"
EXAMPLE="$REPO/examples/first_scene.xml"
PY=/usr/bin/python3

# block BEGIN END FILE: the lines strictly between the marker lines starting with BEGIN and END,
# without the ``` fence lines.
block() {
  awk -v b="$1" -v e="$2" 'index($0, e) == 1 {on = 0} on && !/^```/ {print} index($0, b) == 1 {on = 1; n++} END {if (n != 1) exit 1}' "$3"
}

check "README's first-scene XML block is examples/first_scene.xml"
block '<!-- first-scene:begin' '<!-- first-scene:end' "$README" >readme_scene.xml ||
  fail "README has no single <!-- first-scene:begin --> ... <!-- first-scene:end --> block"
[[ -s readme_scene.xml ]] || fail "README's first-scene block is empty"
expect_same_file readme_scene.xml "$EXAMPLE"

check "README's first-scene commands run as written"
block '<!-- first-scene-commands:begin' '<!-- first-scene-commands:end' "$README" >commands.txt ||
  fail "README has no single <!-- first-scene-commands:begin --> ... :end --> block"
ln -s "$REPO/examples" examples
ran=0
while IFS= read -r line; do
  [[ -z "$line" || "$line" == \#* ]] && continue
  [[ "$line" == "build/simbob "* ]] || fail "a command line that does not start with build/simbob: $line"
  read -r -a words <<<"${line#build/simbob }"
  # The render line needs a GL back end: skip it (and report the skip at the end) without one.
  if [[ "${words[0]}" == render ]]; then
    info_status=0
    "$SIMBOB" info >info.txt 2>&1 || info_status=$?
    if [ "$info_status" -eq 66 ] && ! grep -q ': EGL \|: OSMesa' info.txt; then
      no_gl="no GL back end: $(tr '\n' ' ' <info.txt)"
      continue
    fi
  fi
  say "  simbob ${words[*]}"
  expect_status 0 "$SIMBOB" "${words[@]}"
  ran=$((ran + 1))
done <commands.txt
[[ $ran -ge 3 ]] || fail "expected at least the check, run and plot lines, ran $ran"

check "the outputs README names are there"
expect_file box.csv
expect_file box.json
expect_eq "box.json status" "$(json_get box.json "j['status']")" completed
png_size() { $PY -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); sys.exit("not a PNG") if d[:8]!=b"\x89PNG\r\n\x1a\n" else print("%dx%d" % struct.unpack(">II", d[16:24]))' "$1"; }
expect_file box-plot.png
png_size box-plot.png >/dev/null || fail "box-plot.png is not a PNG"

check "the box falls freely, lands at sqrt(2 * 0.9 m / g), does not bounce, and rests at y = 0.1 m"
dt=$(json_get box.json "j['dt']")
$PY - box.csv "$dt" <<'PY' || fail "the first scene does not do what README says"
import csv, math, sys
rows = [r for r in csv.DictReader(open(sys.argv[1]))]
h = float(sys.argv[2])
g, y0, half = 9.81, 1.0, 0.1
bad = []
assert {r["body"] for r in rows} == {"Box"}, "expected the one body Box"
t = [float(r["time"]) for r in rows]
y = [float(r["y"]) for r in rows]
# Free fall until the bottom face reaches the ground at t_c = sqrt(2 (y0 - half) / g) = 0.428 s.
t_c = math.sqrt(2 * (y0 - half) / g)
# ODE integrates semi-implicitly (velocity first), so after n steps y = y0 - g h^2 n (n + 1) / 2:
# the exact parabola less g h t / 2 (0.2 mm at 0.4 s). Rounding of the sums: 1e-9 m.
for ti, yi in zip(t, y):
    if ti < t_c - 2 * h:
        n = round(ti / h)
        want = y0 - g * h * h * n * (n + 1) / 2
        if abs(yi - want) > 1e-9:
            bad.append(f"free fall: y({ti}) = {yi}, expected {want} (y0 - g t^2/2 - g h t/2)")
# It lands within one sample interval of t_c: the first sample at or below 0.1 m + 1 mm.
land = next((ti for ti, yi in zip(t, y) if yi <= half + 1e-3), None)
if land is None:
    sys.exit("\n".join(bad + [f"the box never came down to y = {half} m: lowest {min(y)}"]))
interval = t[1] - t[0]
if not (t_c - interval < land <= t_c + interval):
    bad.append(f"landed at t = {land}, expected within one sample ({interval} s) of {t_c:.4f}")
# No bounce (the default material has Bounceness 0): afterwards the box never rises by more
# than it sank in the landing step, at most its impact speed times one step (4.2 mm); a
# bounce with Bounceness 0.6 would rise 0.6^2 * 0.9 m = 0.32 m.
v_c = math.sqrt(2 * g * (y0 - half))
top = max(yi for ti, yi in zip(t, y) if ti > land)
if top > half + v_c * h:
    bad.append(f"after landing the box rose to y = {top} (> {half} + v h = {half + v_c * h}): it bounced")
# At rest at t = 2 s, centre at half the box's size. The sinking of the landing step decays by
# (1 - ERP) = 0.8 per step, so after 1.5 s only the contact's softness remains, CFM m g = 1e-9 m
# (measured 1.5e-10 m); 1e-6 m.
last = rows[-1]
if abs(float(last["y"]) - half) > 1e-6:
    bad.append(f"at t = {last['time']} y = {last['y']}, expected {half} +- 1e-6 m")
# It lands flat on its face and stays there: x and z stay at 0 and the orientation at identity
# up to QuickStep's residual over the four contact points, which rocks the box on single
# samples by 4e-5 rad (measured: 2.1e-5 in a quaternion component, 2.8e-6 m); 1e-4. Tipping
# onto an edge or sliding away is far beyond that.
for r in rows:
    if max(abs(float(r["x"])), abs(float(r["z"]))) > 1e-4:
        bad.append(f"the box moved sideways: t = {r['time']} x = {r['x']} z = {r['z']}")
        break
    if max(abs(float(r[k])) for k in ("qx", "qy", "qz")) > 1e-4:
        bad.append(f"the box turned: t = {r['time']} q = {r['qw']} {r['qx']} {r['qy']} {r['qz']}")
        break
if bad:
    sys.exit("\n".join(bad))
print(f"landed at t = {land} (t_c = {t_c:.4f}); highest after landing {top:.6f}; final y = {last['y']}")
PY

if [[ -n "${no_gl:-}" ]]; then
  say "skipped the render line: $no_gl"
  exit 77
fi
check "the render line drew the box: box-at-1s.png is 640x480 with the orange box in its middle"
expect_file box-at-1s.png
expect_eq "box-at-1s.png size" "$(png_size box-at-1s.png)" 640x480
$PY - box-at-1s.png <<'PY' || fail "box-at-1s.png does not show the box where README's picture does"
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
pos, idat, w, h, ctype = 8, b"", 0, 0, 0
while pos < len(data):
    n, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    if kind == b"IHDR":
        w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and ctype in (2, 6), f"expected 8-bit RGB(A), got depth {depth} type {ctype}"
    elif kind == b"IDAT":
        idat += body
    pos += 12 + n
bpp = 3 if ctype == 2 else 4
raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
for r in range(h):
    f, line = raw[r * (stride + 1)], bytearray(raw[r * (stride + 1) + 1:(r + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - bpp] if i >= bpp else 0
        b, c = prev[i], prev[i - bpp] if i >= bpp else 0
        p = a + b - c
        pred = [0, a, b, (a + b) // 2, a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c][f]
        line[i] = (line[i] + pred) & 0xFF
    rows.append(line)
    prev = line
px = lambda x, y: tuple(rows[y][x * bpp:x * bpp + 3])
# The camera stands 2 m in front, 0.5 m up, tilted 10 deg down: the box (0.2 m, centre 0.1 m
# up) is drawn around the middle column, a little below the middle row; the sky above it.
box = px(w // 2, h * 250 // 480)
r, g, b = box
assert r > 120 and r > g + 40 and g > b + 30, f"expected the orange box at the centre, got {box}"
top = px(w // 2, 10)
assert top != box and top[2] > top[0], f"expected the background (bluish) at the top, got {top}"
print(f"centre {box}, top {top}")
PY
say "ok"
