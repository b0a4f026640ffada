// lib/mesh/scan.cpp through loadMesh: hostile mesh files (issue 43) are refused before assimp or
// qhull sees them, each in well under a second, with the limit or the mesh file's line named:
// other formats and the files they name, non-finite vertices, COLLADA instance cycles, deep and
// exponential instancing, polygons of many corners, triangle counts over the limit, FIFOs.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <string>

#include "scene/scene_helpers.h"
#include "simbob/mesh.h"

using namespace simbob;
using scenetest::TempDir;

namespace {

// loadMesh(path) must fail with kind 65 and a message containing `what`, within `seconds`.
void refused(const std::string& path, const std::string& what, double seconds = 2.0) {
  INFO(path);
  const auto start = std::chrono::steady_clock::now();
  const MeshLoad l = loadMesh(path, {1, 1, 1}, UpAxis::Z);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE_FALSE(l.ok());
  CHECK(l.error.kind == ErrorKind::InvalidInput);
  INFO(l.error.message);
  CHECK(l.error.message.find(what) != std::string::npos);
  CHECK(took < seconds);
}

const char* const kColladaHead = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries><geometry id="tri"><mesh>
    <source id="pos"><float_array id="pos-array" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pos-array" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#verts" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
)";

// `s` with its first `from` replaced by `to`.
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  return s.replace(at, from.size(), to);
}

std::string collada(const std::string& library_nodes, const std::string& scene_nodes) {
  return std::string(kColladaHead) + "<library_nodes>" + library_nodes +
         "</library_nodes>\n<library_visual_scenes><visual_scene id=\"s\">" + scene_nodes +
         "</visual_scene></library_visual_scenes>\n<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n";
}

}  // namespace

