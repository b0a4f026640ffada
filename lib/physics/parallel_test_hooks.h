// Tests only: process-wide switches of the parallel paths of a World's step (contacts.cpp),
// for tests/physics_ode/threads_test.cpp and the scene_run fuzz target (fuzz/entry.h). No ODE
// type, so that code which may not include ODE can set them. Not thread-safe: set them while no
// World steps.
#pragma once

#include <cstddef>

namespace simbob {

struct ParallelTestHooks {
  size_t grain = 0;             ///< pairs (and swept boxes) per chunk at least; 0: kPairGrain, kSweepGrain
  bool reverse_commit = false;  ///< commit the pairs' contacts last pair first: unordered on purpose
};
ParallelTestHooks& parallelTestHooks();

}  // namespace simbob
