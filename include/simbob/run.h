// One batch run: build the world from a Model, step it to the duration on the clock, sample
// poses into a trajectory, and check every step for a non-finite or runaway state.
#pragma once

#include <csignal>
#include <cstdint>
#include <functional>
#include <string>

#include "simbob/error.h"
#include "simbob/model.h"
#include "simbob/trajectory.h"

namespace simbob {

struct RunOptions {
  double duration = 10.0;         ///< s of simulated time
  double dt = 0.0;                ///< s; 0 = the scene's MaxTimeStep
  double sample_interval = 0.01;  ///< s of simulated time between trajectory samples
  uint32_t seed = 0;              ///< ODE's random generator (QuickStep constraint order)
  double runaway_limit = 1e6;     ///< |position| in m or |velocity| in m/s, rad/s beyond which a run diverged
  /// Called about every 1% of the run with the simulated time reached.
  std::function<void(double)> progress;
  /// Called with every sample: time and kPoseSize doubles per body (x y z qw qx qy qz).
  std::function<void(double, const double*)> on_sample;
  /// Set asynchronously (SIGINT/SIGTERM) to stop at the next step.
  const volatile std::sig_atomic_t* stop = nullptr;
};

enum class RunStatus { Completed, Diverged, Interrupted, Failed };

struct RunResult {
  RunStatus status = RunStatus::Failed;
  Error error;  ///< set unless Completed
  uint64_t steps = 0;
  double sim_time = 0.0;  ///< s reached
  uint64_t samples = 0;
  double wall_seconds = 0.0;
  double dt = 0.0;  ///< step size used
};

/// Runs the model. Samples go to `writer` (may be null: no trajectory). The caller commits
/// or keeps the writer's output according to the result.
RunResult runModel(const Model& model, const RunOptions& opts, TrajectoryWriter* writer);

/// "out.csv" -> "out.partial.csv" (the trajectory kept by a failed or interrupted run).
std::string partialPath(const std::string& out);

}  // namespace simbob
