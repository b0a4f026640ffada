// GeomComponents (guide 6.5): collision shapes. Cylinders and capsules lie along local Z.
// The model-derived geoms (RCModelMatchGeom, RCModelWrapGeom) live in model_geoms.cpp.
#include <cmath>

#include "compile/context.h"
#include "components/families.h"
#include "components/geoms.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kSubGeom{"SubGeom"};
constexpr ValueParam<double> kWidth{"Width"};
constexpr ValueParam<double> kHeight{"Height"};
constexpr ValueParam<double> kDepth{"Depth"};
constexpr ValueParam<double> kRadius{"Radius"};
constexpr ValueParam<double> kLength{"Length"};
constexpr ValueParam<Triple> kScale{"Scale"};
constexpr EnumParam kHull{"Hull"};
/// Auto decides by the body (a dump writes the default as it is, so it must not be True or False).
const EnumTable kHullChoice{"Hull", {{"Auto", 0}, {"True", 1}, {"False", 2}}};

}  // namespace

void registerGeoms(Registry& r) {
  r.add({"RCTransformGeom",
         Family::Geom,
         int(GeomKind::Transform),
         {componentParam(kPose, {Family::Pose}, "", "pose of SubGeom in the body frame"),
          componentParam(kSubGeom, {Family::Geom}, "", "the transformed geom")},
         {},
         "Offsets another geom from the body origin."});
  r.add({"RCCuboidGeom",
         Family::Geom,
         int(GeomKind::Cuboid),
         {number(kWidth, 1.0, "m", "extent along X", Range::Positive),
          number(kHeight, 1.0, "m", "extent along Y", Range::Positive),
          number(kDepth, 1.0, "m", "extent along Z", Range::Positive)},
         {},
         "Box centred on the body origin."});
  r.add({"RCPlaneGeom",
         Family::Geom,
         int(GeomKind::Plane),
         {componentParam(kPose, {Family::Pose}, "", "a point of the plane; the local Y axis is its normal")},
         {},
         "Infinite plane; static bodies only."});
  r.add({"RCSphereGeom",
         Family::Geom,
         int(GeomKind::Sphere),
         {number(kRadius, 0.5, "m", "radius", Range::Positive)},
         {},
         "Sphere."});
  r.add({"RCCylinderGeom",
         Family::Geom,
         int(GeomKind::Cylinder),
         {number(kRadius, 0.5, "m", "radius", Range::Positive),
          number(kLength, 1.0, "m", "length along local Z", Range::Positive)},
         {},
         "Flat-ended cylinder along local Z."});
  r.add({"RCCappedCylinderGeom",
         Family::Geom,
         int(GeomKind::CappedCylinder),
         {number(kRadius, 0.5, "m", "radius", Range::Positive),
          number(kLength, 1.0, "m", "length of the cylindrical part along local Z (caps add Radius at each end)",
                 Range::Positive)},
         {},
         "Capsule along local Z."});
  r.add({"RCMeshGeom",
         Family::Geom,
         int(GeomKind::Mesh),
         {text(kFileParam, "", "mesh file (.stl, .obj, .dae), relative to this file; docs/meshes.md"),
          triple(kScale, {1, 1, 1}, "", "factors along the body's X, Y, Z (0.001 for a file in millimetres)"),
          enumParam(kHull, ValueType::Enum, &kHullChoice, 0,
                    "True: the convex hull of the mesh (dGeomConvex); False: its triangles (dGeomTriMesh); Auto: "
                    "the hull on a mobile body, the triangles on a static one")},
         {},
         "Collision shape from a mesh file, in the body frame (Y up; a COLLADA file's unit and up axis are "
         "applied)."});
  r.add({"RCEmptyGeom",
         Family::Geom,
         int(GeomKind::Empty),
         {},
         {},
         "No collision shape (what the NoGeom macro creates)."});
  r.addMacro({"NoGeom", Family::Geom, "RCEmptyGeom", {}, "a body without collision shape"});
}

void addPlane(CompileContext& ctx, Vec3 n, const Vec3& point, int material, const std::string& key) {
  n = scale(n, 1.0 / norm(n));
  GeomDef g;
  g.key = key;
  g.shape = GeomShape::Plane;
  g.body = -1;
  g.material = material;
  g.plane = {n[0], n[1], n[2], dot(n, point)};
  ctx.model.geoms.push_back(g);
}

void lowerGeom(CompileContext& ctx, const Link& l, const GeomTarget& t, const Transform& offset) {
  if (l.comp < 0) return;
  const Component& c = ctx.at(l.comp);
  GeomDef g;
  g.key = ctx.modelKey(*t.owner);
  g.body = t.body;
  g.static_body = t.static_body;
  g.material = t.material;
  g.offset = offset;
  g.loc = c.loc;
  switch (static_cast<GeomKind>(c.type->kind)) {
    case GeomKind::Transform: {
      Transform sub;
      lowerPose(ctx, c.get(kPose), c, &offset, &sub);
      lowerGeom(ctx, c.get(kSubGeom), t, sub);
      return;
    }
    case GeomKind::Cuboid:
      g.shape = GeomShape::Box;
      g.size = {c.get(kWidth), c.get(kHeight), c.get(kDepth)};
      break;
    case GeomKind::Sphere:
      g.shape = GeomShape::Sphere;
      g.size = {c.get(kRadius), 0, 0};
      break;
    case GeomKind::Cylinder:
      g.shape = GeomShape::Cylinder;
      g.size = {c.get(kRadius), c.get(kLength), 0};
      break;
    case GeomKind::CappedCylinder:
      g.shape = GeomShape::Capsule;
      g.size = {c.get(kRadius), c.get(kLength), 0};
      break;
    case GeomKind::Plane: {
      if (t.body >= 0) {
        ctx.error(c, "a plane is infinite and can only belong to a static body");
        return;
      }
      Transform p;
      lowerPose(ctx, c.get(kPose), c, &offset, &p);
      Transform global = compose(t.frame, p);
      addPlane(ctx, rotate(global.q, {0, 1, 0}), global.p, t.material, g.key);
      return;
    }
    case GeomKind::ModelMatch:
    case GeomKind::ModelWrap:
      lowerModelGeom(ctx, c, t, offset);
      return;
    case GeomKind::Empty:
      return;
    case GeomKind::Mesh: {
      // A moving body collides best with a hull; a static one (terrain, a room) with its triangles.
      const uint32_t hull = c.get(kHull);
      const bool use_hull = hull == 0 ? t.body >= 0 : hull == 1;
      const Triple& s = c.get(kScale);
      for (double f : s)
        if (!std::isfinite(f) || f == 0) {
          ctx.errorAt(c.slotOf(kScale), c, "parameter 'Scale' needs three finite, non-zero factors");
          return;
        }
      g.mesh = lowerMeshFile(ctx, c, c.slotOf(kFileParam), c.get(kFileParam), {s[0], s[1], s[2]});
      if (g.mesh < 0) return;
      const MeshData& mesh = *ctx.model.meshes[static_cast<size_t>(g.mesh)].data;
      if (use_hull && mesh.hull.empty()) {
        ctx.errorAt(c.slotOf(kFileParam), c, "mesh '" + mesh.file + "' has no convex hull: " + mesh.hull_problem);
        return;
      }
      g.shape = use_hull ? GeomShape::ConvexHull : GeomShape::TriMesh;
      break;
    }
  }
  // A static geom's offset is its global pose.
  if (t.body < 0) g.offset = compose(t.frame, offset);
  ctx.model.geoms.push_back(g);
}

}  // namespace simbob
