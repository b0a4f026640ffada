// std::array <-> Eigen conversions for the math behind simbob/transform.h and compile/mass.h.
// Internal: the public headers stay plain data and free of Eigen (it costs seconds per
// translation unit that includes it).
#pragma once

#include <Eigen/Geometry>

#include "simbob/model.h"

namespace simbob {

inline Eigen::Vector3d toEigen(const Vec3& v) { return {v[0], v[1], v[2]}; }
inline Eigen::Quaterniond toEigen(const Quat& q) { return {q[0], q[1], q[2], q[3]}; }  // w x y z
inline Eigen::Matrix3d toEigen(const Mat3& m) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(m.data());
}
inline Vec3 toVec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
inline Quat toQuat(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }
inline Mat3 toMat3(const Eigen::Matrix3d& m) {
  Mat3 out;
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(out.data()) = m;
  return out;
}

}  // namespace simbob
