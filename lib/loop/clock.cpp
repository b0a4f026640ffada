#include "simbob/clock.h"

#include <algorithm>
#include <cmath>

namespace simbob {

std::optional<SimTime> toSimTime(double seconds) {
  const double ns = seconds * 1e9;
  // 2^63 is exact in a double; every double below it in magnitude rounds to a value that fits
  // (the largest double under 2^63 is an integer). NaN fails both comparisons.
  constexpr double kLimit = 9223372036854775808.0;
  if (!(ns < kLimit && ns > -kLimit)) return std::nullopt;
  return static_cast<SimTime>(std::llround(ns));
}

int Clock::addParty(SimTime first) {
  requests_.push_back({first, false});
  return static_cast<int>(requests_.size() - 1);
}

int Clock::grantable() const {
  int best = -1;
  for (size_t i = 0; i < requests_.size(); ++i) {
    const Request& r = requests_[i];
    // Strictly earlier wins, so equal times keep the lowest id.
    if (!r.waits && due(r.next) && (best < 0 || r.next < requests_[static_cast<size_t>(best)].next))
      best = static_cast<int>(i);
  }
  return best;
}

void Clock::granted(int party, SimTime next) {
  Request& r = requests_[static_cast<size_t>(party)];
  r.next = next;
  r.waits = due(next);
  any_waiting_ = any_waiting_ || r.waits;
}

void Clock::advance() {
  ++steps_;
  now_ += step_;
  if (any_waiting_) {
    for (Request& r : requests_) r.waits = false;
    any_waiting_ = false;
  }
}

SimTime gridInstant(SimTime t, SimTime step, SimTime min_step) {
  if (t == kNever) return kNever;
  const SimTime from = t - min_step;  // t >= 0 and min_step >= 0: no overflow
  if (from <= 0) return 0;
  const SimTime k = from / step + (from % step != 0 ? 1 : 0);
  if (k > kNever / step) return kNever;
  return k * step;
}

}  // namespace simbob
