// PoseComponents (guide 6.8).
#include "components/families.h"

namespace simbob {

void registerPoses(Registry& r) {
  r.add({"RCGlobalCoordinates",
         Family::Pose,
         int(PoseKind::Global),
         {valueParam("Pose", ValueType::Pose, Pose{}, "m, deg", "pose in global coordinates")},
         {},
         "A pose in the global frame."});
  r.add({"RCLocalCoordinates",
         Family::Pose,
         int(PoseKind::Local),
         {valueParam("Pose", ValueType::Pose, Pose{}, "m, deg", "pose relative to the parent object's frame")},
         {},
         "A pose relative to the object that owns it (joint, construction, body)."});
  r.addMacro({"Origin", Family::Pose, "RCLocalCoordinates", {}, "the parent's frame itself"});
}

}  // namespace simbob
