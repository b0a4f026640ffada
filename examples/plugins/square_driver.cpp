// Example plug-in in C++ (docs/plugins.md), through simbob/plugin.hpp over the C ABI: the
// controller type SquareDriver drives a two-wheeled robot along a square through its wheels'
// RCVelControl drives. Each cycle of Side + Turn seconds: both wheels at +WheelSpeed rad/s for
// Side s (straight ahead), then the left wheel at -WheelSpeed and the right at +WheelSpeed for
// Turn s (a turn to the left on the spot). With wheel radius r and track b the robot moves
// r WheelSpeed m/s on the sides and turns at 2 r WheelSpeed / b rad/s in the corners. Built by
// CMake as build/plugins/square_driver.so:
//   build/simbob run examples/plugins/square_robot.xml --duration 10 --plugin build/plugins/square_driver.so
#include <cmath>

#include "simbob/plugin.hpp"

namespace {

class SquareDriver : public simbob::plugin::Controller {
 public:
  // The numbers in the order kNumbers declares them.
  explicit SquareDriver(const double* numbers) : speed_(numbers[0]), side_(numbers[1]), turn_(numbers[2]) {}
  void act(simbob::plugin::Host& host, double t) override {
    const double cycle = side_ + turn_;
    const double phase = cycle > 0 ? std::fmod(t, cycle) : 0.0;
    const bool straight = phase < side_;
    host.setCommand(0, straight ? speed_ : -speed_);  // ref 0: ControlLeft
    host.setCommand(1, speed_);                       // ref 1: ControlRight
  }

 private:
  double speed_, side_, turn_;
};

const SimbobNumber kNumbers[] = {{"WheelSpeed", 2.0, "rad/s", "wheel velocity"},
                                 {"Side", 2.0, "s", "time straight ahead per side"},
                                 {"Turn", 1.0, "s", "time turning per corner"}};
const SimbobRef kRefs[] = {{"ControlLeft", "RCVelControl", "left wheel velocity control"},
                           {"ControlRight", "RCVelControl", "right wheel velocity control"}};

}  // namespace

SIMBOB_PLUGIN("square_driver",
              simbob::plugin::controller<SquareDriver>(
                  "SquareDriver",
                  "Drives two wheels along a square: Side s straight, Turn s turning left on the spot (example "
                  "plug-in).",
                  kNumbers, kRefs))
