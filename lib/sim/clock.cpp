#include "simbob/clock.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simbob {

SimTime toSimTime(double seconds) { return static_cast<SimTime>(std::llround(seconds * 1e9)); }

int Clock::addPeriodic(SimTime first, SimTime period) {
  requests_.push_back({first, std::max<SimTime>(period, 1)});
  return static_cast<int>(requests_.size() - 1);
}

SimTime Clock::nextRequest() const {
  SimTime t = std::numeric_limits<SimTime>::max();
  for (const auto& r : requests_) t = std::min(t, r.next);
  return t;
}

bool Clock::due(int id) const { return requests_[static_cast<size_t>(id)].next - now_ <= min_step_; }

void Clock::served(int id) {
  Request& r = requests_[static_cast<size_t>(id)];
  while (r.next - now_ <= min_step_) r.next += r.period;
}

SimTime Clock::stepToward(SimTime until) const {
  SimTime gap = until - now_;
  if (gap <= min_step_) return 0;
  return std::min(gap, max_step_);
}

}  // namespace simbob
