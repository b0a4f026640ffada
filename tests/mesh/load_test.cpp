// lib/mesh: loading STL, OBJ and DAE (units, up axis, scale), the cache, hulls and the mass of
// closed meshes against analytic answers.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "scene/scene_helpers.h"
#include "simbob/mesh.h"

using namespace simbob;
using scenetest::TempDir;

namespace {

const std::string kData = std::string(SIMBOB_SOURCE_DIR) + "/tests/data/meshes/";
const std::string kDart = "/usr/share/doc/dart/data/urdf/";

// The unit cube [0,1]^3 as 12 outward triangles.
std::vector<Vec3> cubeVertices(double s) {
  std::vector<Vec3> v;
  for (int k = 0; k < 8; ++k) v.push_back({(k & 1) * s, ((k >> 1) & 1) * s, ((k >> 2) & 1) * s});
  return v;
}
const std::vector<std::array<uint32_t, 3>> kCubeTriangles = {{0, 3, 1}, {0, 2, 3}, {4, 5, 7}, {4, 7, 6},
                                                             {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                                             {1, 3, 7}, {1, 7, 5}, {0, 4, 6}, {0, 6, 2}};

}  // namespace

TEST_CASE("mesh: polyhedronMass of a cube and a tetrahedron is the analytic one", "[mesh]") {
  // Cube of side 2 with a corner at the origin: V = 8, centre (1,1,1), I = V s^2 / 6 = 16/3 on
  // the diagonal about the centre, 0 off it. Exact arithmetic on small integers: 1e-12.
  const MeshMass cube = polyhedronMass(cubeVertices(2), kCubeTriangles);
  CHECK(cube.volume == Approx(8).epsilon(1e-12));
  for (size_t k = 0; k < 3; ++k) CHECK(cube.centre[k] == Approx(1).epsilon(1e-12));
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) CHECK(cube.inertia[i * 3 + j] == Approx(i == j ? 16.0 / 3.0 : 0.0).margin(1e-12));
  // Tetrahedron (0,0,0) (a,0,0) (0,a,0) (0,0,a): V = a^3/6, centroid a/4 on each axis; about the
  // origin the covariance is V a^2/10 on the diagonal and V a^2/20 off it (Tonon 2004), so about
  // the centroid I_xx = 2 (V a^2/10 - V a^2/16) and I_xy = -(V a^2/20 - V a^2/16).
  const double a = 3;
  const std::vector<Vec3> tv = {{0, 0, 0}, {a, 0, 0}, {0, a, 0}, {0, 0, a}};
  const std::vector<std::array<uint32_t, 3>> tt = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const MeshMass tet = polyhedronMass(tv, tt);
  const double v = a * a * a / 6;
  CHECK(tet.volume == Approx(v).epsilon(1e-12));
  for (size_t k = 0; k < 3; ++k) CHECK(tet.centre[k] == Approx(a / 4).epsilon(1e-12));
  const double diag = 2 * (v * a * a / 10 - v * a * a / 16), off = -(v * a * a / 20 - v * a * a / 16);
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) CHECK(tet.inertia[i * 3 + j] == Approx(i == j ? diag : off).epsilon(1e-12));
}

