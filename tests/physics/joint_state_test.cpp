// World::joint: the child's motion relative to its parent about (hinge) or along (slider) the
// joint axis, zero at the start pose. Each expectation is a closed-form answer.
#include <catch2/catch.hpp>

#include <cmath>

#include "physics/model_builder.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

using namespace simbob;
using namespace simbob::test;

namespace {

constexpr double kG = 9.81;
constexpr double kDt = 0.001;

Vec3 unit(Vec3 v) { return scale(v, 1 / norm(v)); }

// ODE's rotation update (q += h/2 w q, then normalise) turns a body spinning at w by
// 2 atan(w h / 2) per step: (w h)^3 / 12 short of w h, 2e-6 rad after 3000 steps at 2 rad/s.
double odeTurn(double om, int steps) { return steps * 2 * std::atan(om * kDt / 2); }

// A point-like bob on a massless rod of length L, hinged at the origin about `axis`, released
// from rest at theta0 about +Z (bob at (L sin theta0, -L cos theta0, 0)), under gravity -Y.
struct Pendulum {
  static constexpr double L = 1.0, mass = 1.0, r = 0.05;
  Model model;
  explicit Pendulum(double theta0, Vec3 axis) : model(baseModel(kDt)) {
    addBody(model, {L * std::sin(theta0), -L * std::cos(theta0), 0}, mass, sphereInertia(mass, r));
    addJoint(model, JointKind::Hinge, -1, 0, {0, 0, 0}, axis);
  }
  // Small-angle frequency, with the first finite-amplitude correction of the period.
  static double omega(double theta0) {
    const double iPivot = 0.4 * mass * r * r + mass * L * L;
    return std::sqrt(mass * kG * L / iPivot) / (1 + theta0 * theta0 / 16);
  }
};

}  // namespace

TEST_CASE("joint state: a hinge pendulum released at theta0 follows theta0 (cos wt - 1)", "[physics][joint]") {
  const double theta0 = 5.0 * kPi / 180.0;
  Pendulum p(theta0, {0, 0, 1});
  auto w = World::create(p.model, 1);
  REQUIRE(w);
  REQUIRE(w->jointCount() == 1);
  // Zero at the start pose, exactly (ODE's reading at creation is subtracted).
  CHECK(w->joint(0).position == 0.0);
  CHECK(w->joint(0).velocity == 0.0);

  const double om = Pendulum::omega(theta0);
  double maxLawErr = 0, maxRateErr = 0, maxGeomErr = 0;
  for (int i = 1; i <= 4000; ++i) {  // about two periods
    w->step(kDt);
    const double t = i * kDt;
    const JointState s = w->joint(0);
    if (i == 1) {
      // Gravity pulls the bob (at +x) down: it turns about -Z, the negative sense of the axis.
      CHECK(s.velocity < 0);
      CHECK(s.position < 0);
    }
    // The same angle read from the bob's position: the angle about +Z from straight down.
    const Vec3 x = w->body(0).pose.p;
    maxGeomErr = std::max(maxGeomErr, std::fabs(s.position - (std::atan2(x[0], -x[1]) - theta0)));
    maxLawErr = std::max(maxLawErr, std::fabs(s.position - theta0 * (std::cos(om * t) - 1)));
    maxRateErr = std::max(maxRateErr, std::fabs(s.velocity - (-theta0 * om * std::sin(om * t))));
  }
  INFO("law error " << maxLawErr << " rad, rate error " << maxRateErr << " rad/s, geometric " << maxGeomErr);
  // 1% of theta0 (8.7e-4 rad): the neglected third harmonic is theta0^3 / 192 = 3.5e-6 rad;
  // Euler's phase error h w / 2 per radian of phase adds at most theta0 * w t * h w / 2 ~ 4e-4 rad
  // over two periods.
  // Measured: 1.4e-4 rad.
  CHECK(maxLawErr < 0.01 * theta0);
  // 2% of the peak rate theta0 w (5.5e-3 rad/s): the hinge reads the bob's spin, which QuickStep's
  // 20 iterations leave up to 2e-3 rad/s apart from its orbital rate near the turning points
  // (1e-6 with 200 iterations); elsewhere the error is below 1e-4 rad/s.
  CHECK(maxRateErr < 0.02 * theta0 * om);
  // The joint and the bob agree up to the anchor drift the hinge allows (< 1e-3 m on a 1 m rod
  // in the period test; far less here): 1e-5 rad.
  CHECK(maxGeomErr < 1e-5);
}

