// Sensor noise (lib/physics/sensor_noise.h): the configured mean and deviation over 10,000
// readings, the same readings for the same seed and key, and readings independent of other keys.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "physics/sensor_noise.h"

using namespace simbob;

namespace {

std::vector<double> draw(uint32_t seed, const char* key, int n, double sigma) {
  SensorNoise noise(seed, key);
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(noise.gaussian(sigma));
  return v;
}

}  // namespace

TEST_CASE("sensor noise has the configured mean and deviation", "[physics][noise]") {
  const int n = 10000;
  const double sigma = 0.02;
  std::vector<double> v = draw(7, "Bot.Front.Range", n, sigma);
  double sum = 0, sq = 0;
  for (double x : v) sum += x;
  const double mean = sum / n;
  for (double x : v) sq += (x - mean) * (x - mean);
  const double sd = std::sqrt(sq / (n - 1));
  // The sample mean of n normal deviates has standard error sigma/sqrt(n) = 2e-4; 4 standard
  // errors is a bound a correct generator exceeds about once in 16,000 seeds. The sample deviation
  // has relative standard error 1/sqrt(2(n-1)) = 0.7 %; 4 % is over 5 standard errors.
  CHECK(std::abs(mean) < 4 * sigma / std::sqrt(double(n)));
  CHECK(std::abs(sd / sigma - 1) < 0.04);
}

TEST_CASE("sensor noise repeats for the same seed and key, and differs otherwise", "[physics][noise]") {
  CHECK(draw(7, "Bot.Front.Range", 100, 1.0) == draw(7, "Bot.Front.Range", 100, 1.0));
  CHECK(draw(7, "Bot.Front.Range", 100, 1.0) != draw(8, "Bot.Front.Range", 100, 1.0));
  CHECK(draw(7, "Bot.Front.Range", 100, 1.0) != draw(7, "Bot.Back.Range", 100, 1.0));
}

TEST_CASE("a noiseless sensor draws nothing and reads exactly", "[physics][noise]") {
  SensorNoise a(1, "k"), b(1, "k");
  for (int i = 0; i < 5; ++i) CHECK(a.gaussian(0.0) == 0.0);
  CHECK(a.uniform() == b.uniform());
}
