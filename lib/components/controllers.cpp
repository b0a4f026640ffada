// ControllerComponents (guide 6.12). Parsed and kept; they run once robots land.
#include "components/families.h"

namespace simbob {

void registerControllers(Registry& r) {
  const ParamSpec period = number("Period", 0.01, "s", "loop period", Range::Positive);
  r.add({"RCDriveTest",
         Family::Controller,
         int(ControllerKind::DriveTest),
         {componentParam("Drive", {Family::Periphery}, "", "drive to control (Ref)"), period,
          number("Variation", 6.0, "1/min", "sine cycles per minute", Range::NonNegative)},
         {},
         "Sine voltage on a drive."});
  r.add({"RCServoTest",
         Family::Controller,
         int(ControllerKind::ServoTest),
         {componentParam("PosControl", {Family::Periphery}, "", "servo to control (Ref)"), period,
          number("Variation", 6.0, "1/min", "oscillations per minute", Range::NonNegative)},
         {},
         "Moves a servo between its limits."});
  r.add({"RCTwoWheelMotionControl",
         Family::Controller,
         int(ControllerKind::TwoWheelMotionControl),
         {componentParam("ControlLeft", {Family::Periphery}, "", "left wheel velocity control (Ref)"),
          componentParam("ControlRight", {Family::Periphery}, "", "right wheel velocity control (Ref)"),
          number("WheelDistance", 0.5, "m", "distance between the wheels", Range::Positive),
          number("Variation", 0.1, "m", "wheel radius (the guide's name)", Range::Positive)},
         {},
         "Differential drive: linear and angular velocity to two wheel velocities."});
}

}  // namespace simbob
