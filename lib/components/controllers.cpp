// ControllerComponents (guide 6.12): the software of an RCRobot. Each controller checks that
// the components it refers to implement the interface it needs. They do not run yet.
#include <cmath>

#include "compile/context.h"
#include "components/families.h"

namespace simbob {

namespace {

enum class ControllerKind { DriveTest, ServoTest, TwoWheelMotionControl };

constexpr LinkParam kDrive{"Drive"};
constexpr LinkParam kPosControl{"PosControl"};
constexpr LinkParam kControlLeft{"ControlLeft"};
constexpr LinkParam kControlRight{"ControlRight"};
constexpr ValueParam<double> kPeriod{"Period"};
constexpr ValueParam<double> kVariation{"Variation"};
constexpr ValueParam<double> kWheelDistance{"WheelDistance"};

/// The component behind `param`, which must implement `interface`; nullptr after an error.
const Component* target(CompileContext& ctx, const Component& c, LinkParam param, const char* interface) {
  const Link& l = c.get(param);
  if (l.comp < 0) {
    if (!l.isRef())
      ctx.error(c, std::string("parameter '") + param.name + "' is required (a Ref to a component implementing " +
                       interface + ")");
    return nullptr;
  }
  const Component& t = ctx.at(l.comp);
  if (!t.type->implements(interface)) {
    ctx.error(l, c,
              std::string("parameter '") + param.name + "' must refer to a component implementing " + interface +
                  ", but " + CompileContext::describe(t) + " does not");
    return nullptr;
  }
  return &t;
}

}  // namespace

void registerControllers(Registry& r) {
  const ParamSpec period = number(kPeriod, 0.01, "s", "loop period", Range::Positive);
  r.add({"RCDriveTest",
         Family::Controller,
         int(ControllerKind::DriveTest),
         {componentParam(kDrive, {Family::Periphery}, "", "drive to control (Ref, RCDriver)"), period,
          number(kVariation, 6.0, "1/min", "sine cycles per minute", Range::NonNegative)},
         {},
         "Sine voltage on a drive."});
  r.add({"RCServoTest",
         Family::Controller,
         int(ControllerKind::ServoTest),
         {componentParam(kPosControl, {Family::Periphery}, "", "servo to control (Ref, RCPosControl)"), period,
          number(kVariation, 6.0, "1/min", "oscillations per minute", Range::NonNegative)},
         {},
         "Moves a servo between its limits."});
  r.add({"RCTwoWheelMotionControl",
         Family::Controller,
         int(ControllerKind::TwoWheelMotionControl),
         {componentParam(kControlLeft, {Family::Periphery}, "", "left wheel velocity control (Ref, RCVelControl)"),
          componentParam(kControlRight, {Family::Periphery}, "", "right wheel velocity control (Ref, RCVelControl)"),
          number(kWheelDistance, 0.5, "m", "distance between the wheels", Range::Positive),
          number(kVariation, 0.1, "m", "wheel radius (the guide's name)", Range::Positive)},
         {},
         "Differential drive: linear and angular velocity to two wheel velocities."});
}

void lowerController(CompileContext& ctx, const Component& c) {
  switch (static_cast<ControllerKind>(c.type->kind)) {
    case ControllerKind::DriveTest:
      target(ctx, c, kDrive, "RCDriver");
      break;
    case ControllerKind::ServoTest: {
      const Component* servo = target(ctx, c, kPosControl, "RCPosControl");
      double lo, hi;
      if (servo && peripheryLimits(*servo, &lo, &hi) && !(std::isfinite(lo) && std::isfinite(hi)))
        ctx.error(c, "RCServoTest moves its servo between MinPos and MaxPos, but " + CompileContext::describe(*servo) +
                         " has an infinite limit");
      break;
    }
    case ControllerKind::TwoWheelMotionControl:
      target(ctx, c, kControlLeft, "RCVelControl");
      target(ctx, c, kControlRight, "RCVelControl");
      break;
  }
  ctx.warning(c, "controllers are read but do not run yet");
}

}  // namespace simbob
