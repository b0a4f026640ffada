// Copies of bodies (guide 6.1.5, 6.1.6): RCImportBody reads a body from another file,
// RigidBodyClone copies a body of this scene (with its joints and everything hanging on it).
// Both lower the source body and then move all it created rigidly to their own Pose. Inside a
// clone, keys are renamed from the original's prefix to the clone's; a clone of a clone renames
// twice (innermost first), so every copy has keys of its own.
#include <algorithm>

#include "compile/context.h"
#include "components/bodies.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

constexpr int kMaxCloneDepth = 8;

constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kMotion{"Motion"};
constexpr ValueParam<std::string> kOriginal{"Original"};

/// Marks `ci` and every component written inside it (not Refs) as part of the original.
void markInside(CompileContext& ctx, int ci) {
  std::vector<int> todo{ci};
  while (!todo.empty()) {
    int i = todo.back();
    todo.pop_back();
    if (!ctx.clone.inside.insert(i).second) continue;
    const Component& c = ctx.at(i);
    for (const Slot& s : c.slots) {
      if (s.link().comp >= 0 && !s.link().isRef()) todo.push_back(s.link().comp);
      for (const Link& l : s.list())
        if (l.comp >= 0 && !l.isRef()) todo.push_back(l.comp);
    }
    for (int k : c.imported) todo.push_back(k);
  }
}

/// Moves everything created since (b0, g0, j0, f0) rigidly by t.
void moveRigidly(CompileContext& ctx, const Transform& t, size_t b0, size_t g0, size_t j0, size_t f0) {
  Model& m = ctx.model;
  for (size_t i = f0; i < m.frames.size(); ++i)  // a URDF link fixed to the world
    if (m.frames[i].body < 0) m.frames[i].offset = compose(t, m.frames[i].offset);
  for (size_t i = b0; i < m.bodies.size(); ++i) {
    BodyDef& b = m.bodies[i];
    b.pose = compose(t, b.pose);
    b.lin_vel = rotate(t.q, b.lin_vel);
    b.ang_vel = rotate(t.q, b.ang_vel);
  }
  for (size_t i = g0; i < m.geoms.size(); ++i) {
    GeomDef& g = m.geoms[i];
    if (g.body >= 0) continue;
    if (g.shape == GeomShape::Plane) {
      Vec3 n = rotate(t.q, {g.plane[0], g.plane[1], g.plane[2]});
      Vec3 p = add(t.p, rotate(t.q, scale({g.plane[0], g.plane[1], g.plane[2]}, g.plane[3])));
      g.plane = {n[0], n[1], n[2], dot(n, p)};
    } else {
      g.offset = compose(t, g.offset);
    }
  }
  for (size_t i = j0; i < m.joints.size(); ++i) {
    JointDef& j = m.joints[i];
    j.anchor = add(t.p, rotate(t.q, j.anchor));
    j.axis = rotate(t.q, j.axis);
  }
}

