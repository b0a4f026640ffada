// Flat cylinder caps against box faces and against other caps: simbob's own contact manifold
// where ODE's colliders give one that cannot hold a cylinder flat (issue 42, "flat cylinders").
//
// ODE 0.16's cylinder-box collider (Croteam's, collision_cylinder_box.cpp) takes the axis of
// least penetration as the normal; when the cylinder's axis lies within 25.8 degrees of it
// (|cos| >= 0.9) it clips the box face against the cap's octagon and gives every point the same
// depth, the deepest penetration of the pair: a tilted cap is pushed up on its high side as much
// as on its low side and never levelled, and the points are where the box face is, not where
// the cap is. With fewer contacts allowed than its 8 points (MaxContacts 4, the default) it keeps
// the first ones, half of the rim. A puck dropped flat on a box bounced, turned over and came to
// rest on its rim. Debian's cylinder-cylinder collider (libccd) gives 8 points when the axes
// are exactly parallel and one otherwise: a puck on a puck rocks on that point.
//
// Here, for such a pair, the contact region is a cap's polygon (kRim points on its rim, one of
// them at the rim's deepest point) clipped against the box face, or against the other cap's
// polygon, and every point keeps its own depth; a point that does not penetrate is no contact.
// More points than MaxContacts: the deepest and the others spread evenly round the polygon.
// Everything else is ODE's collider, bit for bit: a cylinder's side against a box (wheels), the
// edge cases of ODE's cap branch that give no clipped point here, cylinders whose axes are more
// than 25.8 degrees apart or that touch side to side, and every other pair of classes.
//
// Only + - * / and sqrt per step (the rim's directions come from crCos and crSin, once): the
// same bits on every CPU.
#include <array>
#include <cmath>

#include "simbob/cr_math.h"
#include "world_impl.h"

