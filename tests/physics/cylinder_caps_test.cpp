// Flat cylinders on boxes and on each other (lib/physics/cylinder_caps.cpp, issue 42): scenes in
// the native format, stepped, against their analytic rest heights and orientations.
//
// Common tolerances:
//  - height: a resting body sinks into its support by the contact's softness, about
//    g dt^2 / ERP = 9.81e-6 / 0.2 = 5e-5 m at the default ERP 0.2 and dt 1 ms; 1 mm is 20 times
//    that and a fortieth of what a puck of radius 5 cm standing on its rim shows (4 cm higher);
//  - tilt: the angle between a cylinder's axis and the vertical. A cap held by contacts of equal
//    depth is level to the depth differences the solver leaves, 5e-5 m over a 0.1 m diameter
//    (5e-4 rad); 0.01 rad (0.6 degrees) is 20 times that, and a puck on its rim is at pi/2.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>

#include "test_registry.h"
#include "simbob/compile.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

using namespace simbob;

namespace {

constexpr double kHeightTol = 1e-3;  // m, see above
constexpr double kTiltTol = 0.01;    // rad, see above

Model compileXml(const std::string& components) {
  Scene scene;
  Diagnostics d;
  Model m;
  const std::string xml = "<Simulation><ComponentList>" + components + "</ComponentList></Simulation>";
  REQUIRE(loadSceneFromText(xml, "cylinders.xml", Format::Xml, testRegistry(), &scene, d));
  REQUIRE(compileScene(scene, &m, d));
  return m;
}

/// A static box of `w` x `h` x `d` m centred at (x, y, z).
std::string box(double x, double y, double z, double w, double h, double d) {
  return "<RCStaticRigidBody Key=\"Table\"><Pose><RCGlobalCoordinates><Pose Value=\"" + std::to_string(x) + " " +
         std::to_string(y) + " " + std::to_string(z) +
         " 0 0 0\"/></RCGlobalCoordinates></Pose><Geom><RCCuboidGeom><Width Value=\"" + std::to_string(w) +
         "\"/><Height Value=\"" + std::to_string(h) + "\"/><Depth Value=\"" + std::to_string(d) +
         "\"/></RCCuboidGeom></Geom></RCStaticRigidBody>";
}

/// A mobile cylinder (radius r, length len, 1000 kg/m^3) at (x, y, z), its axis turned from the
/// body's Z onto the world's Y (lying flat) and then tilted by `tilt` degrees about Z.
std::string puck(const std::string& key, double x, double y, double z, double r, double len, double tilt = 0,
                 const std::string& motion = "") {
  return "<RCMobileRigidBody Key=\"" + key + "\"><Pose><RCGlobalCoordinates><Pose Value=\"" + std::to_string(x) + " " +
         std::to_string(y) + " " + std::to_string(z) + " -90 0 " + std::to_string(tilt) +
         "\"/></RCGlobalCoordinates></Pose>" + motion + "<Geom><RCCylinderGeom><Radius Value=\"" + std::to_string(r) +
         "\"/><Length Value=\"" + std::to_string(len) + "\"/></RCCylinderGeom></Geom></RCMobileRigidBody>";
}

/// The angle (rad) between body i's Z axis (its cylinder's axis, which starts pointing up) and
/// the world's +Y: near pi when the cylinder has turned over.
double tilt(const World& w, int i) {
  const Vec3 axis = rotate(w.body(i).pose.q, {0, 0, 1});
  return std::acos(std::max(-1.0, std::min(1.0, axis[1])));
}

void run(World& w, double seconds) {
  for (int i = 0; i < static_cast<int>(std::lround(seconds / 0.001)); ++i) w.step(0.001);
}

}  // namespace

