// The camera sensors of a Simulation (RCCameraSensor, docs/sensors.md): a party that owns one
// Renderer per camera sensor -- created only when the scene has one, so other scenes never need
// GL -- and draws its image from the world's poses at each Period instant. It is served right
// after the trajectory sampler, before the controllers, so a controller granted at t reads the
// image of t. It draws inline, on the stepping thread: the image must be there before the
// controllers of the same instant run, so a render thread could not draw it while the physics
// steps on. It only reads the world: the trajectory does not depend on it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "simbob/physics.h"
#include "simbob/renderer.h"
#include "simbob/robot.h"
#include "simbob/loop.h"
#include "simbob/simulation.h"

namespace simbob {

class CameraSensors : public Party, public CameraImages {
 public:
  /// A renderer per Model::camera_sensors entry (the model must outlive this). Null and *err
  /// (no GL back end, a texture missing) on failure.
  static std::unique_ptr<CameraSensors> create(const Model& model, const SimulationOptions& opts, Error* err);
  SimTime first() override;
  SimTime onGrant(SimTime now, World& world) override;
  const Error* failure() const override { return failed_ ? &error_ : nullptr; }
  /// The latest image of the camera sensor with this key (empty before its first); null if none.
  const Image* image(const std::string& key) const override;

 private:
  struct Camera {
    const CameraSensorDef* def = nullptr;
    std::unique_ptr<Renderer> renderer;
    SimTime period = 0;  ///< ns; 0: every step
    SimTime next = 0;    ///< the multiple of the period it draws at next
    Image image;
  };
  CameraSensors() = default;
  std::vector<Camera> cameras_;
  std::vector<Transform> poses_;
  SimTime min_step_ = 0;
  Error error_;
  bool failed_ = false;
};

}  // namespace simbob
