// RCServoTest (guide 6.12.2): every Period, a target that moves from MinPos to MaxPos and back
// at constant speed, Variation round trips per minute: with T = 60 / Variation and
// f = frac(t / T), target = MinPos + (MaxPos - MinPos) * (f < 1/2 ? 2 f : 2 - 2 f).
// Variation 0 holds MinPos.
#include <cmath>

#include "robot/controllers.h"
#include "simbob/physics.h"

namespace simbob::robot {

namespace {

class ServoTest : public Party {
 public:
  ServoTest(const ServoTestDef& c, const ActuatorDef& servo)
      : servo_(c.servo), lo_(servo.min_pos), hi_(servo.max_pos), variation_(c.variation), tick_(c.period) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    double f = 0;
    if (variation_ > 0) {
      const double cycles = toSeconds(now) * variation_ / 60;
      f = cycles - std::floor(cycles);
    }
    world.setCommand(servo_, lo_ + (hi_ - lo_) * (f < 0.5 ? 2 * f : 2 - 2 * f));
    return tick_.next(now);
  }

 private:
  int servo_;
  double lo_, hi_, variation_;
  Periodic tick_;
};

}  // namespace

std::unique_ptr<Party> makeServoTest(const ServoTestDef& c, const Model& model) {
  return std::make_unique<ServoTest>(c, model.actuators.at(static_cast<size_t>(c.servo)));
}

}  // namespace simbob::robot
