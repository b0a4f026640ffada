// The physics layer: builds an ODE world from a compiled Model and steps it.
// This header exposes no ODE type; only lib/physics/*.cpp include <ode/ode.h>.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "simbob/model.h"

namespace simbob {

/// "ODE <configuration>" of the linked ODE (precision and build options), for run summaries.
std::string physicsVersion();

/// State of one mobile body, global frame.
struct BodyState {
  Transform pose;
  Vec3 lin_vel{0, 0, 0};
  Vec3 ang_vel{0, 0, 0};
};

/// An ODE world built from a Model. ODE keeps process-wide state (its random generator among
/// it), so only one World may exist per process at a time; creating a second one while the
/// first lives is an Internal error.
class World {
 public:
  /// Validates nothing: the Model must come from compile(). `seed` seeds ODE's global random
  /// generator (dRandSetSeed), which QuickStep uses to reorder constraints.
  static std::unique_ptr<World> create(const Model& model, uint32_t seed);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advance by h seconds: collide, add contacts per the material rules, step, clear contacts.
  void step(double h);

  int bodyCount() const;
  BodyState body(int i) const;

  /// Index of the first body whose state is non-finite or beyond `limit` (m or m/s, rad/s),
  /// or -1 when all are fine.
  int firstBadBody(double limit = 1e6) const;

  /// Contact joints created by the last step (for tests and diagnostics).
  int lastContactCount() const;

 private:
  World();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace simbob
