// RCWallStop end to end (scenes/wall_stop_robot.xml): the two-wheel robot drives at 0.2 m/s
// towards a wall whose face is at x = 1.4 m; its front proximity sensor reaches 0.1 m beyond the
// chassis front. It stops for good at the first touch, with the chassis short of the wall.
// Also: RCWallStop checks the interfaces of what it refers to.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene_helpers.h"
#include "simbob/physics.h"
#include "simbob/robot.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"

using namespace simbob;

namespace {

constexpr double kWallFace = 1.4;      // m, x of the wall's face
constexpr double kChassisFront = 0.2;  // m, the chassis front relative to its centre (Width 0.4)
constexpr double kSensorReach = 0.1;   // m, the sensor's front face beyond the chassis front

// Notes when sensor 0 first touches, checking at every step (a party of its own). The run owns
// and destroys its parties, so the time goes to a variable of the test's.
class SensorLog : public Party {
 public:
  explicit SensorLog(double* first_touch) : first_touch_(first_touch) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    if (world.touching(0) && *first_touch_ < 0) *first_touch_ = toSeconds(now);
    return now + 1000000;  // every 1 ms: every step
  }

 private:
  double* first_touch_;
};

}  // namespace

TEST_CASE("robot: RCWallStop stops a robot at a wall before its body touches it", "[robot]") {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/scenes/wall_stop_robot.xml", testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  REQUIRE(m.bodies[0].key == "Bot.Cart.Chassis");
  REQUIRE(m.sensors.size() == 1);
  CHECK(m.sensors[0].key == "Bot.Cart.Front");
  CHECK(m.sensors[0].body == 0);

  std::vector<double> x, z;
  SimulationOptions o;
  o.duration = 10;
  double first_touch = -1;
  Diagnostics sd;
  std::unique_ptr<Simulation> sim = Simulation::fromModel(m, o, sd);
  REQUIRE(sim);
  sim->addParty(std::make_unique<SensorLog>(&first_touch));
  sim->sampleTrajectory(nullptr, 0.01, [&](double, const double* p) {
    x.push_back(p[0]);
    z.push_back(p[2]);
  });
  RunResult r = sim->runToEnd();
  REQUIRE(r.status == RunStatus::Completed);
  // The sensor first touches when the chassis centre has covered 1.4 - 0.3 = 1.1 m; at 0.2 m/s
  // that takes 5.5 s plus the spin-up of the wheels from rest.
  REQUIRE(first_touch > 5.5);
  CHECK(first_touch < 5.7);
  // Stopped: the chassis does not move over the last 2 s.
  const double final_x = x.back();
  CHECK(std::fabs(x[x.size() - 201] - final_x) < 1e-6);
  // Where: the controller sees the touch within one Period (10 ms, 2 mm at 0.2 m/s) and the
  // wheels brake with 5 N m each; the chassis front ends between 0.09 m and 0.1 m from the wall:
  // closer than the sensor's reach (it overran the touch a little), never at the wall.
  double max_x = 0;
  for (double v : x) max_x = std::max(max_x, v);
  const double gap = kWallFace - (max_x + kChassisFront);
  CHECK(gap > kSensorReach - 0.01);
  CHECK(gap <= kSensorReach);
  // Straight ahead all the way.
  for (double v : z) CHECK(std::fabs(v) < 1e-6);
}

TEST_CASE("robot: RCWallStop checks that Motion and Sensor implement their interfaces", "[robot]") {
  const std::string text = R"(<Simulation><ComponentList>
<RCRobot Key="Bot"><Construction><RCConstruction Key="C">
  <Body><RCMobileRigidBody Key="Base"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>
  <ChildList>
    <RCHingeJoint Key="H"><Body><RCMobileRigidBody Key="Wheel"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body></RCHingeJoint>
    <RCGenericDrive Key="D"><Joint Ref="Bot.C.H"/></RCGenericDrive>
    <RCProximitySensor Key="S"><Geom><RCSphereGeom/></Geom></RCProximitySensor>
  </ChildList></RCConstruction></Construction>
  <ControllerList>
    <RCDriveTest Key="T"><Drive Ref="Bot.C.D"/></RCDriveTest>
    <RCWallStop Key="W">
      <Motion Ref="Bot.T"/>
      <Sensor Ref="Bot.C.D"/>
    </RCWallStop>
  </ControllerList></RCRobot>
</ComponentList></Simulation>)";
  Scene s = scenetest::mustLoad(text);
  Model m;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m, d));
  const std::string errors = scenetest::errorText(d);
  CHECK(errors ==
        "test.xml:12: RCWallStop 'Bot.W': parameter 'Motion' must refer to a component implementing "
        "RC2DMotionControl, but RCDriveTest 'Bot.T' does not\n"
        "test.xml:13: RCWallStop 'Bot.W': parameter 'Sensor' must refer to a component implementing "
        "RCContactSensor, but RCGenericDrive 'Bot.C.D' does not\n");
}

TEST_CASE("robot: an RCProximitySensor lowers to sensor geoms on the construction's root body", "[robot]") {
  // Local pose relative to the root body (at x = 1); the geom is massless: the body's mass and
  // inertia come from its own geoms alone.
  const Model m = scenetest::mustCompile(R"(<Simulation><ComponentList>
<RCConstruction Key="C">
  <Body><RCMobileRigidBody Key="Base">
    <Pose><RCGlobalCoordinates><Pose Value="1 2 0 0 0 90"/></RCGlobalCoordinates></Pose>
    <Geom><RCCuboidGeom/></Geom>
    <Inertia><RCInertiaByGeom><Mass Value="2"/></RCInertiaByGeom></Inertia>
  </RCMobileRigidBody></Body>
  <ChildList>
    <RCProximitySensor Key="S">
      <Pose><RCLocalCoordinates><Pose Value="0.5 0 0 0 0 0"/></RCLocalCoordinates></Pose>
      <Geom><RCSphereGeom><Radius Value="0.05"/></RCSphereGeom></Geom>
    </RCProximitySensor>
  </ChildList>
</RCConstruction>
</ComponentList></Simulation>)");
  REQUIRE(m.sensors.size() == 1);
  REQUIRE(m.sensors[0].geoms.size() == 1);
  const GeomDef& g = m.geoms[static_cast<size_t>(m.sensors[0].geoms[0])];
  CHECK(g.sensor);
  CHECK(g.body == 0);
  CHECK(g.shape == GeomShape::Sphere);
  CHECK(g.offset.p[0] == Approx(0.5));
  CHECK(g.offset.p[1] == Approx(0).margin(1e-12));
  CHECK(m.bodies[0].mass == 2.0);
  CHECK(m.bodies[0].com[0] == 0.0);
  for (const GeomDef& other : m.geoms)
    if (&other != &g) CHECK_FALSE(other.sensor);
}
