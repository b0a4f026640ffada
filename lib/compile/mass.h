// Mass properties of geoms and the positive-definiteness check of inertia tensors (Eigen inside;
// plain arrays at the interface so the compiled Model stays plain data).
#pragma once

#include "simbob/model.h"

namespace simbob {

/// Volume (m^3) and inertia per unit density (m^5, about the body origin, body frame) of one
/// placeable geom; planes have none. A ConvexHull or TriMesh geom needs its mesh
/// (Model::meshes[g.mesh].data): the solid of its hull or of its (closed) triangles.
struct MassProps {
  double volume = 0;
  Vec3 moment{0, 0, 0};  ///< m^4: volume times the centroid (body frame)
  Mat3 inertia{0, 0, 0, 0, 0, 0, 0, 0, 0};
};
MassProps geomMassProps(const GeomDef& g, const MeshData* mesh = nullptr);

/// Whether a symmetric 3x3 matrix (its lower triangle is read) is finite and positive definite.
bool isPositiveDefinite(const Mat3& m);

}  // namespace simbob
