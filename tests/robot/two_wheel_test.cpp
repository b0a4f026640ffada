// lib/robot end to end: scenes/two_wheel_robot.xml, whose schedule drives the two-wheel
// controller forward at v = 0.2 m/s (0-2 s), turns it at w = 0.5 rad/s (2-4 s), then stops.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "scene/scene_helpers.h"
#include "simbob/robot.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"

using namespace simbob;

namespace {

struct Track {
  std::vector<double> t, x, z, yaw;  // chassis (body 0) position and heading about +Y
  std::vector<double> raw;
};

Track runRobot(const Model& m) {
  Track tr;
  SimulationOptions o;
  o.duration = 5;
  Diagnostics d;
  std::unique_ptr<Simulation> sim = Simulation::fromModel(m, o, d);
  REQUIRE(sim);
  sim->sampleTrajectory(nullptr, 0.5, [&](double t, const double* p) {
    tr.t.push_back(t);
    tr.x.push_back(p[0]);
    tr.z.push_back(p[2]);
    // Heading of the chassis's +X axis, counter-clockwise seen from above (about +Y).
    const double w = p[3], qx = p[4], qy = p[5], qz = p[6];
    const double fx = 1 - 2 * (qy * qy + qz * qz), fz = 2 * (qx * qz - w * qy);
    tr.yaw.push_back(std::atan2(-fz, fx));
    tr.raw.insert(tr.raw.end(), p, p + kPoseSize * m.bodies.size());
  });
  RunResult r = sim->runToEnd();
  REQUIRE(r.status == RunStatus::Completed);
  return tr;
}

}  // namespace

TEST_CASE("robot: a scheduled two-wheel robot drives v t forward and turns w t", "[robot]") {
  Scene s;
  Diagnostics d;
  REQUIRE(loadScene(std::string(SIMBOB_SOURCE_DIR) + "/scenes/two_wheel_robot.xml", testRegistry(), &s, d));
  Model m;
  REQUIRE(compileScene(s, &m, d));
  REQUIRE(m.bodies[0].key == "Bot.Cart.Chassis");
  const Track tr = runRobot(m);
  REQUIRE(tr.t.size() == 11);  // 0, 0.5, ..., 5
  // Forward, once up to speed (the wheels start at rest): x(2) - x(1) = v * 1 s, straight ahead.
  CHECK(tr.x[4] - tr.x[2] == Approx(0.2).margin(1e-3));
  CHECK(std::fabs(tr.z[4]) < 1e-6);
  CHECK(std::fabs(tr.yaw[4]) < 1e-6);
  // Turning on the spot from 2 s: heading gained over [3 s, 4 s] is w * 1 s = 0.5 rad to the
  // left (positive). The round tyres touch the ground at WheelDistance / 2 from the centre, as
  // the kinematics assume, and roll without slipping (the velocity motors reach their targets
  // within the first second): measured 0.4999997 rad. (Flat cylinder tyres roll on their outer
  // rims, an effective track of 0.42 m: 0.38 / 0.42 of w, 9.5 % slow.) Tolerance 1e-4 rad.
  CHECK(tr.yaw[8] - tr.yaw[6] == Approx(0.5).margin(1e-4));
  // Stopped after 4 s: nothing moves between 4.5 s and 5 s.
  CHECK(tr.x[10] == Approx(tr.x[9]).margin(1e-6));
  CHECK(tr.yaw[10] == Approx(tr.yaw[9]).margin(1e-6));
  // Reruns are byte-identical (controllers are fresh parties each run).
  const Track again = runRobot(m);
  CHECK(again.raw == tr.raw);
}
