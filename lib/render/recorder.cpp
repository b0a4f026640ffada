// The recorder party: frame n shows the first grid instant at or after n / fps (within
// MinTimeStep), the world's poses handed to a FrameDrawer. It
// reads the world and never changes it, so the trajectory is the same with or without --record.
#include <optional>

#include "simbob/physics.h"
#include "simbob/renderer.h"

namespace simbob {

Recorder::Recorder(FrameDrawer& drawer, double fps, SimTime min_step, int body_count, const Model* rays_of)
    : drawer_(drawer), fps_(fps), min_step_(min_step), poses_(static_cast<size_t>(body_count)), rays_of_(rays_of) {}

SimTime Recorder::first() { return 0; }

SimTime Recorder::onGrant(SimTime now, World& world) {
  for (int i = 0; i < world.bodyCount(); ++i) poses_[static_cast<size_t>(i)] = world.body(i).pose;
  if (rays_of_) rays_ = sensorRays(*rays_of_, world);
  // Every frame due at this grid instant shows it: frames closer together than the step repeat
  // the instant, so the video keeps one frame per 1/fps.
  const uint64_t due = framesDue(frames_, fps_, now, min_step_);
  for (uint64_t k = 0; k < due; ++k) {
    if (const Error* e = drawer_.draw(poses_, toSeconds(now), rays_)) {
      error_ = *e;
      failed_ = true;
      return kNever;
    }
    ++frames_;
  }
  return frameTime(frames_, fps_);
}

std::vector<double> sensorRays(const Model& model, const World& world) {
  std::vector<double> out;
  for (int i = 0; i < world.sensorCount(); ++i) {
    switch (model.sensors[static_cast<size_t>(i)].kind) {
      case SensorKind::Range:
      case SensorKind::Scanner: {
        const std::vector<double>& r = world.sensorReading(i);
        out.insert(out.end(), r.begin(), r.end());
        break;
      }
      case SensorKind::Proximity:
      case SensorKind::Imu:
      case SensorKind::Encoder:
      case SensorKind::Plugin:
        break;
    }
  }
  return out;
}

uint64_t framesDue(uint64_t drawn, double fps, SimTime now, SimTime min_step) {
  uint64_t n = drawn;
  for (;;) {
    const SimTime t = frameTime(n, fps);
    if (t == kNever || (t > now && t - now > min_step)) return n - drawn;
    ++n;
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
