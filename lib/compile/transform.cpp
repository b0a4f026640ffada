// The rigid-transform math of simbob/transform.h, over Eigen. Each function keeps the rounding
// of the hand-written formulas it replaced (tests/compile/transform_test.cpp pins it), since
// golden trajectories depend on the last bit of every initial pose.
#include "simbob/transform.h"

#include <cmath>

#include "compile/eigen.h"
#include "simbob/cr_math.h"

namespace simbob {

// --- vectors ---

Vec3 add(const Vec3& a, const Vec3& b) { return toVec3(toEigen(a) + toEigen(b)); }
Vec3 sub(const Vec3& a, const Vec3& b) { return toVec3(toEigen(a) - toEigen(b)); }
Vec3 scale(const Vec3& a, double s) { return toVec3(toEigen(a) * s); }
double dot(const Vec3& a, const Vec3& b) { return toEigen(a).dot(toEigen(b)); }
Vec3 cross(const Vec3& a, const Vec3& b) { return toVec3(toEigen(a).cross(toEigen(b))); }
double norm(const Vec3& a) { return toEigen(a).norm(); }

// --- rotations ---

// b's right-multiplication matrix applied to a (w x y z), which Eigen sums in the order a0..a3
// for every component: the rounding of the textbook formula. Eigen's own Quaterniond product groups the terms
// differently (its SSE path), which moves results by an ulp and with them the trajectories of
// every scene whose initial poses compose rotations.
Quat quatMul(const Quat& a, const Quat& b) {
  Eigen::Matrix4d right;
  // clang-format off
  right << b[0], -b[1], -b[2], -b[3],
           b[1],  b[0],  b[3], -b[2],
           b[2], -b[3],  b[0],  b[1],
           b[3],  b[2], -b[1],  b[0];
  // clang-format on
  const Eigen::Vector4d r = right * Eigen::Vector4d(a[0], a[1], a[2], a[3]);
  return {r[0], r[1], r[2], r[3]};
}

Quat quatConj(const Quat& q) { return toQuat(toEigen(q).conjugate()); }

namespace {
// Eigen's AngleAxis to quaternion (w = cos(angle / 2), v = sin(angle / 2) axis, the axis as given),
// with correctly rounded sin and cos (cr_math.h): libm's give other bits on other CPUs for a few
// angles, and an initial rotation's last bit reaches the whole trajectory.
Eigen::Quaterniond fromAxisAngle(double rad, const Eigen::Vector3d& axis) {
  const double half = 0.5 * rad, s = crSin(half);
  return {crCos(half), s * axis[0], s * axis[1], s * axis[2]};
}
}  // namespace

Quat quatAxisAngle(const Vec3& axis, double rad) { return toQuat(fromAxisAngle(rad, toEigen(axis))); }

Quat quatFromEulerDeg(const Triple& abc) {
  const double d = kPi / 180.0;
  const Eigen::Quaterniond qx = fromAxisAngle(abc[0] * d, Eigen::Vector3d::UnitX());
  const Eigen::Quaterniond qy = fromAxisAngle(abc[1] * d, Eigen::Vector3d::UnitY());
  const Eigen::Quaterniond qz = fromAxisAngle(abc[2] * d, Eigen::Vector3d::UnitZ());
  return toQuat(qz * (qy * qx));
}

// q (0, v) q*, not Eigen's q * v: that cheaper formula rounds differently (see quatMul).
Vec3 rotate(const Quat& q, const Vec3& v) {
  const Quat r = quatMul(quatMul(q, {0, v[0], v[1], v[2]}), quatConj(q));
  return {r[1], r[2], r[3]};
}

Mat3 toMatrix(const Quat& q) { return toMat3(toEigen(q).toRotationMatrix()); }

Quat quatZTo(const Vec3& d) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), e = toEigen(d);
  const double c = z.dot(e);
  if (c > 1.0 - 1e-15) return {1, 0, 0, 0};
  if (c < -1.0 + 1e-15) return {0, 1, 0, 0};  // half turn about X
  const Eigen::Vector3d axis = z.cross(e);
  const double n = axis.norm();
  // axis * (1 / n), not axis / n: the rounding of the formula this replaced.
  return toQuat(fromAxisAngle(crAtan2(n, c), axis * (1.0 / n)));
}

// --- rigid transforms ---

Transform compose(const Transform& parent, const Transform& child) {
  return {add(parent.p, rotate(parent.q, child.p)), quatMul(parent.q, child.q)};
}

Transform inverse(const Transform& t) {
  Quat qi = quatConj(t.q);
  return {scale(rotate(qi, t.p), -1.0), qi};
}

Transform fromPose(const Pose& p) { return {{p.pos[0], p.pos[1], p.pos[2]}, quatFromEulerDeg(p.euler_deg)}; }

}  // namespace simbob
