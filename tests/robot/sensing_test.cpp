// RCObstacleAvoider and RCWallFollower end to end, on the small robot of bench/gen_robots.py
// (scenes in tests/data/sensing/, written by that script): chassis centre 0.06 m above the
// ground, eight range sensors at the chassis centre (MinRange 0.15 m, MaxRange 0.65 m), every point of the robot within
// 0.135 m of its chassis centre in the ground plane. Also: both check what they refer to.
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

constexpr double kRobotRadius = 0.135;  // m, the robot's footprint about its chassis centre

/// The chassis (body 0) sampled every 0.01 s: position and heading (rad, counter-clockwise
/// seen from above, 0 along +X).
struct Track {
  std::vector<double> t, x, z, heading;
};

Track runScene(const std::string& name, double duration) {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/tests/data/sensing/" + name, testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  REQUIRE(m.bodies[0].key == "Bot.Cart.Chassis");
  SimulationOptions o;
  o.duration = duration;
  Diagnostics sd;
  std::unique_ptr<Simulation> sim = Simulation::fromModel(m, o, sd);
  REQUIRE(sim);
  Track tr;
  sim->sampleTrajectory(nullptr, 0.01, [&](double t, const double* p) {
    tr.t.push_back(t);
    tr.x.push_back(p[0]);
    tr.z.push_back(p[2]);
    const double qw = p[3], qx = p[4], qy = p[5], qz = p[6];
    const double fx = 1 - 2 * (qy * qy + qz * qz), fz = 2 * (qx * qz - qw * qy);
    tr.heading.push_back(std::atan2(-fz, fx));
  });
  RunResult r = sim->runToEnd();
  REQUIRE(r.status == RunStatus::Completed);
  return tr;
}

size_t at(const Track& tr, double t) { return std::min(tr.t.size() - 1, static_cast<size_t>(std::lround(t / 0.01))); }

}  // namespace

TEST_CASE("robot: RCObstacleAvoider drives straight at Speed with nothing in range", "[robot][sensing]") {
  // Every sensor reads MaxRange: a = 0, so f = p = 0: v = Speed = 0.12 m/s, w = 0: both wheels
  // are commanded exactly 3 rad/s. Straight to the iterative solver's residuals (QuickStep lets
  // the heading wander by about 3e-4 rad over 6 s): within 1 mrad and 1 mm.
  const Track tr = runScene("open.xml", 6);
  for (size_t i = 0; i < tr.t.size(); ++i) {
    CHECK(std::fabs(tr.z[i]) < 1e-3);
    CHECK(std::fabs(tr.heading[i]) < 1e-3);
  }
  // The wheels reach their speed within the first second (2 W drives on a 1.2 kg robot); after
  // that the chassis covers 0.12 m/s exactly (to the wheels' rolling: 0.5 %).
  const double v = (tr.x[at(tr, 6)] - tr.x[at(tr, 3)]) / 3;
  CHECK(v == Approx(0.12).epsilon(0.005));
}

TEST_CASE("robot: RCObstacleAvoider facing a wall turns away before it touches", "[robot][sensing]") {
  // The wall's face is at x = 1, square to the robot's path. The front sensors (bearings +-15
  // degrees, at the chassis centre, MaxRange 0.65 m) first see it when the chassis centre is at
  // 1 - 0.65 cos 15 = 0.372 m: until then it drives straight along +X.
  const Track tr = runScene("wall.xml", 15);
  const double first_seen = 1 - 0.65 * std::cos(15 * 3.14159265358979 / 180);
  double closest = 1e9;
  bool seen = false;
  for (size_t i = 0; i < tr.t.size(); ++i) {
    seen = seen || tr.x[i] >= first_seen - 0.005;  // 5 mm: one Period at Speed is 6 mm
    if (!seen) {
      CHECK(std::fabs(tr.z[i]) < 1e-3);  // straight, as in the open: to the solver's residuals
      CHECK(std::fabs(tr.heading[i]) < 1e-3);
    }
    closest = std::min(closest, 1 - tr.x[i]);
  }
  CHECK(seen);
  INFO("closest chassis centre to the wall face: " << closest << " m");
  CHECK(closest > kRobotRadius);  // its footprint never reaches the wall
  // Head-on (p = 0 when it first sees the wall) it turns left (s = +1) and drives away: at the
  // end it heads away from the wall (|heading| > 90 degrees) and is farther from it.
  CHECK(std::fabs(tr.heading.back()) > 3.14159265358979 / 2);
  CHECK(tr.x.back() < 1 - closest - 0.3);
}

