// BodyComponents (guide 6.1): static and mobile rigid bodies, rods and constructions. Imported
// and cloned bodies (RCImportBody, RigidBodyClone) live in clones.cpp.
#include <cmath>

#include "compile/context.h"
#include "compile/mass.h"
#include "components/bodies.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

// Bodies lowered inside one another (constructions chained through joints) recurse once per
// link; this bounds the depth.
constexpr size_t kMaxBodyChain = 500;
// Bodies + geoms + joints of the whole model (clones of clones multiply).
constexpr size_t kMaxModelItems = 100000;

constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kMotion{"Motion"};
constexpr LinkParam kGeom{"Geom"};
constexpr LinkParam kMaterial{"Material"};
constexpr LinkParam kModel{"Model"};
constexpr LinkParam kInertia{"Inertia"};
constexpr LinkParam kPos1{"Pos1"};
constexpr LinkParam kPos2{"Pos2"};
constexpr ValueParam<double> kRadius{"Radius"};
constexpr ValueParam<bool> kCapped{"Capped"};
constexpr ValueParam<bool> kHullPositions{"HullPositions"};
constexpr ValueParam<double> kMass{"Mass"};
constexpr LinkParam kSkin{"Skin"};
constexpr LinkParam kBody{"Body"};
constexpr ListParam kChildList{"ChildList"};

/// Appends a mobile body to the Model under its key; what its parent joint needs of it.
Built addMobileBody(CompileContext& ctx, const BodyDef& b) {
  Built out;
  out.index = static_cast<int>(ctx.model.bodies.size());
  out.frame = b.pose;
  out.ok = true;
  ctx.model.bodies.push_back(b);
  ctx.recordBody(b.key, out.index);
  return out;
}

Built rod(CompileContext& ctx, const Component& c, const Transform* parent) {
  Built out;
  Transform p1, p2;
  if (!lowerPose(ctx, c.get(kPos1), c, parent, &p1) || !lowerPose(ctx, c.get(kPos2), c, parent, &p2)) return out;
  Vec3 d = sub(p2.p, p1.p);
  double dist = norm(d);
  double r = c.get(kRadius);
  bool capped = c.get(kCapped);
  bool hull = c.get(kHullPositions);
  // Cylinder length between the flat ends, or of the cylindrical part of a capsule.
  double len = capped ? (hull ? dist - 2 * r : dist) : (hull ? dist : dist + 2 * r);
  if (!(dist > 0) || !(len > 0)) {
    ctx.error(c, "Pos1 and Pos2 are too close for a rod of Radius " + formatNumber(r) +
                     (capped && hull ? " with caps inside the end points" : ""));
    return out;
  }
  BodyDef b;
  b.key = ctx.modelKey(c);
  b.loc = c.loc;
  b.pose.p = scale(add(p1.p, p2.p), 0.5);
  b.pose.q = quatZTo(scale(d, 1.0 / dist));
  lowerMotion(ctx, c.get(kMotion), &b);
  int index = static_cast<int>(ctx.model.bodies.size());
  GeomDef g;
  g.key = b.key;
  g.body = index;
  g.shape = capped ? GeomShape::Capsule : GeomShape::Cylinder;
  g.size = {r, len, 0};
  g.material = lowerMaterial(ctx, c.get(kMaterial));
  MassProps mp = geomMassProps(g);
  b.mass = c.get(kMass);
  for (int k = 0; k < 9; ++k) b.inertia[k] = mp.inertia[k] * b.mass / mp.volume;
  ctx.model.geoms.push_back(g);
  VisualDef v;  // the rod draws its own shape
  v.shape = VisualDef::Cylinder;
  v.body = index;
  v.size = {r, len, 0};
  v.mask = capped ? 25 : 7;
  v.skin = lowerSkin(ctx, c.get(kSkin));
  v.key = b.key;
  ctx.model.visuals.push_back(v);
  return addMobileBody(ctx, b);
}

