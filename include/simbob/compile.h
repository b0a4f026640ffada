// The compile step: component graph -> Model. Resolves frames (global/local poses), joints of
// constructions, imports, clones, inertia, materials and settings; validates everything ODE
// would otherwise abort on. No ODE here.
#pragma once

#include "simbob/graph.h"
#include "simbob/model.h"

namespace simbob {

/// Fill *model from scene. Returns false (with messages in diag) if the scene is invalid.
bool compileScene(const Scene& scene, Model* model, Diagnostics& diag);

/// Warnings about legal scenes that make ODE unstable or wrong (`simbob check`): mass ratios
/// across joints, bodies thin and fast enough to tunnel, a step too large for the fastest
/// pendulum, joints far from their bodies, bodies overlapping at t = 0. Each says why and what
/// to change.
void lintModel(const Model& model, Diagnostics& diag);

/// Volume (m^3) and inertia per unit density (m^5, about the body origin, body frame) of one
/// placeable geom; planes have none.
struct MassProps {
  double volume = 0;
  Vec3 moment{0, 0, 0};  ///< m^4: volume times the centroid (body frame)
  Mat3 inertia{0, 0, 0, 0, 0, 0, 0, 0, 0};
};
MassProps geomMassProps(const GeomDef& g);

/// Whether a symmetric 3x3 matrix is positive definite (Cholesky).
bool isPositiveDefinite(const Mat3& m);

}  // namespace simbob
