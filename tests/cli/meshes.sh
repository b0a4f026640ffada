#!/usr/bin/env bash
# Mesh files in scenes (RCMeshGeom, RCMeshModel; docs/meshes.md): check reports each mesh once;
# a missing mesh is 66 and a corrupt one 65, at the File line; file names with spaces work; two
# triangle meshes that can touch are named in a warning; `types` lists both types; the replay
# page embeds each mesh once.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

mkdir -p "s/my meshes"
cp "$REPO/tests/data/meshes/cube_100mm.stl" "s/my meshes/cube 100mm.stl"
printf 'this is not a mesh\n' >s/junk.stl
# scene GEOM_FILE [MORE]: a ground and one free body whose geom and model read GEOM_FILE, plus MORE.
scene() {
  cat <<XML
<Simulation>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCMobileRigidBody Key="Part">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.2 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Model><RCMeshModel><File Value="$1"/><Scale Value="0.001 0.001 0.001"/></RCMeshModel></Model>
      <Geom><RCMeshGeom><File Value="$1"/>
        <Scale Value="0.001 0.001 0.001"/></RCMeshGeom></Geom>
    </RCMobileRigidBody>
${2:-}
  </ComponentList>
</Simulation>
XML
}

check "check reports the mesh once, read from a folder and file whose names have spaces"
scene "my meshes/cube 100mm.stl" >s/spaces.xml
expect_status 0 "$SIMBOB" check s/spaces.xml
expect_match "ok line" "$LAST_ERR" "s/spaces.xml: ok \(1 mobile body, 2 geoms, 0 joints\)"
expect_match "mesh line" "$LAST_ERR" \
  "s/spaces.xml: mesh s/my meshes/cube 100mm.stl \(scale 0.001 0.001 0.001\): 8 vertices, 12 triangles, closed; hull of 1 geom \(8 points, 6 faces\); drawn by 1 model$"
expect_eq "mesh lines" "$(grep -c ': mesh ' "$LAST_ERR")" 1

check "it runs: the 0.1 m cube comes to rest at half its size"
expect_status 0 "$SIMBOB" run s/spaces.xml --duration 1 --out spaces.csv
last=$(tail -n 1 spaces.csv)
y=$(cut -d, -f4 <<<"$last")
float_between "resting height" "$y" 0.0499 0.0501

check "a hull drawn away from its frame (origin outside it) runs without ODE's warnings and rests right"
# The same 0.1 m cube, its vertices 1.0 to 1.1 m along x from the mesh frame's origin: ODE's
# dGeomConvex wants the origin inside the hull and prints "Plane N does not contain the origin"
# on stdout otherwise; simbob hands ODE the hull moved to its centre and moves the geom back.
# The body's frame comes to rest where the centred cube's did in the check above (spaces.csv):
# within 1e-6 m on every axis (the contacts are computed in the moved frame, so they agree to
# rounding, not to the bit; a contact at the wrong place would leave the cube 0.05 m off or tipped).
/usr/bin/python3 - "$REPO/tests/data/meshes/cube_100mm.stl" s/off_origin.stl <<'PY'
import sys
out = []
for line in open(sys.argv[1]):
    parts = line.split()
    if parts and parts[0] == "vertex":
        line = "      vertex %g %s %s\n" % (float(parts[1]) + 1050, parts[2], parts[3])
    out.append(line)
open(sys.argv[2], "w").write("".join(out))
PY
scene "off_origin.stl" >s/off_origin.xml
expect_status 0 "$SIMBOB" run s/off_origin.xml --duration 1 --out off_origin.csv
expect_eq "ODE's warnings on stdout or stderr" "$(grep -c WARNING "$LAST_OUT" "$LAST_ERR" | paste -sd' ')" \
  "$LAST_OUT:0 $LAST_ERR:0"
