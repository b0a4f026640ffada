// Analytic physics tests of the ODE layer: every expectation is a closed-form answer, with a
// tolerance derived from the step size (ODE integrates with semi-implicit Euler).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "simbob/physics.h"

using namespace simbob;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;
constexpr double kDt = 0.001;

Model baseModel() {
  Model m;
  m.settings.max_time_step = kDt;
  m.materials.push_back(MaterialDef{});  // [0] default material
  return m;
}

Mat3 diag(double a, double b, double c) { return {a, 0, 0, 0, b, 0, 0, 0, c}; }
Mat3 sphereInertia(double m, double r) {
  const double i = 0.4 * m * r * r;
  return diag(i, i, i);
}
Mat3 boxInertia(double m, double x, double y, double z) {
  return diag(m * (y * y + z * z) / 12, m * (x * x + z * z) / 12, m * (x * x + y * y) / 12);
}

int addBody(Model& m, Vec3 p, double mass, Mat3 inertia, Quat q = {1, 0, 0, 0}) {
  BodyDef b;
  b.key = "b" + std::to_string(m.bodies.size());
  b.pose.p = p;
  b.pose.q = q;
  b.mass = mass;
  b.inertia = inertia;
  m.bodies.push_back(b);
  return static_cast<int>(m.bodies.size()) - 1;
}

void addGeom(Model& m, int body, GeomShape shape, Vec3 size, int material = 0) {
  GeomDef g;
  g.shape = shape;
  g.body = body;
  g.size = size;
  g.material = material;
  m.geoms.push_back(g);
}

void addGround(Model& m, int material = 0) {
  GeomDef g;
  g.shape = GeomShape::Plane;
  g.body = -1;
  g.plane = {0, 1, 0, 0};
  g.material = material;
  m.geoms.push_back(g);
}

int addMaterial(Model& m, double friction, double bounceness, double minBounceVel) {
  MaterialDef mat;
  mat.key = "mat" + std::to_string(m.materials.size());
  mat.friction = friction;
  mat.bounceness = bounceness;
  mat.min_bounce_vel = minBounceVel;
  m.materials.push_back(mat);
  return static_cast<int>(m.materials.size()) - 1;
}

void addJoint(Model& m, JointKind kind, int b1, int b2, Vec3 anchor, Vec3 axis) {
  JointDef j;
  j.key = "j" + std::to_string(m.joints.size());
  j.kind = kind;
  j.body1 = b1;
  j.body2 = b2;
  j.anchor = anchor;
  j.axis = axis;
  m.joints.push_back(j);
}

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
Vec3 normalized(const Vec3& a) {
  const double n = norm(a);
  return {a[0] / n, a[1] / n, a[2] / n};
}

Quat conj(const Quat& q) { return {q[0], -q[1], -q[2], -q[3]}; }
Quat mul(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}
Vec3 rotate(const Quat& q, const Vec3& v) {
  const Quat r = mul(mul(q, {0, v[0], v[1], v[2]}), conj(q));
  return {r[1], r[2], r[3]};
}
Quat axisAngle(Vec3 axis, double angle) {
  const Vec3 a = normalized(axis);
  const double s = std::sin(angle / 2);
  return {std::cos(angle / 2), a[0] * s, a[1] * s, a[2] * s};
}
// Distance between two rotations, insensitive to the q / -q ambiguity.
double quatDistance(const Quat& a, const Quat& b) {
  double dm = 0, dp = 0;
  for (int k = 0; k < 4; ++k) {
    dm = std::max(dm, std::fabs(a[k] - b[k]));
    dp = std::max(dp, std::fabs(a[k] + b[k]));
  }
  return std::min(dm, dp);
}

