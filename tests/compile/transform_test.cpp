// include/simbob/transform.h: the Eigen-backed functions give the textbook answers, convert
// between std::array and Eigen in the documented layouts, and keep the rounding of the Hamilton
// product summed in order (golden trajectories depend on it; see quatMul).
#include "compile/eigen.h"
#include "simbob/transform.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <random>

using namespace simbob;

namespace {

/// The Hamilton product written out, terms summed left to right.
Quat hamilton(const Quat& a, const Quat& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

template <size_t N>
bool sameBits(const std::array<double, N>& a, const std::array<double, N>& b) {
  return std::memcmp(a.data(), b.data(), sizeof a) == 0;
}

}  // namespace

TEST_CASE("transform: conversions keep w x y z and row-major order", "[compile][transform]") {
  const Mat3 m{1, 2, 3, 4, 5, 6, 7, 8, 9};
  CHECK(toEigen(m)(0, 1) == 2);
  CHECK(toEigen(m)(1, 0) == 4);
  CHECK(toMat3(toEigen(m)) == m);
  const Eigen::Quaterniond q = toEigen(Quat{0.5, -0.5, 0.5, -0.5});
  CHECK(q.w() == 0.5);
  CHECK(q.x() == -0.5);
  CHECK(toQuat(q) == Quat{0.5, -0.5, 0.5, -0.5});
  CHECK(toVec3(toEigen(Vec3{1, 2, 3})) == Vec3{1, 2, 3});
}

TEST_CASE("transform: textbook rotations", "[compile][transform]") {
  // 90 deg about Z takes X onto Y; about X takes Y onto Z (docs/scene-format.md: Conventions).
  const Vec3 y = rotate(quatFromEulerDeg({0, 0, 90}), {1, 0, 0});
  CHECK(y[0] == Approx(0).margin(1e-15));
  CHECK(y[1] == Approx(1));
  const Vec3 z = rotate(quatFromEulerDeg({90, 0, 0}), {0, 1, 0});
  CHECK(z[2] == Approx(1));
  CHECK(z[1] == Approx(0).margin(1e-15));
  // Two quarter turns about one axis are a half turn: (0, 0, 0, 1) about Z.
  const Quat q90 = quatAxisAngle({0, 0, 1}, kPi / 2);
  const Quat half = quatMul(q90, q90);
  CHECK(half[0] == Approx(0).margin(1e-15));
  CHECK(half[3] == Approx(1));
  // i * j = k.
  CHECK(quatMul({0, 1, 0, 0}, {0, 0, 1, 0}) == Quat{0, 0, 0, 1});
  CHECK(quatMul({0, 0, 1, 0}, {0, 1, 0, 0}) == Quat{0, 0, 0, -1});
  // The matrix of a quarter turn about Z.
  const Mat3 r = toMatrix(q90);
  const Mat3 want{0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (int i = 0; i < 9; ++i) CHECK(r[i] == Approx(want[i]).margin(1e-15));
  CHECK(cross({1, 0, 0}, {0, 1, 0}) == Vec3{0, 0, 1});
  CHECK(dot({1, 2, 3}, {4, 5, 6}) == 32);
  CHECK(norm({3, 4, 12}) == 13);
}

TEST_CASE("transform: quatMul and rotate round exactly like the Hamilton product in order", "[compile][transform]") {
  // Eigen's own Quaterniond product groups the terms differently; trajectories would move by an ulp.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 10000; ++i) {
    const Quat a{u(rng), u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng), u(rng)};
    const Vec3 v{u(rng), u(rng), u(rng)};
    REQUIRE(sameBits(quatMul(a, b), hamilton(a, b)));
    const Quat r = hamilton(hamilton(a, {0, v[0], v[1], v[2]}), {a[0], -a[1], -a[2], -a[3]});
    REQUIRE(sameBits(rotate(a, v), Vec3{r[1], r[2], r[3]}));
  }
}