for axis in 3 4 5; do
  a=$(tail -n 1 off_origin.csv | cut -d, -f$axis)
  b=$(tail -n 1 spaces.csv | cut -d, -f$axis)
  float_between "resting position (column $axis) minus the centred cube's" "$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3g", a - b }')" -0.000001 0.000001
done

check "a missing mesh is 66, one line naming the scene's File line and the file"
scene "my meshes/nothing here.stl" >s/missing.xml
expect_status 66 "$SIMBOB" run s/missing.xml --duration 1 --out missing.csv
expect_eq "error line" "$(cat "$LAST_ERR")" \
  "s/missing.xml:7: error: RCMeshGeom 'Part.Geom': mesh 's/my meshes/nothing here.stl': cannot read the mesh: No such file or directory
s/missing.xml:6: error: RCMeshModel 'Part.Model': mesh 's/my meshes/nothing here.stl': cannot read the mesh: No such file or directory"
expect_no_file missing.csv
expect_status 66 "$SIMBOB" check s/missing.xml

check "a corrupt mesh is 65 at its line"
scene "junk.stl" >s/junk.xml
expect_status 65 "$SIMBOB" check s/junk.xml
expect_match "corrupt" "$LAST_ERR" "^s/junk.xml:7: error: RCMeshGeom 'Part.Geom': mesh 's/junk.stl': not a mesh assimp can read: "

check "two triangle meshes that can touch: a warning naming both, with their files and lines"
scene "my meshes/cube 100mm.stl" '    <RCStaticRigidBody Key="Floor"><Geom><RCMeshGeom><File Value="my meshes/cube 100mm.stl"/>
      <Scale Value="0.01 0.001 0.01"/></RCMeshGeom></Geom></RCStaticRigidBody>' >s/pair.xml
sed -i 's|<Scale Value="0.001 0.001 0.001"/></RCMeshGeom>|<Scale Value="0.001 0.001 0.001"/><Hull Value="False"/></RCMeshGeom>|' s/pair.xml
expect_status 0 "$SIMBOB" check s/pair.xml
expect_match "pair warning" "$LAST_ERR" \
  "s/pair.xml:7: warning: the triangle meshes of 'Part' \(cube 100mm.stl, s/pair.xml:7\) and 'Floor' \(cube 100mm.stl, s/pair.xml:10\) can touch"
expect_match "both are triangle meshes" "$LAST_ERR" "triangle mesh of 1 geom"

check "types lists RCMeshGeom and RCMeshModel with their parameters"
expect_status 0 "$SIMBOB" types RCMeshGeom
expect_match "File" "$LAST_OUT" "File"
expect_match "Hull" "$LAST_OUT" "Hull"
expect_status 0 "$SIMBOB" types RCMeshModel
expect_match "Scale" "$LAST_OUT" "Scale"

check "the replay page embeds each mesh once (the model's triangles; the geom's hull)"
expect_status 0 "$SIMBOB" view spaces.csv --scene s/spaces.xml --out spaces.html
/usr/bin/python3 - spaces.html <<'PY' || fail "page meshes"
import json, re, sys
page = open(sys.argv[1]).read()
data = json.loads(re.search(r'<script type="application/json" id="simbob-data">(.*?)</script>', page, re.S).group(1))
meshes = data["model"]["meshes"]
assert len(meshes) == 1, meshes
m = meshes[0]
assert m["file"] == "cube 100mm.stl", m["file"]
assert set(m) == {"file", "triangles", "hull"}, set(m)
# 8 float32 vertices x 3 = 96 bytes -> 128 base64 characters; 12 triangles x 3 uint32 = 144 bytes -> 192.
assert len(m["triangles"]["positions"]) == 128 and len(m["triangles"]["indices"]) == 192, m["triangles"]
assert [v["mesh"] for v in data["model"]["visuals"] if v["shape"] == "mesh"] == [0]
assert [g["shape"] for g in data["model"]["geoms"] if g["shape"] != "plane"] == ["hull"]
PY
say "ok"
