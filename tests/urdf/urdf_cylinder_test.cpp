// URDF cylinders on a URDF table (lib/physics/cylinder_caps.cpp, issue 42): a puck link dropped
// onto a box link fixed to the world rests flat, and a second puck rests flat on the first.
// Tolerances as in tests/physics/cylinder_caps_test.cpp: 1 mm of height (20 times the contact's
// softness, g dt^2 / ERP = 5e-5 m; a puck on its rim stands 4 cm higher) and 0.01 rad of tilt (20
// times the 5e-4 rad that depth differences of 5e-5 m make over its 0.1 m diameter).
#include <cmath>

#include "simbob/transform.h"
#include "urdf/urdf_test_util.h"

using namespace urdftest;

namespace {

const char* kTable = R"(<robot name="table">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="top"/><origin xyz="0 0 0"/></joint>
  <link name="top">
    <inertial><mass value="10"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><box size="1 1 1"/></geometry></collision>
  </link>
</robot>)";

// A puck: radius 5 cm, 2 cm along the link's Z (URDF's up), 0.157 kg (1000 kg/m^3).
const char* kPuck = R"(<robot name="puck">
  <link name="puck">
    <inertial><mass value="0.157"/><inertia ixx="1.03e-4" ixy="0" ixz="0" iyy="1.03e-4" iyz="0" izz="1.96e-4"/></inertial>
    <collision><geometry><cylinder radius="0.05" length="0.02"/></geometry></collision>
  </link>
</robot>)";

/// RCImportURDF of `file` with its root at scene pose `pose` ("x y z a b c", Y up).
std::string import(const std::string& key, const std::string& file, const std::string& pose) {
  return "<RCImportURDF Key=\"" + key + "\"><File Value=\"" + file + "\"/><Pose><RCGlobalCoordinates><Pose Value=\"" +
         pose + "\"/></RCGlobalCoordinates></Pose></RCImportURDF>";
}

/// The angle (rad) between body `b`'s cylinder axis (its geom's Z, which starts pointing up) and
/// the scene's +Y.
double tilt(const Model& m, const Simulation& sim, int b) {
  for (const GeomDef& g : m.geoms) {
    if (g.body != b || g.shape != GeomShape::Cylinder) continue;
    const Vec3 axis = rotate(sim.world().body(b).pose.q, rotate(g.offset.q, {0, 0, 1}));
    return std::acos(std::max(-1.0, std::min(1.0, axis[1])));  // near pi if it turned over
  }
  FAIL("body " << b << " has no cylinder");
  return 0;
}

}  // namespace

/// Compiles and runs the scene of `imports` for 3 s.
std::unique_ptr<Simulation> runPucks(TempDir& dir, const std::string& imports, Model* m) {
  const std::string scene =
      dir.write("pucks.xml", "<Simulation><ComponentList>" + import("table", "table.urdf", "0 0 0 0 0 0") + imports +
                                 "</ComponentList></Simulation>");
  Diagnostics d;
  INFO(errorText(d));
  REQUIRE(compileFile(scene, m, d));
  Diagnostics sd;
  auto sim = Simulation::fromModel(*m, SimulationOptions{}, sd);
  INFO(errorText(sd));
  REQUIRE(sim);
  sim->runUntil(3.0);
  return sim;
}

TEST_CASE("urdf cylinders: a puck link dropped onto a box link rests flat, and a second puck on it",
          "[urdf][cylinder]") {
  TempDir dir;
  dir.write("table.urdf", kTable);
  dir.write("puck.urdf", kPuck);
  SECTION("dropped flat from 49 cm above its rest height") {
    // The table's top at y = 0.5: the puck rests at 0.51. Nothing turns it or pushes it sideways,
    // so it lands level where it was let go (ODE's own collider left it 4 degrees tilted, 3 cm
    // away).
    Model m;
    auto sim = runPucks(dir, import("a", "puck.urdf", "0.1 1 -0.2 0 0 0"), &m);
    const int a = bodyIndex(m, "a.puck");
    CHECK(sim->world().body(a).pose.p[1] == Approx(0.51).margin(1e-3));
    CHECK(sim->world().body(a).pose.p[0] == Approx(0.1).margin(1e-3));
    CHECK(sim->world().body(a).pose.p[2] == Approx(-0.2).margin(1e-3));
    CHECK(tilt(m, *sim, a) < 0.01);
  }
  SECTION("a second puck, 1 cm off the first's axis and turned 5 degrees, dropped on it") {
    Model m;
    auto sim = runPucks(
        dir, import("a", "puck.urdf", "0.1 0.511 -0.2 0 0 0") + import("b", "puck.urdf", "0.11 0.58 -0.2 0 0 5"), &m);
    const int a = bodyIndex(m, "a.puck"), b = bodyIndex(m, "b.puck");
    CHECK(sim->world().body(a).pose.p[1] == Approx(0.51).margin(1e-3));
    CHECK(sim->world().body(b).pose.p[1] == Approx(0.53).margin(2e-3));  // on two contacts' softness
    CHECK(tilt(m, *sim, a) < 0.01);
    CHECK(tilt(m, *sim, b) < 0.01);
  }
}
