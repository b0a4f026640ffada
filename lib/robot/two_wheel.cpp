// RCTwoWheelMotionControl (guide 6.12.3): a linear velocity v (m/s) and an angular velocity w
// (rad/s, counter-clockwise about the up axis) become the wheel velocities
//   left = (v - w WheelDistance / 2) / r,  right = (v + w WheelDistance / 2) / r  (rad/s)
// with r = Variation, the wheel radius. Each wheel's hinge must turn the wheel forward in its
// positive sense (its axis points to the robot's left). v and w are 0 until a command schedule
// sets them; the wheels are commanded at t = 0 and whenever they change.
#include "robot/controllers.h"
#include "simbob/physics.h"

namespace simbob::robot {

namespace {

class TwoWheel : public MotionControl2D {
 public:
  explicit TwoWheel(const TwoWheelDef& c)
      : left_(c.left), right_(c.right), half_track_(c.wheel_distance / 2), radius_(c.wheel_radius) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime, World& world) override {
    command(world);
    return kNever;
  }
  void setMotion(double linear, double angular, World& world) override {
    v_ = linear;
    w_ = angular;
    command(world);
  }

 private:
  void command(World& world) {
    world.setCommand(left_, (v_ - w_ * half_track_) / radius_);
    world.setCommand(right_, (v_ + w_ * half_track_) / radius_);
  }

  int left_, right_;
  double half_track_, radius_;
  double v_ = 0, w_ = 0;
};

}  // namespace

std::unique_ptr<MotionControl2D> makeTwoWheel(const TwoWheelDef& c) { return std::make_unique<TwoWheel>(c); }

}  // namespace simbob::robot
