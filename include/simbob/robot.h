// Robots' software: the built-in controllers (guide 6.12) and command schedules of a Model, each
// a Party of the run loop (run.h) that commands actuators through World::setCommand.
// No ODE here: lib/robot sees the world only through simbob/physics.h.
#pragma once

#include <memory>
#include <vector>

#include "simbob/model.h"
#include "simbob/run.h"

namespace simbob {

/// One party per Model::controllers entry, in that order (ties in the run loop follow it), then
/// one per Model::sockets entry (the socket peers, docs/socket-protocol.md).
std::vector<std::unique_ptr<Party>> robotParties(const Model& model);

}  // namespace simbob
