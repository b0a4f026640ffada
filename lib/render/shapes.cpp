// Model primitives as GL quads and triangles. Segment counts follow guide 6.3.3: quadrangles
// step pi / (8 Accuracy) in both spherical angles; triangles split an icosahedron's faces
// Accuracy times (at most 4).
#include "render/shapes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "simbob/transform.h"

namespace simbob::render {

namespace {

constexpr int kMaxSubdivisions = 4;

// Texture coordinate along one axis (guide 6.2.1): TexScale > 0 is the size of one mapped image
// in metres (0.5: an image every 0.5 m); < 0 is that size as a fraction of the extension (-0.5:
// the image twice across). 0 maps one texel over the whole extent.
double texCoord(double x, double extent, double scale) {
  if (scale == 0) return 0;
  return scale > 0 ? x / scale : (x / extent + 0.5) / -scale;
}

void vertex(const GlApi& gl, const Vec3& p, const Vec3& n) {
  gl.Normal3d(n[0], n[1], n[2]);
  gl.Vertex3d(p[0], p[1], p[2]);
}

// Each face of a cuboid as seen from outside: the local axis pointing right in the image and the
// one pointing up, each as (axis, sign). The four sides have +Y up; the top (+Y) is seen from
// above with -Z up, the bottom from below with +Z up (the ground's and the sky's orientation).
struct FaceAxes {
  int right, right_sign, up, up_sign;
};
// Indexed by axis * 2 + side (side 1 = the + face), the bit order of SideMask.
constexpr FaceAxes kFaceAxes[6] = {
    {2, 1, 1, 1},   // -X: right +Z, up +Y
    {2, -1, 1, 1},  // +X: right -Z, up +Y
    {0, 1, 2, 1},   // -Y: right +X, up +Z
    {0, 1, 2, -1},  // +Y: right +X, up -Z
    {0, -1, 1, 1},  // -Z: right -X, up +Y
    {0, 1, 1, 1},   // +Z: right +X, up +Y
};

// Texture coordinate of a point at `x` along a face direction that spans [lo, hi] (already
// turned by the direction's sign): TexScale > 0 repeats from the local origin, < 0 from the face's
// edge, so -1 maps the image exactly once onto the face.
double faceCoord(double x, double lo, double hi, double scale) {
  if (scale == 0) return 0;
  return scale > 0 ? x / scale : (x - lo) / (hi - lo) / -scale;
}

void cuboid(const GlApi& gl, const VisualDef& v) {
  const Vec3 lo{std::min(v.a[0], v.b[0]), std::min(v.a[1], v.b[1]), std::min(v.a[2], v.b[2])};
  const Vec3 hi{std::max(v.a[0], v.b[0]), std::max(v.a[1], v.b[1]), std::max(v.a[2], v.b[2])};
  gl.Begin(GL_QUADS);
  for (int face = 0; face < 6; ++face) {
    if (!(v.mask & (1u << face))) continue;
    const int axis = face / 2;
    const bool plus = face % 2 == 1;
    const FaceAxes& f = kFaceAxes[face];
    Vec3 n{0, 0, 0};
    n[axis] = plus ? 1 : -1;
    // Corners counter-clockwise seen from outside: (right, up) = (0,0), (1,0), (1,1), (0,1).
    const int corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& c : corners) {
      Vec3 p{0, 0, 0};
      p[axis] = plus ? hi[axis] : lo[axis];
      p[f.right] = (c[0] == 1) == (f.right_sign > 0) ? hi[f.right] : lo[f.right];
      p[f.up] = (c[1] == 1) == (f.up_sign > 0) ? hi[f.up] : lo[f.up];
      auto coord = [&](int k, int sign) {
        return sign > 0 ? faceCoord(p[k], lo[k], hi[k], v.tex_scale) : faceCoord(-p[k], -hi[k], -lo[k], v.tex_scale);
      };
      gl.TexCoord2d(coord(f.right, f.right_sign), coord(f.up, f.up_sign));
      vertex(gl, p, n);
    }
  }
  gl.End();
}

void plane(const GlApi& gl, const VisualDef& v) {
  const double ex = v.size[0], ey = v.size[1];
  auto cells = [&](double e) {
    if (v.max_cell <= 0) return 1;
    return static_cast<int>(std::min(1000.0, std::ceil(e / v.max_cell)));
  };
  const int nx = std::max(1, cells(ex)), ny = std::max(1, cells(ey));
  gl.Begin(GL_QUADS);
  gl.Normal3d(0, 0, 1);
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const double x0 = -ex / 2 + ex * i / nx, x1 = -ex / 2 + ex * (i + 1) / nx;
      const double y0 = -ey / 2 + ey * j / ny, y1 = -ey / 2 + ey * (j + 1) / ny;
      const double xs[4] = {x0, x1, x1, x0}, ys[4] = {y0, y0, y1, y1};
      for (int k = 0; k < 4; ++k) {
        gl.TexCoord2d(texCoord(xs[k], ex, v.tex_scale), texCoord(ys[k], ey, v.tex_scale));
        gl.Vertex3d(xs[k], ys[k], 0);
      }
    }
  gl.End();
}