// Drops a sphere (bottom 1 m above the plane) and returns the apex of the sphere bottom after
// the first impact.
double firstReboundApex(double ballBounce, double ballMinVel, double groundBounce, double groundMinVel) {
  const double r = 0.1;
  const double h = 1.0;
  Model m = baseModel();
  const int ballMat = addMaterial(m, 0.5, ballBounce, ballMinVel);
  const int groundMat = addMaterial(m, 0.5, groundBounce, groundMinVel);
  // Light ball: the world CFM costs cfm m (1 + e) v / h of rebound speed (0.2% at 0.1 kg, but
  // 2.3% at 1 kg), because ODE's CFM is not scaled by mass.
  const double mass = 0.1;
  const int b = addBody(m, {0, h + r, 0}, mass, sphereInertia(mass, r));
  addGeom(m, b, GeomShape::Sphere, {r, 0, 0}, ballMat);
  addGround(m, groundMat);
  auto w = World::create(m, 1);
  REQUIRE(w);
  bool impacted = false;
  double apex = -1;
  for (int i = 0; i < 3000; ++i) {
    w->step(kDt);
    const BodyState s = w->body(0);
    if (!impacted) {
      impacted = w->lastContactCount() > 0;
      continue;
    }
    apex = std::max(apex, s.pose.p[1] - r);
    if (s.lin_vel[1] < 0 && s.pose.p[1] - r > 1e-3) break;  // falling again: apex passed
  }
  REQUIRE(impacted);
  return apex;
}

}  // namespace

TEST_CASE("physics: free fall follows y = y0 - g t^2 / 2", "[physics]") {
  Model m = baseModel();
  const int b = addBody(m, {0, 10, 0}, 1.0, sphereInertia(1.0, 0.1));
  addGeom(m, b, GeomShape::Sphere, {0.1, 0, 0});
  auto w = World::create(m, 1);
  REQUIRE(w);
  double maxErr = 0;
  for (int i = 1; i <= 1000; ++i) {
    w->step(kDt);
    const double t = i * kDt;
    const BodyState s = w->body(0);
    // Semi-implicit Euler: y_n = y0 - g h^2 n(n+1)/2, i.e. exactly g h t / 2 below the parabola.
    const double bound = kG * kDt * t / 2 + 1e-9;
    REQUIRE(std::fabs(s.pose.p[1] - (10 - kG * t * t / 2)) <= bound);
    // Velocity update v += g h is exact up to rounding of 1000 additions.
    REQUIRE(std::fabs(s.lin_vel[1] - (-kG * t)) <= 1e-9);
    REQUIRE(s.pose.p[0] == 0);
    REQUIRE(s.pose.p[2] == 0);
    maxErr = std::max(maxErr, std::fabs(s.pose.p[1] - (10 - kG * t * t / 2)));
  }
  INFO("max |y error| = " << maxErr);
  CHECK(w->lastContactCount() == 0);
}

TEST_CASE("physics: hinge pendulum period", "[physics]") {
  const double L = 1.0;
  const double mass = 1.0;
  const double r = 0.05;
  const double theta0 = 5.0 * kPi / 180.0;
  Model m = baseModel();
  const int b = addBody(m, {L * std::sin(theta0), -L * std::cos(theta0), 0}, mass, sphereInertia(mass, r));
  addGeom(m, b, GeomShape::Sphere, {r, 0, 0});
  addJoint(m, JointKind::Hinge, -1, b, {0, 0, 0}, {0, 0, 1});
  auto w = World::create(m, 1);
  REQUIRE(w);

  const double iPivot = 0.4 * mass * r * r + mass * L * L;
  const double expected = 2 * kPi * std::sqrt(iPivot / (mass * kG * L)) * (1 + theta0 * theta0 / 16);
  std::vector<double> crossings;
  double prevX = w->body(0).pose.p[0];
  double maxRadiusErr = 0;
  for (int i = 1; i <= 9500; ++i) {
    w->step(kDt);
    const BodyState s = w->body(0);
    const double x = s.pose.p[0];
    if ((prevX > 0) != (x > 0)) {
      // Linear interpolation of the crossing time inside the step.
      crossings.push_back((i - 1) * kDt + kDt * prevX / (prevX - x));
    }
    prevX = x;
    maxRadiusErr = std::max(maxRadiusErr, std::fabs(norm(s.pose.p) - L));
  }
  REQUIRE(crossings.size() >= 9);
  // Consecutive zero crossings are half a period apart.
  const double period = 2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  INFO("period " << period << " expected " << expected << " radius err " << maxRadiusErr);
  // 0.5%: Euler's O(h) phase error is ~1e-4 relative at h = 1 ms, the series correction is
  // accurate to O(theta0^4) ~ 1e-5; the rest is margin.
  CHECK(std::fabs(period - expected) / expected < 0.005);
  // The hinge holds the bob on its circle up to ERP/CFM drift (far below 1 mm).
  CHECK(maxRadiusErr < 1e-3);
}

