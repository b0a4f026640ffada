// lib/compile/mass.cpp: volumes and inertia tensors of the geom shapes against textbook formulas
// (the capsule against a numerical integration over slices), rotated and offset geoms, and the
// positive-definiteness check on known definite, semidefinite and indefinite matrices.
#include "compile/mass.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "simbob/transform.h"

using namespace simbob;

namespace {

GeomDef geom(GeomShape shape, Vec3 size, Transform offset = {}) {
  GeomDef g;
  g.shape = shape;
  g.size = size;
  g.offset = offset;
  return g;
}

void checkTensor(const Mat3& got, const Mat3& want, double rel = 1e-12) {
  double scale = 0;
  for (double w : want) scale = std::max(scale, std::fabs(w));
  for (int i = 0; i < 9; ++i) {
    INFO("element " << i << ": got " << got[i] << ", want " << want[i]);
    CHECK(got[i] == Approx(want[i]).margin(rel * scale));
  }
}

Mat3 diag(double a, double b, double c) { return {a, 0, 0, 0, b, 0, 0, 0, c}; }

}  // namespace

TEST_CASE("mass: box, sphere and cylinder match the textbook formulas", "[compile][mass]") {
  // Box 1 x 2 x 3: V = 6, I = V (b^2 + c^2) / 12 per axis.
  MassProps box = geomMassProps(geom(GeomShape::Box, {1, 2, 3}));
  CHECK(box.volume == Approx(6));
  checkTensor(box.inertia, diag(6.5, 5, 2.5));
  CHECK(box.moment == Vec3{0, 0, 0});

  // Solid sphere r = 0.5: V = 4/3 pi r^3, I = 2/5 V r^2.
  const double vs = 4.0 / 3.0 * kPi * 0.125;
  MassProps sphere = geomMassProps(geom(GeomShape::Sphere, {0.5, 0, 0}));
  CHECK(sphere.volume == Approx(vs));
  checkTensor(sphere.inertia, diag(0.1 * vs, 0.1 * vs, 0.1 * vs));

  // Cylinder r = 0.5, length 2 along Z: V = pi r^2 l, Ixx = V (3 r^2 + l^2) / 12, Izz = V r^2 / 2.
  const double vc = kPi * 0.25 * 2;
  MassProps cyl = geomMassProps(geom(GeomShape::Cylinder, {0.5, 2, 0}));
  CHECK(cyl.volume == Approx(vc));
  checkTensor(cyl.inertia, diag(vc * 4.75 / 12, vc * 4.75 / 12, vc * 0.125));

  // Planes have no volume and no inertia.
  MassProps plane = geomMassProps(geom(GeomShape::Plane, {0, 0, 0}));
  CHECK(plane.volume == 0);
  CHECK(plane.inertia == Mat3{0, 0, 0, 0, 0, 0, 0, 0, 0});
}

TEST_CASE("mass: capsule matches an integration over slices along its axis", "[compile][mass]") {
  const double r = 0.3, l = 1.2;
  // Radius of the slice at height z (cylinder, then the hemispherical caps).
  auto rho = [&](double z) {
    const double cap = std::fabs(z) - l / 2;
    return cap <= 0 ? r : std::sqrt(std::max(0.0, r * r - cap * cap));
  };
  // Composite Simpson over [-l/2 - r, l/2 + r] of a disc's volume and moments.
  const int n = 20000;
  const double a = -l / 2 - r, h = (l + 2 * r) / n;
  double v = 0, ixx = 0, izz = 0;
  for (int i = 0; i <= n; ++i) {
    const double z = a + i * h, p = rho(z), w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    v += w * kPi * p * p;
    ixx += w * (kPi * p * p * p * p / 4 + kPi * p * p * z * z);
    izz += w * kPi * p * p * p * p / 2;
  }
  v *= h / 3, ixx *= h / 3, izz *= h / 3;
  MassProps cap = geomMassProps(geom(GeomShape::Capsule, {r, l, 0}));
  CHECK(cap.volume == Approx(v).epsilon(1e-8));
  // The caps' square-root edge limits Simpson's accuracy to about 1e-7 here.
  checkTensor(cap.inertia, diag(ixx, ixx, izz), 1e-6);
}

TEST_CASE("mass: rotated geoms turn the tensor, offset geoms add the parallel-axis term", "[compile][mass]") {
  // Box 1 x 2 x 3 turned 90 deg about X: local Y lies along global Z, so Iyy and Izz swap.
  MassProps turned = geomMassProps(geom(GeomShape::Box, {1, 2, 3}, {{0, 0, 0}, quatFromEulerDeg({90, 0, 0})}));
  checkTensor(turned.inertia, diag(6.5, 2.5, 5));

  // Turned 30 deg about Z: Ixx = a cos^2 + b sin^2, Iyy = a sin^2 + b cos^2, Ixy = (a - b) sin cos.
  const double t = 30 * kPi / 180, c = std::cos(t), s = std::sin(t), ia = 6.5, ib = 5;
  MassProps z30 = geomMassProps(geom(GeomShape::Box, {1, 2, 3}, {{0, 0, 0}, quatFromEulerDeg({0, 0, 30})}));
  const double ixy = (ia - ib) * s * c;
  checkTensor(z30.inertia, {ia * c * c + ib * s * s, ixy, 0, ixy, ia * s * s + ib * c * c, 0, 0, 0, 2.5});

  // Sphere of radius 1 at (1, 2, 0): I + V (|o|^2 E - o o^T); moment = V o.
  const double v = 4.0 / 3.0 * kPi, i0 = 0.4 * v;
  MassProps moved = geomMassProps(geom(GeomShape::Sphere, {1, 0, 0}, {{1, 2, 0}, {1, 0, 0, 0}}));
  checkTensor(moved.inertia, {i0 + 4 * v, -2 * v, 0, -2 * v, i0 + v, 0, 0, 0, i0 + 5 * v});
  CHECK(moved.moment[0] == Approx(v));
  CHECK(moved.moment[1] == Approx(2 * v));
  CHECK(moved.moment[2] == 0);
}

TEST_CASE("mass: positive definiteness", "[compile][mass]") {
  CHECK(isPositiveDefinite(diag(1, 1, 1)));
  CHECK(isPositiveDefinite(diag(1e-6, 2, 3e6)));
  // Tridiagonal 2/-1: eigenvalues 2 - sqrt 2, 2, 2 + sqrt 2.
  CHECK(isPositiveDefinite({2, -1, 0, -1, 2, -1, 0, -1, 2}));
  // Positive diagonal, yet indefinite: eigenvalues -1, 5 and 1.
  CHECK_FALSE(isPositiveDefinite({2, 3, 0, 3, 2, 0, 0, 0, 1}));
  // All ones: eigenvalues 3, 0, 0 (semidefinite).
  CHECK_FALSE(isPositiveDefinite({1, 1, 1, 1, 1, 1, 1, 1, 1}));
  CHECK_FALSE(isPositiveDefinite(diag(1, 0, 1)));
  CHECK_FALSE(isPositiveDefinite(diag(-1, -2, -3)));
  CHECK_FALSE(isPositiveDefinite(diag(1, 1, -1e-9)));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK_FALSE(isPositiveDefinite(diag(1, 1, nan)));
  CHECK_FALSE(isPositiveDefinite({1, 0, nan, 0, 1, 0, nan, 0, 1}));
  CHECK_FALSE(isPositiveDefinite(diag(inf, 1, 1)));
}