// A point of the ellipsoid with radii r at polar angle th (from +Z) and azimuth ph, with its
// normal (the gradient of the implicit surface).
void ellipsoidVertex(const GlApi& gl, const Vec3& r, double th, double ph, const Vec3& center) {
  const Vec3 s{std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
  const Vec3 p{r[0] * s[0], r[1] * s[1], r[2] * s[2]};
  Vec3 n{s[0] / r[0], s[1] / r[1], s[2] / r[2]};
  const double len = norm(n);
  n = scale(n, 1 / len);
  gl.TexCoord2d(ph / (2 * kPi), 1 - th / kPi);  // the image's top row at the +Z pole
  vertex(gl, add(p, center), n);
}

// Quadrangles between polar angles th0..th1 (a whole ellipsoid: 0..pi) shifted by `center`.
void ellipsoidBand(const GlApi& gl, const Vec3& r, int accuracy, double th0, double th1, const Vec3& center) {
  const double step = kPi / (8.0 * accuracy);
  const int rings = std::max(1, static_cast<int>(std::lround((th1 - th0) / step)));
  const int segs = 16 * accuracy;
  gl.Begin(GL_QUADS);
  for (int i = 0; i < rings; ++i) {
    const double a = th0 + (th1 - th0) * i / rings, b = th0 + (th1 - th0) * (i + 1) / rings;
    for (int j = 0; j < segs; ++j) {
      const double p0 = 2 * kPi * j / segs, p1 = 2 * kPi * (j + 1) / segs;
      ellipsoidVertex(gl, r, a, p0, center);
      ellipsoidVertex(gl, r, b, p0, center);
      ellipsoidVertex(gl, r, b, p1, center);
      ellipsoidVertex(gl, r, a, p1, center);
    }
  }
  gl.End();
}

void subdivided(const GlApi& gl, const Vec3& r, const Vec3& a, const Vec3& b, const Vec3& c, int depth) {
  if (depth == 0) {
    for (const Vec3* s : {&a, &b, &c}) {
      const Vec3 p{r[0] * (*s)[0], r[1] * (*s)[1], r[2] * (*s)[2]};
      Vec3 n{(*s)[0] / r[0], (*s)[1] / r[1], (*s)[2] / r[2]};
      n = scale(n, 1 / norm(n));
      vertex(gl, p, n);
    }
    return;
  }
  auto mid = [](const Vec3& x, const Vec3& y) {
    Vec3 m = scale(add(x, y), 0.5);
    return scale(m, 1 / norm(m));
  };
  const Vec3 ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
  subdivided(gl, r, a, ab, ca, depth - 1);
  subdivided(gl, r, ab, b, bc, depth - 1);
  subdivided(gl, r, ca, bc, c, depth - 1);
  subdivided(gl, r, ab, bc, ca, depth - 1);
}

// The guide's triangle mode: 12 * 4^Accuracy... faces of a split polyhedron; an icosahedron
// (20 faces) split the same way.
void ellipsoidTriangles(const GlApi& gl, const VisualDef& v) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::array<Vec3, 12> p{{{-1, t, 0},
                          {1, t, 0},
                          {-1, -t, 0},
                          {1, -t, 0},
                          {0, -1, t},
                          {0, 1, t},
                          {0, -1, -t},
                          {0, 1, -t},
                          {t, 0, -1},
                          {t, 0, 1},
                          {-t, 0, -1},
                          {-t, 0, 1}}};
  for (Vec3& x : p) x = scale(x, 1 / norm(x));
  static const int kFaces[20][3] = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  gl.Begin(GL_TRIANGLES);
  for (const auto& f : kFaces)
    subdivided(gl, v.size, p[static_cast<size_t>(f[0])], p[static_cast<size_t>(f[1])], p[static_cast<size_t>(f[2])],
               std::min(v.accuracy, kMaxSubdivisions));
  gl.End();
}

