// RCSimGoToPoint (simbob's own SimControllerComponent, guide 2.1: a controller that may read the
// simulation's state). Every Period it reads its Body's pose from the World and steers its
// RC2DMotionControl towards Target (x z on the ground plane; Y is up). The body's forward axis
// is its local +X (as in the two-wheel scenes, whose wheel axles point to the robot's left,
// local -Z). With e the heading error, the angle from the forward axis (projected on the ground)
// to the direction of the target, wrapped into (-pi, pi], positive counter-clockwise seen from
// above:
//   w = clamp(kGain e, -TurnRate, TurnRate),  v = Speed max(0, cos e),
// until the body's origin is within Tolerance of the target (distance on the ground plane);
// then it commands (0, 0) and asks no more: the robot stays stopped for good.
#include <algorithm>
#include <cmath>

#include "robot/controllers.h"
#include "simbob/cr_math.h"
#include "simbob/physics.h"

namespace simbob::robot {

namespace {

constexpr double kPi = 3.14159265358979323846;
/// Proportional heading gain (1/s): w = kGain e before the TurnRate clamp.
constexpr double kGain = 2.0;

class GoToPoint : public Party {
 public:
  GoToPoint(const GoToPointDef& c, MotionControl2D* motion)
      : motion_(motion),
        body_(c.body),
        goal_x_(c.goal_x),
        goal_z_(c.goal_z),
        speed_(c.speed),
        turn_rate_(c.turn_rate),
        tolerance_(c.tolerance),
        tick_(c.period) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    const Transform pose = world.body(body_).pose;
    const double dx = goal_x_ - pose.p[0];
    const double dz = goal_z_ - pose.p[2];
    if (std::hypot(dx, dz) <= tolerance_) {
      motion_->setMotion(0, 0, world);
      return kNever;
    }
    // Headings as angles counter-clockwise seen from above (about +Y): the direction (x, z) on
    // the ground has the angle atan2(-z, x). The forward axis is the local +X rotated by q.
    const double qw = pose.q[0], qx = pose.q[1], qy = pose.q[2], qz = pose.q[3];
    const double fx = 1 - 2 * (qy * qy + qz * qz);
    const double fz = 2 * (qx * qz - qw * qy);
    double e = crAtan2(-dz, dx) - crAtan2(-fz, fx);
    if (e > kPi) e -= 2 * kPi;
    if (e <= -kPi) e += 2 * kPi;
    const double w = std::clamp(kGain * e, -turn_rate_, turn_rate_);
    const double v = speed_ * std::max(0.0, crCos(e));
    motion_->setMotion(v, w, world);
    return tick_.next(now);
  }

 private:
  MotionControl2D* motion_;
  int body_;
  double goal_x_, goal_z_, speed_, turn_rate_, tolerance_;
  Periodic tick_;
};

}  // namespace

std::unique_ptr<Party> makeGoToPoint(const GoToPointDef& c, MotionControl2D* motion) {
  return std::make_unique<GoToPoint>(c, motion);
}

}  // namespace simbob::robot
