// MotionComponents (guide 6.9).
#include "components/families.h"

namespace simbob {

void registerMotions(Registry& r) {
  r.add({"RCGlobalMotion",
         Family::Motion,
         int(MotionKind::Global),
         {triple("LinVelocity", {0, 0, 0}, "m/s", "linear velocity of the body origin, global"),
          triple("AngVelocity", {0, 0, 0}, "rad/s", "angular velocity; norm = speed, direction = axis")},
         {},
         "Initial motion in the global frame."});
  r.addMacro({"NoMotion", Family::Motion, "RCGlobalMotion", {}, "at rest"});
}

}  // namespace simbob