namespace simbob {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Points on a cap's rim: ODE's octagon. Each contact costs three solver rows, and 8 points keep
/// a cap within 1 - cos(pi/8) = 7.6 % of its radius of the true circle.
constexpr int kRim = 8;
/// The largest |cos| between the normal and the cylinder's axis where ODE's cylinder-box collider
/// clips the box face against the cap (its _cldClipBoxToCylinder): the same test, the same bits.
constexpr double kCapCos = 0.9;
/// A polygon clipped by one convex polygon gains at most one point per clipping edge.
constexpr int kMaxClipped = 2 * kRim + 4;

struct V {
  double x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
/// Column k of ODE's 3x4 rotation (the body's axis k in world coordinates).
V column(const dReal* r, int k) { return {r[k], r[4 + k], r[8 + k]}; }
V position(dGeomID g) {
  const dReal* p = dGeomGetPosition(g);
  return {p[0], p[1], p[2]};
}

/// cos and sin of the rim points' angles 2 pi m / kRim, correctly rounded, computed once.
struct Rim {
  std::array<double, kRim> c, s;
};
const Rim& rim() {
  static const Rim table = [] {
    Rim t{};
    for (int m = 0; m < kRim; ++m) {
      const double angle = 2 * kPi * m / kRim;
      t.c[static_cast<size_t>(m)] = crCos(angle);
      t.s[static_cast<size_t>(m)] = crSin(angle);
    }
    return t;
  }();
  return table;
}

struct Cylinder {
  V c, axis, x;  ///< centre, unit axis (the geom's Z), the geom's X (perpendicular to the axis)
  double r, half;
};
Cylinder cylinder(dGeomID g) {
  Cylinder k{};
  const dReal* rot = dGeomGetRotation(g);
  k.c = position(g);
  k.axis = column(rot, 2);
  k.x = column(rot, 0);
  dReal r = 0, length = 0;
  dGeomCylinderGetParams(g, &r, &length);
  k.r = r;
  k.half = length / 2;
  return k;
}

/// A point of a polygon being clipped: its coordinates (u, v) in the reference plane, the point
/// of the incident surface it stands for, and that point's depth below the reference surface.
struct ClipPoint {
  double u, v;
  V p;
  double depth;
};
using Polygon = std::array<ClipPoint, kMaxClipped>;

/// Keeps the part of polygon `in` (n points) where nu * u + nv * v <= w (Sutherland-Hodgman);
/// position and depth vary linearly along an edge (the incident surface is flat).
int clip(const Polygon& in, int n, double nu, double nv, double w, Polygon& out) {
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const ClipPoint& p = in[static_cast<size_t>(i == 0 ? n - 1 : i - 1)];
    const ClipPoint& q = in[static_cast<size_t>(i)];
    const double dp = nu * p.u + nv * p.v - w;
    const double dq = nu * q.u + nv * q.v - w;
    if (k + 2 > kMaxClipped) break;  // only a polygon folded by rounding gets here: keep what fits
    if ((dp <= 0) != (dq <= 0)) {
      const double t = dp / (dp - dq);
      out[static_cast<size_t>(k++)] = {p.u + t * (q.u - p.u), p.v + t * (q.v - p.v), p.p + t * (q.p - p.p),
                                       p.depth + t * (q.depth - p.depth)};
    }
    if (dq <= 0) out[static_cast<size_t>(k++)] = q;
  }
  return k;
}

/// Clips `poly` (n points) to the rim polygon of radius r in the (u, v) plane (counter-clockwise).
int clipToRim(Polygon& poly, int n, double r) {
  const Rim& t = rim();
  Polygon other;
  for (int m = 0; m < kRim && n > 0; ++m) {
    const auto a = static_cast<size_t>(m), b = static_cast<size_t>((m + 1) % kRim);
    // Outside of edge a -> b: its outward normal (dy, -dx), through the rim point a.
    const double nu = t.s[b] - t.s[a], nv = t.c[a] - t.c[b];
    n = clip(poly, n, nu, nv, nu * r * t.c[a] + nv * r * t.s[a], other);
    poly = other;
  }
  return n;
}

/// Clips `poly` (n points) to the rectangle |u| <= hu, |v| <= hv.
int clipToRectangle(Polygon& poly, int n, double hu, double hv) {
  Polygon other;
  const double planes[4][3] = {{1, 0, hu}, {0, 1, hv}, {-1, 0, hu}, {0, -1, hv}};
  for (const auto& pl : planes) {
    if (n == 0) break;
    n = clip(poly, n, pl[0], pl[1], pl[2], other);
    poly = other;
  }
  return n;
}

/// The points of a cap's rim, kRim of them counter-clockwise about `axis` from d0 (a unit vector
/// perpendicular to it), in the (u, v) frame of a reference plane through `origin`, depth along
/// -`normal` from that plane.
int rimPolygon(V centre, V axis, V d0, double r, V origin, V eu, V ev, V normal, Polygon& poly) {
  const Rim& t = rim();
  const V d1 = cross(axis, d0);
  for (int m = 0; m < kRim; ++m) {
    const auto i = static_cast<size_t>(m);
    const V p = centre + r * (t.c[i] * d0 + t.s[i] * d1);
    const V rel = p - origin;
    poly[i] = {dot(rel, eu), dot(rel, ev), p, -dot(rel, normal)};
  }
  return kRim;
}

/// The unit vector perpendicular to `axis` towards `toward`'s component perpendicular to it, or
/// `fallback` (perpendicular to the axis) when that component vanishes (the cap is level).
V towards(V axis, V toward, V fallback) {
  const V p = toward - dot(toward, axis) * axis;
  const double len = std::sqrt(dot(p, p));
  return len > 1e-9 ? (1 / len) * p : fallback;
}

dContactGeom* at(dContactGeom* out, int i, int stride) {
  return reinterpret_cast<dContactGeom*>(reinterpret_cast<char*>(out) + static_cast<ptrdiff_t>(i) * stride);
}

/// Writes the penetrating points of `poly` as contacts of (g1, g2) with `normal` (from g2 into
/// g1): all of them, or, beyond `most`, the deepest and the others evenly spread round the
/// polygon. Returns how many.
int emit(const Polygon& poly, int n, V normal, dGeomID g1, dGeomID g2, int most, dContactGeom* out, int stride) {
  std::array<const ClipPoint*, kMaxClipped> keep{};
  int k = 0;
  for (int i = 0; i < n; ++i)
    if (poly[static_cast<size_t>(i)].depth > 0) keep[static_cast<size_t>(k++)] = &poly[static_cast<size_t>(i)];
  int deepest = 0;
  for (int i = 1; i < k; ++i)
    if (keep[static_cast<size_t>(i)]->depth > keep[static_cast<size_t>(deepest)]->depth) deepest = i;
  const int count = k < most ? k : most;
  for (int j = 0; j < count; ++j) {
    const ClipPoint& p = *keep[static_cast<size_t>((deepest + j * k / count) % k)];
    dContactGeom* c = at(out, j, stride);
    c->pos[0] = p.p.x;
    c->pos[1] = p.p.y;
    c->pos[2] = p.p.z;
    c->pos[3] = 0;
    c->normal[0] = normal.x;
    c->normal[1] = normal.y;
    c->normal[2] = normal.z;
    c->normal[3] = 0;
    c->depth = p.depth;
    c->g1 = g1;
    c->g2 = g2;
    c->side1 = -1;
    c->side2 = -1;
  }
  return count;
}

/// A cylinder's cap against a box face, `u` the normal ODE found (from the box into the
/// cylinder). Contacts of (cyl, box); 0 when no clipped point penetrates.
int capOnBox(dGeomID cyl, dGeomID box, V u, int most, dContactGeom* out, int stride) {
  const Cylinder k = cylinder(cyl);
  const dReal* rot = dGeomGetRotation(box);
  dVector3 sides;
  dGeomBoxGetLengths(box, sides);
  const V e[3] = {column(rot, 0), column(rot, 1), column(rot, 2)};
  // The box face turned most towards the cylinder; f its outward normal.
  int face = 0;
  for (int i = 1; i < 3; ++i)
    if (std::fabs(dot(e[i], u)) > std::fabs(dot(e[face], u))) face = i;
  const V f = dot(e[face], u) >= 0 ? e[face] : -1.0 * e[face];
  const V fc = position(box) + (sides[face] / 2) * f;
  const int iu = (face + 1) % 3, iv = (face + 2) % 3;
  // The cap facing the box: outward normal g, against f.
  const V g = dot(k.axis, f) > 0 ? -1.0 * k.axis : k.axis;
  const V cc = k.c + k.half * g;
  Polygon poly;
  int n = 0;
  V normal{};
  if (std::fabs(dot(f, u)) >= std::fabs(dot(k.axis, u))) {
    // The box face is the reference: the rim, from its point deepest into the box, clipped to the face.
    n = rimPolygon(cc, k.axis, towards(k.axis, -1.0 * f, k.x), k.r, fc, e[iu], e[iv], f, poly);
    n = clipToRectangle(poly, n, sides[iu] / 2, sides[iv] / 2);
    normal = f;
  } else {
    // The cap is the reference (a small box on a large cap): the box face clipped to the rim.
    const V d0 = towards(k.axis, k.x, k.x);
    const V d1 = cross(k.axis, d0);
    const double hu = sides[iu] / 2, hv = sides[iv] / 2;
    const double corner[4][2] = {{hu, hv}, {-hu, hv}, {-hu, -hv}, {hu, -hv}};
    for (int i = 0; i < 4; ++i) {
      const V p = fc + corner[i][0] * e[iu] + corner[i][1] * e[iv];
      const V rel = p - cc;
      poly[static_cast<size_t>(i)] = {dot(rel, d0), dot(rel, d1), p, -dot(rel, g)};
    }
    n = clipToRim(poly, 4, k.r);
    normal = -1.0 * g;
  }
  return emit(poly, n, normal, cyl, box, most, out, stride);
}

/// Support of a cylinder along unit vector w: the largest dot(p - centre, w) over its points.
double support(const Cylinder& k, V w) {
  const double c = dot(k.axis, w);
  const double s2 = 1 - c * c;
  return k.half * std::fabs(c) + k.r * std::sqrt(s2 > 0 ? s2 : 0);
}

/// Two cylinders whose caps face each other within kCapCos: contacts of (g1, g2), or -1 where
/// ODE's collider decides (axes further apart, side against side, or no clipped point that
/// penetrates).
int capOnCap(dGeomID g1, dGeomID g2, int most, dContactGeom* out, int stride) {
  const Cylinder a = cylinder(g1), b = cylinder(g2);
  if (std::fabs(dot(a.axis, b.axis)) < kCapCos) return -1;
  const V d = b.c - a.c;
  // Overlap along each axis, and sideways (the separating axes of two nearly parallel cylinders).
  const double overlapA = a.half + support(b, a.axis) - std::fabs(dot(d, a.axis));
  const double overlapB = b.half + support(a, b.axis) - std::fabs(dot(d, b.axis));
  const V side = d - dot(d, a.axis) * a.axis;
  const double sideLen = std::sqrt(dot(side, side));
  if (sideLen > 1e-12) {
    const V w = (1 / sideLen) * side;
    const double overlapSide = a.r + support(b, w) - sideLen;
    if (overlapSide < 0) return 0;
    if (overlapSide < (overlapA < overlapB ? overlapA : overlapB)) return -1;  // rims side by side
  }
  if (overlapA < 0 || overlapB < 0) return 0;
  // The cap of the shallower overlap is the reference; the other cap's rim is clipped to it.
  const bool refIsA = overlapA <= overlapB;
  const Cylinder& ref = refIsA ? a : b;
  const Cylinder& inc = refIsA ? b : a;
  const V toInc = inc.c - ref.c;
  const V gr = dot(toInc, ref.axis) >= 0 ? ref.axis : -1.0 * ref.axis;  // reference cap's outward normal
  const V gi = dot(toInc, inc.axis) >= 0 ? -1.0 * inc.axis : inc.axis;  // incident cap's outward normal
  const V ccr = ref.c + ref.half * gr;
  const V cci = inc.c + inc.half * gi;
  const V d0 = towards(ref.axis, ref.x, ref.x);
  const V d1 = cross(ref.axis, d0);
  Polygon poly;
  int n = rimPolygon(cci, inc.axis, towards(inc.axis, -1.0 * gr, inc.x), inc.r, ccr, d0, d1, gr, poly);
  n = clipToRim(poly, n, ref.r);
  // The normal pushes g1 away from g2: against the reference cap's outward normal when it is g1's.
  const int k = emit(poly, n, refIsA ? -1.0 * gr : gr, g1, g2, most, out, stride);
  return k > 0 ? k : -1;  // nothing clipped penetrates (rim against rim): ODE's collider decides
}

}  // namespace

