// IMUs (lib/physics/imu.cpp): at rest on the ground the accelerometer reads +g upwards in the
// sensor frame, in free fall 0; on a turntable at omega the gyro reads omega and the
// accelerometer omega^2 r towards the axis; bias and noise as configured.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "physics/model_builder.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr double kDt = 0.001;
constexpr double kG = 9.81;

GeomDef box(int body, Vec3 p, Vec3 size) {
  GeomDef g;
  g.shape = GeomShape::Box;
  g.body = body;
  g.offset.p = p;
  g.size = size;
  return g;
}

int addImu(Model& m, int body, Transform pose = {}) {
  SensorDef s;
  s.key = "imu" + std::to_string(m.sensors.size());
  s.kind = SensorKind::Imu;
  s.body = body;
  s.pose = pose;
  m.sensors.push_back(s);
  return static_cast<int>(m.sensors.size()) - 1;
}

}  // namespace

/// A 0.2 m box resting on the ground plane y = 0 with an upright IMU on its top face, and a second
/// one turned on its side (90 degrees about X: +g lies along that sensor's -Z).
Model restingBoxes(bool quickstep) {
  Model m = baseModel(kDt);
  m.settings.quickstep = quickstep;
  GeomDef ground;
  ground.shape = GeomShape::Plane;
  ground.plane = {0, 1, 0, 0};
  m.geoms.push_back(ground);
  const int b = addBody(m, {0, 0.1, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  addImu(m, b, {{0.05, 0.1, 0}, {1, 0, 0, 0}});
  const int c = addBody(m, {1, 0.1, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.geoms.push_back(box(c, {0, 0, 0}, {0.2, 0.2, 0.2}));
  addImu(m, c, {{0, 0, 0}, quatAxisAngle({1, 0, 0}, kPi / 2)});
  return m;
}

TEST_CASE("imu: at rest on the ground it reads +g upwards in its frame", "[physics][imu]") {
  SECTION("exact solver: every step") {
    // dWorldStep solves the resting contact (nearly) exactly: what is left is the contact's ERP
    // correction of CFM-sized penetrations, velocity changes of ~1e-9 m/s per step (1e-6 m/s^2).
    auto w = World::create(restingBoxes(false), 0);
    CHECK(w->sensorQuantities(0) == std::vector<std::string>{"ax", "ay", "az", "gx", "gy", "gz"});
    for (int k = 0; k < 1000; ++k) {
      w->step(kDt);
      const std::vector<double> r = w->sensorReading(0), s = w->sensorReading(1);
      const double up[6] = {0, kG, 0, 0, 0, 0}, side[6] = {0, 0, -kG, 0, 0, 0};
      for (size_t i = 0; i < 6; ++i) {
        CHECK(std::fabs(r[i] - up[i]) < 1e-5);
        CHECK(std::fabs(s[i] - side[i]) < 1e-5);
      }
    }
  }
  SECTION("QuickStep: on average") {
    // QuickStep's 20 iterations leave the resting box chattering (single steps read up to several
    // m/s^2 off); the IMU reads that faithfully. Its mean over 2 s telescopes to the velocity
    // change over 2 s (of order 1e-5 m/s for a resting box) divided by 2 s, plus g.
    auto w = World::create(restingBoxes(true), 0);
    double sum[2][3] = {{0}};
    const int n = 2000;
    for (int k = 0; k < n; ++k) {
      w->step(kDt);
      for (int j = 0; j < 2; ++j)
        for (size_t i = 0; i < 3; ++i) sum[j][i] += w->sensorReading(j)[i];
    }
    CHECK(std::fabs(sum[0][0] / n) < 1e-3);
    CHECK(std::fabs(sum[0][1] / n - kG) < 1e-3);
    CHECK(std::fabs(sum[0][2] / n) < 1e-3);
    CHECK(std::fabs(sum[1][0] / n) < 1e-3);
    CHECK(std::fabs(sum[1][1] / n) < 1e-3);
    CHECK(std::fabs(sum[1][2] / n + kG) < 1e-3);
  }
}

TEST_CASE("imu: in free fall it reads 0", "[physics][imu]") {
  Model m = baseModel(kDt);
  const int b = addBody(m, {0, 10, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[0].lin_vel = {1, 2, 0};
  addImu(m, b, {{0, 0, 0}, quatAxisAngle({0, 0, 1}, 0.4)});
  auto w = World::create(m, 0);
  // At creation no step has been taken: the acceleration counts as 0, the reading is -gravity.
  CHECK(std::fabs(w->sensorReading(0)[0] - kG * std::sin(0.4)) < 1e-12);
  CHECK(std::fabs(w->sensorReading(0)[1] - kG * std::cos(0.4)) < 1e-12);
  for (int k = 0; k < 100; ++k) {
    w->step(kDt);
    for (double v : w->sensorReading(0)) CHECK(std::fabs(v) < 1e-9);
  }
}

TEST_CASE("imu: on a turntable at omega the gyro reads omega and the accelerometer omega^2 r towards the axis",
          "[physics][imu]") {
  // A body on a hinge about the vertical axis through the origin, spinning freely at omega; the
  // IMU sits at radius r on +X (at the start), upright. Gravity on: the hinge carries the weight.
  // The exact solver (dWorldStep): QuickStep's 20 iterations let the body wobble about the
  // horizontal axes by ~1e-2 rad/s, which the IMU would read faithfully.
  const double omega = 2.0, r = 0.5;
  Model m = baseModel(kDt);
  m.settings.quickstep = false;
  const int b = addBody(m, {r, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[0].ang_vel = {0, omega, 0};
  m.bodies[0].lin_vel = {0, 0, -omega * r};  // omega x (r, 0, 0)
  addJoint(m, JointKind::Hinge, -1, b, {0, 0, 0}, {0, 1, 0});
  addImu(m, b);
  auto w = World::create(m, 0);
  for (int k = 0; k < 2000; ++k) {  // about 0.6 turns
    w->step(kDt);
    if (k % 100 != 99)
      continue;  // after the start transient: ODE's hinge constrains velocities, so the
                 // centripetal pull comes from correcting the radius the step before
                 // (ERP), which settles within tens of steps
    const std::vector<double> s = w->sensorReading(0);
    const double c = omega * omega * r;  // 2 m/s^2
    // The velocity difference over a step, seen from the frame at its end, lags the true
    // acceleration by about omega h = 2e-3 rad (half a step of turning plus the constraint's
    // one-step delay): up to 2e-3 c in the tangential axis, 2e-6 c off the radial one.
    INFO("t = " << (k + 1) * kDt);
    CHECK(std::fabs(s[0] + c) < 1e-4 * c);  // towards the axis: the sensor's -X
    CHECK(std::fabs(s[1] - kG) < 1e-6);
    CHECK(std::fabs(s[2]) < 1.5 * omega * kDt * c);
    CHECK(std::fabs(s[3]) < 1e-9);
    CHECK(std::fabs(s[4] - omega) < 1e-4);  // the ERP corrections cost 2e-5 of omega over the run
    CHECK(std::fabs(s[5]) < 1e-9);
  }
}

TEST_CASE("imu: bias is added in the sensor frame, noise has the configured deviation", "[physics][imu]") {
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  const int b = addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  const int s = addImu(m, b);
  m.sensors[static_cast<size_t>(s)].accel_bias = {0.1, 0.2, 0.3};
  m.sensors[static_cast<size_t>(s)].gyro_bias = {-0.01, 0, 0.02};
  SECTION("bias") {
    auto w = World::create(m, 0);
    w->step(kDt);
    CHECK(w->sensorReading(0) == std::vector<double>{0.1, 0.2, 0.3, -0.01, 0, 0.02});
  }
  SECTION("noise") {
    m.sensors[static_cast<size_t>(s)].noise = 0.05;
    m.sensors[static_cast<size_t>(s)].gyro_noise = 0.002;
    auto w = World::create(m, 5);
    const int n = 10000;
    double sum[6] = {0}, sq[6] = {0};
    for (int k = 0; k < n; ++k) {
      w->step(kDt);
      const std::vector<double>& r = w->sensorReading(0);
      for (size_t i = 0; i < 6; ++i) {
        sum[i] += r[i];
        sq[i] += r[i] * r[i];
      }
    }
    const double bias[6] = {0.1, 0.2, 0.3, -0.01, 0, 0.02};
    for (size_t i = 0; i < 6; ++i) {
      const double sigma = i < 3 ? 0.05 : 0.002;
      const double mean = sum[i] / n;
      const double sd = std::sqrt(sq[i] / n - mean * mean);
      INFO("quantity " << i);
      CHECK(std::fabs(mean - bias[i]) < 4 * sigma / 100);
      CHECK(std::fabs(sd - sigma) < 4 * sigma / 141);
    }
  }
}
