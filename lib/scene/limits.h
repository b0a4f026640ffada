// The magnitude every number of a scene may have, one value for scene files (params.cpp) and
// URDF files (lib/urdf/read.cpp): a robot read from either passes the same checks.
#pragma once

namespace simbob {

/// The largest magnitude of a number (m, kg, N, m/s, ...): far beyond any robot scene, and below
/// what overflows ODE's inertia and contact math (1e300 m). docs/testing.md, "Limits".
inline constexpr double kMaxValueMagnitude = 1e9;

}  // namespace simbob
