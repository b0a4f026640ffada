// The simulation clock (guide 7.2): parties request access at simulated times; the clock steps
// the physics up to the earliest request in steps of at most MaxTimeStep, and a request closer
// than MinTimeStep to the current time is granted without another step. Time is kept in integer
// nanoseconds so that sample times are exact and runs are reproducible.
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

/// Request bookkeeping of the parties of one run, without the physics: the run loop asks it
/// whom to grant and how far to step. Parties are numbered in the order they were added, and
/// that order breaks ties between requests for the same time.
class Clock {
 public:
  /// Steps of at most `max_step` (>= 1 ns); a request within `min_step` (>= 0) of now is due.
  Clock(SimTime max_step, SimTime min_step) : max_step_(max_step), min_step_(min_step) {}

  /// Adds a party whose first request is `first` (kNever: none). Returns its id (0, 1, ...).
  int addParty(SimTime first);

  /// The party to grant now: the earliest request within MinTimeStep of now, ties to the lowest
  /// id; -1 when none is due.
  int grantable() const;
  /// `party` was granted at now and asks next for `next` (kNever: no more). A party is granted at
  /// most once per instant: a `next` within MinTimeStep of now (or before it) waits for the
  /// next step and is granted after it.
  void granted(int party, SimTime next);

  SimTime now() const { return now_; }
  /// Earliest pending request (kNever if none), not counting requests waiting for the next step.
  SimTime nextRequest() const;
  /// The step to take towards `until` (>= now), capped by MaxTimeStep; 0 if `until` is within
  /// MinTimeStep (it counts as reached).
  SimTime stepToward(SimTime until) const;
  /// Moves the clock on by h >= 0 ns; requests waiting for a step become ordinary again.
  void advance(SimTime h);

 private:
  struct Request {
    SimTime next;
    bool waits;  ///< asked within MinTimeStep of the instant it was granted at
  };
  bool due(SimTime t) const { return t <= now_ || t - now_ <= min_step_; }

  SimTime max_step_;
  SimTime min_step_;
  SimTime now_ = 0;
  std::vector<Request> requests_;
  bool any_waiting_ = false;
};

}  // namespace simbob
