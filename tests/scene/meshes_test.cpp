// RCMeshGeom and RCMeshModel (lib/components/meshes.cpp, geoms.cpp, models.cpp): hull or
// triangles, one Model::meshes entry per file and scale, RCModelMatchGeom on a mesh model, and
// the refusals with their lines and kinds.
#include <catch2/catch.hpp>

#include <string>

#include "scene/scene_helpers.h"
#include "simbob/compile.h"

using namespace scenetest;

namespace {

const std::string kCube = std::string(SIMBOB_SOURCE_DIR) + "/tests/data/meshes/cube_100mm.stl";

std::string meshGeom(const std::string& file, const std::string& more = "") {
  return "<RCMeshGeom><File Value=\"" + file + "\"/><Scale Value=\"0.001 0.001 0.001\"/>" + more + "</RCMeshGeom>";
}

std::string mobile(const std::string& key, const std::string& geom, const std::string& model = "") {
  return "<RCMobileRigidBody Key=\"" + key + "\"><Geom>" + geom + "</Geom>" +
         (model.empty() ? "" : "<Model>" + model + "</Model>") + "</RCMobileRigidBody>";
}

std::string scene(const std::string& components) {
  return "<Simulation><ComponentList>" + components + "</ComponentList></Simulation>";
}

// Compiles text that must fail; returns the diagnostics.
Diagnostics mustFail(const std::string& text) {
  Scene s = mustLoad(text);
  Model m;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m, d));
  return d;
}

}  // namespace

TEST_CASE("meshes: a mobile body's mesh geom is its hull, a static body's its triangles, Hull decides",
          "[scene][mesh]") {
  const Model m = mustCompile(scene(mobile("A", meshGeom(kCube)) +                                      //
                                    mobile("B", meshGeom(kCube, "<Hull Value=\"False\"/>")) +           //
                                    "<RCStaticRigidBody Key=\"C\"><Geom>" + meshGeom(kCube) +           //
                                    "</Geom></RCStaticRigidBody><RCStaticRigidBody Key=\"D\"><Geom>" +  //
                                    meshGeom(kCube, "<Hull Value=\"True\"/>") + "</Geom></RCStaticRigidBody>"));
  REQUIRE(m.geoms.size() == 4);
  CHECK(m.geoms[0].shape == GeomShape::ConvexHull);
  CHECK(m.geoms[1].shape == GeomShape::TriMesh);
  CHECK(m.geoms[2].shape == GeomShape::TriMesh);
  CHECK(m.geoms[3].shape == GeomShape::ConvexHull);
  // One file at one scale: one mesh, read once, shared by all four.
  REQUIRE(m.meshes.size() == 1);
  for (const GeomDef& g : m.geoms) CHECK(g.mesh == 0);
  CHECK(m.meshes[0].data->file == kCube);
  CHECK(m.meshes[0].loc.file == "test.xml");
  CHECK(m.meshes[0].loc.line == 1);
  // The closed cube gives B (a triangle mesh) the same mass as A (its hull): 1 kg default mass.
  CHECK(m.bodies[0].inertia[0] == Approx(m.bodies[1].inertia[0]).epsilon(1e-9));
}

TEST_CASE("meshes: RCMeshModel draws the mesh; RCModelMatchGeom gives its hull; a new scale is a new mesh",
          "[scene][mesh]") {
  const std::string model =
      "<RCMeshModel><File Value=\"" + kCube + "\"/><Scale Value=\"0.002 0.002 0.002\"/></RCMeshModel>";
  const Model m = mustCompile(scene(mobile("A", "<RCModelMatchGeom/>", model) + mobile("B", meshGeom(kCube))));
  REQUIRE(m.meshes.size() == 2);
  REQUIRE(m.visuals.size() == 1);
  CHECK(m.visuals[0].shape == VisualDef::Mesh);
  CHECK(m.visuals[0].mesh == 0);
  CHECK(m.visuals[0].body == 0);
  REQUIRE(m.geoms.size() == 2);
  CHECK(m.geoms[0].shape == GeomShape::ConvexHull);
  CHECK(m.geoms[0].mesh == 0);
  CHECK(m.geoms[1].mesh == 1);
  CHECK(m.meshes[0].data->hi[0] == Approx(0.1).epsilon(1e-6));   // 100 mm * 0.002
  CHECK(m.meshes[1].data->hi[0] == Approx(0.05).epsilon(1e-6));  // 100 mm * 0.001
  // RCModelWrapGeom wraps the hull's corners: a cuboid of the cube's extents.
  const Model w = mustCompile(scene(mobile("A", "<RCModelWrapGeom/>", model)));
  REQUIRE(w.geoms.size() == 1);
  CHECK(w.geoms[0].shape == GeomShape::Box);
  CHECK(w.geoms[0].size[1] == Approx(0.2).epsilon(1e-6));
}