TEST_CASE("mesh: the convex hull of a box's points is six outward quadrilaterals", "[mesh]") {
  std::vector<Vec3> points = cubeVertices(1);
  points.push_back({0.5, 0.5, 0.5});  // inside: not a hull point
  points.push_back({0.5, 0.5, 1.0});  // on a face: merged away
  ConvexHull h;
  std::string problem;
  REQUIRE(convexHull(points, &h, &problem));
  CHECK(problem.empty());
  REQUIRE(h.faceCount() == 6);
  CHECK(h.pointCount() == 8);
  size_t at = 0;
  for (size_t f = 0; f < h.faceCount(); ++f) {
    const Vec3 n{h.planes[f * 4], h.planes[f * 4 + 1], h.planes[f * 4 + 2]};
    const double d = h.planes[f * 4 + 3];
    CHECK(std::fabs(n[0]) + std::fabs(n[1]) + std::fabs(n[2]) == Approx(1));  // axis-aligned unit normal
    REQUIRE(h.polygons[at] == 4);
    // Every corner on the plane, and the corners counterclockwise about the outward normal.
    for (unsigned k = 0; k < 4; ++k) {
      const auto p = [&](unsigned i) {
        const unsigned id = h.polygons[at + 1 + i % 4];
        return Vec3{h.points[id * 3], h.points[id * 3 + 1], h.points[id * 3 + 2]};
      };
      const Vec3 a = p(k), b = p(k + 1), c = p(k + 2);
      CHECK(n[0] * a[0] + n[1] * a[1] + n[2] * a[2] == Approx(d).margin(1e-12));
      const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - b[0], c[1] - b[1], c[2] - b[2]};
      const double turn =
          n[0] * (u[1] * w[2] - u[2] * w[1]) + n[1] * (u[2] * w[0] - u[0] * w[2]) + n[2] * (u[0] * w[1] - u[1] * w[0]);
      CHECK(turn > 0);
    }
    // Outward: the box's centre is behind every face.
    CHECK(n[0] * 0.5 + n[1] * 0.5 + n[2] * 0.5 < d);
    at += 5;
  }
  // Flat points span no volume.
  CHECK_FALSE(convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}, &h, &problem));
  CHECK(problem == "its points span no volume (they lie in one plane)");
  CHECK(h.empty());
  CHECK_FALSE(convexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, &h, &problem));
  CHECK(problem == "its 3 points span no volume");
}

TEST_CASE("mesh: an ASCII STL cube in millimetres scaled to metres", "[mesh]") {
  const MeshLoad l = loadMesh(kData + "cube_100mm.stl", {0.001, 0.001, 0.001}, UpAxis::Y);
  REQUIRE(l.ok());
  const MeshData& m = *l.mesh;
  CHECK(m.vertices.size() == 8);  // STL repeats corners per facet: merged
  CHECK(m.triangles.size() == 12);
  CHECK(m.closed);
  for (size_t k = 0; k < 3; ++k) {
    CHECK(m.lo[k] == Approx(-0.05).epsilon(1e-6));  // float32 in the file: 1e-6 relative
    CHECK(m.hi[k] == Approx(0.05).epsilon(1e-6));
  }
  CHECK(m.mass.volume == Approx(1e-3).epsilon(1e-6));
  CHECK(m.hull.faceCount() == 6);
  CHECK(m.hull_mass.volume == Approx(1e-3).epsilon(1e-6));
  CHECK(m.hull_mass.inertia[0] == Approx(1e-3 * 0.01 / 6).epsilon(1e-6));  // V s^2 / 6
}

TEST_CASE("mesh: a negative scale mirrors the mesh and keeps its triangles outward", "[mesh]") {
  const MeshLoad l = loadMesh(kData + "cube_100mm.stl", {-0.001, 0.001, 0.001}, UpAxis::Y);
  REQUIRE(l.ok());
  CHECK(l.mesh->closed);
  CHECK(l.mesh->mass.volume == Approx(1e-3).epsilon(1e-6));  // positive: still wound outward
}

