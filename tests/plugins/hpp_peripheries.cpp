// The sensor and actuator of tests/plugins/c_plugins.c and examples/plugins/beam_sensor.c again,
// in C++ through simbob/plugin.hpp (tests/cli/plugins_c.sh checks they give the same bytes):
// HppBeam, a one-ray distance sensor offering RCRangeSensor, and HppThruster, a force of
// Force * command N along its mount's +X.
#include <algorithm>

#include "simbob/plugin.hpp"

namespace {

class Beam : public simbob::plugin::Sensor {
 public:
  explicit Beam(const double* numbers) : min_(numbers[0]), max_(numbers[1]) {}
  void read(simbob::plugin::Host& host, double, double* out, int) override {
    const double origin[3] = {0, 0, 0}, forward[3] = {0, 0, -1};
    const double d = host.castRay(origin, forward, max_);
    out[0] = d < 0 ? max_ : std::max(d, min_);
  }

 private:
  double min_, max_;
};

class Thruster : public simbob::plugin::Actuator {
 public:
  explicit Thruster(const double* numbers) : force_(numbers[0]) {}
  void apply(simbob::plugin::Host&, double, double, double command, double force[3], double torque[3]) override {
    force[0] = force_ * command;
    force[1] = force[2] = 0;
    torque[0] = torque[1] = torque[2] = 0;
  }

 private:
  double force_;
};

const SimbobNumber kBeamNumbers[] = {{"MinRange", 0.0, "m", "closest distance it measures"},
                                     {"MaxRange", 5.0, "m", "farthest distance it measures"}};
const char* const kBeamQuantities[] = {"distance"};
const SimbobNumber kThrusterNumbers[] = {{"Force", 1.0, "N", "force at command 1"}};

}  // namespace

SIMBOB_PLUGIN("hpp_peripheries",
              simbob::plugin::sensor<Beam>("HppBeam", "BeamSensor in C++ (test plug-in).", kBeamNumbers,
                                           kBeamQuantities, "RCRangeSensor"),
              simbob::plugin::actuator<Thruster>("HppThruster", "Thruster in C++ (test plug-in).", kThrusterNumbers))
