// MotionComponents (guide 6.9): a body's initial velocities.
#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

enum class MotionKind { Global };

constexpr ValueParam<Triple> kLinVelocity{"LinVelocity"};
constexpr ValueParam<Triple> kAngVelocity{"AngVelocity"};

}  // namespace

void registerMotions(Registry& r) {
  r.add({"RCGlobalMotion",
         Family::Motion,
         int(MotionKind::Global),
         {triple(kLinVelocity, {0, 0, 0}, "m/s", "linear velocity of the body origin, global"),
          triple(kAngVelocity, {0, 0, 0}, "rad/s", "angular velocity; norm = speed, direction = axis")},
         {},
         "Initial motion in the global frame."});
  r.addMacro({"NoMotion", Family::Motion, "RCGlobalMotion", {}, "at rest"});
}

void lowerMotion(CompileContext& ctx, const Link& l, BodyDef* b) {
  if (l.comp < 0) return;
  const Component& c = ctx.at(l.comp);
  switch (static_cast<MotionKind>(c.type->kind)) {
    case MotionKind::Global: {
      const Triple& v = c.get(kLinVelocity);
      const Triple& w = c.get(kAngVelocity);
      b->lin_vel = {v[0], v[1], v[2]};
      b->ang_vel = {w[0], w[1], w[2]};
      break;
    }
  }
}

}  // namespace simbob
