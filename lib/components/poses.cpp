// PoseComponents (guide 6.8): where a body, joint, geom or camera sits.
#include "compile/context.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

enum class PoseKind { Global, Local };

constexpr ValueParam<Pose> kPose{"Pose"};

PoseKind kindOf(const Component& c) { return static_cast<PoseKind>(c.type->kind); }

}  // namespace

void registerPoses(Registry& r) {
  r.add({"RCGlobalCoordinates",
         Family::Pose,
         int(PoseKind::Global),
         {valueParam(kPose, ValueType::Pose, Pose{}, "m, deg", "pose in global coordinates")},
         {},
         "A pose in the global frame."});
  r.add({"RCLocalCoordinates",
         Family::Pose,
         int(PoseKind::Local),
         {valueParam(kPose, ValueType::Pose, Pose{}, "m, deg", "pose relative to the parent object's frame")},
         {},
         "A pose relative to the object that owns it (joint, construction, body)."});
  r.addMacro({"Origin", Family::Pose, "RCLocalCoordinates", {}, "the parent's frame itself"});
}

bool lowerPose(CompileContext& ctx, const Link& l, const Component& owner, const Transform* parent, Transform* out) {
  if (l.comp < 0) {
    *out = parent ? *parent : Transform{};
    return true;
  }
  const Component& c = ctx.at(l.comp);
  Transform local = fromPose(c.get(kPose));
  switch (kindOf(c)) {
    case PoseKind::Global:
      *out = local;
      return true;
    case PoseKind::Local:
      if (!parent) {
        // Reached only at the top level: a construction's root body sits there too, only a joint
        // gives a frame (to its own poses and to the body it carries).
        ctx.error(l, owner,
                  "RCLocalCoordinates needs a parent frame, which only a joint gives (to its own poses and the "
                  "body it carries); at the top level and for a construction's root body use RCGlobalCoordinates");
        return false;
      }
      *out = compose(*parent, local);
      return true;
  }
  return false;
}

bool isLocalPose(const CompileContext& ctx, const Link& l) {
  return l.comp < 0 || kindOf(ctx.at(l.comp)) == PoseKind::Local;
}

Transform poseValue(const CompileContext& ctx, const Link& l) {
  return l.comp < 0 ? Transform{} : fromPose(ctx.at(l.comp).get(kPose));
}

}  // namespace simbob
