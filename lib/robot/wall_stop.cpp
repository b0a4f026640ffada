// RCWallStop (simbob's own): every Period it reads its RCContactSensor; while the sensor touches
// nothing it commands its RC2DMotionControl forward at Speed (angular 0), and the first time the
// sensor touches it commands (0, 0) and asks no more: the robot stays stopped for good.
#include "robot/controllers.h"
#include "simbob/physics.h"

namespace simbob::robot {

namespace {

class WallStop : public Party {
 public:
  WallStop(const WallStopDef& c, MotionControl2D* motion)
      : motion_(motion), sensor_(c.sensor), speed_(c.speed), tick_(c.period) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    if (world.touching(sensor_)) {
      motion_->setMotion(0, 0, world);
      return kNever;
    }
    if (!driving_) {
      motion_->setMotion(speed_, 0, world);
      driving_ = true;
    }
    return tick_.next(now);
  }

 private:
  MotionControl2D* motion_;
  int sensor_;
  double speed_;
  Periodic tick_;
  bool driving_ = false;
};

}  // namespace

std::unique_ptr<Party> makeWallStop(const WallStopDef& c, MotionControl2D* motion) {
  return std::make_unique<WallStop>(c, motion);
}

}  // namespace simbob::robot
