// Mesh collision shapes (RCMeshGeom) against analytic answers: a hull rests like the primitive
// it encloses, a scaled millimetre cube rests at half its size, a COLLADA box lands with its
// unit and up axis applied, a ball rests on a static triangle mesh.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "scene/scene_helpers.h"
#include "simbob/physics.h"

using namespace simbob;
using scenetest::mustCompile;

namespace {

const std::string kMeshes = std::string(SIMBOB_SOURCE_DIR) + "/tests/data/meshes/";

// A scene with a ground and one mobile body at height y whose geom is `geom`.
std::string dropScene(const std::string& geom, double y, const std::string& inertia = "<Density Value=\"500\"/>") {
  return "<Simulation><ComponentList><RCGround Key=\"Ground\"/>"
         "<RCMobileRigidBody Key=\"Drop\"><Pose><RCGlobalCoordinates><Pose Value=\"0 " +
         std::to_string(y) + " 0 0 0 0\"/></RCGlobalCoordinates></Pose><Geom>" + geom +
         "</Geom><Inertia><RCInertiaByGeom>" + inertia +
         "</RCInertiaByGeom></Inertia></RCMobileRigidBody></ComponentList></Simulation>";
}

std::string meshGeom(const std::string& file, const std::string& scale, const std::string& more = "") {
  return "<RCMeshGeom><File Value=\"" + kMeshes + file + "\"/><Scale Value=\"" + scale + "\"/>" + more +
         "</RCMeshGeom>";
}

// Steps `seconds` and returns the body's final state.
BodyState settle(const Model& m, double seconds, int body = 0) {
  auto w = World::create(m, 1);
  REQUIRE(w);
  const int steps = static_cast<int>(std::lround(seconds / m.settings.max_time_step));
  for (int i = 0; i < steps; ++i) w->step(m.settings.max_time_step);
  return w->body(body);
}

}  // namespace

TEST_CASE("physics: a free STL cube in millimetres scaled by 0.001 comes to rest at half its size", "[physics][mesh]") {
  // cube_100mm.stl: a 100 mm cube centred on its origin; its hull (the default for a mobile
  // body) is the cube. Dropped from 0.2 m it settles with its centre 0.05 m above the ground.
  const Model m = mustCompile(dropScene(meshGeom("cube_100mm.stl", "0.001 0.001 0.001"), 0.2));
  REQUIRE(m.geoms.size() == 2);
  CHECK(m.geoms[1].shape == GeomShape::ConvexHull);
  REQUIRE(m.meshes.size() == 1);
  // Mass from the closed hull: 500 kg/m^3 * (0.1 m)^3 = 0.5 kg, I = m s^2 / 6 about each axis.
  CHECK(m.bodies[0].mass == Approx(0.5).epsilon(1e-6));
  CHECK(m.bodies[0].inertia[0] == Approx(0.5 * 0.01 / 6).epsilon(1e-6));
  CHECK(m.bodies[0].inertia[1] == Approx(0).margin(1e-12));
  const BodyState s = settle(m, 2.0);
  // Resting contact in ODE sinks by the error the solver leaves per step: with ERP 0.2 and
  // CFM 1e-10 well below 1e-5 m for half a kilogram (measured 7e-7 m); 1e-5 m leaves room.
  CHECK(s.pose.p[1] == Approx(0.05).margin(1e-5));
  CHECK(std::fabs(s.pose.p[0]) < 1e-6);  // a straight drop: no sideways drift
  CHECK(std::fabs(s.pose.q[0]) == Approx(1).margin(1e-6));
  CHECK(std::fabs(s.lin_vel[1]) < 1e-3);
}

