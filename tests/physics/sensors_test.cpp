// Proximity sensors (lib/physics/sensors.cpp): a sensor geom reports touching another body and
// never pushes it (the trajectory is bit-identical with and without the sensor), ignores its own
// body and the bodies joined to it, and switches on when a moving body brings it to a wall at the
// time kinematics predicts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "physics/model_builder.h"
#include "simbob/physics.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr double kDt = 0.001;

Mat3 boxInertia(double mass, double side) {
  const double i = mass * side * side / 6;
  return {i, 0, 0, 0, i, 0, 0, 0, i};
}

GeomDef box(int body, Vec3 p, Vec3 size, bool sensor = false) {
  GeomDef g;
  g.shape = GeomShape::Box;
  g.body = body;
  g.offset.p = p;
  g.size = size;
  g.sensor = sensor;
  return g;
}

/// Adds a sensor made of one geom; returns its index.
int addSensor(Model& m, GeomDef g) {
  m.geoms.push_back(g);
  SensorDef s;
  s.key = "s" + std::to_string(m.sensors.size());
  s.body = g.body;
  s.geoms = {static_cast<int>(m.geoms.size()) - 1};
  m.sensors.push_back(s);
  return static_cast<int>(m.sensors.size()) - 1;
}

// A 0.2 m box dropped from 5 cm onto the ground plane y = 0: it falls, lands and settles.
Model droppedBox() {
  Model m = baseModel(kDt);
  GeomDef ground;
  ground.shape = GeomShape::Plane;
  ground.plane = {0, 1, 0, 0};
  m.geoms.push_back(ground);
  const int b = addBody(m, {0, 0.15, 0}, 1.0, boxInertia(1.0, 0.2), {0.9990482215818578, 0.0436193873653360, 0, 0});
  m.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  return m;
}

