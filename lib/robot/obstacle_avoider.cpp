// RCObstacleAvoider (simbob's own, Braitenberg style): every Period it reads its RCRangeSensors
// and steers its RC2DMotionControl away from what they see. Sensor i, on the robot's body, looks
// along the bearing b_i: the angle of its ray (local -Z) in the body's frame projected on the
// body's ground plane, from the forward axis +X, positive counter-clockwise seen from above
// (towards -Z, the robot's left). Its reading d_i (MaxRange: nothing seen) gives the activation
//   a_i = clamp((MaxRange_i - d_i) / (MaxRange_i - MinRange_i), 0, 1)
// (0: nothing in range, 1: at MinRange or nearer: mount the sensors so that MinRange is where
// the robot's own hull ends)
// and with
//   f = max_i a_i max(0, cos b_i)                  (how close something is ahead)
//   p = sum_i a_i (-sin b_i)                       (> 0: more on the right: turn left)
// it commands
//   v = Speed (1 - f),  w = TurnRate clamp(p + s f, -1, 1)
// where s, the side it turns to, is chosen when something first comes in range ahead (f > 0):
// +1 (left) if p >= 0, else -1, and held while f > 0 (so a wall straight ahead makes it turn one
// way, not dither). With nothing in range it drives straight at Speed.
#include <algorithm>
#include <cmath>

#include "robot/controllers.h"
#include "simbob/cr_math.h"
#include "simbob/physics.h"
#include "simbob/transform.h"

namespace simbob::robot {

namespace {

class ObstacleAvoider : public Party {
 public:
  ObstacleAvoider(const ObstacleAvoiderDef& c, const Model& model, MotionControl2D* motion)
      : motion_(motion), sensors_(c.sensors), speed_(c.speed), turn_rate_(c.turn_rate), tick_(c.period) {
    for (int i : sensors_) {
      const SensorDef& s = model.sensors[static_cast<size_t>(i)];
      const Vec3 d = rotate(s.pose.q, Vec3{0, 0, -1});
      const double b = crAtan2(-d[2], d[0]);
      cos_.push_back(crCos(b));
      sin_.push_back(crSin(b));
      max_range_.push_back(s.max_range);
      min_range_.push_back(std::min(s.min_range, 0.999 * s.max_range));
    }
  }
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    double f = 0, p = 0;
    for (size_t i = 0; i < sensors_.size(); ++i) {
      const double d = world.sensorReading(sensors_[i])[0];
      const double a = std::clamp((max_range_[i] - d) / (max_range_[i] - min_range_[i]), 0.0, 1.0);
      f = std::max(f, a * std::max(0.0, cos_[i]));
      p -= a * sin_[i];
    }
    if (f <= 0)
      side_ = 0;
    else if (side_ == 0)
      side_ = p >= 0 ? 1 : -1;
    motion_->setMotion(speed_ * (1 - f), turn_rate_ * std::clamp(p + side_ * f, -1.0, 1.0), world);
    return tick_.next(now);
  }

 private:
  MotionControl2D* motion_;
  std::vector<int> sensors_;
  std::vector<double> cos_, sin_, max_range_, min_range_;
  double speed_, turn_rate_;
  Periodic tick_;
  int side_ = 0;
};

}  // namespace

std::unique_ptr<Party> makeObstacleAvoider(const ObstacleAvoiderDef& c, const Model& model, MotionControl2D* motion) {
  return std::make_unique<ObstacleAvoider>(c, model, motion);
}

}  // namespace simbob::robot