namespace {

// A COLLADA box from `lo` to `hi` (12 triangles), with `up` as its <up_axis> ("" for none) and
// `unit` as its <unit meter>.
std::string colladaBox(const Vec3& lo, const Vec3& hi, const std::string& up, double unit = 1) {
  std::string positions;
  for (size_t k = 0; k < 8; ++k)
    for (size_t a = 0; a < 3; ++a) positions += std::to_string(((k >> a) & 1) ? hi[a] : lo[a]) + " ";
  std::string p;
  for (const auto& t : kCubeTriangles)
    for (uint32_t i : t) p += std::to_string(i) + " ";
  const std::string up_axis = up.empty() ? "" : "<up_axis>" + up + "</up_axis>";
  return "<?xml version=\"1.0\"?>\n"
         "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
         "<asset><unit name=\"u\" meter=\"" +
         std::to_string(unit) + "\"/>" + up_axis +
         "</asset>\n"
         "<library_geometries><geometry id=\"box\"><mesh>\n"
         "<source id=\"pos\"><float_array id=\"pos-array\" count=\"24\">" +
         positions +
         "</float_array>\n"
         "<technique_common><accessor source=\"#pos-array\" count=\"8\" stride=\"3\">"
         "<param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/><param name=\"Z\" type=\"float\"/>"
         "</accessor></technique_common></source>\n"
         "<vertices id=\"verts\"><input semantic=\"POSITION\" source=\"#pos\"/></vertices>\n"
         "<triangles count=\"12\"><input semantic=\"VERTEX\" source=\"#verts\" offset=\"0\"/><p>" +
         p +
         "</p></triangles>\n"
         "</mesh></geometry></library_geometries>\n"
         "<library_visual_scenes><visual_scene id=\"scene\"><node id=\"n\"><instance_geometry url=\"#box\"/></node>"
         "</visual_scene></library_visual_scenes>\n"
         "<scene><instance_visual_scene url=\"#scene\"/></scene>\n"
         "</COLLADA>\n";
}

}  // namespace

TEST_CASE("mesh: a URDF's COLLADA file is taken as ROS takes it: unit kept, up_axis not applied", "[mesh]") {
  // A block 0.1 x 0.1 x 0.4 m along the file's x y z, in centimetres: with Y_UP, with Z_UP and
  // with no up_axis (COLLADA's default, Y_UP), RViz, MoveIt and Gazebo classic all place its
  // vertices as written in the Z-up link frame (rviz#1045, geometric_shapes#52): 0.4 m along +Z.
  TempDir dir;
  for (const std::string up : {"Y_UP", "Z_UP", ""}) {
    INFO("up_axis '" << up << "'");
    const std::string file = dir.write("block" + up + ".dae", colladaBox({-5, -5, -20}, {5, 5, 20}, up, 0.01));
    const MeshLoad l = loadMesh(file, {1, 1, 1}, UpAxis::Z);
    REQUIRE(l.ok());
    const Vec3 hi{0.05, 0.05, 0.2};
    for (size_t k = 0; k < 3; ++k) {
      CHECK(l.mesh->lo[k] == Approx(-hi[k]).margin(1e-7));  // float32 and the 0.01 unit: 1e-7 m
      CHECK(l.mesh->hi[k] == Approx(hi[k]).margin(1e-7));
    }
    CHECK(l.mesh->file_up_axis == up);
    CHECK(l.mesh->closed);
    // In a scene (Y-up) the file's up axis is applied: a Z_UP file's +Z becomes +Y; Y_UP and the
    // default leave it as written.
    const MeshLoad y = loadMesh(file, {1, 1, 1}, UpAxis::Y);
    REQUIRE(y.ok());
    CHECK(y.mesh->hi[1] == Approx(up == "Z_UP" ? 0.2 : 0.05).margin(1e-7));
    CHECK(y.mesh->hi[2] == Approx(up == "Z_UP" ? 0.05 : 0.2).margin(1e-7));
  }
}

