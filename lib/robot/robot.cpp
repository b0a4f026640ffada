// The parties of a Model's controllers, and the periodic timing of the test controllers.
#include <algorithm>

#include "robot/controllers.h"
#include "simbob/robot.h"

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

std::vector<std::unique_ptr<Party>> robotParties(const Model& model) {
  std::vector<std::unique_ptr<Party>> out(model.controllers.size());
  std::vector<robot::MotionControl2D*> motion(model.controllers.size(), nullptr);
  // Two-wheel controllers first: a schedule may command one listed after it.
  for (size_t i = 0; i < model.controllers.size(); ++i)
    if (model.controllers[i].kind == ControllerDef::TwoWheel) {
      auto p = robot::makeTwoWheel(model.controllers[i]);
      motion[i] = p.get();
      out[i] = std::move(p);
    }
  for (size_t i = 0; i < model.controllers.size(); ++i) {
    const ControllerDef& c = model.controllers[i];
    switch (c.kind) {
      case ControllerDef::DriveTest:
        out[i] = robot::makeDriveTest(c);
        break;
      case ControllerDef::ServoTest:
        out[i] = robot::makeServoTest(c, model);
        break;
      case ControllerDef::TwoWheel:
        break;  // made above
      case ControllerDef::Plugin:
        out[i] = c.make(c);
        break;
      case ControllerDef::CommandSchedule:
        out[i] = robot::makeCommandSchedule(c, c.target >= 0 ? motion[static_cast<size_t>(c.target)] : nullptr);
        break;
      case ControllerDef::WallStop:
        out[i] = robot::makeWallStop(c, motion[static_cast<size_t>(c.target)]);
        break;
      case ControllerDef::GoToPoint:
        out[i] = robot::makeGoToPoint(c, motion[static_cast<size_t>(c.target)]);
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
    out.push_back(robot::makeSocketPeer(d, model, motions));
    out.back()->name = "RCLocalSocketCommunicator '" + d.key + "'";
    out.back()->loc = d.loc;
  }
  return out;
}

}  // namespace simbob
