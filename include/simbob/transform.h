// Rigid transforms on plain arrays (header-only; used by the compile step and tests).
// Euler convention of the scene format: angles (a, b, c) in degrees rotate about global X, then
// global Y, then global Z: R = Rz(c) * Ry(b) * Rx(a).
#pragma once

#include <cmath>

#include "simbob/model.h"
#include "simbob/values.h"

namespace simbob {

constexpr double kPi = 3.14159265358979323846;

inline Quat quatMul(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

inline Quat quatConj(const Quat& q) { return {q[0], -q[1], -q[2], -q[3]}; }

inline Quat quatAxisAngle(const Vec3& axis, double rad) {
  double s = std::sin(rad / 2);
  return {std::cos(rad / 2), axis[0] * s, axis[1] * s, axis[2] * s};
}

/// R = Rz(c) * Ry(b) * Rx(a), angles in degrees.
inline Quat quatFromEulerDeg(const Triple& abc) {
  const double d = kPi / 180.0;
  Quat qx = quatAxisAngle({1, 0, 0}, abc[0] * d);
  Quat qy = quatAxisAngle({0, 1, 0}, abc[1] * d);
  Quat qz = quatAxisAngle({0, 0, 1}, abc[2] * d);
  return quatMul(qz, quatMul(qy, qx));
}

inline Vec3 rotate(const Quat& q, const Vec3& v) {
  Quat p{0, v[0], v[1], v[2]};
  Quat r = quatMul(quatMul(q, p), quatConj(q));
  return {r[1], r[2], r[3]};
}

inline Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 scale(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

/// parent * child: child expressed in parent's frame -> global.
inline Transform compose(const Transform& parent, const Transform& child) {
  return {add(parent.p, rotate(parent.q, child.p)), quatMul(parent.q, child.q)};
}

inline Transform inverse(const Transform& t) {
  Quat qi = quatConj(t.q);
  return {scale(rotate(qi, t.p), -1.0), qi};
}

inline Transform fromPose(const Pose& p) { return {{p.pos[0], p.pos[1], p.pos[2]}, quatFromEulerDeg(p.euler_deg)}; }

/// Rotation matrix (row-major) of a unit quaternion.
inline Mat3 toMatrix(const Quat& q) {
  double w = q[0], x = q[1], y = q[2], z = q[3];
  return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
          2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}

/// The rotation taking local +Z onto unit vector d (shortest arc).
inline Quat quatZTo(const Vec3& d) {
  Vec3 z{0, 0, 1};
  double c = dot(z, d);
  if (c > 1.0 - 1e-15) return {1, 0, 0, 0};
  if (c < -1.0 + 1e-15) return {0, 1, 0, 0};  // half turn about X
  Vec3 axis = cross(z, d);
  double n = norm(axis);
  return quatAxisAngle(scale(axis, 1.0 / n), std::atan2(n, c));
}

}  // namespace simbob