/// Every body's pose after each of `steps` steps, and each step's sensor 0 reading (if any).
std::vector<double> run(const Model& m, int steps, std::vector<bool>* touching = nullptr) {
  auto w = World::create(m, 0);
  REQUIRE(w);
  std::vector<double> out;
  for (int k = 0; k < steps; ++k) {
    w->step(kDt);
    for (int i = 0; i < w->bodyCount(); ++i) {
      const BodyState s = w->body(i);
      out.insert(out.end(), s.pose.p.begin(), s.pose.p.end());
      out.insert(out.end(), s.pose.q.begin(), s.pose.q.end());
    }
    if (touching) touching->push_back(w->touching(0));
  }
  return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("sensors: a sensor overlapping a falling box reports it and pushes nothing", "[physics][sensors]") {
  const Model plain = droppedBox();
  const std::vector<double> reference = run(plain, 1000);
  // The box lands and rests on the ground (centre 0.1 m up), tilted 5 degrees at the start.
  REQUIRE(reference[reference.size() - 6] == Approx(0.1).margin(1e-3));

  SECTION("a static sensor box around the box") {
    Model m = plain;
    const int s = addSensor(m, box(-1, {0, 0.3, 0}, {0.5, 0.4, 0.5}, true));  // y from 0.1 to 0.5
    std::vector<bool> touching;
    const std::vector<double> traj = run(m, 1000, &touching);
    CHECK(sameBits(traj, reference));
    CHECK(s == 0);
    CHECK(std::count(touching.begin(), touching.end(), true) == 1000);
  }
  SECTION("a sensor on a second box beside it, reaching into it") {
    Model m = plain;
    const int b2 = addBody(m, {0.5, 0.1, 0}, 1.0, boxInertia(1.0, 0.2));
    m.geoms.push_back(box(b2, {0, 0, 0}, {0.2, 0.2, 0.2}));
    Model with = m;
    addSensor(with, box(b2, {-0.3, 0.05, 0}, {0.3, 0.1, 0.1}, true));  // x from 0.05 to 0.35: into box 1
    std::vector<bool> touching;
    CHECK(sameBits(run(with, 1000, &touching), run(m, 1000)));
    CHECK(std::count(touching.begin(), touching.end(), true) == 1000);
  }
}

TEST_CASE("sensors: its own body and bodies joined to it are not 'another body'", "[physics][sensors]") {
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  const int a = addBody(m, {0, 0, 0}, 1.0, boxInertia(1.0, 0.2));
  m.geoms.push_back(box(a, {0, 0, 0}, {0.2, 0.2, 0.2}));
  const int b = addBody(m, {0.3, 0, 0}, 1.0, boxInertia(1.0, 0.2));
  m.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  addSensor(m, box(a, {0.1, 0, 0}, {0.4, 0.1, 0.1}, true));  // x from -0.1 to 0.3: into both boxes
  std::vector<bool> touching;
  SECTION("unjoined: box b is another body") {
    run(m, 1, &touching);
    CHECK(touching[0]);
  }
  SECTION("joined by a hinge: nothing else is touched") {
    addJoint(m, JointKind::Hinge, a, b, {0.15, 0, 0}, {0, 0, 1});
    run(m, 1, &touching);
    CHECK_FALSE(touching[0]);
  }
}

TEST_CASE("sensors: a sensor carried towards a wall switches on when it reaches it", "[physics][sensors]") {
  // No gravity. A 0.2 m box moves at v = 1 m/s along +X carrying a sensor whose front face is at
  // x = 0.25 m; the wall's face is at x = 0.9005 m. The sensor meets it at t* = 0.6505 s: it must
  // read false at every step before t* and true from the first step at or after it (0.651 s).
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  const int b = addBody(m, {0, 0, 0}, 1.0, boxInertia(1.0, 0.2));
  m.bodies[b].lin_vel = {1, 0, 0};
  m.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  m.geoms.push_back(box(-1, {1.0005, 0, 0}, {0.2, 1, 1}));  // the wall: x from 0.9005 to 1.1005
  addSensor(m, box(b, {0.2, 0, 0}, {0.1, 0.1, 0.1}, true));
  auto w = World::create(m, 0);
  REQUIRE(w);
  CHECK_FALSE(w->touching(0));  // read at creation: t = 0
  const double t_star = 0.6505;
  int first = -1;
  for (int k = 1; k <= 700 && first < 0; ++k) {
    w->step(kDt);
    if (w->touching(0)) first = k;
  }
  REQUIRE(first > 0);
  const double t = first * kDt;
  CHECK(t >= t_star);
  CHECK(t < t_star + kDt);
  // The sensor pushed nothing: the box still moves at 1 m/s and its own face (x = 0.1 + t) is
  // short of the wall.
  CHECK(w->body(0).lin_vel[0] == 1.0);
  CHECK(w->body(0).pose.p[0] + 0.1 < 0.9005);
}

TEST_CASE("sensors: an encoder on a wheel turned 10 full turns reads 20 pi and 10 Resolution ticks",
          "[physics][sensors]") {
  // A wheel on a hinge about Z turning freely: ODE turns it by 2 atan(om h / 2) per step, chosen
  // here as exactly 1/1000 turn, so 10,000 steps are 10 turns.
  const double om = (2 / kDt) * std::tan(3.14159265358979323846 / 1000);
  const double res = 500;  // half a tick per step
  for (double sense : {1.0, -1.0}) {
    Model m = baseModel(kDt);
    m.settings.gravity = {0, 0, 0};
    addBody(m, {0, 0, 0}, 1.0, boxInertia(1.0, 0.2));
    m.bodies[0].ang_vel = {0, 0, sense * om};
    addJoint(m, JointKind::Hinge, -1, 0, {0, 0, 0}, {0, 0, 1});
    SensorDef e;
    e.key = "odo";
    e.kind = SensorKind::Encoder;
    e.body = 0;
    e.joint = 0;
    e.resolution = res;
    m.sensors.push_back(e);
    auto w = World::create(m, 0);
    CHECK(w->sensorQuantities(0) == std::vector<std::string>{"ticks"});
    CHECK(w->sensorReading(0).at(0) == 0);
    for (int k = 0; k < 10000; ++k) w->step(kDt);
    INFO("sense " << sense);
    CHECK(std::fabs(w->joint(0).position - sense * 20 * 3.14159265358979323846) < 1e-9);
    w->step(kDt);  // 10.001 turns: 5000.5 ticks, floored
    CHECK(w->sensorReading(0).at(0) == (sense > 0 ? 10 * res : -10 * res - 1));
  }
}