TEST_CASE("physics: bounce height follows the max bounceness rule", "[physics]") {
  const double h = 1.0;
  const double e = 0.8;  // max(0.5, 0.8)
  const double apex = firstReboundApex(0.5, 0.1, 0.8, 0.1);
  INFO("apex " << apex << " expected " << e * e * h);
  // 5%: the impact lands mid-step (penetration up to v h = 4.4 mm), ERP pushes the ball out
  // and CFM softens the impact, together a few mm on 0.64 m.
  CHECK(std::fabs(apex - e * e * h) <= 0.05 * e * e * h);
}

TEST_CASE("physics: min bounce velocity follows the min rule", "[physics]") {
  const double expected = 0.8 * 0.8 * 1.0;
  // Impact speed is sqrt(2 g h) = 4.4 m/s: the ball's threshold 100 m/s alone would forbid the
  // bounce, but min(100, 0.1) = 0.1 lets it bounce.
  const double bounced = firstReboundApex(0.5, 100.0, 0.8, 0.1);
  INFO("apex with min(100, 0.1) = " << bounced);
  CHECK(std::fabs(bounced - expected) <= 0.05 * expected);
  // Both thresholds above the impact speed: no bounce, only the ERP push-out of a few cm.
  const double dead = firstReboundApex(0.5, 100.0, 0.8, 50.0);
  INFO("apex with min(100, 50) = " << dead);
  CHECK(dead < 0.1 * expected);
}

TEST_CASE("physics: Coulomb sliding stops at v0^2 / (2 mu g) with the max friction rule", "[physics]") {
  const double side = 0.2;
  const double v0 = 2.0;
  const double mu = 0.5;  // max(0.3, 0.5)
  Model m = baseModel();
  const int boxMat = addMaterial(m, 0.3, 0.0, 0.1);
  const int groundMat = addMaterial(m, 0.5, 0.0, 0.1);
  const int b = addBody(m, {0, side / 2, 0}, 1.0, boxInertia(1.0, side, side, side));
  m.bodies[static_cast<size_t>(b)].lin_vel = {v0, 0, 0};
  addGeom(m, b, GeomShape::Box, {side, side, side}, boxMat);
  addGround(m, groundMat);
  auto w = World::create(m, 1);
  REQUIRE(w);
  for (int i = 0; i < 700; ++i) w->step(kDt);  // stops after v0 / (mu g) = 0.41 s
  const BodyState s = w->body(0);
  const double expected = v0 * v0 / (2 * mu * kG);
  INFO("distance " << s.pose.p[0] << " expected " << expected);
  // 2%: deceleration is exact per step; the discrete stop is off by at most v0 h = 2 mm (0.5%).
  CHECK(std::fabs(s.pose.p[0] - expected) <= 0.02 * expected);
  // At rest: only solver residue (CFM softness) remains.
  CHECK(norm(s.lin_vel) < 1e-3);
  CHECK(std::fabs(s.pose.p[1] - side / 2) < 1e-3);
}

