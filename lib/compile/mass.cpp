#include "compile/mass.h"

#include <Eigen/Cholesky>

#include "compile/eigen.h"
#include "simbob/transform.h"

namespace simbob {

bool isPositiveDefinite(const Mat3& m) {
  const Eigen::Matrix3d a = toEigen(m);
  // LLT lets NaN pivots through (it only rejects pivots <= 0), so finiteness is checked apart.
  if (!a.allFinite()) return false;
  const Eigen::LLT<Eigen::Matrix3d> llt(a);
  return llt.info() == Eigen::Success && llt.matrixLLT().allFinite();
}

namespace {

// A mesh geom: the solid of its hull or of its closed triangles, moved to the geom's offset.
MassProps meshMassProps(const GeomDef& g, const MeshMass& mm) {
  MassProps p;
  p.volume = mm.volume;
  const Eigen::Matrix3d r = toEigen(g.offset.q).toRotationMatrix();
  const Eigen::Matrix3d local = toEigen(mm.inertia);
  Eigen::Matrix3d inertia = r * local * r.transpose();
  const Eigen::Vector3d c = toEigen(g.offset.p) + r * toEigen(mm.centre);
  inertia += p.volume * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  p.inertia = toMat3(inertia);
  p.moment = toVec3(p.volume * c);
  return p;
}

}  // namespace

MassProps geomMassProps(const GeomDef& g, const MeshData* mesh) {
  MassProps p;
  Eigen::Vector3d principal;  // inertia per unit density about the geom's own axes
  switch (g.shape) {
    case GeomShape::Box: {
      const double x = g.size[0], y = g.size[1], z = g.size[2];
      p.volume = x * y * z;
      principal = {p.volume * (y * y + z * z) / 12, p.volume * (x * x + z * z) / 12, p.volume * (x * x + y * y) / 12};
      break;
    }
    case GeomShape::Sphere: {
      const double r = g.size[0];
      p.volume = 4.0 / 3.0 * kPi * r * r * r;
      principal.setConstant(0.4 * p.volume * r * r);
      break;
    }
    case GeomShape::Cylinder: {
      const double r = g.size[0], l = g.size[1];
      p.volume = kPi * r * r * l;
      const double side = p.volume * (3 * r * r + l * l) / 12;
      principal = {side, side, p.volume * r * r / 2};
      break;
    }
    case GeomShape::Capsule: {
      const double r = g.size[0], l = g.size[1];
      const double vc = kPi * r * r * l, vs = 4.0 / 3.0 * kPi * r * r * r;
      p.volume = vc + vs;
      // Cylinder plus two hemispheres whose centres of mass sit 3r/8 beyond the cylinder ends.
      const double side = vc * (3 * r * r + l * l) / 12 + vs * (0.4 * r * r + l * l / 4 + 3 * l * r / 8);
      principal = {side, side, vc * r * r / 2 + vs * 0.4 * r * r};
      break;
    }
    case GeomShape::Plane:
      return p;
    case GeomShape::ConvexHull:
      return mesh ? meshMassProps(g, mesh->hull_mass) : p;
    case GeomShape::TriMesh:
      return mesh ? meshMassProps(g, mesh->mass) : p;
  }
  // Rotate into the body frame: R diag(principal) R^T, summed as principal moment times the outer
  // product of its axis (the columns of R), axis by axis. Eigen's 3x3 product R D R^T sums the
  // last row in another order, which moves inertias, and so trajectories, by an ulp.
  const Eigen::Matrix3d r = toEigen(g.offset.q).toRotationMatrix();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) inertia += (principal[k] * r.col(k)) * r.col(k).transpose();
  // Then move to the body origin (parallel axis theorem).
  const Eigen::Vector3d o = toEigen(g.offset.p);
  inertia += p.volume * (o.squaredNorm() * Eigen::Matrix3d::Identity() - o * o.transpose());
  p.inertia = toMat3(inertia);
  p.moment = toVec3(p.volume * o);
  return p;
}

}  // namespace simbob
