// Geoms and the collision space: shapes in Model order, attached to their bodies with offsets
// relative to ODE's centre-of-mass frame, and the contact data each geom carries (its material).
#include <algorithm>
#include <cstdint>

#include "simbob/transform.h"
#include "world_impl.h"

namespace simbob {

namespace {

bool isIdentity(const Transform& t) {
  return t.p[0] == 0 && t.p[1] == 0 && t.p[2] == 0 && t.q[0] == 1 && t.q[1] == 0 && t.q[2] == 0 && t.q[3] == 0;
}

// ODE's dGeomConvex wants the origin of the geom's frame inside the hull: it prints a warning on
// stdout for every face whose plane leaves the origin outside ("Plane N does not contain the
// origin", "Polygon N is not defined counterclockwise") and its collision tests measure from
// that origin. A link's mesh is often drawn away from its link frame (drchubo's feet), so such a
// hull goes to ODE moved by the mean of its vertices (inside: the hull is convex), and the geom's
// offset moves back by the same vector. Hulls that hold their origin, on their surface included
// (a pyramid standing on it), go as they are: ODE steps them well, and their bytes stay.
bool holdsOrigin(const ConvexHull& h) {
  for (size_t f = 0; f < h.faceCount(); ++f)
    if (h.planes[f * 4 + 3] < 0) return false;
  return true;
}

const WorldImpl::OdeHull& odeHull(WorldImpl& im, size_t mesh, const ConvexHull& h) {
  WorldImpl::OdeHull& out = im.odeHulls[mesh];
  if (!out.planes.empty()) return out;
  Vec3 mean{0, 0, 0};
  for (size_t i = 0; i < h.pointCount(); ++i)
    for (size_t k = 0; k < 3; ++k) mean[k] += h.points[i * 3 + k];
  for (double& m : mean) m /= static_cast<double>(h.pointCount());
  out.shift = mean;
  out.points = h.points;
  for (size_t i = 0; i < h.pointCount(); ++i)
    for (size_t k = 0; k < 3; ++k) out.points[i * 3 + k] -= mean[k];
  out.planes = h.planes;
  for (size_t f = 0; f < h.faceCount(); ++f) {
    const double* n = &h.planes[f * 4];
    out.planes[f * 4 + 3] -= n[0] * mean[0] + n[1] * mean[1] + n[2] * mean[2];
  }
  return out;
}

// A mesh geom: ODE reads the hull's and the triangles' arrays in place (dReal is double, and
// ODE never writes them), so the World holds the MeshData (and any moved hull) for as long as
// the geoms live. *shift: where the geom's frame origin lies in the mesh frame (0 but for a
// moved hull).
dGeomID createMeshGeom(WorldImpl& im, const Model& model, const GeomDef& gd, dSpaceID space, Vec3* shift) {
  const auto mi = static_cast<size_t>(gd.mesh);
  if (im.meshes.empty()) {
    im.meshes.resize(model.meshes.size());
    im.triMeshData.assign(model.meshes.size(), nullptr);
    im.odeHulls.resize(model.meshes.size());
  }
  im.meshes[mi] = model.meshes[mi].data;
  const MeshData& mesh = *im.meshes[mi];
  if (gd.shape == GeomShape::ConvexHull) {
    const ConvexHull& h = mesh.hull;
    const double* planes = h.planes.data();
    const double* points = h.points.data();
    if (!holdsOrigin(h)) {
      const WorldImpl::OdeHull& moved = odeHull(im, mi, h);
      planes = moved.planes.data();
      points = moved.points.data();
      *shift = moved.shift;
    }
    return dCreateConvex(space, const_cast<dReal*>(planes), static_cast<unsigned>(h.faceCount()),  // NOLINT
                         const_cast<dReal*>(points), static_cast<unsigned>(h.pointCount()),        // NOLINT
                         const_cast<unsigned*>(h.polygons.data()));                                // NOLINT
  }
  static_assert(sizeof(dTriIndex) == sizeof(uint32_t), "ODE's triangle indices are 32-bit");
  if (!im.triMeshData[mi]) {
    im.triMeshData[mi] = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(im.triMeshData[mi], mesh.vertices.data(), sizeof(Vec3),
                                static_cast<int>(mesh.vertices.size()), mesh.triangles.data(),
                                static_cast<int>(mesh.triangles.size() * 3), sizeof(mesh.triangles[0]));
    // Hull-trimesh contacts (libccd) abort the process without the face angles; capsules use
    // the concave edges.
    dGeomTriMeshDataPreprocess2(
        im.triMeshData[mi],
        (1U << dTRIDATAPREPROCESS_BUILD_CONCAVE_EDGES) | (1U << dTRIDATAPREPROCESS_BUILD_FACE_ANGLES), nullptr);
  }
  return dCreateTriMesh(space, im.triMeshData[mi], nullptr, nullptr, nullptr);
}

}  // namespace

dSpaceID createSpace(const Model& model) {
  switch (model.settings.space) {
    case SpaceKind::Hash:
      return dHashSpaceCreate(nullptr);
    case SpaceKind::Simple:
      return dSimpleSpaceCreate(nullptr);
    case SpaceKind::SweepAndPrune:
      return dSweepAndPruneSpaceCreate(nullptr, dSAP_AXES_XZY);  // Y is up
    case SpaceKind::QuadTree: {
      // The tree covers where the bodies start, with a margin; geoms outside it still collide.
      double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
      auto grow = [&](const Vec3& p) {
        for (int k = 0; k < 3; ++k) {
          lo[k] = std::min(lo[k], p[k]);
          hi[k] = std::max(hi[k], p[k]);
        }
      };
      for (const BodyDef& b : model.bodies) grow(b.pose.p);
      for (const GeomDef& g : model.geoms)
        if (g.body < 0 && g.shape != GeomShape::Plane) grow(g.offset.p);
      if (lo[0] > hi[0]) lo[0] = lo[1] = lo[2] = hi[0] = hi[1] = hi[2] = 0;
      dVector3 center, extents;
      for (int k = 0; k < 3; ++k) {
        center[k] = (lo[k] + hi[k]) / 2;
        extents[k] = std::max(hi[k] - lo[k], 1.0) * 2;
      }
      center[3] = extents[3] = 0;
      return dQuadTreeSpaceCreate(nullptr, center, extents, 6);
    }
  }
  return dHashSpaceCreate(nullptr);
}

void createGeoms(WorldImpl& im, const Model& model) {
  im.geoms.reserve(model.geoms.size());
  im.geomInfo.reserve(model.geoms.size());
  for (size_t gi = 0; gi < model.geoms.size(); ++gi) {
    const GeomDef& gd = model.geoms[gi];
    // Sensor geoms go to a space of their own: the collision space stays what it is without them.
    if (gd.sensor && !im.sensorSpace) im.sensorSpace = dSimpleSpaceCreate(nullptr);
    dSpaceID space = gd.sensor ? im.sensorSpace : im.space;
    dGeomID g = nullptr;
    Vec3 shift{0, 0, 0};  // a moved hull's origin in the geom's frame
    switch (gd.shape) {
      case GeomShape::Box:
        g = dCreateBox(space, gd.size[0], gd.size[1], gd.size[2]);
        break;
      case GeomShape::Sphere:
        g = dCreateSphere(space, gd.size[0]);
        break;
      case GeomShape::Cylinder:
        g = dCreateCylinder(space, gd.size[0], gd.size[1]);
        break;
      case GeomShape::Capsule:
        g = dCreateCapsule(space, gd.size[0], gd.size[1]);
        break;
      case GeomShape::Plane:
        g = dCreatePlane(space, gd.plane[0], gd.plane[1], gd.plane[2], gd.plane[3]);
        break;
      case GeomShape::ConvexHull:
      case GeomShape::TriMesh:
        g = createMeshGeom(im, model, gd, space, &shift);
        break;
    }
    const dQuaternion q = {gd.offset.q[0], gd.offset.q[1], gd.offset.q[2], gd.offset.q[3]};
    Vec3 at = gd.offset.p;
    if (shift != Vec3{0, 0, 0}) {
      const Vec3 turned = rotate(gd.offset.q, shift);
      for (size_t k = 0; k < 3; ++k) at[k] += turned[k];
    }
    if (gd.body >= 0) {
      dGeomSetBody(g, im.bodies[static_cast<size_t>(gd.body)]);
      const Vec3& c = im.com[static_cast<size_t>(gd.body)];
      if (!isIdentity(gd.offset) || c != Vec3{0, 0, 0} || at != gd.offset.p) {
        // Offsets are relative to ODE's body frame, which sits at the centre of mass.
        dGeomSetOffsetPosition(g, at[0] - c[0], at[1] - c[1], at[2] - c[2]);
        dGeomSetOffsetQuaternion(g, q);
      }
    } else if (gd.shape != GeomShape::Plane) {
      // Static geom: the offset is its global pose. Planes are non-placeable.
      dGeomSetPosition(g, at[0], at[1], at[2]);
      dGeomSetQuaternion(g, q);
    }
    // ODE's user data is a pointer; the geom's index travels in it (read back in contacts.cpp).
    dGeomSetData(g, reinterpret_cast<void*>(static_cast<intptr_t>(gi)));  // NOLINT(performance-no-int-to-ptr)
    const MaterialDef& mat = model.materials[static_cast<size_t>(gd.material)];
    im.geomInfo.push_back({mat.friction, mat.bounceness, mat.min_bounce_vel, gd.sensor, gd.static_body, gd.group});
    if (mat.surface()) {  // a URDF link's <gazebo> surface (contacts.cpp); the others stay as they were
      im.geomInfo.back().surface = static_cast<int>(im.surfaces.size());
      im.surfaces.push_back(mat);
    }
    im.geoms.push_back(g);
  }
}

}  // namespace simbob