TEST_CASE("physics: slider joint keeps its constraint", "[physics]") {
  const Vec3 axis = normalized({1, 2, 0.5});
  Model m = baseModel();
  const Quat q0 = axisAngle({0.3, 1, -0.2}, 0.7);
  const int b = addBody(m, {0.5, 1, -0.3}, 1.0, boxInertia(1.0, 0.3, 0.1, 0.2), q0);
  m.bodies[static_cast<size_t>(b)].ang_vel = {0.5, -1, 0.3};  // must be cancelled by the joint
  addGeom(m, b, GeomShape::Box, {0.3, 0.1, 0.2});
  addJoint(m, JointKind::Slider, -1, b, {0, 0, 0}, axis);
  auto w = World::create(m, 1);
  REQUIRE(w);
  const Vec3 p0 = m.bodies[0].pose.p;
  const double ga = dot(m.settings.gravity, axis);
  double maxPerp = 0, maxRot = 0, maxAlongErr = 0;
  for (int i = 1; i <= 1000; ++i) {
    w->step(kDt);
    const double t = i * kDt;
    const BodyState s = w->body(0);
    const Vec3 d = sub(s.pose.p, p0);
    const double along = dot(d, axis);
    const Vec3 perp = {d[0] - along * axis[0], d[1] - along * axis[1], d[2] - along * axis[2]};
    maxPerp = std::max(maxPerp, norm(perp));
    maxRot = std::max(maxRot, quatDistance(s.pose.q, q0));
    const double alongErr = std::fabs(along - 0.5 * ga * t * t);
    maxAlongErr = std::max(maxAlongErr, alongErr);
    // Same Euler bound as free fall, with the projected gravity g.a.
    REQUIRE(alongErr <= std::fabs(ga) * kDt * t / 2 + 1e-9);
  }
  INFO("perp " << maxPerp << " rot " << maxRot << " along err " << maxAlongErr);
  // CFM makes the joint a stiff spring (k = ERP / (h CFM) = 2e7 N/m): the perpendicular gravity
  // force m g sin(angle) = 4.8 N sags it by 2.4e-7 m.
  CHECK(maxPerp < 1e-6);
  CHECK(maxRot < 1e-6);
}

TEST_CASE("physics: ball joint keeps its anchor distance", "[physics]") {
  Model m = baseModel();
  const int b = addBody(m, {0, -1, 0}, 1.5, boxInertia(1.5, 0.2, 0.1, 0.3));
  m.bodies[0].lin_vel = {1.5, 0, 0.7};
  m.bodies[0].ang_vel = {0.5, 2, -1};
  addGeom(m, b, GeomShape::Box, {0.2, 0.1, 0.3});
  addJoint(m, JointKind::BallSocket, -1, b, {0, 0, 0}, {0, 0, 1});
  auto w = World::create(m, 1);
  REQUIRE(w);
  double maxErr = 0;
  double maxSpeed = 0;
  for (int i = 0; i < 2000; ++i) {
    w->step(kDt);
    const BodyState s = w->body(0);
    maxErr = std::max(maxErr, std::fabs(norm(s.pose.p) - 1.0));
    maxSpeed = std::max(maxSpeed, norm(s.lin_vel));
  }
  INFO("max |distance - 1| = " << maxErr);
  // Velocity-level constraint plus ERP: drift per step is O(v^2 h^2 / L), far below 1 mm.
  CHECK(maxErr < 1e-3);
  CHECK(maxSpeed > 0.5);  // it really swung
}