TEST_CASE("cylinder caps: a puck dropped onto a box rests flat on it, the same side up", "[physics][cylinder]") {
  // Radius 5 cm, 2 cm thick, onto a 1 m box whose top is at y = 0.5: it rests at
  // 0.5 + 0.02 / 2 = 0.51 m, level and the same side up. Dropped flat from 19 cm above that, or
  // from 4 cm with its axis 5 degrees off the vertical. (ODE's own collider turned it over in
  // the first case: its contacts, half of the rim, tip the landing puck.)
  const auto [y0, tilt0] = GENERATE(table<double, double>({{0.7, 0.0}, {0.55, 5.0}}));
  CAPTURE(y0, tilt0);
  Model m = compileXml(box(0, 0, 0, 1, 1, 1) + puck("Puck", 0.1, y0, -0.2, 0.05, 0.02, tilt0));
  auto w = World::create(m, 0);
  REQUIRE(w);
  run(*w, 3.0);
  CHECK(w->body(0).pose.p[1] == Approx(0.51).margin(kHeightTol));
  CHECK(tilt(*w, 0) < kTiltTol);
  CHECK(norm(w->body(0).lin_vel) < 1e-2);  // at rest: a hundredth of the 0.9 m/s of the gentler landing
  CHECK(w->lastContactCount() == 4);       // MaxContacts 4: spread round the rim
  if (tilt0 == 0) {                        // dropped flat on a level face: nothing pushes it sideways
    CHECK(w->body(0).pose.p[0] == Approx(0.1).margin(kHeightTol));
    CHECK(w->body(0).pose.p[2] == Approx(-0.2).margin(kHeightTol));
  }
}

TEST_CASE("cylinder caps: a puck overhanging the box edge by 2 cm rests flat with its centre over the box",
          "[physics][cylinder]") {
  // Its centre of mass 3 cm inside the edge at x = 0.5: held by the part of the cap over the box.
  Model m = compileXml(box(0, 0, 0, 1, 1, 1) + puck("Puck", 0.47, 0.52, 0, 0.05, 0.02));
  auto w = World::create(m, 0);
  REQUIRE(w);
  run(*w, 2.0);
  CHECK(w->body(0).pose.p[1] == Approx(0.51).margin(kHeightTol));
  CHECK(w->body(0).pose.p[0] == Approx(0.47).margin(kHeightTol));
  CHECK(tilt(*w, 0) < kTiltTol);
}

TEST_CASE("cylinder caps: a puck dropped onto a puck on a box: both rest flat at their stacked heights",
          "[physics][cylinder]") {
  // The lower puck on the box top (0.5): centre at 0.51; the upper one, 1 cm off its axis and
  // tilted 5 degrees as it falls 4 cm, on the lower one's top (0.52): centre at 0.53.
  Model m = compileXml(box(0, 0, 0, 1, 1, 1) + puck("Lower", 0, 0.511, 0, 0.05, 0.02) +
                       puck("Upper", 0.01, 0.57, 0, 0.05, 0.02, 5));
  auto w = World::create(m, 0);
  REQUIRE(w);
  run(*w, 3.0);
  CHECK(w->body(0).pose.p[1] == Approx(0.51).margin(kHeightTol));
  CHECK(w->body(1).pose.p[1] == Approx(0.53).margin(2 * kHeightTol));  // two contacts' softness
  CHECK(tilt(*w, 0) < kTiltTol);
  CHECK(tilt(*w, 1) < kTiltTol);
  CHECK(w->body(1).pose.p[0] - w->body(0).pose.p[0] == Approx(0.01).margin(kHeightTol));
}

TEST_CASE("cylinder caps: a puck on a wide static drum and a box on a puck rest flat", "[physics][cylinder]") {
  SECTION("a puck on the cap of a static cylinder of radius 0.3 m whose top is at y = 0.5") {
    const std::string drum =
        "<RCStaticRigidBody Key=\"Drum\"><Pose><RCGlobalCoordinates><Pose Value=\"0 0.4 0 -90 0 0\"/>"
        "</RCGlobalCoordinates></Pose><Geom><RCCylinderGeom><Radius Value=\"0.3\"/><Length Value=\"0.2\"/>"
        "</RCCylinderGeom></Geom></RCStaticRigidBody>";
    Model m = compileXml(drum + puck("Puck", 0.1, 0.55, 0, 0.05, 0.02, 5));
    auto w = World::create(m, 0);
    REQUIRE(w);
    run(*w, 2.0);
    CHECK(w->body(0).pose.p[1] == Approx(0.51).margin(kHeightTol));
    CHECK(tilt(*w, 0) < kTiltTol);
  }
  SECTION("a 4 cm cube on a wide puck resting on a box: the cube is the incident face") {
    const std::string cube =
        "<RCMobileRigidBody Key=\"Cube\"><Pose><RCGlobalCoordinates><Pose Value=\"0.05 0.56 0 0 0 3\"/>"
        "</RCGlobalCoordinates></Pose><Geom><RCCuboidGeom><Width Value=\"0.04\"/><Height Value=\"0.04\"/>"
        "<Depth Value=\"0.04\"/></RCCuboidGeom></Geom></RCMobileRigidBody>";
    Model m = compileXml(box(0, 0, 0, 1, 1, 1) + puck("Puck", 0, 0.511, 0, 0.2, 0.02) + cube);
    auto w = World::create(m, 0);
    REQUIRE(w);
    run(*w, 2.0);
    CHECK(w->body(0).pose.p[1] == Approx(0.51).margin(kHeightTol));
    CHECK(w->body(1).pose.p[1] == Approx(0.54).margin(2 * kHeightTol));                   // 0.52 + 0.04 / 2
    CHECK(std::acos(std::min(1.0, rotate(w->body(1).pose.q, {0, 1, 0})[1])) < kTiltTol);  // level
  }
}

