// Model-derived GeomComponents (guide 6.5.7, 6.5.8): collision shapes taken from the body's
// model tree (models.cpp) instead of being described twice.
//  - RCModelMatchGeom: one geom per model that a geom matches exactly (cuboid, sphere, cylinder,
//    capped cylinder); any other model is an error naming it.
//  - RCModelWrapGeom: one geom of GeomType around every part. Each part is reduced to exact
//    pieces (box and plane corners, sphere and capsule-end balls, cylinder and cone rims and
//    apexes; an ellipsoid is a ball of its largest radius plus its exact extents), then:
//    Cuboid = the axis-aligned bounds in the body frame; Sphere = centred on those bounds,
//    reaching the farthest piece; Cylinder / CappedCylinder = axis through the bounds' centre
//    along Alignment, radius reaching the farthest piece from the axis, length = the bounds'
//    extent along the axis (a capsule's caps then reach beyond it). Tight for one box, sphere or
//    cylinder and for parts aligned with the axes; never smaller than the model.
#include <algorithm>
#include <cmath>

#include "compile/context.h"
#include "components/families.h"
#include "components/geoms.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

const EnumTable kWrapGeomType{"GeomType", {{"Cuboid", 0}, {"Sphere", 1}, {"Cylinder", 2}, {"CappedCylinder", 3}}};
const EnumTable kAlignment{"Alignment", {{"XAligned", 0}, {"YAligned", 1}, {"ZAligned", 2}}};

constexpr ValueParam<bool> kIgnoreChilds{"IgnoreChilds"};
constexpr EnumParam kGeomType{"GeomType"};
constexpr EnumParam kAlignmentParam{"Alignment"};

// Exact pieces of a part, body frame: a ball (radius 0: a point) or a disk (rim radius r, normal n).
struct Piece {
  Vec3 c;
  double r = 0;
  bool disk = false;
  Vec3 n{0, 0, 1};
  Vec3 ext{0, 0, 0};  // extra half-extents (ellipsoids: exact bounds beyond the ball's)
};

void piecesOf(CompileContext& ctx, const ModelPart& p, std::vector<Piece>* out) {
  ModelShape s = modelShape(*p.model);
  auto at = [&](const Vec3& local) { return add(p.frame.p, rotate(p.frame.q, local)); };
  Vec3 z = rotate(p.frame.q, {0, 0, 1});
  switch (s.kind) {
    case ModelShape::None:
      return;
    case ModelShape::Box:
      for (int k = 0; k < 8; ++k)
        out->push_back(
            {at({s.center[0] + (k & 1 ? 0.5 : -0.5) * s.size[0], s.center[1] + (k & 2 ? 0.5 : -0.5) * s.size[1],
                 s.center[2] + (k & 4 ? 0.5 : -0.5) * s.size[2]})});
      return;
    case ModelShape::Plane:
      for (int k = 0; k < 4; ++k)
        out->push_back({at({(k & 1 ? 0.5 : -0.5) * s.size[0], (k & 2 ? 0.5 : -0.5) * s.size[1], 0})});
      return;
    case ModelShape::Ellipsoid: {
      Piece e{at({0, 0, 0}), std::max({s.size[0], s.size[1], s.size[2]})};
      // Exact half-extents along the body axes: sqrt(sum_j (R_ij r_j)^2).
      Mat3 r = toMatrix(p.frame.q);
      for (size_t i = 0; i < 3; ++i) {
        const double x = r[i * 3] * s.size[0], y = r[i * 3 + 1] * s.size[1], z = r[i * 3 + 2] * s.size[2];
        e.ext[i] = std::sqrt(x * x + y * y + z * z);
      }
      out->push_back(e);
      return;
    }
    case ModelShape::Cylinder:
      out->push_back({at({0, 0, -s.size[1] / 2}), s.size[0], true, z});
      out->push_back({at({0, 0, s.size[1] / 2}), s.size[0], true, z});
      return;
    case ModelShape::Capsule:
      out->push_back({at({0, 0, -s.size[1] / 2}), s.size[0]});
      out->push_back({at({0, 0, s.size[1] / 2}), s.size[0]});
      return;
    case ModelShape::Cone:  // base at z = 0, apex at z = Length
      out->push_back({at({0, 0, 0}), s.size[0], true, z});
      out->push_back({at({0, 0, s.size[1]})});
      return;
    case ModelShape::Mesh: {  // the corners of its hull (all its vertices when it has none)
      const int mi = lowerModelMesh(ctx, *p.model);
      if (mi < 0) return;
      const MeshData& mesh = *ctx.model.meshes[static_cast<size_t>(mi)].data;
      if (mesh.hull.empty())
        for (const Vec3& v : mesh.vertices) out->push_back({at(v)});
      for (size_t i = 0; i < mesh.hull.pointCount(); ++i)
        out->push_back({at({mesh.hull.points[i * 3], mesh.hull.points[i * 3 + 1], mesh.hull.points[i * 3 + 2]})});
      return;
    }
  }
}

