// JointComponents (guide 6.6, 6.11.5). A joint in an RCConstruction's ChildList connects the
// construction's root body (parent, ODE body 1) with the joint's Body (child, ODE body 2).
#include "compile/context.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

enum class JointCompKind { BallSocket, Hinge, Slider, Fix, Import };

constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kBody{"Body"};
constexpr LinkParam kAnchor{"Anchor"};
constexpr LinkParam kHinge{"Hinge"};
constexpr LinkParam kAxis{"Axis"};

JointCompKind kindOf(const Component& c) { return static_cast<JointCompKind>(c.type->kind); }

}  // namespace

void registerJoints(Registry& r) {
  r.setFamilyParams(Family::Joint,
                    {componentParam(kPose, {Family::Pose}, "", "joint frame (default: the parent body's frame)"),
                     componentParam(kBody, {Family::Body}, "", "the child body (inline, or Ref to an existing body)")});
  r.add({"RCBallSocketJoint",
         Family::Joint,
         int(JointCompKind::BallSocket),
         {componentParam(kAnchor, {Family::Pose}, "", "anchor point (default: joint origin)")},
         {},
         "Rotation about a common point."});
  r.add({"RCHingeJoint",
         Family::Joint,
         int(JointCompKind::Hinge),
         {componentParam(kHinge, {Family::Pose}, "",
                         "anchor point; its local Z axis is the rotation axis (default: joint frame)")},
         {},
         "Rotation about a common axis."});
  r.add({"RCSliderJoint",
         Family::Joint,
         int(JointCompKind::Slider),
         {componentParam(kAxis, {Family::Pose}, "", "its local Z axis is the sliding axis (position ignored)")},
         {},
         "Translation along an axis."});
  r.add({"RCFixJoint",
         Family::Joint,
         int(JointCompKind::Fix),
         {},
         {},
         "No relative motion; keeps the relative position and orientation of the two bodies."});
  r.add({"RCImportJoint",
         Family::Joint,
         int(JointCompKind::Import),
         {text(kFileParam, "", "XML file whose root element <Joint> holds one joint; relative to this file")},
         {},
         "A joint read from another file; Pose and Body, when given, replace the imported ones.",
         false,
         "Joint"});
}

bool jointKindOf(const CompileContext& ctx, const Component& joint, JointKind* kind) {
  const Component* c = &joint;
  for (int hops = 0; kindOf(*c) == JointCompKind::Import; ++hops) {
    if (c->imported.empty() || hops > 16) return false;
    c = &ctx.at(c->imported[0]);
  }
  switch (kindOf(*c)) {
    case JointCompKind::BallSocket:
      *kind = JointKind::BallSocket;
      return true;
    case JointCompKind::Hinge:
      *kind = JointKind::Hinge;
      return true;
    case JointCompKind::Slider:
      *kind = JointKind::Slider;
      return true;
    case JointCompKind::Fix:
      *kind = JointKind::Fixed;
      return true;
    case JointCompKind::Import:
      return false;
  }
  return false;
}

void lowerJoint(CompileContext& ctx, int ji, const Built& parent, const Link* pose_override,
                const Link* body_override) {
  const Component& c = ctx.at(ji);
  if (kindOf(c) == JointCompKind::Import) {
    if (c.imported.empty()) return;  // the import failed and was reported
    const Slot& ps = c.slotOf(kPose);
    const Slot& bs = c.slotOf(kBody);
    lowerJoint(ctx, c.imported[0], parent, ps.set ? &ps.link() : pose_override, bs.set ? &bs.link() : body_override);
    return;
  }
  Transform frame;
  if (!lowerPose(ctx, pose_override ? *pose_override : c.get(kPose), c, &parent.frame, &frame)) return;
  const Link& bl = body_override ? *body_override : c.get(kBody);
  if (bl.comp < 0) {
    if (!bl.isRef()) ctx.error(c, "parameter 'Body' (the body the joint connects to) is required");
    return;
  }
  Built child = lowerBody(ctx, bl.comp, &frame);
  if (!child.ok) return;
  JointDef j;
  j.key = ctx.modelKey(c);  // renamed inside a RigidBodyClone, like the bodies
  j.loc = c.loc;
  j.body1 = parent.index;
  j.body2 = child.index;
  j.static_body = parent.index < 0 ? parent.static_id : child.static_id;
  j.anchor = frame.p;
  j.axis = rotate(frame.q, {0, 0, 1});
  if (j.body1 < 0 && j.body2 < 0) {
    ctx.error(c, "connects two static bodies; one of them must be mobile");
    return;
  }
  if (j.body1 == j.body2) {
    ctx.error(c, "connects a body with itself");
    return;
  }
  switch (kindOf(c)) {
    case JointCompKind::BallSocket: {
      j.kind = JointKind::BallSocket;
      Transform a;
      if (!lowerPose(ctx, c.get(kAnchor), c, &frame, &a)) return;
      j.anchor = a.p;
      break;
    }
    case JointCompKind::Hinge: {
      j.kind = JointKind::Hinge;
      Transform h;
      if (!lowerPose(ctx, c.get(kHinge), c, &frame, &h)) return;
      j.anchor = h.p;
      j.axis = rotate(h.q, {0, 0, 1});
      break;
    }
    case JointCompKind::Slider: {
      j.kind = JointKind::Slider;
      Transform a;
      if (!lowerPose(ctx, c.get(kAxis), c, &frame, &a)) return;
      j.axis = rotate(a.q, {0, 0, 1});
      break;
    }
    case JointCompKind::Fix:
      j.kind = JointKind::Fixed;
      break;
    case JointCompKind::Import:
      return;  // handled above
  }
  ctx.recordJoint(j.key, static_cast<int>(ctx.model.joints.size()));
  ctx.model.joints.push_back(j);
}

}  // namespace simbob
