// Range sensors and laser scanners (lib/physics/rays.cpp): analytic distances to walls, MaxRange
// when nothing is hit, its own body and jointed bodies ignored, MinRange and Resolution, noise with
// the configured mean and deviation that repeats exactly, readings held between Periods, and a
// trajectory bit-identical with and without rays.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "physics/model_builder.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr double kDt = 0.001;

GeomDef box(int body, Vec3 p, Vec3 size) {
  GeomDef g;
  g.shape = GeomShape::Box;
  g.body = body;
  g.offset.p = p;
  g.size = size;
  return g;
}

/// Adds a range sensor (Range) or scanner on `body` at `pose`; returns its index.
int addRay(Model& m, SensorKind kind, int body, Transform pose, double max_range = 5.0) {
  SensorDef s;
  s.key = "ray" + std::to_string(m.sensors.size());
  s.kind = kind;
  s.body = body;
  s.pose = pose;
  s.max_range = max_range;
  m.sensors.push_back(s);
  return static_cast<int>(m.sensors.size()) - 1;
}

Transform yaw(double rad, Vec3 p = {0, 0, 0}) {
  Transform t;
  t.p = p;
  t.q = quatAxisAngle({0, 1, 0}, rad);
  return t;
}

/// No gravity; a 0.2 m box body at the origin (the sensor's carrier, its own body).
Model carrier() {
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  const int b = addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  return m;
}

/// A static wall whose face is the plane z = -d (1 m thick, 100 m wide).
void addWall(Model& m, double d) { m.geoms.push_back(box(-1, {0, 0, -d - 0.5}, {100, 100, 1})); }

double reading(const Model& m, int sensor = 0, uint32_t seed = 0) {
  auto w = World::create(m, seed);
  return w->sensorReading(sensor).at(0);
}

}  // namespace

TEST_CASE("rays: a range sensor facing a wall at distance d and angle theta reads d / cos(theta)", "[physics][rays]") {
  for (double d : {0.3, 1.0, 2.5}) {
    for (double theta : {0.0, 0.2, -0.5, 1.0}) {
      Model m = carrier();
      addWall(m, d);
      // The ray leaves the body's centre (inside its own box) along local -Z, turned by theta about Y.
      addRay(m, SensorKind::Range, 0, yaw(theta));
      auto w = World::create(m, 0);
      INFO("d = " << d << ", theta = " << theta);
      CHECK(w->sensorQuantities(0) == std::vector<std::string>{"distance"});
      CHECK(std::fabs(w->sensorReading(0).at(0) - d / std::cos(theta)) < 1e-9);
      w->step(kDt);  // nothing moves: the same after a step
      CHECK(std::fabs(w->sensorReading(0).at(0) - d / std::cos(theta)) < 1e-9);
    }
  }
}

TEST_CASE("rays: nothing hit reads MaxRange", "[physics][rays]") {
  Model m = carrier();
  addWall(m, 3.0);
  SECTION("facing away") {
    addRay(m, SensorKind::Range, 0, yaw(kPi));
    CHECK(reading(m) == 5.0);
  }
  SECTION("the wall beyond MaxRange") {
    addRay(m, SensorKind::Range, 0, yaw(0), 2.0);
    CHECK(reading(m) == 2.0);
  }
}

TEST_CASE("rays: its own body and the bodies joined to it are ignored, other bodies are not", "[physics][rays]") {
  Model m = carrier();
  addWall(m, 2.0);
  // A second box in front of the sensor: its near face at z = -0.5.
  const int b = addBody(m, {0, 0, -0.6}, 1.0, sphereInertia(1.0, 0.1));
  m.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  addRay(m, SensorKind::Range, 0, yaw(0));
  SECTION("unjoined: the box is seen") { CHECK(std::fabs(reading(m) - 0.5) < 1e-9); }
  SECTION("joined by a hinge: the wall is seen") {
    addJoint(m, JointKind::Hinge, 0, b, {0, 0, -0.3}, {1, 0, 0});
    CHECK(std::fabs(reading(m) - 2.0) < 1e-9);
  }
  SECTION("a static sensor skips its own static body and the bodies jointed to it, and sees the rest") {
    // The carrier's box becomes the sensor's static post, around the sensor's origin.
    m.sensors[0].body = -1;
    m.sensors[0].static_body = 0;
    m.geoms[0].body = -1;
    m.geoms[0].static_body = 0;
    CHECK(std::fabs(reading(m) - 0.5) < 1e-9);  // not the post: the box
    addJoint(m, JointKind::Hinge, -1, b, {0, 0, -0.3}, {1, 0, 0});
    m.joints.back().static_body = 0;
    CHECK(std::fabs(reading(m) - 2.0) < 1e-9);  // the box hinged to the post: the static wall behind it
    m.joints.pop_back();
    m.bodies.pop_back();
    m.geoms.pop_back();
    CHECK(std::fabs(reading(m) - 2.0) < 1e-9);  // without the box: the static wall (MaxRange before)
  }
}