// Half-extent of a piece along body axis i.
double halfExtent(const Piece& p, int i) {
  if (p.disk) return p.r * std::sqrt(std::max(0.0, 1 - p.n[i] * p.n[i]));
  return p.ext[i] > 0 ? p.ext[i] : p.r;
}

// Farthest distance from point o to the piece.
double farthest(const Piece& p, const Vec3& o) {
  Vec3 d = sub(p.c, o);
  if (!p.disk) return norm(d) + p.r;
  double a = dot(d, p.n);
  double rho = norm(sub(d, scale(p.n, a)));
  return std::hypot(a, rho + p.r);
}

// Farthest distance from the line through o along unit u to the piece: the centre's distance
// plus the radius (exact for balls and for disks facing along u; an upper bound otherwise).
double farthestFromAxis(const Piece& p, const Vec3& o, const Vec3& u) {
  Vec3 d = sub(p.c, o);
  return norm(sub(d, scale(u, dot(d, u)))) + p.r;
}

void match(CompileContext& ctx, const Component& geom, const std::vector<ModelPart>& parts, const GeomDef& g,
           const GeomTarget& t) {
  bool any = false;
  for (const ModelPart& p : parts) {
    ModelShape s = modelShape(*p.model);
    GeomDef d = g;
    d.offset = p.frame;
    switch (s.kind) {
      case ModelShape::None:
        continue;
      case ModelShape::Box:
        if (s.size[0] <= 0 || s.size[1] <= 0 || s.size[2] <= 0) {
          ctx.error(*p.model, "a cuboid with zero extent cannot be matched by a geom");
          continue;
        }
        d.shape = GeomShape::Box;
        d.size = s.size;
        d.offset = compose(p.frame, Transform{s.center, {1, 0, 0, 0}});
        break;
      case ModelShape::Ellipsoid:
        if (s.size[0] != s.size[1] || s.size[1] != s.size[2]) {
          ctx.error(geom,
                    "RCModelMatchGeom: ellipsoid '" + p.model->qkey + "' has unequal radii; only a sphere matches");
          continue;
        }
        d.shape = GeomShape::Sphere;
        d.size = {s.size[0], 0, 0};
        break;
      case ModelShape::Cylinder:
      case ModelShape::Capsule:
        d.shape = s.kind == ModelShape::Capsule ? GeomShape::Capsule : GeomShape::Cylinder;
        d.size = s.size;
        break;
      case ModelShape::Mesh:
        // A mesh is matched by its convex hull (what a moving body collides with best).
        d.mesh = lowerModelMesh(ctx, *p.model);
        if (d.mesh < 0) continue;
        if (ctx.model.meshes[static_cast<size_t>(d.mesh)].data->hull.empty()) {
          ctx.error(geom, "RCModelMatchGeom: mesh model '" + p.model->qkey + "' has no convex hull: " +
                              ctx.model.meshes[static_cast<size_t>(d.mesh)].data->hull_problem);
          continue;
        }
        d.shape = GeomShape::ConvexHull;
        break;
      case ModelShape::Plane:
      case ModelShape::Cone:
        ctx.error(geom, "RCModelMatchGeom: no geom matches " + p.model->type->name + " '" + p.model->qkey +
                            "'; use RCModelWrapGeom");
        continue;
    }
    any = true;
    if (d.body < 0) d.offset = compose(t.frame, d.offset);
    ctx.model.geoms.push_back(d);
  }
  if (!any && ctx.diag.ok())
    ctx.error(geom, "RCModelMatchGeom: the body '" + t.owner->qkey + "' has no model to match");
}