int collideGeoms(dGeomID g1, dGeomID g2, int most, dContactGeom* out, int stride) {
  const int c1 = dGeomGetClass(g1), c2 = dGeomGetClass(g2);
  if (c1 == dCylinderClass && c2 == dCylinderClass) {
    const int n = capOnCap(g1, g2, most, out, stride);
    if (n >= 0) return n;
  }
  const int n = dCollide(g1, g2, most, out, stride);
  const bool cylBox = c1 == dCylinderClass && c2 == dBoxClass;
  const bool boxCyl = c1 == dBoxClass && c2 == dCylinderClass;
  if (n <= 0 || !(cylBox || boxCyl)) return n;
  // ODE's normal with the cylinder first (from the box into the cylinder); its cap branch is
  // where that normal is within kCapCos of the cylinder's axis (ODE's own test, same bits).
  const dContactGeom& first = *out;
  const V u = cylBox ? V{first.normal[0], first.normal[1], first.normal[2]}
                     : V{-first.normal[0], -first.normal[1], -first.normal[2]};
  dGeomID cyl = cylBox ? g1 : g2;
  dGeomID box = cylBox ? g2 : g1;
  if (std::fabs(dot(u, column(dGeomGetRotation(cyl), 2))) < kCapCos) return n;
  std::array<dContactGeom, kMaxClipped> mine{};
  const int k = capOnBox(cyl, box, u, most < kMaxClipped ? most : kMaxClipped, mine.data(), sizeof(dContactGeom));
  if (k == 0) return n;  // nothing clipped penetrates (a rim at a box edge): ODE's contacts stand
  for (int i = 0; i < k; ++i) {
    dContactGeom c = mine[static_cast<size_t>(i)];
    if (boxCyl) {  // as dCollide reports a swapped pair: normal reversed, geoms and sides swapped
      for (int j = 0; j < 3; ++j) c.normal[j] = -c.normal[j];
      c.g1 = g1;
      c.g2 = g2;
    }
    *at(out, i, stride) = c;
  }
  return k;
}

}  // namespace simbob
