// RCDriveTest (guide 6.12.1): every Period, the voltage u(t) = sin(2 pi Variation t / 60) on its
// drive (Variation sine cycles per minute).
#include <cmath>

#include "robot/controllers.h"
#include "simbob/cr_math.h"
#include "simbob/physics.h"

namespace simbob::robot {

namespace {

constexpr double kPi = 3.14159265358979323846;

class DriveTest : public Party {
 public:
  explicit DriveTest(const DriveTestDef& c) : drive_(c.drive), variation_(c.variation), tick_(c.period) {}
  SimTime first() override { return 0; }
  SimTime onGrant(SimTime now, World& world) override {
    world.setCommand(drive_, crSin(2 * kPi * variation_ * toSeconds(now) / 60));
    return tick_.next(now);
  }

 private:
  int drive_;
  double variation_;
  Periodic tick_;
};

}  // namespace

std::unique_ptr<Party> makeDriveTest(const DriveTestDef& c) { return std::make_unique<DriveTest>(c); }

}  // namespace simbob::robot
