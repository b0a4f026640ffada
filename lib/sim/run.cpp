#include "simbob/run.h"

#include <chrono>
#include <cmath>
#include <vector>

#include "simbob/clock.h"
#include "simbob/physics.h"
#include "simbob/values.h"

namespace simbob {

std::string partialPath(const std::string& out) {
  const std::string ext = ".csv";
  if (out.size() > ext.size() && out.compare(out.size() - ext.size(), ext.size(), ext) == 0)
    return out.substr(0, out.size() - ext.size()) + ".partial.csv";
  return out + ".partial.csv";
}

RunResult runModel(const Model& model, const RunOptions& opts, TrajectoryWriter* writer) {
  RunResult res;
  auto wall0 = std::chrono::steady_clock::now();
  const double dt = opts.dt > 0 ? opts.dt : model.settings.max_time_step;
  res.dt = dt;
  std::unique_ptr<World> world = World::create(model, opts.seed);
  if (!world) {
    res.error = {ErrorKind::Internal, {}, "cannot create the physics world (another one is alive in this process)"};
    return res;
  }
  const SimTime end = toSimTime(opts.duration);
  Clock clock(std::max<SimTime>(toSimTime(dt), 1), toSimTime(model.settings.min_time_step));
  const int sampler = clock.addPeriodic(0, std::max<SimTime>(toSimTime(opts.sample_interval), 1));
  const int n = world->bodyCount();
  std::vector<double> poses(static_cast<size_t>(n) * kPoseSize);

  auto sample = [&]() {
    for (int i = 0; i < n; ++i) {
      BodyState s = world->body(i);
      double* p = &poses[static_cast<size_t>(i) * kPoseSize];
      p[0] = s.pose.p[0];
      p[1] = s.pose.p[1];
      p[2] = s.pose.p[2];
      p[3] = s.pose.q[0];
      p[4] = s.pose.q[1];
      p[5] = s.pose.q[2];
      p[6] = s.pose.q[3];
    }
    if (writer) writer->addSample(toSeconds(clock.now()), poses.data());
    if (opts.on_sample) opts.on_sample(toSeconds(clock.now()), poses.data());
    ++res.samples;
  };

  const SimTime progress_every = std::max<SimTime>(end / 100, 1);
  SimTime next_progress = progress_every;
  SimTime last_sample = -1;
  while (true) {
    if (clock.due(sampler) && clock.now() <= end) {
      sample();
      last_sample = clock.now();
      clock.served(sampler);
    }
    if (clock.now() >= end || end - clock.now() <= 0) break;
    if (writer && !writer->ok()) {
      // A full disk is reported when it happens, not after simulating the rest for nothing.
      res.status = RunStatus::Failed;
      res.error = {ErrorKind::IoError,
                   {writer->finalPath(), 0},
                   "writing the trajectory failed at t=" + formatNumber(toSeconds(clock.now())) + " s"};
      break;
    }
    if (opts.stop && *opts.stop) {
      res.status = RunStatus::Interrupted;
      res.error = {ErrorKind::Diverged, {}, "interrupted at t=" + formatNumber(toSeconds(clock.now())) + " s"};
      break;
    }
    SimTime h = clock.stepToward(std::min(clock.nextRequest(), end));
    if (h == 0) {
      // The end is within MinTimeStep: it counts as reached.
      clock.advance(std::min(clock.nextRequest(), end) - clock.now());
      continue;
    }
    world->step(toSeconds(h));
    clock.advance(h);
    ++res.steps;
    int bad = world->firstBadBody(opts.runaway_limit);
    if (bad >= 0) {
      res.status = RunStatus::Diverged;
      const BodyDef& b = model.bodies[static_cast<size_t>(bad)];
      res.error = {ErrorKind::Diverged, b.loc,
                   "body '" + b.key + "' diverged at t=" + formatNumber(toSeconds(clock.now())) +
                       " s (non-finite or beyond " + formatNumber(opts.runaway_limit) +
                       " m or m/s); a smaller step (--dt) or softer joints (ERP/CFM) may help"};
      break;
    }
    if (opts.progress && clock.now() >= next_progress) {
      opts.progress(toSeconds(clock.now()));
      next_progress += progress_every;
    }
  }
  if (res.status == RunStatus::Failed && res.error.message.empty()) {
    // The final state is always recorded, even when the duration is not a multiple of the interval.
    if (last_sample != clock.now()) sample();
    res.status = RunStatus::Completed;
  }
  res.sim_time = toSeconds(clock.now());
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

}  // namespace simbob
