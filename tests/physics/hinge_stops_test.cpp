// Hinge stops carried by simbob's angular motor (lib/physics/joints.cpp, setHingeStops; issue 42):
// against statics and ODE's limit row. An arm resting on its stop is held by m g l; a velocity
// drive pushing into a stop with MaxPower F is held by F; a joint started beyond its stop is
// pushed out at ERP of its error per step (docs/scene-format.md, "Actuators"). The differential
// test against ODE's own hinge stops is tests/physics_ode/hinge_stops_ode_test.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include "physics/model_builder.h"
#include "simbob/physics.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr double kDt = 0.001;
constexpr double kG = 9.81;

// An arm of mass 1 kg whose centre of mass is 0.25 m along +X from a hinge about +Z at the
// origin: its inertia about the hinge is I_c + m l^2 = 0.02 + 0.0625 kg m^2. The parent is the
// static world (ODE attaches the hinge reversed) or a heavy base fixed to it (not reversed).
constexpr double kMass = 1.0, kArm = 0.25, kIc = 0.02;

Model arm(bool world_parent) {
  Model m = baseModel(kDt);
  int parent = -1;
  if (!world_parent) {
    parent = addBody(m, {0, 0, 0}, 1e6, {1e6, 0, 0, 0, 1e6, 0, 0, 0, 1e6});
    addJoint(m, JointKind::Fixed, -1, parent, {0, 0, 0}, {0, 0, 1});
  }
  const int child = addBody(m, {kArm, 0, 0}, kMass, {kIc, 0, 0, 0, kIc, 0, 0, 0, kIc});
  addJoint(m, JointKind::Hinge, parent, child, {0, 0, 0}, {0, 0, 1});
  return m;
}

int hingeOf(const Model& m) { return static_cast<int>(m.joints.size()) - 1; }

/// Steps n times and returns the mean of stopTorque(joint) over them.
double meanStopTorque(World& w, int joint, int n) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    w.step(kDt);
    sum += w.stopTorque(joint);
  }
  return sum / n;
}

}  // namespace

TEST_CASE("hinge stops: an arm resting on its stop is held by the static torque m g l", "[physics][stops]") {
  for (bool world_parent : {true, false}) {
    CAPTURE(world_parent);
    Model m = arm(world_parent);
    m.joints[static_cast<size_t>(hingeOf(m))].lo_stop = 0;  // gravity turns the arm negatively onto it
    auto w = World::create(m, 0);
    REQUIRE(w);
    const int j = hingeOf(m);
    for (int i = 0; i < 1000; ++i) w->step(kDt);
    const double before = w->joint(j).velocity;
    const double mean = meanStopTorque(*w, j, 200);
    const double after = w->joint(j).velocity;
    // Over 0.2 s the stop's mean torque balances gravity's m g l up to the change of the arm's
    // angular momentum, I_h |dw| / 0.2 s; 1e-3 of m g l (2.5e-3 N m) leaves room for dw up to
    // 6e-3 rad/s, and the arm must in fact rest far closer (checked below).
    const double mgl = kMass * kG * kArm;
    CHECK(mean == Approx(mgl).epsilon(1e-3));
    CHECK(std::fabs(after - before) < 1e-3);
    CHECK(std::fabs(after) < 1e-3);
    // On the stop: ERP pulls any penetration out by a fifth per step; 1 mrad is far more.
    CHECK(std::fabs(w->joint(j).position) < 1e-3);
  }
}