TEST_CASE("mesh: the WAM's visual COLLADA and collision STL meshes coincide on every link", "[mesh]") {
  // dart-doc's WAM (wam.urdf): each link's visual wamN.dae (Y_UP, metres) and collision
  // wamN_collision.STL sit at the link's origin (no <origin> on either). The collision meshes are
  // coarse hulls drawn around the visual ones: on every link the visual mesh's bounding box lies
  // inside the collision mesh's (1 mm for float32 vertices and modelling), and no face of the
  // collision box stands more than 4 cm off the visual one (wam3's elbow cover is the widest, 3.1
  // cm). Turned by the file's Y_UP (the old reading), wam1's visual box pokes 8 cm out of its
  // collision box, wam3's half a metre.
  const std::string dir = kDart + "wam/meshes/wam/";
  for (const std::string link : {"wam_base", "wam1", "wam2", "wam3", "wam4", "wam5", "wam6", "wam7"}) {
    INFO(link);
    const MeshLoad visual = loadMesh(dir + link + ".dae", {1, 1, 1}, UpAxis::Z);
    const MeshLoad collision = loadMesh(dir + link + "_collision.STL", {1, 1, 1}, UpAxis::Z);
    REQUIRE(visual.ok());
    REQUIRE(collision.ok());
    CHECK(visual.mesh->file_up_axis == "Y_UP");
    const MeshData& v = *visual.mesh;
    const MeshData& c = *collision.mesh;
    for (size_t k = 0; k < 3; ++k) {
      INFO("axis " << k << ": visual " << v.lo[k] << " .. " << v.hi[k] << ", collision " << c.lo[k] << " .. "
                   << c.hi[k]);
      CHECK(v.lo[k] >= c.lo[k] - 0.001);
      CHECK(v.hi[k] <= c.hi[k] + 0.001);
      CHECK(c.lo[k] >= v.lo[k] - 0.04);
      CHECK(c.hi[k] <= v.hi[k] + 0.04);
    }
  }
}

TEST_CASE("mesh: COLLADA's unit and Z-up axis are applied once (dart#287)", "[mesh]") {
  // box_cm_zup.dae: 10 x 20 x 30 cm along the file's x y z from the origin, Z up.
  const MeshLoad y = loadMesh(kData + "box_cm_zup.dae", {1, 1, 1}, UpAxis::Y);
  REQUIRE(y.ok());
  // In a Y-up scene: the file's z (up) is +Y, its y goes to -Z.
  const Vec3 lo_y{0, 0, -0.2}, hi_y{0.1, 0.3, 0};
  for (size_t k = 0; k < 3; ++k) {
    CHECK(y.mesh->lo[k] == Approx(lo_y[k]).margin(1e-7));  // float32 and the 0.01 unit: 1e-7 m
    CHECK(y.mesh->hi[k] == Approx(hi_y[k]).margin(1e-7));
  }
  CHECK(y.mesh->closed);
  CHECK(y.mesh->mass.volume == Approx(0.006).epsilon(1e-6));
  // In a URDF's Z-up frame: as written (the up axis not applied, and this file's is Z_UP), in metres.
  const MeshLoad z = loadMesh(kData + "box_cm_zup.dae", {1, 1, 1}, UpAxis::Z);
  REQUIRE(z.ok());
  const Vec3 hi_z{0.1, 0.2, 0.3};
  for (size_t k = 0; k < 3; ++k) {
    CHECK(z.mesh->lo[k] == Approx(0).margin(1e-7));
    CHECK(z.mesh->hi[k] == Approx(hi_z[k]).margin(1e-7));
  }
  // Scale applies in the caller's frame, after the unit and the turn.
  const MeshLoad s = loadMesh(kData + "box_cm_zup.dae", {1, 2, 1}, UpAxis::Y);
  REQUIRE(s.ok());
  CHECK(s.mesh->hi[1] == Approx(0.6).margin(1e-7));
}