void disk(const GlApi& gl, double r, double z, double nz, int segs) {
  gl.Begin(GL_TRIANGLE_FAN);
  gl.Normal3d(0, 0, nz);
  gl.TexCoord2d(0.5, 0.5);
  gl.Vertex3d(0, 0, z);
  for (int j = 0; j <= segs; ++j) {
    const double ph = 2 * kPi * (nz > 0 ? j : segs - j) / segs;
    // Seen from outside: +X right on the +Z disk, -X right on the -Z one.
    gl.TexCoord2d(0.5 + 0.5 * nz * std::cos(ph), 0.5 + 0.5 * std::sin(ph));
    gl.Vertex3d(r * std::cos(ph), r * std::sin(ph), z);
  }
  gl.End();
}

void cylinder(const GlApi& gl, const VisualDef& v) {
  const double r = v.size[0], l = v.size[1];
  const int segs = 16 * v.accuracy;
  if (v.mask & 1u) {
    gl.Begin(GL_QUAD_STRIP);
    for (int j = 0; j <= segs; ++j) {
      const double ph = 2 * kPi * j / segs, c = std::cos(ph), s = std::sin(ph);
      gl.Normal3d(c, s, 0);
      gl.TexCoord2d(v.tex_scale * j / segs, v.tex_scale2 * 0);
      gl.Vertex3d(r * c, r * s, -l / 2);
      gl.TexCoord2d(v.tex_scale * j / segs, v.tex_scale2 * l);
      gl.Vertex3d(r * c, r * s, l / 2);
    }
    gl.End();
  }
  if (v.mask & 2u) disk(gl, r, l / 2, 1, segs);
  if (v.mask & 4u) disk(gl, r, -l / 2, -1, segs);
  const Vec3 ball{r, r, r};
  if (v.mask & 8u) ellipsoidBand(gl, ball, v.accuracy, 0, kPi / 2, {0, 0, l / 2});
  if (v.mask & 16u) ellipsoidBand(gl, ball, v.accuracy, kPi / 2, kPi, {0, 0, -l / 2});
}

void cone(const GlApi& gl, const VisualDef& v) {
  const double r = v.size[0], l = v.size[1];
  const int segs = 16 * v.accuracy;
  const double k = 1 / std::hypot(l, r);  // side normal: (l cos, l sin, r) / |.|
  gl.Begin(GL_TRIANGLES);
  for (int j = 0; j < segs; ++j) {
    const double p0 = 2 * kPi * j / segs, p1 = 2 * kPi * (j + 1) / segs, pm = (p0 + p1) / 2;
    vertex(gl, {r * std::cos(p0), r * std::sin(p0), 0}, {l * k * std::cos(p0), l * k * std::sin(p0), r * k});
    vertex(gl, {r * std::cos(p1), r * std::sin(p1), 0}, {l * k * std::cos(p1), l * k * std::sin(p1), r * k});
    vertex(gl, {0, 0, l}, {l * k * std::cos(pm), l * k * std::sin(pm), r * k});
  }
  gl.End();
  if (v.mask & 1u) disk(gl, r, 0, -1, segs);
}

// One normal per face: STL and most CAD meshes are faceted, and the replay page shades them the
// same way (lib/view/viewer.js).
void meshTriangles(const GlApi& gl, const MeshData& m) {
  gl.Begin(GL_TRIANGLES);
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Vec3 n = cross(sub(b, a), sub(c, a));
    const double len = norm(n);
    if (len > 0) gl.Normal3d(n[0] / len, n[1] / len, n[2] / len);
    for (const Vec3* p : {&a, &b, &c}) gl.Vertex3d((*p)[0], (*p)[1], (*p)[2]);
  }
  gl.End();
}

