// The recorder party: frame n at t = n / fps, the world's poses handed to a FrameDrawer. It
// reads the world and never changes it, so the trajectory is the same with or without --record.
#include <optional>

#include "simbob/physics.h"
#include "simbob/render.h"

namespace simbob {

Recorder::Recorder(FrameDrawer& drawer, double fps, SimTime min_step, int body_count)
    : drawer_(drawer), fps_(fps), min_step_(min_step), poses_(static_cast<size_t>(body_count)) {}

SimTime Recorder::first() { return 0; }

SimTime Recorder::onGrant(SimTime now, World& world) {
  for (int i = 0; i < world.bodyCount(); ++i) poses_[static_cast<size_t>(i)] = world.body(i).pose;
  if (const Error* e = drawer_.draw(poses_, toSeconds(now))) {
    error_ = *e;
    failed_ = true;
    return kNever;
  }
  ++frames_;
  return nextFrameTime(&frames_, fps_, now, min_step_);
}

SimTime nextFrameTime(uint64_t* drawn, double fps, SimTime now, SimTime min_step) {
  // Frame n shows t = n / fps: the next request is the first such time beyond MinTimeStep.
  for (;;) {
    const std::optional<SimTime> next = toSimTime(static_cast<double>(*drawn) / fps);
    if (!next) return kNever;
    if (*next - now > min_step) return *next;
    ++*drawn;  // a frame closer than MinTimeStep to this one cannot be reached apart from it
  }
}

void Recorder::finish(SimTime /*end*/, World& /*world*/) {
  if (failed_) return;
  if (const Error* e = drawer_.finish()) {
    error_ = *e;
    failed_ = true;
  }
}

const Error* Recorder::failure() const { return failed_ ? &error_ : nullptr; }

}  // namespace simbob
