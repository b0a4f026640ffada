// A body whose geoms sit off its origin: ODE must get the centre of mass, and the trajectory
// must still report the body origin.
#include <catch2/catch.hpp>

#include "test_registry.h"
#include "simbob/compile.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

using namespace simbob;

namespace {

Model compileText(const std::string& xml) {
  Scene scene;
  Diagnostics d;
  Model m;
  REQUIRE(loadSceneFromText(xml, "com.xml", Format::Xml, testRegistry(), &scene, d));
  REQUIRE(compileScene(scene, &m, d));
  return m;
}

// A sphere of radius 0.1 m held 1 m along +X from the body origin, its bottom on the ground.
const char* kOffsetBall = R"(<Simulation><ComponentList>
<RCGround Key="G"/>
<RCMobileRigidBody Key="B">
  <Pose><RCGlobalCoordinates><Pose Value="-1 0.1 0 0 0 0"/></RCGlobalCoordinates></Pose>
  <Geom><RCTransformGeom>
    <Pose><RCLocalCoordinates><Pose Value="1 0 0 0 0 0"/></RCLocalCoordinates></Pose>
    <SubGeom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></SubGeom>
  </RCTransformGeom></Geom>
</RCMobileRigidBody>
</ComponentList></Simulation>)";

}  // namespace

TEST_CASE("an offset geom moves the centre of mass, and the body rests on it", "[physics][com]") {
  Model m = compileText(kOffsetBall);
  REQUIRE(m.bodies.size() == 1);
  const BodyDef& b = m.bodies[0];
  CHECK(b.com[0] == Approx(1.0));
  CHECK(b.com[1] == Approx(0.0).margin(1e-15));
  // The sphere's own inertia about its centre: 2/5 m r^2.
  CHECK(b.inertia[0] == Approx(0.4 * b.mass * 0.01));
  auto w = World::create(m, 0);
  REQUIRE(w);
  BodyState s0 = w->body(0);
  // The reported pose is the body origin as written, not ODE's centre-of-mass frame.
  CHECK(s0.pose.p[0] == Approx(-1.0));
  CHECK(s0.pose.p[1] == Approx(0.1));
  for (int i = 0; i < 2000; ++i) w->step(0.001);
  BodyState s = w->body(0);
  // Supported right under its centre of mass, the body stays put and does not tip: with the
  // centre of mass at the origin (1 m beside the contact) it would fall over.
  CHECK(s.pose.p[0] == Approx(-1.0).margin(1e-3));
  CHECK(s.pose.p[1] == Approx(0.1).margin(1e-3));
  CHECK(std::fabs(s.pose.q[3]) < 1e-3);
  CHECK(norm(s.ang_vel) < 1e-3);
}

TEST_CASE("initial motion is of the body origin, also with an offset centre of mass", "[physics][com]") {
  // Spin at 1 rad/s about Y with the body origin at rest: the centre of mass, 1 m along +X from
  // the origin, then moves at w x r = (0, 0, -1) m/s, and the origin circles it.
  std::string xml = kOffsetBall;
  xml.replace(xml.find("<RCGround Key=\"G\"/>"), 19, "");
  xml.replace(xml.find("<Geom>"), 6,
              "<Motion><RCGlobalMotion><AngVelocity Value=\"0 1 0\"/></RCGlobalMotion></Motion><Geom>");
  Model m = compileText(xml);
  m.settings.gravity = {0, 0, 0};
  auto w = World::create(m, 0);
  REQUIRE(w);
  BodyState s0 = w->body(0);
  CHECK(norm(s0.lin_vel) < 1e-12);
  for (int i = 0; i < 1000; ++i) w->step(0.001);
  BodyState s = w->body(0);
  // After 1 s the centre of mass is at (0, 0.1, -1) and the origin has swung 1 rad around it
  // from the offset (-1, 0, 0): Ry(1) (-1, 0, 0) = (-cos 1, 0, sin 1).
  const double a = 1.0;
  CHECK(s.pose.p[0] == Approx(-std::cos(a)).margin(1e-3));
  CHECK(s.pose.p[1] == Approx(0.1).margin(1e-9));
  CHECK(s.pose.p[2] == Approx(-1.0 + std::sin(a)).margin(1e-3));
}
