// Private to lib/robot: one factory per controller file, and the periodic timing they share.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "simbob/clock.h"
#include "simbob/model.h"
#include "simbob/robot.h"
#include "simbob/loop.h"

namespace simbob::robot {

/// Requests at 0, period, 2 period, ... (integer ns, so no drift); the next one after `now`.
class Periodic {
 public:
  explicit Periodic(double period_s);
  SimTime next(SimTime now);

 private:
  SimTime period_;
  SimTime next_ = 0;
};

/// RC2DMotionControl: what a command schedule calls on a two-wheel controller.
class MotionControl2D : public Party {
 public:
  /// Linear velocity (m/s) and angular velocity (rad/s, counter-clockwise seen from above).
  virtual void setMotion(double linear, double angular, World& world) = 0;
};

std::unique_ptr<Party> makeDriveTest(const DriveTestDef& c);
std::unique_ptr<Party> makeServoTest(const ServoTestDef& c, const Model& model);
std::unique_ptr<MotionControl2D> makeTwoWheel(const TwoWheelDef& c);
/// `target`: the controller a 2-D schedule commands (nullptr for an actuator schedule).
std::unique_ptr<Party> makeCommandSchedule(const CommandScheduleDef& c, MotionControl2D* target);
/// `motion`: the RC2DMotionControl it drives (never nullptr).
std::unique_ptr<Party> makeWallStop(const WallStopDef& c, MotionControl2D* motion);
/// An RCLocalSocketCommunicator's peer: it may command every actuator of `model` and every
/// RC2DMotionControl in `motions` (key, controller).
std::unique_ptr<Party> makeSocketPeer(const SocketDef& d, const Model& model,
                                      std::vector<std::pair<std::string, MotionControl2D*>> motions,
                                      const CameraImages* images);
/// A SimControllerComponent: reads its body's pose from the World. `motion` never nullptr.
std::unique_ptr<Party> makeGoToPoint(const GoToPointDef& c, MotionControl2D* motion);
/// A plug-in's controller (plugin_controller.cpp).
std::unique_ptr<Party> makePluginController(const ControllerDef& c);
/// Reads the range sensors model.sensors[c.sensors[i]]; `motion` never nullptr.
std::unique_ptr<Party> makeObstacleAvoider(const ObstacleAvoiderDef& c, const Model& model, MotionControl2D* motion);
/// Reads the laser scanner model.sensors[c.sensors[0]]; `motion` never nullptr.
std::unique_ptr<Party> makeWallFollower(const WallFollowerDef& c, const Model& model, MotionControl2D* motion);

}  // namespace simbob::robot
