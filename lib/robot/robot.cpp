// The parties of a Model's controllers, and the periodic timing of the test controllers.
#include <algorithm>
#include <exception>

#include "robot/controllers.h"
#include "simbob/physics.h"
#include "simbob/robot.h"
#include "simbob/values.h"

namespace simbob {

namespace robot {

Periodic::Periodic(double period_s) : period_(std::max<SimTime>(toSimTime(period_s).value_or(kNever), 1)) {}

SimTime Periodic::next(SimTime now) {
  if (period_ == kNever || next_ > kNever - period_) return kNever;
  next_ += period_;
  if (next_ <= now) next_ = (now / period_ + 1) * period_;  // a grant late by more than a period
  return next_;
}

}  // namespace robot

namespace {

class ClampNotices : public Party {
 public:
  ClampNotices(const Model& model, std::function<void(const Error&)> warn) : model_(model), warn_(std::move(warn)) {}
  SimTime first() override { return kNever; }
  SimTime onGrant(SimTime, World&) override { return kNever; }
  void finish(SimTime, World& world) override {
    for (int i = 0; i < world.actuatorCount(); ++i) {
      double asked = 0;
      const uint64_t n = world.clampedCommands(i, &asked);
      if (n == 0) continue;
      const ActuatorDef& d = model_.actuators[static_cast<size_t>(i)];
      if (d.kind == ActuatorDef::Plugin) continue;  // never clamped
      const bool hinge = model_.joints[static_cast<size_t>(d.joint)].kind == JointKind::Hinge;
      std::string what;
      switch (d.kind) {
        case ActuatorDef::Drive:
          what = "voltage " + formatReadable(asked) + " is beyond [-1, 1]";
          break;
        case ActuatorDef::Servo: {
          const std::string unit = hinge ? " rad" : " m";
          what = "target position " + formatReadable(asked) + unit + " is beyond " +
                 (asked < d.min_pos ? "MinPos " + formatNumber(d.min_pos) : "MaxPos " + formatNumber(d.max_pos)) + unit;
          break;
        }
        case ActuatorDef::VelDrive: {
          const std::string unit = hinge ? " rad/s" : " m/s";
          what = "velocity " + formatReadable(asked) + unit + " is beyond MaxVelocity " + formatNumber(d.max_velocity) +
                 unit;
          break;
        }
        case ActuatorDef::Effort: {
          const std::string unit = hinge ? " N m" : " N";
          what = "effort " + formatReadable(asked) + unit + " is beyond +-" + formatNumber(d.max_power) + unit;
          break;
        }
        case ActuatorDef::Plugin:
          break;
      }
      warn_({ErrorKind::InvalidInput, d.loc,
             "actuator '" + d.key + "': command " + what + ", clamped (" + countOf(n, "command", "commands") +
                 " clamped in this run)"});
    }
  }

 private:
  const Model& model_;
  std::function<void(const Error&)> warn_;
};

}  // namespace

std::unique_ptr<Party> clampNotices(const Model& model, std::function<void(const Error&)> warn) {
  return std::make_unique<ClampNotices>(model, std::move(warn));
}

std::vector<std::unique_ptr<Party>> robotParties(const Model& model, const CameraImages* images) {
  std::vector<std::unique_ptr<Party>> out(model.controllers.size());
  std::vector<robot::MotionControl2D*> motion(model.controllers.size(), nullptr);
  // Two-wheel controllers first: a schedule may command one listed after it.
  for (size_t i = 0; i < model.controllers.size(); ++i)
    if (model.controllers[i].kind() == ControllerDef::TwoWheel) {
      auto p = robot::makeTwoWheel(model.controllers[i].as<TwoWheelDef>());
      motion[i] = p.get();
      out[i] = std::move(p);
    }
  auto motionOf = [&](int target) { return target >= 0 ? motion[static_cast<size_t>(target)] : nullptr; };
  for (size_t i = 0; i < model.controllers.size(); ++i) {
    const ControllerDef& c = model.controllers[i];
    switch (c.kind()) {
      case ControllerDef::DriveTest:
        out[i] = robot::makeDriveTest(c.as<DriveTestDef>());
        break;
      case ControllerDef::ServoTest:
        out[i] = robot::makeServoTest(c.as<ServoTestDef>(), model);
        break;
      case ControllerDef::TwoWheel:
        break;  // made above
      case ControllerDef::Plugin:
        out[i] = robot::makePluginController(c);
        break;
      case ControllerDef::CommandSchedule:
        out[i] = robot::makeCommandSchedule(c.as<CommandScheduleDef>(), motionOf(c.as<CommandScheduleDef>().target));
        break;
      case ControllerDef::WallStop:
        out[i] = robot::makeWallStop(c.as<WallStopDef>(), motionOf(c.as<WallStopDef>().target));
        break;
      case ControllerDef::GoToPoint:
        out[i] = robot::makeGoToPoint(c.as<GoToPointDef>(), motionOf(c.as<GoToPointDef>().target));
        break;
      case ControllerDef::ObstacleAvoider:
        out[i] =
            robot::makeObstacleAvoider(c.as<ObstacleAvoiderDef>(), model, motionOf(c.as<ObstacleAvoiderDef>().target));
        break;
      case ControllerDef::WallFollower:
        out[i] = robot::makeWallFollower(c.as<WallFollowerDef>(), model, motionOf(c.as<WallFollowerDef>().target));
        break;
    }
  }
  for (size_t i = 0; i < out.size(); ++i) {
    out[i]->name = "controller '" + model.controllers[i].key + "'";
    out[i]->loc = model.controllers[i].loc;
  }
  // Socket peers last: at an instant they see what the controllers commanded and may override it.
  std::vector<std::pair<std::string, robot::MotionControl2D*>> motions;
  for (size_t i = 0; i < model.controllers.size(); ++i)
    if (motion[i]) motions.emplace_back(model.controllers[i].key, motion[i]);
  for (const SocketDef& d : model.sockets) {
    out.push_back(robot::makeSocketPeer(d, model, motions, images));
    out.back()->name = "RCLocalSocketCommunicator '" + d.key + "'";
    out.back()->loc = d.loc;
  }
  return out;
}

}  // namespace simbob
