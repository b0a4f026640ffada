// Mass properties of the solid a closed triangle mesh bounds: each triangle with the reference
// point spans a signed tetrahedron; their volumes, first and second moments sum to the solid's
// (exact for polyhedra; the divergence theorem in the form of Tonon 2004 / Eberly's notes).
#include <array>
#include <vector>

#include "simbob/mesh.h"

namespace simbob {

MeshMass polyhedronMass(const std::vector<Vec3>& vertices, const std::vector<std::array<uint32_t, 3>>& triangles) {
  MeshMass out;
  if (vertices.empty() || triangles.empty()) return out;
  // Sums relative to a point near the mesh (its first vertex): far from the origin, products of
  // large coordinates would cancel and lose digits.
  const Vec3 o = vertices[0];
  double volume = 0;
  double moment[3] = {0, 0, 0};
  double cov[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // integral of x_i x_j over the solid
  for (const auto& t : triangles) {
    Vec3 a, b, c;
    for (size_t k = 0; k < 3; ++k) {
      a[k] = vertices[t[0]][k] - o[k];
      b[k] = vertices[t[1]][k] - o[k];
      c[k] = vertices[t[2]][k] - o[k];
    }
    const double v =
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6.0;
    volume += v;
    double s[3];
    for (size_t i = 0; i < 3; ++i) {
      s[i] = a[i] + b[i] + c[i];
      moment[i] += v * s[i] / 4.0;
    }
    // Tetrahedron (0, a, b, c): integral of x_i x_j = v/20 (sum over vertices of p_i p_j + s_i s_j).
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) cov[i][j] += v / 20.0 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
  }
  out.volume = volume;
  if (volume == 0) return out;
  double centre[3];
  for (size_t i = 0; i < 3; ++i) {
    centre[i] = moment[i] / volume;
    out.centre[i] = o[i] + centre[i];
  }
  // Covariance about the centroid, then the inertia tensor I = tr(C) 1 - C.
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) cov[i][j] -= volume * centre[i] * centre[j];
  const double trace = cov[0][0] + cov[1][1] + cov[2][2];
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) out.inertia[i * 3 + j] = (i == j ? trace : 0.0) - cov[i][j];
  return out;
}

}  // namespace simbob