TEST_CASE("mesh scan: only STL, OBJ and COLLADA are read, and no file a mesh names", "[mesh]") {
  TempDir dir;
  dir.write("secret.txt", "AWS_SECRET_ACCESS_KEY=do-not-leak-me\n");
  // A glTF whose buffer is a file outside its folder: the old reader embedded its bytes.
  const std::string gltf = R"({"asset":{"version":"2.0"},"buffers":[{"uri":"../secret.txt","byteLength":36}],
"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
  refused(dir.write("robot/part.gltf", gltf),
          "'.gltf' is not a mesh format simbob reads (STL .stl, OBJ .obj, COLLADA .dae)");
  refused(dir.write("robot/part", gltf), "a file without an extension is not a mesh format simbob reads");
  // The same bytes under a name of a format simbob reads are read by that format's importer only.
  refused(dir.write("robot/gltf.dae", gltf), "not XML");
  refused(dir.write("robot/gltf.stl", gltf), "is not an STL file");
  refused(dir.write("robot/gltf.obj", gltf), "");  // whatever OBJ makes of it, nothing
  // An OBJ's material library is not opened: a FIFO there would block its reader for ever.
  REQUIRE(::mkfifo((dir.path() / "robot/trap.mtl").c_str(), 0600) == 0);
  const std::string obj = dir.write("robot/tri.obj",
                                    "mtllib trap.mtl\nmtllib ../secret.txt\nusemtl x\n"
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const MeshLoad l = loadMesh(obj, {1, 1, 1}, UpAxis::Z);
  REQUIRE(l.ok());
  CHECK(l.mesh->triangles.size() == 4);
}

TEST_CASE("mesh scan: non-finite and out-of-range vertices are refused at their line", "[mesh]") {
  TempDir dir;
  refused(dir.write("nan.obj", "v 0 0 0\nv 1 0 0\nv nan 0 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"),
          "line 3: a vertex coordinate 'nan' is not a finite number");
  refused(dir.write("big.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1e39\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"),
          "line 4: a vertex coordinate '1e39' is beyond the range of a float (3.4e38)");
  refused(dir.write("inf.stl",
                    "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                    "vertex 0 inf 0\nendloop\nendfacet\nendsolid x\n"),
          "line 6: a vertex coordinate 'inf' is not a finite number");
  // A binary STL of 4 facets, the third with a NaN corner.
  std::string stl(84 + 4 * 50, '\0');
  const uint32_t facets = 4;
  std::memcpy(&stl[80], &facets, 4);
  const float nan = std::nanf("");
  std::memcpy(&stl[84 + 2 * 50 + 12 + 4], &nan, 4);
  refused(dir.write("nan_binary.stl", stl), "facet 3: a vertex coordinate is not a finite number");
  refused(dir.write("nan.dae", replaced(collada("", "<node id=\"a\"><instance_geometry url=\"#tri\"/></node>"),
                                        "0 0 0 1 0 0 0 1 0", "0 0 0 1 0 0 0 NaN 0")),
          "line 4: a number of <float_array> 'NaN' is not a finite number");
  // Finite in the file, beyond range after the node's transform: refused before qhull.
  refused(
      dir.write("scaled.dae",
                collada("", "<node id=\"a\"><scale>1e30 1e30 1e30</scale><instance_geometry url=\"#tri\"/></node>")),
      "a vertex lies beyond 1e9 m after the file's transforms and the scale");
}

TEST_CASE("mesh scan: COLLADA instance cycles, deep nesting and exponential instancing", "[mesh]") {
  TempDir dir;
  // A node that instances itself: assimp recursed until SIGSEGV.
  refused(dir.write("loop.dae", collada("", "<node id=\"loop\"><instance_node url=\"#loop\"/></node>")),
          "node 'loop' contains itself (through <instance_node>)");
  refused(dir.write("loop2.dae", collada("<node id=\"a\"><instance_node url=\"#b\"/></node>"
                                         "<node id=\"b\"><instance_node url=\"#a\"/></node>",
                                         "<node id=\"top\"><instance_node url=\"#a\"/></node>")),
          "contains itself (through <instance_node>)");
  // 100,000 nested nodes: assimp's recursion overflowed the stack.
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<node>";
  deep += "<instance_geometry url=\"#tri\"/>";
  for (int i = 0; i < 100000; ++i) deep += "</node>";
  refused(dir.write("deep.dae", collada("", deep)), "more than the limit of 256 deep");
  // A chain of instances 150 deep (each node instances the one before once): within the element
  // depth, past the node depth.
  std::string chain = "<node id=\"n0\"><instance_geometry url=\"#tri\"/></node>";
  for (int i = 1; i <= 150; ++i)
    chain += "<node id=\"n" + std::to_string(i) + "\"><instance_node url=\"#n" + std::to_string(i - 1) + "\"/></node>";
  refused(dir.write("chain.dae", collada(chain, "<node id=\"top\"><instance_node url=\"#n150\"/></node>")),
          "nodes nested more than the limit of 100 deep (counting <instance_node>)");
  // 22 nodes, each instancing the one before twice: a 3 KB file of 2^21 nodes and triangles,
  // which assimp built (gigabytes) before the triangle limit was checked on its one mesh.
  std::string doubling = "<node id=\"d0\"><instance_geometry url=\"#tri\"/></node>";
  for (int i = 1; i <= 21; ++i) {
    const std::string before = "#d" + std::to_string(i - 1);
    doubling += "<node id=\"d" + std::to_string(i) + "\"><instance_node url=\"" + before + "\"/><instance_node url=\"" +
                before + "\"/></node>";
  }
  const std::string bomb = collada(doubling, "<node id=\"top\"><instance_node url=\"#d21\"/></node>");
  CHECK(bomb.size() < 4000);
  refused(dir.write("bomb.dae", bomb), "nodes after instancing, more than the limit of 100000");
  // The same with few nodes and many triangles: 2^12 instances of a 1,000-triangle polygon soup.
  std::string many = "<node id=\"d0\"><instance_geometry url=\"#soup\"/></node>";
  for (int i = 1; i <= 12; ++i) {
    const std::string before = "#d" + std::to_string(i - 1);
    many += "<node id=\"d" + std::to_string(i) + "\"><instance_node url=\"" + before + "\"/><instance_node url=\"" +
            before + "\"/></node>";
  }
  std::string p;
  for (int i = 0; i < 1000; ++i) p += "0 1 2 ";
  std::string soup = collada(many, "<node id=\"top\"><instance_node url=\"#d12\"/></node>");
  soup = replaced(soup, "</library_geometries>",
                  "<geometry id=\"soup\"><mesh><source id=\"p2\"><float_array id=\"p2a\" count=\"9\">0 0 0 1 0 0 0 1 "
                  "0</float_array><technique_common><accessor source=\"#p2a\" count=\"3\" stride=\"3\"><param "
                  "name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" "
                  "type=\"float\"/></accessor></technique_common></source><vertices id=\"v2\"><input "
                  "semantic=\"POSITION\" source=\"#p2\"/></vertices><triangles count=\"1000\"><input "
                  "semantic=\"VERTEX\" source=\"#v2\" offset=\"0\"/><p>" +
                      p + "</p></triangles></mesh></geometry></library_geometries>");
  refused(dir.write("many.dae", soup), "has 4096000 triangles after instancing, more than the limit of 2000000");
}

TEST_CASE("mesh scan: a polygon of many corners and a triangle count over the limit, before assimp", "[mesh]") {
  TempDir dir;
  // One OBJ face of 100,000 corners (about 600 KB): assimp's triangulation took a minute.
  std::string obj;
  for (int i = 0; i < 100000; ++i)
    obj += "v " + std::to_string(std::cos(i * 6.283185307179586 / 100000)) + " " +
           std::to_string(std::sin(i * 6.283185307179586 / 100000)) + " 0\n";
  obj += "f";
  for (int i = 1; i <= 100000; ++i) obj += " " + std::to_string(i);
  obj += "\n";
  refused(dir.write("fan.obj", obj), "line 100001: a polygon of 100000 corners, more than the limit of 256");
  // The same face spread over continued lines ('\' at their ends) is one face.
  std::string split = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (int i = 0; i < 300; ++i) split += " 1 2 3\\\n";
  refused(dir.write("split.obj", split + "\n"), "line 4: a polygon of 900 corners, more than the limit of 256");
  // assimp takes any line that starts with 'f' for a face: "fo" (an old spelling) too.
  std::string fo = "v 0 0 0\nv 1 0 0\nv 0 1 0\nfo";
  for (int i = 0; i < 100; ++i) fo += " 1 2 3";
  refused(dir.write("fo.obj", fo + "\n"), "line 4: a polygon of 300 corners, more than the limit of 256");
  // 2,000,001 triangles in 16 MB: refused by the count, before assimp allocated for them.
  std::string faces = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  faces.reserve(faces.size() + 8 * 2000001);
  for (int i = 0; i < 2000001; ++i) faces += "f 1 2 3\n";
  refused(dir.write("faces.obj", faces),
          "line 2000004: the faces so far make more than the limit of 2000000 triangles");
  // A binary STL that says it has 2,000,001 facets (and has them: 100 MB is too slow a test; its
  // size says so, and its size is what is checked).
  std::string stl(84, '\0');
  const uint32_t facets = 2000001;
  std::memcpy(&stl[80], &facets, 4);
  const std::string big = dir.write("big.stl", stl);
  REQUIRE(::truncate(big.c_str(), static_cast<off_t>(84 + 50 * uint64_t{facets})) == 0);
  refused(big, "has 2000001 facets, more than the limit of 2000000 triangles");
  // A facet count whose 32-bit size wraps to the file's size.
  std::string wrap(84 + 50, '\0');
  const uint32_t lie = 1 + (uint32_t{1} << 31);  // 84 + 50 * lie = 84 + 50 + 25 * 2^32
  std::memcpy(&wrap[80], &lie, 4);
  std::memcpy(&wrap[0], "solid", 5);
  refused(dir.write("wrap.stl", wrap), "its binary facet count (2147483649) does not match its size");
  // A COLLADA polygon of many corners.
  std::string poly = collada("", "<node id=\"a\"><instance_geometry url=\"#tri\"/></node>");
  poly = replaced(poly, "<triangles count=\"1\">", "<polylist count=\"1\"><vcount>300</vcount>");
  poly = replaced(poly, "</triangles>", "</polylist>");
  refused(dir.write("poly.dae", poly), "a polygon of 300 corners, more than the limit of 256");
}

TEST_CASE("mesh scan: a FIFO or a folder is not read (the reader would wait for ever)", "[mesh]") {
  TempDir dir;
  const std::string fifo = (dir.path() / "pipe.stl").string();
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const MeshLoad l = loadMesh(fifo, {1, 1, 1}, UpAxis::Y);
  REQUIRE_FALSE(l.ok());
  CHECK(l.error.kind == ErrorKind::MissingInput);
  CHECK(l.error.message == "cannot read the mesh: not a regular file");
  const MeshLoad d = loadMesh(dir.path().string(), {1, 1, 1}, UpAxis::Y);
  REQUIRE_FALSE(d.ok());
  CHECK(d.error.kind == ErrorKind::MissingInput);
}

TEST_CASE("mesh scan: COLLADA index lists hold whole numbers, counts fit the file, before assimp", "[mesh]") {
  // Found by the mesh fuzz target: one '!' in a <p> list made assimp ask for 2.4 GB.
  TempDir dir;
  const std::string good = collada("", "<node id=\"n\"><instance_geometry url=\"#tri\"/></node>");
  CHECK(loadMesh(dir.write("good.dae", good), {1, 1, 1}, UpAxis::Z).ok());
  refused(dir.write("bang.dae", replaced(good, "<p>0 1 2</p>", "<p>0 1!2</p>")),
          "line 9: '1!2' in <p> is not a whole number");
  refused(dir.write("float.dae", replaced(good, "<p>0 1 2</p>", "<p>0 1.5 2</p>")),
          "'1.5' in <p> is not a whole number");
  refused(dir.write("count.dae", replaced(good, "count=\"9\"", "count=\"900000000\"")),
          "line 4: <float_array count=\"900000000\"> is more than the file holds");
  refused(dir.write("stride.dae", replaced(good, "stride=\"3\"", "stride=\"100000\"")),
          "<accessor stride=\"100000\"> is over 64");
}
