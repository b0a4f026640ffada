// Rigid transforms on the plain arrays of model.h (used by the compile step, lint, physics and
// tests). Computed with Eigen in lib/compile/transform.cpp; Eigen stays out of this header, which
// would otherwise cost every includer seconds of compile time.
// Euler convention of the scene format: angles (a, b, c) in degrees rotate about global X, then
// global Y, then global Z: R = Rz(c) * Ry(b) * Rx(a).
#pragma once

#include "simbob/model.h"
#include "simbob/values.h"

namespace simbob {

constexpr double kPi = 3.14159265358979323846;

// --- vectors ---
Vec3 add(const Vec3& a, const Vec3& b);
Vec3 sub(const Vec3& a, const Vec3& b);
Vec3 scale(const Vec3& a, double s);
double dot(const Vec3& a, const Vec3& b);
Vec3 cross(const Vec3& a, const Vec3& b);
double norm(const Vec3& a);

// --- rotations (quaternions w x y z) ---

/// The Hamilton product a * b (apply b, then a), rounded exactly like the product written out
/// with its terms summed left to right.
Quat quatMul(const Quat& a, const Quat& b);
Quat quatConj(const Quat& q);
/// Rotation by rad about a unit axis.
Quat quatAxisAngle(const Vec3& axis, double rad);
/// R = Rz(c) * Ry(b) * Rx(a), angles in degrees.
Quat quatFromEulerDeg(const Triple& abc);
/// v rotated by the unit quaternion q: the vector part of q (0, v) q*.
Vec3 rotate(const Quat& q, const Vec3& v);
/// Rotation matrix (row-major) of a unit quaternion.
Mat3 toMatrix(const Quat& q);
/// The rotation taking local +Z onto unit vector d (shortest arc).
Quat quatZTo(const Vec3& d);

// --- rigid transforms ---

/// parent * child: child expressed in parent's frame -> global.
Transform compose(const Transform& parent, const Transform& child);
Transform inverse(const Transform& t);
Transform fromPose(const Pose& p);

}  // namespace simbob
