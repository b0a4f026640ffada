// The trajectory sampler: the first party of every run.
#include <vector>

#include "simbob/physics.h"
#include "simbob/loop.h"
#include "simbob/transform.h"
#include "simbob/values.h"

namespace simbob {

TrajectorySampler::TrajectorySampler(int body_count, SimTime interval, SimTime min_step, TrajectoryWriter* writer,
                                     std::function<void(double, const double*)> on_sample, std::vector<FrameDef> frames)
    : interval_(interval > 0 ? interval : 1),
      min_step_(min_step),
      writer_(writer),
      on_sample_(std::move(on_sample)),
      frames_(std::move(frames)),
      poses_((static_cast<size_t>(body_count) + frames_.size()) * kPoseSize) {}

SimTime TrajectorySampler::first() { return next_; }

SimTime TrajectorySampler::onGrant(SimTime now, World& world) {
  sample(now, world);
  // The first multiple of the interval more than MinTimeStep past now (now + min_step would
  // count as reached); kNever once the next multiple is beyond SimTime.
  if (next_ <= now || next_ - now <= min_step_) {
    const SimTime behind = now - next_ + min_step_;  // >= 0, fits: both are clock times
    const SimTime k = behind / interval_ + 1;
    if (k > (kNever - next_) / interval_) return next_ = kNever;
    next_ += k * interval_;
  }
  return next_;
}

void TrajectorySampler::finish(SimTime end, World& world) {
  // The final state is always recorded, even when the duration is not a multiple of the interval.
  if (last_ != end) sample(end, world);
}

const Error* TrajectorySampler::failure() const { return error_.message.empty() ? nullptr : &error_; }

void TrajectorySampler::sample(SimTime now, const World& world) {
  const int n = static_cast<int>(poses_.size() / kPoseSize - frames_.size());
  // The velocity block (run --columns pose,velocity): linear then angular, world frame.
  std::vector<double> velocities(writer_ && writer_->withVelocity() ? poses_.size() / kPoseSize * kVelocitySize : 0);
  for (int i = 0; i < n; ++i) {
    const BodyState s = world.body(i);
    if (!velocities.empty()) {
      double* v = &velocities[static_cast<size_t>(i) * kVelocitySize];
      for (size_t k = 0; k < 3; ++k) {
        v[k] = s.lin_vel[k];
        v[3 + k] = s.ang_vel[k];
      }
    }
    double* p = &poses_[static_cast<size_t>(i) * kPoseSize];
    p[0] = s.pose.p[0];
    p[1] = s.pose.p[1];
    p[2] = s.pose.p[2];
    p[3] = s.pose.q[0];
    p[4] = s.pose.q[1];
    p[5] = s.pose.q[2];
    p[6] = s.pose.q[3];
  }
  for (size_t f = 0; f < frames_.size(); ++f) {
    const FrameDef& fd = frames_[f];
    const Transform t = fd.body < 0 ? fd.offset : compose(world.body(fd.body).pose, fd.offset);
    const size_t row = static_cast<size_t>(n) + f;
    if (!velocities.empty()) {
      const BodyState s = fd.body < 0 ? BodyState{} : world.body(fd.body);
      const Vec3 r = sub(t.p, s.pose.p);  // the frame's point moves with the body: v + w x r
      const Vec3 v = add(s.lin_vel, cross(s.ang_vel, r));
      double* out = &velocities[row * kVelocitySize];
      for (size_t k = 0; k < 3; ++k) {
        out[k] = v[k];
        out[3 + k] = s.ang_vel[k];
      }
    }
    double* p = &poses_[row * kPoseSize];
    for (size_t k = 0; k < 3; ++k) p[k] = t.p[k];
    for (size_t k = 0; k < 4; ++k) p[3 + k] = t.q[k];
  }
  const double t = toSeconds(now);
  if (writer_) writer_->addSample(t, poses_.data(), velocities.empty() ? nullptr : velocities.data());
  if (on_sample_) on_sample_(t, poses_.data());
  ++samples_;
  last_ = now;
  if (writer_ && !writer_->ok() && error_.message.empty()) {
    // A full disk is reported when it happens, not after simulating the rest for nothing.
    error_ = {
        ErrorKind::IoError, {writer_->finalPath(), 0}, "writing the trajectory failed at t=" + formatNumber(t) + " s"};
  }
}

}  // namespace simbob
