// `simbob run --check-determinism`: the run is repeated in the same process and the two must give
// the same bits at every sample. A SampleRecord keeps the first run's samples (attach its
// record() as the sampler's on_sample); checkDeterminism runs the model again and names the first
// sample where the two runs part.
#pragma once

#include <string>
#include <vector>

#include "simbob/model.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"
#include "simbob/trajectory.h"

namespace simbob {

/// Every sample of a run: times and the poses of every body (kPoseSize doubles each).
class SampleRecord {
 public:
  explicit SampleRecord(size_t body_count) : bodies_(body_count) {}
  void record(double t, const double* poses);
  size_t size() const { return times_.size(); }
  double time(size_t s) const { return times_[s]; }
  const double* poses(size_t s) const { return &poses_[s * bodies_ * kPoseSize]; }

 private:
  size_t bodies_;
  std::vector<double> times_, poses_;
};

struct DeterminismCheck {
  bool same = true;   ///< the second run gave the same bits at every sample
  std::string where;  ///< when not: the first difference, in words
  RunResult second;   ///< how the second run ended (an interrupt is not a difference)
};

/// Runs `model` again with `opts` (its progress callback is dropped), sampling every
/// `sample_interval` s, and compares each sample with `first` bit for bit. `on_sample` sees the
/// second run's samples as they come (for an interrupt message, say).
DeterminismCheck checkDeterminism(const Model& model, SimulationOptions opts, double sample_interval,
                                  const SampleRecord& first,
                                  const std::function<void(double, const double*)>& on_sample = nullptr);

}  // namespace simbob