TEST_CASE("robot: RCObstacleAvoider turns away from the nearer side of a slanted wall", "[robot][sensing]") {
  // The wall turned 30 degrees counter-clockwise: its left end (-Z) is nearer, so the left
  // sensors see it first (p < 0): it turns right (clockwise, heading < 0) and never touches.
  const Track tr = runScene("wall_angled.xml", 15);
  double lowest = 0, highest = 0, closest = 1e9;
  const double c = std::cos(30 * 3.14159265358979 / 180), s = std::sin(30 * 3.14159265358979 / 180);
  for (size_t i = 0; i < tr.t.size(); ++i) {
    lowest = std::min(lowest, tr.heading[i]);
    highest = std::max(highest, tr.heading[i]);
    // The 0.1 m thick wall turns about its centre (1.05, 0): its face's normal towards the robot
    // is (-cos 30, sin 30) and the face passes through (1.05 - 0.05 cos 30, 0.05 sin 30).
    closest = std::min(closest, (tr.x[i] - (1.05 - 0.05 * c)) * -c + (tr.z[i] - 0.05 * s) * s);
  }
  INFO("closest chassis centre to the wall face: " << closest << " m");
  CHECK(closest > kRobotRadius);
  CHECK(lowest < -0.5);
  CHECK(highest < 1e-3);
}

TEST_CASE("robot: RCWallFollower keeps its distance along a straight wall", "[robot][sensing]") {
  // Started at the set distance (0.3 m from the wall face on its left, parallel) it stays there:
  // the 36 rays are 10 degrees apart, so the nearest one is at most 5 degrees off the
  // perpendicular and over-reads the distance by at most 0.3 (1 / cos 5 - 1) = 1.1 mm; the PD
  // law answers that with a correction of the same size. So within 5 mm over 20 s (4 m).
  const Track tr = runScene("corridor.xml", 20);
  double worst = 0;
  for (size_t i = 0; i < tr.t.size(); ++i) worst = std::max(worst, std::fabs(tr.z[i]));
  INFO("largest deviation from the set distance: " << worst << " m");
  CHECK(worst < 0.005);
  CHECK(tr.x.back() > 3.5);  // it kept going at about Speed (0.2 m/s)
}

TEST_CASE("robot: RCWallFollower closes an offset without hitting the wall", "[robot][sensing]") {
  // Started 0.15 m farther out (0.45 m from the wall): critically damped with W = 2 Speed /
  // Distance = 1.33 rad/s, the error decays as (1 + W t) exp(-W t): below 1 % of 0.15 m by
  // t = 10 s; it never goes nearer than the set distance by more than the 5 mm above, and its
  // footprint stays off the wall.
  const Track tr = runScene("corridor_offset.xml", 25);
  double nearest = 1e9;
  for (size_t i = 0; i < tr.t.size(); ++i) nearest = std::min(nearest, tr.z[i] + 0.45);
  INFO("nearest chassis centre to the wall: " << nearest << " m");
  CHECK(nearest > 0.3 - 0.005);
  for (size_t i = at(tr, 15); i < tr.t.size(); ++i) CHECK(std::fabs(tr.z[i] + 0.15) < 0.005);
}

TEST_CASE("robot: RCObstacleAvoider and RCWallFollower check what they refer to", "[robot][sensing]") {
  const std::string text = R"(<Simulation><ComponentList>
<RCRobot Key="Bot"><Construction><RCConstruction Key="C">
  <Body><RCMobileRigidBody Key="Base"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body>
  <ChildList>
    <RCHingeJoint Key="H"><Body><RCMobileRigidBody Key="Wheel"><Geom><RCSphereGeom/></Geom></RCMobileRigidBody></Body></RCHingeJoint>
    <RCGenericVelControlledDrive Key="D"><Joint Ref="Bot.C.H"/></RCGenericVelControlledDrive>
    <RCRangeSensor Key="R"/>
    <RCLaserScanner Key="L"/>
  </ChildList></RCConstruction></Construction>
  <ControllerList>
    <RCTwoWheelMotionControl Key="M"><ControlLeft Ref="Bot.C.D"/><ControlRight Ref="Bot.C.D"/></RCTwoWheelMotionControl>
    <RCObstacleAvoider Key="A1"><Motion Ref="Bot.M"/></RCObstacleAvoider>
    <RCObstacleAvoider Key="A2">
      <Motion Ref="Bot.M"/>
      <Sensors><Sensor Ref="Bot.C.R"/><Sensor Ref="Bot.C.L"/></Sensors>
    </RCObstacleAvoider>
    <RCWallFollower Key="F"><Motion Ref="Bot.M"/><Scanner Ref="Bot.C.R"/></RCWallFollower>
    <RCWallFollower Key="G"><Motion Ref="Bot.M"/><Scanner Ref="Bot.C.L"/><Side Value="Right"/></RCWallFollower>
  </ControllerList></RCRobot>
</ComponentList></Simulation>)";
  Scene s = scenetest::mustLoad(text);
  Model m;
  Diagnostics d;
  CHECK_FALSE(compileScene(s, &m, d));
  CHECK(scenetest::errorText(d) ==
        "test.xml:12: RCObstacleAvoider 'Bot.A1': parameter 'Sensors' needs at least one Ref to an RCRangeSensor\n"
        "test.xml:15: RCObstacleAvoider 'Bot.A2': parameter 'Sensors' must refer to components implementing "
        "RCRangeSensor, but RCLaserScanner 'Bot.C.L' does not\n"
        "test.xml:17: RCWallFollower 'Bot.F': parameter 'Scanner' must refer to a component implementing "
        "RCLaserScanner, but RCRangeSensor 'Bot.C.R' does not\n");
}