void hullPolygons(const GlApi& gl, const ConvexHull& h) {
  gl.Begin(GL_TRIANGLES);
  size_t at = 0;
  for (size_t f = 0; f < h.faceCount(); ++f) {
    const unsigned n = h.polygons[at];
    gl.Normal3d(h.planes[f * 4], h.planes[f * 4 + 1], h.planes[f * 4 + 2]);
    for (unsigned k = 2; k < n; ++k)
      for (size_t i : {h.polygons[at + 1], h.polygons[at + k], h.polygons[at + k + 1]})
        gl.Vertex3d(h.points[i * 3], h.points[i * 3 + 1], h.points[i * 3 + 2]);
    at += 1 + n;
  }
  gl.End();
}

}  // namespace

void MeshLists::draw(const GlApi& gl, int mesh, bool hull) {
  if (lists_.empty()) lists_.assign(meshes_.size() * 2, 0);
  const size_t slot = static_cast<size_t>(mesh) * 2 + (hull ? 1 : 0);
  if (lists_[slot] == 0) {
    lists_[slot] = gl.GenLists(1);
    gl.NewList(lists_[slot], GL_COMPILE);
    const MeshData& m = *meshes_[static_cast<size_t>(mesh)].data;
    if (hull)
      hullPolygons(gl, m.hull);
    else
      meshTriangles(gl, m);
    gl.EndList();
  }
  gl.CallList(lists_[slot]);
}

void MeshLists::bounds(int mesh, Vec3* lo, Vec3* hi) const {
  const MeshData& m = *meshes_[static_cast<size_t>(mesh)].data;
  *lo = m.lo;
  *hi = m.hi;
}

void MeshLists::release(const GlApi& gl) {
  for (GLuint id : lists_)
    if (id) gl.DeleteLists(id, 1);
  lists_.clear();
}

void drawShape(const GlApi& gl, const VisualDef& v, MeshLists& meshes) {
  switch (v.shape) {
    case VisualDef::Cuboid:
      cuboid(gl, v);
      return;
    case VisualDef::Plane:
      plane(gl, v);
      return;
    case VisualDef::Ellipsoid:
      if (v.triangles)
        ellipsoidTriangles(gl, v);
      else
        ellipsoidBand(gl, v.size, v.accuracy, 0, kPi, {0, 0, 0});
      return;
    case VisualDef::Cylinder:
      cylinder(gl, v);
      return;
    case VisualDef::Cone:
      cone(gl, v);
      return;
    case VisualDef::Mesh:
      meshes.draw(gl, v.mesh, v.hull);
      return;
  }
}

void drawBoundingBox(const GlApi& gl, const VisualDef& v, const MeshLists& meshes) {
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  switch (v.shape) {
    case VisualDef::Cuboid:
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(v.a[i], v.b[i]);
        hi[i] = std::max(v.a[i], v.b[i]);
      }
      break;
    case VisualDef::Plane:
      lo = {-v.size[0] / 2, -v.size[1] / 2, 0};
      hi = {v.size[0] / 2, v.size[1] / 2, 0};
      break;
    case VisualDef::Ellipsoid:
      lo = {-v.size[0], -v.size[1], -v.size[2]};
      hi = v.size;
      break;
    case VisualDef::Cylinder: {
      const double caps = (v.mask & 24u) ? v.size[0] : 0;
      lo = {-v.size[0], -v.size[0], -v.size[1] / 2 - caps};
      hi = {v.size[0], v.size[0], v.size[1] / 2 + caps};
      break;
    }
    case VisualDef::Cone:
      lo = {-v.size[0], -v.size[0], 0};
      hi = {v.size[0], v.size[0], v.size[1]};
      break;
    case VisualDef::Mesh:
      meshes.bounds(v.mesh, &lo, &hi);
      break;
  }
  gl.Begin(GL_LINES);
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 0; k < 4; ++k) {
      Vec3 p = lo, q = hi;
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      p[u] = q[u] = (k & 1) ? hi[u] : lo[u];
      p[w] = q[w] = (k & 2) ? hi[w] : lo[w];
      p[axis] = lo[axis];
      q[axis] = hi[axis];
      gl.Vertex3d(p[0], p[1], p[2]);
      gl.Vertex3d(q[0], q[1], q[2]);
    }
  gl.End();
}

}  // namespace simbob::render