Built lowerUncached(CompileContext& ctx, int ci, const Transform* parent) {
  const Component& c = ctx.at(ci);
  Built out;
  switch (static_cast<BodyKind>(c.type->kind)) {
    case BodyKind::StaticRigid: {
      if (!lowerPose(ctx, c.get(kPose), c, parent, &out.frame)) return out;
      checkModelTree(ctx, c.get(kModel));
      out.static_id = ctx.static_bodies++;
      GeomTarget t{&c, -1, out.frame, lowerMaterial(ctx, c.get(kMaterial)), &c.get(kModel), out.static_id};
      lowerGeom(ctx, c.get(kGeom), t, Transform{});
      lowerVisuals(ctx, c.get(kModel), -1, out.frame, c.qkey);
      out.ok = true;
      return out;
    }
    case BodyKind::MobileRigid: {
      BodyDef b;
      b.key = ctx.modelKey(c);
      b.loc = c.loc;
      if (!lowerPose(ctx, c.get(kPose), c, parent, &b.pose)) return out;
      lowerMotion(ctx, c.get(kMotion), &b);
      checkModelTree(ctx, c.get(kModel));
      int index = static_cast<int>(ctx.model.bodies.size());
      size_t first_geom = ctx.model.geoms.size();
      GeomTarget t{&c, index, b.pose, lowerMaterial(ctx, c.get(kMaterial)), &c.get(kModel)};
      const size_t errors = ctx.diag.errors().size();
      lowerGeom(ctx, c.get(kGeom), t, Transform{});
      // A bad inertia is reported and the body kept, so that what hangs on it is checked too.
      // A body whose geoms all failed (a missing mesh file) has no volume to weigh: their errors
      // say it all.
      if (ctx.model.geoms.size() > first_geom || ctx.diag.errors().size() == errors)
        lowerInertia(ctx, c.get(kInertia), c, first_geom, &b);
      lowerVisuals(ctx, c.get(kModel), index, Transform{}, b.key);
      return addMobileBody(ctx, b);
    }
    case BodyKind::Rod:
      return rod(ctx, c, parent);
    case BodyKind::Construction: {
      const Link& root = c.get(kBody);
      if (root.comp < 0) {
        if (!root.isRef()) ctx.error(c, "parameter 'Body' (the root body) is required");  // a bad Ref is reported
        return out;
      }
      out = lowerBody(ctx, root.comp, parent);
      if (!out.ok) return out;
      // Joints first, then peripheries: a periphery refers to joints of any position in the list.
      const std::vector<Link>& children = c.get(kChildList);
      for (const Link& child : children)
        if (child.comp >= 0 && ctx.at(child.comp).type->family == Family::Joint)
          lowerJoint(ctx, child.comp, out, nullptr, nullptr);
      for (const Link& child : children)
        if (child.comp >= 0 && ctx.at(child.comp).type->family == Family::Periphery)
          lowerPeriphery(ctx, ctx.at(child.comp), out);
      return out;
    }
    case BodyKind::Import:
      return lowerImportBody(ctx, c, parent);
    case BodyKind::Clone:
      return lowerClone(ctx, c, parent);
    case BodyKind::Urdf:
      return lowerUrdfImport(ctx, c, parent);
    case BodyKind::UrdfLink:
      return lowerUrdfLink(ctx, c);
  }
  return out;
}

}  // namespace

void registerBodies(Registry& r) {
  const ParamSpec pose = componentParam(kPose, {Family::Pose}, "RCGlobalCoordinates", "initial pose");
  const ParamSpec motion = componentParam(kMotion, {Family::Motion}, "RCGlobalMotion", "initial motion");
  const ParamSpec geom = componentParam(kGeom, {Family::Geom}, "RCEmptyGeom", "collision shape");
  const ParamSpec material = componentParam(kMaterial, {Family::Material}, "RCGenericMaterial", "contact properties");
  const ParamSpec model = componentParam(kModel, {Family::Model}, "RCEmptyModel", "visible hull");
  r.add({"RCStaticRigidBody",
         Family::Body,
         int(BodyKind::StaticRigid),
         {pose, geom, material, model},
         {},
         "An immovable body: collision geometry without dynamics."});
  r.add({"RCMobileRigidBody",
         Family::Body,
         int(BodyKind::MobileRigid),
         {pose, motion, geom, componentParam(kInertia, {Family::Inertia}, "RCInertiaByGeom", "mass and inertia tensor"),
          material, model},
         {},
         "A moving rigid body."});
  r.add({"RCRodBody",
         Family::Body,
         int(BodyKind::Rod),
         {componentParam(kPos1, {Family::Pose}, "RCGlobalCoordinates", "one end (orientation ignored)"),
          componentParam(kPos2, {Family::Pose}, "RCGlobalCoordinates", "other end (orientation ignored)"),
          number(kRadius, 0.05, "m", "radius of the rod", Range::Positive),
          flag(kCapped, false, "spherical caps instead of flat ends"),
          flag(kHullPositions, true, "Pos1/Pos2 are the outermost points (else the rod extends Radius beyond them)"),
          motion, number(kMass, 1.0, "kg", "mass; inertia from the shape", Range::Positive), material,
          componentParam(kSkin, {Family::Skin}, "", "appearance of the rod")},
         {},
         "A mobile cylinder or capsule between two points.",
         true});
  r.add({"RCConstruction",
         Family::Body,
         int(BodyKind::Construction),
         {componentParam(kBody, {Family::Body}, "", "root body"),
          listParam(kChildList, {Family::Joint, Family::Periphery}, "joints and peripheries on the root body")},
         {},
         "A root body with joints (each joint's Body hangs on the root) and peripheries."});
}

Built lowerBody(CompileContext& ctx, int ci, const Transform* parent) {
  BuiltMemo& memo = ctx.clone.active && ctx.clone.inside.count(ci) ? ctx.clone.memo : ctx.memo;
  if (const Built* done = memo.find(ci)) return *done;
  if (!ctx.in_progress.insert(ci)) {
    ctx.error(ctx.at(ci), "body is part of its own construction (a joint's Body refers back to it)");
    return {};
  }
  auto giveUp = [&](const std::string& why) {
    ctx.in_progress.erase(ci);
    if (!ctx.too_big) ctx.error(ctx.at(ci), why);
    ctx.too_big = true;
    return Built{};
  };
  if (ctx.in_progress.size() > kMaxBodyChain)
    return giveUp("bodies nested more than " + std::to_string(kMaxBodyChain) +
                  " levels deep (constructions chained through joints)");
  if (ctx.model.bodies.size() + ctx.model.geoms.size() + ctx.model.joints.size() > kMaxModelItems)
    return giveUp("the scene makes more than " + std::to_string(kMaxModelItems) +
                  " bodies, geoms and joints (clones of clones?)");
  if (parent) ctx.recordParentFrame(ci, *parent);
  Built b = lowerUncached(ctx, ci, parent);
  ctx.in_progress.erase(ci);
  memo.set(ci, b);
  return b;
}

}  // namespace simbob