TEST_CASE("physics: fixed joint keeps the relative pose", "[physics]") {
  Model m = baseModel();
  const Quat qa = axisAngle({0, 0, 1}, kPi / 6);
  const Quat qb = axisAngle({1, 0, 0}, kPi / 4);
  const int a = addBody(m, {0, 5, 0}, 1.0, boxInertia(1.0, 0.2, 0.2, 0.2), qa);
  const int b = addBody(m, {0.15, 5.1, 0.0}, 0.5, boxInertia(0.5, 0.1, 0.3, 0.1), qb);
  // A rigid spin (consistent velocities, so the joint applies no impulse): without the joint
  // B would fly off along a straight line instead of circling with A.
  const Vec3 omega = {0.15, 0.5, -0.25};
  const Vec3 va = {1, 0, 0};
  const Vec3 r = sub(m.bodies[1].pose.p, m.bodies[0].pose.p);
  m.bodies[static_cast<size_t>(a)].lin_vel = va;
  m.bodies[static_cast<size_t>(a)].ang_vel = omega;
  m.bodies[static_cast<size_t>(b)].lin_vel = {va[0] + omega[1] * r[2] - omega[2] * r[1],
                                              va[1] + omega[2] * r[0] - omega[0] * r[2],
                                              va[2] + omega[0] * r[1] - omega[1] * r[0]};
  m.bodies[static_cast<size_t>(b)].ang_vel = omega;
  addGeom(m, a, GeomShape::Box, {0.2, 0.2, 0.2});
  addGeom(m, b, GeomShape::Box, {0.1, 0.3, 0.1});
  addJoint(m, JointKind::Fixed, a, b, {0, 0, 0}, {0, 0, 1});
  auto w = World::create(m, 1);
  REQUIRE(w);
  const Vec3 relP0 = rotate(conj(qa), sub(m.bodies[1].pose.p, m.bodies[0].pose.p));
  const Quat relQ0 = mul(conj(qa), qb);
  double maxP = 0, maxQ = 0;
  for (int i = 0; i < 1000; ++i) {
    w->step(kDt);
    const BodyState sa = w->body(a);
    const BodyState sb = w->body(b);
    const Vec3 relP = rotate(conj(sa.pose.q), sub(sb.pose.p, sa.pose.p));
    maxP = std::max(maxP, norm(sub(relP, relP0)));
    maxQ = std::max(maxQ, quatDistance(mul(conj(sa.pose.q), sb.pose.q), relQ0));
  }
  INFO("relative position drift " << maxP << " rotation drift " << maxQ);
  // Linear position updates stretch the spinning pair by r h^2 w^2 / 2 per step, which ERP
  // removes at rate ERP: steady drift r h^2 w^2 / (2 ERP) ~ 2.5e-7 m for |w| = 0.58 rad/s.
  CHECK(maxP < 1e-6);
  CHECK(maxQ < 1e-6);
  // The boxes overlap, yet jointed bodies do not collide with each other.
  CHECK(w->lastContactCount() == 0);
}

TEST_CASE("physics: identical model and seed give bit-identical runs", "[physics]") {
  Model m = baseModel();
  addGround(m);
  for (int i = 0; i < 5; ++i) {
    const Quat q = axisAngle({1.0 + i, 0.5, -0.3 * i}, 0.4 * i);
    const int b = addBody(m, {0.15 * i, 0.3 + 0.35 * i, 0.05 * (i % 2)}, 1.0, boxInertia(1.0, 0.2, 0.2, 0.2), q);
    addGeom(m, b, GeomShape::Box, {0.2, 0.2, 0.2});
  }
  auto run = [&m](long& contacts) {
    std::vector<BodyState> out;
    auto w = World::create(m, 42);
    REQUIRE(w);
    contacts = 0;
    for (int i = 0; i < 1000; ++i) {
      w->step(kDt);
      contacts += w->lastContactCount();
    }
    for (int i = 0; i < w->bodyCount(); ++i) out.push_back(w->body(i));
    return out;
  };
  long c1 = 0, c2 = 0;
  const std::vector<BodyState> s1 = run(c1);
  const std::vector<BodyState> s2 = run(c2);
  REQUIRE(c1 > 0);  // the boxes did collide
  REQUIRE(c1 == c2);
  REQUIRE(s1.size() == s2.size());
  for (size_t i = 0; i < s1.size(); ++i) {
    CHECK(std::memcmp(s1[i].pose.p.data(), s2[i].pose.p.data(), sizeof(Vec3)) == 0);
    CHECK(std::memcmp(s1[i].pose.q.data(), s2[i].pose.q.data(), sizeof(Quat)) == 0);
    CHECK(std::memcmp(s1[i].lin_vel.data(), s2[i].lin_vel.data(), sizeof(Vec3)) == 0);
    CHECK(std::memcmp(s1[i].ang_vel.data(), s2[i].ang_vel.data(), sizeof(Vec3)) == 0);
  }
}

