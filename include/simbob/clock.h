// The simulation clock (guide 7.2): parties request access at simulated times; the clock steps
// the physics up to the earliest request in steps of at most MaxTimeStep, and a request closer
// than MinTimeStep to the current time is granted without another step. Time is kept in integer
// nanoseconds so that sample times are exact and runs are reproducible.
#pragma once

#include <cstdint>
#include <vector>

namespace simbob {

using SimTime = int64_t;  ///< nanoseconds of simulated time
constexpr SimTime kSecond = 1000000000;

/// Seconds -> nanoseconds, rounded to the nearest nanosecond.
SimTime toSimTime(double seconds);
inline double toSeconds(SimTime t) { return static_cast<double>(t) / static_cast<double>(kSecond); }

class Clock {
 public:
  Clock(SimTime max_step, SimTime min_step) : max_step_(max_step), min_step_(min_step) {}

  /// A periodic request: first at `first`, then every `period` (> 0). Returns its id.
  /// Trajectory sampling is one; controllers will join the same way.
  int addPeriodic(SimTime first, SimTime period);

  SimTime now() const { return now_; }
  /// Earliest pending request time.
  SimTime nextRequest() const;
  /// Whether request `id` is due now (within MinTimeStep); serving it schedules the next one.
  bool due(int id) const;
  void served(int id);
  /// The step to take towards `until` (capped by MaxTimeStep); 0 if `until` is within MinTimeStep.
  SimTime stepToward(SimTime until) const;
  void advance(SimTime h) { now_ += h; }

 private:
  struct Request {
    SimTime next;
    SimTime period;
  };
  SimTime max_step_;
  SimTime min_step_;
  SimTime now_ = 0;
  std::vector<Request> requests_;
};

}  // namespace simbob
