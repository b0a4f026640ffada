// The physics layer: the only translation unit of simbob that includes <ode/ode.h>.
// Builds an ODE world from a compiled Model (bodies, geoms, joints in Model order) and steps it
// with the contact rules of the Simulator Bob guide 7.1.
#include "simbob/physics.h"
#include "simbob/transform.h"

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace simbob {

namespace {

static_assert(sizeof(dReal) == sizeof(double), "simbob needs ODE built in double precision");

// ODE keeps process-wide state (allocators, its random generator), so at most one World lives
// at a time; World::create refuses (returns nullptr) while this flag is set.
bool worldAlive = false;

// dInitODE2 once per process and never dCloseODE: ODE's global state outlives every World, so
// consecutive Worlds in one process (tests, batch runs) need no re-initialisation.
void initOdeOnce() {
  static const bool initialised = (dInitODE2(0) != 0);
  (void)initialised;
  // Per-thread collision data; idempotent, so calling it for every World is cheap and safe.
  dAllocateODEDataForThread(dAllocateMaskAll);
}

bool isIdentity(const Transform& t) {
  return t.p[0] == 0 && t.p[1] == 0 && t.p[2] == 0 && t.q[0] == 1 && t.q[1] == 0 && t.q[2] == 0 && t.q[3] == 0;
}

// Contact-relevant data of one geom, looked up by the index stored with dGeomSetData.
struct GeomInfo {
  double friction;
  double bounceness;
  double minBounceVel;
  bool sensor;
};

// The collision space chosen by the scene (SceneSettings Space, --space).
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

}  // namespace

struct World::Impl {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID contactGroup = nullptr;
  std::vector<dBodyID> bodies;
  std::vector<Vec3> com;  // centre of mass in the body frame, per body
  std::vector<dGeomID> geoms;
  std::vector<dJointID> joints;
  std::vector<GeomInfo> geomInfo;
  std::vector<dContact> contactBuffer;  // sized max_contacts once; reused by every collision
  int lastContacts = 0;
  bool quickstep = true;

  ~Impl() {
    // Contact joints first (they reference bodies), then the space with its geoms, then the
    // world with its bodies and remaining joints.
    if (contactGroup) dJointGroupDestroy(contactGroup);
    if (space) dSpaceDestroy(space);  // cleanup mode is on by default: destroys its geoms
    if (world) dWorldDestroy(world);
  }

  static void nearCallback(void* data, dGeomID g1, dGeomID g2) { static_cast<Impl*>(data)->collidePair(g1, g2); }

  const GeomInfo& infoOf(dGeomID g) const {
    return geomInfo[static_cast<size_t>(reinterpret_cast<intptr_t>(dGeomGetData(g)))];
  }

  void collidePair(dGeomID g1, dGeomID g2) {
    dBodyID b1 = dGeomGetBody(g1);
    dBodyID b2 = dGeomGetBody(g2);
    // Two geoms of one body, or two static geoms (both bodies null): nothing to resolve.
    if (b1 == b2) return;
    // Bodies joined by a joint do not collide with each other (the usual ODE idiom).
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
    const GeomInfo& i1 = infoOf(g1);
    const GeomInfo& i2 = infoOf(g2);
    // Sensors create no contact joints; nothing reads sensor contacts yet, so skip dCollide too.
    if (i1.sensor || i2.sensor) return;

    const int maxContacts = static_cast<int>(contactBuffer.size());
    const int n = dCollide(g1, g2, maxContacts, &contactBuffer[0].geom, sizeof(dContact));
    if (n <= 0) return;

    // Guide 7.1: the larger friction, the larger bounceness, the smaller MinBounceVel.
    const double mu = std::max(i1.friction, i2.friction);
    const double bounce = std::max(i1.bounceness, i2.bounceness);
    const double bounceVel = std::min(i1.minBounceVel, i2.minBounceVel);
    for (int k = 0; k < n; ++k) {
      dContact& c = contactBuffer[static_cast<size_t>(k)];
      // Approx1: Coulomb friction with the friction pyramid, bound = mu * normal force.
      // No SoftERP/SoftCFM: without them ODE applies the world's ERP and CFM to contacts,
      // which are exactly the settings' values, so the flags would change nothing.
      c.surface.mode = dContactBounce | dContactApprox1;
      c.surface.mu = mu;
      c.surface.bounce = bounce;
      c.surface.bounce_vel = bounceVel;
      dJointID j = dJointCreateContact(world, contactGroup, &c);
      dJointAttach(j, b1, b2);
      ++lastContacts;
    }
  }
};

World::World() : impl_(new Impl) {}

World::~World() {
  impl_.reset();  // ODE objects go before the flag allows a new World
  worldAlive = false;
}

std::unique_ptr<World> World::create(const Model& model, uint32_t seed) {
  // Only one World per process at a time (ODE global state); a second create fails softly.
  if (worldAlive) return nullptr;
  initOdeOnce();
  std::unique_ptr<World> w(new World());
  worldAlive = true;  // set once w exists, so its destructor is what clears it
  Impl& im = *w->impl_;
  const SolverSettings& s = model.settings;

  // Seed before anything else so QuickStep's constraint reordering is reproducible.
  dRandSetSeed(seed);
  im.world = dWorldCreate();
  dWorldSetGravity(im.world, s.gravity[0], s.gravity[1], s.gravity[2]);
  dWorldSetERP(im.world, s.erp);
  dWorldSetCFM(im.world, s.cfm);
  dWorldSetQuickStepNumIterations(im.world, s.iterations);
  im.quickstep = s.quickstep;
  im.space = createSpace(model);
  if (s.auto_disable) dWorldSetAutoDisableFlag(im.world, 1);
  im.contactGroup = dJointGroupCreate(0);
  im.contactBuffer.resize(static_cast<size_t>(std::max(1, s.max_contacts)));

  im.bodies.reserve(model.bodies.size());
  for (const BodyDef& bd : model.bodies) {
    dBodyID b = dBodyCreate(im.world);
    dMass m;
    const Mat3& I = bd.inertia;
    // COM at the body origin; full inertia tensor (row-major: I12 = [1], I13 = [2], I23 = [5]).
    dMassSetParameters(&m, bd.mass, 0, 0, 0, I[0], I[4], I[8], I[1], I[2], I[5]);
    dBodySetMass(b, &m);
    // ODE's body frame sits at the centre of mass; simbob's at the body origin. Both share axes.
    Vec3 p = bd.pose.p, v = bd.lin_vel;
    const bool offset = bd.com != Vec3{0, 0, 0};
    if (offset) {
      Vec3 rc = rotate(bd.pose.q, bd.com);
      p = add(p, rc);
      v = add(v, cross(bd.ang_vel, rc));
    }
    dBodySetPosition(b, p[0], p[1], p[2]);
    const dQuaternion q = {bd.pose.q[0], bd.pose.q[1], bd.pose.q[2], bd.pose.q[3]};
    dBodySetQuaternion(b, q);
    dBodySetLinearVel(b, v[0], v[1], v[2]);
    dBodySetAngularVel(b, bd.ang_vel[0], bd.ang_vel[1], bd.ang_vel[2]);
    im.bodies.push_back(b);
    im.com.push_back(bd.com);
  }

  im.geoms.reserve(model.geoms.size());
  im.geomInfo.reserve(model.geoms.size());
  for (size_t gi = 0; gi < model.geoms.size(); ++gi) {
    const GeomDef& gd = model.geoms[gi];
    dGeomID g = nullptr;
    switch (gd.shape) {
      case GeomShape::Box:
        g = dCreateBox(im.space, gd.size[0], gd.size[1], gd.size[2]);
        break;
      case GeomShape::Sphere:
        g = dCreateSphere(im.space, gd.size[0]);
        break;
      case GeomShape::Cylinder:
        g = dCreateCylinder(im.space, gd.size[0], gd.size[1]);
        break;
      case GeomShape::Capsule:
        g = dCreateCapsule(im.space, gd.size[0], gd.size[1]);
        break;
      case GeomShape::Plane:
        g = dCreatePlane(im.space, gd.plane[0], gd.plane[1], gd.plane[2], gd.plane[3]);
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
    dGeomSetData(g, reinterpret_cast<void*>(static_cast<intptr_t>(gi)));
    const MaterialDef& mat = model.materials[static_cast<size_t>(gd.material)];
    im.geomInfo.push_back({mat.friction, mat.bounceness, mat.min_bounce_vel, gd.sensor});
    im.geoms.push_back(g);
  }

  im.joints.reserve(model.joints.size());
  for (const JointDef& jd : model.joints) {
    dJointID j = nullptr;
    switch (jd.kind) {
      case JointKind::BallSocket:
        j = dJointCreateBall(im.world, nullptr);
        break;
      case JointKind::Hinge:
        j = dJointCreateHinge(im.world, nullptr);
        break;
      case JointKind::Slider:
        j = dJointCreateSlider(im.world, nullptr);
        break;
      case JointKind::Fixed:
        j = dJointCreateFixed(im.world, nullptr);
        break;
    }
    // Index -1 is the static world, which ODE spells as a null body.
    dBodyID b1 = jd.body1 >= 0 ? im.bodies[static_cast<size_t>(jd.body1)] : nullptr;
    dBodyID b2 = jd.body2 >= 0 ? im.bodies[static_cast<size_t>(jd.body2)] : nullptr;
    dJointAttach(j, b1, b2);
    // Anchors/axes after attach: ODE stores them relative to the attached bodies.
    switch (jd.kind) {
      case JointKind::BallSocket:
        dJointSetBallAnchor(j, jd.anchor[0], jd.anchor[1], jd.anchor[2]);
        break;
      case JointKind::Hinge:
        dJointSetHingeAnchor(j, jd.anchor[0], jd.anchor[1], jd.anchor[2]);
        dJointSetHingeAxis(j, jd.axis[0], jd.axis[1], jd.axis[2]);
        break;
      case JointKind::Slider:
        dJointSetSliderAxis(j, jd.axis[0], jd.axis[1], jd.axis[2]);
        break;
      case JointKind::Fixed:
        dJointSetFixed(j);
        break;
    }
    im.joints.push_back(j);
  }
  return w;
}

void World::step(double h) {
  Impl& im = *impl_;
  im.lastContacts = 0;
  dSpaceCollide(im.space, &im, &Impl::nearCallback);
  if (im.quickstep) {
    dWorldQuickStep(im.world, h);
  } else {
    dWorldStep(im.world, h);
  }
  dJointGroupEmpty(im.contactGroup);
}

int World::bodyCount() const { return static_cast<int>(impl_->bodies.size()); }

BodyState World::body(int i) const {
  dBodyID b = impl_->bodies[static_cast<size_t>(i)];
  const dReal* p = dBodyGetPosition(b);
  const dReal* q = dBodyGetQuaternion(b);
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);
  BodyState s;
  s.pose.p = {p[0], p[1], p[2]};
  s.pose.q = {q[0], q[1], q[2], q[3]};
  s.lin_vel = {v[0], v[1], v[2]};
  s.ang_vel = {w[0], w[1], w[2]};
  const Vec3& c = impl_->com[static_cast<size_t>(i)];
  if (c != Vec3{0, 0, 0}) {
    // Report the body origin, not ODE's centre-of-mass frame.
    Vec3 rc = rotate(s.pose.q, c);
    s.pose.p = sub(s.pose.p, rc);
    s.lin_vel = sub(s.lin_vel, cross(s.ang_vel, rc));
  }
  return s;
}

int World::firstBadBody(double limit) const {
  // Runs after every step: read ODE's arrays in place. `!(|x| <= limit)` is also true for NaN;
  // an infinite limit still catches infinities through isfinite.
  auto bad = [limit](const dReal* v, int n) {
    for (int k = 0; k < n; ++k)
      if (!(std::fabs(v[k]) <= limit) || !std::isfinite(v[k])) return true;
    return false;
  };
  const int n = bodyCount();
  for (int i = 0; i < n; ++i) {
    dBodyID b = impl_->bodies[static_cast<size_t>(i)];
    if (bad(dBodyGetPosition(b), 3) || bad(dBodyGetLinearVel(b), 3) || bad(dBodyGetAngularVel(b), 3)) return i;
    const dReal* q = dBodyGetQuaternion(b);
    for (int k = 0; k < 4; ++k)
      if (!std::isfinite(q[k])) return i;
  }
  return -1;
}

int World::lastContactCount() const { return impl_->lastContacts; }

}  // namespace simbob
