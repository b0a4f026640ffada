// Actuators (lib/physics/actuators.cpp) against closed-form answers: a free flywheel of known
// inertia under a drive (angular acceleration = torque / I), a velocity drive and a servo on it,
// a slider drive, stops, and the sign convention with the world or a body as the parent.
#include <catch2/catch.hpp>

#include <cmath>

#include "physics/model_builder.h"
#include "simbob/physics.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr double kDt = 0.001;
constexpr double kI = 0.02;  // kg m^2 about every axis of the flywheel

ActuatorDef actuator(ActuatorDef::Kind kind, int joint, double power, double vmax) {
  ActuatorDef a;
  a.key = "a";
  a.kind = kind;
  a.joint = joint;
  a.max_power = power;
  a.max_velocity = vmax;
  return a;
}

// A flywheel on a hinge about +Z at the origin, no gravity; the parent is the static world
// (`world_parent`) or a heavy body that is itself hinged to the world (so ODE sees two bodies).
Model flywheel(bool world_parent = true) {
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  if (world_parent) {
    addBody(m, {0, 0, 0}, 1.0, {kI, 0, 0, 0, kI, 0, 0, 0, kI});
    addJoint(m, JointKind::Hinge, -1, 0, {0, 0, 0}, {0, 0, 1});
  } else {
    addBody(m, {0, 0, 0}, 1e6, {1e6, 0, 0, 0, 1e6, 0, 0, 0, 1e6});  // a base too heavy to turn noticeably
    addBody(m, {0, 0, 0}, 1.0, {kI, 0, 0, 0, kI, 0, 0, 0, kI});
    addJoint(m, JointKind::Fixed, -1, 0, {0, 0, 0}, {0, 0, 1});
    addJoint(m, JointKind::Hinge, 0, 1, {0, 0, 0}, {0, 0, 1});
  }
  return m;
}

// Angular acceleration of the flywheel's joint over one step from rest at velocity v0, spun up
// with an initial angular velocity about +Z.
double accelAt(double v0, double u, double stall, double vmax, double power) {
  Model m = flywheel();
  m.bodies[0].ang_vel = {0, 0, v0};
  ActuatorDef a = actuator(ActuatorDef::Drive, 0, power, vmax);
  a.stall = stall;
  m.actuators.push_back(a);
  auto w = World::create(m, 1);
  REQUIRE(w);
  w->setCommand(0, u);
  const double before = w->joint(0).velocity;
  w->step(kDt);
  return (w->joint(0).velocity - before) / kDt;
}

}  // namespace

TEST_CASE("actuators: drive torque follows the stall curve of guide 6.11.1", "[physics][actuators]") {
  // MaxPower 2 N m, MaxVelocity 10 rad/s, Stall 0.6: full torque up to 6 rad/s, none at 10.
  const double P = 2, vmax = 10, stall = 0.6;
  const double full = P / kI;  // 100 rad/s^2
  // Semi-implicit Euler: the velocity change over one step is exactly torque * h / I.
  CHECK(accelAt(0, 1, stall, vmax, P) == Approx(full).epsilon(1e-9));
  CHECK(accelAt(stall * vmax, 1, stall, vmax, P) == Approx(full).epsilon(1e-9));
  CHECK(accelAt(8, 1, stall, vmax, P) == Approx(full * 0.5).epsilon(1e-9));  // midway: factor 1/2
  CHECK(std::fabs(accelAt(vmax, 1, stall, vmax, P)) < 1e-9);
  CHECK(std::fabs(accelAt(12, 1, stall, vmax, P)) < 1e-9);
  // Half the voltage, half the torque; negative voltage pushes the other way.
  CHECK(accelAt(0, 0.5, stall, vmax, P) == Approx(full * 0.5).epsilon(1e-9));
  CHECK(accelAt(0, -1, stall, vmax, P) == Approx(-full).epsilon(1e-9));
  // Moving backwards at -8 rad/s: pushing backwards fades, braking (pushing forwards) does not.
  CHECK(accelAt(-8, -1, stall, vmax, P) == Approx(-full * 0.5).epsilon(1e-9));
  CHECK(accelAt(-12, 1, stall, vmax, P) == Approx(full).epsilon(1e-9));
  // Voltage beyond [-1, 1] is clamped.
  CHECK(accelAt(0, 5, stall, vmax, P) == Approx(full).epsilon(1e-9));
}