void wrap(CompileContext& ctx, const Component& geom, const std::vector<ModelPart>& parts, const GeomDef& g,
          const GeomTarget& t) {
  std::vector<Piece> pieces;
  for (const ModelPart& p : parts) piecesOf(ctx, p, &pieces);
  if (pieces.empty()) {
    ctx.error(geom, "RCModelWrapGeom: the body '" + t.owner->qkey + "' has no visible model to wrap");
    return;
  }
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Piece& p : pieces)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p.c[i] - halfExtent(p, i));
      hi[i] = std::max(hi[i], p.c[i] + halfExtent(p, i));
    }
  Vec3 center = scale(add(lo, hi), 0.5), half = scale(sub(hi, lo), 0.5);
  GeomDef d = g;
  d.offset = Transform{center, {1, 0, 0, 0}};
  const uint32_t type = geom.get(kGeomType);
  switch (type) {
    case 0:
      d.shape = GeomShape::Box;
      d.size = scale(half, 2.0);
      break;
    case 1: {
      double r = 0;
      for (const Piece& p : pieces) r = std::max(r, farthest(p, center));
      d.shape = GeomShape::Sphere;
      d.size = {r, 0, 0};
      break;
    }
    default: {
      // Cylinders lie along local Z: rotate Z onto the chosen axis.
      int axis = static_cast<int>(geom.get(kAlignmentParam));
      Vec3 u{0, 0, 0};
      u[static_cast<size_t>(axis)] = 1;
      double r = 0;
      for (const Piece& p : pieces) r = std::max(r, farthestFromAxis(p, center, u));
      d.shape = type == 3 ? GeomShape::Capsule : GeomShape::Cylinder;
      d.size = {r, 2 * half[static_cast<size_t>(axis)], 0};
      if (axis == 0) d.offset.q = quatAxisAngle({0, 1, 0}, kPi / 2);
      if (axis == 1) d.offset.q = quatAxisAngle({1, 0, 0}, -kPi / 2);
      break;
    }
  }
  if (d.body < 0) d.offset = compose(t.frame, d.offset);
  ctx.model.geoms.push_back(d);
}

}  // namespace

void registerModelGeoms(Registry& r) {
  r.add({"RCModelMatchGeom",
         Family::Geom,
         int(GeomKind::ModelMatch),
         {flag(kIgnoreChilds, false, "use only the root model")},
         {"RCMoelMatchGeom"},
         "The geom that exactly matches the body's model (cuboid, sphere, cylinder, capped cylinder).",
         true});
  r.add({"RCModelWrapGeom",
         Family::Geom,
         int(GeomKind::ModelWrap),
         {enumParam(kGeomType, ValueType::Enum, &kWrapGeomType, 0, "shape that wraps the model"),
          enumParam(kAlignmentParam, ValueType::Enum, &kAlignment, 2, "axis of a cylindric wrap"),
          flag(kIgnoreChilds, false, "wrap only the root model")},
         {"RCMoelWrapGeom"},
         "A geom of GeomType around the body's whole model (docs/scene-format.md says how tight).",
         true});
}

void lowerModelGeom(CompileContext& ctx, const Component& geom, const GeomTarget& t, const Transform& offset) {
  GeomDef g;
  g.key = ctx.modelKey(*t.owner);
  g.body = t.body;
  g.static_body = t.static_body;
  g.material = t.material;
  std::vector<ModelPart> parts;
  static const Link kNone;
  if (!collectModelParts(ctx, t.model ? *t.model : kNone, offset, !geom.get(kIgnoreChilds), &parts)) {
    if (parts.size() >= kMaxModelParts)
      ctx.error(geom, "the model of '" + t.owner->qkey + "' has more than " + std::to_string(kMaxModelParts) +
                          " parts (model Refs shared over and over?)");
    return;
  }
  if (static_cast<GeomKind>(geom.type->kind) == GeomKind::ModelWrap)
    wrap(ctx, geom, parts, g, t);
  else
    match(ctx, geom, parts, g, t);
}

}  // namespace simbob