TEST_CASE("hinge stops: a velocity drive pushing into a stop with MaxPower F is held by F", "[physics][stops]") {
  // No gravity; the drive asks for 2 rad/s into the stop, so its motor stays at its force limit
  // F = 3 N m while the stop holds the arm: the stop's torque is -F, in the drive's opposite sense.
  for (bool world_parent : {true, false}) {
    for (double sense : {-1.0, 1.0}) {
      CAPTURE(world_parent, sense);
      Model m = arm(world_parent);
      m.settings.gravity = {0, 0, 0};
      const int j = hingeOf(m);
      ActuatorDef a;
      a.key = "a";
      a.kind = ActuatorDef::VelDrive;
      a.joint = j;
      a.max_power = 3.0;
      a.max_velocity = 2.0;
      a.min_pos = -0.4;
      a.max_pos = 0.3;
      m.actuators.push_back(a);
      auto w = World::create(m, 0);
      REQUIRE(w);
      w->setCommand(0, 2.0 * sense);
      for (int i = 0; i < 1000; ++i) w->step(kDt);  // at 2 rad/s the stop is reached within 0.2 s
      const double mean = meanStopTorque(*w, j, 200);
      // The same bound as for the resting arm: the arm does not turn, so the torques balance to
      // I_h |dw| / 0.2 s; 1e-3 of F.
      CHECK(mean == Approx(-3.0 * sense).epsilon(1e-3));
      CHECK(std::fabs(w->joint(j).velocity) < 1e-3);
      CHECK(w->joint(j).position == Approx(sense < 0 ? -0.4 : 0.3).margin(1e-3));
      // Every step, not only on average, to QuickStep's residual: its 20 iterations share the
      // step's impulse among the hinge's rows, the stop's and (with a base) the fixed joint's.
      CHECK(w->stopTorque(j) == Approx(-3.0 * sense).epsilon(1e-2));
    }
  }
}

TEST_CASE("hinge stops: a joint started beyond its stop leaves it at ERP of its error per step", "[physics][stops]") {
  // A flywheel (centre of mass on the hinge, so the stop's row is the only one about the axis),
  // no gravity, its lower stop 0.01 rad above the start pose. The stop's row asks for the
  // velocity ERP * error / dt out of the stop (ODE's limit row, with the world's ERP); nothing
  // brakes the joint afterwards, so it keeps that velocity and, after n steps, has moved by
  // n * ERP * error: out of the stop after 1 / ERP steps and beyond it at the same speed.
  const double err = 0.01;
  for (bool quickstep : {true, false}) {
    for (double erp : {0.2, 0.5}) {
      for (bool world_parent : {true, false}) {
        CAPTURE(quickstep, erp, world_parent);
        Model m = baseModel(kDt);
        m.settings.gravity = {0, 0, 0};
        m.settings.erp = erp;
        m.settings.quickstep = quickstep;
        int parent = -1;
        if (!world_parent) {
          parent = addBody(m, {0, 0, 0}, 1e6, {1e6, 0, 0, 0, 1e6, 0, 0, 0, 1e6});
          addJoint(m, JointKind::Fixed, -1, parent, {0, 0, 0}, {0, 0, 1});
        }
        const int child = addBody(m, {0, 0, 0}, 1.0, {kIc, 0, 0, 0, kIc, 0, 0, 0, kIc});
        const int j = addJoint(m, JointKind::Hinge, parent, child, {0, 0, 0}, {0, 0, 1});
        m.joints[static_cast<size_t>(j)].lo_stop = err;
        auto w = World::create(m, 0);
        REQUIRE(w);
        w->step(kDt);
        // One row about the axis, solved exactly by either solver, up to rounding and the
        // stop's CFM (1e-10: a relative 1e-10 / (dt / I) = 2e-9 of the impulse).
        const double v = erp * err / kDt;
        CHECK(w->joint(j).velocity == Approx(v).epsilon(1e-8));
        CHECK(w->stopTorque(j) == Approx(kIc * v / kDt).epsilon(1e-8));  // the impulse I v over one step
        const int n = 10;
        for (int i = 1; i < n; ++i) w->step(kDt);
        CHECK(w->joint(j).velocity == Approx(v).epsilon(1e-8));
        // n * ERP * error, as ODE turns a body: its rotation (q + dt/2 w q, normalised) turns
        // 2 atan(w dt / 2) a step, short of w dt by a relative (w dt)^2 / 12 (3e-7 at 2 rad/s).
        CHECK(w->joint(j).position == Approx(n * 2 * std::atan(v * kDt / 2)).epsilon(1e-8));
        CHECK(w->joint(j).position == Approx(n * erp * err).epsilon(v * v * kDt * kDt / 12 + 1e-8));
        CHECK(w->stopTorque(j) == 0);  // off the stop: no torque
      }
    }
  }
}
