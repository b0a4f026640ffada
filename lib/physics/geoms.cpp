// Geoms and the collision space: shapes in Model order, attached to their bodies with offsets
// relative to ODE's centre-of-mass frame, and the contact data each geom carries (its material).
#include <algorithm>
#include <cstdint>

#include "world_impl.h"

namespace simbob {

namespace {

bool isIdentity(const Transform& t) {
  return t.p[0] == 0 && t.p[1] == 0 && t.p[2] == 0 && t.q[0] == 1 && t.q[1] == 0 && t.q[2] == 0 && t.q[3] == 0;
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
    }
    const dQuaternion q = {gd.offset.q[0], gd.offset.q[1], gd.offset.q[2], gd.offset.q[3]};
    if (gd.body >= 0) {
      dGeomSetBody(g, im.bodies[static_cast<size_t>(gd.body)]);
      const Vec3& c = im.com[static_cast<size_t>(gd.body)];
      if (!isIdentity(gd.offset) || c != Vec3{0, 0, 0}) {
        // Offsets are relative to ODE's body frame, which sits at the centre of mass.
        dGeomSetOffsetPosition(g, gd.offset.p[0] - c[0], gd.offset.p[1] - c[1], gd.offset.p[2] - c[2]);
        dGeomSetOffsetQuaternion(g, q);
      }
    } else if (gd.shape != GeomShape::Plane) {
      // Static geom: the offset is its global pose. Planes are non-placeable.
      dGeomSetPosition(g, gd.offset.p[0], gd.offset.p[1], gd.offset.p[2]);
      dGeomSetQuaternion(g, q);
    }
    // ODE's user data is a pointer; the geom's index travels in it (read back in contacts.cpp).
    dGeomSetData(g, reinterpret_cast<void*>(static_cast<intptr_t>(gi)));  // NOLINT(performance-no-int-to-ptr)
    const MaterialDef& mat = model.materials[static_cast<size_t>(gd.material)];
    im.geomInfo.push_back({mat.friction, mat.bounceness, mat.min_bounce_vel, gd.sensor, gd.static_body});
    im.geoms.push_back(g);
  }
}

}  // namespace simbob