TEST_CASE("actuators: a driven flywheel levels off at MaxVelocity", "[physics][actuators]") {
  Model m = flywheel();
  ActuatorDef a = actuator(ActuatorDef::Drive, 0, 2, 10);
  a.stall = 0.6;
  m.actuators.push_back(a);
  auto w = World::create(m, 1);
  w->setCommand(0, 1);
  double vmaxSeen = 0;
  for (int i = 0; i < 3000; ++i) {
    w->step(kDt);
    vmaxSeen = std::max(vmaxSeen, w->joint(0).velocity);
    CHECK(std::fabs(w->driveEffort(0)) <= 2 + 1e-12);
  }
  // Approaches 10 rad/s from below (exponentially once past 6 rad/s) and never passes it.
  CHECK(vmaxSeen <= 10 * (1 + 1e-12));
  CHECK(w->joint(0).velocity > 9.99);
}

TEST_CASE("actuators: a positive command turns the joint positively, whichever body is the parent",
          "[physics][actuators]") {
  for (bool world_parent : {true, false}) {
    CAPTURE(world_parent);
    for (auto kind : {ActuatorDef::Drive, ActuatorDef::VelDrive, ActuatorDef::Servo}) {
      CAPTURE(int(kind));
      Model m = flywheel(world_parent);
      const int hinge = world_parent ? 0 : 1;
      m.actuators.push_back(actuator(kind, hinge, 1, 2));
      auto w = World::create(m, 1);
      w->setCommand(0, kind == ActuatorDef::Servo ? 0.5 : 1.0);
      for (int i = 0; i < 100; ++i) w->step(kDt);
      CHECK(w->joint(hinge).velocity > 0.1);
      CHECK(w->joint(hinge).position > 0);
    }
  }
}

TEST_CASE("actuators: a velocity drive reaches and holds its target with at most MaxPower", "[physics][actuators]") {
  // Target 5 rad/s, MaxPower 0.5 N m: the torque-limited ramp takes I * 5 / 0.5 = 0.2 s.
  Model m = flywheel();
  m.actuators.push_back(actuator(ActuatorDef::VelDrive, 0, 0.5, 8));
  auto w = World::create(m, 1);
  w->setCommand(0, 5);
  double prev = 0;
  for (int i = 1; i <= 1000; ++i) {
    w->step(kDt);
    const double v = w->joint(0).velocity;
    // Torque = I dv/dt never above MaxPower (1e-9 relative: the solver's rounding).
    CHECK(kI * std::fabs(v - prev) / kDt <= 0.5 * (1 + 1e-9));
    if (i == 100) CHECK(v == Approx(2.5).epsilon(1e-6));  // still on the ramp: 0.5 / I * 0.1 s
    if (i >= 250) CHECK(v == Approx(5).epsilon(1e-6));    // reached and held
    prev = v;
  }
  // A target beyond MaxVelocity is clamped to it.
  w->setCommand(0, 100);
  for (int i = 0; i < 1000; ++i) w->step(kDt);
  CHECK(w->joint(0).velocity == Approx(8).epsilon(1e-6));
}

TEST_CASE("actuators: a servo reaches its target within its limits, never faster than MaxVelocity",
          "[physics][actuators]") {
  Model m = flywheel();
  ActuatorDef a = actuator(ActuatorDef::Servo, 0, 5, 2);
  a.min_pos = -0.5;
  a.max_pos = 1.0;
  a.smooth = 0.05;
  m.actuators.push_back(a);
  auto w = World::create(m, 1);
  w->setCommand(0, 3.0);  // beyond MaxPos: clamped to 1 rad
  double fastest = 0;
  for (int i = 0; i < 2000; ++i) {
    w->step(kDt);
    fastest = std::max(fastest, std::fabs(w->joint(0).velocity));
    CHECK(w->joint(0).position <= 1.0 + 1e-9);
  }
  CHECK(fastest <= 2 * (1 + 1e-9));
  CHECK(fastest == Approx(2).epsilon(1e-6));  // it does run at MaxVelocity on the way
  CHECK(w->joint(0).position == Approx(1.0).margin(1e-6));
  w->setCommand(0, -0.25);
  for (int i = 0; i < 2000; ++i) w->step(kDt);
  CHECK(w->joint(0).position == Approx(-0.25).margin(1e-6));
}

