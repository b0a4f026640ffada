// The run loop driven directly, for the tests of lib/loop: a Runner with the given parties, or
// with a trajectory sampler only. (simbob itself runs through the Simulation API and the Run.)
#pragma once

#include <algorithm>
#include <functional>
#include <vector>

#include "simbob/loop.h"

namespace simbob::test {

/// SimulationOptions with what a sampled test run adds: the interval and a sample callback.
struct LoopOptions : SimulationOptions {
  LoopOptions() { duration = 10.0; }
  double sample_interval = 0.01;                         ///< s between samples
  std::function<void(double, const double*)> on_sample;  ///< time and kPoseSize doubles per body
};

/// Runs the model to opts.duration, serving `parties` in list order at tied instants.
inline RunResult runParties(const Model& model, const SimulationOptions& opts, const std::vector<Party*>& parties) {
  Runner runner(model, opts, parties);
  runner.runUntil(runner.end());
  return runner.complete();
}

/// Runs the model with a trajectory sampler as its only party, writing to `writer` (may be null).
inline RunResult runModel(const Model& model, const LoopOptions& opts, TrajectoryWriter* writer) {
  const SimTime interval = std::max<SimTime>(toSimTime(opts.sample_interval).value_or(1), 1);
  const SimTime min_step = toSimTime(model.settings.min_time_step).value_or(0);
  TrajectorySampler sampler(static_cast<int>(model.bodies.size()), interval, min_step, writer, opts.on_sample);
  RunResult r = runParties(model, opts, {&sampler});
  r.samples = sampler.samples();
  return r;
}

}  // namespace simbob::test