TEST_CASE("cylinder caps: a wheel rolling across a box top touches it until its centre passes the edge",
          "[physics][cylinder]") {
  // A wheel of radius 0.1 m and width 0.04 m, axis along Z, on the box top at y = 0.5 (centre at
  // 0.6), rolling at 1 m/s towards the edge at x = 0.5 (w = -v / r about Z). Its cylinder side on
  // the box face is ODE's own collider, which gives no point at zero depth: a wheel resting at
  // exactly 0.6 m has no contact for that one step and sinks g dt^2 = 1e-5 m into the next. Held
  // up, the gaps are single steps and the centre stays at the rolling height; a wheel that lost
  // the box would have fallen 1 mm within 14 ms (g t^2 / 2).
  const std::string motion =
      "<Motion><RCGlobalMotion><LinVelocity Value=\"1 0 0\"/><AngVelocity Value=\"0 0 "
      "-10\"/></RCGlobalMotion></Motion>";
  const std::string wheel =
      "<RCMobileRigidBody Key=\"Wheel\"><Pose><RCGlobalCoordinates><Pose Value=\"-0.3 0.5999 0 0 0 0\"/>"
      "</RCGlobalCoordinates></Pose>" +
      motion +
      "<Geom><RCCylinderGeom><Radius Value=\"0.1\"/><Length Value=\"0.04\"/></RCCylinderGeom></Geom>"
      "</RCMobileRigidBody>";
  Model m = compileXml(box(0, 0, 0, 1, 1, 1) + wheel);
  auto w = World::create(m, 0);
  REQUIRE(w);
  int steps = 0, gap = 0, longestGap = 0;
  double worst = 0;
  while (w->body(0).pose.p[0] < 0.5) {
    w->step(0.001);
    ++steps;
    if (w->body(0).pose.p[0] >= 0.5) break;
    gap = w->lastContactCount() == 0 ? gap + 1 : 0;
    longestGap = std::max(longestGap, gap);
    worst = std::max(worst, std::fabs(w->body(0).pose.p[1] - 0.6));
    REQUIRE(steps < 2000);  // 0.8 m at about 1 m/s
  }
  CHECK(longestGap <= 1);
  CHECK(worst < kHeightTol);
  run(*w, 0.5);
  CHECK(w->body(0).pose.p[1] < 0.5);  // past the edge it fell: the test sees losing the box
}

TEST_CASE("cylinder caps: the same bits on 1 and 3 threads (the narrow phase's workers collide caps too)",
          "[physics][cylinder]") {
  // A puck on a puck on a box: both kinds of cap contact, collided on a worker with 3 threads.
  Model m = compileXml(box(0, 0, 0, 1, 1, 1) + puck("Lower", 0, 0.511, 0, 0.05, 0.02) +
                       puck("Upper", 0.01, 0.57, 0, 0.05, 0.02, 5));
  auto one = World::create(m, 0, 1), three = World::create(m, 0, 3);
  REQUIRE(one);
  REQUIRE(three);
  bool same = true;
  for (int i = 0; i < 1000 && same; ++i) {
    one->step(0.001);
    three->step(0.001);
    for (int b = 0; b < 2; ++b) {
      const BodyState x = one->body(b), y = three->body(b);
      same = same && std::memcmp(&x.pose, &y.pose, sizeof(Transform)) == 0;
    }
  }
  CHECK(same);
  CHECK(one->lastContactCount() == 8);  // it did rest on caps: 4 on the box, 4 between the pucks
}
