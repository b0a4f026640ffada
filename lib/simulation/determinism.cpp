// A run repeated and compared bit for bit: see simbob/determinism.h.
#include "simulation/determinism.h"

#include <cmath>
#include <cstring>

#include "simbob/trajectory.h"
#include "simbob/values.h"

namespace simbob {

void SampleRecord::record(double t, const double* poses) {
  times_.push_back(t);
  poses_.insert(poses_.end(), poses, poses + bodies_ * kPoseSize);
}

DeterminismCheck checkDeterminism(const Model& model, SimulationOptions opts, double sample_interval,
                                  const SampleRecord& first,
                                  const std::function<void(double, const double*)>& on_sample) {
  DeterminismCheck c;
  const size_t n = model.bodies.size();
  size_t sample = 0;
  opts.progress = nullptr;
  auto compare = [&](double t, const double* p) {
    if (on_sample) on_sample(t, p);
    if (!c.same) return;
    if (sample >= first.size() || t != first.time(sample)) {
      c.same = false;
      c.where = "sample times differ at sample " + std::to_string(sample);
      return;
    }
    const double* q = first.poses(sample);
    for (size_t b = 0; b < n && c.same; ++b)
      // Bitwise on purpose: determinism means the same bits (-0.0 vs 0.0, NaN payloads).
      if (std::memcmp(&p[b * kPoseSize], &q[b * kPoseSize], kPoseSize * sizeof(double)) != 0) {  // NOLINT
        c.same = false;
        const double* pb = &p[b * kPoseSize];
        const double* qb = &q[b * kPoseSize];
        const double dist =
            std::sqrt(std::pow(pb[0] - qb[0], 2) + std::pow(pb[1] - qb[1], 2) + std::pow(pb[2] - qb[2], 2));
        c.where = "first difference at t=" + formatNumber(t) + " s (sample " + std::to_string(sample) + "), body '" +
                  model.bodies[b].key + "', position apart by " + formatNumber(dist) + " m";
      }
    ++sample;
  };
  Diagnostics unused;  // the model and options were accepted for the first run
  std::unique_ptr<Simulation> sim = Simulation::fromModel(model, opts, unused);
  sim->sampleTrajectory(nullptr, sample_interval, compare);
  c.second = sim->runToEnd();
  if (c.second.status != RunStatus::Completed) return c;  // not a difference: the caller decides
  if (c.same && sample != first.size()) {
    c.same = false;
    c.where = "second run produced " + std::to_string(sample) + " samples, first " + std::to_string(first.size());
  }
  return c;
}

}  // namespace simbob
