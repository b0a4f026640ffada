// The one check of a time option against the clock's range: see simbob/options.h.
#include "simbob/options.h"

#include <cmath>

#include "simbob/values.h"

namespace simbob {

std::string clockTimeProblem(const std::string& name, double seconds, bool zero_allowed) {
  if (zero_allowed && seconds == 0) return "";
  if (std::isfinite(seconds) && seconds >= kMinClockTime && seconds <= kMaxClockTime) return "";
  return name + " must be between 1e-9 and 1e9 s, got " + formatNumber(seconds);
}

}  // namespace simbob
