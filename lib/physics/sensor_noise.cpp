// See sensor_noise.h.
#include "sensor_noise.h"

#include <cmath>

#include "simbob/cr_math.h"

namespace simbob {

namespace {

// FNV-1a, 64 bits: a stable hash of the key (std::hash is not specified across libraries).
uint64_t hashKey(std::string_view key) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : key) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace

SensorNoise::SensorNoise(uint32_t run_seed, std::string_view key)
    : state_(hashKey(key) ^ (static_cast<uint64_t>(run_seed) * 0x9e3779b97f4a7c15ull)) {}

uint64_t SensorNoise::next() {
  uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

double SensorNoise::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double SensorNoise::gaussian(double sigma) {
  if (sigma == 0.0) return 0.0;
  if (has_spare_) {
    has_spare_ = false;
    return sigma * spare_;
  }
  // Box-Muller: u1 in (0, 1] so that the logarithm is finite.
  const double u1 = 1.0 - uniform();
  const double u2 = uniform();
  // Correctly rounded log, sin and cos (cr_math.h): libm's differ between CPUs for a few draws.
  const double r = std::sqrt(-2.0 * crLog(u1));
  const double phi = 2.0 * M_PI * u2;
  spare_ = r * crSin(phi);
  has_spare_ = true;
  return sigma * r * crCos(phi);
}

}  // namespace simbob
