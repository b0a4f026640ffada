// RCCommandSchedule: rows "time value..." sent to one actuator (a voltage, target position or
// target velocity) or to an RC2DMotionControl (linear, angular) at their times; each command
// holds until the next row's time.
#include "robot/controllers.h"
#include "simbob/physics.h"

namespace simbob::robot {

namespace {

class CommandSchedule : public Party {
 public:
  CommandSchedule(const CommandScheduleDef& c, MotionControl2D* target)
      : actuator_(c.actuator), target_(target), width_(static_cast<size_t>(c.values) + 1), rows_(c.commands) {}
  SimTime first() override { return timeOf(0); }
  SimTime onGrant(SimTime now, World& world) override {
    const double* r = &rows_[row_ * width_];
    if (target_)
      target_->setMotion(r[1], r[2], world);
    else if (actuator_ >= 0)
      world.setCommand(actuator_, r[1]);
    ++row_;
    SimTime next = timeOf(row_);
    return next > now ? next : now + 1;  // rows closer than 1 ns: the next one at once after
  }

 private:
  SimTime timeOf(size_t row) const {
    if (row * width_ >= rows_.size()) return kNever;
    return toSimTime(rows_[row * width_]).value_or(kNever);
  }

  int actuator_;
  MotionControl2D* target_;
  size_t width_;
  std::vector<double> rows_;
  size_t row_ = 0;
};

}  // namespace

std::unique_ptr<Party> makeCommandSchedule(const CommandScheduleDef& c, MotionControl2D* target) {
  return std::make_unique<CommandSchedule>(c, target);
}

}  // namespace simbob::robot
