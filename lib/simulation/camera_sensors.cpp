// Camera sensors: see camera_sensors.h.
#include "simulation/camera_sensors.h"

#include <algorithm>
#include <cstdlib>

#include "simbob/physics.h"

namespace simbob {

std::unique_ptr<CameraSensors> CameraSensors::create(const Model& model, const SimulationOptions& opts, Error* err) {
  std::unique_ptr<CameraSensors> cs(new CameraSensors());
  cs->name = "the camera sensors";
  cs->min_step_ = toSimTime(model.settings.min_time_step).value_or(0);
  for (const CameraSensorDef& d : model.camera_sensors) {
    RenderOptions ro;  // what `simbob render --camera KEY --size WxH` draws
    ro.width = d.width;
    ro.height = d.height;
    ro.camera = d.key;
    ro.backend = opts.gl;
    ro.texture_folder = opts.texture_folder;
    Camera c;
    c.def = &d;
    c.period = d.period > 0 ? toSimTime(d.period).value_or(kNever) : 0;
    c.renderer = Renderer::create(model, ro, err);
    if (!c.renderer) {
      err->message = "RCCameraSensor '" + d.key + "': " + err->message;
      err->loc = d.loc;
      return nullptr;
    }
    cs->cameras_.push_back(std::move(c));
  }
  return cs;
}

SimTime CameraSensors::first() {
  for (Camera& c : cameras_) c.next = 0;
  return cameras_.empty() ? kNever : 0;
}

SimTime CameraSensors::onGrant(SimTime now, World& world) {
  const int n = world.bodyCount();
  poses_.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) poses_[static_cast<size_t>(i)] = world.body(i).pose;
  SimTime next = kNever;
  for (Camera& c : cameras_) {
    if (c.next != kNever && c.next <= now + min_step_) {
      if (const Error* e = c.renderer->render(poses_, toSeconds(now), &c.image)) {
        error_ = *e;
        error_.message = "RCCameraSensor '" + c.def->key + "': " + error_.message;
        failed_ = true;
        return kNever;
      }
      // The next multiple of the period not yet reached (a period below the step skips some).
      if (c.period == 0) {
        c.next = now + 1;
      } else {
        while (c.next != kNever && c.next <= now + min_step_)
          c.next = c.next > kNever - c.period ? kNever : c.next + c.period;
      }
    }
    next = std::min(next, c.next);
  }
  return next;
}

const Image* CameraSensors::image(const std::string& key) const {
  for (const Camera& c : cameras_)
    if (c.def->key == key) return &c.image;
  return nullptr;
}

}  // namespace simbob
