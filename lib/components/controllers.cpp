// ControllerComponents (guide 6.12): the software of an RCRobot. Each controller checks that
// the components it refers to implement the interface it needs and lowers to a ControllerDef;
// lib/robot runs them as parties of the run loop. RCCommandSchedule (simbob's own) sends timed
// commands to a drive, a servo or an RC2DMotionControl; RCWallStop drives an RC2DMotionControl
// forward until an RCContactSensor touches something; RCSimGoToPoint (a SimControllerComponent,
// guide 2.1) reads a body's pose and steers an RC2DMotionControl to a point; RCObstacleAvoider
// steers one away from what its RCRangeSensors see and RCWallFollower along a wall its
// RCLaserScanner sees (docs/sensors.md).
#include <algorithm>
#include <cmath>

#include "compile/context.h"
#include "components/families.h"
#include "simbob/plugin.h"

namespace simbob {

namespace {

constexpr LinkParam kDrive{"Drive"};
constexpr LinkParam kPosControl{"PosControl"};
constexpr LinkParam kControlLeft{"ControlLeft"};
constexpr LinkParam kControlRight{"ControlRight"};
constexpr ValueParam<double> kPeriod{"Period"};
constexpr ValueParam<double> kVariation{"Variation"};
constexpr ValueParam<double> kWheelDistance{"WheelDistance"};
constexpr LinkParam kTarget{"Target"};
constexpr ValueParam<std::string> kCommands{"Commands"};
constexpr LinkParam kMotion{"Motion"};
constexpr LinkParam kSensor{"Sensor"};
constexpr ValueParam<double> kSpeed{"Speed"};
constexpr LinkParam kBody{"Body"};
constexpr ValueParam<std::string> kGoal{"Target"};  // RCSimGoToPoint's point (not a Ref)
constexpr ValueParam<double> kTurnRate{"TurnRate"};
constexpr ValueParam<double> kTolerance{"Tolerance"};
constexpr ListParam kSensors{"Sensors"};
constexpr LinkParam kScanner{"Scanner"};
constexpr ValueParam<double> kDistance{"Distance"};
constexpr EnumParam kSideParam{"Side"};
const EnumTable kSide{"Side", {{"Left", 0}, {"Right", 1}}};

/// Model::actuators index of a drive or servo component, or -1 after an error.
int actuatorOf(CompileContext& ctx, const Component& c, const Link& l, const Component& drive) {
  const int i = ctx.actuatorIndex(ctx.modelKey(drive));
  if (i == -1 && !ctx.failedQuietly())
    ctx.error(l, c,
              CompileContext::describe(drive) +
                  " is not part of a construction built before this controller (put it in the ChildList of "
                  "its robot's construction)");
  return i;
}

/// Rows "time value..." of a command schedule; false after an error naming the row.
bool parseCommands(CompileContext& ctx, const Component& c, int values, std::vector<double>* out) {
  std::string err;
  const std::string& text = c.get(kCommands);
  auto nums = parseNumberList(text, &err);
  const Slot& slot = c.slotOf(kCommands);
  if (!nums) {
    ctx.errorAt(slot, c, "parameter 'Commands': " + err);
    return false;
  }
  const size_t width = static_cast<size_t>(values) + 1;
  if (nums->empty() || nums->size() % width != 0) {
    ctx.errorAt(slot, c,
                "parameter 'Commands' must hold rows of " +
                    std::string(values == 1 ? "'time value'" : "'time linear angular'") + " (" + std::to_string(width) +
                    " numbers each), got " + std::to_string(nums->size()) + " numbers");
    return false;
  }
  for (size_t row = 0; row * width < nums->size(); ++row) {
    const double t = (*nums)[row * width];
    if (t < 0 || t > 1e9) {
      ctx.errorAt(slot, c,
                  "parameter 'Commands': row " + std::to_string(row + 1) + ": time " + formatNumber(t) +
                      " s must be in [0, 1e9]");
      return false;
    }
    if (row > 0 && !(t > (*nums)[(row - 1) * width])) {
      ctx.errorAt(slot, c,
                  "parameter 'Commands': row " + std::to_string(row + 1) + ": time " + formatNumber(t) +
                      " s is not after the previous row's " + formatNumber((*nums)[(row - 1) * width]) +
                      " s (times must increase strictly)");
      return false;
    }
    for (size_t k = 1; k < width; ++k)
      if (std::fabs((*nums)[row * width + k]) > 1e9) {
        ctx.errorAt(slot, c,
                    "parameter 'Commands': row " + std::to_string(row + 1) + ": value " +
                        formatNumber((*nums)[row * width + k]) + " is beyond 1e9");
        return false;
      }
  }
  *out = std::move(*nums);
  return true;
}

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

/// Model::controllers index of an RC2DMotionControl controller (lowered now if it comes later in
/// the document), or -1 after an error.
int motionControlOf(CompileContext& ctx, const Component& c, LinkParam param) {
  const Component* t = target(ctx, c, param, "RC2DMotionControl");
  if (!t) return -1;
  lowerController(ctx, *t);
  auto it = ctx.controller_index.find(ctx.indexOf(*t));
  return it == ctx.controller_index.end() ? -1 : it->second;
}

/// Model::sensors index of the RCContactSensor behind `param`, or -1 after an error.
int sensorOf(CompileContext& ctx, const Component& c, LinkParam param) {
  const Component* t = target(ctx, c, param, "RCContactSensor");
  if (!t) return -1;
  const int i = ctx.sensorIndex(ctx.modelKey(*t));
  if (i == -1 && !ctx.failedQuietly())
    ctx.error(c.get(param), c,
              CompileContext::describe(*t) +
                  " is not part of a construction built before this controller (put it in the ChildList of "
                  "its robot's construction)");
  return i < 0 ? -1 : i;
}

/// Model::sensors index of the sensor `l` (an item of `param`) refers to, which must implement
/// `interface`; -1 after an error.
int sensorLinkOf(CompileContext& ctx, const Component& c, const Link& l, const char* param, const char* interface) {
  if (l.comp < 0) return -1;  // a bad Ref: reported where it was resolved
  const Component& t = ctx.at(l.comp);
  if (!t.type->implements(interface)) {
    ctx.error(l, c,
              std::string("parameter '") + param + "' must refer to components implementing " + interface + ", but " +
                  CompileContext::describe(t) + " does not");
    return -1;
  }
  const int i = ctx.sensorIndex(ctx.modelKey(t));
  if (i == -1 && !ctx.failedQuietly())
    ctx.error(l, c,
              CompileContext::describe(t) +
                  " is not part of a construction built before this controller (put it in the ChildList of "
                  "its robot's construction)");
  return i < 0 ? -1 : i;
}

/// Model::bodies index of the mobile body behind `param`, or -1 after an error.
int mobileBodyOf(CompileContext& ctx, const Component& c, LinkParam param) {
  const Link& l = c.get(param);
  if (l.comp < 0) {
    if (!l.isRef()) ctx.error(c, std::string("parameter '") + param.name + "' is required (a Ref to a mobile body)");
    return -1;
  }
  const Component& t = ctx.at(l.comp);
  const int i = ctx.bodyIndex(ctx.modelKey(t));
  if (i < 0 && !ctx.failedQuietly())
    ctx.error(l, c,
              std::string("parameter '") + param.name +
                  "' must refer to a mobile body built before this controller, but " + CompileContext::describe(t) +
                  " is not one");
  return i < 0 ? -1 : i;
}

/// A plug-in controller's ref `r`: appends to d->refs the Model::actuators index of the actuator
/// or the Model::sensors index of the sensor it refers to (which must offer r.interface;
/// "RCSensor": any sensor), or for "RCBody" the Model::bodies index of the mobile body, and
/// returns it, or -1 after an error.
int pluginRefOf(CompileContext& ctx, const Component& c, const PluginRef& r, PluginControllerDef* d) {
  const LinkParam param{r.name.c_str()};
  if (r.interface == "RCBody") {
    const int b = mobileBodyOf(ctx, c, param);
    d->refs.push_back(b);
    d->ref_kind.push_back(2);
    return b;
  }
  const Link& l = c.get(param);
  const Component* t = nullptr;
  if (l.comp >= 0 && r.interface == "RCSensor" && ctx.at(l.comp).type->family == Family::Periphery)
    t = &ctx.at(l.comp);
  else
    t = target(ctx, c, param, r.interface.c_str());
  int i = -1;
  const bool is_actuator = t && ctx.actuatorIndex(ctx.modelKey(*t)) != -1;
  if (is_actuator)
    i = actuatorOf(ctx, c, l, *t);
  else if (t) {
    i = ctx.sensorIndex(ctx.modelKey(*t));
    if (i == -1 && !ctx.failedQuietly())
      ctx.error(l, c,
                CompileContext::describe(*t) +
                    " is not a sensor of a construction built before this controller (put it in the ChildList of "
                    "its robot's construction)");
    i = std::max(i, -1);
  }
  d->refs.push_back(i);
  d->ref_kind.push_back(is_actuator ? 0 : 1);
  return i;
}

/// RCSimGoToPoint's Target "x z"; false after an error.
bool parseGoal(CompileContext& ctx, const Component& c, double* x, double* z) {
  std::string err;
  auto nums = parseNumberList(c.get(kGoal), &err);
  if (!nums || nums->size() != 2) {
    ctx.errorAt(c.slotOf(kGoal), c,
                "parameter 'Target' must be a point 'x z' on the ground plane (2 numbers, m)" +
                    (nums ? ", got " + std::to_string(nums->size()) + " numbers" : ": " + err));
    return false;
  }
  *x = (*nums)[0];
  *z = (*nums)[1];
  return true;
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
  TypeSpec two_wheel{
      "RCTwoWheelMotionControl",
      Family::Controller,
      int(ControllerKind::TwoWheelMotionControl),
      {componentParam(kControlLeft, {Family::Periphery}, "", "left wheel velocity control (Ref, RCVelControl)"),
       componentParam(kControlRight, {Family::Periphery}, "", "right wheel velocity control (Ref, RCVelControl)"),
       number(kWheelDistance, 0.5, "m", "distance between the wheels", Range::Positive),
       number(kVariation, 0.1, "m", "wheel radius (the guide's name)", Range::Positive)},
      {},
      "Differential drive: linear and angular velocity to two wheel velocities."};
  two_wheel.interfaces = {"RC2DMotionControl"};
  r.add(std::move(two_wheel));
  r.add({"RCCommandSchedule",
         Family::Controller,
         int(ControllerKind::CommandSchedule),
         {componentParam(kTarget, {Family::Periphery, Family::Controller}, "",
                         "drive, servo or motion control to command (Ref: RCDriver, RCPosControl, RCVelControl or "
                         "RC2DMotionControl)"),
          text(kCommands, "",
               "rows 'time value' (s, then voltage, position or velocity), or 'time linear angular' (s, m/s, rad/s) "
               "for RC2DMotionControl; times increasing; each holds until the next")},
         {},
         "Timed commands to one drive, servo or motion control.",
         true});
  r.add({"RCWallStop",
         Family::Controller,
         int(ControllerKind::WallStop),
         {componentParam(kMotion, {Family::Controller}, "", "motion control to drive (Ref, RC2DMotionControl)"),
          componentParam(kSensor, {Family::Periphery}, "", "front proximity sensor (Ref, RCContactSensor)"),
          number(kSpeed, 0.1, "m/s", "forward speed until the sensor touches", Range::NonNegative), period},
         {},
         "Drives forward until its contact sensor touches something, then stops for good."});
  r.add({"RCSimGoToPoint",
         Family::Controller,
         int(ControllerKind::GoToPoint),
         {componentParam(kMotion, {Family::Controller}, "", "motion control to steer (Ref, RC2DMotionControl)"),
          componentParam(kBody, {Family::Body}, "", "the robot's body whose pose it reads (Ref, mobile body)"),
          text(kGoal, "", "the point to reach, 'x z' on the ground plane (m; Y is up)"),
          number(kSpeed, 0.1, "m/s", "linear speed when heading straight at the target", Range::NonNegative),
          number(kTurnRate, 1.0, "rad/s", "largest angular velocity", Range::NonNegative),
          number(kTolerance, 0.05, "m", "distance to the target at which it stops for good", Range::Positive), period},
         {},
         "Sim controller: reads its body's pose and steers a motion control to a point, then stops."});
  r.add({"RCObstacleAvoider",
         Family::Controller,
         int(ControllerKind::ObstacleAvoider),
         {componentParam(kMotion, {Family::Controller}, "", "motion control to steer (Ref, RC2DMotionControl)"),
          listParam(kSensors, {Family::Periphery},
                    "range sensors on the robot's body (Refs, RCRangeSensor); each one's direction in the body's "
                    "frame (forward +X, left -Z) says which way it pushes"),
          number(kSpeed, 0.2, "m/s", "cruise speed when nothing is in range", Range::NonNegative),
          number(kTurnRate, 1.5, "rad/s", "largest angular velocity", Range::NonNegative), period},
         {},
         "Braitenberg-style: slows down and turns away from what its range sensors see (docs/sensors.md)."});
  r.add({"RCWallFollower",
         Family::Controller,
         int(ControllerKind::WallFollower),
         {componentParam(kMotion, {Family::Controller}, "", "motion control to steer (Ref, RC2DMotionControl)"),
          componentParam(kScanner, {Family::Periphery}, "",
                         "laser scanner on the robot's body, upright, covering the wall's side and the front (Ref, "
                         "RCLaserScanner)"),
          enumParam(kSideParam, ValueType::Enum, &kSide, 0, "the side the wall is kept on"),
          number(kDistance, 0.3, "m", "distance to keep between the scanner and the wall", Range::Positive),
          number(kSpeed, 0.2, "m/s", "forward speed along a straight wall", Range::Positive),
          number(kTurnRate, 1.0, "rad/s", "largest angular velocity", Range::Positive), period},
         {},
         "Follows a wall on one side at a set distance, turning at corners (docs/sensors.md)."});
}

namespace {

// ---- one lowering per kind: fills its definition, false after an error (reported) ----

/// The actuator behind `param`, which must implement `interface`: its Model index, or -1.
int actuatorParam(CompileContext& ctx, const Component& c, LinkParam param, const char* interface) {
  const Component* t = target(ctx, c, param, interface);
  return t ? actuatorOf(ctx, c, c.get(param), *t) : -1;
}

bool lowerDriveTest(CompileContext& ctx, const Component& c, DriveTestDef* d) {
  d->period = c.get(kPeriod);
  d->variation = c.get(kVariation);
  d->drive = actuatorParam(ctx, c, kDrive, "RCDriver");
  return d->drive >= 0;
}

bool lowerServoTest(CompileContext& ctx, const Component& c, ServoTestDef* d) {
  d->period = c.get(kPeriod);
  d->variation = c.get(kVariation);
  const Component* servo = target(ctx, c, kPosControl, "RCPosControl");
  double lo, hi;
  if (servo && peripheryLimits(*servo, &lo, &hi) && !(std::isfinite(lo) && std::isfinite(hi))) {
    ctx.error(c, "RCServoTest moves its servo between MinPos and MaxPos, but " + CompileContext::describe(*servo) +
                     " has an infinite limit");
    servo = nullptr;
  }
  d->servo = servo ? actuatorOf(ctx, c, c.get(kPosControl), *servo) : -1;
  return d->servo >= 0;
}

bool lowerTwoWheel(CompileContext& ctx, const Component& c, TwoWheelDef* d) {
  d->wheel_distance = c.get(kWheelDistance);
  d->wheel_radius = c.get(kVariation);
  d->left = actuatorParam(ctx, c, kControlLeft, "RCVelControl");
  d->right = actuatorParam(ctx, c, kControlRight, "RCVelControl");
  return d->left >= 0 && d->right >= 0;
}

bool lowerCommandSchedule(CompileContext& ctx, const Component& c, CommandScheduleDef* d) {
  const Link& l = c.get(kTarget);
  if (l.comp < 0) {
    if (!l.isRef())
      ctx.error(c,
                "parameter 'Target' is required (a Ref to a component implementing RCDriver, RCPosControl, "
                "RCVelControl or RC2DMotionControl)");
    return false;
  }
  const Component& t = ctx.at(l.comp);
  bool ok = true;
  if (t.type->implements("RC2DMotionControl")) {
    d->values = 2;
    lowerController(ctx, t);  // a target listed later is lowered now, so its index is known
    auto it = ctx.controller_index.find(l.comp);
    d->target = it == ctx.controller_index.end() ? -1 : it->second;
    ok = d->target >= 0;
  } else if (t.type->implements("RCDriver") || t.type->implements("RCPosControl") ||
             t.type->implements("RCVelControl")) {
    d->actuator = actuatorOf(ctx, c, l, t);
    ok = d->actuator >= 0;
  } else {
    ctx.error(l, c,
              "parameter 'Target' must refer to a component implementing RCDriver, RCPosControl, RCVelControl "
              "or RC2DMotionControl, but " +
                  CompileContext::describe(t) + " does not");
    return false;
  }
  return parseCommands(ctx, c, d->values, &d->commands) && ok;
}

bool lowerWallStop(CompileContext& ctx, const Component& c, WallStopDef* d) {
  d->period = c.get(kPeriod);
  d->speed = c.get(kSpeed);
  d->target = motionControlOf(ctx, c, kMotion);
  d->sensor = sensorOf(ctx, c, kSensor);
  return d->target >= 0 && d->sensor >= 0;
}

bool lowerPluginController(CompileContext& ctx, const Component& c, PluginControllerDef* d) {
  const PluginType& t = *c.type->plugin;
  d->type = t.name;
  d->plugin = t.plugin;
  d->plugin_type = t.c;
  d->period = c.get(kPeriod);
  bool ok = true;
  for (const PluginRef& r : t.refs)
    if (pluginRefOf(ctx, c, r, d) < 0) ok = false;
  for (const PluginNumber& n : t.numbers) d->numbers.push_back(c.get(ValueParam<double>{n.name.c_str()}));
  return ok;
}

bool lowerGoToPoint(CompileContext& ctx, const Component& c, GoToPointDef* d) {
  d->period = c.get(kPeriod);
  d->speed = c.get(kSpeed);
  d->turn_rate = c.get(kTurnRate);
  d->tolerance = c.get(kTolerance);
  d->target = motionControlOf(ctx, c, kMotion);
  d->body = mobileBodyOf(ctx, c, kBody);
  const bool goal = parseGoal(ctx, c, &d->goal_x, &d->goal_z);
  return goal && d->target >= 0 && d->body >= 0;
}

bool lowerObstacleAvoider(CompileContext& ctx, const Component& c, ObstacleAvoiderDef* d) {
  d->period = c.get(kPeriod);
  d->speed = c.get(kSpeed);
  d->turn_rate = c.get(kTurnRate);
  d->target = motionControlOf(ctx, c, kMotion);
  const std::vector<Link>& sensors = c.get(kSensors);
  if (sensors.empty()) ctx.error(c, "parameter 'Sensors' needs at least one Ref to an RCRangeSensor");
  for (const Link& l : sensors) d->sensors.push_back(sensorLinkOf(ctx, c, l, kSensors.name, "RCRangeSensor"));
  return d->target >= 0 && !sensors.empty() && !std::count(d->sensors.begin(), d->sensors.end(), -1);
}

bool lowerWallFollower(CompileContext& ctx, const Component& c, WallFollowerDef* d) {
  d->period = c.get(kPeriod);
  d->speed = c.get(kSpeed);
  d->turn_rate = c.get(kTurnRate);
  d->wall_distance = c.get(kDistance);
  d->side = c.get(kSideParam) == 0 ? 1 : -1;
  d->target = motionControlOf(ctx, c, kMotion);
  const Component* t = target(ctx, c, kScanner, "RCLaserScanner");
  d->scanner = t ? sensorLinkOf(ctx, c, c.get(kScanner), kScanner.name, "RCLaserScanner") : -1;
  return d->target >= 0 && d->scanner >= 0;
}

/// The kind's definition, lowered by its function: the one dispatch over controller kinds.
template <typename Def>
bool lowerAs(CompileContext& ctx, const Component& c, ControllerDef* d,
             bool (*lower)(CompileContext&, const Component&, Def*)) {
  Def def;
  const bool ok = lower(ctx, c, &def);
  d->def = std::move(def);
  return ok;
}

bool lowerKind(CompileContext& ctx, const Component& c, ControllerDef* d) {
  switch (static_cast<ControllerKind>(c.type->kind)) {
    case ControllerKind::DriveTest:
      return lowerAs(ctx, c, d, lowerDriveTest);
    case ControllerKind::ServoTest:
      return lowerAs(ctx, c, d, lowerServoTest);
    case ControllerKind::TwoWheelMotionControl:
      return lowerAs(ctx, c, d, lowerTwoWheel);
    case ControllerKind::CommandSchedule:
      return lowerAs(ctx, c, d, lowerCommandSchedule);
    case ControllerKind::WallStop:
      return lowerAs(ctx, c, d, lowerWallStop);
    case ControllerKind::Plugin:
      return lowerAs(ctx, c, d, lowerPluginController);
    case ControllerKind::GoToPoint:
      return lowerAs(ctx, c, d, lowerGoToPoint);
    case ControllerKind::ObstacleAvoider:
      return lowerAs(ctx, c, d, lowerObstacleAvoider);
    case ControllerKind::WallFollower:
      return lowerAs(ctx, c, d, lowerWallFollower);
  }
  return false;
}

}  // namespace

void lowerController(CompileContext& ctx, const Component& c) {
  const int ci = ctx.indexOf(c);
  if (ctx.controller_index.count(ci)) return;  // lowered already (a schedule's target, or listed twice)
  ctx.controller_index[ci] = -1;               // being lowered
  ControllerDef d;
  d.key = c.qkey;
  d.loc = c.loc;
  if (!lowerKind(ctx, c, &d)) return;
  ctx.controller_index[ci] = static_cast<int>(ctx.model.controllers.size());
  ctx.model.controllers.push_back(std::move(d));
}

}  // namespace simbob