TEST_CASE("physics: the hull of a box-shaped mesh falls and rests like the box primitive", "[physics][mesh]") {
  // The same 0.1 m cube as RCCuboidGeom and as a mesh hull, dropped tilted 20 degrees about X
  // so it lands on an edge and tips over: the free fall is shape-independent, and both
  // colliders (ODE's box-plane and convex-plane) find the same corners, so the paths agree but
  // for rounding, which the impact and the tumble amplify: measured 9e-6 m apart at worst over
  // the 2 s, checked at 1e-4 m; both rest at the same height.
  const std::string pose = "0 0.3 0 20 0 0";
  auto scene = [&](const std::string& geom) {
    std::string s = dropScene(geom, 0.3);
    const std::string flat = "0 0.300000 0 0 0 0";
    s.replace(s.find(flat), flat.size(), pose);
    return s;
  };
  const Model box = mustCompile(
      scene("<RCCuboidGeom><Width Value=\"0.1\"/><Height Value=\"0.1\"/><Depth Value=\"0.1\"/></RCCuboidGeom>"));
  const Model hull = mustCompile(scene(meshGeom("cube_100mm.stl", "0.001 0.001 0.001")));
  CHECK(hull.bodies[0].mass == Approx(box.bodies[0].mass).epsilon(1e-6));
  auto wb = World::create(box, 1);
  auto wh = World::create(hull, 1);
  REQUIRE(wb);
  REQUIRE(wh);
  double worst = 0;
  for (int i = 0; i < 2000; ++i) {
    wb->step(0.001);
    wh->step(0.001);
    for (size_t k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(wb->body(0).pose.p[k] - wh->body(0).pose.p[k]));
  }
  CHECK(worst < 1e-4);
  CHECK(wh->body(0).pose.p[1] == Approx(0.05).margin(1e-5));
  CHECK(wb->body(0).pose.p[1] == Approx(0.05).margin(1e-5));
}

TEST_CASE("physics: a COLLADA box in centimetres, Z up, lands with its unit and up axis applied", "[physics][mesh]") {
  // box_cm_zup.dae: 10 x 20 x 30 cm along the file's x y z from its origin, Z up. In the Y-up
  // scene it is 0.1 m along X, 0.3 m tall (Y) and 0.2 m along -Z, with a corner at the body
  // origin: its centre of mass sits at (0.05, 0.15, -0.1) in the body frame.
  const Model m = mustCompile(dropScene(meshGeom("box_cm_zup.dae", "1 1 1"), 0.1));
  const BodyDef& b = m.bodies[0];
  CHECK(b.mass == Approx(500 * 0.006).epsilon(1e-6));
  CHECK(b.com[0] == Approx(0.05).margin(1e-6));
  CHECK(b.com[1] == Approx(0.15).margin(1e-6));
  CHECK(b.com[2] == Approx(-0.1).margin(1e-6));
  // The tall box stands on its 0.1 x 0.2 m foot: the body origin (its bottom corner) comes to
  // rest on the ground, upright (tolerance as for the cube above).
  const BodyState s = settle(m, 2.0);
  CHECK(s.pose.p[1] == Approx(0).margin(1e-4));
  CHECK(std::fabs(s.pose.q[0]) == Approx(1).margin(1e-5));
}

TEST_CASE("physics: a ball rests on a static triangle mesh", "[physics][mesh]") {
  // The cube scaled to 1 m on a static body is a triangle mesh (no Hull given) with its top at
  // y = 0.5; a 0.1 m ball dropped on it rests with its centre at 0.6 (ODE's sphere-trimesh
  // contact; same solver tolerance as above).
  const std::string scene =
      "<Simulation><ComponentList>"
      "<RCStaticRigidBody Key=\"Block\"><Geom>" +
      meshGeom("cube_100mm.stl", "0.01 0.01 0.01") +
      "</Geom></RCStaticRigidBody>"
      "<RCMobileRigidBody Key=\"Ball\"><Pose><RCGlobalCoordinates><Pose Value=\"0.1 0.8 -0.2 0 0 0\"/>"
      "</RCGlobalCoordinates></Pose><Geom><RCSphereGeom><Radius Value=\"0.1\"/></RCSphereGeom></Geom>"
      "<Inertia><RCInertiaByGeom><Mass Value=\"1\"/></RCInertiaByGeom></Inertia></RCMobileRigidBody>"
      "</ComponentList></Simulation>";
  const Model m = mustCompile(scene);
  REQUIRE(m.geoms.size() == 2);
  CHECK(m.geoms[0].shape == GeomShape::TriMesh);
  CHECK(m.geoms[0].body == -1);
  const BodyState s = settle(m, 1.5);
  CHECK(s.pose.p[1] == Approx(0.6).margin(1e-4));
  CHECK(s.pose.p[0] == Approx(0.1).margin(1e-6));
  CHECK(s.pose.p[2] == Approx(-0.2).margin(1e-6));
}