TEST_CASE("mesh: an OBJ file with a quad face loads as triangles; STL and OBJ are not turned", "[mesh]") {
  TempDir dir;
  const std::string obj = dir.write("square.obj",
                                    "# a unit square pyramid\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0.5 2 0.5\n"
                                    "f 1 2 3 4\nf 1 5 2\nf 2 5 3\nf 3 5 4\nf 4 5 1\n");
  const MeshLoad l = loadMesh(obj, {1, 1, 1}, UpAxis::Z);
  REQUIRE(l.ok());
  CHECK(l.mesh->vertices.size() == 5);
  CHECK(l.mesh->triangles.size() == 6);
  CHECK(l.mesh->hi[1] == Approx(2));  // Z-up caller: an OBJ is taken as written
  CHECK(l.mesh->closed);
  CHECK(std::fabs(l.mesh->mass.volume) == Approx(2.0 / 3.0).epsilon(1e-6));  // base 1, height 2: V = 1*2/3
}

TEST_CASE("mesh: missing, corrupt, empty and badly scaled meshes are refused with the reason", "[mesh]") {
  const MeshLoad missing = loadMesh(kData + "no_such.stl", {1, 1, 1}, UpAxis::Y);
  CHECK_FALSE(missing.ok());
  CHECK(missing.error.kind == ErrorKind::MissingInput);
  CHECK(missing.error.loc.file == kData + "no_such.stl");
  CHECK(missing.error.message == "cannot read the mesh: No such file or directory");
  TempDir dir;
  const std::string junk = dir.write("junk.stl", "this is not a mesh\n");
  const MeshLoad corrupt = loadMesh(junk, {1, 1, 1}, UpAxis::Y);
  CHECK_FALSE(corrupt.ok());
  CHECK(corrupt.error.kind == ErrorKind::InvalidInput);
  CHECK(corrupt.error.message.rfind("is not an STL file", 0) == 0);
  const std::string empty = dir.write("empty.obj", "v 0 0 0\nv 1 0 0\n");
  const MeshLoad none = loadMesh(empty, {1, 1, 1}, UpAxis::Y);
  CHECK_FALSE(none.ok());
  CHECK(none.error.kind == ErrorKind::InvalidInput);
  const MeshLoad zero = loadMesh(kData + "cube_100mm.stl", {1, 0, 1}, UpAxis::Y);
  CHECK_FALSE(zero.ok());
  CHECK(zero.error.message == "scale needs three finite, non-zero factors");
}

TEST_CASE("mesh: the cache reads each file, scale and up axis once", "[mesh]") {
  MeshCache cache;
  const MeshLoad a = cache.load(kData + "cube_100mm.stl", {1, 1, 1}, UpAxis::Y);
  const MeshLoad b = cache.load(kData + "cube_100mm.stl", {1, 1, 1}, UpAxis::Y);
  const MeshLoad c = cache.load(kData + "cube_100mm.stl", {2, 2, 2}, UpAxis::Y);
  REQUIRE(a.ok());
  CHECK(a.mesh == b.mesh);
  CHECK(c.mesh != a.mesh);
  CHECK(cache.size() == 2);
}

TEST_CASE("mesh: dart-doc's real STL and DAE files load", "[mesh]") {
  // KR5's binary STL (a file name beside one with spaces), WAM's DAE visual, drchubo's hull STL.
  for (const std::string f :
       {"KR5/meshes/base_link.STL", "wam/meshes/wam/wam1.dae", "drchubo/meshes/convhull_NK2.stl"}) {
    INFO(f);
    const MeshLoad l = loadMesh(kDart + f, {1, 1, 1}, UpAxis::Z);
    REQUIRE(l.ok());
    CHECK(l.mesh->triangles.size() > 10);
    CHECK_FALSE(l.mesh->hull.empty());
    CHECK(l.mesh->hull_mass.volume > 0);
    // A real part is well under a metre and a half across once its units are right.
    for (size_t k = 0; k < 3; ++k) CHECK(l.mesh->hi[k] - l.mesh->lo[k] < 1.5);
  }
  const MeshLoad bad = loadMesh(kDart + "test/invalid_mesh.stl", {1, 1, 1}, UpAxis::Z);
  CHECK_FALSE(bad.ok());
  CHECK(bad.error.kind == ErrorKind::InvalidInput);
}
