// The simulation clock: a fixed step grid. The physics advances only in whole steps of the
// run's step h (MaxTimeStep, or --dt), so the clock only ever shows t = k h. Parties (samplers,
// controllers, recorders, peers) request access at simulated times; a request is granted at the
// first grid instant at or after it, where "at" allows MinTimeStep of slack (a request for
// 0.0333333 s is granted at 0.033 s when the step is 1 ms and MinTimeStep 1 us). So observing a
// run never changes it: requests pick grid instants, they never split a step. Time is kept in
// integer nanoseconds so that grid times are exact and runs are reproducible.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace simbob {

using SimTime = int64_t;  ///< nanoseconds of simulated time
constexpr SimTime kSecond = 1000000000;
/// A request that is never reached: a party asking for it asks no more.
constexpr SimTime kNever = std::numeric_limits<SimTime>::max();

/// Seconds -> nanoseconds, rounded to the nearest nanosecond (halves away from zero). Returns
/// std::nullopt for NaN, infinities, and times whose nanoseconds do not fit in SimTime
/// (|seconds| >= 2^63 ns, about 9.22e9 s or 292 years): never a wrapped or saturated value.
std::optional<SimTime> toSimTime(double seconds);
inline double toSeconds(SimTime t) { return static_cast<double>(t) / static_cast<double>(kSecond); }

/// The first instant of the grid k * step (k >= 0) at or after `t` - `min_step`: where a request
/// for `t` is granted. kNever for kNever, and when that instant does not fit SimTime.
SimTime gridInstant(SimTime t, SimTime step, SimTime min_step);

/// Request bookkeeping of the parties of one run, without the physics: the run loop asks it
/// whom to grant and steps the world by step() whenever nobody is due. Parties are numbered in
/// the order they were added, and that order breaks ties between requests for the same time.
class Clock {
 public:
  /// A grid of `step` (>= 1 ns); a request within `min_step` (>= 0) after now is due now.
  Clock(SimTime step, SimTime min_step) : step_(step), min_step_(min_step) {}

  /// Adds a party whose first request is `first` (kNever: none). Returns its id (0, 1, ...).
  int addParty(SimTime first);

  /// The party to grant now: the earliest due request (at or before now + MinTimeStep), ties to
  /// the lowest id; -1 when none is due.
  int grantable() const;
  /// `party` was granted at now and asks next for `next` (kNever: no more). A party is granted at
  /// most once per instant: a `next` that is due now waits for the next grid instant.
  void granted(int party, SimTime next);

  /// The grid instant reached: steps() * step().
  SimTime now() const { return now_; }
  SimTime step() const { return step_; }
  uint64_t steps() const { return steps_; }
  /// True once `t` is due: at or before now + MinTimeStep (the end of a run is reached then).
  bool reached(SimTime t) const { return due(t); }
  /// The world took one whole step: now moves to the next grid instant.
  void advance();

 private:
  struct Request {
    SimTime next;
    bool waits;  ///< asked for an instant already due when it was granted: waits for the next step
  };
  bool due(SimTime t) const { return t <= now_ || t - now_ <= min_step_; }

  SimTime step_;
  SimTime min_step_;
  SimTime now_ = 0;
  uint64_t steps_ = 0;
  std::vector<Request> requests_;
  bool any_waiting_ = false;
};

}  // namespace simbob