/// Lower `source` and move what it made so that its root lands on `pose_link` (when given);
/// `motion_link` (when given) replaces the motion of the whole copy.
Built rigidCopy(CompileContext& ctx, const Component& c, int source, const Transform* parent, const Link& pose_link,
                const Link& motion_link, bool is_clone) {
  Built out;
  size_t b0 = ctx.model.bodies.size(), g0 = ctx.model.geoms.size(), j0 = ctx.model.joints.size();
  const size_t f0 = ctx.model.frames.size();
  CompileContext::CloneScope saved = ctx.clone;
  const Transform* source_parent = parent;
  if (is_clone) {
    if (ctx.clone_depth >= kMaxCloneDepth) {
      ctx.error(c, "clones nested deeper than " + std::to_string(kMaxCloneDepth));
      return out;
    }
    // The original is lowered in the frame it hangs in (a joint's child may use local
    // coordinates), then moved to the clone's Pose.
    if (const Transform* f = ctx.parentFrame(source)) source_parent = f;
    ctx.clone.active = true;
    ctx.clone.renames.push_back({ctx.at(source).qkey, c.qkey});
    ctx.clone.memo.clear();
    ctx.clone.inside.clear();
    markInside(ctx, source);
    ++ctx.clone_depth;
  }
  Built inner = lowerBody(ctx, source, source_parent);
  if (is_clone) {
    --ctx.clone_depth;
    ctx.clone = saved;
  }
  if (!inner.ok) return out;
  out = inner;
  if (pose_link.comp >= 0) {
    Transform target;
    if (!lowerPose(ctx, pose_link, c, parent, &target)) return Built{};
    moveRigidly(ctx, compose(target, inverse(inner.frame)), b0, g0, j0, f0);
    out.frame = target;
  } else if (is_clone) {
    ctx.diag.warning(c.loc, CompileContext::describe(c) + ": no Pose given; the copy overlaps the original");
  }
  if (motion_link.comp >= 0) {
    if (ctx.model.bodies.size() == b0) {
      ctx.error(motion_link, c, "parameter 'Motion' is given but the imported body is static: it cannot move");
      return out;
    }
    BodyDef m;
    lowerMotion(ctx, motion_link, &m);
    // A rigid motion of the whole copy: v_i = v + w x (p_i - p_root).
    for (size_t i = b0; i < ctx.model.bodies.size(); ++i) {
      BodyDef& b = ctx.model.bodies[i];
      b.lin_vel = add(m.lin_vel, cross(m.ang_vel, sub(b.pose.p, out.frame.p)));
      b.ang_vel = m.ang_vel;
    }
  }
  return out;
}

}  // namespace

void registerClones(Registry& r) {
  r.add({"RCImportBody",
         Family::Body,
         int(BodyKind::Import),
         {componentParam(kPose, {Family::Pose}, "", "replaces the imported body's pose"),
          componentParam(kMotion, {Family::Motion}, "", "replaces the imported body's motion (mobile bodies only)"),
          text(kFileParam, "", "XML file whose root element <Body> holds one body; relative to this file")},
         {},
         "A body read from another file.",
         false,
         "Body"});
  r.add({"RigidBodyClone",
         Family::Body,
         int(BodyKind::Clone),
         {componentParam(kPose, {Family::Pose}, "", "pose of the copy (default: the original's)"),
          text(kOriginal, "", "fully qualified key of the body to copy")},
         {"RCRigidBodyClone"},
         "A copy of another body (with its joints and children) at a new pose.",
         true});
}

bool isClone(const Component& c) {
  return c.type->family == Family::Body && static_cast<BodyKind>(c.type->kind) == BodyKind::Clone;
}

Built lowerImportBody(CompileContext& ctx, const Component& c, const Transform* parent) {
  if (c.imported.empty()) return Built{};  // the import failed and was reported
  return rigidCopy(ctx, c, c.imported[0], parent, c.get(kPose), c.get(kMotion), false);
}

Built lowerClone(CompileContext& ctx, const Component& c, const Transform* parent) {
  const std::string& original = c.get(kOriginal);
  const Slot& slot = c.slotOf(kOriginal);
  if (original.empty()) {
    ctx.errorAt(slot, c, "parameter 'Original' is required (the fully qualified key of the body to copy)");
    return Built{};
  }
  const int f = ctx.scene.find(original);
  if (f >= 0 && f == ctx.indexOf(c)) {
    // Not a misspelling: no "did you mean" another body.
    ctx.errorAt(slot, c, "parameter 'Original' '" + original + "' names the clone itself; a clone cannot copy itself");
    return Built{};
  }
  if (f < 0 || ctx.at(f).type->family != Family::Body) {
    std::vector<std::string> keys;
    for (int i : ctx.scene.by_qkey.indices())
      if (ctx.at(i).type->family == Family::Body && ctx.at(i).qkey != c.qkey) keys.push_back(ctx.at(i).qkey);
    std::sort(keys.begin(), keys.end());  // by_qkey is unordered: the nearest of equals by key order
    std::string near = didYouMean(original, keys);
    ctx.errorAt(slot, c,
                "parameter 'Original' '" + original + "' names no body" +
                    (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    return Built{};
  }
  return rigidCopy(ctx, c, f, parent, c.get(kPose), Link{}, true);
}

}  // namespace simbob
