// Example plug-in (docs/plugins.md): the controller type SquareDriver drives a two-wheeled
// robot along a square through its wheels' RCVelControl drives. Each cycle of Side + Turn
// seconds: both wheels at +WheelSpeed rad/s for Side s (straight ahead), then the left wheel at
// -WheelSpeed and the right at +WheelSpeed for Turn s (a turn to the left on the spot). With
// wheel radius r and track b the robot moves r WheelSpeed m/s on the sides and turns at
// 2 r WheelSpeed / b rad/s in the corners. Built by CMake as build/plugins/square_driver.so:
//   build/simbob run scenes/plugin_square.xml --duration 10 --plugin build/plugins/square_driver.so
#include <cmath>
#include <memory>

#include "simbob/physics.h"
#include "simbob/plugin.h"

namespace {

class SquareDriver : public simbob::Party {
 public:
  explicit SquareDriver(const simbob::ControllerDef& d)
      : left_(d.actuators.at(0)),
        right_(d.actuators.at(1)),
        speed_(d.numbers.at(0)),
        side_(d.numbers.at(1)),
        turn_(d.numbers.at(2)),
        period_(static_cast<simbob::SimTime>(std::llround(d.period * 1e9))) {
    if (period_ < 1) period_ = 1;
  }
  simbob::SimTime first() override { return 0; }
  simbob::SimTime onGrant(simbob::SimTime now, simbob::World& world) override {
    const double t = simbob::toSeconds(now);
    const double cycle = side_ + turn_;
    const double phase = cycle > 0 ? std::fmod(t, cycle) : 0.0;
    const bool straight = phase < side_;
    world.setCommand(left_, straight ? speed_ : -speed_);
    world.setCommand(right_, speed_);
    return (now / period_ + 1) * period_;
  }

 private:
  int left_, right_;
  double speed_, side_, turn_;
  simbob::SimTime period_;
};

std::unique_ptr<simbob::Party> make(const simbob::ControllerDef& d) { return std::make_unique<SquareDriver>(d); }

bool registerTypes(simbob::PluginHost* host) {
  simbob::PluginControllerType t;
  t.name = "SquareDriver";
  t.doc = "Drives two wheels along a square: Side s straight, Turn s turning left on the spot (example plug-in).";
  t.refs = {{"ControlLeft", "RCVelControl", "left wheel velocity control"},
            {"ControlRight", "RCVelControl", "right wheel velocity control"}};
  t.numbers = {{"WheelSpeed", 2.0, "rad/s", "wheel velocity"},
               {"Side", 2.0, "s", "time straight ahead per side"},
               {"Turn", 1.0, "s", "time turning per corner"}};
  t.make = make;
  return host->addController(t);
}

const SimbobPluginV1 kPlugin{SIMBOB_PLUGIN_ABI_VERSION, "square_driver", registerTypes};

}  // namespace

extern "C" const SimbobPluginV1* simbob_plugin_v1(void) { return &kPlugin; }