TEST_CASE("rays: proximity sensors' volumes are not seen", "[physics][rays]") {
  Model m = carrier();
  addWall(m, 2.0);
  // A proximity sensor's box on a second body, across the ray at z = -1.
  const int b = addBody(m, {0, 0, -1}, 1.0, sphereInertia(1.0, 0.1));
  GeomDef g = box(b, {0, 0, 0}, {0.5, 0.5, 0.5});
  g.sensor = true;
  m.geoms.push_back(g);
  SensorDef p;
  p.key = "bump";
  p.body = b;
  p.geoms = {static_cast<int>(m.geoms.size()) - 1};
  m.sensors.push_back(p);
  addRay(m, SensorKind::Range, 0, yaw(0));
  CHECK(std::fabs(reading(m, 1) - 2.0) < 1e-9);
  m.geoms.back().sensor = false;  // the same box as a plain geom is seen: its face at z = -0.75
  CHECK(std::fabs(reading(m, 1) - 0.75) < 1e-9);
}

TEST_CASE("rays: MinRange and Resolution", "[physics][rays]") {
  Model m = carrier();
  addWall(m, 1.23456);
  addRay(m, SensorKind::Range, 0, yaw(0));
  SECTION("a hit nearer than MinRange reads MinRange") {
    m.sensors[0].min_range = 1.5;
    m.sensors[0].max_range = 3.0;
    CHECK(reading(m) == 1.5);
  }
  SECTION("rounded to a multiple of Resolution") {
    m.sensors[0].resolution = 0.01;
    CHECK(std::fabs(reading(m) - 1.23) < 1e-12);
  }
}

TEST_CASE("rays: noise has the configured mean and deviation over 10,000 readings and repeats exactly",
          "[physics][rays]") {
  Model m = carrier();
  addWall(m, 1.0);
  addRay(m, SensorKind::Range, 0, yaw(0));
  const double sigma = 0.01;
  m.sensors[0].noise = sigma;
  auto series = [&](const Model& model, uint32_t seed) {
    auto w = World::create(model, seed);
    std::vector<double> v;
    for (int k = 0; k < 10000; ++k) {
      w->step(kDt);
      v.push_back(w->sensorReading(0).at(0));
    }
    return v;
  };
  const std::vector<double> a = series(m, 3);
  double sum = 0, sq = 0;
  for (double x : a) sum += x;
  const double mean = sum / a.size();
  for (double x : a) sq += (x - mean) * (x - mean);
  const double sd = std::sqrt(sq / (a.size() - 1));
  // Standard errors: sigma / 100 for the mean, about sigma / 141 for the deviation; 4 of them.
  CHECK(std::fabs(mean - 1.0) < 4 * sigma / 100);
  CHECK(std::fabs(sd - sigma) < 4 * sigma / 141);
  const std::vector<double> b = series(m, 3);
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
  // Another seed, or another sensor added before it, changes nothing but what it should.
  CHECK(series(m, 4) != a);
  Model more = m;
  addRay(more, SensorKind::Range, 0, yaw(0.3));
  std::swap(more.sensors[0], more.sensors[1]);
  auto w = World::create(more, 3);
  for (int k = 0; k < 10; ++k) {
    w->step(kDt);
    CHECK(w->sensorReading(1).at(0) == a[static_cast<size_t>(k)]);
  }
}

TEST_CASE("rays: a scanner in a square room reads the wall distances ray by ray", "[physics][rays]") {
  // Walls' inner faces at x = +-2 and z = +-2 (the room is 4 m square); the scanner at (x0, 0, z0).
  const double L = 2.0, x0 = 0.5, z0 = -0.3;
  for (double heading : {0.0, 0.7}) {
    for (double fov : {360.0, 270.0, 90.0}) {
      Model m = carrier();
      m.bodies[0].pose.p = {x0, 0, z0};
      m.geoms.push_back(box(-1, {L + 0.5, 0, 0}, {1, 10, 10}));
      m.geoms.push_back(box(-1, {-L - 0.5, 0, 0}, {1, 10, 10}));
      m.geoms.push_back(box(-1, {0, 0, L + 0.5}, {10, 10, 1}));
      m.geoms.push_back(box(-1, {0, 0, -L - 0.5}, {10, 10, 1}));
      const int n = 36;
      const int s = addRay(m, SensorKind::Scanner, 0, yaw(heading), 10.0);
      m.sensors[static_cast<size_t>(s)].rays = n;
      m.sensors[static_cast<size_t>(s)].field_of_view = fov;
      auto w = World::create(m, 0);
      const std::vector<double>& r = w->sensorReading(s);
      REQUIRE(r.size() == static_cast<size_t>(n));
      CHECK(w->sensorQuantities(s).front() == "range0");
      CHECK(w->sensorQuantities(s).back() == "range35");
      for (int k = 0; k < n; ++k) {
        // docs/sensors.md: from -FOV/2 (right) to +FOV/2 (left), counterclockwise seen from +Y.
        const double f = fov * kPi / 180;
        const double a = fov >= 360 ? -kPi + k * 2 * kPi / n : -f / 2 + k * f / (n - 1);
        const double dx = -std::sin(a + heading), dz = -std::cos(a + heading);
        double t = 1e300;
        if (dx > 0) t = std::min(t, (L - x0) / dx);
        if (dx < 0) t = std::min(t, (-L - x0) / dx);
        if (dz > 0) t = std::min(t, (L - z0) / dz);
        if (dz < 0) t = std::min(t, (-L - z0) / dz);
        INFO("heading " << heading << ", fov " << fov << ", ray " << k);
        CHECK(std::fabs(r[static_cast<size_t>(k)] - t) < 1e-9);
      }
    }
  }
}

