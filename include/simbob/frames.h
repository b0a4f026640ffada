// Vectors, rotations and rigid frames of the compiled model (plain data; transform.h has the math).
#pragma once

#include <array>

namespace simbob {

using Vec3 = std::array<double, 3>;
/// Unit quaternion, w x y z.
using Quat = std::array<double, 4>;
/// Row-major 3x3.
using Mat3 = std::array<double, 9>;

struct Transform {
  Vec3 p{0, 0, 0};
  Quat q{1, 0, 0, 0};
};

}  // namespace simbob
