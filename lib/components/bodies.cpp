// BodyComponents (guide 6.1).
#include "components/families.h"

namespace simbob {

void registerBodies(Registry& r) {
  const ParamSpec pose = componentParam("Pose", {Family::Pose}, "RCGlobalCoordinates", "initial pose");
  const ParamSpec motion = componentParam("Motion", {Family::Motion}, "RCGlobalMotion", "initial motion");
  const ParamSpec geom = componentParam("Geom", {Family::Geom}, "RCEmptyGeom", "collision shape");
  const ParamSpec material = componentParam("Material", {Family::Material}, "RCGenericMaterial", "contact properties");
  const ParamSpec model = componentParam("Model", {Family::Model}, "RCEmptyModel", "visible hull");
  r.add({"RCStaticRigidBody",
         Family::Body,
         int(BodyKind::StaticRigid),
         {pose, geom, material, model},
         {},
         "An immovable body: collision geometry without dynamics."});
  r.add({"RCMobileRigidBody",
         Family::Body,
         int(BodyKind::MobileRigid),
         {pose, motion, geom,
          componentParam("Inertia", {Family::Inertia}, "RCInertiaByGeom", "mass and inertia tensor"), material, model},
         {},
         "A moving rigid body."});
  r.add({"RCRodBody",
         Family::Body,
         int(BodyKind::Rod),
         {componentParam("Pos1", {Family::Pose}, "RCGlobalCoordinates", "one end (orientation ignored)"),
          componentParam("Pos2", {Family::Pose}, "RCGlobalCoordinates", "other end (orientation ignored)"),
          number("Radius", 0.05, "m", "radius of the rod", Range::Positive),
          flag("Capped", false, "spherical caps instead of flat ends"),
          flag("HullPositions", true, "Pos1/Pos2 are the outermost points (else the rod extends Radius beyond them)"),
          motion, number("Mass", 1.0, "kg", "mass; inertia from the shape", Range::Positive), material,
          componentParam("Skin", {Family::Skin}, "", "appearance of the rod")},
         {},
         "A mobile cylinder or capsule between two points.",
         true});
  r.add({"RCConstruction",
         Family::Body,
         int(BodyKind::Construction),
         {componentParam("Body", {Family::Body}, "", "root body"),
          listParam("ChildList", {Family::Joint, Family::Periphery}, "joints and peripheries on the root body")},
         {},
         "A root body with joints (each joint's Body hangs on the root) and peripheries."});
  r.add({"RCImportBody",
         Family::Body,
         int(BodyKind::Import),
         {componentParam("Pose", {Family::Pose}, "", "replaces the imported body's pose"),
          componentParam("Motion", {Family::Motion}, "", "replaces the imported body's motion"),
          text("File", "", "XML file whose root element <Body> holds one body; relative to this file")},
         {},
         "A body read from another file.",
         false,
         "Body"});
  r.add({"RigidBodyClone",
         Family::Body,
         int(BodyKind::Clone),
         {componentParam("Pose", {Family::Pose}, "", "pose of the copy (default: the original's)"),
          text("Original", "", "fully qualified key of the body to copy")},
         {"RCRigidBodyClone"},
         "A copy of another body (with its joints and children) at a new pose.",
         true});
}

}  // namespace simbob