TEST_CASE("rays: a sensor with a Period updates at multiples of it and holds its reading in between",
          "[physics][rays]") {
  // The carrier moves towards the wall (face z = -2) at 1 m/s: the distance is 2 - t.
  Model m = carrier();
  m.bodies[0].lin_vel = {0, 0, -1};
  addWall(m, 2.0);
  addRay(m, SensorKind::Range, 0, yaw(0));
  m.sensors[0].period = 0.01;
  auto w = World::create(m, 0);
  CHECK(std::fabs(w->sensorReading(0).at(0) - 2.0) < 1e-9);
  for (int k = 1; k <= 100; ++k) {
    w->step(kDt);
    const double last = (k / 10) * 0.01;  // the last multiple of the period at or before k dt
    INFO("step " << k);
    CHECK(std::fabs(w->sensorReading(0).at(0) - (2.0 - last)) < 1e-9);
  }
}

TEST_CASE("rays: a reading does not depend on who reads it or how often", "[physics][rays]") {
  Model m = carrier();
  m.bodies[0].lin_vel = {0, 0, -0.5};
  addWall(m, 2.0);
  addRay(m, SensorKind::Range, 0, yaw(0));
  m.sensors[0].noise = 0.01;
  auto often = World::create(m, 9);
  auto once = World::create(m, 9);
  for (int k = 0; k < 500; ++k) {
    often->step(kDt);
    once->step(kDt);
    (void)often->sensorReading(0);
    (void)often->sensorReading(0);
  }
  CHECK(often->sensorReading(0) == once->sensorReading(0));
}

TEST_CASE("rays: the trajectory is bit-identical with and without range sensors and scanners", "[physics][rays]") {
  // Boxes dropped onto the ground, tumbling into each other; every body carries a sensor that sees
  // the ground and the others.
  Model plain = baseModel(kDt);
  GeomDef ground;
  ground.shape = GeomShape::Plane;
  ground.plane = {0, 1, 0, 0};
  plain.geoms.push_back(ground);
  for (int i = 0; i < 6; ++i) {
    const int b = addBody(plain, {0.15 * i, 0.2 + 0.25 * i, 0.05 * (i % 2)}, 1.0, sphereInertia(1.0, 0.1),
                          quatAxisAngle({1, 0, 1}, 0.3 * i));
    plain.geoms.push_back(box(b, {0, 0, 0}, {0.2, 0.2, 0.2}));
  }
  Model with = plain;
  for (int i = 0; i < 6; ++i) {
    const int s = addRay(with, i % 2 ? SensorKind::Scanner : SensorKind::Range, i, yaw(0.4 * i));
    with.sensors[static_cast<size_t>(s)].rays = 12;
    with.sensors[static_cast<size_t>(s)].noise = 0.01;
  }
  auto run = [](const Model& m) {
    auto w = World::create(m, 1);
    std::vector<double> out;
    for (int k = 0; k < 1500; ++k) {
      w->step(kDt);
      for (int i = 0; i < w->bodyCount(); ++i) {
        const BodyState s = w->body(i);
        out.insert(out.end(), s.pose.p.begin(), s.pose.p.end());
        out.insert(out.end(), s.pose.q.begin(), s.pose.q.end());
      }
    }
    return out;
  };
  const std::vector<double> a = run(plain), b = run(with);
  REQUIRE(a.size() == b.size());
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

TEST_CASE("rays: a ray that starts inside another body's geom reads where it leaves it", "[physics][rays]") {
  // docs/sensors.md: every shape is seen from both sides. The carrier has no geom here; a second
  // body's geom encloses the sensor's origin and reaches to z = -0.3 (capsule: -0.4) along the ray.
  for (GeomShape shape : {GeomShape::Box, GeomShape::Sphere, GeomShape::Cylinder, GeomShape::Capsule}) {
    Model m = baseModel(kDt);
    m.settings.gravity = {0, 0, 0};
    addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
    const int b = addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
    GeomDef g;
    g.shape = shape;
    g.body = b;
    g.size = shape == GeomShape::Box ? Vec3{0.6, 0.6, 0.6} : Vec3{0.3, 0.2, 0};
    m.geoms.push_back(g);
    addRay(m, SensorKind::Range, 0, yaw(0));
    const double exit = shape == GeomShape::Capsule ? 0.4 : shape == GeomShape::Cylinder ? 0.1 : 0.3;
    INFO("shape " << static_cast<int>(shape));
    CHECK(std::fabs(reading(m) - exit) < 1e-9);
  }
}