TEST_CASE("joint state: flipping a hinge axis flips the sign", "[physics][joint]") {
  const double theta0 = 5.0 * kPi / 180.0;
  double plus = 0, minus = 0, plusRate = 0, minusRate = 0;
  for (double sign : {1.0, -1.0}) {
    Pendulum p(theta0, {0, 0, sign});
    auto w = World::create(p.model, 1);
    REQUIRE(w);
    for (int i = 0; i < 300; ++i) w->step(kDt);
    (sign > 0 ? plus : minus) = w->joint(0).position;
    (sign > 0 ? plusRate : minusRate) = w->joint(0).velocity;
  }
  INFO("+Z: " << plus << " rad, " << plusRate << " rad/s; -Z: " << minus << " rad, " << minusRate << " rad/s");
  CHECK(plus < -0.01);  // well on its way down: theta0 (cos(w 0.3 s) - 1) = -0.055 rad
  CHECK(std::fabs(plus + minus) < 1e-12);
  CHECK(std::fabs(plusRate + minusRate) < 1e-12);
}

TEST_CASE("joint state: a slider under gravity moves by (g.axis) t^2 / 2", "[physics][joint]") {
  // Straight up: position -g t^2 / 2, velocity -g t. Tilted: gravity's component along the axis.
  for (const Vec3 axis : {Vec3{0, 1, 0}, unit({1, -2, 0.5})}) {
    Model m = baseModel(kDt);
    // Offset from the origin and turned: the start pose still reads 0.
    addBody(m, {0.5, 3, -1}, 2.0, sphereInertia(2.0, 0.1), quatAxisAngle({1, 1, 0}, 0.4));
    addJoint(m, JointKind::Slider, -1, 0, {0, 0, 0}, axis);
    auto w = World::create(m, 1);
    REQUIRE(w);
    CHECK(w->joint(0).position == 0.0);
    CHECK(w->joint(0).velocity == 0.0);
    const double ga = dot(m.settings.gravity, axis);  // -g for the axis straight up
    for (int i = 1; i <= 1000; ++i) {
      w->step(kDt);
      const double t = i * kDt;
      const JointState s = w->joint(0);
      // Semi-implicit Euler lands |ga| h t / 2 off the parabola (as free fall); v is exact.
      REQUIRE(std::fabs(s.position - ga * t * t / 2) <= std::fabs(ga) * kDt * t / 2 + 1e-9);
      REQUIRE(std::fabs(s.velocity - ga * t) <= 1e-9);
    }
  }
}

