// Robots' software: the built-in controllers (guide 6.12) and command schedules of a Model, each
// a Party of the run loop (run.h) that commands actuators through World::setCommand.
// No ODE here: lib/robot sees the world only through simbob/physics.h.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simbob/model.h"
#include "simbob/loop.h"

namespace simbob {

struct Image;
/// Where the robot's parties find the images of camera sensors: the Simulation draws them
/// (lib/simulation, camera sensors) before the controllers of their Period instants. The world
/// knows nothing of them: it is physics only.
class CameraImages {
 public:
  virtual ~CameraImages() = default;
  /// The latest image of the RCCameraSensor with this key; null if there is none.
  virtual const Image* image(const std::string& key) const = 0;
};

/// One party per Model::controllers entry, in that order (ties in the run loop follow it), then
/// one per Model::sockets entry (the socket peers, docs/socket-protocol.md), which send the
/// images of `images` (may be null: a scene without camera sensors) to peers that subscribe.
std::vector<std::unique_ptr<Party>> robotParties(const Model& model, const CameraImages* images = nullptr);

/// A party that is never granted: when the run completes it hands `warn` one warning per
/// actuator whose commands were clamped (World::clampedCommands), with the first command and the
/// limit it met: "actuator 'Bot.LeftDrive': command 2 rad/s is beyond MaxVelocity 1 rad/s,
/// clamped (1 of 1 commands)".
std::unique_ptr<Party> clampNotices(const Model& model, std::function<void(const Error&)> warn);

}  // namespace simbob
