#!/usr/bin/env bash
# Mesh files in scenes (RCMeshGeom, RCMeshModel; docs/meshes.md): check reports each mesh once;
# a missing mesh is 66 and a corrupt one 65, at the File line; file names with spaces work; two
# triangle meshes that can touch are named in a warning; `types` lists both types; the replay
# page embeds each mesh once. A URDF's COLLADA mesh is read as ROS reads it (up_axis not applied)
# and check says what was done with every stated up axis; hostile mesh files (other formats,
# non-finite vertices, FIFOs) are refused at the line naming them (issues 42 and 43). assimp is
# linked into the program: no mesh module is looked for (tests/cli/modules.sh).
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
expect_match "corrupt" "$LAST_ERR" "^s/junk.xml:7: error: RCMeshGeom 'Part.Geom': mesh 's/junk.stl': is not an STL file \\(neither 84 \\+ 50 bytes a facet, binary, nor text starting with 'solid'\\)$"

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
# first_error: a file holding the first line of the last command's stderr.
first_error() {
  head -n 1 "$LAST_ERR" >first_error.txt
  echo first_error.txt
}

check "a URDF's 0.4 m tall COLLADA block, Y_UP or with no up_axis, stands at half its height (as in RViz and Gazebo)"
# The block's vertices: 0.1 x 0.1 x 0.4 m along x y z, centred on the link frame. ROS takes a
# URDF's COLLADA vertices as written (Z-up, the file's up_axis ignored): it rests on its end with
# its centre 0.2 m up. Turned by its Y_UP (the old reading) it lay on its side at 0.05 m. The
# contact leaves the hull a fraction of a millimetre in the ground: 1 mm either way.
block_dae() {
  printf '<?xml version="1.0"?>\n<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">\n'
  printf '<asset><unit name="meter" meter="1"/>%s</asset>\n' "$1"
  printf '<library_geometries><geometry id="b"><mesh><source id="p"><float_array id="pa" count="24">'
  printf -- '-0.05 -0.05 -0.2 0.05 -0.05 -0.2 -0.05 0.05 -0.2 0.05 0.05 -0.2 '
  printf -- '-0.05 -0.05 0.2 0.05 -0.05 0.2 -0.05 0.05 0.2 0.05 0.05 0.2'
  printf '</float_array><technique_common><accessor source="#pa" count="8" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>\n'
  printf '<vertices id="v"><input semantic="POSITION" source="#p"/></vertices><triangles count="12"><input semantic="VERTEX" source="#v" offset="0"/>'
  printf '<p>0 3 1 0 2 3 4 5 7 4 7 6 0 1 5 0 5 4 2 6 7 2 7 3 1 3 7 1 7 5 0 4 6 0 6 2</p></triangles></mesh></geometry></library_geometries>\n'
  printf '<library_visual_scenes><visual_scene id="s"><node id="n"><instance_geometry url="#b"/></node></visual_scene></library_visual_scenes>\n'
  printf '<scene><instance_visual_scene url="#s"/></scene>\n</COLLADA>\n'
}
block_urdf() {
  cat <<URDF
<robot name="block">
  <link name="block">
    <inertial><mass value="1"/><inertia ixx="0.0141667" iyy="0.0141667" izz="0.0016667" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="$1"/></geometry></collision>
  </link>
</robot>
URDF
}
block_dae '<up_axis>Y_UP</up_axis>' >block_y.dae
block_dae '' >block_none.dae
for up in y none; do
  block_urdf "block_$up.dae" >"block_$up.urdf"
  cat >"block_$up.xml" <<XML
<Simulation><ComponentList><RCGround Key="Ground"/>
  <RCImportURDF Key="blk"><File Value="block_$up.urdf"/>
    <Pose><RCGlobalCoordinates><Pose Value="0 0.5 0 0 0 0"/></RCGlobalCoordinates></Pose></RCImportURDF>
</ComponentList></Simulation>
XML
  expect_status 0 "$SIMBOB" run "block_$up.xml" --duration 2 --out "block_$up.csv"
  y=$(grep ',blk\.block,' "block_$up.csv" | tail -n 1 | cut -d, -f4)
  float_between "resting height of the block (up_axis $up)" "$y" 0.199 0.201
