// Sensor noise (private to lib/physics): one generator per sensor, seeded from the run's seed and
// the sensor's fully qualified key. A sensor's readings therefore repeat exactly for the same
// scene and seed, and do not change when other sensors are added, removed or reordered.
//
// The generator is SplitMix64 and normal deviates come from the Box-Muller transform, both written
// out here rather than taken from <random>: the standard distributions are not specified bit for
// bit, so another standard library could give other readings for the same seed.
#pragma once

#include <cstdint>
#include <string_view>

namespace simbob {

class SensorNoise {
 public:
  SensorNoise(uint32_t run_seed, std::string_view key);

  /// The next uniform deviate in [0, 1), 53 bits.
  double uniform();
  /// The next normal deviate with mean 0 and standard deviation `sigma` (0 gives exactly 0 and
  /// draws nothing, so a noiseless sensor's readings are exact).
  double gaussian(double sigma);

 private:
  uint64_t next();
  uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace simbob
