// PeripheryComponents (guide 6.11): drives, servos and sensors on the joints of a construction,
// and the socket communicator. Each type names the interfaces it offers to controllers
// (guide 6.12): RCDriver, RCPosControl, RCVelControl, RCContactSensor. simbob's own sensors
// (range, scanner, IMU, encoder) are periphery types in files of their own (families.h).
// Drives and servos lower to Model::actuators (lib/physics/actuators.cpp makes them act); the
// proximity sensor to Model::sensors and sensor geoms (lib/physics/sensors.cpp); the socket
// communicator to Model::sockets (lib/robot/socket_peer.cpp talks to its peer).
#include <cmath>
#include <filesystem>
#include <limits>

#include "compile/context.h"
#include "components/families.h"
#include "simbob/transform.h"

namespace simbob {

namespace {

constexpr LinkParam kJoint{"Joint"};
constexpr ValueParam<double> kMaxPower{"MaxPower"};
constexpr ValueParam<double> kMaxVelocity{"MaxVelocity"};
constexpr ValueParam<double> kMinPos{"MinPos"};
constexpr ValueParam<double> kMaxPos{"MaxPos"};
constexpr ValueParam<double> kStall{"Stall"};
constexpr ValueParam<double> kSmooth{"Smooth"};
constexpr LinkParam kPose{"Pose"};
constexpr LinkParam kGeom{"Geom"};
constexpr ValueParam<bool> kIsServer{"IsServer"};
constexpr ValueParam<int64_t> kPort{"Port"};
constexpr ValueParam<double> kPeriod{"Period"};
constexpr ValueParam<std::string> kController{"Controller"};

constexpr int64_t kMaxPort = 65535;
constexpr double kPi = 3.14159265358979323846;

PeripheryKind kindOf(const Component& c) { return static_cast<PeripheryKind>(c.type->kind); }

TypeSpec offering(TypeSpec t, std::vector<std::string> interfaces) {
  t.interfaces = std::move(interfaces);
  return t;
}

/// Drives and servos: the Joint must be a hinge (angular) or a slider (linear); limits ordered.
/// Returns the joint's Model index, or -1 after an error.
int checkJointDrive(CompileContext& ctx, const Component& c) {
  const Link& jl = c.get(kJoint);
  if (jl.comp < 0) {
    if (!jl.isRef()) ctx.error(c, "parameter 'Joint' is required (a Ref to the hinge or slider joint it drives)");
    return -1;
  }
  const Component& joint = ctx.at(jl.comp);
  JointKind kind;
  if (joint.type->family != Family::Joint || !jointKindOf(ctx, joint, &kind)) return -1;  // reported by the loader
  bool ok = true;
  if (kind != JointKind::Hinge && kind != JointKind::Slider) {
    ctx.error(jl, c,
              "parameter 'Joint' must be a hinge or slider joint, but " + CompileContext::describe(joint) +
                  " is not (guide 6.11)");
    ok = false;
  }
  double lo = c.get(kMinPos), hi = c.get(kMaxPos);
  if (std::isfinite(lo) && std::isfinite(hi) && lo > hi) {
    ctx.errorAt(c.slotOf(kMaxPos), c,
                "MinPos (" + formatNumber(lo) + ") is greater than MaxPos (" + formatNumber(hi) + ")");
    ok = false;
  }
  // ODE keeps hinge stops within [-pi, pi] of the start pose.
  if (kind == JointKind::Hinge && ((std::isfinite(lo) && lo < -kPi) || (std::isfinite(hi) && hi > kPi))) {
    ctx.error(c, "hinge limits MinPos/MaxPos must lie within [-pi, pi] rad (or be infinite), got " + formatNumber(lo) +
                     " .. " + formatNumber(hi));
    ok = false;
  }
  if (!ok) return -1;
  // Joints of the construction are lowered before its peripheries; a joint elsewhere must be too.
  const int index = ctx.jointIndex(ctx.modelKey(joint));
  if (index < 0 && !ctx.failedQuietly())
    ctx.error(jl, c,
              "parameter 'Joint' refers to " + CompileContext::describe(joint) +
                  ", which is not built before this periphery: put the periphery in the ChildList of the "
                  "construction that holds the joint (after it)");
  return index;
}

void lowerActuator(CompileContext& ctx, const Component& c, ActuatorDef::Kind kind) {
  const int joint = checkJointDrive(ctx, c);
  if (joint < 0) {
    ctx.recordActuator(ctx.modelKey(c), kFailedActuator);  // controllers referring to it say nothing more
    return;
  }
  ActuatorDef a;
  a.key = ctx.modelKey(c);
  a.loc = c.loc;
  a.kind = kind;
  a.joint = joint;
  a.max_power = c.get(kMaxPower);
  a.max_velocity = c.get(kMaxVelocity);
  a.min_pos = c.get(kMinPos);
  a.max_pos = c.get(kMaxPos);
  if (kind == ActuatorDef::Drive) a.stall = c.get(kStall);
  if (kind == ActuatorDef::Servo) a.smooth = c.get(kSmooth);
  ctx.recordActuator(a.key, static_cast<int>(ctx.model.actuators.size()));
  ctx.model.actuators.push_back(a);
}

/// RCProximitySensor: its Geom, posed by Pose (local coordinates: relative to the body the
/// construction's root is; global: in the world), becomes sensor geoms on that body.
void lowerSensor(CompileContext& ctx, const Component& c, const Built& parent) {
  const std::string key = ctx.modelKey(c);
  if (!parent.ok) return;
  if (c.get(kGeom).comp < 0) {
    if (!c.get(kGeom).isRef()) ctx.error(c, "parameter 'Geom' is required (the volume the sensor watches)");
    ctx.recordSensor(key, kFailedActuator);
    return;
  }
  Transform pose;
  if (!lowerPose(ctx, c.get(kPose), c, &parent.frame, &pose)) {
    ctx.recordSensor(key, kFailedActuator);
    return;
  }
  SensorDef s;
  s.key = key;
  s.loc = c.loc;
  s.kind = SensorKind::Proximity;
  s.body = parent.index;
  const size_t first = ctx.model.geoms.size();
  static const Link kNoModel;
  GeomTarget t{&c, parent.index, parent.frame, 0, &kNoModel};
  lowerGeom(ctx, c.get(kGeom), t, compose(inverse(parent.frame), pose));
  for (size_t gi = first; gi < ctx.model.geoms.size(); ++gi) {
    GeomDef& g = ctx.model.geoms[gi];
    if (g.shape == GeomShape::Plane) {
      ctx.error(c, "a proximity sensor's Geom cannot be a plane (it would touch half the world)");
      ctx.model.geoms.resize(first);
      ctx.recordSensor(key, kFailedActuator);
      return;
    }
    g.sensor = true;
    s.geoms.push_back(static_cast<int>(gi));
  }
  if (s.geoms.empty()) {
    if (!ctx.failedQuietly()) ctx.error(c, "parameter 'Geom' gives no volume to watch");
    ctx.recordSensor(key, kFailedActuator);
    return;
  }
  ctx.recordSensor(key, static_cast<int>(ctx.model.sensors.size()));
  ctx.model.sensors.push_back(std::move(s));
}

}  // namespace

bool lowerSensorPose(CompileContext& ctx, const Component& c, const Link& pose, const Built& parent, Transform* out) {
  Transform global;
  if (!lowerPose(ctx, pose, c, &parent.frame, &global)) return false;
  *out = parent.index >= 0 ? compose(inverse(parent.frame), global) : global;
  return true;
}

bool checkSensorPeriod(CompileContext& ctx, const Component& c, const Slot& slot, double period) {
  if (period == 0 || (period >= 1e-9 && period <= 1e9)) return true;
  ctx.errorAt(slot, c,
              "parameter 'Period' must be 0 (every step) or between 1e-9 and 1e9 s, got " + formatNumber(period));
  return false;
}

void registerPeripheries(Registry& r) {
  const ParamSpec joint = componentParam(kJoint, {Family::Joint}, "", "hinge or slider joint (Ref)");
  const ParamSpec power = number(kMaxPower, 10.0, "N or N m", "largest force or torque", Range::NonNegative);
  const ParamSpec vel = number(kMaxVelocity, 1.0, "m/s or rad/s", "largest velocity", Range::NonNegative);
  const ParamSpec minpos =
      limit(number(kMinPos, -std::numeric_limits<double>::infinity(), "m or rad", "lower limit (-Infinite: none)"));
  const ParamSpec maxpos =
      limit(number(kMaxPos, std::numeric_limits<double>::infinity(), "m or rad", "upper limit (Infinite: none)"));
  r.add(offering({"RCGenericDrive",
                  Family::Periphery,
                  int(PeripheryKind::GenericDrive),
                  {joint, power, vel, minpos, maxpos,
                   number(kStall, 0.8, "", "fraction of MaxVelocity where power starts to fade", Range::Unit)},
                  {},
                  "Voltage-controlled drive on a joint."},
                 {"RCDriver"}));
  r.add(offering(
      {"RCGenericServo",
       Family::Periphery,
       int(PeripheryKind::GenericServo),
       {joint, power, vel, minpos, maxpos,
        number(kSmooth, 1.0, "s", "time constant of the final approach (v = error / Smooth)", Range::Positive)},
       {},
       "Position-controlled drive on a joint."},
      {"RCPosControl"}));
  r.add(offering({"RCGenericVelControlledDrive",
                  Family::Periphery,
                  int(PeripheryKind::VelControlledDrive),
                  {joint, power, vel, minpos, maxpos},
                  {},
                  "Velocity-controlled drive on a joint."},
                 {"RCVelControl"}));
  r.add(offering({"RCProximitySensor",
                  Family::Periphery,
                  int(PeripheryKind::ProximitySensor),
                  {componentParam(kPose, {Family::Pose}, "",
                                  "pose of the geom: local coordinates relative to the construction's root body "
                                  "(default: its frame), or global"),
                   componentParam(kGeom, {Family::Geom}, "", "sensing volume (no contact forces)")},
                  {},
                  "Reports whether its geom touches anything."},
                 {"RCContactSensor"}));
  r.add({"RCLocalSocketCommunicator",
         Family::Periphery,
         int(PeripheryKind::LocalSocketCommunicator),
         {flag(kIsServer, false, "wait for a client instead of connecting"),
          integer(kPort, 5000, "TCP port on 127.0.0.1 (1 to 65535; run --port-offset adds to it)", Range::Positive),
          number(kPeriod, 0.01, "s", "simulated time between exchanges with the peer (simbob's own)", Range::Positive),
          text(kController, "",
               "command line of the peer program simbob starts itself, run in this file's folder "
               "(docs/socket-protocol.md#controllers-started-by-simbob; run --controller overrides)")},
         {},
         "Lets another program on this computer read the robot and command it, in lockstep "
         "(docs/socket-protocol.md)."});
}

bool peripheryLimits(const Component& c, double* lo, double* hi) {
  switch (kindOf(c)) {
    case PeripheryKind::GenericDrive:
    case PeripheryKind::GenericServo:
    case PeripheryKind::VelControlledDrive:
      *lo = c.get(kMinPos);
      *hi = c.get(kMaxPos);
      return true;
    case PeripheryKind::ProximitySensor:
    case PeripheryKind::LocalSocketCommunicator:
    case PeripheryKind::RangeSensor:
    case PeripheryKind::LaserScanner:
    case PeripheryKind::ImuSensor:
    case PeripheryKind::Encoder:
    case PeripheryKind::CameraSensor:
    case PeripheryKind::PluginSensor:
    case PeripheryKind::PluginActuator:
    case PeripheryKind::UrdfDrive:  // its limits are the URDF's, in the Model (ActuatorDef)
      return false;
  }
  return false;
}

void lowerPeriphery(CompileContext& ctx, const Component& c, const Built& parent) {
  switch (kindOf(c)) {
    case PeripheryKind::GenericDrive:
      lowerActuator(ctx, c, ActuatorDef::Drive);
      break;
    case PeripheryKind::GenericServo:
      lowerActuator(ctx, c, ActuatorDef::Servo);
      break;
    case PeripheryKind::VelControlledDrive:
      lowerActuator(ctx, c, ActuatorDef::VelDrive);
      break;
    case PeripheryKind::ProximitySensor:
      lowerSensor(ctx, c, parent);
      break;
    case PeripheryKind::RangeSensor:
    case PeripheryKind::LaserScanner:
      lowerRangeSensor(ctx, c, parent);
      break;
    case PeripheryKind::ImuSensor:
      lowerImuSensor(ctx, c, parent);
      break;
    case PeripheryKind::Encoder:
      lowerEncoder(ctx, c, parent);
      break;
    case PeripheryKind::CameraSensor:
      lowerCameraSensor(ctx, c, parent);
      break;
    case PeripheryKind::PluginSensor:
    case PeripheryKind::PluginActuator:
      lowerPluginPeriphery(ctx, c, parent);
      break;
    case PeripheryKind::UrdfDrive:
      ctx.error(c, "made by an RCImportURDF for each movable joint (Drives); it cannot be written in a scene");
      break;
    case PeripheryKind::LocalSocketCommunicator: {
      if (c.get(kPort) > kMaxPort) {
        ctx.errorAt(c.slotOf(kPort), c, "parameter 'Port' must be at most 65535, got " + std::to_string(c.get(kPort)));
        break;
      }
      const double period = c.get(kPeriod);
      if (!(period >= 1e-9 && period <= 1e9)) {
        ctx.errorAt(c.slotOf(kPeriod), c,
                    "parameter 'Period' must be between 1e-9 and 1e9 s, got " + formatNumber(period));
        break;
      }
      SocketDef d;
      d.key = ctx.modelKey(c);
      d.loc = c.loc;
      d.is_server = c.get(kIsServer);
      d.port = static_cast<int>(c.get(kPort));
      d.period = period;
      d.controller = c.get(kController);
      if (!d.controller.empty()) {
        std::vector<std::string> words;
        std::string problem;
        if (!splitCommandLine(d.controller, &words, &problem)) {
          ctx.errorAt(c.slotOf(kController), c, "parameter 'Controller': " + problem);
          break;
        }
        d.controller_dir = std::filesystem::path(c.loc.file.str()).parent_path().string();
        if (d.controller_dir.empty()) d.controller_dir = ".";
      }
      ctx.model.sockets.push_back(d);
      break;
    }
  }
}

bool splitCommandLine(const std::string& line, std::vector<std::string>* words, std::string* problem) {
  words->clear();
  std::string word;
  bool in_word = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r') {
      if (in_word) words->push_back(word);
      word.clear();
      in_word = false;
      continue;
    }
    in_word = true;
    if (ch == '\'') {
      const size_t end = line.find('\'', i + 1);
      if (end == std::string::npos) {
        *problem = "a quote (') is not closed";
        return false;
      }
      word += line.substr(i + 1, end - i - 1);
      i = end;
    } else if (ch == '"') {
      size_t j = i + 1;
      for (; j < line.size() && line[j] != '"'; ++j) {
        if (line[j] == '\\' && j + 1 < line.size() && (line[j + 1] == '"' || line[j + 1] == '\\')) ++j;
        word += line[j];
      }
      if (j >= line.size()) {
        *problem = "a quote (\") is not closed";
        return false;
      }
      i = j;
    } else if (ch == '\\') {
      if (i + 1 >= line.size()) {
        *problem = "a backslash ends the command line";
        return false;
      }
      word += line[++i];
    } else {
      word += ch;
    }
  }
  if (in_word) words->push_back(word);
  if (words->empty()) *problem = "the command line holds no program";
  return !words->empty();
}

}  // namespace simbob
