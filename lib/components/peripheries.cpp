// PeripheryComponents (guide 6.11). Parsed and kept; they act once robots land.
#include <limits>

#include "components/families.h"

namespace simbob {

void registerPeripheries(Registry& r) {
  const ParamSpec joint = componentParam("Joint", {Family::Joint}, "", "hinge or slider joint (Ref)");
  const ParamSpec power = number("MaxPower", 10.0, "N or N m", "largest force or torque", Range::NonNegative);
  const ParamSpec vel = number("MaxVelocity", 1.0, "m/s or rad/s", "largest velocity", Range::NonNegative);
  const ParamSpec minpos =
      limit(number("MinPos", -std::numeric_limits<double>::infinity(), "m or rad", "lower limit (-Infinite: none)"));
  const ParamSpec maxpos =
      limit(number("MaxPos", std::numeric_limits<double>::infinity(), "m or rad", "upper limit (Infinite: none)"));
  r.add({"RCGenericDrive",
         Family::Periphery,
         int(PeripheryKind::GenericDrive),
         {joint, power, vel, minpos, maxpos,
          number("Stall", 0.8, "", "fraction of MaxVelocity where power starts to fade", Range::Unit)},
         {},
         "Voltage-controlled drive on a joint."});
  r.add({"RCGenericServo",
         Family::Periphery,
         int(PeripheryKind::GenericServo),
         {joint, power, vel, minpos, maxpos,
          number("Smooth", 1.0, "", "velocity reduction near the target", Range::Positive)},
         {},
         "Position-controlled drive on a joint."});
  r.add({"RCGenericVelControlledDrive",
         Family::Periphery,
         int(PeripheryKind::VelControlledDrive),
         {joint, power, vel, minpos, maxpos},
         {},
         "Velocity-controlled drive on a joint."});
  r.add({"RCProximitySensor",
         Family::Periphery,
         int(PeripheryKind::ProximitySensor),
         {componentParam("Pose", {Family::Pose}, "", "sensor pose"),
          componentParam("Geom", {Family::Geom}, "", "sensing volume (no contact forces)")},
         {},
         "Reports whether its geom touches anything."});
  r.add({"RCLocalSocketCommunicator",
         Family::Periphery,
         int(PeripheryKind::LocalSocketCommunicator),
         {flag("IsServer", false, "wait for a client instead of connecting"),
          integer("Port", 5000, "TCP port on localhost", Range::Positive)},
         {},
         "Talks to another program over a local socket."});
}

}  // namespace simbob
