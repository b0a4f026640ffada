// Mass properties of geoms and the positive-definiteness check of inertia tensors.
#include "compile/mass.h"

#include <cmath>

#include "simbob/transform.h"

namespace simbob {

bool isPositiveDefinite(const Mat3& m) {
  // Cholesky of the symmetric part: every pivot must be positive.
  double a = m[0];
  if (!(a > 0)) return false;
  double l10 = m[3] / std::sqrt(a), l20 = m[6] / std::sqrt(a);
  double b = m[4] - l10 * l10;
  if (!(b > 0)) return false;
  double l21 = (m[7] - l20 * l10) / std::sqrt(b);
  double c = m[8] - l20 * l20 - l21 * l21;
  return c > 0 && std::isfinite(c);
}

MassProps geomMassProps(const GeomDef& g) {
  MassProps p;
  double ixx = 0, iyy = 0, izz = 0;
  switch (g.shape) {
    case GeomShape::Box: {
      double x = g.size[0], y = g.size[1], z = g.size[2];
      p.volume = x * y * z;
      ixx = p.volume * (y * y + z * z) / 12;
      iyy = p.volume * (x * x + z * z) / 12;
      izz = p.volume * (x * x + y * y) / 12;
      break;
    }
    case GeomShape::Sphere: {
      double r = g.size[0];
      p.volume = 4.0 / 3.0 * kPi * r * r * r;
      ixx = iyy = izz = 0.4 * p.volume * r * r;
      break;
    }
    case GeomShape::Cylinder: {
      double r = g.size[0], l = g.size[1];
      p.volume = kPi * r * r * l;
      ixx = iyy = p.volume * (3 * r * r + l * l) / 12;
      izz = p.volume * r * r / 2;
      break;
    }
    case GeomShape::Capsule: {
      double r = g.size[0], l = g.size[1];
      double vc = kPi * r * r * l, vs = 4.0 / 3.0 * kPi * r * r * r;
      p.volume = vc + vs;
      // Cylinder plus two hemispheres whose centres of mass sit 3r/8 beyond the cylinder ends.
      ixx = iyy = vc * (3 * r * r + l * l) / 12 + vs * (0.4 * r * r + l * l / 4 + 3 * l * r / 8);
      izz = vc * r * r / 2 + vs * 0.4 * r * r;
      break;
    }
    case GeomShape::Plane:
      return p;
  }
  // Rotate into the body frame (R I R^T), then move to the body origin (parallel axis).
  Mat3 r = toMatrix(g.offset.q);
  double d[3] = {ixx, iyy, izz};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0;
      for (int k = 0; k < 3; ++k) s += r[i * 3 + k] * d[k] * r[j * 3 + k];
      p.inertia[i * 3 + j] = s;
    }
  const Vec3& o = g.offset.p;
  p.moment = scale(o, p.volume);
  double o2 = dot(o, o);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.inertia[i * 3 + j] += p.volume * ((i == j ? o2 : 0) - o[i] * o[j]);
  return p;
}

}  // namespace simbob
