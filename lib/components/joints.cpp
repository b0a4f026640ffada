// JointComponents (guide 6.6). A joint in an RCConstruction's ChildList connects the
// construction's root body (parent) with the joint's Body (child).
#include "components/families.h"

namespace simbob {

void registerJoints(Registry& r) {
  r.setFamilyParams(
      Family::Joint,
      {componentParam("Pose", {Family::Pose}, "", "joint frame (default: the parent body's frame)"),
       componentParam("Body", {Family::Body}, "", "the child body (inline, or Ref to an existing body)")});
  r.add({"RCBallSocketJoint",
         Family::Joint,
         int(JointCompKind::BallSocket),
         {componentParam("Anchor", {Family::Pose}, "", "anchor point (default: joint origin)")},
         {},
         "Rotation about a common point."});
  r.add({"RCHingeJoint",
         Family::Joint,
         int(JointCompKind::Hinge),
         {componentParam("Hinge", {Family::Pose}, "",
                         "anchor point; its local Z axis is the rotation axis (default: joint frame)")},
         {},
         "Rotation about a common axis."});
  r.add({"RCSliderJoint",
         Family::Joint,
         int(JointCompKind::Slider),
         {componentParam("Axis", {Family::Pose}, "", "its local Z axis is the sliding axis (position ignored)")},
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
         {text("File", "", "XML file whose root element <Joint> holds one joint; relative to this file")},
         {},
         "A joint read from another file; Pose and Body, when given, replace the imported ones.",
         false,
         "Joint"});
}

}  // namespace simbob