TEST_CASE("joint state: two mobile bodies, the child moving relative to its parent", "[physics][joint]") {
  // No gravity; velocities that already satisfy the joint, so it applies no impulse and the
  // relative motion is uniform: position = v0 t for the sliders, ODE's turn for the hinges.
  const double v0 = 0.7, om = 1.3;
  const Vec3 axis = unit({1, 1, 0});
  const Quat turned = quatAxisAngle({0, 1, 1}, 0.6);
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  // Slider: parent at rest, child offset from it (and off the axis) sliding along +axis.
  const int p1 = addBody(m, {0, 1, 0}, 1.0, sphereInertia(1.0, 0.1), turned);
  const int c1 = addBody(m, {1, 2, 0.5}, 0.5, sphereInertia(0.5, 0.1));
  m.bodies[static_cast<size_t>(c1)].lin_vel = scale(axis, v0);
  addJoint(m, JointKind::Slider, p1, c1, {0, 0, 0}, axis);
  // Hinge: parent at rest, child spinning about +axis through its own centre.
  const int p2 = addBody(m, {5, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  const int c2 = addBody(m, {5, 1, 1}, 0.5, sphereInertia(0.5, 0.1), turned);
  m.bodies[static_cast<size_t>(c2)].ang_vel = scale(axis, om);
  addJoint(m, JointKind::Hinge, p2, c2, {5, 1, 1}, axis);
  // The static world as the child: the world moves by minus the parent's motion.
  const int p3 = addBody(m, {-5, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[static_cast<size_t>(p3)].lin_vel = scale(axis, v0);
  addJoint(m, JointKind::Slider, p3, -1, {0, 0, 0}, axis);
  const int p4 = addBody(m, {-5, 5, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[static_cast<size_t>(p4)].ang_vel = scale(axis, om);
  addJoint(m, JointKind::Hinge, p4, -1, {-5, 5, 0}, axis);
  // Ball and fixed joints have no single axis: always 0.
  const int p5 = addBody(m, {0, -5, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[static_cast<size_t>(p5)].ang_vel = {0.3, 0.2, 0.1};
  addJoint(m, JointKind::BallSocket, -1, p5, {0, -5, 0}, axis);
  const int p6 = addBody(m, {0, -8, 0}, 1.0, sphereInertia(1.0, 0.1));
  const int p7 = addBody(m, {0.5, -8, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[static_cast<size_t>(p6)].lin_vel = m.bodies[static_cast<size_t>(p7)].lin_vel = {0.2, 0.1, 0};
  addJoint(m, JointKind::Fixed, p6, p7, {0, 0, 0}, axis);

  auto w = World::create(m, 1);
  REQUIRE(w);
  REQUIRE(w->jointCount() == 6);
  for (int j = 0; j < 6; ++j) {
    CHECK(w->joint(j).position == 0.0);
    // Up to the rounding of ODE's axis and velocity products.
    CHECK(std::fabs(w->joint(j).velocity - (j == 0 ? v0 : j == 1 ? om : j == 2 ? -v0 : j == 3 ? -om : 0.0)) < 1e-12);
  }
  // 2 s: the hinges pass pi (om t = 2.6 rad stays inside), positions stay unwrapped.
  for (int i = 1; i <= 2000; ++i) {
    w->step(kDt);
    const double t = i * kDt;
    REQUIRE(std::fabs(w->joint(0).position - v0 * t) < 1e-9);
    REQUIRE(std::fabs(w->joint(0).velocity - v0) < 1e-9);
    REQUIRE(std::fabs(w->joint(1).position - odeTurn(om, i)) < 1e-9);
    REQUIRE(std::fabs(w->joint(1).velocity - om) < 1e-9);
    REQUIRE(std::fabs(w->joint(2).position + v0 * t) < 1e-9);
    REQUIRE(std::fabs(w->joint(2).velocity + v0) < 1e-9);
    REQUIRE(std::fabs(w->joint(3).position + odeTurn(om, i)) < 1e-9);
    REQUIRE(std::fabs(w->joint(3).velocity + om) < 1e-9);
  }
  CHECK(w->joint(4).position == 0.0);
  CHECK(w->joint(4).velocity == 0.0);
  CHECK(w->joint(5).position == 0.0);
  CHECK(w->joint(5).velocity == 0.0);
}

TEST_CASE("joint state: a hinge position is the total angle, unwrapped across turns", "[physics][joint]") {
  // Turning freely at om for 3 s: about one turn (6 rad). ODE's wrapped reading jumps by 2 pi at
  // +-pi; the joint's position keeps growing with the analytic turn.
  const double om = 2.0;
  Model m = baseModel(kDt);
  m.settings.gravity = {0, 0, 0};
  addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[0].ang_vel = {0, 0, om};
  addJoint(m, JointKind::Hinge, -1, 0, {0, 0, 0}, {0, 0, 1});
  auto w = World::create(m, 1);
  REQUIRE(w);
  for (int i = 1; i <= 3000; ++i) {
    w->step(kDt);
    REQUIRE(std::fabs(w->joint(0).position - odeTurn(om, i)) < 1e-9);
  }
  CHECK(w->joint(0).position > 5.9);
}