TEST_CASE("meshes: a missing file is MissingInput at the File line, naming the path", "[scene][mesh]") {
  const Diagnostics d = mustFail(
      "<Simulation><ComponentList>\n<RCMobileRigidBody Key=\"A\"><Geom><RCMeshGeom>\n"
      "<File Value=\"no such.stl\"/></RCMeshGeom></Geom></RCMobileRigidBody>\n</ComponentList></Simulation>");
  REQUIRE(d.errors().size() == 1);
  CHECK(d.errors()[0].kind == ErrorKind::MissingInput);
  CHECK(d.errors()[0].str() ==
        "test.xml:3: RCMeshGeom 'A.Geom': mesh 'no such.stl': cannot read the mesh: No such file or directory");
}

TEST_CASE("meshes: no File, a zero Scale and an open triangle mesh with RCInertiaByGeom are refused at their lines",
          "[scene][mesh]") {
  Diagnostics d =
      mustFail("<Simulation><ComponentList>\n" + mobile("A", "<RCMeshGeom/>") + "\n</ComponentList></Simulation>");
  REQUIRE_FALSE(d.errors().empty());
  CHECK(d.errors()[0].str() ==
        "test.xml:2: RCMeshGeom 'A.Geom': parameter 'File' names no mesh file (.stl, .obj or .dae)");
  d = mustFail("<Simulation><ComponentList>\n<RCMobileRigidBody Key=\"A\"><Geom><RCMeshGeom><File Value=\"" + kCube +
               "\"/>\n<Scale Value=\"1 0 1\"/></RCMeshGeom></Geom></RCMobileRigidBody></ComponentList></Simulation>");
  REQUIRE_FALSE(d.errors().empty());
  CHECK(d.errors()[0].str() ==
        "test.xml:3: RCMeshGeom 'A.Geom': parameter 'Scale' needs three finite, non-zero factors");
  // A single triangle: open, so a triangle mesh of it has no volume to weigh; its points are flat,
  // so it has no hull either.
  TempDir dir;
  const std::string tri = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  d = mustFail(scene(mobile("A", "<RCMeshGeom><File Value=\"" + tri + "\"/><Hull Value=\"False\"/></RCMeshGeom>")));
  REQUIRE_FALSE(d.errors().empty());
  CHECK(d.errors()[0].message ==
        "RCMobileRigidBody 'A': RCInertiaByGeom: the triangle mesh '" + tri +
            "' of body 'A' is not closed, so it has no volume; use its hull (Hull=\"True\") or RCGenericInertia");
  d = mustFail(scene(mobile("A", "<RCMeshGeom><File Value=\"" + tri + "\"/></RCMeshGeom>")));
  REQUIRE_FALSE(d.errors().empty());
  CHECK(d.errors()[0].message ==
        "RCMeshGeom 'A.Geom': mesh '" + tri + "' has no convex hull: its 3 points span no volume");
}

TEST_CASE("meshes: check names both of two triangle meshes that can touch, and describes each mesh", "[scene][mesh]") {
  const Model m =
      mustCompile("<Simulation><ComponentList>\n" + mobile("A", meshGeom(kCube, "<Hull Value=\"False\"/>")) +
                  "\n<RCStaticRigidBody Key=\"F\"><Geom>" + meshGeom(kCube) + "</Geom></RCStaticRigidBody>\n" +
                  mobile("H", meshGeom(kCube)) + "\n</ComponentList></Simulation>");
  Diagnostics lint;
  lintModel(m, lint);
  size_t pairs = 0;
  for (const Error& w : lint.warnings())
    if (w.message.find("triangle meshes") != std::string::npos) {
      ++pairs;
      CHECK(w.str() ==
            "test.xml:2: the triangle meshes of 'A' (cube_100mm.stl, test.xml:2) and 'F' (cube_100mm.stl, "
            "test.xml:3) can touch: ODE's contacts between two triangle meshes are unreliable; give the "
            "moving one its convex hull (Hull=\"True\") or a primitive geom");
    }
  CHECK(pairs == 1);  // H is a hull: no warning for it
  const std::vector<std::string> lines = describeMeshes(m);
  REQUIRE(lines.size() == 1);
  CHECK(lines[0] == "mesh " + kCube +
                        " (scale 0.001 0.001 0.001): 8 vertices, 12 triangles, closed; hull of 1 geom (8 points, 6 "
                        "faces); triangle mesh of 2 geoms");
}