done
expect_status 0 "$SIMBOB" check block_y.xml
expect_match "check names the up axis and what was done" "$LAST_ERR" \
  "mesh block_y.dae \(scale 1 1 1\): 8 vertices, 12 triangles, closed; hull of 1 geom \(8 points, 6 faces\); its up_axis Y_UP not applied \(a URDF's mesh: vertices as written, as ROS reads them\)$"
expect_status 0 "$SIMBOB" check block_none.xml
expect_eq "no up axis stated, none named" "$(grep -c 'up_axis' "$LAST_ERR")" 0
# In a scene, a Z_UP file is turned onto the scene's +Y, and check says so.
scene "$REPO/tests/data/meshes/box_cm_zup.dae" >s/zup.xml
expect_status 0 "$SIMBOB" check s/zup.xml
expect_match "scene's Z_UP" "$LAST_ERR" "box_cm_zup.dae \(scale 0.001 0.001 0.001\): .*; its up_axis Z_UP turned onto the scene's \+Y$"

check "a glTF (its buffer a file outside the folder) is refused at the line naming it, and nothing of the file is embedded"
mkdir -p pack/meshes
printf 'AWS_SECRET_ACCESS_KEY=do-not-leak-me\n' >secret.txt
cat >pack/meshes/part.gltf <<'JSON'
{"asset":{"version":"2.0"},"buffers":[{"uri":"../../secret.txt","byteLength":36}],
"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0}
JSON
scene "../pack/meshes/part.gltf" >s/gltf.xml
expect_status 65 "$SIMBOB" run s/gltf.xml --duration 0.1 --out gltf.csv --html gltf.html
expect_match "scene's line" "$(first_error)" \
  "^s/gltf.xml:7: error: RCMeshGeom 'Part.Geom': mesh 's/../pack/meshes/part.gltf': '.gltf' is not a mesh format simbob reads \(STL .stl, OBJ .obj, COLLADA .dae\)$"
expect_no_file gltf.html
block_urdf "meshes/part.gltf" >pack/robot.urdf
expect_status 65 "$SIMBOB" check pack/robot.urdf
expect_match "URDF's line" "$LAST_ERR" "^pack/robot.urdf:4: error: mesh 'meshes/part.gltf': '.gltf' is not a mesh format simbob reads"
# The same bytes named .dae are not XML, and named .obj read as OBJ (no triangles): never as glTF.
cp pack/meshes/part.gltf pack/meshes/part.obj
scene "../pack/meshes/part.obj" >s/gltf_obj.xml
expect_status 65 "$SIMBOB" view spaces.csv --scene s/gltf_obj.xml --out gltf_obj.html
expect_no_file gltf_obj.html
if grep -rqs "do-not-leak-me\|QVdTX1NFQ1JFV" ./*.html; then fail "the secret reached a page"; fi

check "non-finite and out-of-range vertices are refused by check at the scene's line and the mesh file's line"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1e39\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n' >s/big.obj
scene "big.obj" >s/big.xml
expect_status 65 "$SIMBOB" check s/big.xml
expect_match "1e39" "$(first_error)" \
  "^s/big.xml:7: error: RCMeshGeom 'Part.Geom': mesh 's/big.obj': line 4: a vertex coordinate '1e39' is beyond the range of a float \(3.4e38\)$"
printf 'v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n' >s/nan.obj
scene "nan.obj" >s/nan.xml
expect_status 65 "$SIMBOB" run s/nan.xml --duration 0.1 --out nan.csv
expect_match "nan" "$(first_error)" "^s/nan.xml:7: error: .*'s/nan.obj': line 2: a vertex coordinate 'nan' is not a finite number$"

check "a FIFO as a scene's mesh file is refused (66) at once, like a URDF's"
mkfifo s/pipe.stl
scene "pipe.stl" >s/pipe.xml
expect_status 66 timeout 20 "$SIMBOB" check s/pipe.xml
expect_match "fifo" "$(first_error)" "^s/pipe.xml:7: error: RCMeshGeom 'Part.Geom': mesh 's/pipe.stl': cannot read the mesh: not a regular file$"

say "ok"