TEST_CASE("actuators: MinPos and MaxPos hold a driven joint (hinge and slider)", "[physics][actuators]") {
  SECTION("hinge") {
    for (bool world_parent : {true, false}) {
      CAPTURE(world_parent);
      Model m = flywheel(world_parent);
      const int hinge = world_parent ? 0 : 1;
      ActuatorDef a = actuator(ActuatorDef::Drive, hinge, 1, 100);
      a.min_pos = -0.3;
      a.max_pos = 0.4;
      m.actuators.push_back(a);
      auto w = World::create(m, 1);
      w->setCommand(0, 1);
      for (int i = 0; i < 2000; ++i) w->step(kDt);
      CHECK(w->joint(hinge).position == Approx(0.4).margin(0.01));
      w->setCommand(0, -1);
      for (int i = 0; i < 2000; ++i) w->step(kDt);
      CHECK(w->joint(hinge).position == Approx(-0.3).margin(0.01));
    }
  }
  SECTION("slider") {
    // A 2 kg block on a slider along +X: force F gives acceleration F / m, the stop holds it.
    Model m = baseModel(kDt);
    m.settings.gravity = {0, 0, 0};
    addBody(m, {0, 0, 0}, 2.0, sphereInertia(2.0, 0.1));
    addJoint(m, JointKind::Slider, -1, 0, {0, 0, 0}, {1, 0, 0});
    ActuatorDef a = actuator(ActuatorDef::Drive, 0, 4, 100);
    a.max_pos = 0.5;
    m.actuators.push_back(a);
    auto w = World::create(m, 1);
    w->setCommand(0, 1);
    w->step(kDt);
    CHECK(w->joint(0).velocity == Approx(4.0 / 2.0 * kDt).epsilon(1e-9));
    CHECK(w->body(0).lin_vel[0] > 0);  // positive along the axis
    for (int i = 0; i < 2000; ++i) w->step(kDt);
    CHECK(w->joint(0).position == Approx(0.5).margin(0.01));
  }
  SECTION("slider between two bodies, every kind") {
    for (auto kind : {ActuatorDef::Drive, ActuatorDef::VelDrive, ActuatorDef::Servo}) {
      CAPTURE(int(kind));
      Model m = baseModel(kDt);
      m.settings.gravity = {0, 0, 0};
      addBody(m, {0, 0, 0}, 1e6, sphereInertia(1e6, 0.1));
      addBody(m, {0, 0, 0}, 2.0, sphereInertia(2.0, 0.1));
      addJoint(m, JointKind::Fixed, -1, 0, {0, 0, 0}, {1, 0, 0});
      addJoint(m, JointKind::Slider, 0, 1, {0, 0, 0}, {1, 0, 0});
      ActuatorDef a = actuator(kind, 1, 4, 1);
      a.min_pos = -0.2;
      a.max_pos = 0.3;
      a.smooth = 0.05;  // the servo's approach: error falls by e in 0.05 s
      m.actuators.push_back(a);
      auto w = World::create(m, 1);
      w->setCommand(0, kind == ActuatorDef::Servo ? 0.3 : 1.0);
      for (int i = 0; i < 100; ++i) w->step(kDt);
      CHECK(w->joint(1).velocity > 0);
      for (int i = 0; i < 2000; ++i) w->step(kDt);
      CHECK(w->joint(1).position == Approx(0.3).margin(0.01));
      w->setCommand(0, kind == ActuatorDef::Servo ? -0.2 : -1.0);
      for (int i = 0; i < 2000; ++i) w->step(kDt);
      CHECK(w->joint(1).position == Approx(-0.2).margin(0.01));
    }
  }
}

TEST_CASE("actuators: a velocity drive without a command applies nothing", "[physics][actuators]") {
  Model m = flywheel();
  m.bodies[0].ang_vel = {0, 0, 3};
  m.actuators.push_back(actuator(ActuatorDef::VelDrive, 0, 1, 10));
  auto w = World::create(m, 1);
  for (int i = 0; i < 100; ++i) w->step(kDt);
  CHECK(w->joint(0).velocity == Approx(3).epsilon(1e-12));
}
