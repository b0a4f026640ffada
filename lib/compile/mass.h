// Mass properties of geoms (for RCInertiaByGeom and rods) and the inertia check.
#pragma once

#include "simbob/model.h"

namespace simbob {

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