TEST_CASE("physics: a second World may live beside the first", "[physics]") {
  Model m = baseModel();
  addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  auto w1 = World::create(m, 1);
  REQUIRE(w1);
  auto w2 = World::create(m, 1);
  REQUIRE(w2);
  w1->step(kDt);
  w2->step(kDt);
  CHECK(w1->body(0).pose.p[1] == w2->body(0).pose.p[1]);
}

TEST_CASE("physics: firstBadBody finds runaway and NaN states", "[physics]") {
  Model m = baseModel();
  addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  const int huge = addBody(m, {0, 0, 0}, 1.0, sphereInertia(1.0, 0.1));
  m.bodies[static_cast<size_t>(huge)].lin_vel = {1e300, 0, 0};
  {
    auto w = World::create(m, 1);
    REQUIRE(w);
    CHECK(w->firstBadBody() == 1);
    CHECK(w->firstBadBody(1e301) == -1);
    w->step(kDt);
    CHECK(w->firstBadBody() == 1);
  }
  m.bodies[0].ang_vel = {0, std::numeric_limits<double>::quiet_NaN(), 0};
  {
    auto w = World::create(m, 1);
    REQUIRE(w);
    CHECK(w->firstBadBody() == 0);
    CHECK(w->firstBadBody(std::numeric_limits<double>::infinity()) == 0);
  }
  m.bodies[0].ang_vel = {0, 0, 0};
  m.bodies[static_cast<size_t>(huge)].lin_vel = {0, -std::numeric_limits<double>::infinity(), 0};
  {
    auto w = World::create(m, 1);
    REQUIRE(w);
    // Non-finite is bad even when no finite limit applies.
    CHECK(w->firstBadBody(std::numeric_limits<double>::infinity()) == 1);
  }
  m.bodies[static_cast<size_t>(huge)].lin_vel = {0, 0, 0};
  m.bodies[static_cast<size_t>(huge)].pose.p = {0, -2e6, 0};  // a position beyond the limit
  {
    auto w = World::create(m, 1);
    REQUIRE(w);
    CHECK(w->firstBadBody() == 1);
    CHECK(w->firstBadBody(2e6) == -1);  // at the limit is within it
  }
  m.bodies[static_cast<size_t>(huge)].pose.p = {0, 0, 0};
  {  // (ODE itself refuses a NaN orientation: it cannot be set to test the quaternion's check)
    auto w = World::create(m, 1);
    REQUIRE(w);
    CHECK(w->firstBadBody() == -1);
  }
}

TEST_CASE("physics: sensor geoms create no contact joints", "[physics]") {
  Model m = baseModel();
  addGround(m);
  const int b = addBody(m, {0, 0.2, 0}, 1.0, sphereInertia(1.0, 0.1));
  addGeom(m, b, GeomShape::Sphere, {0.1, 0, 0});
  m.geoms.back().sensor = true;
  auto w = World::create(m, 1);
  REQUIRE(w);
  int contacts = 0;
  for (int i = 0; i < 500; ++i) {
    w->step(kDt);
    contacts += w->lastContactCount();
  }
  CHECK(contacts == 0);
  // It fell through the plane as in free fall (0.2 - g t^2 / 2 at t = 0.5 s, Euler bound 2.5 mm).
  CHECK(std::fabs(w->body(0).pose.p[1] - (0.2 - kG * 0.25 / 2)) < 3e-3);
}
